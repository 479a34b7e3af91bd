//! The data sets of the aesthetic-curves project, embedded in the binary so that nothing
//! reads outside the repository (see `README.md` beside this crate for sources and licences).
//!
//! - [`PRIUS`]: five measured car key lines (millimetres) with the published single
//!   log-aesthetic fit of each (Graiff Zurita, Kajiwara & Miura 2023; MIT licence,
//!   [`PRIUS_LICENSE`]).
//! - [`PSEUDO_TABLE1`], [`PSEUDO_TABLE2`]: the point sets of the pseudo-elastic spline
//!   paper's figures; [`PSEUDO_UNIT_CIRCLE_REFERENCE`]: the 40-digit reference for its unit
//!   circle tables.
//! - [`HAND_STROKE`]: a pen stroke with hand jitter.
//!
//! [`parse_xy`] reads the `x,y` text of any of them.

/// One measured Prius key line and the published fit of one log-aesthetic curve to it.
#[derive(Clone, Copy, Debug)]
pub struct PriusLine {
    /// `ps_1` .. `ps_5`.
    pub name: &'static str,
    /// The points, `x,y` per row after a header, millimetres, in order along the line.
    pub csv: &'static str,
    /// The published fit's parameters ("Guess" then "Output" blocks of `name value` rows).
    pub published_fit: &'static str,
}

impl PriusLine {
    /// The points of the line, in order.
    pub fn points(&self) -> Vec<[f64; 2]> {
        parse_xy(self.csv)
    }

    /// The points of the line, in order, as any point type made from `(x, y)` (such as
    /// `aesthetic_curves::Point`).
    pub fn points_as<P: From<(f64, f64)>>(&self) -> Vec<P> {
        self.points()
            .into_iter()
            .map(|[x, y]| P::from((x, y)))
            .collect()
    }

    /// A parameter of the published fit: `output = false` for the start ("Guess"), `true`
    /// for the optimised result ("Output"). `None` if the file has no such row.
    pub fn published(&self, key: &str, output: bool) -> Option<f64> {
        let mut block = false;
        for line in self.published_fit.lines() {
            if line.starts_with("Guess") {
                block = false;
            } else if line.starts_with("Output") {
                block = true;
            } else if block == output {
                let mut it = line.split_whitespace();
                if it.next() == Some(key) {
                    return it.next().and_then(|v| v.parse().ok());
                }
            }
        }
        None
    }

    /// The published fit ("Output" block, or "Guess" for `output = false`) as a curve.
    pub fn published_curve(&self, output: bool) -> Option<PublishedFit> {
        let get = |k: &str| self.published(k, output);
        let (scale, h, n) = (get("S")?, get("h")?, get("N")?);
        Some(PublishedFit {
            alpha: get("alpha")?,
            s0: get("s0")?,
            // The file's `l` and `ds` are rounded to 3 decimals; (N - 1) h / S keeps 4-7 digits.
            l: (n - 1.0) * h / scale,
            scale,
            phi: get("phi")?,
            x0: get("x0")?,
            y0: get("y0")?,
            case: get("case")? as u8,
            n: n as usize,
        })
    }
}

/// The published fit of one log-aesthetic curve to a Prius line, as a curve: the "basic LAC"
/// of Graiff Zurita, Kajiwara & Miura (2023), tangent angle
/// `θ(s) = ((1 + α s)^(1 - 1/α) - 1)/(α - 1)` (`1 - e^(-s)` for α = 0, `ln(1 + s)` for α = 1),
/// curvature `dθ/ds = (1 + α s)^(-1/α)`, on `s ∈ [s0, s0 + l]`, then scaled by `S`, rotated
/// by `φ` and moved to `(x0, y0)`; "case" 1 lists it from the other end, 2 and 3 also swap
/// x and y. The files print every parameter to 3 decimals, so the curve rebuilt here is that
/// rounding of the published one (φ to ±5e-4 rad moves an end of a 1.5 m line by up to
/// 0.4 mm).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PublishedFit {
    /// Shape parameter.
    pub alpha: f64,
    /// Start of the basic curve's arc-length interval.
    pub s0: f64,
    /// Its length (unscaled): `(N - 1) h / S`.
    pub l: f64,
    /// Scale `S`.
    pub scale: f64,
    /// Rotation `φ` (radians).
    pub phi: f64,
    /// Translation.
    pub x0: f64,
    /// Translation.
    pub y0: f64,
    /// The paper's case number (0..=3).
    pub case: u8,
    /// Number of points `N` of their discretisation.
    pub n: usize,
}

impl PublishedFit {
    /// Tangent angle of the basic curve at `s`.
    pub fn theta(&self, s: f64) -> f64 {
        let a = self.alpha;
        if a == 0.0 {
            1.0 - (-s).exp()
        } else if a == 1.0 {
            (1.0 + s).ln()
        } else {
            ((1.0 + a * s).abs().powf(1.0 - 1.0 / a) - 1.0) / (a - 1.0)
        }
    }

    /// Unsigned curvature (1/mm) at the fraction `u ∈ [0, 1]` of the basic interval.
    pub fn curvature(&self, u: f64) -> f64 {
        let s = self.s0 + u * self.l;
        let a = self.alpha;
        let k = if a == 0.0 {
            (-s).exp()
        } else {
            (1.0 + a * s).abs().powf(-1.0 / a)
        };
        k / self.scale
    }

    /// The largest curvature (1/mm): the curvature is monotone, so at an end.
    pub fn max_curvature(&self) -> f64 {
        self.curvature(0.0).max(self.curvature(1.0))
    }

    fn place(&self, pts: Vec<[f64; 2]>) -> Vec<[f64; 2]> {
        let (sn, c) = self.phi.sin_cos();
        let mut out: Vec<[f64; 2]> = pts
            .into_iter()
            .map(|[x, y]| {
                let p = [
                    self.x0 + self.scale * (x * c - y * sn),
                    self.y0 + self.scale * (x * sn + y * c),
                ];
                if self.case >= 2 {
                    [p[1], p[0]]
                } else {
                    p
                }
            })
            .collect();
        if self.case % 2 == 1 {
            out.reverse();
        }
        out
    }

    /// The `N` points of the authors' own discretisation (forward Euler steps of `l/(N-1)`
    /// from `(x0, y0)`), in the data's order.
    pub fn euler_points(&self) -> Vec<[f64; 2]> {
        let ds = self.l / (self.n - 1) as f64;
        let mut p = [0.0, 0.0];
        let mut out = vec![p];
        for k in 0..self.n - 1 {
            let (sy, cx) = self.theta(self.s0 + k as f64 * ds).sin_cos();
            p = [p[0] + cx * ds, p[1] + sy * ds];
            out.push(p);
        }
        self.place(out)
    }

    /// The continuous curve the parameters define, at `m` points evenly spaced in arc length
    /// (`m >= 2`; midpoint rule with 16 steps between samples: far below 1e-6 mm here), in
    /// the data's order.
    pub fn points(&self, m: usize) -> Vec<[f64; 2]> {
        let m = m.max(2);
        let sub = 16;
        let h = self.l / ((m - 1) * sub) as f64;
        let mut p = [0.0, 0.0];
        let mut out = vec![p];
        for k in 0..(m - 1) * sub {
            let (sy, cx) = self.theta(self.s0 + (k as f64 + 0.5) * h).sin_cos();
            p = [p[0] + cx * h, p[1] + sy * h];
            if (k + 1) % sub == 0 {
                out.push(p);
            }
        }
        self.place(out)
    }
}

macro_rules! prius {
    ($($n:literal),*) => {
        [$(PriusLine {
            name: concat!("ps_", $n),
            csv: include_str!(concat!("../data/prius/ps_", $n, ".csv")),
            published_fit: include_str!(concat!("../data/prius/ps_", $n, "-published-fit.txt")),
        }),*]
    };
}

/// The five Prius key lines, `ps_1` .. `ps_5`.
pub const PRIUS: [PriusLine; 5] = prius!("1", "2", "3", "4", "5");

/// The MIT licence under which the Prius data are redistributed.
pub const PRIUS_LICENSE: &str = include_str!("../data/prius/LICENSE");

/// Inoue & Shibata, Table 1 (Fig. 8-12): nine points; the middle point's y is a parameter.
pub const PSEUDO_TABLE1: &str = include_str!("../data/pseudo-spline/table1.csv");

/// Inoue & Shibata, Table 2 (Fig. 13-17).
pub const PSEUDO_TABLE2: &str = include_str!("../data/pseudo-spline/table2.csv");

/// The closed pseudo-elastic spline through n = 3..10 points of the unit circle, one row per
/// n: `n length area tangent_length energy`, from `tools/pseudo_reference.py` (mpmath, 40
/// digits).
pub const PSEUDO_UNIT_CIRCLE_REFERENCE: &str =
    include_str!("../data/pseudo-spline/unit-circle-reference.txt");

/// A pen stroke of 240 points with hand jitter (`x,y`, pixels, y down).
pub const HAND_STROKE: &str = include_str!("../data/strokes/hand-stroke.csv");

/// The `x,y` rows of a text: rows whose first two comma-separated fields are numbers;
/// headers, comments (`#`) and blank lines are skipped.
pub fn parse_xy(text: &str) -> Vec<[f64; 2]> {
    text.lines()
        .filter_map(|l| {
            let mut it = l.split(',').map(|v| v.trim().parse::<f64>());
            match (it.next(), it.next()) {
                (Some(Ok(x)), Some(Ok(y))) => Some([x, y]),
                _ => None,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn prius_lines_read_whole() {
        // Every row after the header is a point.
        for l in PRIUS {
            let rows = l.csv.lines().filter(|r| !r.trim().is_empty()).count();
            assert_eq!(l.points().len() + 1, rows, "{}", l.name);
            assert!(l.points().len() > 600, "{}", l.name);
        }
        assert_eq!(PRIUS[0].published("alpha", true), Some(4.084));
        assert_eq!(PRIUS[0].published("alpha", false), Some(4.437));
        assert!(PRIUS_LICENSE.contains("MIT License"));
    }

    /// The rebuilt published curves run along their lines, from the first point to the last
    /// (case 1 lists the curve from its other end).
    #[test]
    fn published_curves_follow_their_lines() {
        for l in PRIUS {
            let pts = l.points();
            let f = l.published_curve(true).unwrap();
            for curve in [f.points(200), f.euler_points()] {
                let d = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).hypot(a[1] - b[1]);
                assert!(d(curve[0], pts[0]) < 2.0, "{}", l.name);
                assert!(
                    d(curve[curve.len() - 1], pts[pts.len() - 1]) < 2.0,
                    "{}",
                    l.name
                );
            }
            assert!(f.max_curvature() > 2e-4 && f.max_curvature() < 5e-4);
        }
    }

    #[test]
    fn tables_and_stroke_parse() {
        // The middle point's y is the parameter Y, not a number.
        assert_eq!(parse_xy(PSEUDO_TABLE1).len(), 8);
        assert!(parse_xy(PSEUDO_TABLE2).len() >= 4);
        assert_eq!(parse_xy(HAND_STROKE).len(), 240);
    }
}

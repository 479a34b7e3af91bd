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

    #[test]
    fn tables_and_stroke_parse() {
        // The middle point's y is the parameter Y, not a number.
        assert_eq!(parse_xy(PSEUDO_TABLE1).len(), 8);
        assert!(parse_xy(PSEUDO_TABLE2).len() >= 4);
        assert_eq!(parse_xy(HAND_STROKE).len(), 240);
    }
}

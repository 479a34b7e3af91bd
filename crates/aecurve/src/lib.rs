//! The `aecurve` command-line tool as a library: the JSON protocol, the batch loop, the
//! benchmark of the monotonicity tests, plots and the demo gallery.

pub mod batch;
pub mod bench;
pub mod plot;
pub mod protocol;

/// Parse `"x,y x,y ..."` (whitespace or `;` between points) into points.
pub fn parse_points(s: &str) -> anyhow::Result<Vec<aesthetic_curves::Point>> {
    s.split(|c: char| c.is_whitespace() || c == ';')
        .filter(|p| !p.is_empty())
        .map(|p| {
            let (x, y) = p
                .split_once(',')
                .ok_or_else(|| anyhow::anyhow!("point '{p}' is not of the form x,y"))?;
            let x: f64 = x
                .trim()
                .parse()
                .map_err(|_| anyhow::anyhow!("bad x in '{p}'"))?;
            let y: f64 = y
                .trim()
                .parse()
                .map_err(|_| anyhow::anyhow!("bad y in '{p}'"))?;
            anyhow::ensure!(x.is_finite() && y.is_finite(), "point '{p}' is not finite");
            Ok(aesthetic_curves::Point::new(x, y))
        })
        .collect()
}

/// Parse `"a b c"` or `"a,b,c"` into numbers.
pub fn parse_numbers(s: &str) -> anyhow::Result<Vec<f64>> {
    s.split(|c: char| c.is_whitespace() || c == ',' || c == ';')
        .filter(|p| !p.is_empty())
        .map(|p| {
            let v: f64 = p
                .parse()
                .map_err(|_| anyhow::anyhow!("'{p}' is not a number"))?;
            anyhow::ensure!(v.is_finite(), "'{p}' is not finite");
            Ok(v)
        })
        .collect()
}

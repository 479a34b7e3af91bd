//! Plain-language summaries of results, shared by the commands' text output and the
//! gallery's pages (which wrap them in HTML).

use aesthetic_curves::sketch::Sketch;

/// A length or curvature for a reader: four decimals in a middle range, else four digits in
/// scientific notation.
pub fn number(x: f64) -> String {
    if x == 0.0 || (1e-3..1e4).contains(&x.abs()) {
        format!("{x:.4}")
    } else {
        format!("{x:.3e}")
    }
}

/// What a sketch fit delivered, in words.
pub struct SketchSummary {
    /// Pieces, deviation against the tolerance, curvature jump and G2.
    pub headline: String,
    /// Monotonicity of the pieces, inflections and curvature extrema.
    pub details: String,
    /// The fairing's iterations and the jump before and after it.
    pub fairing: String,
    /// One row a piece: index, kind, α (marked at its bound), curvature at the start and at
    /// the end, monotone or not (the exact test).
    pub rows: Vec<[String; 6]>,
}

/// The column heads of [`SketchSummary::rows`], with `unit` the input's length unit.
pub fn sketch_columns(unit: &str) -> [String; 6] {
    [
        "piece".into(),
        "kind".into(),
        "alpha".into(),
        format!("curvature at start (1/{unit})"),
        format!("at end (1/{unit})"),
        "monotone (exact test)".into(),
    ]
}

/// The summary of `sk`, fitted within `tolerance` (in `unit`s).
pub fn sketch(sk: &Sketch, tolerance: f64, unit: &str) -> SketchSummary {
    let headline = format!(
        "{} pieces, largest deviation {} {unit} (tolerance {} {unit}), largest curvature \
         jump {:.1e} of the largest curvature ({})",
        sk.pieces.len(),
        number(sk.max_deviation),
        number(tolerance),
        sk.max_curvature_jump,
        if sk.g2 { "G2" } else { "not G2" },
    );
    let details = format!(
        "{}; {} inflections and {} curvature extrema",
        if sk.all_monotone {
            "every piece curvature-monotone (exact test)"
        } else {
            "NOT every piece curvature-monotone (exact test)"
        },
        sk.inflections,
        sk.curvature_extrema
    );
    let fairing = format!(
        "fairing: {} Newton iterations ({}), jump {:.2e} -> {:.2e}",
        sk.fairing.iterations,
        if sk.fairing.converged {
            "converged"
        } else {
            "NOT converged"
        },
        sk.fairing.initial_jump,
        sk.fairing.final_jump
    );
    let rows = sk
        .pieces
        .iter()
        .enumerate()
        .map(|(i, p)| {
            [
                i.to_string(),
                p.kind.as_str().to_string(),
                format!(
                    "{:.4}{}",
                    p.alpha,
                    if p.alpha_at_bound { " (bound)" } else { "" }
                ),
                format!("{:+.4e}", p.end_curvatures.0),
                format!("{:+.4e}", p.end_curvatures.1),
                if p.monotone { "yes" } else { "NO" }.to_string(),
            ]
        })
        .collect();
    SketchSummary {
        headline,
        details,
        fairing,
        rows,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_read_plainly_in_the_middle_range() {
        assert_eq!(number(0.0), "0.0000");
        assert_eq!(number(0.25), "0.2500");
        assert_eq!(number(-1234.5), "-1234.5000");
        assert_eq!(number(2.5e-5), "2.500e-5");
        assert_eq!(number(3.0e6), "3.000e6");
    }

    #[test]
    fn a_sketch_summary_states_what_was_delivered() {
        let pts: Vec<aesthetic_curves::Point> = (0..60)
            .map(|i| {
                let t = i as f64 / 59.0;
                aesthetic_curves::Point::new(100.0 * t, 30.0 * (3.0 * t).sin())
            })
            .collect();
        let tol = aesthetic_curves::sketch::default_tolerance(&pts);
        let sk = aesthetic_curves::sketch::fit_sketch(
            &pts,
            &aesthetic_curves::sketch::SketchOptions::with_tolerance(tol),
        )
        .unwrap();
        let s = sketch(&sk, tol, "mm");
        assert_eq!(s.rows.len(), sk.pieces.len());
        assert!(s
            .headline
            .starts_with(&format!("{} pieces, ", sk.pieces.len())));
        assert!(s.headline.contains(&number(tol)));
        assert!(s
            .details
            .contains(&format!("{} inflections", sk.inflections)));
        for (row, p) in s.rows.iter().zip(&sk.pieces) {
            assert_eq!(row[1], p.kind.as_str());
            assert_eq!(row[5] == "yes", p.monotone);
        }
        assert_eq!(sketch_columns("mm")[3], "curvature at start (1/mm)");
    }
}

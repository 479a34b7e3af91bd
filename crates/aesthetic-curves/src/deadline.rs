//! Cooperative cancellation: a caller (the editor's server, say) runs work under a deadline
//! with [`with_deadline`]; the long loops of the library (exact-mode pseudo-elastic
//! segments, the sketch pipeline's rounds and fairing, the single-LAC fit) call [`check`]
//! and stop with [`Error::Timeout`] once it has passed. The deadline is per thread; work
//! without one never stops early. A check costs one clock read.

use crate::error::{Error, Result};
use std::cell::Cell;
use std::time::Instant;

thread_local! {
    static DEADLINE: Cell<Option<Instant>> = const { Cell::new(None) };
}

/// Run `f` with `deadline` set on this thread (the previous one, if any, is restored after).
pub fn with_deadline<T>(deadline: Instant, f: impl FnOnce() -> T) -> T {
    let previous = DEADLINE.with(|d| d.replace(Some(deadline)));
    struct Restore(Option<Instant>);
    impl Drop for Restore {
        fn drop(&mut self) {
            DEADLINE.with(|d| d.set(self.0));
        }
    }
    let _restore = Restore(previous);
    f()
}

/// This thread's deadline, if any (to hand to worker threads with [`inherit`]).
pub fn current() -> Option<Instant> {
    DEADLINE.with(|d| d.get())
}

/// Run `f` under `deadline` when there is one (a worker thread taking on its caller's
/// deadline, from [`current`]), else as it is.
pub fn inherit<T>(deadline: Option<Instant>, f: impl FnOnce() -> T) -> T {
    match deadline {
        Some(d) => with_deadline(d, f),
        None => f(),
    }
}

/// Whether this thread's deadline has passed.
pub fn expired() -> bool {
    DEADLINE
        .with(|d| d.get())
        .is_some_and(|t| Instant::now() >= t)
}

/// [`Error::Timeout`] once this thread's deadline has passed.
pub fn check() -> Result<()> {
    if expired() {
        Err(Error::Timeout(
            "the work ran past its deadline and was stopped".into(),
        ))
    } else {
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    #[test]
    fn deadlines_nest_and_restore() {
        assert!(check().is_ok());
        let past = Instant::now() - Duration::from_millis(1);
        let future = Instant::now() + Duration::from_secs(60);
        with_deadline(future, || {
            assert!(check().is_ok());
            with_deadline(past, || assert_eq!(check().unwrap_err().kind(), "timeout"));
            assert!(check().is_ok());
        });
        assert!(!expired());
    }

    /// Long work stops soon after its deadline: exact-mode pseudo-elastic splines (a
    /// minimisation per segment, seconds per point) and a sketch fit.
    #[test]
    fn long_work_stops_at_the_deadline() {
        use crate::pseudo_spline::{pseudo_elastic, Mode};
        use kurbo::Point;
        let pts: Vec<Point> = (0..12)
            .map(|i| Point::new(i as f64, ((i * 37) % 11) as f64 / 3.0))
            .collect();
        let t = Instant::now();
        let r = with_deadline(t + Duration::from_millis(200), || {
            pseudo_elastic(&pts, false, Mode::Exact)
        });
        let secs = t.elapsed().as_secs_f64();
        assert_eq!(r.unwrap_err().kind(), "timeout");
        assert!(secs < 1.5, "{secs} s");
        let stroke: Vec<Point> = (0..400)
            .map(|i| {
                let t = i as f64 / 399.0;
                Point::new(
                    300.0 * t,
                    40.0 * (9.0 * t).sin() + ((i * 7919) % 13) as f64 * 0.3,
                )
            })
            .collect();
        let r = with_deadline(Instant::now(), || {
            crate::sketch::fit_sketch(&stroke, &crate::sketch::SketchOptions::with_tolerance(0.5))
        });
        assert_eq!(r.unwrap_err().kind(), "timeout");
    }
}

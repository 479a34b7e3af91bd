//! Third-party parsers run on hostile bytes: a panic inside one (its robustness is not
//! ours) becomes an error naming it, and the caller goes on ([`contained`]). Such a panic
//! is an answer, not a crash, so it is not printed: the process's panic hook stays quiet
//! while a contained call runs on its thread (every other panic still prints as Rust's
//! default hook prints it).

use anyhow::{bail, Result};
use std::cell::Cell;
use std::sync::Once;

thread_local! {
    /// Contained calls running on this thread (nested calls count).
    static DEPTH: Cell<usize> = const { Cell::new(0) };
    /// Panics the hook kept quiet on this thread.
    static QUIETED: Cell<usize> = const { Cell::new(0) };
}

/// The hook: quiet inside a contained call, the default one elsewhere (installed once).
fn install_hook() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let default = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if DEPTH.with(|d| d.get()) > 0 {
                QUIETED.with(|q| q.set(q.get() + 1));
            } else {
                default(info);
            }
        }));
    });
}

/// How many contained panics were kept quiet on this thread so far.
pub fn quieted() -> usize {
    QUIETED.with(|q| q.get())
}

/// Runs a third-party parser on hostile bytes: a panic inside it becomes an error naming
/// it (not printed), and the caller goes on.
pub fn contained<T>(f: impl FnOnce() -> Result<T>) -> Result<T> {
    install_hook();
    DEPTH.with(|d| d.set(d.get() + 1));
    let run = std::panic::catch_unwind(std::panic::AssertUnwindSafe(f));
    DEPTH.with(|d| d.set(d.get() - 1));
    match run {
        Ok(r) => r,
        Err(p) => {
            let why = p
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| p.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown".into());
            bail!("the file's parser failed on these bytes (a damaged file?): {why}")
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_contained_panic_is_an_error_and_is_not_printed() {
        let before = quieted();
        let r: Result<()> = contained(|| panic!("the parser's own bug"));
        let e = r.expect_err("a panic is an error");
        assert!(e.to_string().contains("the parser's own bug"), "{e}");
        assert_eq!(quieted(), before + 1, "the hook kept it quiet");
        // Outside a contained call the hook is the default one again.
        let outside = std::panic::catch_unwind(|| panic!("not contained"));
        assert!(outside.is_err());
        assert_eq!(
            quieted(),
            before + 1,
            "an uncontained panic is not counted quiet"
        );
        assert_eq!(contained(|| Ok(7)).unwrap(), 7);
    }
}

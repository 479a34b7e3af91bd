//! Shared by the table generators (`gen_pseudo_tables`, `gen_approx_optima`): run a job
//! per index on every core, with a progress bar.

use indicatif::{ProgressBar, ProgressStyle};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

/// `f(0..count)` on all cores (each index once, in any order), the results in index order;
/// `init` fills the slots before they are computed.
pub fn parallel<T: Send + Clone>(
    count: usize,
    init: T,
    label: &str,
    f: impl Fn(usize) -> T + Sync,
) -> Vec<T> {
    let out = Mutex::new(vec![init; count]);
    let next = AtomicUsize::new(0);
    let bar = ProgressBar::new(count as u64);
    bar.set_style(
        ProgressStyle::with_template("{msg:>12} [{bar:40}] {pos}/{len} ({eta})")
            .expect("template")
            .progress_chars("=> "),
    );
    bar.set_message(label.to_string());
    let threads = std::thread::available_parallelism()
        .map(|n| n.get())
        .unwrap_or(2);
    std::thread::scope(|s| {
        for _ in 0..threads {
            s.spawn(|| loop {
                let idx = next.fetch_add(1, Ordering::Relaxed);
                if idx >= count {
                    break;
                }
                let v = f(idx);
                out.lock().expect("lock")[idx] = v;
                bar.inc(1);
            });
        }
    });
    bar.finish();
    out.into_inner().expect("lock")
}

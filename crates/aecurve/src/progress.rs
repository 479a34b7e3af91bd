//! Progress bars on stderr (indicatif), one style for every long command: the label, the
//! bar, the count and a message. indicatif draws nothing when stderr is not a terminal.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// A bar of `len` steps, drawn as `label [bar] pos/len msg`, or never drawn when `shown`
/// is false (a short job, or output that is itself the terminal's).
pub fn bar(len: u64, label: &str, shown: bool) -> ProgressBar {
    let pb = ProgressBar::new(len);
    if !shown {
        pb.set_draw_target(ProgressDrawTarget::hidden());
    }
    let template = if label.is_empty() {
        "{bar:40} {pos}/{len} {msg}".to_string()
    } else {
        format!("{label} {{bar:40}} {{pos}}/{{len}} {{msg}}")
    };
    pb.set_style(
        ProgressStyle::with_template(&template).unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    pb
}

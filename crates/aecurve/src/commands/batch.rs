//! `aecurve batch`: JSON Lines requests on stdin, one response line each on stdout.

use crate::cli::count;
use crate::commands::Command;
use aecurve::batch;
use anyhow::Result;

/// The arguments of `aecurve batch` (the command's help is its entry in `cli.rs`).
#[derive(clap::Args)]
pub(crate) struct Args {
    /// Largest accepted request line in bytes (1 to 1 GiB).
    #[arg(long, default_value_t = batch::DEFAULT_MAX_LINE, value_parser = count::<1, 1_073_741_824>)]
    max_line_bytes: usize,
    /// Wall-clock budget of one request in seconds (1 to 86,400): longer work stops
    /// and the request gets a `timeout` error.
    #[arg(long, default_value_t = batch::DEFAULT_TIMEOUT_SECS, value_parser = count::<1, 86_400>)]
    timeout_secs: usize,
}

impl Command for Args {
    fn run(self) -> Result<()> {
        let stdin = std::io::stdin();
        let stdout = std::io::stdout();
        batch::run_with_timeout(
            stdin.lock(),
            stdout.lock(),
            self.max_line_bytes,
            std::time::Duration::from_secs(self.timeout_secs as u64),
        )?;
        Ok(())
    }
}

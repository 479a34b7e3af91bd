//! `aecurve editor`: the interactive editor's local server.

use crate::cli::parse_timeout;
use crate::commands::Command;
use anyhow::Result;

/// The arguments of `aecurve editor` (the command's help is its entry in `cli.rs`).
#[derive(clap::Args)]
pub(crate) struct Args {
    /// Port (0: any free port); the URL is printed.
    #[arg(long, default_value_t = 8731)]
    port: u16,
    /// Do not open the page in the system's browser.
    #[arg(long)]
    no_open: bool,
    /// Wall-clock limit of one request, in seconds (0.1 to 600); a request past it gets
    /// a `timeout` error.
    #[arg(long, default_value_t = 5.0, value_parser = parse_timeout)]
    timeout: f64,
}

impl Command for Args {
    fn run(self) -> Result<()> {
        aecurve::editor::serve(
            self.port,
            !self.no_open,
            aecurve::editor::Limits {
                request_timeout: std::time::Duration::from_secs_f64(self.timeout),
                ..Default::default()
            },
        )?;
        Ok(())
    }
}

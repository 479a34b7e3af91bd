//! `aecurve`: the command-line tool of aesthetic-curves.

use anyhow::{Context, Result};
use clap::Parser;

mod cli;
mod commands;
mod gallery;

use cli::Cli;

fn main() {
    // A closed stdout (`aecurve ... | head`) ends the program quietly, as for other Unix
    // tools, instead of a panic message from println!.
    let default_hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let p = info.payload();
        let msg = p
            .downcast_ref::<String>()
            .map(String::as_str)
            .or_else(|| p.downcast_ref::<&str>().copied())
            .unwrap_or("");
        if msg.contains("Broken pipe") {
            std::process::exit(141);
        }
        // Any other failure to write the output (a full disk, /dev/full): a message and a
        // failure status, not a panic.
        if let Some(why) = msg.strip_prefix("failed printing to stdout: ") {
            eprintln!("error: cannot write the output: {why}");
            std::process::exit(1);
        }
        default_hook(info);
    }));
    if let Err(e) = run() {
        eprintln!("error: {e:#}");
        std::process::exit(1);
    }
}

fn run() -> Result<()> {
    let cli = Cli::parse();
    cli.cmd.check()?;
    // Outputs go where the user says: create their folders.
    for path in cli.cmd.outputs() {
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir)
                .with_context(|| format!("creating the folder {}", dir.display()))?;
        }
    }
    cli.cmd.run()
}

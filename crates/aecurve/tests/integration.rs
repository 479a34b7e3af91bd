//! The command line's and the protocol's integration tests, as one test binary (one link
//! instead of one per file): each file beside this one is a module, named for what it checks.
//! Run one file's tests with `cargo test --release -p aecurve --test integration FILE::`.

mod check;
mod cli;
mod fix;
mod limits;
mod protocol_fuzz;
mod readers;
mod readme_commands;
mod schema;
mod write_safety;

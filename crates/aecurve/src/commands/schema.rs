//! `aecurve schema`: the JSON Schema of the protocol, generated from its request and
//! response types.

use crate::commands::Command;
use anyhow::Result;

/// The arguments of `aecurve schema` (the command's help is its entry in `cli.rs`).
#[derive(clap::Args)]
pub(crate) struct Args {
    /// Only this op's request and response schemas (with the definitions they use).
    #[arg(long)]
    op: Option<String>,
}

impl Command for Args {
    fn run(self) -> Result<()> {
        let schema = aecurve::protocol::schema();
        let out = match &self.op {
            None => schema,
            Some(op) => {
                let Some(pair) = schema["x-ops"].get(op) else {
                    anyhow::bail!(
                        "unknown op {op:?}; known: {}",
                        aecurve::protocol::OPS.join(", ")
                    );
                };
                serde_json::json!({
                    "$schema": schema["$schema"],
                    "title": format!("aecurve protocol: {op}"),
                    "request": pair["request"],
                    "response": pair["response"],
                    "$defs": schema["$defs"],
                })
            }
        };
        println!("{}", serde_json::to_string_pretty(&out)?);
        Ok(())
    }
}

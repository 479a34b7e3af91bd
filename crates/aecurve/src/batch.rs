//! `aecurve batch`: JSON Lines in, one response line per request out, in order, flushed
//! after each. Blank lines are skipped; a line over the size limit or not UTF-8 gets an error
//! response and the stream goes on.

use crate::protocol::{error_response, handle_line, ProtoError};
use serde_json::Value;
use std::io::{BufRead, Write};

/// Default largest request line, in bytes.
pub const DEFAULT_MAX_LINE: usize = 16 * 1024 * 1024;

/// Default wall-clock budget of one request (seconds): the library's long loops stop at it
/// and the request gets a `timeout` error, as in the editor (whose budget is 5 s).
pub const DEFAULT_TIMEOUT_SECS: usize = 60;

/// Counts of one batch run.
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
pub struct BatchStats {
    /// Requests answered.
    pub requests: usize,
    /// Of which answered with an error.
    pub errors: usize,
}

/// Read one line of at most `max` bytes (the newline excluded). Returns `None` at end of
/// input, `Some(Err(len))` when the line was longer (it is consumed to its end).
fn read_line_capped<R: BufRead>(
    r: &mut R,
    max: usize,
    buf: &mut Vec<u8>,
) -> std::io::Result<Option<Result<(), usize>>> {
    buf.clear();
    let mut total = 0usize;
    let mut any = false;
    loop {
        let chunk = r.fill_buf()?;
        if chunk.is_empty() {
            return Ok(if any {
                Some(if total > max { Err(total) } else { Ok(()) })
            } else {
                None
            });
        }
        any = true;
        let (part, done) = match chunk.iter().position(|&b| b == b'\n') {
            Some(i) => (&chunk[..i], Some(i + 1)),
            None => (chunk, None),
        };
        total += part.len();
        if total <= max {
            buf.extend_from_slice(part);
        }
        let consumed = done.unwrap_or(chunk.len());
        r.consume(consumed);
        if done.is_some() {
            return Ok(Some(if total > max { Err(total) } else { Ok(()) }));
        }
    }
}

/// Run the batch loop from `input` to `output`, each request within
/// [`DEFAULT_TIMEOUT_SECS`].
pub fn run<R: BufRead, W: Write>(
    input: R,
    output: W,
    max_line: usize,
) -> std::io::Result<BatchStats> {
    run_with_timeout(
        input,
        output,
        max_line,
        std::time::Duration::from_secs(DEFAULT_TIMEOUT_SECS as u64),
    )
}

/// One request under its deadline; a panic inside (a bug: no input should cause one) is an
/// `internal` error for that request, and the batch goes on.
fn answer(text: &str, timeout: std::time::Duration) -> Value {
    let deadline = std::time::Instant::now() + timeout;
    let run = || aesthetic_curves::deadline::with_deadline(deadline, || handle_line(text));
    match std::panic::catch_unwind(run) {
        Ok(v) => v,
        Err(_) => error_response(
            Value::Null,
            ProtoError {
                kind: "internal",
                message: "the request made the program fail (a bug: please report the request)"
                    .into(),
            },
        ),
    }
}

/// The batch loop with a per-request wall-clock budget.
pub fn run_with_timeout<R: BufRead, W: Write>(
    mut input: R,
    mut output: W,
    max_line: usize,
    timeout: std::time::Duration,
) -> std::io::Result<BatchStats> {
    let mut stats = BatchStats::default();
    let mut buf = Vec::new();
    while let Some(line) = read_line_capped(&mut input, max_line, &mut buf)? {
        let response: Value = match line {
            Err(len) => error_response(
                Value::Null,
                ProtoError {
                    kind: "invalid_input",
                    message: format!(
                        "request line of {len} bytes is over the limit of {max_line} bytes"
                    ),
                },
            ),
            Ok(()) => match std::str::from_utf8(&buf) {
                Err(e) => error_response(
                    Value::Null,
                    ProtoError {
                        kind: "parse",
                        message: format!("request line is not UTF-8: {e}"),
                    },
                ),
                Ok(text) => {
                    if text.trim().is_empty() {
                        continue;
                    }
                    answer(text, timeout)
                }
            },
        };
        stats.requests += 1;
        if response["ok"] != Value::Bool(true) {
            stats.errors += 1;
        }
        serde_json::to_writer(&mut output, &response)?;
        output.write_all(b"\n")?;
        output.flush()?;
    }
    Ok(stats)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every error kind a batch or the editor sends is one the schema of a response line
    /// accepts (`timeout` and `internal` come from here, `forbidden` from the editor), and
    /// no other kind is.
    #[test]
    fn every_error_kind_sent_is_in_the_schema() {
        let v = jsonschema::validator_for(&crate::protocol::response_line_schema())
            .expect("the schema compiles");
        let answer = |kind: &'static str| {
            crate::protocol::error_response(
                Value::from(1),
                ProtoError {
                    kind,
                    message: "why".into(),
                },
            )
        };
        for kind in crate::protocol::ERROR_KINDS {
            assert!(v.is_valid(&answer(kind)), "{kind}");
        }
        for kind in ["timeout", "internal", "forbidden"] {
            assert!(crate::protocol::ERROR_KINDS.contains(&kind), "{kind}");
        }
        assert!(!v.is_valid(&answer("surprise")));
    }

    fn run_str(input: &[u8], max: usize) -> Vec<Value> {
        let mut out = Vec::new();
        run(input, &mut out, max).unwrap();
        String::from_utf8(out)
            .unwrap()
            .lines()
            .map(|l| serde_json::from_str(l).unwrap())
            .collect()
    }

    /// 20,000 spline points with `draw: 2000` grew `batch` past 17 GB; the exact
    /// mode had no budget. Now the first is refused at once naming the drawing budget, the
    /// second stops at the request's deadline, and the batch answers the next line.
    #[test]
    fn requests_over_their_budgets_are_refused_or_stopped_and_the_batch_goes_on() {
        let pts: Vec<[f64; 2]> = (0..20_000)
            .map(|i| [i as f64, (i as f64 * 0.7).sin()])
            .collect();
        let big = serde_json::json!({"id": 1, "op": "spline.pseudo_elastic", "points": pts, "draw": 2000});
        let exact = serde_json::json!({"id": 2, "op": "spline.pseudo_elastic", "mode": "exact",
            "points": [[0, 0], [1, 1], [2, 0], [3, 1], [4, 0], [5, 1], [6, 0], [7, 1]]});
        let ok = serde_json::json!({"id": 3, "op": "bezier.curvature_monotone",
            "control_points": [[0, 0], [1, 0], [2, 1]]});
        let input = format!("{big}\n{exact}\n{ok}\n");
        let t = std::time::Instant::now();
        let mut out = Vec::new();
        run_with_timeout(
            input.as_bytes(),
            &mut out,
            1 << 28,
            std::time::Duration::from_millis(500),
        )
        .unwrap();
        let r: Vec<Value> = String::from_utf8(out)
            .unwrap()
            .lines()
            .map(|l| serde_json::from_str(l).unwrap())
            .collect();
        assert_eq!(r.len(), 3);
        assert_eq!(r[0]["error"]["kind"], "invalid_input", "{}", r[0]);
        let msg = r[0]["error"]["message"].as_str().unwrap();
        assert!(
            msg.contains("drawing budget") && msg.contains("at most 10 points per piece"),
            "{msg}"
        );
        assert_eq!(r[1]["error"]["kind"], "timeout", "{}", r[1]);
        assert_eq!(r[2]["ok"], true);
        assert!(
            t.elapsed() < std::time::Duration::from_secs(30),
            "{:?}",
            t.elapsed()
        );
    }

    /// An outline check past its deadline stops (cooperative cancellation reaches the
    /// worker threads of the check), answers `timeout`, and the batch goes on: 10,000
    /// segments of degree 20 take seconds (optimised) to check in full.
    #[test]
    fn an_outline_check_stops_at_its_deadline() {
        let segs: Vec<Value> = (0..10_000)
            .map(|i| {
                let pts: Vec<[f64; 2]> = (0..21)
                    .map(|j| [(i * 20 + j) as f64, ((i * 20 + j) as f64).sin()])
                    .collect();
                serde_json::json!({ "control_points": pts })
            })
            .collect();
        let big = serde_json::json!({"id": 1, "op": "outline.check", "segments": segs});
        let ok = serde_json::json!({"id": 2, "op": "outline.check", "path": "M0 0 C1 2 3 2 4 0"});
        let input = format!("{big}\n{ok}\n");
        let t = std::time::Instant::now();
        let mut out = Vec::new();
        let timeout = std::time::Duration::from_millis(300);
        run_with_timeout(input.as_bytes(), &mut out, 1 << 28, timeout).unwrap();
        let r: Vec<Value> = String::from_utf8(out)
            .unwrap()
            .lines()
            .map(|l| serde_json::from_str(l).unwrap())
            .collect();
        assert_eq!(r.len(), 2);
        assert_eq!(
            r[0]["error"]["kind"],
            "timeout",
            "{:.300}",
            r[0].to_string()
        );
        assert_eq!(r[1]["ok"], true);
        // Reading the request is most of what is left (the check itself stopped).
        assert!(
            t.elapsed() < std::time::Duration::from_secs(5),
            "{:?}",
            t.elapsed()
        );
    }

    #[test]
    fn a_bad_line_never_stops_the_batch() {
        let input = b"{\"id\":1,\"op\":\"bezier.curvature_monotone\",\"control_points\":[[0,0],[1,0],[2,1]]}\n\
            garbage\n\n\xff\xfe\n{\"id\":2,\"op\":\"x\"}\n\
            {\"id\":3,\"op\":\"bezier.curvature_monotone\",\"control_points\":[[0,0],[1,0],[2,1]]}";
        let r = run_str(input, 1 << 20);
        assert_eq!(r.len(), 5);
        assert_eq!(r[0]["ok"], true);
        assert_eq!(r[1]["error"]["kind"], "parse");
        assert_eq!(r[2]["error"]["kind"], "parse");
        assert_eq!(r[3]["error"]["kind"], "unknown_op");
        assert_eq!(r[4]["id"], 3);
        assert_eq!(r[4]["ok"], true);
    }

    #[test]
    fn over_long_lines_are_refused_and_skipped() {
        let mut input = vec![b' '; 5000];
        input.extend_from_slice(
            b"\n{\"id\":9,\"op\":\"bezier.curvature_monotone\",\"control_points\":[[0,0],[1,0]]}\n",
        );
        let r = run_str(&input, 1000);
        assert_eq!(r.len(), 2);
        assert_eq!(r[0]["error"]["kind"], "invalid_input");
        assert_eq!(r[1]["id"], 9);
    }
}

//! `aecurve editor`: a local web server for the interactive editor. It listens on 127.0.0.1
//! only, serves the page and its script from assets embedded in the binary, and answers:
//! - `POST /api`: one request of the batch protocol, one response (the same JSON as a batch
//!   line; malformed JSON gets a `parse` error). Each response carries the server's compute
//!   time in a `Server-Timing` header.
//! - `POST /api/region`: the protocol's `region.map` (its body without `op`): which positions
//!   of one control point keep a property, on a grid over a box.
//! - `POST /api/export`: a NURBS (`degree`, `knots`, `control_points`, `weights`) as a
//!   `dxf`, `step`, `iges`, `svg` or `json` file: the one endpoint outside the protocol's ops,
//!   because its answer is a file, not a JSON result.
//!
//! Security model: loopback only, same origin only (the `Host` must be this server, an
//! `Origin` must be its own page, POST bodies must be JSON: see [`router`]), bodies over
//! [`MAX_BODY`] get 413. The computations run on tokio's blocking pool, so concurrent
//! requests proceed in parallel.

use crate::protocol::{self, fields, fields::IntIn, fields::Points, fields::Weights};
use aesthetic_curves::nurbs::Nurbs;
use axum::body::Bytes;
use axum::extract::DefaultBodyLimit;
use axum::http::{header, HeaderValue, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use axum::Router;
use schemars::JsonSchema;
use serde::Deserialize;
use serde_json::{json, Value};
use std::time::Instant;

/// Largest request body (bytes).
pub const MAX_BODY: usize = 4 * 1024 * 1024;

pub use crate::protocol::region::{MAX_REGION_CELLS, REGION_WORK_BUDGET};

static INDEX_HTML: &str = include_str!("../assets/editor/index.html");
static STYLE_CSS: &str = include_str!("../assets/editor/style.css");

/// The page's ES modules: `app.js` (state, update loop, interaction, export) imports the
/// others: `api.js` (requests), `view.js` (viewport), `draw.js` (drawing), `ui.js` (panel
/// text), `modes.js` (one object per editing mode).
static MODULES: [(&str, &str); 6] = [
    ("/app.js", include_str!("../assets/editor/app.js")),
    ("/api.js", include_str!("../assets/editor/api.js")),
    ("/view.js", include_str!("../assets/editor/view.js")),
    ("/draw.js", include_str!("../assets/editor/draw.js")),
    ("/ui.js", include_str!("../assets/editor/ui.js")),
    ("/modes.js", include_str!("../assets/editor/modes.js")),
];

/// Whether a `Host` header names this server: `127.0.0.1`, `localhost` or `[::1]` with the
/// port it listens on. Any other name is how a DNS-rebinding page would reach it.
fn host_ok(host: &str, port: u16) -> bool {
    ["127.0.0.1", "localhost", "[::1]"]
        .iter()
        .any(|h| host.eq_ignore_ascii_case(&format!("{h}:{port}")))
}

/// Same origin only. Every request must name this server in `Host` (421 otherwise); a
/// request whose `Origin` is present must come from this server's own page (403); a POST
/// must say `Content-Type: application/json` (415): a page elsewhere can send forms and
/// `text/plain` without asking, not JSON.
async fn same_origin(
    axum::extract::State(port): axum::extract::State<u16>,
    req: axum::extract::Request,
    next: axum::middleware::Next,
) -> Response {
    let headers = req.headers();
    let text = |name: header::HeaderName| headers.get(name).and_then(|v| v.to_str().ok());
    let refuse = |status: StatusCode, why: &str| {
        (
            status,
            [(header::CONTENT_TYPE, "application/json")],
            protocol::error_response(
                Value::Null,
                protocol::ProtoError {
                    kind: "forbidden",
                    message: why.to_string(),
                },
            )
            .to_string(),
        )
            .into_response()
    };
    if !text(header::HOST).is_some_and(|h| host_ok(h, port)) {
        return refuse(
            StatusCode::MISDIRECTED_REQUEST,
            "the editor answers only requests addressed to 127.0.0.1, localhost or [::1] \
             with its port",
        );
    }
    if let Some(origin) = headers.get(header::ORIGIN) {
        let own = origin
            .to_str()
            .ok()
            .and_then(|o| o.strip_prefix("http://"))
            .is_some_and(|h| host_ok(h, port));
        if !own {
            return refuse(
                StatusCode::FORBIDDEN,
                "cross-origin requests are refused: the editor answers its own page only",
            );
        }
    }
    if req.method() == axum::http::Method::POST {
        let json = text(header::CONTENT_TYPE).is_some_and(|c| {
            c.split(';')
                .next()
                .is_some_and(|m| m.trim().eq_ignore_ascii_case("application/json"))
        });
        if !json {
            return refuse(
                StatusCode::UNSUPPORTED_MEDIA_TYPE,
                "requests must be sent as Content-Type: application/json",
            );
        }
    }
    next.run(req).await
}

/// The editor's routes, for a server listening on `port`.
pub fn router(port: u16, limits: Limits) -> Router {
    let compute = Compute {
        slots: std::sync::Arc::new(tokio::sync::Semaphore::new(limits.computations.max(1))),
        timeout: limits.request_timeout,
    };
    let mut routes = Router::new().route(
        "/",
        get(|| async { asset(INDEX_HTML, "text/html; charset=utf-8") }),
    );
    for (path, body) in MODULES {
        routes = routes.route(
            path,
            get(move || async move { asset(body, "text/javascript; charset=utf-8") }),
        );
    }
    routes
        .route(
            "/style.css",
            get(|| async { asset(STYLE_CSS, "text/css; charset=utf-8") }),
        )
        .route("/api", post(api))
        .route("/api/region", post(region))
        .route("/api/export", post(export))
        .layer(DefaultBodyLimit::max(MAX_BODY))
        .layer(axum::middleware::from_fn_with_state(port, same_origin))
        .with_state(compute)
}

fn asset(body: &'static str, kind: &'static str) -> Response {
    (
        [
            (header::CONTENT_TYPE, kind),
            (header::CACHE_CONTROL, "no-cache"),
        ],
        body,
    )
        .into_response()
}

/// A JSON response with the compute time in `Server-Timing` (milliseconds).
fn timed_json(v: Value, started: Instant) -> Response {
    let ms = started.elapsed().as_secs_f64() * 1e3;
    let mut r = ([(header::CONTENT_TYPE, "application/json")], v.to_string()).into_response();
    if let Ok(h) = HeaderValue::from_str(&format!("compute;dur={ms:.3}")) {
        r.headers_mut().insert("server-timing", h);
    }
    r
}

fn parse_error(msg: String) -> Value {
    protocol::error_response(
        Value::Null,
        protocol::ProtoError {
            kind: "parse",
            message: msg,
        },
    )
}

/// Limits of the editor's server.
#[derive(Clone, Copy, Debug)]
pub struct Limits {
    /// Wall-clock limit of one request's computation: the client then gets a `timeout`
    /// error, and the library's long loops stop at the same deadline
    /// ([`aesthetic_curves::deadline`]), freeing the slot.
    pub request_timeout: std::time::Duration,
    /// Computations at once (further requests wait for a slot, within their time limit).
    pub computations: usize,
    /// Open connections at once (at the cap, the oldest is closed for the new one).
    pub connections: usize,
    /// Time a client has to send a request's headers (slow or idle connections are closed).
    pub header_timeout: std::time::Duration,
    /// Longest life of a connection (a slowly sent body included).
    pub connection_lifetime: std::time::Duration,
}

impl Default for Limits {
    fn default() -> Self {
        Limits {
            request_timeout: std::time::Duration::from_secs(5),
            computations: std::thread::available_parallelism().map_or(2, |n| n.get().max(2)),
            connections: 128,
            header_timeout: std::time::Duration::from_secs(5),
            connection_lifetime: std::time::Duration::from_secs(60),
        }
    }
}

/// The computation slots and the request time limit.
#[derive(Clone)]
struct Compute {
    slots: std::sync::Arc<tokio::sync::Semaphore>,
    timeout: std::time::Duration,
}

/// Why a computation was not answered.
enum NotAnswered {
    Timeout(std::time::Duration),
    Internal,
}

impl NotAnswered {
    fn value(&self) -> Value {
        let e = match self {
            NotAnswered::Timeout(t) => protocol::ProtoError {
                kind: "timeout",
                message: format!(
                    "the request did not finish within the editor's limit of {:.1} s",
                    t.as_secs_f64()
                ),
            },
            NotAnswered::Internal => protocol::ProtoError {
                kind: "internal",
                message: "the request was not answered".into(),
            },
        };
        protocol::error_response(Value::Null, e)
    }
}

impl Compute {
    /// Run `f` on the blocking pool in one of the slots, within the time limit (waiting for
    /// a slot counts).
    async fn run<T: Send + 'static>(
        &self,
        f: impl FnOnce() -> T + Send + 'static,
    ) -> Result<T, NotAnswered> {
        let slots = self.slots.clone();
        // The library's long loops stop at the same deadline (cooperative cancellation), so
        // a timed-out request frees its slot instead of running on for minutes.
        let deadline = std::time::Instant::now() + self.timeout;
        let work = async move {
            let permit = slots
                .acquire_owned()
                .await
                .map_err(|_| NotAnswered::Internal)?;
            tokio::task::spawn_blocking(move || {
                let out = aesthetic_curves::deadline::with_deadline(deadline, f);
                drop(permit);
                out
            })
            .await
            .map_err(|_| NotAnswered::Internal)
        };
        tokio::time::timeout(self.timeout, work)
            .await
            .map_err(|_| NotAnswered::Timeout(self.timeout))?
    }
}

async fn api(axum::extract::State(c): axum::extract::State<Compute>, body: Bytes) -> Response {
    let started = Instant::now();
    let v = c
        .run(move || match std::str::from_utf8(&body) {
            Ok(text) => protocol::handle_line(text),
            Err(e) => parse_error(format!("request is not UTF-8: {e}")),
        })
        .await
        .unwrap_or_else(|e| e.value());
    timed_json(v, started)
}

/// Region request (`POST /api/region`): the protocol's `region.map` (see
/// [`protocol::region`]), its body without `op`; the answer `{"ok": true, "result": {"rows",
/// "judged"}}`.
fn region_answer(v: &Value) -> Result<Value, protocol::ProtoError> {
    use protocol::Op;
    let r = protocol::region::RegionMap::answer(protocol::read(v.clone())?)?;
    Ok(json!({"ok": true, "result": r}))
}

async fn region(axum::extract::State(c): axum::extract::State<Compute>, body: Bytes) -> Response {
    let started = Instant::now();
    let v = c
        .run(move || match serde_json::from_slice::<Value>(&body) {
            Ok(v) => region_answer(&v).unwrap_or_else(|e| protocol::error_response(Value::Null, e)),
            Err(e) => parse_error(format!("request is not valid JSON: {e}")),
        })
        .await
        .unwrap_or_else(|e| e.value());
    timed_json(v, started)
}

/// The file formats the editor exports.
#[derive(Debug, Clone, Copy, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
enum ExportFormat {
    Dxf,
    Step,
    Iges,
    Svg,
    Json,
}

/// An export request: a NURBS and the format of the file.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
struct ExportRequest {
    format: ExportFormat,
    degree: IntIn<1, 20>,
    control_points: Points<2, 100_000>,
    knots: Vec<f64>,
    #[serde(default)]
    weights: Option<Weights>,
}

impl protocol::Request for ExportRequest {
    fn check(&self) -> Result<(), protocol::ProtoError> {
        let n = self.control_points.0.len();
        let k = n + self.degree.0 as usize + 1;
        if self.knots.len() != k {
            return Err(protocol::ProtoError::invalid(
                "knots",
                format!(
                    "needs {k} numbers (control points + degree + 1), got {}",
                    self.knots.len()
                ),
            ));
        }
        if let Some(w) = &self.weights {
            fields::check_weight_count("weights", n, w.len())?;
        }
        Ok(())
    }
}

/// The file for an export request, or a protocol error.
fn export_file(v: &Value) -> Result<(&'static str, String, Vec<u8>), protocol::ProtoError> {
    let req = protocol::read::<ExportRequest>(v.clone())?;
    let (format, degree, pts, knots) = (req.format, req.degree.0, req.control_points.0, req.knots);
    let weights = req
        .weights
        .map_or_else(|| vec![1.0; pts.len()], |w| fields::weights(&w));
    let curve = Nurbs::new(degree as usize, knots, pts, weights)?;
    crate::export::check_exportable(&curve)
        .map_err(|e| protocol::ProtoError::invalid("control_points", e.to_string()))?;
    let name = "aesthetic_curve";
    let bad = |e: anyhow::Error| protocol::ProtoError::invalid("format", e.to_string());
    Ok(match format {
        ExportFormat::Dxf => (
            "application/dxf",
            "curve.dxf".into(),
            crate::export::dxf_bytes(&curve).map_err(bad)?,
        ),
        ExportFormat::Step => (
            "application/step",
            "curve.step".into(),
            crate::export::step_text(&curve, name).into_bytes(),
        ),
        ExportFormat::Iges => (
            "application/iges",
            "curve.iges".into(),
            crate::export::iges_text(&curve, name).into_bytes(),
        ),
        ExportFormat::Json => (
            "application/json",
            "curve.json".into(),
            crate::export::json_text(&curve).to_string().into_bytes(),
        ),
        ExportFormat::Svg => {
            let doc = crate::export::svg_document(&curve, 1e-6 * curve.size(), &[], name)
                .ok_or_else(|| protocol::ProtoError::invalid("knots", "the curve has no spans"))?;
            ("image/svg+xml", "curve.svg".into(), doc.into_bytes())
        }
    })
}

async fn export(axum::extract::State(c): axum::extract::State<Compute>, body: Bytes) -> Response {
    let started = Instant::now();
    let r = c
        .run(move || match serde_json::from_slice::<Value>(&body) {
            Ok(v) => export_file(&v).map_err(|e| protocol::error_response(Value::Null, e)),
            Err(e) => Err(parse_error(format!("request is not valid JSON: {e}"))),
        })
        .await
        .unwrap_or_else(|e| Err(e.value()));
    match r {
        Ok((kind, file, bytes)) => (
            StatusCode::OK,
            [
                (header::CONTENT_TYPE, kind.to_string()),
                (
                    header::CONTENT_DISPOSITION,
                    format!("attachment; filename=\"{file}\""),
                ),
            ],
            bytes,
        )
            .into_response(),
        Err(v) => timed_json(v, started),
    }
}

/// The editor's open connections, oldest first, and the last connection number.
#[derive(Default)]
struct OpenConnections {
    next: u64,
    open: std::collections::VecDeque<(u64, tokio::task::AbortHandle)>,
}

/// Serve the editor on 127.0.0.1:`port` (0: any free port); prints the URL, then opens it
/// in the system's browser unless `open` is false. Runs until the process is stopped.
///
/// Connections: at most `limits.connections` open (at the cap the oldest is closed), headers within
/// `limits.header_timeout` (a client that sends them slowly, or keeps a connection idle, is
/// cut off), each connection closed after `limits.connection_lifetime`.
pub fn serve(port: u16, open: bool, limits: Limits) -> anyhow::Result<()> {
    let rt = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()?;
    rt.block_on(async move {
        let listener = tokio::net::TcpListener::bind((std::net::Ipv4Addr::LOCALHOST, port))
            .await
            .map_err(|e| anyhow::anyhow!("cannot listen on 127.0.0.1:{port}: {e}"))?;
        let addr = listener.local_addr()?;
        let url = format!("http://{addr}/");
        println!("editor: {url}");
        use std::io::Write;
        std::io::stdout().flush()?;
        if open {
            // Best effort: a desktop's URL opener; the URL is printed either way.
            let _ = std::process::Command::new("xdg-open")
                .arg(&url)
                .stdout(std::process::Stdio::null())
                .stderr(std::process::Stdio::null())
                .spawn();
        }
        let app = router(addr.port(), limits);
        // The open connections, oldest first: at the cap, the oldest is closed to make room
        // (a flood of idle connections cannot lock a new request out).
        let open_conns: std::sync::Arc<std::sync::Mutex<OpenConnections>> = Default::default();
        loop {
            let (stream, _) = match listener.accept().await {
                Ok(c) => c,
                // Out of file descriptors and the like: wait and go on.
                Err(_) => {
                    tokio::time::sleep(std::time::Duration::from_millis(50)).await;
                    continue;
                }
            };
            let id = {
                let mut c = open_conns.lock().unwrap_or_else(|e| e.into_inner());
                while c.open.len() >= limits.connections.max(1) {
                    if let Some((_, h)) = c.open.pop_front() {
                        h.abort();
                    }
                }
                c.next += 1;
                c.next
            };
            let svc = hyper_util::service::TowerToHyperService::new(app.clone());
            let registry = open_conns.clone();
            let task = tokio::spawn(async move {
                let conn = hyper::server::conn::http1::Builder::new()
                    .timer(hyper_util::rt::TokioTimer::new())
                    .header_read_timeout(limits.header_timeout)
                    .serve_connection(hyper_util::rt::TokioIo::new(stream), svc);
                let _ = tokio::time::timeout(limits.connection_lifetime, conn).await;
                let mut c = registry.lock().unwrap_or_else(|e| e.into_inner());
                c.open.retain(|(i, _)| *i != id);
            });
            let mut c = open_conns.lock().unwrap_or_else(|e| e.into_inner());
            if !task.is_finished() {
                c.open.push_back((id, task.abort_handle()));
            }
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The grid of a request's `grid` field (errors named `grid.x0`, ...).
    fn grid_param(v: &Value) -> Result<aesthetic_curves::region::Grid, protocol::ProtoError> {
        #[derive(Deserialize, JsonSchema)]
        struct G {
            grid: protocol::region::GridJson,
        }
        impl protocol::Request for G {}
        protocol::read::<G>(json!({ "grid": v }))?.grid.grid()
    }

    use serde_json::json;

    #[test]
    fn only_this_server_is_a_host() {
        for h in [
            "127.0.0.1:8731",
            "localhost:8731",
            "LOCALHOST:8731",
            "[::1]:8731",
        ] {
            assert!(host_ok(h, 8731), "{h}");
        }
        for h in [
            "127.0.0.1",
            "127.0.0.1:8732",
            "evil.example:8731",
            "localhost.evil:8731",
            "",
        ] {
            assert!(!host_ok(h, 8731), "{h}");
        }
    }

    #[test]
    fn a_grid_is_refused_with_the_field_that_is_wrong() {
        let ok = json!({"x0": 0, "y0": 0, "x1": 2, "y1": 1, "nx": 4, "ny": 3});
        assert!(grid_param(&ok).is_ok());
        for (key, bad) in [
            ("nx", json!(0)),
            ("ny", json!(MAX_REGION_CELLS + 1)),
            ("x1", json!("2")),
            ("y0", Value::Null),
        ] {
            let mut g = ok.clone();
            g[key] = bad;
            let e = grid_param(&g).unwrap_err();
            assert!(
                e.message.contains(&format!("grid.{key}")),
                "{key}: {}",
                e.message
            );
            assert_eq!(e.kind, "invalid_input");
        }
    }

    #[test]
    fn a_region_answers_one_row_of_cells_per_grid_row() {
        // Where a cubic's third control point keeps its curvature monotone.
        let v = json!({
            "kind": "bezier",
            "control_points": [[0, 0], [1, 0], [2, 1], [3, 3]],
            "index": 2,
            "grid": {"x0": 0, "y0": -1, "x1": 3, "y1": 3, "nx": 6, "ny": 5},
        });
        let r = region_answer(&v).unwrap();
        assert_eq!(r["ok"], true);
        let rows = r["result"]["rows"].as_array().unwrap();
        assert_eq!(rows.len(), 5);
        assert!(rows.iter().all(|row| {
            let s = row.as_str().unwrap();
            s.len() == 6 && s.chars().all(|c| c == '0' || c == '1')
        }));
        // The given position itself, (2, 1), is in cell (4, 2): the curve there is monotone
        // or not as the exact test says.
        let here = aesthetic_curves::Bezier::new(vec![
            aesthetic_curves::Point::new(0.0, 0.0),
            aesthetic_curves::Point::new(1.0, 0.0),
            aesthetic_curves::Point::new(2.25, 1.2),
            aesthetic_curves::Point::new(3.0, 3.0),
        ])
        .unwrap();
        use aesthetic_curves::CurvatureMonotone;
        let want = if here.is_curvature_monotone().unwrap() {
            '1'
        } else {
            '0'
        };
        assert_eq!(rows[2].as_str().unwrap().chars().nth(4), Some(want));
        assert!(region_answer(&json!({"kind": "nope", "grid": v["grid"]})).is_err());
    }
}

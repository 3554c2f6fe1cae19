//! `spintop book`'s server: the built book over HTTP on loopback, and ▶ for
//! its snippets, compiled against the local spintop and run here.
//!
//! A shell beside the CLI and the TUI (the CLI only launches it). Requests
//! are parsed by `httparse`; each connection has a thread of its own
//! (`http.rs` says why no pooled server crate). What is written here is the
//! policy, because it runs code on the reader's machine:
//!
//! - it listens on 127.0.0.1 only;
//! - a random token, made at start-up and written only into the pages it
//!   serves, must come with every run request (`X-Spintop-Token`), or 403;
//! - a `Host` other than `127.0.0.1:PORT` / `localhost:PORT` (DNS rebinding)
//!   or a foreign `Origin` is refused, 403;
//! - one run at a time: a second request while one runs gets 429;
//! - limits on the request (64 KiB, else 413), the compile time, the run time
//!   (then the process is killed) and the output (then truncated, with a note);
//! - it writes only inside its scratch folder; a malformed body is 400, a
//!   wrong method 405, an unknown path 404, each with a one-line reason.
//!
//! The run protocol keeps mdBook's: the page POSTs the playground's JSON
//! (`{"code": …, "edition": …}`) to `/evaluate.json` and gets the
//! playground's answer shape, `{"result": …}`. A run that takes longer than
//! [`Limits::answer_within`] (a cold first build) is answered 202 with
//! `"pending": true`, and the page polls `/evaluate/status` for its progress
//! and, in the end, its result (mdBook's own request times out after 6 s).

#[doc(hidden)]
pub mod http;
mod run;

pub use run::{Limits, Outcome, OutcomeKind, Runner, default_runner};

use std::io::Read;
use std::net::{TcpListener, TcpStream};
use std::path::{Component, Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;

/// Why the server could not start.
#[derive(Debug, thiserror::Error)]
pub enum ServerError {
    /// The port could not be bound.
    #[error("cannot listen on 127.0.0.1:{port}: {reason}")]
    Bind {
        /// The port asked for.
        port: u16,
        /// The system's reason.
        reason: String,
    },
}

/// What the server serves and where it runs snippets.
#[derive(Debug, Clone)]
pub struct Config {
    /// The built book (mdBook's output folder).
    pub site: PathBuf,
    /// The port, 0 for a free one.
    pub port: u16,
    /// Where snippets are compiled and run.
    pub runner: Runner,
}

/// The state of the one run that may be going on.
#[derive(Debug, Default)]
struct Job {
    running: bool,
    progress: String,
    last: Option<Outcome>,
}

/// The most connections served at once; one more is answered 503 and
/// closed (a browser opens six per page).
const MAX_CONNECTIONS: usize = 64;

/// A running server.
pub struct Server {
    listener: TcpListener,
    inner: Arc<Inner>,
}

/// What every connection's thread shares.
struct Inner {
    port: u16,
    token: String,
    config: Config,
    job: Arc<Mutex<Job>>,
    open: AtomicUsize,
}

/// An answer: status, content type, body.
struct Reply {
    code: u16,
    content_type: &'static str,
    body: Vec<u8>,
}

/// A token nobody can guess: 128 bits from the system's random source.
fn new_token() -> String {
    let mut bytes = [0u8; 16];
    let read = std::fs::File::open("/dev/urandom").and_then(|mut f| f.read_exact(&mut bytes));
    if read.is_err() {
        // No /dev/urandom: the std hasher's random keys, twice.
        use std::hash::{BuildHasher, RandomState};
        let a = RandomState::new()
            .hash_one(std::process::id())
            .to_le_bytes();
        let b = RandomState::new().hash_one(a).to_le_bytes();
        bytes[..8].copy_from_slice(&a);
        bytes[8..].copy_from_slice(&b);
    }
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

impl Server {
    /// Binds 127.0.0.1:`config.port`.
    pub fn bind(config: Config) -> Result<Self, ServerError> {
        let bind_error = |e: std::io::Error| ServerError::Bind {
            port: config.port,
            reason: e.to_string(),
        };
        let listener = TcpListener::bind(("127.0.0.1", config.port)).map_err(bind_error)?;
        listener.set_nonblocking(true).map_err(bind_error)?;
        let port = listener
            .local_addr()
            .map(|a| a.port())
            .unwrap_or(config.port);
        Ok(Self {
            listener,
            inner: Arc::new(Inner {
                port,
                token: new_token(),
                config,
                job: Arc::default(),
                open: AtomicUsize::new(0),
            }),
        })
    }

    /// The port it listens on.
    pub fn port(&self) -> u16 {
        self.inner.port
    }

    /// The book's address.
    pub fn url(&self) -> String {
        format!("http://127.0.0.1:{}/", self.inner.port)
    }

    /// The token (for tests, which play the page's part).
    pub fn token(&self) -> &str {
        &self.inner.token
    }

    /// Accepts connections until `stop` is set (checked every 20 ms); each
    /// connection is served on a thread of its own, so that one a browser
    /// keeps open never holds up another.
    pub fn serve(&self, stop: &AtomicBool) {
        while !stop.load(Ordering::Relaxed) {
            match self.listener.accept() {
                Ok((stream, _)) => {
                    if self.inner.open.load(Ordering::Relaxed) >= MAX_CONNECTIONS {
                        if let Ok(mut c) = http::Connection::new(stream) {
                            let _ = c.respond(503, &[], b"too many connections", false, false);
                        }
                        continue;
                    }
                    let inner = Arc::clone(&self.inner);
                    inner.open.fetch_add(1, Ordering::Relaxed);
                    std::thread::spawn(move || {
                        inner.connection(stream);
                        inner.open.fetch_sub(1, Ordering::Relaxed);
                    });
                }
                // Nothing waiting (the listener does not block), or a
                // transient failure such as too many open files.
                Err(_) => std::thread::sleep(Duration::from_millis(20)),
            }
        }
    }
}

impl Inner {
    /// Serves one connection's requests in order until it closes.
    fn connection(&self, stream: TcpStream) {
        let Ok(mut conn) = http::Connection::new(stream) else {
            return;
        };
        let limit = self.config.runner.limits.request_bytes;
        loop {
            let (reply, keep_alive, head_only) = match conn.next_request(limit) {
                Ok(request) => {
                    let reply = self.handle(&request);
                    (reply, request.keep_alive, request.method == "HEAD")
                }
                Err(http::ReadError::Closed) => return,
                Err(http::ReadError::Malformed(why)) => (reason(400, &why), false, false),
            };
            let headers = [
                ("Content-Type", reply.content_type),
                ("Cache-Control", "no-store"),
            ];
            let sent = conn.respond(reply.code, &headers, &reply.body, keep_alive, head_only);
            if sent.is_err() || !keep_alive {
                return;
            }
        }
    }

    fn handle(&self, request: &http::Request) -> Reply {
        let host = request.header("Host").unwrap_or_default();
        let allowed_hosts = [
            format!("127.0.0.1:{}", self.port),
            format!("localhost:{}", self.port),
        ];
        if !allowed_hosts.iter().any(|h| h == host) {
            return reason(403, &format!("refused: Host {host:?} is not this server"));
        }
        if let Some(origin) = request.header("Origin") {
            let own = allowed_hosts
                .iter()
                .any(|h| origin == format!("http://{h}"));
            if !own {
                return reason(403, &format!("refused: Origin {origin:?} is not this book"));
            }
        }
        let path = request.url.split('?').next().unwrap_or("/");
        let method = request.method.as_str();
        match path {
            "/evaluate.json" | "/evaluate/status" => {
                if request.header("X-Spintop-Token") != Some(self.token.as_str()) {
                    return reason(
                        403,
                        "refused: no valid token (runs are accepted only from this book's own pages)",
                    );
                }
                if path == "/evaluate/status" {
                    if method != "GET" {
                        return reason(405, "use GET for /evaluate/status");
                    }
                    return self.status();
                }
                if method != "POST" {
                    return reason(405, "use POST for /evaluate.json");
                }
                let limit = self.config.runner.limits.request_bytes;
                match &request.body {
                    http::Body::Read(body) => self.evaluate(body),
                    http::Body::TooLong => reason(
                        413,
                        &format!("the snippet is larger than {} KiB", limit / 1024),
                    ),
                    http::Body::Chunked => reason(411, "send the snippet with a Content-Length"),
                }
            }
            _ => {
                if method != "GET" && method != "HEAD" {
                    return reason(405, "the book is read with GET");
                }
                self.file(path)
            }
        }
    }

    /// A file of the built book; HTML pages receive the token.
    fn file(&self, path: &str) -> Reply {
        let Some(file) = site_file(&self.config.site, path) else {
            return reason(404, &format!("no such page: {path}"));
        };
        let Ok(mut bytes) = std::fs::read(&file) else {
            return reason(404, &format!("no such page: {path}"));
        };
        let ext = file.extension().and_then(|e| e.to_str()).unwrap_or("");
        if ext == "html" {
            let text = String::from_utf8_lossy(&bytes);
            let script = format!(
                "<script>window.spintopBook = {{ token: \"{}\" }};</script>",
                self.token
            );
            bytes = match text.find("<head>") {
                Some(i) => format!("{}{script}{}", &text[..i + 6], &text[i + 6..]),
                None => format!("{script}{text}"),
            }
            .into_bytes();
        }
        Reply {
            code: 200,
            content_type: content_type(ext),
            body: bytes,
        }
    }

    /// `/evaluate.json`: start a run, answer within [`Limits::answer_within`].
    fn evaluate(&self, body: &[u8]) -> Reply {
        #[derive(serde::Deserialize)]
        struct Params {
            code: String,
            #[serde(default)]
            edition: Option<String>,
        }
        let params: Params = match serde_json::from_slice(body) {
            Ok(p) => p,
            Err(e) => return reason(400, &format!("malformed request: {e}")),
        };
        {
            let mut job = lock(&self.job);
            if job.running {
                return json(
                    429,
                    serde_json::json!({
                        "result": "busy: another snippet is running; press ▶ again when it has finished",
                        "error": "busy",
                    }),
                );
            }
            *job = Job {
                running: true,
                progress: "starting".into(),
                last: None,
            };
        }
        let job = Arc::clone(&self.job);
        let runner = self.config.runner.clone();
        let edition = params.edition.unwrap_or_else(|| "2024".into());
        let answer_within = runner.limits.answer_within;
        let (done_tx, done_rx) = std::sync::mpsc::channel();
        // The run on a thread of its own: this connection answers within
        // `answer_within` (202 and "pending" if the run goes on), and other
        // connections meanwhile are told "busy", not queued.
        std::thread::spawn(move || {
            let progress_job = Arc::clone(&job);
            let outcome = runner.run(&params.code, &edition, &mut |line: &str| {
                lock(&progress_job).progress = line.to_string();
            });
            let mut j = lock(&job);
            j.running = false;
            j.last = Some(outcome.clone());
            drop(j);
            let _ = done_tx.send(outcome);
        });
        match done_rx.recv_timeout(answer_within) {
            Ok(outcome) => json(200, outcome_json(&outcome)),
            Err(_) => json(
                202,
                serde_json::json!({
                    "result": "compiling… (the first run builds spintop for the book: a minute or two on a small machine; later runs take a second or two)",
                    "pending": true,
                }),
            ),
        }
    }

    /// `/evaluate/status`: the run's progress, or its outcome once done.
    fn status(&self) -> Reply {
        let job = lock(&self.job);
        let value = match (&job.running, &job.last) {
            (true, _) => serde_json::json!({ "done": false, "progress": job.progress }),
            (false, Some(outcome)) => {
                let mut v = outcome_json(outcome);
                v["done"] = serde_json::Value::Bool(true);
                v
            }
            (false, None) => serde_json::json!({ "done": true, "result": "" }),
        };
        drop(job);
        json(200, value)
    }
}

fn lock(job: &Mutex<Job>) -> std::sync::MutexGuard<'_, Job> {
    job.lock().unwrap_or_else(|e| e.into_inner())
}

/// The playground's answer shape: `result` is what the page shows.
fn outcome_json(outcome: &Outcome) -> serde_json::Value {
    serde_json::json!({
        "result": outcome.shown(),
        "error": outcome.error_kind(),
        "success": outcome.success(),
    })
}

/// The file under `site` that `path` names, if it stays inside `site`.
pub fn site_file(site: &Path, path: &str) -> Option<PathBuf> {
    let decoded = percent_decode(path)?;
    let rel = decoded.trim_start_matches('/');
    let rel = if rel.is_empty() || rel.ends_with('/') {
        format!("{rel}index.html")
    } else {
        rel.to_string()
    };
    let rel = Path::new(&rel);
    if rel.components().any(|c| !matches!(c, Component::Normal(_))) {
        return None;
    }
    let file = site.join(rel);
    file.is_file().then_some(file)
}

/// `%xx` decoding; `None` for a malformed escape or a NUL.
fn percent_decode(s: &str) -> Option<String> {
    let bytes = s.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = s.get(i + 1..i + 3)?;
            out.push(u8::from_str_radix(hex, 16).ok()?);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    let text = String::from_utf8(out).ok()?;
    (!text.contains('\0')).then_some(text)
}

fn content_type(ext: &str) -> &'static str {
    match ext {
        "html" => "text/html; charset=utf-8",
        "css" => "text/css; charset=utf-8",
        "js" => "text/javascript; charset=utf-8",
        "svg" => "image/svg+xml",
        "png" => "image/png",
        "json" => "application/json",
        "woff" => "font/woff",
        "woff2" => "font/woff2",
        "ttf" => "font/ttf",
        "ico" => "image/x-icon",
        "txt" | "md" => "text/plain; charset=utf-8",
        _ => "application/octet-stream",
    }
}

/// A one-line reason, as JSON in the playground's shape (the page shows it).
fn reason(code: u16, why: &str) -> Reply {
    json(code, serde_json::json!({ "result": why, "error": why }))
}

fn json(code: u16, value: serde_json::Value) -> Reply {
    Reply {
        code,
        content_type: "application/json",
        body: value.to_string().into_bytes(),
    }
}

/// A minimal HTTP/1.1 client for the server's own checks (`spintop book
/// --self-test` and the tests): one request, `Connection: close`, the
/// status code and the body back.
pub fn request(
    port: u16,
    method: &str,
    path: &str,
    headers: &[(&str, &str)],
    body: &[u8],
) -> std::io::Result<(u16, String)> {
    use std::io::Write;
    let mut stream = std::net::TcpStream::connect(("127.0.0.1", port))?;
    stream.set_read_timeout(Some(Duration::from_secs(1200)))?;
    let mut head = format!(
        "{method} {path} HTTP/1.1\r\nConnection: close\r\nContent-Length: {}\r\n",
        body.len()
    );
    if !headers.iter().any(|(k, _)| k.eq_ignore_ascii_case("Host")) {
        head.push_str(&format!("Host: 127.0.0.1:{port}\r\n"));
    }
    for (k, v) in headers {
        head.push_str(&format!("{k}: {v}\r\n"));
    }
    head.push_str("\r\n");
    stream.write_all(head.as_bytes())?;
    stream.write_all(body)?;
    let mut raw = Vec::new();
    stream.read_to_end(&mut raw)?;
    let text = String::from_utf8_lossy(&raw).into_owned();
    let code = text
        .split_whitespace()
        .nth(1)
        .and_then(|c| c.parse().ok())
        .unwrap_or(0);
    let body = text
        .split_once("\r\n\r\n")
        .map(|(_, b)| b.to_string())
        .unwrap_or_default();
    Ok((code, body))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_path_outside_the_site_is_never_a_file() {
        let site = Path::new(env!("CARGO_MANIFEST_DIR")).join("book/src");
        assert!(site_file(&site, "/SUMMARY.md").is_some());
        assert!(
            site_file(&site, "/figures/").is_none(),
            "no index.html there"
        );
        for bad in [
            "/../Cargo.toml",
            "/figures/../../Cargo.toml",
            "/%2e%2e/Cargo.toml",
            "//etc/passwd",
            "/a%00b",
            "/%zz",
        ] {
            assert!(site_file(&site, bad).is_none(), "{bad}");
        }
    }

    #[test]
    fn tokens_are_long_and_differ() {
        let (a, b) = (new_token(), new_token());
        assert_eq!(a.len(), 32);
        assert_ne!(a, b);
    }
}

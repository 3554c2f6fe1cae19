//! `spintop book`'s server: the built book over HTTP on loopback, and ▶ for
//! its snippets, compiled against the local spintop and run here.
//!
//! A shell beside the CLI and the TUI (the CLI only launches it). Requests
//! are parsed by `httparse`; each connection has a thread of its own
//! (`http.rs` says why no pooled server crate). Because it runs code on the
//! reader's machine, this is what holds, each point tested against the real
//! server in `tests/server.rs`:
//!
//! # Who can run code: the reader, holding the printed address
//!
//! Jupyter's model, and one step further. The port is visible to every user
//! of the machine (`ss -ltn`), so the key is a token: 128 random bits, made
//! at start-up, kept in memory and shown only in the address the server
//! prints, `http://127.0.0.1:PORT/?token=…` ([`Server::url`]).
//!
//! - On Linux, only the reader's processes (and root's) are served: the
//!   kernel's socket tables say whose process made each connection
//!   (`src/server/peer.rs`), and another user's gets 403 whatever it
//!   holds, without taking one of the reader's connections. The token alone
//!   would not do: a browser sends a host's cookies to every port of it, so
//!   a page of another user's server on 127.0.0.1 that the reader opens (by
//!   a link, or a web page that forwards there) receives the cookie, which
//!   is the token. Elsewhere the token is the only key, and a reader who
//!   shares the machine should open no other user's pages on 127.0.0.1
//!   while the book is open.
//! - Every request needs it, pages and static files included. The first
//!   visit with `?token=` sets a cookie (HttpOnly, SameSite=Strict, named
//!   after the port, since a host's cookies are shared by all its ports) and
//!   redirects to the address without the token; a request with neither gets
//!   a 403 page that says to open the address printed in the terminal.
//! - A run (`/evaluate.json`, `/evaluate/status`) carries the token in a
//!   header (`X-Spintop-Token`) that the served pages add; a cookie alone
//!   does not start a run.
//! - Tokens are compared in constant time (`subtle`).
//! - Other origins: the server listens on 127.0.0.1 only; a `Host` other
//!   than `127.0.0.1:PORT`/`localhost:PORT` (DNS rebinding) or a foreign
//!   `Origin` is refused (403); no CORS headers; every answer forbids framing
//!   (`X-Frame-Options: DENY`, CSP `frame-ancestors 'none'`) and sniffing
//!   (`nosniff`), and sends no referrer and `Cache-Control: no-store`.
//!
//! # What a snippet can do: anything the reader can, within limits
//!
//! A snippet runs as the reader, with the reader's files and network. Each
//! build and each run is a process tree under a supervisor
//! (`src/server/tree.rs` says how): its own session and process group, a
//! child subreaper so that what it starts (daemons, double forks, `setsid`,
//! `nohup`) stays in the tree, and for a run resource limits ([`Limits`]):
//! per process 4 GiB of address space and 11 CPU seconds, files up to
//! 64 MiB each, no core dumps, and at most 512 processes and threads more
//! than the reader had when it started (the kernel does not hold root to
//! that one). These bound each process, not the tree's sum: its processes
//! together may take more memory, and its files more disk (or `/dev/shm`,
//! which is memory). A compile (cargo, rustc) has only its time limit. One
//! tree at a time: a second ▶ gets 429 with what is busy and for how long.
//! A run is killed, whole, after 10 s; a compile after 120 s once the
//! scratch project is built (900 s for the first, cold build); the output
//! is cut at 64 KiB.
//!
//! A snippet may kill its own supervisor (it runs as the reader): what it
//! started then lands on the server, and `spintop book` kills every process
//! below it but the running tree as soon as it sees a child end
//! ([`Server::sweep_strays`]). What a snippet hands to a service outside
//! its tree (cron, `systemd-run`, an already running tmux server), or a
//! program written to outrun the kill (each process forking the next and
//! ending faster than `/proc` can be read), is beyond these limits, as it
//! would be for any program the reader runs.
//!
//! # Slow clients
//!
//! A request must arrive whole (head and body) within 10 s of its first byte
//! ([`Limits::request_time`]), else 408; at [`MAX_CONNECTIONS`] the oldest
//! idle or slow connection is dropped for a new one, so slow connections
//! cannot shut the book (and on Linux another user's connections are never
//! among them). Malformed requests get a 4xx with a one-line
//! reason: 400, 405, 404, 411, 413 (over 64 KiB).
//!
//! # Stops
//!
//! [`Server::shutdown`] (also on drop) kills the running tree, a snippet or
//! cargo with its compilers, and waits until it is gone; `spintop book`
//! calls it on SIGINT, SIGTERM, SIGHUP and SIGQUIT, then kills whatever a
//! snippet left to it, and says whether anything survived. If the server
//! itself is killed (SIGKILL), each supervisor sees its control pipe close
//! and kills its tree; what a snippet had already left to the server then
//! goes to init.
//!
//! # What is written where
//!
//! The built book (`target/spintop-book/site`, by mdBook), the scratch
//! project (`target/spintop-book/scratch`), the build folder it shares with
//! the workspace (`target/debug`: spintop's debug build and the snippet's
//! program), and with `--open` a page readable by the reader only that
//! forwards the browser to the address (removed at stop). And whatever a
//! snippet itself writes.
//!
//! The run protocol keeps mdBook's: the page POSTs the playground's JSON
//! (`{"code": …, "edition": …}`) to `/evaluate.json` and gets the
//! playground's answer shape, `{"result": …}`. A run that takes longer than
//! [`Limits::answer_within`] (a cold first build) is answered 202 with
//! `"pending": true`, and the page polls `/evaluate/status` for its progress
//! and, in the end, its result (mdBook's own request times out after 6 s).
//! At start the server builds the scratch project in the background
//! ([`Server::warm_up`]), so that the reader's first ▶ compiles only the
//! snippet; a ▶ pressed meanwhile waits for that build and shows its
//! progress.

#[doc(hidden)]
pub mod http;
mod peer;
mod run;
mod tree;

pub use run::{Limits, Outcome, OutcomeKind, Runner, SNIPPET_CRATES, default_runner};
pub use tree::{SUPERVISE_FLAG, supervise};

use run::{Shared, Stage};
use std::io::Read;
use std::net::{TcpListener, TcpStream};
use std::path::{Component, Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, Instant};
use subtle::ConstantTimeEq;

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

/// The most connections of other users' processes answered (403) at once;
/// more are closed unanswered.
const REFUSING: usize = 8;

/// The most connections served at once (a browser opens six per page);
/// when they are all open, the oldest idle or slow one is dropped for a new
/// one, and if none is (all are being answered), the new one gets 503.
pub const MAX_CONNECTIONS: usize = 64;

/// The headers of every answer: no framing, no sniffing, no referrer, no
/// copy kept (the pages carry the token).
const SECURITY_HEADERS: [(&str, &str); 5] = [
    ("X-Frame-Options", "DENY"),
    ("Content-Security-Policy", "frame-ancestors 'none'"),
    ("X-Content-Type-Options", "nosniff"),
    ("Referrer-Policy", "no-referrer"),
    ("Cache-Control", "no-store"),
];

/// Where the one ▶ run that may be going on is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Phase {
    /// Waiting for the background build (or another tree) to end.
    Waiting,
    /// Cargo compiles it.
    Compiling,
    /// The program runs.
    Running,
}

/// The state of the one ▶ run that may be going on, and the last outcome.
#[derive(Debug)]
struct Job {
    running: bool,
    phase: Phase,
    since: Instant,
    progress: String,
    last: Option<Outcome>,
}

impl Default for Job {
    fn default() -> Self {
        Self {
            running: false,
            phase: Phase::Waiting,
            since: Instant::now(),
            progress: String::new(),
            last: None,
        }
    }
}

/// The background build of the scratch project ([`Server::warm_up`]).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum WarmUp {
    /// Not started.
    NotStarted,
    /// Going on: for how long, and cargo's last progress line.
    Building {
        /// Since it started.
        elapsed: Duration,
        /// Cargo's last "Compiling …" line.
        progress: String,
    },
    /// Done: ▶ compiles only the snippet now.
    Ready {
        /// How long it took.
        took: Duration,
    },
    /// It failed (▶ then builds, and shows why).
    Failed {
        /// What went wrong, as ▶ would show it.
        why: String,
    },
}

/// [`WarmUp`] as stored: `Building` keeps its start.
#[derive(Debug, Clone)]
enum WarmState {
    NotStarted,
    Building { started: Instant, progress: String },
    Ready { took: Duration },
    Failed { why: String },
}

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
    job: Mutex<Job>,
    shared: Shared,
    warm: Mutex<WarmState>,
    connections: Mutex<Vec<Arc<http::Watch>>>,
    refusing: AtomicUsize,
}

/// An answer: status, content type, further headers, body.
struct Reply {
    code: u16,
    content_type: &'static str,
    headers: Vec<(&'static str, String)>,
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

fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|e| e.into_inner())
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
                job: Mutex::default(),
                shared: Shared::default(),
                warm: Mutex::new(WarmState::NotStarted),
                connections: Mutex::default(),
                refusing: AtomicUsize::new(0),
            }),
        })
    }

    /// The port it listens on.
    pub fn port(&self) -> u16 {
        self.inner.port
    }

    /// The address to open, the key included: the only address that
    /// answers (`http://127.0.0.1:PORT/?token=…`).
    pub fn url(&self) -> String {
        format!(
            "http://127.0.0.1:{}/?token={}",
            self.inner.port, self.inner.token
        )
    }

    /// The token (for tests and `--self-test`, which play the page's part).
    pub fn token(&self) -> &str {
        &self.inner.token
    }

    /// The name of the cookie the first visit sets: it holds the port, since
    /// a host's cookies are shared by all its ports.
    pub fn cookie_name(&self) -> String {
        self.inner.cookie_name()
    }

    /// Starts the background build of the scratch project (once), so that
    /// the reader's first ▶ compiles only the snippet. A ▶ pressed while it
    /// goes on waits for it, and its status shows the build's progress.
    pub fn warm_up(&self) {
        {
            let mut warm = lock(&self.inner.warm);
            if !matches!(*warm, WarmState::NotStarted) {
                return;
            }
            *warm = WarmState::Building {
                started: Instant::now(),
                progress: "starting cargo".into(),
            };
        }
        let inner = Arc::clone(&self.inner);
        std::thread::spawn(move || {
            let outcome = inner.config.runner.warm_up(&inner.shared, &mut |stage| {
                if let Stage::Line(line) = stage
                    && let WarmState::Building { progress, .. } = &mut *lock(&inner.warm)
                {
                    *progress = line.to_string();
                }
            });
            *lock(&inner.warm) = if outcome.success() {
                WarmState::Ready {
                    took: outcome.elapsed,
                }
            } else {
                WarmState::Failed {
                    why: outcome.shown(),
                }
            };
        });
    }

    /// Where the background build is.
    pub fn warm_up_state(&self) -> WarmUp {
        match lock(&self.inner.warm).clone() {
            WarmState::NotStarted => WarmUp::NotStarted,
            WarmState::Building { started, progress } => WarmUp::Building {
                elapsed: started.elapsed(),
                progress,
            },
            WarmState::Ready { took } => WarmUp::Ready { took },
            WarmState::Failed { why } => WarmUp::Failed { why },
        }
    }

    /// Accepts connections until `stop` is set (checked every 20 ms); each
    /// connection is served on a thread of its own, so that one a browser
    /// keeps open never holds up another. This process becomes a child
    /// subreaper first (see `src/server/tree.rs`).
    pub fn serve(&self, stop: &AtomicBool) {
        tree::become_subreaper();
        while !stop.load(Ordering::Relaxed) {
            match self.listener.accept() {
                Ok((stream, _)) => {
                    let peer = peer::peer(&stream);
                    let Ok(mut conn) = http::Connection::new(stream) else {
                        continue;
                    };
                    if let Some(why) = refusal(peer) {
                        self.inner.refuse(conn, why);
                        continue;
                    }
                    if !self.inner.admit(&conn) {
                        let _ = conn.respond(
                            503,
                            &SECURITY_HEADERS,
                            b"too many connections",
                            false,
                            false,
                        );
                        continue;
                    }
                    let inner = Arc::clone(&self.inner);
                    std::thread::spawn(move || {
                        let watch = conn.watch();
                        inner.connection(conn);
                        lock(&inner.connections).retain(|w| !Arc::ptr_eq(w, &watch));
                    });
                }
                // Nothing waiting (the listener does not block), or a
                // transient failure such as too many open files.
                Err(_) => std::thread::sleep(Duration::from_millis(20)),
            }
        }
    }

    /// Stops: kills the running process tree (a snippet, or cargo and its
    /// compilers) and refuses new ones; returns once it is gone (true), or
    /// after 3 s without seeing it go (false).
    pub fn shutdown(&self) -> bool {
        self.inner.shared.slot.close(Duration::from_secs(1))
    }

    /// For a process that serves this server and starts nothing else
    /// (`spintop book`): kills every process below this one but the running
    /// tree, and reaps those that have ended; returns how many living ones
    /// it found. A snippet that kills its own supervisor leaves what it
    /// started to this process (see `src/server/tree.rs`); calling this
    /// when a child ends (SIGCHLD) keeps one tree at a time, and after
    /// [`Server::shutdown`], nothing running.
    pub fn sweep_strays(&self) -> usize {
        self.inner.shared.slot.sweep_strays()
    }
}

impl Drop for Server {
    fn drop(&mut self) {
        self.shutdown();
    }
}

impl Inner {
    fn cookie_name(&self) -> String {
        format!("spintop-book-{}", self.port)
    }

    /// Whether `candidate` is the token, in time that does not depend on
    /// where they differ.
    fn is_token(&self, candidate: &str) -> bool {
        bool::from(candidate.as_bytes().ct_eq(self.token.as_bytes()))
    }

    /// Whether the request carries the cookie the first visit set.
    fn has_cookie(&self, request: &http::Request) -> bool {
        let name = self.cookie_name();
        request
            .headers("Cookie")
            .flat_map(|v| v.split(';'))
            .filter_map(|pair| pair.trim().split_once('='))
            .any(|(k, v)| k == name && self.is_token(v))
    }

    /// Answers a connection of another user's process 403 (on a thread of
    /// its own, after reading its request for at most a second), never
    /// among the reader's connections; at most [`REFUSING`] at once, the
    /// rest closed unanswered.
    fn refuse(self: &Arc<Self>, mut conn: http::Connection, why: String) {
        if self.refusing.fetch_add(1, Ordering::SeqCst) >= REFUSING {
            self.refusing.fetch_sub(1, Ordering::SeqCst);
            return;
        }
        let inner = Arc::clone(self);
        std::thread::spawn(move || {
            conn.set_request_time(Duration::from_secs(1));
            let limit = inner.config.runner.limits.request_bytes;
            if !matches!(conn.next_request(limit), Err(http::ReadError::Closed)) {
                let reply = reason(403, &why);
                let mut headers: Vec<(&str, &str)> = vec![("Content-Type", reply.content_type)];
                headers.extend(SECURITY_HEADERS);
                let _ = conn.respond(403, &headers, &reply.body, false, false);
            }
            inner.refusing.fetch_sub(1, Ordering::SeqCst);
        });
    }

    /// Makes room for `conn`: at [`MAX_CONNECTIONS`], the connection idle or
    /// slow for longest is dropped; false if every one is being answered.
    fn admit(&self, conn: &http::Connection) -> bool {
        let mut open = lock(&self.connections);
        if open.len() >= MAX_CONNECTIONS {
            let oldest = open
                .iter()
                .enumerate()
                .filter_map(|(i, w)| w.droppable_since().map(|since| (since, i)))
                .min();
            match oldest {
                Some((_, i)) => open.swap_remove(i).drop_now(),
                None => return false,
            }
        }
        open.push(conn.watch());
        true
    }

    /// Serves one connection's requests in order until it closes.
    fn connection(self: &Arc<Self>, mut conn: http::Connection) {
        let limits = self.config.runner.limits;
        conn.set_request_time(limits.request_time);
        loop {
            let (reply, keep_alive, head_only) = match conn.next_request(limits.request_bytes) {
                Ok(request) => {
                    let reply = self.handle(&request);
                    (reply, request.keep_alive, request.method == "HEAD")
                }
                Err(http::ReadError::Closed) => return,
                Err(http::ReadError::Malformed(why)) => (reason(400, &why), false, false),
                Err(http::ReadError::TooSlow) => (
                    reason(
                        408,
                        &format!(
                            "the request took longer than {} s to arrive",
                            limits.request_time.as_secs_f64()
                        ),
                    ),
                    false,
                    false,
                ),
            };
            let mut headers: Vec<(&str, &str)> = vec![("Content-Type", reply.content_type)];
            headers.extend(SECURITY_HEADERS);
            headers.extend(reply.headers.iter().map(|(k, v)| (*k, v.as_str())));
            let sent = conn.respond(reply.code, &headers, &reply.body, keep_alive, head_only);
            if sent.is_err() || !keep_alive {
                return;
            }
        }
    }

    fn handle(self: &Arc<Self>, request: &http::Request) -> Reply {
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
        let (path, query) = request.url.split_once('?').unwrap_or((&request.url, ""));
        let method = request.method.as_str();
        let header_token = request.header("X-Spintop-Token");
        match path {
            "/evaluate.json" | "/evaluate/status" => {
                if !header_token.is_some_and(|t| self.is_token(t)) {
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
                let (token, rest) = split_token(query);
                if let Some(token) = token {
                    if !self.is_token(token) {
                        return self.forbidden();
                    }
                    // The printed address: keep the key in a cookie, and
                    // the address bar (and history) without it.
                    // One leading slash: a browser reads `//host/` (or
                    // `/\host/`) as another host.
                    let path = format!("/{}", path.trim_start_matches(['/', '\\']));
                    let clean = if rest.is_empty() {
                        path
                    } else {
                        format!("{path}?{rest}")
                    };
                    let mut reply = reason(303, "the book is at the address without its token");
                    reply.headers = vec![
                        ("Location", clean),
                        (
                            "Set-Cookie",
                            format!(
                                "{}={}; HttpOnly; SameSite=Strict; Path=/",
                                self.cookie_name(),
                                self.token
                            ),
                        ),
                    ];
                    return reply;
                }
                let keyed =
                    self.has_cookie(request) || header_token.is_some_and(|t| self.is_token(t));
                if !keyed {
                    return self.forbidden();
                }
                if method != "GET" && method != "HEAD" {
                    return reason(405, "the book is read with GET");
                }
                self.file(path)
            }
        }
    }

    /// The page for a request without the key.
    fn forbidden(&self) -> Reply {
        let page = format!(
            "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>spintop book: open the printed address</title></head>\n<body><h1>Open the address printed in the terminal</h1>\n<p>This book runs code on your machine, so it answers only the address that <code>spintop book</code> printed in the terminal when it started: <code>http://127.0.0.1:{}/?token=…</code>, with its token (the key, not shown here). Copy that whole address into the browser, or start it with <code>spintop book --open</code>.</p></body></html>\n",
            self.port
        );
        Reply {
            code: 403,
            content_type: "text/html; charset=utf-8",
            headers: Vec::new(),
            body: page.into_bytes(),
        }
    }

    /// A file of the built book; HTML pages receive the token, for their ▶.
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
            headers: Vec::new(),
            body: bytes,
        }
    }

    /// What is busy, for how long, and its limit: the 429 answer.
    fn busy(&self, job: &Job) -> Reply {
        let limits = self.config.runner.limits;
        let secs = job.since.elapsed().as_secs();
        let what = match job.phase {
            Phase::Waiting => {
                format!("is waiting for the background build of spintop ({secs} s so far)")
            }
            Phase::Compiling => {
                let limit = if self.shared.warm.load(Ordering::SeqCst) {
                    limits.compile_warm
                } else {
                    limits.compile
                };
                format!(
                    "is compiling ({secs} s so far; the compile limit is {} s)",
                    limit.as_secs()
                )
            }
            Phase::Running => format!(
                "is running ({secs} s so far; the time limit is {} s)",
                limits.run.as_secs()
            ),
        };
        json(
            429,
            serde_json::json!({
                "result": format!("busy: another snippet {what}; press ▶ again when it has finished"),
                "error": "busy",
            }),
        )
    }

    /// `/evaluate.json`: start a run, answer within [`Limits::answer_within`].
    fn evaluate(self: &Arc<Self>, body: &[u8]) -> Reply {
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
                return self.busy(&job);
            }
            *job = Job {
                running: true,
                progress: "waiting for its turn".into(),
                ..Job::default()
            };
        }
        let inner = Arc::clone(self);
        let edition = params.edition.unwrap_or_else(|| "2024".into());
        let answer_within = self.config.runner.limits.answer_within;
        let (done_tx, done_rx) = std::sync::mpsc::channel();
        // The run on a thread of its own: this connection answers within
        // `answer_within` (202 and "pending" if the run goes on), and other
        // connections meanwhile are told "busy", not queued.
        std::thread::spawn(move || {
            let outcome =
                inner
                    .config
                    .runner
                    .run(&params.code, &edition, &inner.shared, &mut |stage| {
                        let mut job = lock(&inner.job);
                        match stage {
                            Stage::Compiling => {
                                job.phase = Phase::Compiling;
                                job.since = Instant::now();
                                job.progress = "compiling".into();
                            }
                            Stage::Line(line) => {
                                let secs = job.since.elapsed().as_secs();
                                job.progress = format!("{line} ({secs} s)");
                            }
                            Stage::Running => {
                                job.phase = Phase::Running;
                                job.since = Instant::now();
                                job.progress = "running".into();
                            }
                        }
                    });
            let mut job = lock(&inner.job);
            job.running = false;
            job.last = Some(outcome.clone());
            drop(job);
            let _ = done_tx.send(outcome);
        });
        match done_rx.recv_timeout(answer_within) {
            Ok(outcome) => json(200, outcome_json(&outcome)),
            Err(_) => {
                // What holds it up: only a build of spintop itself takes
                // minutes.
                let phase = lock(&self.job).phase;
                let result = match phase {
                    Phase::Running => format!(
                        "running… (its time limit is {} s)",
                        self.config.runner.limits.run.as_secs()
                    ),
                    Phase::Compiling if self.shared.warm.load(Ordering::SeqCst) => {
                        "compiling…".to_string()
                    }
                    Phase::Waiting | Phase::Compiling => "compiling… (the first run builds spintop for the book: a minute or two on a small machine; later runs take a second or two)".to_string(),
                };
                json(
                    202,
                    serde_json::json!({ "result": result, "pending": true }),
                )
            }
        }
    }

    /// `/evaluate/status`: the run's progress, or its outcome once done.
    fn status(&self) -> Reply {
        let job = lock(&self.job);
        let value = match (&job.running, &job.last) {
            (true, _) => {
                let progress = match (job.phase, lock(&self.warm).clone()) {
                    (Phase::Waiting, WarmState::Building { started, progress }) => format!(
                        "waiting for the background build of spintop ({} s): {progress}",
                        started.elapsed().as_secs()
                    ),
                    _ => job.progress.clone(),
                };
                serde_json::json!({ "done": false, "progress": progress })
            }
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

/// Why a connection from `peer` is refused, if it is: another user's
/// process, or a peer already gone (see `src/server/peer.rs`).
fn refusal(peer: peer::Peer) -> Option<String> {
    match peer {
        peer::Peer::Trusted | peer::Peer::Unknown => None,
        peer::Peer::OtherUser(uid) => Some(format!(
            "refused: this connection comes from another user's process (uid {uid}); spintop book answers only the user who started it (uid {}), whatever key the request holds",
            rustix::process::geteuid().as_raw()
        )),
        peer::Peer::Gone => Some(
            "refused: the connection's other end was closed before the server could see whose it is"
                .into(),
        ),
    }
}

/// A query's `token` parameter, and the query without it.
fn split_token(query: &str) -> (Option<&str>, String) {
    let mut token = None;
    let mut rest = Vec::new();
    for pair in query.split('&').filter(|p| !p.is_empty()) {
        match pair.strip_prefix("token=") {
            Some(t) if token.is_none() => token = Some(t),
            _ => rest.push(pair),
        }
    }
    (token, rest.join("&"))
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
        headers: Vec::new(),
        body: value.to_string().into_bytes(),
    }
}

/// An answer read by [`fetch`].
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Response {
    /// The status code (0 if the answer was not HTTP).
    pub code: u16,
    /// The headers, in order.
    pub headers: Vec<(String, String)>,
    /// The body.
    pub body: String,
}

impl Response {
    /// The first value of header `name` (case-insensitive).
    pub fn header(&self, name: &str) -> Option<&str> {
        http::values(&self.headers, name).next()
    }
}

/// A minimal HTTP/1.1 client for the server's own checks (`spintop book
/// --self-test` and the tests): one request, `Connection: close`, the
/// answer back.
pub fn fetch(
    port: u16,
    method: &str,
    path: &str,
    headers: &[(&str, &str)],
    body: &[u8],
) -> std::io::Result<Response> {
    use std::io::Write;
    let mut stream = TcpStream::connect(("127.0.0.1", port))?;
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
    let (head, body) = text.split_once("\r\n\r\n").unwrap_or((&text, ""));
    let mut lines = head.lines();
    let code = lines
        .next()
        .and_then(|l| l.split_whitespace().nth(1))
        .and_then(|c| c.parse().ok())
        .unwrap_or(0);
    let headers = lines
        .filter_map(|l| l.split_once(':'))
        .map(|(k, v)| (k.trim().to_string(), v.trim().to_string()))
        .collect();
    Ok(Response {
        code,
        headers,
        body: body.to_string(),
    })
}

/// [`fetch`], the status code and the body only.
pub fn request(
    port: u16,
    method: &str,
    path: &str,
    headers: &[(&str, &str)],
    body: &[u8],
) -> std::io::Result<(u16, String)> {
    fetch(port, method, path, headers, body).map(|r| (r.code, r.body))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_path_outside_the_site_is_never_a_file() {
        let site = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../book/src"));
        assert!(site_file(site, "/SUMMARY.md").is_some());
        assert!(
            site_file(site, "/figures/").is_none(),
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
            assert!(site_file(site, bad).is_none(), "{bad}");
        }
    }

    #[test]
    fn the_token_parameter_is_split_from_the_rest_of_the_query() {
        assert_eq!(split_token(""), (None, String::new()));
        assert_eq!(split_token("token=ab"), (Some("ab"), String::new()));
        assert_eq!(
            split_token("x=1&token=ab&y=2"),
            (Some("ab"), "x=1&y=2".to_string())
        );
        assert_eq!(split_token("tokens=ab"), (None, "tokens=ab".to_string()));
    }

    #[test]
    fn tokens_are_long_and_differ() {
        let (a, b) = (new_token(), new_token());
        assert_eq!(a.len(), 32);
        assert_ne!(a, b);
    }
}

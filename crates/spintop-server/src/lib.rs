//! `spintop book`'s server: the built book over HTTP on loopback, and ▶ for
//! its snippets, compiled against the local spintop and run here.
//!
//! A shell beside the CLI and the TUI (the CLI only launches it). Requests
//! are parsed by `httparse`; each connection has a thread of its own
//! (`http.rs` says why no pooled server crate). Because it runs code on the
//! reader's machine, this is what holds, each point tested against the real
//! server in `tests/book/` (of the application, whose binary supervises):
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
//!   (`crates/spintop-server/src/peer.rs`), and another user's gets 403 whatever it
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
//!   redirects to the address without the token. A request with neither
//!   gets a 403 page that says to open the printed address, and takes the
//!   key again in a form (posted to `/login` from the book's own origin
//!   only): such a page may overwrite the cookie, which cookies' sharing of
//!   ports allows, and the reader then pastes the address or the token
//!   there instead of restarting the book.
//! - A run (`/evaluate.json`, `/evaluate/status`) carries the token in a
//!   header (`X-Spintop-Token`) that the served pages add; a cookie alone
//!   does not start a run. A page asked with that header is served too.
//! - Tokens are compared in constant time (`subtle`).
//! - Other origins: the server listens on 127.0.0.1, and on ::1 at the same
//!   port where the machine has IPv6 loopback, so that no other process can
//!   listen there: a browser resolves `localhost` to ::1 first, and would
//!   send the address to whoever held it. It refuses to start if another
//!   process holds [::1] at the port asked for (with a free port asked for,
//!   it takes one free on both). A `Host` other than
//!   `127.0.0.1:PORT`, `localhost:PORT` or `[::1]:PORT` (DNS rebinding) or a
//!   foreign `Origin` is refused (403); no CORS headers; every answer
//!   forbids framing (`X-Frame-Options: DENY`, CSP `frame-ancestors
//!   'none'`) and sniffing (`nosniff`), sends a referrer only to itself
//!   (`same-origin`: with `no-referrer` a browser sends `Origin: null` on
//!   a form's POST, and the 403 page's form could not prove its origin),
//!   and `Cache-Control: no-store`.
//!
//! # Folders: the reader's own
//!
//! The built book it serves with the token, the scratch project it builds
//! and the build folder whose programs it runs must each be the reader's,
//! and neither they nor any folder above them writable by another user or
//! owned by one but root (a group that is the reader's alone, as the
//! private group of a umask-002 system, is no other user); a sticky folder
//! above (as /tmp) is allowed when the next one down is the reader's
//! (`crates/spintop-server/src/folders.rs`). Else
//! [`Server::bind`] refuses, saying which folder and why. The scratch folder
//! is made fresh at each start, mode 0700, and is the server's alone while
//! it lives (a lock beside it): a second server started with the same one
//! takes `NAME-2` (and so on) instead, with a program name of its own, so
//! that two `spintop book` in one clone never remove each other's project
//! nor run each other's snippet. Cargo runs in `/` and finds the
//! scratch project by its path, so that no `.cargo/config.toml` in a folder
//! above the scratch (which cargo reads from the folder it runs in upward,
//! whoever wrote it, and whatever `--config` or `CARGO_HOME` say) is read;
//! the reader's own `CARGO_HOME` configuration is.
//!
//! # What a snippet can do: anything the reader can, within limits
//!
//! A snippet runs as the reader, with the reader's files and network. Each
//! build and each run is a process tree under a supervisor and its stage
//! (`crates/spintop-server/src/supervise.rs` says how), with resource limits for a run
//! ([`Limits`]): per process 4 GiB of address space and 11 CPU seconds,
//! files up to 64 MiB each, no core dumps, and at most 512 processes and
//! threads more than the reader had when it started, within the reader's
//! own hard limit and leaving 96 below the soft one for the server's
//! threads (the kernel does not hold root to this one). These bound each
//! process, not the tree's sum: its processes together may take more
//! memory, and its files more disk (or `/dev/shm`, which is memory). A
//! compile (cargo, rustc) has only its time limit. One tree at a time: a
//! second ▶ gets 429 with what is busy and for how long. A run is killed,
//! whole, after 10 s; a compile after 120 s once the scratch project is
//! built (900 s for the first, cold build); the output is cut at 64 KiB.
//!
//! Each tree is ended as a unit, the strongest the machine allows
//! ([`Containment`], `crates/spintop-server/src/unit.rs`; [`Server::containment`] says
//! which, and `spintop book` prints it):
//!
//! - **Linux where the reader may make a user namespace** (most
//!   distributions; not Ubuntu 23.10 and later by default, whose AppArmor
//!   restricts them, nor where `user.max_user_namespaces` is 0), **or as
//!   root: a PID namespace.** No process leaves it; when its init (the
//!   stage) dies, the kernel kills every process in it; the stage dies with
//!   the supervisor, and the supervisor with the server (SIGKILL by
//!   `PR_SET_PDEATHSIG`). From inside, neither has a process id, so a
//!   snippet can neither signal nor trace them.
//! - **Linux where the reader may make a cgroup v2 below the server's** (a
//!   systemd user session's terminal; Linux 5.14 for `cgroup.kill`): the
//!   tree's own cgroup, killed at once, forks under way included. The
//!   reader owns the parent cgroup, so a snippet may move itself out; the
//!   supervisor then still finds it below itself.
//! - **Other Linux: the process group and session**, the supervisor and
//!   the stage child subreapers (`PR_SET_CHILD_SUBREAPER`), so that what a
//!   snippet starts (daemons, double forks, `setsid`, `nohup`) stays below
//!   them; every process below the supervisor or in its session is killed,
//!   again and again until none is left.
//!
//! Whatever the unit, on Linux: the supervisor is not dumpable (a process
//! of the reader, root aside, can neither trace it nor open its `/proc`
//! files, such as its control pipe), ends its tree when the server dies
//! (`PR_SET_PDEATHSIG`, checked at once, since a server gone before would
//! send nothing; outside a namespace the signal only wakes it, and it sees
//! its parent gone within 10 ms and ends the tree first), and keeps the
//! time limit on its own clock, so a tree ends on time while the server is
//! stopped (Ctrl-Z) and as soon as the server is killed (SIGKILL, the OOM
//! killer). A snippet may not stop or trace any process (a seccomp filter:
//! SIGSTOP, SIGTSTP, SIGTTIN and SIGTTOU by any call, and `ptrace`, fail
//! with EPERM; on x86_64, aarch64 and riscv64, where seccompiler has a
//! filter), so it cannot stop its supervisor. It may kill it (it runs as
//! the reader) outside a namespace: what it started then lands on the
//! server, which kills the tree's cgroup, session and group, and
//! `spintop book` every process below it but the running tree
//! ([`Server::sweep_strays`]).
//!
//! Beyond these limits, as for any program the reader runs: what a snippet
//! hands to a service outside its tree (cron, `systemd-run`, an already
//! running tmux server); outside a namespace, a program written to outrun
//! the kill (each process forking the next faster than `/proc` is read) or
//! killing its supervisor at the instant the server is killed; and
//! whatever root's snippets do (root may trace and signal anything).
//! Elsewhere than Linux (macOS, the BSDs; not tested) a tree has only its
//! session, process group and limits, and the server's kill of its group.
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
//! # Stops and exhaustion
//!
//! [`Server::shutdown`] (also on drop) kills the running tree, a snippet or
//! cargo with its compilers, and waits until it is gone; `spintop book`
//! calls it on SIGINT, SIGTERM, SIGHUP and SIGQUIT, then kills whatever a
//! snippet left to it, and says whether anything survived. If the server
//! itself is killed, its trees end with it (above).
//!
//! A thread the system refuses (the reader's process limit taken by a fork
//! bomb outside the tree) is no panic: the connection is answered 503 and
//! the server goes on; a run's output is read by the thread that waits for
//! it, and the supervisor starts none.
//!
//! # What is written where
//!
//! The built book (`target/spintop-book/site`, by mdBook), the scratch
//! project (`target/spintop-book/scratch`, or `scratch-2` and on while
//! other servers hold it) and its lock file beside it (`scratch.lock`), in a cgroup unit a cgroup
//! `spintop-book-PID` below the server's for each tree (removed with it),
//! the build folder it shares with
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

mod answer;
mod bounds;
mod client;
mod drain;
mod folders;
#[doc(hidden)]
pub mod http;
mod jobs;
mod peer;
mod procs;
mod run;
mod supervise;
mod tree;
mod unit;

pub use answer::site_file;
pub use client::{Response, fetch, request};
pub use folders::Untrusted;
pub use run::{Limits, Outcome, OutcomeKind, Runner, SNIPPET_CRATES, default_runner};
pub use supervise::{SUPERVISE_FLAG, supervise};
pub use unit::Containment;

use jobs::Job;
use run::{Shared, Stage};
use std::io::Read;
use std::net::{TcpListener, TcpStream};
use std::path::PathBuf;
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
    /// Another process holds the port on ::1, where a browser that resolves
    /// `localhost` to ::1 first would send it the address with the token.
    #[error(
        "cannot listen on [::1]:{port} ({reason}): another process holds it there, and a browser that opens localhost:{port} would send it the book's key; choose another --port"
    )]
    Localhost {
        /// The port asked for.
        port: u16,
        /// The system's reason.
        reason: String,
    },
    /// A folder another user could write, or not the reader's.
    #[error(transparent)]
    Folder(#[from] Untrusted),
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

/// The headers of every answer: no framing, no sniffing, no referrer to
/// another origin, no copy kept (the pages carry the token).
const SECURITY_HEADERS: [(&str, &str); 5] = [
    ("X-Frame-Options", "DENY"),
    ("Content-Security-Policy", "frame-ancestors 'none'"),
    ("X-Content-Type-Options", "nosniff"),
    ("Referrer-Policy", "same-origin"),
    ("Cache-Control", "no-store"),
];

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
    /// 127.0.0.1 and, where the machine has it, ::1.
    listeners: Vec<TcpListener>,
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
    /// Held while anything of this server may use it.
    _scratch: folders::Scratch,
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

/// Listens on 127.0.0.1:`port` and on [::1] at the same port, so that no
/// other process can listen there (a browser resolves `localhost` to ::1
/// first); with port 0, on a free port where both are free. The listeners,
/// and the port.
fn listen(port: u16) -> Result<(Vec<TcpListener>, u16), ServerError> {
    let bind_error = |e: std::io::Error| ServerError::Bind {
        port,
        reason: e.to_string(),
    };
    for _ in 0..32 {
        let v4 = TcpListener::bind(("127.0.0.1", port)).map_err(bind_error)?;
        let got = v4.local_addr().map_err(bind_error)?.port();
        let listeners = match TcpListener::bind(("::1", got)) {
            Ok(v6) => vec![v4, v6],
            // No IPv6 loopback: no process can listen there either.
            Err(e)
                if e.kind() == std::io::ErrorKind::AddrNotAvailable
                    || e.raw_os_error() == Some(rustix::io::Errno::AFNOSUPPORT.raw_os_error()) =>
            {
                vec![v4]
            }
            // Taken there: another free port.
            Err(_) if port == 0 => continue,
            Err(e) => {
                return Err(ServerError::Localhost {
                    port,
                    reason: e.to_string(),
                });
            }
        };
        for l in &listeners {
            l.set_nonblocking(true).map_err(bind_error)?;
        }
        return Ok((listeners, got));
    }
    Err(ServerError::Localhost {
        port,
        reason: "no port tried was free on both 127.0.0.1 and ::1".into(),
    })
}

impl Server {
    /// Checks the folders (each the reader's own, see `folders.rs`), claims
    /// a scratch folder no other living server holds and makes it fresh, finds the strongest containment the
    /// machine allows ([`Server::containment`]), and listens on
    /// 127.0.0.1:`config.port` (and on [::1] at that port, see [`listen`]).
    pub fn bind(mut config: Config) -> Result<Self, ServerError> {
        config.site = folders::check("--site", &config.site)?;
        let target = &config.runner.target_dir;
        std::fs::create_dir_all(target).map_err(|e| Untrusted {
            what: "the build folder".into(),
            path: target.clone(),
            why: format!("cannot be made: {e}"),
        })?;
        config.runner.target_dir = folders::check("the build folder", target)?;
        let scratch = folders::claim_scratch(&config.runner.scratch)?;
        config.runner.scratch = scratch.path.clone();
        config.runner.containment =
            supervise::strongest(config.runner.containment, &config.runner.launcher);
        let (listeners, port) = listen(config.port)?;
        Ok(Self {
            listeners,
            inner: Arc::new(Inner {
                port,
                token: new_token(),
                config,
                job: Mutex::default(),
                shared: Shared::default(),
                warm: Mutex::new(WarmState::NotStarted),
                connections: Mutex::default(),
                refusing: AtomicUsize::new(0),
                _scratch: scratch,
            }),
        })
    }

    /// The scratch folder it compiles snippets in: the one asked for, or
    /// beside it if another living server holds that one (see
    /// `folders.rs`).
    pub fn scratch(&self) -> &std::path::Path {
        &self.inner.config.runner.scratch
    }

    /// The port it listens on.
    pub fn port(&self) -> u16 {
        self.inner.port
    }

    /// How each tree is ended as a unit here: the strongest of those up to
    /// [`Runner::containment`] that this machine allows.
    pub fn containment(&self) -> Containment {
        self.inner.config.runner.containment
    }

    /// Whether it also listens on [::1] (the machine has IPv6 loopback).
    pub fn holds_localhost6(&self) -> bool {
        self.listeners.len() > 1
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
        let spawned = std::thread::Builder::new().spawn(move || {
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
        if let Err(e) = spawned {
            *lock(&self.inner.warm) = WarmState::Failed {
                why: format!("cannot start a thread for the background build: {e}"),
            };
        }
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
    /// keeps open never holds up another. A connection that cannot have a
    /// thread (the reader's process limit is reached: a fork bomb) is
    /// answered 503 at once, and the next is tried again. This process
    /// becomes a child subreaper first (see `crates/spintop-server/src/tree.rs`).
    pub fn serve(&self, stop: &AtomicBool) {
        tree::become_subreaper();
        while !stop.load(Ordering::Relaxed) {
            let mut accepted = false;
            for listener in &self.listeners {
                // Nothing waiting (the listener does not block), or a
                // transient failure such as too many open files.
                if let Ok((stream, _)) = listener.accept() {
                    accepted = true;
                    self.accept(stream);
                }
            }
            if !accepted {
                std::thread::sleep(Duration::from_millis(20));
            }
        }
    }

    /// Takes one connection: refused, answered 503, or served on a thread
    /// of its own.
    fn accept(&self, stream: TcpStream) {
        let peer = peer::peer(&stream);
        let Ok(mut conn) = http::Connection::new(stream) else {
            return;
        };
        if let Some(why) = refusal(peer) {
            self.inner.refuse(conn, why);
            return;
        }
        if !self.inner.admit(&conn) {
            send(
                &mut conn,
                &reason(503, "too many connections"),
                false,
                false,
            );
            return;
        }
        let watch = conn.watch();
        // The connection goes to its thread once the thread exists; if it
        // cannot be made, it stays here for the 503.
        let (hand, take) = std::sync::mpsc::channel::<http::Connection>();
        let inner = Arc::clone(&self.inner);
        let spawned = std::thread::Builder::new().spawn(move || {
            if let Ok(conn) = take.recv() {
                let watch = conn.watch();
                inner.connection(conn);
                lock(&inner.connections).retain(|w| !Arc::ptr_eq(w, &watch));
            }
        });
        match spawned {
            Ok(_) => {
                let _ = hand.send(conn);
            }
            Err(e) => {
                lock(&self.inner.connections).retain(|w| !Arc::ptr_eq(w, &watch));
                send(&mut conn, &jobs::unavailable(&e), false, false);
            }
        }
    }

    /// Stops: kills the running process tree (a snippet, or cargo and its
    /// compilers) and refuses new ones; returns once it is gone (true), or
    /// after [`Server::STOP_WAIT`] without seeing it go (false).
    pub fn shutdown(&self) -> bool {
        self.inner.shared.slot.close()
    }

    /// How long [`Server::shutdown`] waits for the tree to be gone.
    pub const STOP_WAIT: Duration = tree::STOP_WAIT;

    /// For a process that serves this server and starts nothing else
    /// (`spintop book`): kills every process below this one but the running
    /// tree, and reaps those that have ended; returns how many living ones
    /// it found. A snippet that kills its own supervisor leaves what it
    /// started to this process (see `crates/spintop-server/src/tree.rs`); calling this
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
        let spawned = std::thread::Builder::new().spawn(move || {
            conn.set_request_time(Duration::from_secs(1));
            let limit = inner.config.runner.limits.request_bytes;
            if !matches!(conn.next_request(limit), Err(http::ReadError::Closed)) {
                send(&mut conn, &reason(403, &why), false, false);
            }
            inner.refusing.fetch_sub(1, Ordering::SeqCst);
        });
        // No thread: closed unanswered, like those past the limit.
        if spawned.is_err() {
            self.refusing.fetch_sub(1, Ordering::SeqCst);
        }
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
            if !send(&mut conn, &reply, keep_alive, head_only) || !keep_alive {
                return;
            }
        }
    }
}

/// Writes `reply` on `conn` with the [`SECURITY_HEADERS`]; whether it was
/// written.
fn send(conn: &mut http::Connection, reply: &Reply, keep_alive: bool, head_only: bool) -> bool {
    let mut headers: Vec<(&str, &str)> = vec![("Content-Type", reply.content_type)];
    headers.extend(SECURITY_HEADERS);
    headers.extend(reply.headers.iter().map(|(k, v)| (*k, v.as_str())));
    conn.respond(reply.code, &headers, &reply.body, keep_alive, head_only)
        .is_ok()
}

/// Why a connection from `peer` is refused, if it is: another user's
/// process, or a peer already gone (see `crates/spintop-server/src/peer.rs`).
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tokens_are_long_and_differ() {
        let (a, b) = (new_token(), new_token());
        assert_eq!(a.len(), 32);
        assert_ne!(a, b);
    }
}

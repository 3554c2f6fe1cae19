//! `spintop book`'s server, locked down: every rule is tested by sending the
//! bad request to the real server (bound on a free port, in a thread, or the
//! `spintop book` binary itself where signals, a killed server or another
//! user are concerned), and each test fails if its rule is removed.
//!
//! Two tiers. The default one sends requests that never reach a compiler,
//! each well under a second. The end-to-end tier (`cargo test --test app
//! book:: -- --ignored`) compiles real snippets against this spintop in a
//! scratch folder under the system's temp dir, sharing the workspace's
//! build folder, or waits for real time limits; each build and run is
//! supervised by the `spintop` binary, as under `spintop book`. Attacks on
//! the process model that need another user (who cannot write the shared
//! build folder) run `spintop book` as uid 65534 with a stand-in for cargo
//! ([`fake_cargo`]): the snippet is then a shell script, and everything
//! else (server, supervisor, stage, unit, limits) is the real one.
//!
//! Whether a process is gone is read from `/proc` here, independently of the
//! server's own process walk.

mod access;
mod connections;
mod exhaustion;
mod folders;
mod runs;
mod terminal;
mod trees;

use spintop_server::{Config, Containment, Limits, Runner, Server, request};
use std::io::BufRead;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

struct Running {
    port: u16,
    token: String,
    server: Arc<Server>,
    stop: Arc<AtomicBool>,
    thread: Option<std::thread::JoinHandle<()>>,
    root: PathBuf,
}

impl Drop for Running {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
        self.server.shutdown();
        let _ = std::fs::remove_dir_all(&self.root);
    }
}

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn target_dir() -> PathBuf {
    std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| repo().join("target"))
}

/// A small built "book": a page and a stylesheet.
fn site(root: &Path) -> PathBuf {
    let site = root.join("site");
    std::fs::create_dir_all(site.join("css")).unwrap();
    std::fs::write(
        site.join("index.html"),
        "<html><head><title>t</title></head><body>the book</body></html>",
    )
    .unwrap();
    std::fs::write(site.join("css/book.css"), "body {}").unwrap();
    site
}

fn start(name: &str, limits: Limits) -> Running {
    start_in(name, limits, Containment::Namespace)
}

/// A server in a thread of this process, its trees ended at most as
/// `containment` says.
fn start_in(name: &str, limits: Limits, containment: Containment) -> Running {
    let root = scratch_root(name);
    let server = Server::bind(config(
        site(&root),
        root.join("scratch"),
        limits,
        containment,
    ))
    .unwrap();
    let (port, token) = (server.port(), server.token().to_string());
    let server = Arc::new(server);
    let stop = Arc::new(AtomicBool::new(false));
    let (s, serving) = (Arc::clone(&stop), Arc::clone(&server));
    let thread = std::thread::spawn(move || serving.serve(&s));
    Running {
        port,
        token,
        server,
        stop,
        thread: Some(thread),
        root,
    }
}

/// A server's configuration: the book in `site`, snippets compiled in
/// `scratch` against this spintop under `limits`, trees ended at most as
/// `containment` says; a free port.
fn config(site: PathBuf, scratch: PathBuf, limits: Limits, containment: Containment) -> Config {
    Config {
        site,
        port: 0,
        runner: Runner {
            scratch,
            spintop: repo(),
            target_dir: target_dir(),
            launcher: PathBuf::from(env!("CARGO_BIN_EXE_spintop")),
            limits,
            containment,
        },
    }
}

/// A fresh folder for test `name` under the system's temp dir.
fn scratch_root(name: &str) -> PathBuf {
    let root = std::env::temp_dir().join(format!("spintop-server-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&root);
    std::fs::create_dir_all(&root).unwrap();
    root
}

fn limits() -> Limits {
    Limits {
        run: Duration::from_secs(3),
        answer_within: Duration::from_secs(600),
        ..Limits::default()
    }
}

fn body(code: &str) -> Vec<u8> {
    serde_json::json!({ "code": code, "edition": "2024" })
        .to_string()
        .into_bytes()
}

impl Running {
    fn run(&self, code: &str) -> (u16, serde_json::Value) {
        let origin = format!("http://127.0.0.1:{}", self.port);
        let (status, text) = request(
            self.port,
            "POST",
            "/evaluate.json",
            &[("X-Spintop-Token", &self.token), ("Origin", &origin)],
            &body(code),
        )
        .unwrap();
        (status, serde_json::from_str(&text).unwrap_or_default())
    }

    /// The cookie the printed address sets.
    fn cookie(&self) -> String {
        format!("spintop-book-{}={}", self.port, self.token)
    }

    /// A GET with the cookie, as the reader's browser sends it.
    fn get(&self, path: &str) -> (u16, String) {
        request(self.port, "GET", path, &[("Cookie", &self.cookie())], b"").unwrap()
    }
}

/// Every process: pid, parent, state letter.
fn processes() -> Vec<(i32, i32, char)> {
    std::fs::read_dir("/proc")
        .unwrap()
        .flatten()
        .filter_map(|e| std::fs::read_to_string(e.path().join("stat")).ok())
        .filter_map(|stat| {
            let (pid, rest) = stat.split_once(" (")?;
            let mut fields = rest[rest.rfind(')')? + 2..].split(' ');
            let state = fields.next()?.chars().next()?;
            Some((pid.parse().ok()?, fields.next()?.parse().ok()?, state))
        })
        .collect()
}

/// Whether `pid` is a process that still runs (a zombie has ended).
fn alive(pid: i32) -> bool {
    processes()
        .iter()
        .any(|&(p, _, state)| p == pid && state != 'Z' && state != 'X')
}

/// The processes below `root`, by parent links.
fn descendants(root: i32) -> Vec<i32> {
    let table = processes();
    let mut found = Vec::new();
    let mut frontier = vec![root];
    while let Some(parent) = frontier.pop() {
        for &(pid, ppid, _) in &table {
            if ppid == parent && !found.contains(&pid) {
                found.push(pid);
                frontier.push(pid);
            }
        }
    }
    found
}

fn cmdline(pid: i32) -> String {
    std::fs::read(format!("/proc/{pid}/cmdline"))
        .map(|b| String::from_utf8_lossy(&b).replace('\0', " "))
        .unwrap_or_default()
}

/// Waits up to `limit` for `ready`.
fn wait_for(limit: Duration, mut ready: impl FnMut() -> bool) -> bool {
    let start = Instant::now();
    while start.elapsed() < limit {
        if ready() {
            return true;
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    ready()
}

/// Whether there is another user to become: the tests run as root.
fn can_become_another_user() -> bool {
    let root = rustix::process::geteuid().is_root();
    if !root {
        eprintln!("not root, so no other user to become: skipped");
    }
    root
}

/// A snippet that starts a `sleep` child and a busy loop detached in a
/// session of its own (its parent gone at once), writes their process ids
/// into its folder, and then waits forever. Each child writes its own id,
/// read from `/proc/self/stat`: the machine's number (in a PID namespace
/// the snippet sees other numbers).
const LEAVES_CHILDREN: &str = r#"use std::process::Command;
fn main() {
    Command::new("sh")
        .args(["-c", "read -r pid rest < /proc/self/stat; echo $pid > sleeper.pid.tmp; mv sleeper.pid.tmp sleeper.pid; exec sleep 1000"])
        .spawn()
        .unwrap();
    Command::new("sh")
        .args(["-c", "setsid sh -c 'read -r pid rest < /proc/self/stat; echo $pid > escapee.pid.tmp; mv escapee.pid.tmp escapee.pid; while :; do :; done' &"])
        .status()
        .unwrap();
    while std::fs::metadata("escapee.pid").is_err() || std::fs::metadata("sleeper.pid").is_err() {
        std::thread::sleep(std::time::Duration::from_millis(10));
    }
    println!("started both");
    loop {
        std::thread::sleep(std::time::Duration::from_millis(100));
    }
}
"#;

/// The process ids LEAVES_CHILDREN wrote into `scratch`.
fn left_children(scratch: &Path) -> Vec<i32> {
    ["sleeper.pid", "escapee.pid"]
        .iter()
        .filter_map(|f| std::fs::read_to_string(scratch.join(f)).ok())
        .filter_map(|t| t.trim().parse().ok())
        .collect()
}

/// Both children LEAVES_CHILDREN started are gone.
fn both_gone(scratch: &Path) {
    let children = left_children(scratch);
    assert_eq!(children.len(), 2, "{children:?}");
    for pid in children {
        assert!(!alive(pid), "{pid} ({}) outlived the run", cmdline(pid));
    }
}

/// The `spintop book` binary, serving `site` with snippets compiled in
/// `scratch`; its stdout lines come through the receiver.
struct Book {
    child: std::process::Child,
    port: u16,
    token: String,
    lines: std::sync::mpsc::Receiver<String>,
    said: Vec<String>,
}

/// How a [`Book`] starts, beyond its folders.
#[derive(Default)]
struct BookOptions {
    /// Further arguments.
    args: Vec<String>,
    /// Further environment.
    env: Vec<(String, std::ffi::OsString)>,
    /// Another user to run as (uid and gid).
    user: Option<u32>,
    /// A process limit (soft and hard, through `prlimit`).
    nproc: Option<u64>,
}

impl Book {
    fn start(site: &Path, scratch: &Path) -> Self {
        Self::start_with(site, scratch, BookOptions::default())
    }

    /// As [`Book::start`], as `options` say.
    fn start_with(site: &Path, scratch: &Path, options: BookOptions) -> Self {
        use std::os::unix::process::CommandExt;
        let binary = env!("CARGO_BIN_EXE_spintop");
        let mut command = match options.nproc {
            Some(n) => {
                let mut c = std::process::Command::new("prlimit");
                c.arg(format!("--nproc={n}:{n}")).arg("--").arg(binary);
                c
            }
            None => std::process::Command::new(binary),
        };
        command
            .arg("book")
            .args(&options.args)
            .envs(options.env.iter().map(|(k, v)| (k, v)))
            .arg("--site")
            .arg(site)
            .arg("--scratch")
            .arg(scratch)
            .current_dir("/")
            .stdin(std::process::Stdio::null())
            .stdout(std::process::Stdio::piped());
        if let Some(uid) = options.user {
            command.uid(uid).gid(uid);
        }
        let mut child = command.spawn().unwrap();
        let (tx, lines) = std::sync::mpsc::channel();
        let out = child.stdout.take().unwrap();
        std::thread::spawn(move || {
            for line in std::io::BufReader::new(out).lines().map_while(Result::ok) {
                let _ = tx.send(line);
            }
        });
        let mut book = Self {
            child,
            port: 0,
            token: String::new(),
            lines,
            said: Vec::new(),
        };
        let line = book.wait_line("serving http://127.0.0.1:");
        let address = line
            .split_whitespace()
            .find(|w| w.starts_with("http://"))
            .unwrap();
        let (port, token) = address
            .trim_start_matches("http://127.0.0.1:")
            .split_once("/?token=")
            .unwrap();
        book.port = port.parse().unwrap();
        book.token = token.to_string();
        book
    }

    /// The next line that contains `text` (within 15 minutes: a cold build).
    fn wait_line(&mut self, text: &str) -> String {
        loop {
            let line = self
                .lines
                .recv_timeout(Duration::from_secs(900))
                .unwrap_or_else(|_| panic!("no line with {text:?}; said {:?}", self.said));
            self.said.push(line.clone());
            if line.contains(text) {
                return line;
            }
        }
    }

    /// The unit it says it runs each snippet in (the line after the
    /// address): `Containment::described`'s words.
    fn unit(&mut self) -> String {
        let line = self.wait_line("▶ runs each snippet");
        line.split(", in ")
            .nth(1)
            .and_then(|rest| rest.split(';').next())
            .unwrap_or("")
            .to_string()
    }

    /// Sends a run (answered 200 if it ended within the answer time, else
    /// 202 since it goes on).
    fn run(&self, code: &str) {
        let (status, text) = request(
            self.port,
            "POST",
            "/evaluate.json",
            &[("X-Spintop-Token", &self.token)],
            &body(code),
        )
        .unwrap();
        assert!(status == 202 || status == 200, "{status} {text}");
    }

    /// The server's process id.
    fn pid(&self) -> i32 {
        self.child.id() as i32
    }

    /// Sends `signal`.
    fn signal(&self, signal: rustix::process::Signal) {
        let pid = rustix::process::Pid::from_raw(self.pid()).unwrap();
        rustix::process::kill_process(pid, signal).unwrap();
    }

    /// Sends `signal` and waits (up to 20 s) for the exit: its status.
    fn stop(&mut self, signal: rustix::process::Signal) -> std::process::ExitStatus {
        self.signal(signal);
        let start = Instant::now();
        loop {
            if let Some(status) = self.child.try_wait().unwrap() {
                return status;
            }
            assert!(
                start.elapsed() < Duration::from_secs(20),
                "spintop book did not stop on {signal:?}"
            );
            std::thread::sleep(Duration::from_millis(50));
        }
    }
}

/// A test that fails midway still stops its server (which stops its tree).
impl Drop for Book {
    fn drop(&mut self) {
        if let Ok(None) = self.child.try_wait() {
            if let Some(pid) = rustix::process::Pid::from_raw(self.child.id() as i32) {
                let _ = rustix::process::kill_process(pid, rustix::process::Signal::CONT);
                let _ = rustix::process::kill_process(pid, rustix::process::Signal::TERM);
            }
            let _ = self.child.wait();
        }
    }
}

/// The uid the attacks as another user run as.
const NOBODY: u32 = 65534;

/// A stand-in for cargo, written into `dir`: it "builds" the scratch
/// project by copying its `src/main.rs`, a shell script, to the program
/// the server then runs. With it, `spintop book` runs as a user who cannot
/// write the shared build folder, without a cold build of spintop: the
/// snippet is a script (whose text holds `fn main`, so that the server
/// leaves it as it is), and the server, the supervisor, the stage, the
/// unit and the limits are the real ones.
fn fake_cargo(dir: &Path) -> PathBuf {
    use std::os::unix::fs::PermissionsExt;
    let path = dir.join("fake-cargo");
    std::fs::write(
        &path,
        r#"#!/bin/sh
while [ $# -gt 0 ]; do
  case "$1" in --manifest-path) manifest=$2; shift;; esac
  shift
done
name=$(sed -n 's/^name = "\(.*\)"$/\1/p' "$manifest")
mkdir -p "$CARGO_TARGET_DIR/debug"
cp "$(dirname "$manifest")/src/main.rs" "$CARGO_TARGET_DIR/debug/$name"
chmod 755 "$CARGO_TARGET_DIR/debug/$name"
"#,
    )
    .unwrap();
    std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o755)).unwrap();
    path
}

/// `root` and everything in it, given to `uid`.
fn give(root: &Path, uid: u32) {
    std::os::unix::fs::chown(root, Some(uid), Some(uid)).unwrap();
    if root.is_dir() {
        for entry in std::fs::read_dir(root).unwrap().flatten() {
            give(&entry.path(), uid);
        }
    }
}

/// Held by each test that runs processes as uid [`NOBODY`]: the process
/// limit counts every task of a user, so a fork burst of one such test
/// would take what another's server needs.
fn one_nobody_at_a_time() -> std::sync::MutexGuard<'static, ()> {
    static NOBODY_TESTS: std::sync::Mutex<()> = std::sync::Mutex::new(());
    NOBODY_TESTS.lock().unwrap_or_else(|e| e.into_inner())
}

/// `spintop book` as uid [`NOBODY`] with the stand-in cargo, in folders of
/// its own under `root` (given to it), its trees ended at most as
/// `containment` says, under process limit `nproc` if any. `None` (with
/// a reason printed) where there is no other user to become.
fn nobody_book(root: &Path, containment: Containment, nproc: Option<u64>) -> Option<Book> {
    if !can_become_another_user() {
        return None;
    }
    let site = site(root);
    let cargo = fake_cargo(root);
    let target = root.join("target");
    std::fs::create_dir_all(&target).unwrap();
    give(root, NOBODY);
    let options = BookOptions {
        args: vec!["--containment".into(), containment.name().into()],
        env: vec![
            ("CARGO".into(), cargo.into()),
            ("CARGO_TARGET_DIR".into(), target.into()),
            ("HOME".into(), root.into()),
        ],
        user: Some(NOBODY),
        nproc,
    };
    Some(Book::start_with(&site, &root.join("scratch"), options))
}

/// A snippet for the stand-in cargo: `body` as a shell script.
fn script(body: &str) -> String {
    format!("#!/bin/sh\n# fn main: a shell script, for the stand-in cargo\n{body}")
}

/// The host's process id of a process whose pid file `file` (written from
/// `/proc/self/stat`, so in the machine's numbering) is in `dir`, once it
/// is there (within `limit`).
fn pid_file(dir: &Path, file: &str, limit: Duration) -> Option<i32> {
    let path = dir.join(file);
    wait_for(limit, || path.is_file());
    std::fs::read_to_string(path).ok()?.trim().parse().ok()
}

/// The parent of `pid`, as `/proc` says.
fn parent_of(pid: i32) -> Option<i32> {
    processes()
        .into_iter()
        .find(|&(p, _, _)| p == pid)
        .map(|(_, ppid, _)| ppid)
}

/// How long ago process `pid` started, from its start time in `/proc`
/// (clock ticks since boot, 100 a second on Linux) and the machine's
/// uptime.
fn age(pid: i32) -> Option<Duration> {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    let ticks: f64 = stat[stat.rfind(')')? + 2..]
        .split(' ')
        .nth(19)?
        .parse()
        .ok()?;
    let uptime: f64 = std::fs::read_to_string("/proc/uptime")
        .ok()?
        .split_whitespace()
        .next()?
        .parse()
        .ok()?;
    Some(Duration::from_secs_f64((uptime - ticks / 100.0).max(0.0)))
}

//! `spintop book`: the book served on 127.0.0.1, where ▶ compiles and runs
//! every snippet against the local spintop. Builds the book first when its
//! sources are newer than the last build. The server is
//! [`spintop_server`] (its docs state what holds); this file only launches
//! it, shows its background build, and stops it on a signal.

use super::gate::Gate;
use super::{CliError, bad};
use clap::Args;
use spintop_server::{self as server, Config, Containment, Server, WarmUp, default_runner};
use std::ffi::OsString;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::{Duration, Instant, SystemTime};

/// The raw arguments of `book`.
#[derive(Debug, Default, Args)]
#[command(after_help = "Examples:\n  \
    spintop book                                     prints the address (with its token) to open\n  \
    spintop book --open --port 8000")]
pub struct BookArgs {
    /// The port on 127.0.0.1 (default: a free one).
    #[arg(long)]
    port: Option<u16>,
    /// Open the book in the default browser.
    #[arg(long)]
    open: bool,
    /// Serve a book already built into DIR (`mdbook build book --dest-dir DIR`)
    /// instead of building it into target/spintop-book/site.
    #[arg(long, value_name = "DIR")]
    site: Option<PathBuf>,
    /// Compile the snippets in DIR instead of target/spintop-book/scratch.
    #[arg(long, value_name = "DIR")]
    scratch: Option<PathBuf>,
    /// Measure instead of serving: wait for the background build, run one
    /// snippet through the server twice, print the times, exit.
    #[arg(long)]
    self_test: bool,
    /// The strongest way to end a snippet's tree as a unit: namespace (the
    /// default), cgroup or group; the machine may allow less (for tests).
    #[arg(long, hide = true, value_name = "UNIT")]
    containment: Option<String>,
    /// The supervisor of a snippet's process tree (the server starts it;
    /// see `spintop_server`).
    #[arg(long = "supervise", hide = true, num_args = 1.., allow_hyphen_values = true, value_name = "SPEC PROGRAM ARGS")]
    supervise: Option<Vec<OsString>>,
}

/// The newest modification time under `dir`.
fn newest(dir: &Path) -> Option<SystemTime> {
    let mut best = None;
    for entry in std::fs::read_dir(dir).ok()?.flatten() {
        let path = entry.path();
        let t = if path.is_dir() {
            newest(&path)
        } else {
            entry.metadata().ok().and_then(|m| m.modified().ok())
        };
        best = best.max(t);
    }
    best
}

/// Builds the book into `site` unless it is newer than its sources.
///
/// mdBook empties its output folder first: built there, a second `spintop
/// book` of the same clone would pull the pages from under the first one
/// for the length of the build. So the build goes to a folder of its own
/// beside `site`, which then takes `site`'s place in two renames.
fn build(repo: &Path, site: &Path, out: &mut impl Write) -> Result<(), CliError> {
    let book = repo.join("book");
    let built = std::fs::metadata(site.join("index.html"))
        .and_then(|m| m.modified())
        .ok();
    let sources = [newest(&book.join("src")), newest(&book.join("theme"))]
        .into_iter()
        .flatten()
        .chain(
            std::fs::metadata(book.join("book.toml"))
                .and_then(|m| m.modified())
                .ok(),
        )
        .max();
    if built.is_some() && built >= sources {
        return Ok(());
    }
    if Command::new("mdbook").arg("--version").output().is_err() {
        return Err(bad(
            "spintop book needs mdbook and mdbook-katex: cargo install --locked mdbook --version 0.5.4 && cargo install --locked mdbook-katex --version 0.10.0",
        ));
    }
    writeln!(out, "spintop book: building the book (mdbook build)…")?;
    out.flush()?;
    let fresh = site.with_extension(format!("new-{}", std::process::id()));
    let result = Command::new("mdbook")
        .arg("build")
        .arg(&book)
        .arg("--dest-dir")
        .arg(&fresh)
        .output()
        .map_err(|e| bad(format!("cannot run mdbook: {e}")))?;
    if !result.status.success() {
        let _ = std::fs::remove_dir_all(&fresh);
        let text = String::from_utf8_lossy(&result.stderr);
        let first = text
            .lines()
            .find(|l| l.contains("ERROR") || l.contains("error"))
            .unwrap_or("mdbook build failed");
        return Err(bad(format!("the book does not build: {first}")));
    }
    swap_in(&fresh, site)
}

/// Puts the built book `fresh` in `site`'s place; the old one is removed.
/// If another `spintop book` put its own build there meanwhile (built from
/// the same sources), that one stays and `fresh` is removed.
fn swap_in(fresh: &Path, site: &Path) -> Result<(), CliError> {
    let old = site.with_extension(format!("old-{}", std::process::id()));
    let _ = std::fs::rename(site, &old);
    let placed = std::fs::rename(fresh, site);
    let _ = std::fs::remove_dir_all(&old);
    if let Err(e) = placed {
        let _ = std::fs::remove_dir_all(fresh);
        if !site.join("index.html").is_file() {
            return Err(bad(format!(
                "cannot put the built book in {}: {e}",
                site.display()
            )));
        }
    }
    Ok(())
}

/// Runs `spintop book`.
pub(crate) fn execute(args: BookArgs, out: &mut Gate<'_>) -> Result<(), CliError> {
    if let Some(supervised) = &args.supervise {
        // A snippet's supervisor: its exit code is the program's.
        out.flush()?;
        std::process::exit(server::supervise(supervised));
    }
    let repo = spintop_course::repository().to_path_buf();
    if !repo.join("book/book.toml").is_file() || !repo.join("Cargo.toml").is_file() {
        return Err(bad(format!(
            "spintop book serves the book of the repository, and {} is missing; run it from a clone of spintop (cargo run --release -- book), or read the book in the terminal with spintop learn, which also reads the book a course copy carries",
            repo.join("book/book.toml").display()
        )));
    }
    let book_dir = repo.join("target").join("spintop-book");
    let site = match args.site {
        Some(site) if site.join("index.html").is_file() => site,
        Some(site) => {
            return Err(bad(format!(
                "--site {}: no index.html there; build the book into it with mdbook build book --dest-dir DIR",
                site.display()
            )));
        }
        None => {
            let site = book_dir.join("site");
            build(&repo, &site, out)?;
            site
        }
    };
    let mut runner = default_runner(&repo);
    if let Some(scratch) = args.scratch {
        runner.scratch = scratch;
    }
    if let Some(name) = &args.containment {
        runner.containment = Containment::named(name)
            .ok_or_else(|| bad(format!("--containment {name}: namespace, cgroup or group")))?;
    }
    let server = Server::bind(Config {
        site,
        port: args.port.unwrap_or(0),
        runner,
    })
    .map_err(|e| bad(e.to_string()))?;
    if args.self_test {
        return self_test(server, out);
    }
    writeln!(
        out,
        "spintop book: serving {}\n  open this address: the token in it is the key, and the book answers no other (▶ runs each snippet against this spintop, in {}; Ctrl-C stops)",
        server.url(),
        server.containment().described()
    )?;
    out.flush()?;
    // Before the server becomes a subreaper (in `serve`): the browser must
    // not end up its child.
    let forward = if args.open {
        Some(open_browser(&book_dir, &server, out)?)
    } else {
        None
    };
    let signal = Arc::new(AtomicUsize::new(0));
    let stop = Arc::new(AtomicBool::new(false));
    // A child ended: a supervisor, or one of what a snippet that killed its
    // supervisor left to this process.
    let child_ended = Arc::new(AtomicBool::new(false));
    signal_hook::flag::register(signal_hook::consts::SIGCHLD, Arc::clone(&child_ended))?;
    for s in [
        signal_hook::consts::SIGINT,
        signal_hook::consts::SIGTERM,
        signal_hook::consts::SIGHUP,
        signal_hook::consts::SIGQUIT,
    ] {
        signal_hook::flag::register_usize(s, Arc::clone(&signal), s as usize)?;
        signal_hook::flag::register(s, Arc::clone(&stop))?;
    }
    writeln!(
        out,
        "spintop book: building spintop for ▶ in the background (cargo build; a minute or two the first time)…"
    )?;
    out.flush()?;
    server.warm_up();
    serve_until_stopped(&server, &stop, &child_ended, out)?;
    let name = match signal.load(Ordering::Relaxed) as i32 {
        signal_hook::consts::SIGINT => "SIGINT",
        signal_hook::consts::SIGTERM => "SIGTERM",
        signal_hook::consts::SIGHUP => "SIGHUP",
        signal_hook::consts::SIGQUIT => "SIGQUIT",
        _ => "a signal",
    };
    let said = stop_everything(&server, name);
    if let Some(file) = forward {
        let _ = std::fs::remove_file(file);
    }
    writeln!(out, "{said}")?;
    Ok(())
}

/// Serves on a thread of its own until `stop`; meanwhile says when the
/// background build is done, and kills what a snippet left to this process
/// whenever a child ends (`child_ended`).
fn serve_until_stopped(
    server: &Server,
    stop: &AtomicBool,
    child_ended: &AtomicBool,
    out: &mut Gate<'_>,
) -> Result<(), CliError> {
    std::thread::scope(|scope| -> Result<(), CliError> {
        std::thread::Builder::new()
            .spawn_scoped(scope, || server.serve(stop))
            .map_err(|e| CliError::Stopped(format!("cannot start the server's thread: {e}")))?;
        let mut shown = false;
        while !stop.load(Ordering::Relaxed) {
            if child_ended.swap(false, Ordering::Relaxed) {
                server.sweep_strays();
            }
            if !shown {
                shown = say_warm_up(server, out)?;
            }
            std::thread::sleep(Duration::from_millis(50));
        }
        Ok(())
    })
}

/// Says how the background build ended, once it has: whether it did.
fn say_warm_up(server: &Server, out: &mut Gate<'_>) -> Result<bool, CliError> {
    let said = match server.warm_up_state() {
        WarmUp::Ready { took } => {
            writeln!(
                out,
                "spintop book: ▶ is ready (the background build took {:.0} s)",
                took.as_secs_f64()
            )?;
            true
        }
        WarmUp::Failed { why } => {
            let first = why.lines().next().unwrap_or("").to_string();
            writeln!(
                out,
                "spintop book: the background build failed ({first}); ▶ will show the whole message"
            )?;
            true
        }
        WarmUp::NotStarted | WarmUp::Building { .. } => false,
    };
    out.flush()?;
    Ok(said)
}

/// Stops the running tree, then whatever a tree left to this process (for
/// up to 3 s: what is killed may have started more meanwhile); the line
/// that says so, after signal `name`.
fn stop_everything(server: &Server, name: &str) -> String {
    let start = Instant::now();
    let mut gone = server.shutdown();
    let swept = Instant::now();
    while server.sweep_strays() > 0 {
        if swept.elapsed() > Duration::from_secs(3) {
            gone = false;
            break;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    server.sweep_strays();
    if gone {
        format!("spintop book: stopped ({name}); nothing it started is left running")
    } else {
        let waited = start.elapsed().as_secs_f64().ceil();
        format!(
            "spintop book: stopped ({name}), but what its last snippet started did not end within {waited} s"
        )
    }
}

/// `--open`: writes a page readable by the reader only that forwards to the
/// address, and opens that page, detached; returns the page's path.
///
/// NOTE: why not open the address itself: a command line is readable by
/// every user (`/proc/PID/cmdline`), and the browser's would hold the token
/// for as long as it runs. Jupyter opens such a file for the same reason.
fn open_browser(dir: &Path, server: &Server, out: &mut impl Write) -> Result<PathBuf, CliError> {
    use std::os::unix::fs::OpenOptionsExt;
    use std::os::unix::process::CommandExt;
    let page = dir.join(format!("open-{}.html", server.port()));
    let url = server.url();
    let html = format!(
        "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><meta http-equiv=\"refresh\" content=\"0; url={url}\"><title>spintop book</title></head><body><a href=\"{url}\">spintop book</a></body></html>\n"
    );
    std::fs::create_dir_all(dir)?;
    let _ = std::fs::remove_file(&page);
    std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .mode(0o600)
        .open(&page)?
        .write_all(html.as_bytes())?;
    // Through a shell that exits at once, so the opener (and a browser it
    // starts) is nobody's child here; in a process group of its own, so
    // that Ctrl-C or Ctrl-Z at the terminal, which signal the foreground
    // group, stop the book and not the browser (as Python's `webbrowser`
    // starts one in a session of its own).
    let opener = if cfg!(target_os = "macos") {
        "open"
    } else {
        "xdg-open"
    };
    let found = std::env::var_os("PATH")
        .is_some_and(|path| std::env::split_paths(&path).any(|d| d.join(opener).is_file()));
    let opened = found
        && Command::new("sh")
            .process_group(0)
            .args(["-c", "\"$0\" \"$1\" >/dev/null 2>&1 &", opener])
            .arg(&page)
            .status()
            .is_ok_and(|s| s.success());
    if !opened {
        writeln!(
            out,
            "spintop book: could not open a browser ({opener} not found); open the address above"
        )?;
    }
    Ok(page)
}

/// `--self-test`: the background build, then one snippet twice through the
/// real server (the first ▶ after the build, then a warm one), with times.
fn self_test(server: Server, out: &mut impl Write) -> Result<(), CliError> {
    let stop = AtomicBool::new(false);
    server.warm_up();
    std::thread::scope(|scope| {
        std::thread::Builder::new()
            .spawn_scoped(scope, || server.serve(&stop))
            .map_err(|e| CliError::Stopped(format!("cannot start the server's thread: {e}")))?;
        let result = measure(&server, out);
        stop.store(true, Ordering::Relaxed);
        result
    })
}

/// The measurements of `--self-test`, on a serving server.
fn measure(server: &Server, out: &mut impl Write) -> Result<(), CliError> {
    let port = server.port();
    let token = server.token().to_string();
    let took = loop {
        match server.warm_up_state() {
            WarmUp::Ready { took } => break took,
            WarmUp::Failed { why } => {
                return Err(CliError::Stopped(format!(
                    "the background build failed: {why}"
                )));
            }
            WarmUp::NotStarted | WarmUp::Building { .. } => {
                std::thread::sleep(Duration::from_millis(100));
            }
        }
    };
    writeln!(
        out,
        "spintop book --self-test: background build: {:.1} s",
        took.as_secs_f64()
    )?;
    out.flush()?;
    let code = "use spintop::physics::symmetric_top::{self as sym, SymmetricTop};\nuse spintop::math::Vec3;\n\nfn main() {\n    let top = SymmetricTop::figure();\n    let w = sym::reduced_closed_form(&top, &Vec3::new(0.0, 0.1, 0.2), 100.0);\n    println!(\"Omega(100) = ({:.6}, {:.6}, {:.6})\", w.x, w.y, w.z);\n}\n";
    let body = serde_json::json!({ "code": code, "edition": "2024" }).to_string();
    let origin = format!("http://127.0.0.1:{port}");
    let headers = [
        ("X-Spintop-Token", token.as_str()),
        ("Origin", origin.as_str()),
        ("Content-Type", "application/json"),
    ];
    let mut times = Vec::new();
    for label in ["first ▶ after the background build", "warm ▶"] {
        let start = Instant::now();
        let (status, mut answer) =
            server::request(port, "POST", "/evaluate.json", &headers, body.as_bytes())?;
        if status == 202 {
            loop {
                std::thread::sleep(Duration::from_millis(500));
                answer = server::request(port, "GET", "/evaluate/status", &headers, b"")?.1;
                let v: serde_json::Value = serde_json::from_str(&answer).unwrap_or_default();
                if v["done"] == serde_json::Value::Bool(true) {
                    break;
                }
            }
        }
        let secs = start.elapsed().as_secs_f64();
        let v: serde_json::Value = serde_json::from_str(&answer).unwrap_or_default();
        let result = v["result"].as_str().unwrap_or("").trim().to_string();
        writeln!(
            out,
            "spintop book --self-test: {label}: {secs:.2} s → {result}"
        )?;
        out.flush()?;
        if v["success"] != serde_json::Value::Bool(true) {
            return Err(CliError::Stopped(format!(
                "the self-test snippet did not run: {result}"
            )));
        }
        times.push(secs);
    }
    writeln!(
        out,
        "spintop book --self-test: first ▶ {:.2} s, warm ▶ {:.2} s (the goal is under 3 s)",
        times[0], times[1]
    )?;
    Ok(())
}

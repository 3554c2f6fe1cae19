//! `spintop book`: the book served on 127.0.0.1, where ▶ compiles and runs
//! every snippet against the local spintop. Builds the book first when its
//! sources are newer than the last build. The server is
//! [`crate::server`]; this file only launches it.

use super::gate::Gate;
use super::{CliError, bad};
use crate::server::{self, Config, Server, default_runner};
use clap::Args;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Instant, SystemTime};

/// The raw arguments of `book`.
#[derive(Debug, Default, Args)]
pub struct BookArgs {
    /// The port on 127.0.0.1 (default: a free one).
    #[arg(long)]
    port: Option<u16>,
    /// Open the book in the default browser.
    #[arg(long)]
    open: bool,
    /// Measure instead of serving: run one snippet through the server twice
    /// (the first run may build spintop; the second is warm), print the times, exit.
    #[arg(long)]
    self_test: bool,
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
    let result = Command::new("mdbook")
        .arg("build")
        .arg(&book)
        .arg("--dest-dir")
        .arg(site)
        .output()
        .map_err(|e| bad(format!("cannot run mdbook: {e}")))?;
    if !result.status.success() {
        let text = String::from_utf8_lossy(&result.stderr);
        let first = text
            .lines()
            .find(|l| l.contains("ERROR") || l.contains("error"))
            .unwrap_or("mdbook build failed");
        return Err(bad(format!("the book does not build: {first}")));
    }
    Ok(())
}

/// Runs `spintop book`.
pub(crate) fn execute(args: BookArgs, out: &mut Gate<'_>) -> Result<(), CliError> {
    let repo = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    if !repo.join("book/book.toml").is_file() || !repo.join("Cargo.toml").is_file() {
        return Err(bad(format!(
            "spintop book serves the book of the repository, and {} is missing; run it from a clone of spintop (cargo run --release -- book)",
            repo.join("book/book.toml").display()
        )));
    }
    let site = repo.join("target").join("spintop-book").join("site");
    build(&repo, &site, out)?;
    let server = Server::bind(Config {
        site,
        port: args.port.unwrap_or(0),
        runner: default_runner(&repo),
    })
    .map_err(|e| bad(e.to_string()))?;
    if args.self_test {
        return self_test(server, out);
    }
    writeln!(
        out,
        "spintop book: serving {} (▶ runs each snippet against this spintop; Ctrl-C stops)",
        server.url()
    )?;
    out.flush()?;
    if args.open {
        let opened = Command::new("xdg-open").arg(server.url()).spawn().is_ok()
            || Command::new("open").arg(server.url()).spawn().is_ok();
        if !opened {
            writeln!(
                out,
                "spintop book: could not open a browser; open the address above"
            )?;
        }
    }
    let stop = Arc::new(AtomicBool::new(false));
    for signal in [
        signal_hook::consts::SIGINT,
        signal_hook::consts::SIGTERM,
        signal_hook::consts::SIGHUP,
    ] {
        signal_hook::flag::register(signal, Arc::clone(&stop))?;
    }
    server.serve(&stop);
    writeln!(out, "spintop book: stopped")?;
    Ok(())
}

/// `--self-test`: one snippet, twice, through the real server.
fn self_test(server: Server, out: &mut impl Write) -> Result<(), CliError> {
    let port = server.port();
    let token = server.token().to_string();
    let stop = Arc::new(AtomicBool::new(false));
    let stop_thread = Arc::clone(&stop);
    let thread = std::thread::spawn(move || server.serve(&stop_thread));
    let code = "use spintop::physics::symmetric_top::{self as sym, SymmetricTop};\nuse spintop::math::Vec3;\n\nfn main() {\n    let top = SymmetricTop::figure();\n    let w = sym::reduced_closed_form(&top, &Vec3::new(0.0, 0.1, 0.2), 100.0);\n    println!(\"Omega(100) = ({:.6}, {:.6}, {:.6})\", w.x, w.y, w.z);\n}\n";
    let body = serde_json::json!({ "code": code, "edition": "2024" }).to_string();
    let origin = format!("http://127.0.0.1:{port}");
    let headers = [
        ("X-Spintop-Token", token.as_str()),
        ("Origin", origin.as_str()),
        ("Content-Type", "application/json"),
    ];
    let mut times = Vec::new();
    for label in ["first run (may build spintop)", "warm run"] {
        let start = Instant::now();
        let (status, mut answer) =
            server::request(port, "POST", "/evaluate.json", &headers, body.as_bytes())?;
        if status == 202 {
            loop {
                std::thread::sleep(std::time::Duration::from_millis(500));
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
        if v["success"] != serde_json::Value::Bool(true) {
            stop.store(true, Ordering::Relaxed);
            let _ = thread.join();
            return Err(CliError::Stopped(format!(
                "the self-test snippet did not run: {result}"
            )));
        }
        times.push(secs);
    }
    stop.store(true, Ordering::Relaxed);
    let _ = thread.join();
    writeln!(
        out,
        "spintop book --self-test: warm round trip {:.2} s (the goal is under 3 s)",
        times[1]
    )?;
    Ok(())
}

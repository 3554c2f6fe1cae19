//! `spintop book` run the way a reader runs it: typed at an interactive
//! shell on a terminal (tmux with a socket of its own, 80×24), where Ctrl-C
//! and Ctrl-Z signal the terminal's foreground process group, whatever
//! that holds.

use super::*;

/// An interactive shell in tmux, on a socket of its own; killed on drop.
struct Terminal {
    socket: String,
}

impl Terminal {
    /// A shell at 80×24, or `None` (said) where there is no tmux.
    fn open(name: &str) -> Option<Self> {
        let t = Self {
            socket: format!("spintop-{name}-{}", std::process::id()),
        };
        let opened = t.tmux(&[
            "new-session",
            "-d",
            "-x",
            "80",
            "-y",
            "24",
            "bash --norc -i",
        ]);
        if !opened {
            eprintln!("no tmux: skipped");
        }
        opened.then_some(t)
    }

    fn tmux(&self, args: &[&str]) -> bool {
        std::process::Command::new("tmux")
            .args(["-L", &self.socket])
            .args(args)
            .status()
            .is_ok_and(|s| s.success())
    }

    /// Types `line` and Enter.
    fn type_line(&self, line: &str) {
        assert!(self.tmux(&["send-keys", "-l", line]));
        assert!(self.tmux(&["send-keys", "Enter"]));
    }

    /// Presses `key` (`C-c`, `C-z`).
    fn press(&self, key: &str) {
        assert!(self.tmux(&["send-keys", key]));
    }
}

impl Drop for Terminal {
    fn drop(&mut self) {
        self.tmux(&["kill-server"]);
    }
}

/// The command line that runs `spintop book` on `root`'s site and scratch
/// with the stand-in cargo, `args` added, its output to `root/out`.
fn book_line(root: &Path, env: &str, args: &str) -> String {
    format!(
        "{env} CARGO={} CARGO_TARGET_DIR={} {} book {args} --site {} --scratch {} > {} 2>&1",
        fake_cargo(root).display(),
        root.join("target").display(),
        env!("CARGO_BIN_EXE_spintop"),
        site(root).display(),
        root.join("scratch").display(),
        root.join("out").display()
    )
}

/// What `spintop book` said so far.
fn said(root: &Path) -> String {
    std::fs::read_to_string(root.join("out")).unwrap_or_default()
}

/// Ctrl-C at the terminal stops the book, not the browser `--open`
/// started (here a stand-in that sleeps, its process id recorded).
#[test]
#[ignore = "end-to-end: tmux, spintop book at a terminal"]
fn ctrl_c_at_the_terminal_stops_the_book_and_not_the_browser_it_opened() {
    use std::os::unix::fs::PermissionsExt;
    let root = scratch_root("open-tty");
    let bin = root.join("bin");
    std::fs::create_dir_all(&bin).unwrap();
    let browser = root.join("browser.pid");
    let opener = bin.join("xdg-open");
    std::fs::write(
        &opener,
        format!(
            "#!/bin/sh\necho $$ > {0}.tmp; mv {0}.tmp {0}\nexec sleep 60\n",
            browser.display()
        ),
    )
    .unwrap();
    std::fs::set_permissions(&opener, std::fs::Permissions::from_mode(0o755)).unwrap();
    let Some(terminal) = Terminal::open("open-tty") else {
        return;
    };
    let path = format!("PATH={}:$PATH", bin.display());
    terminal.type_line(&book_line(&root, &path, "--open"));
    let ready = wait_for(Duration::from_secs(60), || {
        said(&root).contains("▶ is ready") && browser.is_file()
    });
    assert!(ready, "{}", said(&root));
    let pid = pid_file(&root, "browser.pid", Duration::ZERO).unwrap();
    terminal.press("C-c");
    let stopped = wait_for(Duration::from_secs(20), || {
        said(&root).contains("stopped (SIGINT)")
    });
    let survived = alive(pid);
    drop(terminal);
    if let Some(p) = rustix::process::Pid::from_raw(pid) {
        let _ = rustix::process::kill_process(p, rustix::process::Signal::KILL);
    }
    assert!(stopped, "{}", said(&root));
    assert!(survived, "Ctrl-C at the terminal killed the browser");
    let last = said(&root);
    assert!(
        last.contains("nothing it started is left running"),
        "{last}"
    );
    let _ = std::fs::remove_dir_all(&root);
}

/// Ctrl-Z at the terminal suspends the book (its shell says Stopped), and
/// the snippet it was running, with the daemon it started, still ends at
/// the time limit (10 s): the supervisor is in a session of its own, which
/// the terminal's Ctrl-Z does not reach, and keeps its own clock. `fg`
/// resumes the book, which answers again, and Ctrl-C stops it.
#[test]
#[ignore = "end-to-end: tmux, spintop book at a terminal, real time"]
fn ctrl_z_at_the_terminal_suspends_the_book_and_its_snippet_still_ends_at_its_limit() {
    let root = scratch_root("ctrl-z");
    let Some(terminal) = Terminal::open("ctrl-z") else {
        return;
    };
    terminal.type_line(&book_line(&root, "", ""));
    assert!(
        wait_for(Duration::from_secs(60), || said(&root)
            .contains("▶ is ready")),
        "{}",
        said(&root)
    );
    let address = said(&root)
        .split_whitespace()
        .find(|w| w.starts_with("http://127.0.0.1:"))
        .unwrap()
        .to_string();
    let (port, token) = address
        .trim_start_matches("http://127.0.0.1:")
        .split_once("/?token=")
        .unwrap();
    let (port, token) = (port.parse::<u16>().unwrap(), token.to_string());
    let code = script(
        "setsid sh -c 'read -r pid rest < /proc/self/stat; echo $pid > daemon.pid.tmp; mv daemon.pid.tmp daemon.pid; while :; do sleep 1; done' &\nwhile [ ! -f daemon.pid ]; do sleep 0.01; done\nread -r me rest < /proc/self/stat; echo $me > snippet.pid\nwhile :; do sleep 1; done\n",
    );
    let asked = std::thread::spawn(move || {
        request(
            port,
            "POST",
            "/evaluate.json",
            &[("X-Spintop-Token", &token)],
            &body(&code),
        )
    });
    let scratch = root.join("scratch");
    let snippet = pid_file(&scratch, "snippet.pid", Duration::from_secs(30)).unwrap();
    let daemon = pid_file(&scratch, "daemon.pid", Duration::ZERO).unwrap();
    let supervisor = parent_of(parent_of(snippet).unwrap()).unwrap();
    let book = parent_of(supervisor).unwrap();
    let before = age(supervisor).unwrap();
    let pressed = Instant::now();
    terminal.press("C-z");
    let state = |pid: i32| {
        processes()
            .into_iter()
            .find(|&(p, _, _)| p == pid)
            .map(|(_, _, s)| s)
    };
    assert!(
        wait_for(Duration::from_secs(5), || state(book) == Some('T')),
        "Ctrl-Z did not suspend the book: {:?}",
        state(book)
    );
    let limit = Duration::from_secs(10);
    let gone = wait_for(limit + Duration::from_secs(3), || {
        !alive(snippet) && !alive(daemon)
    });
    let took = before + pressed.elapsed();
    assert!(
        gone,
        "alive {took:?} after its supervisor started, the book suspended"
    );
    assert!(took + Duration::from_millis(50) >= limit, "{took:?}");
    eprintln!(
        "Ctrl-Z {before:?} after the supervisor started; the snippet and its daemon gone {took:?} after (limit {limit:?})"
    );
    terminal.type_line("fg");
    let (status, text) = asked.join().unwrap().unwrap();
    assert!(status == 200 || status == 202, "{status} {text}");
    terminal.press("C-c");
    assert!(
        wait_for(Duration::from_secs(20), || said(&root)
            .contains("nothing it started is left running")),
        "{}",
        said(&root)
    );
    let _ = std::fs::remove_dir_all(&root);
}

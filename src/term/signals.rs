//! Signals that end a terminal session: SIGTERM, SIGINT, SIGHUP and SIGQUIT.
//!
//! By default these kill the process at once, before anything can leave raw
//! mode and the alternate screen, and the user is left typing `reset` blind.
//! [`Signals`] turns them into a flag (signal-hook's `flag` module, which is
//! async-signal-safe) that the draw loops read every frame; the loop then ends
//! the ordinary way, so the same guard that restores the terminal on `q`
//! restores it on a signal too. The caller exits with 128 + the signal's
//! number, as a shell expects of a process a signal stopped.

use std::io;
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};

/// The signals that end a session, with their names.
#[cfg(unix)]
pub const HANDLED: [(i32, &str); 4] = [
    (signal_hook::consts::SIGTERM, "SIGTERM"),
    (signal_hook::consts::SIGINT, "SIGINT"),
    (signal_hook::consts::SIGHUP, "SIGHUP"),
    (signal_hook::consts::SIGQUIT, "SIGQUIT"),
];

/// The handlers, registered while this lives.
pub struct Signals {
    received: Arc<AtomicUsize>,
    /// Set when the session ends the normal way (this value is dropped).
    finished: Arc<std::sync::atomic::AtomicBool>,
    #[cfg(unix)]
    ids: Vec<signal_hook::SigId>,
}

/// How long the draw loop has to end by itself after a signal before the
/// watchdog restores the terminal and exits for it.
pub const GRACE: std::time::Duration = std::time::Duration::from_millis(1500);

/// The watchdog: once a signal has arrived, the loop normally ends within a
/// frame. If it does not (seen when the terminal itself has gone away: the
/// event reader then spins on end-of-file and never returns), the terminal is
/// restored here and the process exits with 128 + the signal's number.
///
/// The terminal can also vanish with no signal to this process (a shell
/// between it and the terminal takes the hang-up): on Linux the process then
/// loses its controlling terminal, which `/proc/self/stat` shows, and the
/// watchdog treats that as SIGHUP.
fn watchdog(received: Arc<AtomicUsize>, finished: Arc<std::sync::atomic::AtomicBool>) {
    std::thread::spawn(move || {
        let had_terminal = controlling_terminal().is_some_and(|t| t != 0);
        loop {
            if finished.load(Ordering::Relaxed) {
                return;
            }
            #[cfg(unix)]
            if had_terminal && controlling_terminal() == Some(0) {
                let _ = received.compare_exchange(
                    0,
                    signal_hook::consts::SIGHUP as usize,
                    Ordering::Relaxed,
                    Ordering::Relaxed,
                );
            }
            let signal = received.load(Ordering::Relaxed);
            if signal != 0 {
                std::thread::sleep(GRACE);
                if finished.load(Ordering::Relaxed) {
                    return;
                }
                restore_from_another_thread();
                std::process::exit(128 + i32::try_from(signal).unwrap_or(0));
            }
            std::thread::sleep(std::time::Duration::from_millis(50));
        }
    });
}

impl Signals {
    /// Registers the handlers.
    pub fn install() -> io::Result<Self> {
        let received = Arc::new(AtomicUsize::new(0));
        #[cfg(unix)]
        {
            let mut ids = Vec::new();
            for (signal, _) in HANDLED {
                ids.push(signal_hook::flag::register_usize(
                    signal,
                    Arc::clone(&received),
                    signal as usize,
                )?);
            }
            let finished = Arc::new(std::sync::atomic::AtomicBool::new(false));
            watchdog(Arc::clone(&received), Arc::clone(&finished));
            Ok(Signals {
                received,
                finished,
                ids,
            })
        }
        #[cfg(not(unix))]
        Ok(Signals {
            received,
            finished: Arc::new(std::sync::atomic::AtomicBool::new(false)),
        })
    }

    /// The signal received so far, if any.
    pub fn received(&self) -> Option<i32> {
        match self.received.load(Ordering::Relaxed) {
            0 => None,
            n => i32::try_from(n).ok(),
        }
    }
}

impl Drop for Signals {
    fn drop(&mut self) {
        self.finished.store(true, Ordering::Relaxed);
        #[cfg(unix)]
        for id in self.ids.drain(..) {
            signal_hook::low_level::unregister(id);
        }
    }
}

/// Restores the terminal without touching `stdout`, whose lock the main
/// thread may hold for the whole session: raw mode is switched off on the
/// terminal device, and the escape codes that leave the alternate screen and
/// show the cursor go to `/dev/tty` (when there is still one).
fn restore_from_another_thread() {
    let _ = crossterm::terminal::disable_raw_mode();
    #[cfg(unix)]
    if let Ok(mut tty) = std::fs::OpenOptions::new().write(true).open("/dev/tty") {
        use std::io::Write;
        // Leave the alternate screen, show the cursor, release the mouse,
        // end bracketed paste.
        let _ = tty.write_all(
            b"\x1b[?1049l\x1b[?25h\x1b[?1000l\x1b[?1002l\x1b[?1003l\x1b[?1006l\x1b[?1015l\x1b[?2004l",
        );
        let _ = tty.flush();
    }
}

/// The controlling terminal's device number (`tty_nr`, field 7 of
/// `/proc/self/stat`; 0 when there is none), where the platform has it.
fn controlling_terminal() -> Option<u64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // The command name (field 2) is in parentheses and may hold spaces.
    let rest = &stat[stat.rfind(')')? + 2..];
    rest.split_whitespace().nth(4)?.parse().ok()
}

/// `crossterm::event::poll`, with a poll cut short by a signal (EINTR) read
/// as "no event": the loop then sees the signal's flag and ends cleanly.
pub fn poll(timeout: std::time::Duration) -> io::Result<bool> {
    match crossterm::event::poll(timeout) {
        Err(e) if e.kind() == io::ErrorKind::Interrupted => Ok(false),
        other => other,
    }
}

/// The name of a signal number (`SIGTERM`), for the message after a session.
pub fn name(signal: i32) -> String {
    #[cfg(unix)]
    if let Some((_, n)) = HANDLED.iter().find(|(s, _)| *s == signal) {
        return (*n).to_string();
    }
    format!("signal {signal}")
}

/// Stops this process as a shell's job is stopped by Ctrl-Z (SIGTSTP, whose
/// default action is to stop), and returns once it is continued (`fg`). In
/// a process group no shell controls the signal is discarded, and this
/// returns at once.
pub fn stop_as_a_job() {
    #[cfg(unix)]
    {
        let _ = signal_hook::low_level::raise(signal_hook::consts::SIGTSTP);
    }
}

#[cfg(all(test, unix))]
mod tests {
    use super::*;

    #[test]
    fn a_raised_signal_is_recorded_not_fatal() {
        let signals = Signals::install().expect("handlers register");
        assert_eq!(signals.received(), None);
        signal_hook::low_level::raise(signal_hook::consts::SIGHUP).expect("raise");
        assert_eq!(signals.received(), Some(signal_hook::consts::SIGHUP));
        assert_eq!(name(signal_hook::consts::SIGHUP), "SIGHUP");
    }
}

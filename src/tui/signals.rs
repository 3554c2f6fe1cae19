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
    #[cfg(unix)]
    ids: Vec<signal_hook::SigId>,
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
            Ok(Signals { received, ids })
        }
        #[cfg(not(unix))]
        Ok(Signals { received })
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
        #[cfg(unix)]
        for id in self.ids.drain(..) {
            signal_hook::low_level::unregister(id);
        }
    }
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

/// Refuses a terminal that cannot draw the full-screen view (`TERM=dumb`,
/// or no `TERM` at all on Unix), as a missing terminal is refused.
pub fn check_terminal_capable() -> Result<(), String> {
    match std::env::var("TERM") {
        Ok(t) if t == "dumb" => {
            Err("TERM=dumb: this terminal cannot draw the full-screen view".into())
        }
        _ => Ok(()),
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

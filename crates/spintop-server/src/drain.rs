//! A tree's output pipes, read without blocking by the thread that waits
//! for the tree: no thread of their own, so that a run needs no thread the
//! reader's process limit might refuse (a fork bomb that used it up would
//! otherwise leave its output unread, and the pipe full).

use std::fs::File;
use std::io::{ErrorKind, Read};
use std::os::fd::OwnedFd;
use std::time::{Duration, Instant};

/// Output kept up to a limit, the rest read and dropped (so a child that
/// prints forever never blocks on a full pipe).
#[derive(Debug, Default)]
pub(crate) struct Capped {
    pub(crate) text: Vec<u8>,
    pub(crate) truncated: bool,
    limit: usize,
}

impl Capped {
    pub(crate) fn new(limit: usize) -> Self {
        Self {
            limit,
            ..Self::default()
        }
    }

    fn push(&mut self, bytes: &[u8]) {
        let room = self.limit.saturating_sub(self.text.len());
        if bytes.len() > room {
            self.truncated = true;
        }
        self.text.extend_from_slice(&bytes[..bytes.len().min(room)]);
    }
}

/// One pipe, set not to block.
pub(crate) struct Drain {
    from: Option<File>,
}

impl Drain {
    /// `from`, set not to block; `None` (nothing to read) stays so.
    pub(crate) fn new(from: Option<impl Into<OwnedFd>>) -> Self {
        let from = from
            .map(|f| File::from(f.into()))
            .filter(|f| rustix::io::ioctl_fionbio(f, true).is_ok());
        Self { from }
    }

    /// Whether the pipe has ended (or there was none).
    pub(crate) fn done(&self) -> bool {
        self.from.is_none()
    }

    /// Appends to `into` what has arrived, without waiting for more.
    pub(crate) fn pull(&mut self, into: &mut impl Extend<u8>) {
        let Some(from) = &mut self.from else {
            return;
        };
        let mut buf = [0u8; 8192];
        loop {
            match from.read(&mut buf) {
                Ok(0) => break self.from = None,
                Ok(n) => into.extend(buf[..n].iter().copied()),
                Err(e) if e.kind() == ErrorKind::Interrupted => {}
                Err(e) if e.kind() == ErrorKind::WouldBlock => break,
                Err(_) => break self.from = None,
            }
        }
    }
}

impl Extend<u8> for Capped {
    fn extend<I: IntoIterator<Item = u8>>(&mut self, bytes: I) {
        let bytes: Vec<u8> = bytes.into_iter().collect();
        self.push(&bytes);
    }
}

/// Once the tree is gone its pipes are closed, unless a process that left
/// it holds one: reads what is left of `drains` until each has ended, for
/// at most a second.
pub(crate) fn finish(drains: &mut [Drain], into: &mut impl Extend<u8>) {
    let start = Instant::now();
    loop {
        for d in drains.iter_mut() {
            d.pull(into);
        }
        if drains.iter().all(Drain::done) || start.elapsed() > Duration::from_secs(1) {
            return;
        }
        std::thread::sleep(Duration::from_millis(10));
    }
}

/// Complete lines out of bytes that arrive in pieces.
#[derive(Debug, Default)]
pub(crate) struct Lines {
    partial: Vec<u8>,
}

impl Lines {
    /// Takes `bytes`; returns the lines they complete.
    pub(crate) fn feed(&mut self, bytes: &[u8]) -> Vec<String> {
        self.partial.extend_from_slice(bytes);
        let mut lines = Vec::new();
        while let Some(i) = self.partial.iter().position(|&b| b == b'\n') {
            let line: Vec<u8> = self.partial.drain(..=i).collect();
            lines.push(
                String::from_utf8_lossy(&line[..i])
                    .trim_end_matches('\r')
                    .to_string(),
            );
        }
        lines
    }

    /// The last line, if it had no newline.
    pub(crate) fn rest(&mut self) -> Option<String> {
        (!self.partial.is_empty())
            .then(|| String::from_utf8_lossy(&std::mem::take(&mut self.partial)).into_owned())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn output_past_the_limit_is_dropped_and_said() {
        let mut c = Capped::new(5);
        c.extend(b"abc".iter().copied());
        assert!(!c.truncated);
        c.extend(b"defg".iter().copied());
        assert_eq!((c.text.as_slice(), c.truncated), (&b"abcde"[..], true));
    }

    #[test]
    fn lines_are_whole_however_the_bytes_arrive() {
        let mut l = Lines::default();
        assert!(l.feed(b"Compi").is_empty());
        assert_eq!(l.feed(b"ling a\r\nerr"), ["Compiling a"]);
        assert_eq!(l.feed(b"or\nx\n"), ["error", "x"]);
        assert_eq!(l.feed(b"tail"), Vec::<String>::new());
        assert_eq!(l.rest().as_deref(), Some("tail"));
        assert_eq!(l.rest(), None);
    }

    #[test]
    fn a_pipe_is_read_without_blocking_to_its_end() {
        let (reader, mut writer) = std::io::pipe().unwrap();
        let mut d = Drain::new(Some(reader));
        let mut got = Capped::new(100);
        d.pull(&mut got);
        assert!(got.text.is_empty() && !d.done(), "nothing yet, and no wait");
        std::io::Write::write_all(&mut writer, b"hello").unwrap();
        drop(writer);
        finish(std::slice::from_mut(&mut d), &mut got);
        assert_eq!(got.text, b"hello");
        assert!(d.done());
    }
}

//! Keys become [`Command`]s; the terminal loop paces frames and feeds the
//! wall clock to [`App::advance_wall`].
//!
//! Keys come from `crossterm`, the same version ratatui's backend is built
//! on (one copy in the dependency tree), so its events and ratatui's agree.

pub use super::app::Command;
use super::app::{App, Mode};
use super::view;
use crate::math::Real;
use crossterm::event::{self, Event, KeyCode, KeyEvent, KeyEventKind, KeyModifiers};
use ratatui::{Terminal, backend::Backend};
use std::io;
use std::time::{Duration, Instant};

/// The command a key asks for in a mode, if any.
pub fn command_for(key: KeyEvent, mode: &Mode) -> Option<Command> {
    if key.kind == KeyEventKind::Release {
        return None;
    }
    if key.modifiers.contains(KeyModifiers::CONTROL) {
        return matches!(key.code, KeyCode::Char('c' | 'C')).then_some(Command::Quit);
    }
    match mode {
        Mode::Quitting => None,
        Mode::Help => Some(match key.code {
            KeyCode::Char('q') => Command::Quit,
            // Any other key closes the overlay.
            _ => Command::ToggleHelp,
        }),
        Mode::Edit { .. } => match key.code {
            KeyCode::Enter => Some(Command::Commit),
            KeyCode::Esc => Some(Command::Cancel),
            KeyCode::Backspace => Some(Command::Backspace),
            KeyCode::Up => Some(Command::NudgeUp),
            KeyCode::Down => Some(Command::NudgeDown),
            KeyCode::Char(c) if c.is_ascii_digit() || ".eE+-".contains(c) => {
                Some(Command::Input(c))
            }
            _ => None,
        },
        Mode::Normal => match key.code {
            KeyCode::Char('q') | KeyCode::Esc => Some(Command::Quit),
            KeyCode::Char(' ') => Some(Command::TogglePause),
            KeyCode::Char('.') | KeyCode::Right => Some(Command::Step),
            // `=` is `+` without Shift on most layouts.
            KeyCode::Char('+' | '=') => Some(Command::Faster),
            KeyCode::Char('-' | '_') => Some(Command::Slower),
            KeyCode::Char('r') => Some(Command::Reset),
            KeyCode::Char('[') => Some(Command::RatioDown),
            KeyCode::Char(']') => Some(Command::RatioUp),
            KeyCode::Up => Some(Command::SelectPrevious),
            KeyCode::Down => Some(Command::SelectNext),
            KeyCode::Enter => Some(Command::StartEdit),
            KeyCode::Char('m') => Some(Command::CycleMethod),
            KeyCode::Char('l') => Some(Command::ToggleLogTime),
            KeyCode::Char('?') => Some(Command::ToggleHelp),
            _ => None,
        },
    }
}

/// The redraw interval: about 30 frames per second.
pub const FRAME: Duration = Duration::from_nanos(1_000_000_000 / 30);

/// What a run of the loop did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LoopReport {
    /// Frames drawn.
    pub frames: u64,
    /// Wall-clock time of the loop.
    pub wall: Duration,
    /// CPU time of the process during the loop (user + system), where the
    /// platform reports it.
    pub cpu: Option<Duration>,
    /// The signal that ended the loop (SIGTERM, SIGINT, SIGHUP, SIGQUIT), if
    /// one did.
    pub signal: Option<i32>,
}

impl LoopReport {
    /// Frames per wall-clock second.
    pub fn fps(&self) -> Real {
        self.frames as Real / self.wall.as_secs_f64()
    }

    /// CPU time as a fraction of one core.
    pub fn cpu_share(&self) -> Option<Real> {
        self.cpu.map(|c| c.as_secs_f64() / self.wall.as_secs_f64())
    }
}

/// The CPU time (user + system) this process has used, from `/proc/self/stat`.
///
/// NOTE: fields 14 and 15 of `/proc/self/stat` count clock ticks of USER_HZ,
/// which Linux fixes at 100 for user space on every architecture; reading the
/// file keeps the crate free of `unsafe` (`getrusage` would need libc).
pub fn process_cpu_time() -> Option<Duration> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // The command name (field 2) is in parentheses and may hold spaces.
    let rest = &stat[stat.rfind(')')? + 2..];
    let fields: Vec<&str> = rest.split_whitespace().collect();
    // `rest` starts at field 3, so utime (14) and stime (15) are at 11 and 12.
    let utime: u64 = fields.get(11)?.parse().ok()?;
    let stime: u64 = fields.get(12)?.parse().ok()?;
    Some(Duration::from_millis((utime + stime) * 10))
}

/// Run the live view on a terminal until quit (or for `limit`, for the
/// benchmark): draw about 30 times a second, step the models by the wall
/// clock, and apply the keys in between.
pub fn run<B: Backend>(
    terminal: &mut Terminal<B>,
    app: &mut App,
    limit: Option<Duration>,
) -> io::Result<LoopReport>
where
    B::Error: Send + Sync + 'static,
{
    let signals = super::signals::Signals::install()?;
    let start = Instant::now();
    let cpu_start = process_cpu_time();
    let mut last = start;
    let mut next_frame = start;
    let mut frames = 0;
    while !app.should_quit() && signals.received().is_none() {
        let now = Instant::now();
        if limit.is_some_and(|l| now - start >= l) {
            break;
        }
        app.advance_wall(now - last);
        last = now;
        terminal
            .draw(|frame| view::draw(frame, app))
            .map_err(io::Error::other)?;
        frames += 1;
        next_frame += FRAME;
        if next_frame < Instant::now() {
            // Behind schedule (a slow terminal): do not try to catch up frames.
            next_frame = Instant::now() + FRAME;
        }
        // Handle keys until the next frame is due.
        loop {
            let timeout = next_frame.saturating_duration_since(Instant::now());
            if timeout.is_zero() || !super::signals::poll(timeout)? {
                break;
            }
            if let Event::Key(key) = event::read()? {
                // On the "please enlarge" screen nothing is visible, so only
                // quit is taken; other keys would change the models unseen.
                let small = terminal
                    .size()
                    .is_ok_and(|s| s.width < view::MIN_WIDTH || s.height < view::MIN_HEIGHT);
                if let Some(command) = command_for(key, app.mode())
                    && (!small || command == Command::Quit)
                {
                    app.apply(command);
                }
                if app.should_quit() {
                    break;
                }
            }
            if signals.received().is_some() {
                break;
            }
            // A resize needs nothing: the next draw fits the new size.
        }
    }
    let wall = start.elapsed();
    let cpu = process_cpu_time()
        .zip(cpu_start)
        .map(|(end, begin)| end.saturating_sub(begin));
    Ok(LoopReport {
        frames,
        wall,
        cpu,
        signal: signals.received(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cpu_time_is_read_on_linux() {
        if cfg!(target_os = "linux") {
            // Busy-wait until the counter moves by 20 ms (or give up after 10 s
            // of wall time, which would mean the counter is stuck).
            let a = process_cpu_time().expect("/proc/self/stat is readable");
            let t = Instant::now();
            let mut x = 0u64;
            let mut b = a;
            while b < a + Duration::from_millis(20) && t.elapsed() < Duration::from_secs(10) {
                for _ in 0..100_000 {
                    x = x.wrapping_add(std::hint::black_box(1));
                }
                b = process_cpu_time().unwrap();
            }
            assert!(b >= a + Duration::from_millis(20), "{a:?} -> {b:?} ({x})");
        }
    }
}

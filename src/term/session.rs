//! The terminal of both views (`spintop tui` and `spintop learn`): checked,
//! set up, run, and always restored.
//!
//! One loop serves both: a [`Screen`] turns terminal events into its own
//! commands, applies them, advances by the wall clock and draws; the loop
//! paces frames, reads events in between and ends on quit or on a signal.
//! Ctrl-Z is the loop's own: the terminal is restored, the process stops as
//! a shell's job does, and `fg` brings the screen back whole. [`Session`]
//! owns the terminal and restores it when dropped, so that every way out
//! (quit, an I/O error, an early return, a panic) leaves the shell usable.

use crossterm::event::{
    self, DisableBracketedPaste, DisableMouseCapture, EnableBracketedPaste, EnableMouseCapture,
    Event, KeyCode, KeyEventKind, KeyModifiers,
};
use ratatui::{DefaultTerminal, Frame, Terminal, backend::Backend};
use spintop::math::Real;
use std::io::{self, IsTerminal};
use std::time::{Duration, Instant};

/// A view the loop can run: its commands, how events become them, and its
/// drawing, which only reads.
pub trait Screen {
    /// What a key (or a resize, or the mouse wheel) asks for.
    type Command;
    /// The command an event asks for now, if any.
    fn command(&self, event: &Event) -> Option<Self::Command>;
    /// Apply one command: the only place the screen's state changes.
    fn apply(&mut self, command: Self::Command);
    /// Let wall-clock time pass (the models step by it).
    fn advance(&mut self, elapsed: Duration);
    /// Draw the state.
    fn draw(&self, frame: &mut Frame);
    /// True once quit was asked for.
    fn should_quit(&self) -> bool;
    /// Whether the screen wants the mouse (its wheel) now; off leaves the
    /// terminal's own selection of text to the reader.
    fn wants_mouse(&self) -> bool {
        false
    }
    /// Before a command that may take long (a search across the book): say
    /// so, and true to have the loop draw that before it applies it.
    fn announce(&mut self, _command: &Self::Command) -> bool {
        false
    }
}

/// What the loop asks of the real terminal besides drawing: a test's
/// backend has none of it ([`NoControl`]).
pub trait Control {
    /// Ctrl-Z: hand the terminal back, stop as a job does, take it again on
    /// `fg` (the loop then redraws everything).
    fn suspend(&mut self) -> io::Result<()>;
    /// Capture the mouse (its wheel), or leave it to the terminal.
    fn set_mouse(&mut self, on: bool) -> io::Result<()>;
}

/// A loop without a real terminal (a test backend): nothing to suspend,
/// no mouse.
pub struct NoControl;

impl Control for NoControl {
    fn suspend(&mut self) -> io::Result<()> {
        Ok(())
    }

    fn set_mouse(&mut self, _on: bool) -> io::Result<()> {
        Ok(())
    }
}

/// Why the full-screen views cannot start here.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum Unusable {
    /// Standard output is a pipe or a file.
    #[error("needs a terminal, but stdout is not one")]
    NotATerminal,
    /// `TERM=dumb`.
    #[error(
        "needs a terminal that can draw it (TERM=dumb: this terminal cannot draw the full-screen view)"
    )]
    Dumb,
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

/// Why the full-screen views cannot start here, if they cannot: stdout is
/// not a terminal, or the terminal cannot draw them (`TERM=dumb`). The
/// reason reads after the view's name: "the live view needs a terminal, …".
pub fn check() -> Result<(), Unusable> {
    if !io::stdout().is_terminal() {
        return Err(Unusable::NotATerminal);
    }
    check_terminal_capable()
}

/// Refuses a terminal that cannot draw the full-screen view (`TERM=dumb`),
/// as a missing terminal is refused.
pub fn check_terminal_capable() -> Result<(), Unusable> {
    match std::env::var("TERM") {
        Ok(t) if t == "dumb" => Err(Unusable::Dumb),
        _ => Ok(()),
    }
}

/// The terminal, in raw mode on the alternate screen until dropped.
pub struct Session {
    terminal: DefaultTerminal,
    control: Crossterm,
}

/// The real terminal's controls, through crossterm.
struct Crossterm {
    mouse: bool,
}

impl Control for Crossterm {
    fn suspend(&mut self) -> io::Result<()> {
        if self.mouse {
            crossterm::execute!(io::stdout(), DisableMouseCapture)?;
        }
        let _ = crossterm::execute!(io::stdout(), DisableBracketedPaste);
        ratatui::restore();
        super::signals::stop_as_a_job();
        // Back from `fg`: the terminal as the session had it.
        crossterm::terminal::enable_raw_mode()?;
        crossterm::execute!(
            io::stdout(),
            crossterm::terminal::EnterAlternateScreen,
            EnableBracketedPaste
        )?;
        if self.mouse {
            crossterm::execute!(io::stdout(), EnableMouseCapture)?;
        }
        Ok(())
    }

    fn set_mouse(&mut self, on: bool) -> io::Result<()> {
        if on != self.mouse {
            if on {
                crossterm::execute!(io::stdout(), EnableMouseCapture)?;
            } else {
                crossterm::execute!(io::stdout(), DisableMouseCapture)?;
            }
            self.mouse = on;
        }
        Ok(())
    }
}

impl Session {
    /// Take over the terminal (raw mode, alternate screen). The mouse is
    /// captured while the screen wants it ([`Screen::wants_mouse`]). A panic
    /// restores the terminal as well (ratatui's hook, and the mouse released
    /// first). Pastes arrive bracketed, as one [`Event::Paste`], never as
    /// keys (a pasted "0.4⏎q" is text for a field, not Enter then quit).
    pub fn start() -> io::Result<Self> {
        let terminal = ratatui::try_init()?;
        crossterm::execute!(io::stdout(), EnableBracketedPaste)?;
        let hook = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            let _ = crossterm::execute!(io::stdout(), DisableMouseCapture, DisableBracketedPaste);
            hook(info);
        }));
        Ok(Self {
            terminal,
            control: Crossterm { mouse: false },
        })
    }

    /// Run `screen` until it quits, a signal arrives, or `limit` has passed.
    pub fn run<S: Screen>(
        &mut self,
        screen: &mut S,
        limit: Option<Duration>,
    ) -> io::Result<LoopReport> {
        run(&mut self.terminal, screen, limit, &mut self.control)
    }
}

impl Drop for Session {
    fn drop(&mut self) {
        if self.control.mouse {
            let _ = crossterm::execute!(io::stdout(), DisableMouseCapture);
        }
        let _ = crossterm::execute!(io::stdout(), DisableBracketedPaste);
        ratatui::restore();
    }
}

/// Draw one frame on `terminal`. Without colour (`NO_COLOR`) the colours
/// are taken out of the frame here and crossterm writes them as the
/// defaults: crossterm's own `NO_COLOR` writes an empty SGR (`ESC[m`) for
/// each colour, which the terminal reads as a reset of every attribute, and
/// the emphasis (reversed, bold, underlined) was lost with the colour.
pub fn draw_frame<B: Backend>(
    terminal: &mut Terminal<B>,
    draw: impl FnOnce(&mut Frame),
    no_color: bool,
) -> io::Result<ratatui::CompletedFrame<'_>>
where
    B::Error: Send + Sync + 'static,
{
    if no_color {
        crossterm::style::force_color_output(true);
    }
    terminal
        .draw(|frame| {
            draw(frame);
            if no_color {
                super::theme::strip_colours(frame.buffer_mut());
            }
        })
        .map_err(io::Error::other)
}

/// True for Ctrl-Z, which the loop takes for itself.
fn is_suspend(event: &Event) -> bool {
    matches!(event, Event::Key(k) if k.kind != KeyEventKind::Release
        && k.modifiers.contains(KeyModifiers::CONTROL)
        && matches!(k.code, KeyCode::Char('z' | 'Z')))
}

/// True for Ctrl-L, which the loop takes for itself: draw everything again.
fn is_repaint(event: &Event) -> bool {
    matches!(event, Event::Key(k) if k.kind != KeyEventKind::Release
        && k.modifiers.contains(KeyModifiers::CONTROL)
        && matches!(k.code, KeyCode::Char('l' | 'L')))
}

/// Run `screen` on `terminal` until it quits (or for `limit`, for the
/// benchmark): draw about 30 times a second, let the wall clock pass, and
/// apply the events in between. The screen learns its size before the
/// first frame, and again at every resize. Ctrl-Z and the mouse go to
/// `control`.
pub fn run<B: Backend, S: Screen>(
    terminal: &mut Terminal<B>,
    screen: &mut S,
    limit: Option<Duration>,
    control: &mut dyn Control,
) -> io::Result<LoopReport>
where
    B::Error: Send + Sync + 'static,
{
    let signals = super::signals::Signals::install()?;
    let no_color = super::theme::no_color();
    let start = Instant::now();
    let cpu_start = process_cpu_time();
    let mut last = start;
    let mut next_frame = start;
    let mut frames = 0;
    let mut size = terminal.size().map_err(io::Error::other)?;
    if let Some(c) = screen.command(&Event::Resize(size.width, size.height)) {
        screen.apply(c);
    }
    while !screen.should_quit() && signals.received().is_none() {
        let now = Instant::now();
        if limit.is_some_and(|l| now - start >= l) {
            break;
        }
        screen.advance(now - last);
        last = now;
        control.set_mouse(screen.wants_mouse())?;
        let drawn = draw_frame(terminal, |frame| screen.draw(frame), no_color)?.area;
        // Keys are judged by the screen the reader sees: the size this frame
        // was drawn at. (Resize events come from a signal, and two quick
        // resizes can arrive as one, of the last size: the "enlarge" screen
        // was drawn, and keys pressed on it were taken at the old size.)
        if (drawn.width, drawn.height) != (size.width, size.height) {
            if let Some(c) = screen.command(&Event::Resize(drawn.width, drawn.height)) {
                screen.apply(c);
            }
            size = drawn.as_size();
        }
        frames += 1;
        next_frame += FRAME;
        if next_frame < Instant::now() {
            // Behind schedule (a slow terminal): do not try to catch up frames.
            next_frame = Instant::now() + FRAME;
        }
        // Handle events until the next frame is due.
        loop {
            let timeout = next_frame.saturating_duration_since(Instant::now());
            if timeout.is_zero() || !super::signals::poll(timeout)? {
                break;
            }
            let event = event::read()?;
            if is_suspend(&event) {
                control.suspend()?;
                terminal.clear().map_err(io::Error::other)?;
                // The time stopped is not the models' to run through.
                last = Instant::now();
                continue;
            }
            if is_repaint(&event) {
                // Ctrl-L, as in less: whatever wrote over the screen (a
                // message from another program) is drawn over again.
                terminal.clear().map_err(io::Error::other)?;
                continue;
            }
            if let Some(command) = screen.command(&event) {
                if screen.announce(&command) {
                    draw_frame(terminal, |frame| screen.draw(frame), no_color)?;
                }
                screen.apply(command);
            }
            if screen.should_quit() || signals.received().is_some() {
                break;
            }
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

//! Terminal events become the live view's [`Command`]s.
//!
//! Keys come from `crossterm`, the same version ratatui's backend is built
//! on (one copy in the dependency tree), so its events and ratatui's agree.
//! The loop that reads them is [`crate::term::session`]'s, shared with
//! `spintop learn`.

use super::view;
use crate::live::{App, Command, Mode};
use crate::term::session::Screen;
use crossterm::event::{Event, KeyCode, KeyEvent, KeyEventKind, KeyModifiers};
use ratatui::Frame;
use std::time::Duration;

/// The command a key asks for in a mode, if any; `page` is the rows a page
/// of the help scrolls.
pub fn command_for(key: KeyEvent, mode: &Mode, page: u16) -> Option<Command> {
    if key.kind == KeyEventKind::Release {
        return None;
    }
    if key.modifiers.contains(KeyModifiers::CONTROL) {
        return match key.code {
            KeyCode::Char('c' | 'C') => Some(Command::Quit),
            KeyCode::Char('u' | 'U') if matches!(mode, Mode::Edit { .. }) => {
                Some(Command::ClearField)
            }
            _ => None,
        };
    }
    match mode {
        Mode::Quitting => None,
        Mode::Help(_) => Some(match key.code {
            KeyCode::Down | KeyCode::Char('j') => Command::ScrollHelp(1),
            KeyCode::Up | KeyCode::Char('k') => Command::ScrollHelp(-1),
            KeyCode::PageDown | KeyCode::Char(' ') => Command::ScrollHelp(i64::from(page)),
            KeyCode::PageUp | KeyCode::Char('b') => Command::ScrollHelp(-i64::from(page)),
            KeyCode::Home | KeyCode::Char('g') => Command::ScrollHelp(i64::MIN / 2),
            KeyCode::End | KeyCode::Char('G') => Command::ScrollHelp(i64::MAX / 2),
            // Any other key closes the overlay (q and Esc too: they close,
            // never quit, from the help).
            _ => Command::ToggleHelp,
        }),
        Mode::Edit { .. } => match key.code {
            KeyCode::Enter => Some(Command::Commit),
            KeyCode::Esc => Some(Command::Cancel),
            KeyCode::Backspace => Some(Command::Backspace),
            KeyCode::Up => Some(Command::NudgeUp),
            KeyCode::Down => Some(Command::NudgeDown),
            // Every character goes to the field, which takes it or says
            // why not (`q` included: it never quits from inside an edit).
            KeyCode::Char(c) => Some(Command::Input(c)),
            _ => None,
        },
        Mode::Normal => match key.code {
            // Esc only closes or cancels, never quits (as in `learn`).
            KeyCode::Char('q') => Some(Command::Quit),
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
            KeyCode::Tab => Some(Command::NextModel),
            KeyCode::Esc => Some(Command::Cancel),
            KeyCode::Modifier(_) => None,
            other => Some(Command::Unknown(key_name(other))),
        },
    }
}

/// A key's name as the keyboard shows it (`x`, `F1`, `←`).
pub fn key_name(code: KeyCode) -> String {
    match code {
        KeyCode::Char(c) => c.to_string(),
        KeyCode::F(n) => format!("F{n}"),
        KeyCode::Left => "←".into(),
        KeyCode::Right => "→".into(),
        KeyCode::Up => "↑".into(),
        KeyCode::Down => "↓".into(),
        KeyCode::Esc => "Esc".into(),
        KeyCode::Backspace => "Backspace".into(),
        KeyCode::BackTab => "Shift-Tab".into(),
        other => format!("{other:?}"),
    }
}

impl Screen for App {
    type Command = Command;

    fn command(&self, event: &Event) -> Option<Command> {
        match event {
            Event::Resize(w, h) => Some(Command::Resize(*w, *h)),
            Event::Key(key) => {
                let page = self.view().size.1.saturating_sub(6).max(1);
                let command = command_for(*key, self.mode(), page)?;
                // On the "please enlarge" screen nothing is visible, so only
                // quit is taken; other keys would change the models unseen.
                (!self.view().too_small() || command == Command::Quit).then_some(command)
            }
            Event::Paste(text) if !self.view().too_small() => Some(Command::Paste(text.clone())),
            _ => None,
        }
    }

    fn apply(&mut self, command: Command) {
        App::apply(self, command);
    }

    fn advance(&mut self, elapsed: Duration) {
        self.advance_wall(elapsed);
    }

    fn draw(&self, frame: &mut Frame) {
        view::draw(frame, self);
    }

    fn should_quit(&self) -> bool {
        App::should_quit(self)
    }
}

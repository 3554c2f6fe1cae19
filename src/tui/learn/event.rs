//! Terminal events become `spintop learn`'s [`Command`]s, and the hooks of
//! the terminal loop ([`super::super::session`]).

use super::super::session::Screen;
use super::scene::SceneKey;
use super::{Command, Learn, Mode};
use crossterm::event::{Event, KeyCode, KeyEvent, KeyEventKind, KeyModifiers, MouseEventKind};
use ratatui::Frame;
use std::time::Duration;

impl Learn {
    /// The command an event asks for now, if any.
    pub fn command_for(&self, event: &Event) -> Option<Command> {
        match event {
            Event::Resize(w, h) => Some(Command::Resize(*w, *h)),
            Event::Mouse(m) => match (m.kind, &self.mode) {
                (MouseEventKind::ScrollDown, Mode::Read) => Some(Command::Scroll(3)),
                (MouseEventKind::ScrollUp, Mode::Read) => Some(Command::Scroll(-3)),
                (MouseEventKind::ScrollDown, Mode::Contents(_)) => Some(Command::ContentsDown),
                (MouseEventKind::ScrollUp, Mode::Contents(_)) => Some(Command::ContentsUp),
                _ => None,
            },
            Event::Key(key) => self.key_command(*key),
            _ => None,
        }
    }

    fn key_command(&self, key: KeyEvent) -> Option<Command> {
        if key.kind == KeyEventKind::Release {
            return None;
        }
        if key.modifiers.contains(KeyModifiers::CONTROL) {
            return matches!(key.code, KeyCode::Char('c' | 'C')).then_some(Command::Quit);
        }
        // On the "please enlarge" screen only quit is taken.
        if self.too_small() {
            return matches!(key.code, KeyCode::Char('q')).then_some(Command::Quit);
        }
        use Command as C;
        Some(match &self.mode {
            Mode::Search(_) => match key.code {
                KeyCode::Enter => C::SearchCommit,
                KeyCode::Esc => C::Close,
                KeyCode::Backspace => C::SearchBackspace,
                KeyCode::Char(c) => C::SearchInput(c),
                _ => return None,
            },
            Mode::Course if key.code == KeyCode::Char('h') => C::Hint,
            Mode::Help | Mode::Course => match key.code {
                KeyCode::Char('q') => C::Quit,
                // Any other key closes the overlay; Esc never quits.
                _ => C::Close,
            },
            Mode::Contents(_) => match key.code {
                KeyCode::Up | KeyCode::Char('k') => C::ContentsUp,
                KeyCode::Down | KeyCode::Char('j') => C::ContentsDown,
                KeyCode::Enter => C::ContentsOpen,
                KeyCode::Char('q') => C::Quit,
                _ => C::Close,
            },
            Mode::Read | Mode::Scene => match key.code {
                KeyCode::Char('q') => C::Quit,
                KeyCode::Esc => C::Close,
                KeyCode::Tab => C::ToggleScene,
                KeyCode::Char('?') => C::Help,
                KeyCode::Char('c') => C::Contents,
                KeyCode::Char('a') => C::Course,
                KeyCode::Char('h') => C::Hint,
                KeyCode::Down | KeyCode::Char('j') => C::Scroll(1),
                KeyCode::Up | KeyCode::Char('k') => C::Scroll(-1),
                KeyCode::PageDown | KeyCode::Char(' ' | 'f') => C::PageDown,
                KeyCode::PageUp | KeyCode::Char('b') => C::PageUp,
                KeyCode::Home | KeyCode::Char('g') => C::Top,
                KeyCode::End | KeyCode::Char('G') => C::End,
                KeyCode::Right => C::NextChapter,
                KeyCode::Left => C::PreviousChapter,
                KeyCode::Char('x') => C::Experiment,
                KeyCode::Char('o') => C::ToggleFolds,
                KeyCode::Char('/') => C::SearchStart,
                KeyCode::Char('n') => C::SearchNext,
                KeyCode::Char('N') => C::SearchPrevious,
                KeyCode::Char('p') => C::Scene(SceneKey::Pause),
                KeyCode::Char('.') => C::Scene(SceneKey::Step),
                KeyCode::Char('r') => C::Scene(SceneKey::Reset),
                KeyCode::Char('l') => C::Scene(SceneKey::Log),
                KeyCode::Char('m') => C::Scene(SceneKey::Method),
                KeyCode::Char('v') => C::Scene(SceneKey::NextModel),
                KeyCode::Char('+' | '=') => C::Scene(SceneKey::Faster),
                KeyCode::Char('-' | '_') => C::Scene(SceneKey::Slower),
                _ => return None,
            },
        })
    }
}

impl Screen for Learn {
    type Command = Command;

    fn command(&self, event: &Event) -> Option<Command> {
        self.command_for(event)
    }

    fn apply(&mut self, command: Command) {
        Learn::apply(self, command);
    }

    fn advance(&mut self, elapsed: Duration) {
        Learn::advance(self, elapsed);
    }

    fn draw(&self, frame: &mut Frame) {
        super::view::draw(frame, self);
    }

    fn should_quit(&self) -> bool {
        self.quit
    }
}

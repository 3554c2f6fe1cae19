//! Terminal events become `spintop learn`'s [`Command`]s, and the hooks of
//! the terminal loop ([`crate::term::session`]). The reading keys are
//! `less`'s: space f b d u (and Ctrl-F B D U) j k g G / ? n N (`?` and
//! Ctrl-R search backward), h or F1 for the help, Backspace or Alt-← back
//! where a link, a search or the contents came from, q quits from the
//! reading view and closes any overlay; Esc never quits; Ctrl-Z suspends
//! (the loop's own). A paste is text for the search prompt, never keys.

use super::scene::SceneKey;
use super::{Command, Learn, Mode};
use crate::term::session::Screen;
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
                (MouseEventKind::ScrollDown, Mode::Contents(_)) => Some(Command::ContentsMove(1)),
                (MouseEventKind::ScrollUp, Mode::Contents(_)) => Some(Command::ContentsMove(-1)),
                (MouseEventKind::ScrollDown, Mode::Help(_) | Mode::Course(_)) => {
                    Some(Command::ScrollPanel(3))
                }
                (MouseEventKind::ScrollUp, Mode::Help(_) | Mode::Course(_)) => {
                    Some(Command::ScrollPanel(-3))
                }
                _ => None,
            },
            Event::Key(key) => self.key_command(*key),
            Event::Paste(text) => Some(match self.mode {
                Mode::Search(..) => Command::SearchPaste(text.clone()),
                _ => Command::PasteIgnored,
            }),
            _ => None,
        }
    }

    /// Rows of a page in the panels and the contents.
    fn panel_page(&self) -> i64 {
        i64::from(self.size.1.saturating_sub(6).max(1))
    }

    fn key_command(&self, key: KeyEvent) -> Option<Command> {
        if key.kind == KeyEventKind::Release {
            return None;
        }
        if key.modifiers.contains(KeyModifiers::CONTROL) {
            return self.control_command(key.code);
        }
        // On the "please enlarge" screen only quit is taken.
        if self.too_small() {
            return matches!(key.code, KeyCode::Char('q')).then_some(Command::Quit);
        }
        use Command as C;
        let page = self.panel_page();
        Some(match &self.mode {
            Mode::Search(..) => match key.code {
                KeyCode::Enter => C::SearchCommit,
                KeyCode::Esc => C::Close,
                KeyCode::Backspace => C::SearchBackspace,
                KeyCode::Char(c) => C::SearchInput(c),
                _ => return None,
            },
            // q closes an overlay or panel, as it closes `less`'s help.
            Mode::Help(_) | Mode::Course(_) => match key.code {
                KeyCode::Char('h') if matches!(self.mode, Mode::Course(_)) => C::Hint,
                KeyCode::Down | KeyCode::Char('j') => C::ScrollPanel(1),
                KeyCode::Up | KeyCode::Char('k') => C::ScrollPanel(-1),
                KeyCode::PageDown | KeyCode::Char(' ' | 'f' | 'd') => C::ScrollPanel(page),
                KeyCode::PageUp | KeyCode::Char('b' | 'u') => C::ScrollPanel(-page),
                KeyCode::Home | KeyCode::Char('g') => C::ScrollPanel(i64::MIN / 2),
                KeyCode::End | KeyCode::Char('G') => C::ScrollPanel(i64::MAX / 2),
                // Any other key closes the panel; Esc never quits.
                _ => C::Close,
            },
            Mode::Contents(_) => match key.code {
                KeyCode::Up | KeyCode::Char('k') => C::ContentsMove(-1),
                KeyCode::Down | KeyCode::Char('j') => C::ContentsMove(1),
                KeyCode::PageUp | KeyCode::Char('b') => C::ContentsMove(-page),
                KeyCode::PageDown | KeyCode::Char(' ' | 'f') => C::ContentsMove(page),
                KeyCode::Home | KeyCode::Char('g') => C::ContentsMove(i64::MIN / 2),
                KeyCode::End | KeyCode::Char('G') => C::ContentsMove(i64::MAX / 2),
                KeyCode::Char(c) if c.is_ascii_digit() => C::ContentsDigit(c),
                KeyCode::Enter => C::ContentsOpen,
                _ => C::Close,
            },
            // Alt-←: a browser's back (← alone is the previous chapter).
            Mode::Read | Mode::Scene
                if key.code == KeyCode::Left && key.modifiers.contains(KeyModifiers::ALT) =>
            {
                C::Back
            }
            Mode::Read | Mode::Scene => return self.reading_command(key.code),
        })
    }

    /// Ctrl with a key: the `less` pages, the backward search, quit.
    fn control_command(&self, code: KeyCode) -> Option<Command> {
        let reading = matches!(self.mode, Mode::Read | Mode::Scene) && !self.too_small();
        match code {
            KeyCode::Char('c' | 'C') => Some(Command::Quit),
            KeyCode::Char('f' | 'F') if reading => Some(Command::PageDown),
            KeyCode::Char('b' | 'B') if reading => Some(Command::PageUp),
            KeyCode::Char('d' | 'D') if reading => Some(Command::HalfDown),
            KeyCode::Char('u' | 'U') if reading => Some(Command::HalfUp),
            // In the search prompt Ctrl-U clears the field, as in the live
            // view's editor.
            KeyCode::Char('u' | 'U') if matches!(self.mode, Mode::Search(..)) => {
                Some(Command::SearchClear)
            }
            KeyCode::Char('r' | 'R') if reading => Some(Command::SearchBackStart),
            // less's lines forward and back, and its other page down.
            KeyCode::Char('e' | 'E' | 'n' | 'N' | 'j' | 'J') if reading => Some(Command::Scroll(1)),
            KeyCode::Char('y' | 'Y' | 'p' | 'P' | 'k' | 'K') if reading => {
                Some(Command::Scroll(-1))
            }
            KeyCode::Char('v' | 'V') if reading => Some(Command::PageDown),
            _ => None,
        }
    }

    fn reading_command(&self, code: KeyCode) -> Option<Command> {
        use Command as C;
        Some(match code {
            KeyCode::Char('q' | 'Q') => C::Quit,
            KeyCode::Esc => C::Close,
            KeyCode::Tab => C::NextLink,
            // less's other names for a line, a page, the top and the end.
            KeyCode::Char('e') => C::Scroll(1),
            KeyCode::Char('y') => C::Scroll(-1),
            KeyCode::Char('z') => C::PageDown,
            KeyCode::Char('<') => C::Top,
            KeyCode::Char('>') => C::End,
            KeyCode::BackTab => C::PreviousLink,
            KeyCode::Enter => C::FollowLink,
            KeyCode::Backspace => C::Back,
            KeyCode::Char('s') => C::ToggleScene,
            KeyCode::Char('w') => C::ToggleSide,
            KeyCode::Char('M') => C::ToggleMouse,
            KeyCode::Char('h') | KeyCode::F(1) => C::Help,
            KeyCode::Char('c') => C::Contents,
            KeyCode::Char('a') => C::Course,
            KeyCode::Down | KeyCode::Char('j') => C::Scroll(1),
            KeyCode::Up | KeyCode::Char('k') => C::Scroll(-1),
            KeyCode::PageDown | KeyCode::Char(' ' | 'f') => C::PageDown,
            KeyCode::PageUp | KeyCode::Char('b') => C::PageUp,
            KeyCode::Char('d') => C::HalfDown,
            KeyCode::Char('u') => C::HalfUp,
            KeyCode::Home | KeyCode::Char('g') => C::Top,
            KeyCode::End | KeyCode::Char('G') => C::End,
            KeyCode::Right => C::NextChapter,
            KeyCode::Left => C::PreviousChapter,
            KeyCode::Char('x') => C::Experiment,
            KeyCode::Char('o') => C::ToggleFolds,
            KeyCode::Char('/') => C::SearchStart,
            KeyCode::Char('?') => C::SearchBackStart,
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

    fn announce(&mut self, command: &Command) -> bool {
        self.announce_search(command)
    }

    fn wants_mouse(&self) -> bool {
        self.mouse
    }
}

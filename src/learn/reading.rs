//! The reader's commands, as `less` has them and a book needs: moving
//! through the text, the chapters and the contents, the links, the panels
//! and the scene's place on the screen. Each is one method of [`Learn`]
//! that [`Learn::apply`] calls.

use super::book::{self, Place};
use super::experiment::Experiment;
use super::scene::{Spec, Stage};
use super::{Learn, Mode};

/// How many places Backspace can go back through.
const BACK_DEPTH: usize = 100;

impl Learn {
    pub(super) fn scroll_by(&mut self, n: i64) {
        self.scroll = self.scroll.saturating_add_signed(n as isize);
        self.clamp_scroll();
        self.keep_link_on_page();
    }

    /// The chapter `step` away (→: 1, ←: −1).
    pub(super) fn next_chapter(&mut self, step: isize) {
        match self.current.checked_add_signed(step) {
            Some(i) if i < self.chapters.len() => self.go(i),
            _ if step > 0 => self.inform("this is the last chapter"),
            _ => self.inform("this is the first chapter"),
        }
    }

    pub(super) fn open_contents(&mut self) {
        let at = self
            .contents
            .iter()
            .position(|e| e.chapter == self.current)
            .unwrap_or(0);
        self.typed.clear();
        self.mode = Mode::Contents(at);
    }

    /// ↑ ↓ PgUp PgDn Home End in the contents.
    pub(super) fn move_in_contents(&mut self, n: i64) {
        if let Mode::Contents(sel) = self.mode {
            let last = self.contents.len().saturating_sub(1);
            self.mode = Mode::Contents(sel.saturating_add_signed(n as isize).min(last));
            self.typed.clear();
        }
    }

    /// A digit typed in the contents: the highlight goes to the chapter of
    /// the number typed so far (Enter opens it).
    pub(super) fn contents_digit(&mut self, c: char) {
        if !matches!(self.mode, Mode::Contents(_)) {
            return;
        }
        if self.typed.len() >= 3 {
            self.typed.clear();
        }
        self.typed.push(c);
        let chapter = self
            .typed
            .parse::<usize>()
            .ok()
            .filter(|n| (1..=self.chapters.len()).contains(n));
        match chapter.and_then(|n| {
            self.contents
                .iter()
                .position(|e| e.chapter == n - 1 && e.heading.is_none())
        }) {
            Some(at) => {
                self.mode = Mode::Contents(at);
                self.inform(format!(
                    "chapter {}: Enter opens it, more digits change it",
                    self.typed
                ));
            }
            None => {
                let typed = std::mem::take(&mut self.typed);
                self.refuse(format!(
                    "there is no chapter {typed}: the chapters are 1 to {}",
                    self.chapters.len()
                ));
            }
        }
    }

    /// Enter in the contents: the chapter, at the heading when it is one.
    pub(super) fn open_entry(&mut self) {
        let Mode::Contents(sel) = self.mode else {
            return;
        };
        self.mode = Mode::Read;
        self.typed.clear();
        let entry = self.contents[sel].clone();
        self.mark_place();
        if entry.chapter != self.current {
            self.go(entry.chapter);
        }
        if let Some((_, text)) = entry.heading {
            self.scroll_to_heading(&text);
        }
    }

    fn scroll_to_heading(&mut self, text: &str) -> bool {
        let line = self
            .rendered
            .headings
            .iter()
            .find(|(_, _, h)| h == text || book::slug(h) == text)
            .map(|(line, ..)| *line)
            .or_else(|| {
                // Or an anchor written as HTML: `<a id="jackson">`.
                self.rendered
                    .anchors
                    .iter()
                    .find(|(_, id)| id == text)
                    .map(|(line, _)| *line)
            });
        if let Some(line) = line {
            self.scroll = line;
            self.clamp_scroll();
        }
        line.is_some()
    }

    /// The help's and the course panel's scrolling.
    pub(super) fn scroll_panel(&mut self, n: i64) {
        let max = self.panel_max_scroll();
        match &mut self.mode {
            // From where the panel is drawn: its content may have shrunk
            // since (a fixed assignment), and the first PgUp must move it.
            Mode::Help(s) | Mode::Course(s) => {
                *s = (*s).min(max).saturating_add_signed(n as isize).min(max)
            }
            _ => {}
        }
    }

    fn panel_max_scroll(&self) -> usize {
        let (lines, width) = match self.mode {
            Mode::Help(_) => (super::view::help_lines(self), super::view::HELP_WIDTH),
            Mode::Course(_) => (
                super::view::course_lines(self, self.size.0),
                super::view::COURSE_WIDTH,
            ),
            _ => return 0,
        };
        crate::term::popup::max_scroll(self.size, width, &lines)
    }

    /// Esc: closes a panel; in the text, clears a search, a link's focus.
    pub(super) fn close(&mut self) {
        if self.mode == Mode::Read {
            if self.search.take().is_some() {
                self.inform("search cleared");
            } else if self.link.take().is_some() {
                self.inform("link left");
            } else {
                self.inform("q quits");
            }
        }
        self.typed.clear();
        self.mode = Mode::Read;
    }

    /// s: the scene full screen, or back to the text.
    pub(super) fn toggle_scene(&mut self) {
        if self.mode == Mode::Scene {
            self.mode = Mode::Read;
        } else if matches!(self.stage, Stage::None) {
            self.inform(self.scene_info.describe());
        } else {
            self.mode = Mode::Scene;
        }
        self.resize_stage();
    }

    /// w: the scene beside the text hidden, the text the whole width, or
    /// the scene back.
    pub(super) fn toggle_side(&mut self) {
        if matches!(self.stage, Stage::None) {
            self.inform(self.scene_info.describe());
            return;
        }
        self.side_hidden = !self.side_hidden;
        self.resize_stage();
        self.render();
        self.inform(if self.side_hidden {
            "the text takes the whole width; w brings the scene back, s shows it full screen"
        } else {
            "the scene is beside the text; w hides it"
        });
    }

    pub(super) fn toggle_folds(&mut self) {
        self.unfolded = !self.unfolded;
        self.render();
        self.inform(if self.unfolded {
            "library source shown whole; o folds it again"
        } else {
            "library source folded to one line each; o shows it"
        });
    }

    /// M: the mouse wheel captured, or the mouse left to the terminal.
    pub(super) fn toggle_mouse(&mut self) {
        self.mouse = !self.mouse;
        self.inform(if self.mouse {
            "the mouse wheel scrolls; to select text hold Shift, or press M to free the mouse"
        } else {
            "the mouse is the terminal's: drag to select text; M lets the wheel scroll here"
        });
    }

    /// The links whose first part is on the page now, by index.
    fn links_on_page(&self) -> Vec<usize> {
        let end = self.scroll + self.page();
        (0..self.rendered.links.len())
            .filter(|&i| {
                self.rendered.links[i]
                    .parts
                    .first()
                    .is_some_and(|(line, _)| (self.scroll..end).contains(line))
            })
            .collect()
    }

    /// A link scrolled off the page leaves the focus.
    fn keep_link_on_page(&mut self) {
        if let Some(i) = self.link
            && !self.links_on_page().contains(&i)
        {
            self.link = None;
        }
    }

    /// Tab (Shift-Tab): the next (previous) link in focus, as a browser
    /// moves it: from the one in focus, or from the page's top (bottom);
    /// a link below (above) the page is scrolled to.
    pub(super) fn focus_link(&mut self, forward: bool) {
        let links = &self.rendered.links;
        let line_of = |i: usize| links[i].parts.first().map_or(0, |(line, _)| *line);
        let end = self.scroll + self.page();
        let next = match (self.link, forward) {
            (Some(l), true) => (l + 1 < links.len()).then_some(l + 1),
            (Some(l), false) => l.checked_sub(1),
            (None, true) => (0..links.len()).find(|&i| line_of(i) >= self.scroll),
            (None, false) => (0..links.len()).rev().find(|&i| line_of(i) < end),
        };
        let Some(next) = next else {
            self.inform(match (links.is_empty(), forward) {
                (true, _) => "no link in this chapter",
                (false, true) => "no link further down in this chapter (g goes to the top)",
                (false, false) => "no link further up in this chapter",
            });
            return;
        };
        let line = line_of(next);
        let target = links[next].target.clone();
        self.link = Some(next);
        if !(self.scroll..end).contains(&line) {
            self.scroll = line.saturating_sub(self.page() / 3);
            self.clamp_scroll();
        }
        self.inform(format!("link: {target} (Enter follows it, Esc leaves it)"));
    }

    /// Enter on a link: a chapter of the book (at its heading), a heading
    /// of this chapter, or an address outside, which is shown to copy.
    pub(super) fn follow_link(&mut self) {
        let Some(target) = self
            .link
            .and_then(|i| self.rendered.links.get(i))
            .map(|l| l.target.clone())
        else {
            self.inform("Tab puts a link in focus; Enter follows it");
            return;
        };
        if target.contains("://") || target.starts_with("mailto:") {
            self.inform(format!(
                "{target} is outside the book: open it in a browser (the terminal cannot)"
            ));
            return;
        }
        let (file, anchor) = target.split_once('#').unwrap_or((target.as_str(), ""));
        let file = file.trim_start_matches("./");
        let chapter = match file {
            "" => self.current,
            _ => match self.chapters.iter().position(|c| c.file == file) {
                Some(i) => i,
                None => {
                    self.refuse(format!("{file} is not a chapter of this book"));
                    return;
                }
            },
        };
        self.mark_place();
        if chapter != self.current {
            self.go(chapter);
        }
        let title = self.chapters[self.current].title.clone();
        if anchor.is_empty() || self.scroll_to_heading(anchor) {
            self.inform(format!(
                "followed the link to {title}; Backspace comes back"
            ));
        } else {
            self.inform(format!(
                "followed the link to {title} (no heading or anchor “{anchor}” in it)"
            ));
        }
    }

    /// Keeps the place the reader is about to leave (a link followed, the
    /// contents opened, a search gone to another chapter), for Backspace.
    pub(super) fn mark_place(&mut self) {
        let place = Place {
            chapter: self.current,
            line: self.scroll,
            total: self.rendered.lines.len().max(1),
            link: self.link,
        };
        if self.back.last() != Some(&place) {
            if self.back.len() == BACK_DEPTH {
                self.back.remove(0);
            }
            self.back.push(place);
        }
    }

    /// Backspace or Alt-←: back to the last place a link or the contents
    /// left, the link followed in focus again.
    pub(super) fn go_back(&mut self) {
        let Some(place) = self.back.pop() else {
            self.inform(
                "nothing to go back to: Backspace returns after a link, the contents or a search took you to another chapter",
            );
            return;
        };
        if place.chapter != self.current {
            self.go(place.chapter);
        }
        self.scroll = place.line * self.rendered.lines.len().max(1) / place.total.max(1);
        self.clamp_scroll();
        self.link = place.link.filter(|i| self.links_on_page().contains(i));
        let title = &self.chapters[self.current].title;
        let more = match self.back.len() {
            0 => String::new(),
            n => format!("; Backspace again goes {n} further back"),
        };
        self.inform(format!("back in {title}{more}"));
    }

    /// x: the chapter's next experiment on the scene (from the chapter's own
    /// values), the text scrolled to it.
    pub(super) fn next_experiment(&mut self) {
        let experiments = &self.rendered.experiments;
        if experiments.is_empty() {
            let why = match self.scene_info.spec {
                Spec::None => format!(
                    "this chapter has no experiments ({})",
                    self.scene_info.describe()
                ),
                _ => {
                    "this chapter has no experiments; its scene runs with the chapter's own values"
                        .into()
                }
            };
            self.refuse(why);
            return;
        }
        let k = self.next_experiment % experiments.len();
        let (line, text) = experiments[k].clone();
        let n = experiments.len();
        self.next_experiment = k + 1;
        self.scroll = line.saturating_sub(2);
        self.clamp_scroll();
        let Spec::Top {
            settings: base,
            log_time,
            ..
        } = &self.scene_info.spec
        else {
            self.refuse(format!(
                "experiment `{text}` is for the live view, and this chapter's scene is not one"
            ));
            return;
        };
        let (base, log_time) = (*base, *log_time);
        let result = Experiment::parse(&text)
            .and_then(|e| Ok((e.apply(&base)?, e.log_time)))
            .map_err(super::scene::SceneError::from)
            .and_then(|(settings, log)| {
                let spec = Spec::Top {
                    settings,
                    columns: Vec::new(),
                    log_time: log.unwrap_or(log_time),
                };
                Stage::start(&spec, self.background)
            });
        let shown = self.panes().scene.is_some();
        match result {
            Ok(stage) => {
                self.stage = stage;
                self.resize_stage();
                let caption = text
                    .split_once('|')
                    .map_or(text.as_str(), |(s, _)| s)
                    .trim();
                // The key first: the settings may be cut at 80 columns.
                self.inform(format!(
                    "experiment {} of {n} applied{}: {caption}",
                    k + 1,
                    if shown { "" } else { " (s shows the scene)" }
                ));
            }
            Err(e) => self.refuse(format!("experiment {} of {n} refused: {e}", k + 1)),
        }
    }
}

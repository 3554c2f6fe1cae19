//! The search commands of [`Learn`]: `/` and Ctrl-R typed, Enter, `n` and
//! `N`, each from where the reader is, across the book (the search's state
//! is [`super::search`]'s).

use super::search::{LONGEST, Search, find};
use super::{Command, Learn, Mode};

impl Learn {
    /// Before a search (Enter, n, N): "searching…" on the status line, to
    /// be drawn before the search runs (across the book it may take a
    /// moment). True when there is a search to announce.
    pub fn announce_search(&mut self, command: &Command) -> bool {
        let query = match (command, &self.mode, &self.search) {
            (Command::SearchCommit, Mode::Search(q, _), _) if !q.trim().is_empty() => q.clone(),
            (Command::SearchCommit, Mode::Search(..), Some(s))
            | (Command::SearchNext | Command::SearchPrevious, Mode::Read, Some(s)) => {
                s.query.clone()
            }
            _ => return false,
        };
        self.searching = Some(format!("searching for “{query}”…"));
        true
    }

    /// A character typed into the search (`None`: Backspace).
    pub(super) fn search_input(&mut self, c: Option<char>) {
        if let Mode::Search(q, _) = &mut self.mode {
            match c {
                Some(c) if q.chars().count() < LONGEST => q.push(c),
                Some(_) => {}
                None => {
                    q.pop();
                }
            }
        }
    }

    /// Enter: searches for what was typed, from where the reader is; an
    /// empty search repeats the last, as in `less`.
    pub(super) fn search_commit(&mut self) {
        let Mode::Search(q, forward) = std::mem::replace(&mut self.mode, Mode::Read) else {
            return;
        };
        if q.trim().is_empty() {
            match &mut self.search {
                Some(s) => {
                    s.forward = forward;
                    self.seek(forward, false);
                }
                None => self.inform("type a word to search for"),
            }
            return;
        }
        self.search = Some(Search {
            matches: find(&self.rendered, &q),
            query: q,
            forward,
            at: None,
        });
        // A word only in folded library source: show the source whole (as
        // o does) rather than miss it.
        let mut unfolded_now = false;
        if self.search.as_ref().is_some_and(|s| s.matches.is_empty()) && !self.unfolded {
            self.unfolded = true;
            self.render();
            unfolded_now = self.search.as_ref().is_some_and(|s| !s.matches.is_empty());
            if !unfolded_now {
                self.unfolded = false;
                self.render();
            }
        }
        self.seek(forward, true);
        if unfolded_now && let Some((text, _)) = &mut self.message {
            text.push_str(", in library source, now shown whole (o folds it)");
        }
    }

    /// n (`same` true) or N: the next match in the search's direction, or
    /// the other way.
    pub(super) fn search_again(&mut self, same: bool) {
        let Some(s) = &self.search else {
            self.inform("/ searches forward, Ctrl-R backward; then n and N go on and back");
            return;
        };
        let forward = s.forward == same;
        self.seek(forward, false);
    }

    /// The match to show in this chapter going `forward` or back: from the
    /// match shown when it is on the page, else from the page (`fresh`: a
    /// new search, which may find the top line's own match).
    fn match_here(&self, forward: bool, fresh: bool) -> Option<usize> {
        let s = self.search.as_ref()?;
        let page = self.scroll..self.scroll + self.page();
        let current =
            s.at.and_then(|k| s.matches.get(k).map(|m| (k, m.line())))
                .filter(|(_, line)| page.contains(line));
        let m = &s.matches;
        match (current, forward) {
            (Some((k, _)), true) => (k + 1 < m.len()).then_some(k + 1),
            (Some((k, _)), false) => k.checked_sub(1),
            (None, true) => {
                let top = if fresh { self.scroll } else { self.scroll + 1 };
                m.iter().position(|m| m.line() >= top)
            }
            (None, false) => m.iter().rposition(|m| m.line() < page.end),
        }
    }

    /// Shows match `k` of this chapter a third of the way down the page, as
    /// less puts it, and says which it is (`note`: where it was found).
    fn show_match(&mut self, k: usize, note: &str) {
        let Some(s) = &mut self.search else { return };
        s.at = Some(k);
        let (line, n, query) = (s.matches[k].line(), s.matches.len(), s.query.clone());
        self.scroll = line.saturating_sub(self.page() / 3);
        self.clamp_scroll();
        self.inform(format!("“{query}”: match {} of {n}{note}", k + 1));
    }

    /// Goes to the next match `forward` or back: in this chapter, else in
    /// the next chapters (or the previous) round the book.
    fn seek(&mut self, forward: bool, fresh: bool) {
        if let Some(k) = self.match_here(forward, fresh) {
            self.show_match(k, "");
            return;
        }
        let Some(query) = self.search.as_ref().map(|s| s.query.clone()) else {
            return;
        };
        let n = self.chapters.len();
        let here = self.current;
        for step in 1..=n {
            let j = if forward {
                (here + step) % n
            } else {
                (here + n - step) % n
            };
            let wrapped = if forward { j <= here } else { j >= here };
            let source = || {
                super::search::chapter_source(&self.book.join(&self.chapters[j].file), &self.book)
            };
            if j != here && !self.texts.holds(j, source, self.unfolded, &query) {
                continue;
            }
            if j != here {
                self.mark_place();
                self.go(j);
            }
            let Some(s) = &mut self.search else { return };
            s.at = None;
            if s.matches.is_empty() {
                continue;
            }
            let k = if forward { 0 } else { s.matches.len() - 1 };
            let title = &self.chapters[j].title;
            let note = match (j == here, wrapped) {
                (true, _) => {
                    " in this chapter, from its other end (no other chapter has it)".to_string()
                }
                (false, true) => format!(
                    " in {title} (chapter {} of {n}; round the book from its {})",
                    j + 1,
                    if forward { "start" } else { "end" }
                ),
                (false, false) => format!(" in {title} (chapter {} of {n})", j + 1),
            };
            self.show_match(k, &note);
            return;
        }
        self.refuse(format!("“{query}” is nowhere in the book"));
    }
}

//! `spintop learn`: the book's chapters in the terminal, each beside its own
//! scene, read as easily as in `less`, with the course graded beside it.
//!
//! The text is the book itself: `book/src/SUMMARY.md` gives the chapters and
//! their order, and each chapter's Markdown is read from `book/src` at run
//! time (one source, no copies) and rendered by [`markdown`], with every
//! equation turned into Unicode by [`tex`], the paper's Figures 1 and 2
//! drawn in place by [`figures`] and every other picture of the book by
//! [`diagrams`]. The scene is the chapter's own ([`scene::Scene::of`]): the
//! live models ([`crate::live`]) for the chapters about the top; the charge
//! in a field for Section 2; the shell model for the appendix. A chapter's
//! experiments ([`experiment`]) are inline code `` `spintop: key=value …` ``
//! in its Markdown; `x` applies the next one to the scene.
//!
//! The shape is the live view's: [`Learn`] is the state, keys become a
//! [`Command`] ([`event`]), [`Learn::apply`] is the one place the state
//! changes (its commands are handled in [`reading`], [`seek`] and
//! [`grade`], which no other module imports), and [`view`] draws it
//! without changing anything. The reader's place is kept in a file as it
//! moves ([`progress`]).

pub mod book;
pub mod course;
pub mod diagrams;
pub mod event;
pub mod experiment;
pub mod figures;
pub mod grade;
pub mod markdown;
pub mod panes;
pub mod progress;
pub mod reading;
pub mod scene;
pub mod search;
pub mod seek;
pub mod tex;
pub mod view;

pub use book::{Chapter, Entry, chapters, find_chapter, headings};
pub use experiment::{Experiment, ExperimentError};
pub use panes::{MIN_SIZE, Panes, SIDE_BY_SIDE, panes, text_inner};
pub use progress::Progress;
pub use search::Search;

use scene::{SceneError, SceneKey, Stage};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// Why the book could not be opened or a chapter read.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LearnError {
    /// A file of the book could not be read.
    #[error("cannot read {path}: {why}")]
    Read {
        /// The file.
        path: String,
        /// The system's reason.
        why: String,
    },
    /// `SUMMARY.md` names no chapter.
    #[error("{0} lists no chapters")]
    NoChapters(String),
    /// `--chapter` named none.
    #[error(
        "--chapter {wanted}: no such chapter; use the chapter's number as the header shows it (1 to {count}), a section of the paper ({sections}), a file name such as {example}, or words of its title"
    )]
    NoSuchChapter {
        /// What was asked for.
        wanted: String,
        /// The paper's sections.
        sections: String,
        /// How many chapters there are.
        count: usize,
        /// A file name to show.
        example: String,
    },
    /// `--chapter` named words more than one chapter's title holds.
    #[error(
        "--chapter {wanted}: {count} chapters' titles hold it: {candidates}; give the chapter's number or more of its title"
    )]
    ManyChapters {
        /// What was asked for.
        wanted: String,
        /// How many chapters hold it.
        count: usize,
        /// Each: its number and title.
        candidates: String,
    },
    /// A chapter's scene could not start.
    #[error(transparent)]
    Scene(#[from] SceneError),
}

/// Why `--chapter wanted` opens none: the chapters it could mean, or the
/// ways to name one.
fn no_chapter(chapters: &[Chapter], wanted: &str) -> LearnError {
    let many = book::candidates(chapters, wanted);
    if !many.is_empty() {
        return LearnError::ManyChapters {
            wanted: wanted.to_string(),
            count: many.len(),
            candidates: many.join(", "),
        };
    }
    LearnError::NoSuchChapter {
        wanted: wanted.to_string(),
        sections: book::section_names(chapters),
        count: chapters.len(),
        example: chapters[0].file.trim_end_matches(".md").to_string(),
    }
}

fn read(path: &Path) -> Result<String, LearnError> {
    std::fs::read_to_string(path).map_err(|e| LearnError::Read {
        path: path.display().to_string(),
        why: e.to_string(),
    })
}

/// What the keys do now.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Mode {
    /// Reading, scene beside the text (or text alone on a narrow screen).
    Read,
    /// The scene full screen.
    Scene,
    /// The contents: chapters and their headings, one highlighted.
    Contents(usize),
    /// The help overlay, scrolled to this row.
    Help(usize),
    /// The course: every assignment with its state, scrolled to this row.
    Course(usize),
    /// Typing a word to search for: forward (`/`) or backward (Ctrl-R).
    Search(String, bool),
}

/// Everything a key (or the mouse wheel, or a resize) asks of `spintop learn`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Command {
    /// `q` or Ctrl-C.
    Quit,
    /// The terminal's size (columns, rows).
    Resize(u16, u16),
    /// Scroll by this many lines (↓ j: 1, ↑ k: −1, the wheel: ±3).
    Scroll(i64),
    /// Space, PgDn, f, Ctrl-F: a page down.
    PageDown,
    /// b, PgUp, Ctrl-B: a page up.
    PageUp,
    /// d, Ctrl-D: half a page down.
    HalfDown,
    /// u, Ctrl-U: half a page up.
    HalfUp,
    /// g, Home.
    Top,
    /// G, End.
    End,
    /// →: the next chapter.
    NextChapter,
    /// ←: the previous chapter.
    PreviousChapter,
    /// c: the contents.
    Contents,
    /// ↑ ↓ PgUp PgDn Home End in the contents: move the highlight.
    ContentsMove(i64),
    /// A digit typed in the contents: the chapter of that number.
    ContentsDigit(char),
    /// Enter in the contents: open the chapter or heading.
    ContentsOpen,
    /// h or F1: the help.
    Help,
    /// a: the course panel.
    Course,
    /// ↑ ↓ j k PgUp PgDn in the help or the course panel: scroll it.
    ScrollPanel(i64),
    /// h in the course panel: the next hint rung.
    Hint,
    /// Esc, or any key that closes an overlay: back to reading.
    Close,
    /// x: the next experiment.
    Experiment,
    /// s: the scene full screen, or back.
    ToggleScene,
    /// w: the scene beside the text hidden (the text wide), or shown.
    ToggleSide,
    /// o: library source unfolded, or folded back to one line.
    ToggleFolds,
    /// M: the mouse wheel captured, or the mouse left to the terminal (to
    /// select text).
    ToggleMouse,
    /// /: start typing a search forward (an empty one repeats the last).
    SearchStart,
    /// ? or Ctrl-R: start typing a search backward.
    SearchBackStart,
    /// A character of the search.
    SearchInput(char),
    /// Text pasted into the search (its line breaks left out).
    SearchPaste(String),
    /// Text pasted outside the search prompt: ignored, with a note.
    PasteIgnored,
    /// Backspace in the search.
    SearchBackspace,
    /// Ctrl-U in the search: clears what was typed (as in the live view's
    /// editor).
    SearchClear,
    /// Enter: search.
    SearchCommit,
    /// n: the next match, in the search's direction, from where the reader is.
    SearchNext,
    /// N: the match the other way.
    SearchPrevious,
    /// Tab: the next link on the page.
    NextLink,
    /// Shift-Tab: the previous link on the page.
    PreviousLink,
    /// Enter: follow the link in focus.
    FollowLink,
    /// Backspace or Alt-←: back to where the reader was before a link, the
    /// contents or a search took them to another place, as a browser's back.
    Back,
    /// A key for the scene.
    Scene(SceneKey),
}

/// The state of `spintop learn`.
pub struct Learn {
    book: PathBuf,
    chapters: Vec<Chapter>,
    contents: Vec<Entry>,
    current: usize,
    source: String,
    rendered: markdown::Rendered,
    size: (u16, u16),
    scroll: usize,
    /// Where each chapter was left: (first line shown, lines at the time).
    positions: Vec<Option<(usize, usize)>>,
    next_experiment: usize,
    stage: Stage,
    scene_info: scene::Scene,
    background: bool,
    unfolded: bool,
    side_hidden: bool,
    mouse: bool,
    /// No colour (`NO_COLOR`): see [`Learn::plain`].
    plain: bool,
    mode: Mode,
    search: Option<Search>,
    /// The plain text of every chapter at the width last searched, for a
    /// search across the book.
    texts: search::Texts,
    /// "searching…", shown from before a search runs until a command ends it.
    searching: Option<String>,
    /// The link in focus (Tab), by its index in the rendered chapter.
    link: Option<usize>,
    /// The places a link or the contents left, the last on top.
    back: Vec<book::Place>,
    /// Digits typed in the contents.
    typed: String,
    message: Option<(String, bool)>,
    visited: Vec<bool>,
    quit: bool,
    /// The course beside the book.
    course: course::Panel,
    /// The progress file, kept as the reader moves.
    keeper: Option<progress::Keeper>,
}

impl Learn {
    /// Opens the book at `book` (the `book/src` folder) on chapter `start`,
    /// its scenes stepped on this thread whenever asked (the tests' way).
    pub fn open(book: &Path, start: Option<&str>) -> Result<Self, LearnError> {
        Self::open_with(book, start, false)
    }

    /// [`Learn::open`] with every scene's models and computations on
    /// threads of their own (the terminal's way: no key waits on them).
    pub fn open_in_background(book: &Path, start: Option<&str>) -> Result<Self, LearnError> {
        figures::compute_in_background();
        Self::open_with(book, start, true)
    }

    fn open_with(book: &Path, start: Option<&str>, background: bool) -> Result<Self, LearnError> {
        let summary_path = book.join("SUMMARY.md");
        let chapters = chapters(&read(&summary_path)?);
        if chapters.is_empty() {
            return Err(LearnError::NoChapters(summary_path.display().to_string()));
        }
        let current = match start {
            None => 0,
            Some(w) => find_chapter(&chapters, w).ok_or_else(|| no_chapter(&chapters, w))?,
        };
        let mut contents = Vec::new();
        for (i, c) in chapters.iter().enumerate() {
            contents.push(Entry {
                chapter: i,
                heading: None,
            });
            let text = std::fs::read_to_string(book.join(&c.file)).unwrap_or_default();
            contents.extend(headings(&text).into_iter().map(|h| Entry {
                chapter: i,
                heading: Some(h),
            }));
        }
        let scene_info = chapters[current].scene();
        let n = chapters.len();
        let texts = search::Texts::warm(
            chapters.iter().map(|c| book.join(&c.file)).collect(),
            book.to_path_buf(),
        );
        let mut learn = Learn {
            book: book.to_path_buf(),
            chapters,
            contents,
            current,
            source: String::new(),
            rendered: markdown::Rendered::default(),
            size: (80, 24),
            scroll: 0,
            positions: vec![None; n],
            next_experiment: 0,
            stage: Stage::None,
            scene_info,
            background,
            unfolded: false,
            side_hidden: false,
            mouse: false,
            plain: false,
            mode: Mode::Read,
            search: None,
            texts,
            searching: None,
            link: None,
            back: Vec::new(),
            typed: String::new(),
            message: None,
            visited: vec![false; n],
            quit: false,
            course: course::Panel::default(),
            keeper: None,
        };
        learn.load(current)?;
        if let Some(note) = start.and_then(|w| book::ambiguity(&learn.chapters, w)) {
            learn.message = Some((note, false));
        }
        Ok(learn)
    }

    /// Without colour (`NO_COLOR`, the terminal's way when it is set): the
    /// figures drawn in the text tell their curves apart by glyph and their
    /// titles name the glyphs, not colours.
    pub fn plain(mut self, on: bool) -> Self {
        if self.plain != on {
            self.plain = on;
            self.render();
        }
        self
    }

    /// The chapters.
    pub fn chapters(&self) -> &[Chapter] {
        &self.chapters
    }

    /// The contents: every chapter and its headings.
    pub fn contents(&self) -> &[Entry] {
        &self.contents
    }

    /// The chapter shown.
    pub fn current(&self) -> usize {
        self.current
    }

    /// The scene running.
    pub fn stage(&self) -> &Stage {
        &self.stage
    }

    /// The chapter's scene.
    pub fn scene_info(&self) -> &scene::Scene {
        &self.scene_info
    }

    /// The scene's live-view state, when the scene is the live view's.
    pub fn scene(&self) -> Option<&crate::live::App> {
        self.stage.app()
    }

    /// The mode.
    pub fn mode(&self) -> &Mode {
        &self.mode
    }

    /// The search, if one was made.
    pub fn search(&self) -> Option<&Search> {
        self.search.as_ref()
    }

    /// The line in the status bar, and whether it is a refusal.
    pub fn message(&self) -> Option<&(String, bool)> {
        self.message.as_ref()
    }

    /// "searching…", while a search is about to run.
    pub fn searching(&self) -> Option<&str> {
        self.searching.as_deref()
    }

    /// True once quit was asked for.
    pub fn should_quit(&self) -> bool {
        self.quit
    }

    /// The chapters opened in this session (or an earlier one).
    pub fn visited(&self) -> &[bool] {
        &self.visited
    }

    /// The terminal's size.
    pub fn size(&self) -> (u16, u16) {
        self.size
    }

    /// The chapter rendered at the text's width.
    pub fn rendered(&self) -> &markdown::Rendered {
        &self.rendered
    }

    /// True when library source is shown whole (`o`), not folded.
    pub fn unfolded(&self) -> bool {
        self.unfolded
    }

    /// True while the mouse wheel is captured (`M`).
    pub fn mouse(&self) -> bool {
        self.mouse
    }

    /// The link in focus, if any (its index in [`markdown::Rendered::links`]).
    pub fn focused_link(&self) -> Option<usize> {
        self.link
    }

    /// The digits typed in the contents so far.
    pub fn typed(&self) -> &str {
        &self.typed
    }

    /// The first line of the text shown.
    pub fn scroll(&self) -> usize {
        self.scroll
    }

    /// The course beside the book.
    pub fn course_panel(&self) -> &course::Panel {
        &self.course
    }

    /// True on a terminal too small to draw in: only quit is taken.
    pub fn too_small(&self) -> bool {
        self.size.0 < MIN_SIZE.0 || self.size.1 < MIN_SIZE.1
    }

    /// The panes at the current size and mode.
    pub fn panes(&self) -> Panes {
        self.panes_in(self.size)
    }

    /// The panes of a frame of `size` in the current mode. The view draws
    /// in the frame it is given: after a resize the terminal draws a frame
    /// at its new size before the resize event reaches [`Learn::apply`].
    pub fn panes_in(&self, size: (u16, u16)) -> Panes {
        panes(
            size,
            self.mode == Mode::Scene,
            !matches!(self.stage, Stage::None) && !self.side_hidden,
        )
    }

    /// The text's width and height in lines (as in Read mode, also while
    /// the scene is full screen, so that coming back finds the same lines).
    fn text_geometry(&self) -> (u16, usize) {
        let has_scene = !matches!(self.stage, Stage::None) && !self.side_hidden;
        let panes = panes(self.size, false, has_scene);
        let inner = text_inner(panes.text.unwrap_or(panes.header));
        (inner.width, usize::from(inner.height).max(1))
    }

    fn page(&self) -> usize {
        self.text_geometry().1
    }

    /// Keeps the progress in the file at `path` as the reader moves (see
    /// [`progress::Keeper`]), starting from `read`, what it held.
    pub fn keep_progress(&mut self, path: PathBuf, read: Progress) {
        self.keeper = Some(progress::Keeper::new(path, read));
    }

    /// Writes the progress now; the failure, if the file could not be
    /// written (now or at the last try).
    pub fn save_progress(&mut self) -> Result<(), progress::NotKept> {
        let progress = self.progress();
        match self.keeper.as_mut() {
            Some(k) => k.save(&progress),
            None => Ok(()),
        }
    }

    /// Marks chapters as visited and restores where each was left
    /// (progress from an earlier session).
    pub fn restore(&mut self, progress: &Progress) {
        for (i, c) in self.chapters.iter().enumerate() {
            if progress.opened.contains(&c.file) {
                self.visited[i] = true;
            }
            if let Some(p) = progress.positions.get(&c.file) {
                self.positions[i] = Some(*p);
            }
        }
        self.restore_position();
    }

    /// The open chapter as plain text at `width` columns, as the reader
    /// draws it (the library's excerpts folded to one line, the lessons'
    /// code whole, figures and diagrams drawn, no colour): what
    /// `spintop learn --chapter X --list` prints.
    pub fn chapter_text(&self, width: u16) -> String {
        let options = markdown::Options {
            unfold: false,
            figures_later: false,
            images: Some(self.book.clone()),
            // Plain text has no colour: the figures name their glyphs.
            plain: true,
        };
        markdown::plain(&markdown::render_with(&self.source, width, &options).lines)
    }

    /// Shows `text` on the status line until the next key (what the reader
    /// should know at the start, such as which book is read).
    pub fn note(&mut self, text: impl Into<String>) {
        self.inform(text);
    }

    /// The progress of this session: the chapters opened, the one open,
    /// where each was left.
    pub fn progress(&self) -> Progress {
        let mut positions = std::collections::BTreeMap::new();
        for (i, c) in self.chapters.iter().enumerate() {
            let here = if i == self.current {
                Some((self.scroll, self.rendered.lines.len().max(1)))
            } else {
                self.positions[i]
            };
            if let Some(p) = here {
                positions.insert(c.file.clone(), p);
            }
        }
        Progress {
            opened: self
                .chapters
                .iter()
                .zip(&self.visited)
                .filter(|(_, v)| **v)
                .map(|(c, _)| c.file.clone())
                .collect(),
            last: Some(self.chapters[self.current].file.clone()),
            positions,
        }
    }

    fn remember_position(&mut self) {
        self.positions[self.current] = Some((self.scroll, self.rendered.lines.len().max(1)));
    }

    fn restore_position(&mut self) {
        self.scroll = match self.positions[self.current] {
            // At the width it was left at, the very line; else the same
            // fraction of the chapter.
            Some((line, total)) => line * self.rendered.lines.len().max(1) / total.max(1),
            None => 0,
        };
        self.clamp_scroll();
    }

    fn load(&mut self, index: usize) -> Result<(), LearnError> {
        let chapter = &self.chapters[index];
        let path = self.book.join(&chapter.file);
        let text = read(&path)?;
        let dir = path.parent().unwrap_or(&self.book).to_path_buf();
        self.source = markdown::resolve_includes(&text, &dir);
        self.current = index;
        self.visited[index] = true;
        self.next_experiment = 0;
        self.link = None;
        if let Some(s) = &mut self.search {
            s.matches.clear();
        }
        let info = chapter.scene();
        if info != self.scene_info || matches!(self.stage, Stage::None) {
            self.stage = Stage::start(&info.spec, self.background)?;
        }
        self.scene_info = info;
        self.resize_stage();
        self.render();
        self.restore_position();
        Ok(())
    }

    /// Tells the scene the size it is drawn at (its models pick what fits).
    fn resize_stage(&mut self) {
        let area = self
            .panes_in(self.size)
            .scene
            .or(panes(self.size, true, true).scene)
            .unwrap_or_default();
        self.stage.resize(area.width, area.height);
    }

    /// Render the chapter at the text's width, keeping the reader on the
    /// same place in the text.
    fn render(&mut self) {
        let fraction = if self.rendered.lines.is_empty() {
            0.0
        } else {
            self.scroll as f64 / self.rendered.lines.len() as f64
        };
        let (width, _) = self.text_geometry();
        self.rendered = markdown::render_with(
            &self.source,
            width,
            &markdown::Options {
                unfold: self.unfolded,
                figures_later: self.background,
                images: Some(self.book.clone()),
                plain: self.plain,
            },
        );
        self.scroll = (fraction * self.rendered.lines.len() as f64).round() as usize;
        self.clamp_scroll();
        self.link = None;
        if let Some(query) = self.search.as_ref().map(|s| s.query.clone()) {
            let found = search::find(&self.rendered, &query);
            if let Some(s) = &mut self.search {
                s.matches = found;
            }
        }
    }

    fn max_scroll(&self) -> usize {
        self.rendered.lines.len().saturating_sub(self.page())
    }

    fn clamp_scroll(&mut self) {
        self.scroll = self.scroll.min(self.max_scroll());
    }

    fn go(&mut self, index: usize) {
        self.remember_position();
        match self.load(index) {
            Ok(()) => self.message = None,
            Err(e) => self.message = Some((e.to_string(), true)),
        }
        self.start_probe();
    }

    fn inform(&mut self, text: impl Into<String>) {
        self.message = Some((text.into(), false));
    }

    fn refuse(&mut self, text: impl Into<String>) {
        self.message = Some((text.into(), true));
    }

    /// Apply one command: the only place the state changes (besides the
    /// clock and the grader's news).
    pub fn apply(&mut self, command: Command) {
        self.searching = None;
        if !matches!(command, Command::Resize(..) | Command::Scroll(_)) {
            self.message = None;
        }
        match command {
            Command::Quit => self.quit = true,
            Command::Resize(w, h) => {
                self.size = (w, h);
                self.resize_stage();
                self.render();
                self.scroll_panel(0);
            }
            Command::Scroll(n) => self.scroll_by(n),
            Command::PageDown => self.scroll_by(self.page().saturating_sub(2).max(1) as i64),
            Command::PageUp => self.scroll_by(-(self.page().saturating_sub(2).max(1) as i64)),
            Command::HalfDown => self.scroll_by((self.page() / 2).max(1) as i64),
            Command::HalfUp => self.scroll_by(-((self.page() / 2).max(1) as i64)),
            Command::Top => self.scroll = 0,
            Command::End => self.scroll = self.max_scroll(),
            Command::NextChapter => self.next_chapter(1),
            Command::PreviousChapter => self.next_chapter(-1),
            Command::Contents => self.open_contents(),
            Command::ContentsMove(n) => self.move_in_contents(n),
            Command::ContentsDigit(c) => self.contents_digit(c),
            Command::ContentsOpen => self.open_entry(),
            Command::Help => self.mode = Mode::Help(0),
            Command::Course => self.mode = Mode::Course(0),
            Command::ScrollPanel(n) => self.scroll_panel(n),
            Command::Hint => self.next_hint(),
            Command::Close => self.close(),
            Command::Experiment => self.next_experiment(),
            Command::ToggleScene => self.toggle_scene(),
            Command::ToggleSide => self.toggle_side(),
            Command::ToggleFolds => self.toggle_folds(),
            Command::ToggleMouse => self.toggle_mouse(),
            Command::SearchStart => self.mode = Mode::Search(String::new(), true),
            Command::SearchBackStart => self.mode = Mode::Search(String::new(), false),
            Command::SearchInput(c) => self.search_input(Some(c)),
            Command::SearchPaste(text) => {
                for c in text.chars().filter(|c| !c.is_control()) {
                    self.search_input(Some(c));
                }
            }
            Command::PasteIgnored => {
                self.inform("paste ignored: / or ? starts a search to paste into")
            }
            Command::SearchBackspace => self.search_input(None),
            Command::SearchClear => {
                if let Mode::Search(q, _) = &mut self.mode {
                    q.clear();
                }
            }
            Command::SearchCommit => self.search_commit(),
            Command::SearchNext => self.search_again(true),
            Command::SearchPrevious => self.search_again(false),
            Command::NextLink => self.focus_link(true),
            Command::PreviousLink => self.focus_link(false),
            Command::FollowLink => self.follow_link(),
            Command::Back => self.go_back(),
            Command::Scene(key) => {
                let shown = match &self.scene_info.spec {
                    scene::Spec::Top { columns, .. } => columns.clone(),
                    _ => Vec::new(),
                };
                let (text, refused) = self.stage.key(key, &shown);
                if !text.is_empty() {
                    self.message = Some((text, refused));
                }
            }
        }
    }

    /// Steps the scene by wall-clock time, takes the course grader's news,
    /// and keeps the reader's place in the progress file.
    pub fn advance(&mut self, elapsed: Duration) {
        self.stage.advance(elapsed);
        if self.rendered.figures_pending
            && [
                spintop::figure::FigureNumber::One,
                spintop::figure::FigureNumber::Two,
            ]
            .into_iter()
            .all(figures::ready)
        {
            self.render();
        }
        self.poll_course();
        let progress = self.progress();
        if let Some(failure) = self
            .keeper
            .as_mut()
            .and_then(|k| k.keep(&progress, Instant::now()))
        {
            self.refuse(failure.to_string());
        }
    }
}

/// A progress bar of `width` cells for `k` of `n`: ▰ done, ▱ to do.
pub fn progress_bar(k: usize, n: usize, width: usize) -> String {
    let done = (k * width + n / 2).checked_div(n).unwrap_or(0).min(width);
    format!("{}{}", "▰".repeat(done), "▱".repeat(width - done))
}

/// Runs `learn` in the terminal until the reader quits or a signal
/// arrives; the terminal is restored however it ends.
pub fn run(learn: &mut Learn) -> std::io::Result<crate::term::session::LoopReport> {
    crate::term::session::Session::start()?.run(learn, None)
}

//! `spintop learn`: the book's chapters in the terminal, each beside its own
//! scene, read as easily as in `less`.
//!
//! The text is the book itself: `book/src/SUMMARY.md` gives the chapters and
//! their order, and each chapter's Markdown is read from `book/src` at run
//! time (one source, no copies) and rendered by [`markdown`], with every
//! equation turned into Unicode by [`tex`] and the paper's Figures 1 and 2
//! drawn in place by [`figures`]. The scene is the chapter's own
//! ([`scene::Scene::of`]): the live view's models for the chapters about the
//! top, drawn by the live view's own column widget; the charge in a field for
//! Section 2; the shell model for the appendix. A chapter's experiments are
//! `<!-- spintop: key=value … -->` comments in its Markdown (mdBook drops
//! them); `x` applies the next one to the scene and scrolls the text to it.
//!
//! The shape is the live view's: [`Learn`] is the state, keys become a
//! [`Command`] ([`event`]), [`Learn::apply`] is the one place the state
//! changes, and [`view`] draws it without changing anything.

pub mod event;
pub mod figures;
pub mod markdown;
pub mod scene;
pub mod tex;
pub mod view;

use super::app::{Settings, Top, WARPS};
use ratatui::layout::{Constraint, Layout, Rect};
use scene::{SceneKey, Spec, Stage};
use spintop::math::Real;
use spintop::numbers::parse_number;
use spintop::sim::MethodChoice;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::Duration;

/// One chapter of `SUMMARY.md`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Chapter {
    /// The title as `SUMMARY.md` gives it.
    pub title: String,
    /// The file name under `book/src`, e.g. `section-4-2.md`.
    pub file: String,
    /// The part of the book it sits in (`Numerics`, …), if any.
    pub part: Option<String>,
}

impl Chapter {
    /// The paper's section number this chapter is about (`2`, `3`, `4.1`,
    /// `4.2`, `5`, `A`), if it is one of the paper's sections.
    pub fn section(&self) -> Option<&'static str> {
        Some(match self.file.as_str() {
            "section-2.md" => "2",
            "section-3.md" => "3",
            "section-4-1.md" => "4.1",
            "section-4-2.md" => "4.2",
            "section-5.md" => "5",
            "appendix.md" => "A",
            _ => return None,
        })
    }

    /// The chapter's scene (see [`scene::Scene::of`]).
    pub fn scene(&self) -> scene::Scene {
        scene::Scene::of(&self.file)
    }
}

/// Reads `SUMMARY.md`: the chapters in book order, with their parts.
pub fn chapters(summary: &str) -> Vec<Chapter> {
    let mut part = None;
    let mut out = Vec::new();
    for line in summary.lines() {
        let t = line.trim();
        if let Some(h) = t.strip_prefix("# ") {
            if h.trim() != "Summary" {
                part = Some(h.trim().to_string());
            }
            continue;
        }
        let Some(open) = t.find('[') else { continue };
        let Some(close) = t[open..].find("](").map(|i| open + i) else {
            continue;
        };
        let Some(end) = t[close..].find(')').map(|i| close + i) else {
            continue;
        };
        let title = t[open + 1..close].to_string();
        let file = t[close + 2..end].to_string();
        if file.ends_with(".md") {
            out.push(Chapter {
                title,
                file,
                part: part.clone(),
            });
        }
    }
    out
}

/// Finds a chapter by the paper's section number (`2`, `3`, `4.1`, `4.2`,
/// `5`, `A`) or by its file name, with or without `.md`.
pub fn find_chapter(chapters: &[Chapter], wanted: &str) -> Option<usize> {
    let w = wanted.trim();
    chapters.iter().position(|c| {
        c.section().is_some_and(|s| s.eq_ignore_ascii_case(w))
            || c.file == w
            || c.file.strip_suffix(".md") == Some(w)
    })
}

/// The headings of a chapter's Markdown (`## …` and `### …`, outside code),
/// as (level, text), for the contents.
pub fn headings(markdown: &str) -> Vec<(u8, String)> {
    let mut fence = false;
    let mut out = Vec::new();
    for line in markdown.lines() {
        let t = line.trim_start();
        if t.starts_with("```") {
            fence = !fence;
            continue;
        }
        if fence {
            continue;
        }
        for (prefix, level) in [("### ", 3), ("## ", 2)] {
            if let Some(h) = t.strip_prefix(prefix) {
                out.push((level, markdown::plain_inline(h.trim())));
                break;
            }
        }
    }
    out
}

/// One experiment, parsed from the book's `` `spintop: ratio=1.5 method=rk4` ``.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Experiment {
    /// I₃/I₁.
    pub ratio: Option<Real>,
    /// Ω₀.
    pub omega: Option<[Real; 3]>,
    /// The method.
    pub method: Option<MethodChoice>,
    /// τ per second, one of [`WARPS`].
    pub warp: Option<Real>,
    /// Log time axis.
    pub log_time: Option<bool>,
}

impl Experiment {
    /// Parses `key=value` words; unknown keys or bad values are an error (a
    /// test runs this over every experiment in the book).
    pub fn parse(text: &str) -> Result<Self, String> {
        let mut e = Experiment::default();
        let settings = text.split_once('|').map_or(text, |(s, _)| s);
        for word in settings.split_whitespace() {
            let Some((k, v)) = word.split_once('=') else {
                return Err(format!("`{word}` is not key=value"));
            };
            match k {
                "ratio" => e.ratio = Some(parse_number(v)?),
                "omega" => {
                    let parts: Result<Vec<Real>, String> = v.split(',').map(parse_number).collect();
                    let parts = parts?;
                    let [a, b, c] = parts[..] else {
                        return Err(format!("omega takes three numbers, got `{v}`"));
                    };
                    e.omega = Some([a, b, c]);
                }
                "method" => {
                    e.method = Some(MethodChoice::from_name(v).ok_or_else(|| {
                        format!(
                            "method `{v}`: use one of {}",
                            MethodChoice::NAMES.join(", ")
                        )
                    })?);
                }
                "warp" => {
                    let w = parse_number(v)?;
                    if !WARPS.contains(&w) {
                        return Err(format!("warp {w} is not one of the live view's warps"));
                    }
                    e.warp = Some(w);
                }
                "log" => {
                    e.log_time = Some(match v {
                        "on" | "true" => true,
                        "off" | "false" => false,
                        other => return Err(format!("log takes on or off, got `{other}`")),
                    })
                }
                other => {
                    return Err(format!(
                        "unknown key `{other}` (ratio, omega, method, warp, log)"
                    ));
                }
            }
        }
        Ok(e)
    }

    /// The settings this experiment makes of `base` (the chapter's own: an
    /// experiment never inherits an earlier one's changes).
    pub fn apply(&self, base: &Settings) -> Result<Settings, String> {
        let omega = self.omega.unwrap_or(base.omega0());
        let method = self.method.unwrap_or(base.method());
        let warp = self.warp.unwrap_or(base.warp());
        match base.top() {
            Top::General(top) => {
                if self.ratio.is_some() {
                    return Err("this scene is a general top: ratio does not apply".into());
                }
                Settings::general(*top, omega, method, warp)
            }
            Top::Full(top) => Settings::full(self.ratio.unwrap_or(top.ratio()), omega, warp),
            Top::Symmetric(top) => {
                Settings::new(self.ratio.unwrap_or(top.ratio()), omega, method, warp)
            }
        }
    }
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
    /// The help overlay.
    Help,
    /// The course: every assignment with its state.
    Course,
    /// Typing a word to search for.
    Search(String),
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
    /// Space, PgDn, f: a page down.
    PageDown,
    /// b, PgUp: a page up.
    PageUp,
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
    /// ↑ in the contents.
    ContentsUp,
    /// ↓ in the contents.
    ContentsDown,
    /// Enter in the contents: open the chapter or heading.
    ContentsOpen,
    /// ?: the help.
    Help,
    /// a: the course panel.
    Course,
    /// h: the next hint rung.
    Hint,
    /// Esc, or any key that closes an overlay: back to reading.
    Close,
    /// x: the next experiment.
    Experiment,
    /// Tab: the scene full screen, or back.
    ToggleScene,
    /// o: library source unfolded, or folded back to one line.
    ToggleFolds,
    /// /: start typing a search (an empty one repeats the last).
    SearchStart,
    /// A character of the search.
    SearchInput(char),
    /// Backspace in the search.
    SearchBackspace,
    /// Enter: search.
    SearchCommit,
    /// n: the next match.
    SearchNext,
    /// N: the previous match.
    SearchPrevious,
    /// A key for the scene.
    Scene(SceneKey),
}

/// A search and what it found: (line, byte range in the line's text).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Search {
    /// The word searched for.
    pub query: String,
    /// Every match, in reading order.
    pub matches: Vec<(usize, std::ops::Range<usize>)>,
    /// The match last jumped to.
    pub at: usize,
}

/// One line of the contents: a chapter, or one of its headings.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Entry {
    /// The chapter.
    pub chapter: usize,
    /// The heading (level, text), or `None` for the chapter itself.
    pub heading: Option<(u8, String)>,
}

/// Where the screen's parts are, for a terminal of one size: the apply step
/// (rendering width, page height) and the drawing use the same.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Panes {
    /// The header line.
    pub header: Rect,
    /// The text's frame, if the text is shown.
    pub text: Option<Rect>,
    /// The scene, if shown.
    pub scene: Option<Rect>,
    /// The status line.
    pub status: Rect,
    /// The keys.
    pub footer: Rect,
}

/// The smallest terminal `spintop learn` draws in.
pub const MIN_SIZE: (u16, u16) = (40, 10);

/// From this width the scene stands beside the text.
pub const SIDE_BY_SIDE: u16 = 120;

/// The panes of a `size` terminal with the scene full screen (`scene_full`)
/// or not, and whether the chapter has a scene to put beside the text.
pub fn panes(size: (u16, u16), scene_full: bool, has_scene: bool) -> Panes {
    let area = Rect::new(0, 0, size.0, size.1);
    let [header, body, status, footer] = Layout::vertical([
        Constraint::Length(1),
        Constraint::Fill(1),
        Constraint::Length(1),
        Constraint::Length(1),
    ])
    .areas(area);
    let (text, scene) = if scene_full {
        (None, Some(body))
    } else if body.width >= SIDE_BY_SIDE && has_scene {
        let [left, right] =
            Layout::horizontal([Constraint::Percentage(50), Constraint::Percentage(50)])
                .areas(body);
        (Some(left), Some(right))
    } else {
        (Some(body), None)
    };
    Panes {
        header,
        text,
        scene,
        status,
        footer,
    }
}

/// The text's lines area inside its frame (the right column is the
/// position mark).
pub fn text_inner(frame: Rect) -> Rect {
    let inner = Rect {
        x: frame.x + 1,
        y: frame.y + 1,
        width: frame.width.saturating_sub(2),
        height: frame.height.saturating_sub(2),
    };
    Rect {
        width: inner.width.saturating_sub(1).max(20),
        ..inner
    }
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
    mode: Mode,
    search: Option<Search>,
    message: Option<(String, bool)>,
    visited: Vec<bool>,
    quit: bool,
    /// The course's grader, watching the student's files, if started.
    watch: Option<spintop_course::Watch>,
    /// Why nothing is graded, when grading was turned off.
    grading_off: Option<String>,
    /// The last grading, and whether one is running.
    course: Option<spintop_course::Status>,
    grading: bool,
    course_error: Option<String>,
    /// The lessons crate being graded (where the hint rungs are kept).
    course_dir: Option<PathBuf>,
    /// The last hint rung shown (`h`).
    hint: Option<spintop_course::Hint>,
    /// The hint rungs used, when there is no course folder to keep them in.
    hints_used: spintop_course::Progress,
    /// The student's function of time being sampled (see [`Self::start_probe`]).
    probe_rx: Option<std::sync::mpsc::Receiver<ProbeReport>>,
    /// The student's function of time, sampled, to draw against the reference.
    yours: Option<ProbeReport>,
}

/// A probe's request and what it found.
pub type ProbeReport = (
    spintop_course::ProbeSpec,
    Result<spintop_course::Probed, String>,
);

impl Learn {
    /// Opens the book at `book` (the `book/src` folder) on chapter `start`,
    /// its scenes stepped on this thread whenever asked (the tests' way).
    pub fn open(book: &Path, start: Option<&str>) -> Result<Self, String> {
        Self::open_with(book, start, false)
    }

    /// [`Learn::open`] with every scene's models and computations on
    /// threads of their own (the terminal's way: no key waits on them).
    pub fn open_in_background(book: &Path, start: Option<&str>) -> Result<Self, String> {
        figures::compute_in_background();
        Self::open_with(book, start, true)
    }

    fn open_with(book: &Path, start: Option<&str>, background: bool) -> Result<Self, String> {
        let summary = std::fs::read_to_string(book.join("SUMMARY.md"))
            .map_err(|e| format!("cannot read {}: {e}", book.join("SUMMARY.md").display()))?;
        let chapters = chapters(&summary);
        if chapters.is_empty() {
            return Err(format!(
                "{} lists no chapters",
                book.join("SUMMARY.md").display()
            ));
        }
        let current = match start {
            None => 0,
            Some(w) => find_chapter(&chapters, w).ok_or_else(|| {
                let sections: Vec<&str> = chapters.iter().filter_map(Chapter::section).collect();
                format!(
                    "--chapter {w}: no such chapter; use a section ({}) or a file name such as {}",
                    sections.join(", "),
                    chapters[0].file.trim_end_matches(".md")
                )
            })?,
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
        let visited = vec![false; chapters.len()];
        let positions = vec![None; chapters.len()];
        let mut learn = Learn {
            book: book.to_path_buf(),
            chapters,
            contents,
            current,
            source: String::new(),
            rendered: markdown::Rendered::default(),
            size: (80, 24),
            scroll: 0,
            positions,
            next_experiment: 0,
            stage: Stage::None,
            scene_info,
            background,
            unfolded: false,
            mode: Mode::Read,
            search: None,
            message: None,
            visited,
            quit: false,
            watch: None,
            grading_off: None,
            course: None,
            grading: false,
            course_error: None,
            course_dir: None,
            hint: None,
            hints_used: Default::default(),
            probe_rx: None,
            yours: None,
        };
        learn.load(current)?;
        Ok(learn)
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
    pub fn scene(&self) -> Option<&super::app::App> {
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

    /// The first line of the text shown.
    pub fn scroll(&self) -> usize {
        self.scroll
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
            !matches!(self.stage, Stage::None),
        )
    }

    /// The text's width and height in lines (as in Read mode, also while
    /// the scene is full screen, so that coming back finds the same lines).
    fn text_geometry(&self) -> (u16, usize) {
        let panes = panes(self.size, false, !matches!(self.stage, Stage::None));
        let inner = text_inner(panes.text.unwrap_or(panes.header));
        (inner.width, usize::from(inner.height).max(1))
    }

    fn page(&self) -> usize {
        self.text_geometry().1
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

    /// Marks chapters as visited (progress restored from an earlier session).
    pub fn mark_visited(&mut self, files: &[String]) {
        for (i, c) in self.chapters.iter().enumerate() {
            if files.contains(&c.file) {
                self.visited[i] = true;
            }
        }
    }

    /// Says why nothing is graded in this session (`--no-grading`).
    pub fn grading_off(&mut self, why: impl Into<String>) {
        self.grading_off = Some(why.into());
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

    fn load(&mut self, index: usize) -> Result<(), String> {
        let chapter = &self.chapters[index];
        let path = self.book.join(&chapter.file);
        let text = std::fs::read_to_string(&path)
            .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
        let dir = path.parent().unwrap_or(&self.book).to_path_buf();
        self.source = markdown::resolve_includes(&text, &dir);
        self.current = index;
        self.visited[index] = true;
        self.next_experiment = 0;
        self.search = None;
        let info = chapter.scene();
        if info != self.scene_info || matches!(self.stage, Stage::None) {
            self.stage = Stage::start(&info.spec, self.background)?;
            self.stage.resize(self.size.0, self.size.1);
        }
        self.scene_info = info;
        self.render();
        self.restore_position();
        Ok(())
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
            markdown::Options {
                unfold: self.unfolded,
                figures_later: self.background,
            },
        );
        self.scroll = (fraction * self.rendered.lines.len() as f64).round() as usize;
        self.clamp_scroll();
        if let Some(query) = self.search.as_ref().map(|s| s.query.clone()) {
            self.find(&query);
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
            Err(e) => self.message = Some((e, true)),
        }
        self.start_probe();
    }

    /// Samples the student's function of time of this chapter, if it has one
    /// that the student has started (passing or failing), in the background;
    /// the scene then draws it against the reference.
    pub fn start_probe(&mut self) {
        use spintop_course::{ProbeSpec, State};
        let (Some(dir), Some(status)) = (&self.course_dir, &self.course) else {
            return;
        };
        let Some(spec) = ProbeSpec::for_chapter(&self.chapters[self.current].title) else {
            return;
        };
        let started = status.states.iter().any(|(a, st)| {
            a.function == spec.function && matches!(st, State::Passing | State::Failing(_))
        });
        if !started {
            return;
        }
        let (tx, rx) = std::sync::mpsc::channel();
        let dir = dir.clone();
        std::thread::spawn(move || {
            let _ = tx.send((spec, spintop_course::probe(&dir, &spec)));
        });
        self.probe_rx = Some(rx);
    }

    /// Takes a probe's report (from the background, or from a test).
    pub fn probe_report(&mut self, report: ProbeReport) {
        self.yours = Some(report);
    }

    /// The student's function of time of this chapter against the reference,
    /// when it has been sampled.
    pub fn yours(
        &self,
    ) -> Option<(
        &spintop_course::ProbeSpec,
        &Result<spintop_course::Probed, String>,
    )> {
        let (spec, probed) = self.yours.as_ref()?;
        let here = spintop_course::ProbeSpec::for_chapter(&self.chapters[self.current].title)?;
        (*spec == here).then_some((spec, probed))
    }

    /// Runs the chapter's next experiment on the scene (from the chapter's
    /// own values) and scrolls to it.
    fn next_experiment(&mut self) {
        let experiments = &self.rendered.experiments;
        if experiments.is_empty() {
            self.message = Some((
                match self.scene_info.spec {
                    Spec::None => format!("this chapter has no experiments ({})", self.scene_info.describe()),
                    _ => "this chapter has no experiments; its scene runs with the chapter's own values"
                        .into(),
                },
                true,
            ));
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
            self.message = Some((
                format!(
                    "experiment `{text}` is for the live view, and this chapter's scene is not one"
                ),
                true,
            ));
            return;
        };
        let result = Experiment::parse(&text).and_then(|e| {
            let settings = e.apply(base)?;
            let spec = Spec::Top {
                settings,
                columns: Vec::new(),
                log_time: e.log_time.unwrap_or(*log_time),
            };
            Stage::start(&spec, self.background)
        });
        let shown = self.panes().scene.is_some();
        match result {
            Ok(stage) => {
                self.stage = stage;
                self.stage.resize(self.size.0, self.size.1);
                let caption = text
                    .split_once('|')
                    .map_or(text.as_str(), |(s, _)| s)
                    .trim();
                // The key first: the settings may be cut at 80 columns.
                self.message = Some((
                    format!(
                        "experiment {} of {n} applied{}: {caption}",
                        k + 1,
                        if shown { "" } else { " (Tab shows the scene)" }
                    ),
                    false,
                ));
            }
            Err(e) => {
                self.message = Some((format!("experiment {} of {n} refused: {e}", k + 1), true))
            }
        }
    }

    /// Steps the scene by wall-clock time, and takes the course grader's news.
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
        let reports = self.watch.as_ref().map(|w| w.poll()).unwrap_or_default();
        for report in reports {
            self.course_report(report);
        }
        if let Some(report) = self.probe_rx.as_ref().and_then(|rx| rx.try_recv().ok()) {
            self.probe_rx = None;
            self.probe_report(report);
        }
    }

    /// Starts grading the lessons crate in `dir` in the background, again on
    /// every save of a file under its `src/`.
    pub fn watch_course(&mut self, dir: &Path) {
        self.watch = Some(spintop_course::Watch::start(dir));
        self.course_dir = Some(dir.to_path_buf());
    }

    /// The assignment a hint is for: the first of this chapter's assignments
    /// that does not pass yet, else the course's next one.
    pub fn hint_target(&self) -> Option<&'static spintop_course::Assignment> {
        use spintop_course::{COURSE, State};
        let title = &self.chapters[self.current].title;
        let passing = |a: &spintop_course::Assignment| {
            self.course.as_ref().is_some_and(|s| {
                s.states
                    .iter()
                    .any(|(b, st)| b.function == a.function && *st == State::Passing)
            })
        };
        COURSE
            .iter()
            .find(|a| title.starts_with(a.chapter) && !passing(a))
            .or_else(|| COURSE.iter().find(|a| !passing(a)))
    }

    /// The next hint rung (`h`): for [`Self::hint_target`], kept in the
    /// course's progress file when the course is being graded.
    fn next_hint(&mut self) {
        use spintop_course as course;
        let Some(a) = self.hint_target() else {
            self.hint = None;
            return;
        };
        let mut progress = match self.course_dir.as_deref() {
            Some(dir) => course::load_progress(dir),
            None => self.hints_used.clone(),
        };
        self.hint = Some(course::next_hint(&mut progress, a));
        self.hints_used = progress.clone();
        if let Some(dir) = &self.course_dir
            && let Err(e) = course::save_progress(dir, &progress)
        {
            self.message = Some((format!("cannot keep the hint: {e}"), true));
        }
        self.mode = Mode::Course;
    }

    /// The hint on screen, if any.
    pub fn hint(&self) -> Option<&spintop_course::Hint> {
        self.hint.as_ref()
    }

    /// Takes one report of the course grader.
    pub fn course_report(&mut self, report: spintop_course::Report) {
        use spintop_course::Report;
        match report {
            Report::Grading => self.grading = true,
            Report::Graded(status) => {
                self.grading = false;
                self.course_error = None;
                if let Some(dir) = &self.course_dir {
                    spintop_course::record_passes_now(dir, &status);
                }
                self.course = Some(status);
                self.start_probe();
            }
            Report::Failed(e) => {
                self.grading = false;
                self.course_error = Some(e);
            }
        }
    }

    /// The last grading of the course, if any.
    pub fn course(&self) -> Option<&spintop_course::Status> {
        self.course.as_ref()
    }

    /// True while a grading runs.
    pub fn grading(&self) -> bool {
        self.grading
    }

    /// Why the grader could not run, if it could not.
    pub fn course_error(&self) -> Option<&str> {
        self.course_error.as_deref()
    }

    /// Why nothing is graded in this session, if grading is off.
    pub fn grading_off_reason(&self) -> Option<&str> {
        self.grading_off.as_deref()
    }

    /// Apply one command: the only place the state changes (besides the
    /// clock and the grader's news).
    pub fn apply(&mut self, command: Command) {
        if !matches!(command, Command::Resize(..) | Command::Scroll(_)) {
            self.message = None;
        }
        match command {
            Command::Quit => self.quit = true,
            Command::Resize(w, h) => {
                self.size = (w, h);
                self.stage.resize(w, h);
                self.render();
            }
            Command::Scroll(n) => {
                self.scroll = self.scroll.saturating_add_signed(n as isize);
                self.clamp_scroll();
            }
            Command::PageDown => {
                self.scroll += self.page().saturating_sub(2).max(1);
                self.clamp_scroll();
            }
            Command::PageUp => {
                self.scroll = self
                    .scroll
                    .saturating_sub(self.page().saturating_sub(2).max(1));
            }
            Command::Top => self.scroll = 0,
            Command::End => self.scroll = self.max_scroll(),
            Command::NextChapter => {
                if self.current + 1 < self.chapters.len() {
                    self.go(self.current + 1);
                } else {
                    self.message = Some(("this is the last chapter".into(), false));
                }
            }
            Command::PreviousChapter => {
                if self.current > 0 {
                    self.go(self.current - 1);
                } else {
                    self.message = Some(("this is the first chapter".into(), false));
                }
            }
            Command::Contents => {
                let at = self
                    .contents
                    .iter()
                    .position(|e| e.chapter == self.current)
                    .unwrap_or(0);
                self.mode = Mode::Contents(at);
            }
            Command::ContentsUp => {
                if let Mode::Contents(sel) = self.mode {
                    self.mode = Mode::Contents(sel.saturating_sub(1));
                }
            }
            Command::ContentsDown => {
                if let Mode::Contents(sel) = self.mode {
                    self.mode = Mode::Contents((sel + 1).min(self.contents.len() - 1));
                }
            }
            Command::ContentsOpen => {
                if let Mode::Contents(sel) = self.mode {
                    self.mode = Mode::Read;
                    let entry = self.contents[sel].clone();
                    if entry.chapter != self.current {
                        self.go(entry.chapter);
                    }
                    if let Some((_, text)) = entry.heading
                        && let Some((line, ..)) =
                            self.rendered.headings.iter().find(|(_, _, h)| *h == text)
                    {
                        self.scroll = *line;
                        self.clamp_scroll();
                    }
                }
            }
            Command::Help => self.mode = Mode::Help,
            Command::Course => self.mode = Mode::Course,
            Command::Hint => self.next_hint(),
            Command::Close => {
                self.mode = match self.mode {
                    // Esc in the full-screen scene goes back to the text.
                    Mode::Read => {
                        if self.search.take().is_none() {
                            self.message = Some(("q quits".into(), false));
                        }
                        Mode::Read
                    }
                    _ => Mode::Read,
                }
            }
            Command::Experiment => self.next_experiment(),
            Command::ToggleScene => {
                if self.mode == Mode::Scene {
                    self.mode = Mode::Read;
                } else if matches!(self.stage, Stage::None) {
                    self.message = Some((self.scene_info.describe(), false));
                } else {
                    self.mode = Mode::Scene;
                }
            }
            Command::ToggleFolds => {
                self.unfolded = !self.unfolded;
                self.render();
                self.message = Some((
                    if self.unfolded {
                        "library source shown whole; o folds it again"
                    } else {
                        "library source folded to one line each; o shows it"
                    }
                    .into(),
                    false,
                ));
            }
            // As in `less`: `/` starts an empty field; Enter on it repeats
            // the last search from the next match.
            Command::SearchStart => self.mode = Mode::Search(String::new()),
            Command::SearchInput(c) => {
                if let Mode::Search(q) = &mut self.mode
                    && q.chars().count() < 64
                {
                    q.push(c);
                }
            }
            Command::SearchBackspace => {
                if let Mode::Search(q) = &mut self.mode {
                    q.pop();
                }
            }
            Command::SearchCommit => {
                if let Mode::Search(q) = std::mem::replace(&mut self.mode, Mode::Read) {
                    if q.trim().is_empty() {
                        if self.search.is_some() {
                            self.jump(true, false);
                        }
                    } else {
                        self.find(&q);
                        // A word only in folded library source: show the
                        // source whole (as o does) rather than miss it.
                        let missed =
                            |l: &Self| l.search.as_ref().is_some_and(|s| s.matches.is_empty());
                        let mut unfolded_now = false;
                        if missed(self) && !self.unfolded {
                            self.unfolded = true;
                            self.render();
                            unfolded_now = !missed(self);
                            if !unfolded_now {
                                self.unfolded = false;
                                self.render();
                            }
                        }
                        self.jump(true, true);
                        if unfolded_now && let Some((text, _)) = &mut self.message {
                            text.push_str(", in library source, now shown whole (o folds it)");
                        }
                    }
                }
            }
            Command::SearchNext | Command::SearchPrevious => {
                if self.search.is_none() {
                    self.message = Some((
                        "/ searches; then n and N go to the next and previous match".into(),
                        false,
                    ));
                } else {
                    self.jump(command == Command::SearchNext, false);
                }
            }
            Command::Scene(key) => {
                let (text, refused) = self.stage.key(key);
                if !text.is_empty() {
                    self.message = Some((text, refused));
                }
            }
        }
    }

    /// Every match of `query` (case-insensitive) in the rendered text.
    fn find(&mut self, query: &str) {
        let needle = query.to_lowercase();
        let mut matches = Vec::new();
        for (i, line) in self.rendered.lines.iter().enumerate() {
            let text: String = line.spans.iter().map(|s| s.content.as_ref()).collect();
            let lower = text.to_lowercase();
            // Lower-casing keeps byte offsets for the text this book holds
            // (ASCII and Greek letters of the same length); where it would
            // not, the match is skipped rather than misplaced.
            if lower.len() != text.len() {
                continue;
            }
            let mut from = 0;
            while let Some(at) = lower[from..].find(&needle) {
                let start = from + at;
                matches.push((i, start..start + needle.len()));
                from = start + needle.len().max(1);
            }
        }
        let at = self
            .search
            .as_ref()
            .filter(|s| s.query == query)
            .map_or(0, |s| s.at);
        self.search = Some(Search {
            query: query.to_string(),
            at: at.min(matches.len().saturating_sub(1)),
            matches,
        });
    }

    /// Go to the next (or previous) match from the top of the page (`first`:
    /// the first one at or below it).
    fn jump(&mut self, forward: bool, first: bool) {
        let Some(search) = &mut self.search else {
            return;
        };
        let n = search.matches.len();
        if n == 0 {
            self.message = Some((format!("“{}” is not in this chapter", search.query), true));
            return;
        }
        let top = self.scroll;
        let current = search.matches.get(search.at).map(|m| m.0);
        search.at = if first {
            search.matches.iter().position(|m| m.0 >= top).unwrap_or(0)
        } else if forward {
            let after = current.unwrap_or(top);
            search
                .matches
                .iter()
                .enumerate()
                .position(|(k, m)| m.0 > after || (m.0 == after && k > search.at))
                .unwrap_or(0)
        } else if search.at == 0 {
            n - 1
        } else {
            search.at - 1
        };
        let line = search.matches[search.at].0;
        let text = format!("“{}”: match {} of {n}", search.query, search.at + 1);
        // The match a third of the way down the page, as less puts it.
        self.scroll = line.saturating_sub(self.page() / 3);
        self.clamp_scroll();
        self.message = Some((text, false));
    }
}

/// A progress bar of `width` cells for `k` of `n`: ▰ done, ▱ to do.
pub fn progress_bar(k: usize, n: usize, width: usize) -> String {
    let done = (k * width + n / 2).checked_div(n).unwrap_or(0).min(width);
    format!("{}{}", "▰".repeat(done), "▱".repeat(width - done))
}

/// The progress file's content: the chapters opened so far, the last one,
/// and where each was left.
#[derive(Debug, Default, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Progress {
    /// File names of the chapters opened.
    pub opened: Vec<String>,
    /// The chapter open when the session ended.
    pub last: Option<String>,
    /// Where each chapter was left: (first line shown, lines of the chapter
    /// at the width it was read at).
    #[serde(default)]
    pub positions: BTreeMap<String, (usize, usize)>,
}

impl Progress {
    /// Progress from a session.
    pub fn of(learn: &Learn) -> Self {
        let mut positions = BTreeMap::new();
        for (i, c) in learn.chapters.iter().enumerate() {
            let here = if i == learn.current {
                Some((learn.scroll, learn.rendered.lines.len().max(1)))
            } else {
                learn.positions[i]
            };
            if let Some(p) = here {
                positions.insert(c.file.clone(), p);
            }
        }
        Progress {
            opened: learn
                .chapters
                .iter()
                .zip(&learn.visited)
                .filter(|(_, v)| **v)
                .map(|(c, _)| c.file.clone())
                .collect(),
            last: Some(learn.chapters[learn.current].file.clone()),
            positions,
        }
    }
}

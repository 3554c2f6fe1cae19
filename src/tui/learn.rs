//! `spintop learn`: the book's chapters in the terminal, each beside its live
//! scene.
//!
//! The text is the book itself: `book/src/SUMMARY.md` gives the chapters and
//! their order, and each chapter's Markdown is read from `book/src` at run
//! time (one source, no copies) and rendered by [`markdown`], with every
//! equation turned into Unicode by [`tex`]. The scene is the live view's own
//! [`App`], drawn by the live view's own column widget, so a chapter's chart
//! is exactly what `spintop` shows. A chapter's experiments are
//! `<!-- spintop: key=value … -->` comments in its Markdown (mdBook drops
//! them); `x` applies the next one to the scene and scrolls the text to it.

pub mod markdown;
pub mod tex;

use super::app::{App, Settings, WARPS};
use super::theme;
use super::view;
use crate::math::{Real, Vec3};
use crate::numbers::parse_number;
use crate::physics::general_top::GeneralTop;
use crate::sim::MethodChoice;
use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, BorderType, Clear, List, ListItem, ListState, Paragraph, Wrap};
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

    /// The chapter's scene: the live view's settings, which of its columns
    /// to show, and a one-line description.
    pub fn scene(&self) -> Scene {
        let figure = Settings::default();
        let both = Scene {
            settings: figure,
            columns: vec![0, 1],
            about: "the paper's top, I₃/I₁ = 2/5: truncated and reduced side by side",
        };
        match self.file.as_str() {
            "section-3.md" => {
                // An asymmetric top under the truncated ALE (3.3).
                let top = GeneralTop::new(Vec3::new(1.0, 1.5, 2.0), Vec3::new(0.3, 0.2, 1.0)).ok();
                match top.and_then(|t| {
                    Settings::general(t, [0.05, 0.1, 0.2], MethodChoice::Dop853, 10.0).ok()
                }) {
                    Some(settings) => Scene {
                        settings,
                        columns: vec![0],
                        about: "an asymmetric top under the truncated ALE (3.3), DOP853",
                    },
                    None => both,
                }
            }
            "section-4-1.md" => Scene {
                columns: vec![0],
                about: "the truncated top (4.2)–(4.4) at I₃/I₁ = 2/5",
                ..both
            },
            "section-4-2.md" => Scene {
                columns: vec![1],
                about: "the reduced top (4.12)–(4.14) at I₃/I₁ = 2/5",
                ..both
            },
            "numerical-methods.md" | "where-methods-fail.md" => {
                match Settings::new(0.4, [0.0, 0.1, 0.2], MethodChoice::Rk4, 100.0) {
                    Ok(settings) => Scene {
                        settings,
                        columns: vec![0, 1],
                        about: "both models under fixed-step RK4 at 100 τ/s: press x to break it",
                    },
                    Err(_) => both,
                }
            }
            "speed-accuracy.md" => {
                match Settings::new(0.4, [0.0, 0.1, 0.2], MethodChoice::Dop853, 10.0) {
                    Ok(settings) => Scene {
                        settings,
                        columns: vec![0, 1],
                        about: "both models by DOP853 beside their closed forms",
                    },
                    Err(_) => both,
                }
            }
            "asymmetric-top.md" => {
                // The chapter's top: three models side by side.
                let top = GeneralTop::new(Vec3::new(1.0, 2.0, 2.5), Vec3::new(1.0, 0.5, 0.2)).ok();
                match top.and_then(|t| {
                    Settings::general(t, [0.3, -0.2, 0.1], MethodChoice::Dop853, 10.0).ok()
                }) {
                    Some(settings) => Scene {
                        settings,
                        columns: vec![0, 1, 2],
                        about: "I = (1, 2, 2.5), d = (1, 0.5, 0.2): (3.3), reduced and physical (3.4), in u",
                    },
                    None => both,
                }
            }
            _ => both,
        }
    }
}

/// What a chapter shows on the right.
#[derive(Debug, Clone)]
pub struct Scene {
    /// The live view's settings.
    pub settings: Settings,
    /// The live view's columns to draw (0 truncated, 1 reduced; for a general
    /// top 0 truncated (3.3), 1 reduced, 2 physical (3.4)).
    pub columns: Vec<usize>,
    /// One line about it, for the header.
    pub about: &'static str,
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

/// One experiment, parsed from `<!-- spintop: ratio=1.5 method=rk4 -->`.
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

    /// The settings this experiment makes of `base`.
    pub fn apply(&self, base: &Settings) -> Result<Settings, String> {
        let omega = self.omega.unwrap_or(base.omega0());
        let method = self.method.unwrap_or(base.method());
        let warp = self.warp.unwrap_or(base.warp());
        match base.top() {
            super::app::Top::General(top) => {
                if self.ratio.is_some() {
                    return Err("this scene is a general top: ratio does not apply".into());
                }
                Settings::general(*top, omega, method, warp)
            }
            super::app::Top::Symmetric(_) => Settings::new(
                self.ratio.or(base.ratio()).unwrap_or(0.4),
                omega,
                method,
                warp,
            ),
        }
    }
}

/// What the keys do now.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// Reading, scene beside the text (or text alone on a narrow screen).
    Read,
    /// The scene full screen.
    Scene,
    /// The table of contents, with the highlighted chapter.
    Contents(usize),
    /// The help overlay.
    Help,
    /// The course: every assignment with its state.
    Course,
}

/// The state of `spintop learn`.
pub struct Learn {
    book: PathBuf,
    chapters: Vec<Chapter>,
    current: usize,
    source: String,
    rendered: markdown::Rendered,
    width: u16,
    scroll: usize,
    page: usize,
    next_experiment: usize,
    scene: App,
    scene_info: Scene,
    mode: Mode,
    message: Option<(String, bool)>,
    visited: Vec<bool>,
    quit: bool,
    too_small: bool,
    /// The course's grader, watching the student's files, if started.
    watch: Option<crate::course::Watch>,
    /// The last grading, and whether one is running.
    course: Option<crate::course::Status>,
    grading: bool,
    course_error: Option<String>,
    /// The lessons crate being graded (where the hint rungs are kept).
    course_dir: Option<PathBuf>,
    /// The last hint rung shown (`h`).
    hint: Option<crate::course::Hint>,
    /// The hint rungs used, when there is no course folder to keep them in.
    hints_used: crate::course::Progress,
    /// The student's function of time being sampled (see [`Self::start_probe`]).
    probe_rx: Option<std::sync::mpsc::Receiver<ProbeReport>>,
    /// The student's function of time, sampled, to draw against the reference.
    yours: Option<ProbeReport>,
}

/// A probe's request and what it found.
pub type ProbeReport = (
    crate::course::ProbeSpec,
    Result<crate::course::Probed, String>,
);

/// The keys, for the footer and the help.
const KEYS: [(&str, &str); 10] = [
    ("?", "help"),
    ("q", "quit"),
    ("↑↓ PgUp PgDn", "scroll"),
    ("← →", "chapter"),
    ("c", "contents"),
    ("a", "assignments"),
    ("h", "hint"),
    ("x", "try the next experiment"),
    ("space", "pause scene"),
    ("Tab", "scene full screen"),
];

impl Learn {
    /// Opens the book at `book` (the `book/src` folder) on chapter `start`.
    pub fn open(book: &Path, start: Option<&str>) -> Result<Self, String> {
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
        let scene_info = chapters[current].scene();
        let scene = App::new(scene_info.settings).map_err(|e| e.to_string())?;
        let visited = vec![false; chapters.len()];
        let mut learn = Learn {
            book: book.to_path_buf(),
            chapters,
            current,
            source: String::new(),
            rendered: markdown::Rendered::default(),
            width: 0,
            scroll: 0,
            page: 20,
            next_experiment: 0,
            scene,
            scene_info,
            mode: Mode::Read,
            message: None,
            visited,
            quit: false,
            too_small: false,
            watch: None,
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

    /// The chapter shown.
    pub fn current(&self) -> usize {
        self.current
    }

    /// The scene's state.
    pub fn scene(&self) -> &App {
        &self.scene
    }

    /// The mode.
    pub fn mode(&self) -> Mode {
        self.mode
    }

    /// True once quit was asked for.
    pub fn should_quit(&self) -> bool {
        self.quit
    }

    /// The chapters opened in this session.
    pub fn visited(&self) -> &[bool] {
        &self.visited
    }

    /// Marks chapters as visited (progress restored from an earlier session).
    pub fn mark_visited(&mut self, files: &[String]) {
        for (i, c) in self.chapters.iter().enumerate() {
            if files.contains(&c.file) {
                self.visited[i] = true;
            }
        }
    }

    /// The first line of the text shown.
    pub fn scroll(&self) -> usize {
        self.scroll
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
        self.width = 0;
        self.scroll = 0;
        self.next_experiment = 0;
        let info = chapter.scene();
        if info.settings != self.scene_info.settings || info.columns != self.scene_info.columns {
            self.scene = App::new(info.settings)?;
        }
        self.scene_info = info;
        Ok(())
    }

    /// The chapter rendered at `width` (cached until the width changes).
    pub fn rendered(&mut self, width: u16) -> &markdown::Rendered {
        if width != self.width {
            // Keep the reader at the same place in the text across a resize.
            let fraction = if self.rendered.lines.is_empty() {
                0.0
            } else {
                self.scroll as f64 / self.rendered.lines.len() as f64
            };
            self.rendered = markdown::render(&self.source, width);
            self.width = width;
            self.scroll = (fraction * self.rendered.lines.len() as f64) as usize;
        }
        &self.rendered
    }

    fn go(&mut self, index: usize) {
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
        use crate::course::{ProbeSpec, State};
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
            let _ = tx.send((spec, crate::course::probe(&dir, &spec)));
        });
        self.probe_rx = Some(rx);
    }

    /// Takes a probe's report (from the background, or from a test).
    pub fn probe_report(&mut self, report: ProbeReport) {
        self.yours = Some(report);
    }

    fn max_scroll(&self) -> usize {
        self.rendered.lines.len().saturating_sub(self.page.max(1))
    }

    /// Runs the chapter's next experiment on the scene and scrolls to it.
    pub fn next_experiment(&mut self) {
        if self.width == 0 {
            self.rendered(80);
        }
        let experiments = &self.rendered.experiments;
        if experiments.is_empty() {
            self.message = Some((
                "this chapter has no experiments; its scene runs with the chapter's parameters"
                    .into(),
                false,
            ));
            return;
        }
        let k = self.next_experiment % experiments.len();
        let (line, text) = experiments[k].clone();
        self.next_experiment = k + 1;
        self.scroll = line.saturating_sub(2).min(self.max_scroll());
        let result = Experiment::parse(&text).and_then(|e| {
            let settings = e.apply(self.scene.settings())?;
            let mut app = App::new(settings)?;
            if e.log_time == Some(true) {
                app.apply(super::Command::ToggleLogTime);
            }
            Ok(app)
        });
        match result {
            Ok(app) => {
                self.scene = app;
                self.message = Some((
                    format!("experiment {} of {}: {text}", k + 1, experiments.len()),
                    false,
                ));
            }
            Err(e) => self.message = Some((format!("experiment `{text}`: {e}"), true)),
        }
    }

    /// Steps the scene by wall-clock time, and takes the course grader's news.
    pub fn advance(&mut self, elapsed: Duration) {
        self.scene.advance_wall(elapsed);
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
        self.watch = Some(crate::course::Watch::start(dir));
        self.course_dir = Some(dir.to_path_buf());
    }

    /// The assignment a hint is for: the first of this chapter's assignments
    /// that does not pass yet, else the course's next one.
    pub fn hint_target(&self) -> Option<&'static crate::course::Assignment> {
        use crate::course::{COURSE, State};
        let title = &self.chapters[self.current].title;
        let passing = |a: &crate::course::Assignment| {
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
    pub fn next_hint(&mut self) {
        use crate::course;
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
    pub fn hint(&self) -> Option<&crate::course::Hint> {
        self.hint.as_ref()
    }

    /// Takes one report of the course grader.
    pub fn course_report(&mut self, report: crate::course::Report) {
        use crate::course::Report;
        match report {
            Report::Grading => self.grading = true,
            Report::Graded(status) => {
                self.grading = false;
                self.course_error = None;
                if let Some(dir) = &self.course_dir {
                    crate::course::record_passes_now(dir, &status);
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
    pub fn course(&self) -> Option<&crate::course::Status> {
        self.course.as_ref()
    }

    /// Applies one key.
    pub fn key(&mut self, key: KeyEvent) {
        if key.modifiers.contains(KeyModifiers::CONTROL) && key.code == KeyCode::Char('c') {
            self.quit = true;
            return;
        }
        // On the "please enlarge" screen only quit is taken.
        if self.too_small {
            if matches!(key.code, KeyCode::Char('q') | KeyCode::Esc) {
                self.quit = true;
            }
            return;
        }
        match self.mode {
            Mode::Course if key.code == KeyCode::Char('h') => self.next_hint(),
            Mode::Help | Mode::Course => {
                if matches!(key.code, KeyCode::Char('q')) {
                    self.quit = true;
                }
                self.mode = Mode::Read;
            }
            Mode::Contents(sel) => match key.code {
                KeyCode::Up | KeyCode::Char('k') => {
                    self.mode = Mode::Contents(sel.saturating_sub(1))
                }
                KeyCode::Down | KeyCode::Char('j') => {
                    self.mode = Mode::Contents((sel + 1).min(self.chapters.len() - 1))
                }
                KeyCode::Enter => {
                    self.mode = Mode::Read;
                    self.go(sel);
                }
                KeyCode::Char('q') => self.quit = true,
                _ => self.mode = Mode::Read,
            },
            Mode::Read | Mode::Scene => match key.code {
                KeyCode::Char('q') | KeyCode::Esc if self.mode == Mode::Read => self.quit = true,
                KeyCode::Esc | KeyCode::Tab if self.mode == Mode::Scene => self.mode = Mode::Read,
                KeyCode::Tab => self.mode = Mode::Scene,
                KeyCode::Char('q') => self.quit = true,
                KeyCode::Char('?') => self.mode = Mode::Help,
                KeyCode::Char('c') => self.mode = Mode::Contents(self.current),
                KeyCode::Char('a') => self.mode = Mode::Course,
                KeyCode::Char('h') => self.next_hint(),
                KeyCode::Down | KeyCode::Char('j') => {
                    self.scroll = (self.scroll + 1).min(self.max_scroll())
                }
                KeyCode::Up | KeyCode::Char('k') => self.scroll = self.scroll.saturating_sub(1),
                KeyCode::PageDown | KeyCode::Char('f') => {
                    self.scroll =
                        (self.scroll + self.page.saturating_sub(2).max(1)).min(self.max_scroll())
                }
                KeyCode::PageUp | KeyCode::Char('b') => {
                    self.scroll = self
                        .scroll
                        .saturating_sub(self.page.saturating_sub(2).max(1))
                }
                KeyCode::Home | KeyCode::Char('g') => self.scroll = 0,
                KeyCode::End | KeyCode::Char('G') => self.scroll = self.max_scroll(),
                KeyCode::Right | KeyCode::Char('n') if self.current + 1 < self.chapters.len() => {
                    self.go(self.current + 1)
                }
                KeyCode::Left | KeyCode::Char('p') if self.current > 0 => self.go(self.current - 1),
                KeyCode::Char('x') => self.next_experiment(),
                KeyCode::Char(' ') => self.scene.apply(super::Command::TogglePause),
                KeyCode::Char('r') => self.scene.apply(super::Command::Reset),
                KeyCode::Char('l') => self.scene.apply(super::Command::ToggleLogTime),
                KeyCode::Char('+') => self.scene.apply(super::Command::Faster),
                KeyCode::Char('-') => self.scene.apply(super::Command::Slower),
                _ => {}
            },
        }
    }

    /// Draws the screen.
    pub fn draw(&mut self, frame: &mut Frame) {
        let area = frame.area();
        self.too_small = area.width < 40 || area.height < 10;
        if self.too_small {
            let p = Paragraph::new(vec![
                Line::from(Span::styled("Please enlarge the terminal", theme::error())),
                Line::from(format!(
                    "spintop learn needs 40×10; this one is {}×{}. q quits.",
                    area.width, area.height
                )),
            ])
            .wrap(ratatui::widgets::Wrap { trim: true });
            frame.render_widget(p, area);
            return;
        }
        let [header, body, footer] = Layout::vertical([
            Constraint::Length(1),
            Constraint::Fill(1),
            Constraint::Length(1),
        ])
        .areas(area);
        self.draw_header(frame, header);
        let side_by_side = body.width >= 120 && self.mode != Mode::Scene;
        if self.mode == Mode::Scene {
            self.draw_scene(frame, body);
        } else if side_by_side {
            let [left, right] =
                Layout::horizontal([Constraint::Percentage(52), Constraint::Percentage(48)])
                    .areas(body);
            self.draw_text(frame, left);
            self.draw_scene(frame, right);
        } else {
            self.draw_text(frame, body);
        }
        self.draw_footer(frame, footer, side_by_side);
        match self.mode {
            Mode::Help => self.draw_help(frame, area),
            Mode::Course => self.draw_course(frame, area),
            Mode::Contents(sel) => self.draw_contents(frame, area, sel),
            _ => {}
        }
    }

    fn draw_header(&self, frame: &mut Frame, area: Rect) {
        let chapter = &self.chapters[self.current];
        let seen = self.visited.iter().filter(|v| **v).count();
        let course = match (&self.course, self.grading, &self.course_error) {
            (_, _, Some(_)) => " course: cannot grade ".to_string(),
            (Some(s), true, _) => format!(
                " course {} of {} {} grading… ",
                s.passing(),
                s.states.len(),
                progress_bar(s.passing(), s.states.len(), 10)
            ),
            (None, true, _) => " course: grading… ".to_string(),
            (Some(s), false, _) => format!(
                " course {} of {} {} (a) ",
                s.passing(),
                s.states.len(),
                progress_bar(s.passing(), s.states.len(), 10)
            ),
            (None, false, None) => String::new(),
        };
        let line = Line::from(vec![
            Span::styled(" spintop learn ", theme::status(false)),
            Span::styled(course, theme::key()),
            Span::styled(format!(" {} ", chapter.title), theme::title()),
            Span::styled(
                format!(
                    "│ chapter {} of {} │ {} opened │ scene t = {:.1}{}",
                    self.current + 1,
                    self.chapters.len(),
                    seen,
                    self.scene.time(),
                    self.scene.settings().top().time_unit()
                ),
                theme::label(),
            ),
        ]);
        frame.render_widget(Paragraph::new(line), area);
    }

    fn draw_text(&mut self, frame: &mut Frame, area: Rect) {
        let block = Block::bordered()
            .border_type(BorderType::Rounded)
            .border_style(theme::frame())
            .title(Span::styled(
                format!(" {} ", self.chapters[self.current].file),
                theme::label(),
            ));
        let inner = block.inner(area);
        frame.render_widget(block, area);
        let width = inner.width.saturating_sub(1).max(20);
        self.page = usize::from(inner.height);
        let total = self.rendered(width).lines.len();
        self.scroll = self.scroll.min(self.max_scroll());
        let end = (self.scroll + usize::from(inner.height)).min(total);
        let lines: Vec<Line> = self.rendered.lines[self.scroll..end].to_vec();
        frame.render_widget(Paragraph::new(lines), inner);
        if total > usize::from(inner.height) && inner.height > 0 {
            // A one-column position mark on the right edge.
            let pos = self.scroll * usize::from(inner.height - 1) / self.max_scroll().max(1);
            let mark = Rect {
                x: area.x + area.width - 1,
                y: inner.y + pos as u16,
                width: 1,
                height: 1,
            };
            frame.render_widget(Paragraph::new(Span::styled("┃", theme::key())), mark);
        }
    }

    fn draw_scene(&self, frame: &mut Frame, area: Rect) {
        let [about, params, rest] = Layout::vertical([
            Constraint::Length(1),
            Constraint::Length(1),
            Constraint::Fill(1),
        ])
        .areas(area);
        let text = match &self.message {
            Some((m, true)) => Span::styled(format!(" {m}"), theme::error()),
            Some((m, false)) => Span::styled(format!(" {m}"), theme::info()),
            None => Span::styled(format!(" scene: {}", self.scene_info.about), theme::label()),
        };
        frame.render_widget(Paragraph::new(Line::from(text)), about);
        frame.render_widget(
            Paragraph::new(Line::from(scene_parameters(self.scene.settings()))),
            params,
        );
        let columns: Vec<usize> = self
            .scene_info
            .columns
            .iter()
            .copied()
            .filter(|c| *c < self.scene.columns().len())
            .collect();
        // The student's function of time, when there is one, below the scene.
        let rest = if self.yours().is_some() && rest.height >= 20 {
            let [scene, yours] =
                Layout::vertical([Constraint::Fill(2), Constraint::Fill(1)]).areas(rest);
            self.draw_yours(frame, yours);
            scene
        } else {
            rest
        };
        // Two columns stacked need height; otherwise the first alone.
        let shown = if rest.height >= 44 || (rest.width >= 160 && columns.len() > 1) {
            columns.len()
        } else {
            1
        };
        let parts = if rest.width >= 160 {
            Layout::horizontal((0..shown).map(|_| Constraint::Ratio(1, shown as u32))).split(rest)
        } else {
            Layout::vertical((0..shown).map(|_| Constraint::Ratio(1, shown as u32))).split(rest)
        };
        for (part, c) in parts.iter().zip(columns.iter()) {
            view::draw_column(frame, *part, &self.scene, *c);
        }
    }

    /// The student's function of time of this chapter against the reference,
    /// when it has been sampled.
    fn yours(
        &self,
    ) -> Option<(
        &crate::course::ProbeSpec,
        &Result<crate::course::Probed, String>,
    )> {
        let (spec, probed) = self.yours.as_ref()?;
        let here = crate::course::ProbeSpec::for_chapter(&self.chapters[self.current].title)?;
        (*spec == here).then_some((spec, probed))
    }

    fn draw_yours(&self, frame: &mut Frame, area: Rect) {
        use crate::course::Probed;
        use ratatui::widgets::{Axis, Chart, Dataset, GraphType};
        let Some((spec, probed)) = self.yours() else {
            return;
        };
        let samples = match probed {
            Ok(Probed::Samples(s)) => s,
            Ok(Probed::Panicked(m)) => {
                let line = format!(" yours: {} panics: {m}", spec.function);
                frame.render_widget(Paragraph::new(Span::styled(line, theme::error())), area);
                return;
            }
            Err(e) => {
                let line = format!(" yours: {} could not be sampled: {e}", spec.function);
                frame.render_widget(Paragraph::new(Span::styled(line, theme::error())), area);
                return;
            }
        };
        let reference: Vec<(f64, [f64; 3])> = samples
            .iter()
            .map(|(t, _)| (*t, reference_omega(spec, *t)))
            .collect();
        let worst = samples
            .iter()
            .zip(&reference)
            .map(|((_, a), (_, b))| (0..3).map(|i| (a[i] - b[i]).abs()).fold(0.0, f64::max))
            .fold(
                0.0,
                |m: f64, d| if d.is_nan() { f64::INFINITY } else { m.max(d) },
            );
        let scale = spec.omega0.iter().fold(0.0f64, |m, w| m.max(w.abs()));
        let agrees = worst <= 1e-9 * scale.max(1e-300);
        let curve = |data: &[(f64, [f64; 3])], i: usize| -> Vec<(f64, f64)> {
            data.iter().map(|(t, w)| (*t, w[i])).collect()
        };
        let series = [
            (curve(&reference, 0), theme::frame()),
            (curve(&reference, 1), theme::frame()),
            (curve(samples, 0), Style::new().fg(theme::OMEGA[0])),
            (curve(samples, 1), Style::new().fg(theme::OMEGA[1])),
        ];
        let datasets = series
            .iter()
            .map(|(data, style)| {
                Dataset::default()
                    .marker(ratatui::symbols::Marker::Braille)
                    .graph_type(GraphType::Line)
                    .style(*style)
                    .data(data)
            })
            .collect();
        let equation = if spec.function == "truncated_closed_form" {
            "(4.7)"
        } else {
            "(4.15)-(4.16)"
        };
        let verdict = if agrees {
            Span::styled(format!("agrees ✓ ({worst:.0e})"), theme::info())
        } else {
            Span::styled(format!("off by {worst:.1e} ✗"), theme::error())
        };
        let title = Line::from(vec![
            Span::styled(format!(" yours: {} ", spec.function), theme::title()),
            Span::styled("━Ω₁ ", Style::new().fg(theme::OMEGA[0])),
            Span::styled("━Ω₂ ", Style::new().fg(theme::OMEGA[1])),
            Span::styled(format!("vs {equation} grey │ "), theme::label()),
            verdict,
        ]);
        // Ω₁ and Ω₂ are drawn: they stay within Ω⊥₀.
        let perp = spec.omega0[0].hypot(spec.omega0[1]);
        let y = crate::numbers::nice_ceiling(if perp > 0.0 { perp } else { scale } * 1.05);
        let chart = Chart::new(datasets)
            .block(Block::new().title(title))
            .legend_position(None)
            .x_axis(
                Axis::default()
                    .style(theme::frame())
                    .bounds([0.0, spec.t_end])
                    .labels(["0".to_string(), format!("{:.0} t/τ", spec.t_end)]),
            )
            .y_axis(
                Axis::default()
                    .style(theme::frame())
                    .bounds([-y, y])
                    .labels([format!("{}", -y), "0".into(), format!("{y}")]),
            );
        frame.render_widget(chart, area);
    }

    fn draw_footer(&self, frame: &mut Frame, area: Rect, side_by_side: bool) {
        let mut spans = Vec::new();
        for (k, what) in KEYS {
            if k == "Tab" && side_by_side {
                continue;
            }
            spans.push(Span::styled(format!(" {k}"), theme::key()));
            spans.push(Span::styled(format!(" {what} "), theme::label()));
        }
        frame.render_widget(Paragraph::new(Line::from(spans)), area);
    }

    fn draw_help(&self, frame: &mut Frame, area: Rect) {
        let mut lines = vec![
            Line::from(Span::styled("spintop learn", theme::title())),
            Line::from(""),
            Line::from("The book's chapters, each beside the scene it is about."),
            Line::from("Places marked ▶ try this are experiments: x runs the next one."),
            Line::from(""),
        ];
        for (k, what) in KEYS {
            lines.push(Line::from(vec![
                Span::styled(format!("{k:>14}  "), theme::key()),
                Span::raw(what),
            ]));
        }
        for (k, what) in [
            ("r l + -", "reset, log time, warp of the scene"),
            ("g G", "top, end of the chapter"),
        ] {
            lines.push(Line::from(vec![
                Span::styled(format!("{k:>14}  "), theme::key()),
                Span::raw(what),
            ]));
        }
        lines.push(Line::from(""));
        lines.push(Line::from("any key closes this help"));
        let popup = centered(area, 64, lines.len() as u16 + 2);
        frame.render_widget(Clear, popup);
        frame.render_widget(
            Paragraph::new(lines).block(
                Block::bordered()
                    .border_type(BorderType::Rounded)
                    .title(" help "),
            ),
            popup,
        );
    }

    fn draw_course(&self, frame: &mut Frame, area: Rect) {
        use crate::course::State;
        let mut lines = Vec::new();
        match (&self.course, &self.course_error) {
            (_, Some(e)) => lines.push(Line::from(Span::styled(e.clone(), theme::error()))),
            (None, None) => lines.push(Line::from(if self.grading {
                "grading (cargo test -p spintop-lessons)…"
            } else {
                "not graded: run spintop learn from the repository"
            })),
            (Some(status), None) => {
                lines.push(Line::from(Span::styled(
                    format!(
                        "{} {} of {} passing{}",
                        progress_bar(status.passing(), status.states.len(), 22),
                        status.passing(),
                        status.states.len(),
                        if self.grading { "  (grading…)" } else { "" }
                    ),
                    theme::title(),
                )));
                // This chapter's assignments; the whole course where it has none.
                let title = &self.chapters[self.current].title;
                let mine: Vec<_> = status
                    .states
                    .iter()
                    .filter(|(a, _)| title.starts_with(a.chapter))
                    .collect();
                let shown = if mine.is_empty() {
                    status.states.iter().collect()
                } else {
                    lines.push(Line::from(Span::styled(
                        format!("this chapter ({}):", mine.len()),
                        theme::label(),
                    )));
                    mine
                };
                for (a, s) in shown {
                    let (mark, style) = match s {
                        State::Passing => ("✓", theme::info()),
                        State::Failing(_) | State::DoesNotCompile(_) | State::TimedOut(_) => {
                            ("✗", theme::error())
                        }
                        _ => ("·", theme::label()),
                    };
                    lines.push(Line::from(vec![
                        Span::styled(format!(" {mark} "), style),
                        Span::raw(format!(
                            "{:<14} {:<24} {:<24} ",
                            a.equation, a.function, a.file
                        )),
                        Span::styled(s.word(), style),
                    ]));
                }
                let target = self.hint_target();
                if let Some((a, s)) = target
                    .and_then(|t| status.states.iter().find(|(a, _)| a.function == t.function))
                {
                    lines.push(Line::from(""));
                    lines.push(Line::from(Span::styled(
                        format!("next: {} {} ({})", a.equation, a.function, a.chapter),
                        theme::title(),
                    )));
                    match s {
                        State::Failing(report) => {
                            for l in report.lines().take(8) {
                                lines.push(Line::from(format!("  {l}")));
                            }
                        }
                        State::DoesNotCompile(e) | State::TimedOut(e) => {
                            lines.push(Line::from(format!("  {e}")))
                        }
                        _ => lines.push(Line::from(format!(
                            "  edit {}: its todo!() is still there; saving re-grades",
                            a.file
                        ))),
                    }
                }
            }
        }
        if let Some(h) = &self.hint
            && self
                .hint_target()
                .is_some_and(|t| t.function == h.assignment.function)
        {
            let label = h.label();
            lines.push(Line::from(Span::styled(
                format!(
                    "hint {} of {} ({label}) for {}:",
                    h.rung,
                    h.assignment.hints.len(),
                    h.assignment.function
                ),
                theme::title(),
            )));
            lines.push(Line::from(format!("  {}", h.text)));
        }
        lines.push(Line::from(""));
        lines.push(Line::from(Span::styled(
            "saving a file under lessons/src re-grades it; h: a hint (one rung per press); any other key closes",
            theme::label(),
        )));
        // Rows once wrapped to the popup's inner width.
        let inner = usize::from(area.width.min(100).saturating_sub(2)).max(1);
        let rows: usize = lines.iter().map(|l| l.width().max(1).div_ceil(inner)).sum();
        let popup = centered(area, 100, rows as u16 + 2);
        frame.render_widget(Clear, popup);
        frame.render_widget(
            Paragraph::new(lines).wrap(Wrap { trim: false }).block(
                Block::bordered()
                    .border_type(BorderType::Rounded)
                    .title(" course "),
            ),
            popup,
        );
    }

    fn draw_contents(&self, frame: &mut Frame, area: Rect, selected: usize) {
        let mut items = Vec::new();
        let mut part = None;
        let mut row_of = Vec::new();
        for (i, c) in self.chapters.iter().enumerate() {
            if c.part != part {
                part = c.part.clone();
                if let Some(p) = &part {
                    items.push(ListItem::new(Line::from(Span::styled(
                        p.clone(),
                        theme::label(),
                    ))));
                }
            }
            row_of.push(items.len());
            let mark = if self.visited[i] { "✓" } else { " " };
            let section = c
                .section()
                .map(|s| format!("§{s:<4}"))
                .unwrap_or_else(|| "     ".into());
            items.push(ListItem::new(format!(" {mark} {section} {}", c.title)));
        }
        let height = (items.len() as u16 + 2).min(area.height);
        let popup = centered(area, 72, height);
        let mut state = ListState::default().with_selected(row_of.get(selected).copied());
        frame.render_widget(Clear, popup);
        frame.render_stateful_widget(
            List::new(items)
                .highlight_style(Style::new().add_modifier(Modifier::REVERSED))
                .block(
                    Block::bordered()
                        .border_type(BorderType::Rounded)
                        .title(" contents: ↑↓ Enter "),
                ),
            popup,
            &mut state,
        );
    }
}

/// The scene's parameters, one line: what an experiment changes.
fn scene_parameters(settings: &Settings) -> Vec<Span<'static>> {
    let w = settings.omega0();
    let mut spans = vec![Span::raw(" ")];
    if let Some(r) = settings.ratio() {
        spans.push(Span::styled("I₃/I₁ = ", theme::label()));
        spans.push(Span::styled(format!("{r}"), theme::value()));
        spans.push(Span::styled("  ", theme::label()));
    }
    spans.push(Span::styled("Ω₀ = ", theme::label()));
    spans.push(Span::styled(
        format!("({}, {}, {})", w[0], w[1], w[2]),
        theme::value(),
    ));
    spans.push(Span::styled("  method ", theme::label()));
    spans.push(Span::styled(
        settings.method().title().to_string(),
        theme::value(),
    ));
    spans.push(Span::styled("  warp ", theme::label()));
    spans.push(Span::styled(
        format!("{} {}/s", settings.warp(), settings.top().time_unit()),
        theme::value(),
    ));
    spans
}

fn centered(area: Rect, width: u16, height: u16) -> Rect {
    let w = width.min(area.width);
    let h = height.min(area.height);
    Rect {
        x: area.x + (area.width - w) / 2,
        y: area.y + (area.height - h) / 2,
        width: w,
        height: h,
    }
}

/// Ω(t) of the probe's model by spintop's own closed form, the reference
/// the student's function is drawn against.
fn reference_omega(spec: &crate::course::ProbeSpec, t: f64) -> [f64; 3] {
    use crate::physics::symmetric_top::{self as sym, SymmetricTop};
    let Ok(top) = SymmetricTop::new(spec.ratio, spec.tau) else {
        return [f64::NAN; 3];
    };
    let w0 = crate::math::Vec3::from(spec.omega0);
    let w = if spec.function == "truncated_closed_form" {
        sym::truncated_closed_form(&top, &w0, t)
    } else {
        sym::reduced_closed_form(&top, &w0, t)
    };
    [w.x, w.y, w.z]
}

/// A progress bar of `width` cells for `k` of `n`: ▰ done, ▱ to do.
pub fn progress_bar(k: usize, n: usize, width: usize) -> String {
    let done = (k * width + n / 2).checked_div(n).unwrap_or(0).min(width);
    format!("{}{}", "▰".repeat(done), "▱".repeat(width - done))
}

/// The progress file's content: the chapters opened so far and the last one.
#[derive(Debug, Default, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Progress {
    /// File names of the chapters opened.
    pub opened: Vec<String>,
    /// The chapter open when the session ended.
    pub last: Option<String>,
}

impl Progress {
    /// Progress from a session.
    pub fn of(learn: &Learn) -> Self {
        Progress {
            opened: learn
                .chapters
                .iter()
                .zip(&learn.visited)
                .filter(|(_, v)| **v)
                .map(|(c, _)| c.file.clone())
                .collect(),
            last: Some(learn.chapters[learn.current].file.clone()),
        }
    }
}

/// Runs `spintop learn` on a terminal until quit.
/// Returns the signal that ended it, if one did (see [`super::signals`]).
pub fn run<B: ratatui::backend::Backend>(
    terminal: &mut ratatui::Terminal<B>,
    learn: &mut Learn,
) -> std::io::Result<Option<i32>>
where
    B::Error: Send + Sync + 'static,
{
    use crossterm::event::{self, Event, KeyEventKind};
    use std::time::Instant;
    let signals = super::signals::Signals::install()?;
    let frame_time = Duration::from_millis(33);
    let mut last = Instant::now();
    while !learn.should_quit() && signals.received().is_none() {
        let now = Instant::now();
        learn.advance(now - last);
        last = now;
        terminal
            .draw(|f| learn.draw(f))
            .map_err(std::io::Error::other)?;
        let deadline = Instant::now() + frame_time;
        loop {
            let timeout = deadline.saturating_duration_since(Instant::now());
            if timeout.is_zero() || !super::signals::poll(timeout)? {
                break;
            }
            if let Event::Key(key) = event::read()?
                && key.kind != KeyEventKind::Release
            {
                learn.key(key);
                if learn.should_quit() {
                    break;
                }
            }
            if signals.received().is_some() {
                break;
            }
        }
    }
    Ok(signals.received())
}

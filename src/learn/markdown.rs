//! The book's Markdown, rendered for a terminal.
//!
//! The parsing is pulldown-cmark's (the parser mdBook itself uses), with its
//! math extension on so that `$…$` and `$$…$$` arrive as math events. What is
//! written here is the part no crate does for this book: mdBook's
//! `{{#include file:anchor}}` is resolved the way mdBook resolves it, rustdoc's
//! hidden `# ` lines are dropped from Rust snippets as mdBook hides them,
//! MathJax-style `\\[ … \\]` and `\\( … \\)` are read as math, every equation
//! goes through [`super::tex`] to Unicode, and the result is wrapped to the
//! panel's width as styled ratatui lines. Inline code that starts with
//! `spintop: ` (`` `spintop: ratio=1.5` ``, visible in the web book as the
//! settings to try) marks one of the chapter's experiments.

mod include;
mod math;
mod table;
mod wrap;

pub use include::resolve_includes;
pub use wrap::{CONTINUATION, prose_subscripts, without_colours, wrap_code};

use super::tex;
use include::FOLD;
use math::normalise_math_delimiters;
use pulldown_cmark::{Alignment, CodeBlockKind, Event, HeadingLevel, Parser, Tag, TagEnd};
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};
use std::path::PathBuf;
use unicode_width::UnicodeWidthStr;
use wrap::{NBSP, Piece, is_function_word, split_too_long, unbreakable_groups};

/// A chapter rendered at one width.
#[derive(Debug, Clone, Default)]
pub struct Rendered {
    /// The lines, ready for a `Paragraph`.
    pub lines: Vec<Line<'static>>,
    /// Headings: (line index, level 1–6, text).
    pub headings: Vec<(usize, u8, String)>,
    /// Experiments: (line index, the text after `spintop:`).
    pub experiments: Vec<(usize, String)>,
    /// TeX commands the converter did not know (a test keeps this empty).
    pub unknown_tex: Vec<String>,
    /// A figure is still being computed: render again once it is there.
    pub figures_pending: bool,
    /// The links, in reading order.
    pub links: Vec<Link>,
    /// Anchors written as HTML (`<a id="jackson">`, the bibliography's
    /// entries): (line index, id).
    pub anchors: Vec<(usize, String)>,
    /// Lines that go on from the line before (prose wrapped at the width):
    /// (line index, bytes of its prefix, what the wrap stands for: a space
    /// or nothing), so that a phrase is searched as written, not as wrapped.
    pub wraps: Vec<(usize, usize, &'static str)>,
}

/// A link of the text: where it points, and where it is drawn (a link that
/// wraps is in more than one part).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Link {
    /// Its destination as the Markdown gives it (`section-3.md#anchor`,
    /// `#anchor`, `https://…`).
    pub target: String,
    /// Each part: (line, byte range in the line's text).
    pub parts: Vec<(usize, std::ops::Range<usize>)>,
}

/// The styles of the rendered text.
mod style {
    use super::*;
    pub fn heading(level: u8) -> Style {
        match level {
            1 => Style::new()
                .fg(Color::Yellow)
                .add_modifier(Modifier::BOLD | Modifier::UNDERLINED),
            2 => Style::new().fg(Color::Yellow).add_modifier(Modifier::BOLD),
            _ => Style::new().add_modifier(Modifier::BOLD),
        }
    }
    pub fn code() -> Style {
        Style::new().fg(Color::Cyan)
    }
    pub fn math() -> Style {
        Style::new().fg(Color::LightMagenta)
    }
    pub fn link() -> Style {
        Style::new()
            .fg(Color::LightBlue)
            .add_modifier(Modifier::UNDERLINED)
    }
    pub fn quote() -> Style {
        Style::new().fg(Color::Gray).add_modifier(Modifier::ITALIC)
    }
    pub fn rule() -> Style {
        Style::new().fg(Color::DarkGray)
    }
    pub fn fold() -> Style {
        Style::new()
            .fg(Color::DarkGray)
            .add_modifier(Modifier::ITALIC)
    }
    pub fn experiment() -> Style {
        Style::new()
            .fg(Color::Black)
            .bg(Color::Yellow)
            .add_modifier(Modifier::BOLD)
    }
}

struct Renderer {
    options: Options,
    /// The image being read: its file and the alt text so far.
    image: Option<(String, String)>,
    width: usize,
    out: Rendered,
    /// The inline pieces of the paragraph being built.
    pieces: Vec<Piece>,
    /// Inline style stack (emphasis, strong, link…).
    styles: Vec<Style>,
    /// Prefix of each line: list indentation, quote bars.
    prefix: Vec<String>,
    /// Pending first-line prefix of a list item (`• `, `3. `).
    item_marker: Option<String>,
    lists: Vec<Option<u64>>,
    code: Option<(String, String)>,
    heading: Option<u8>,
    table: Option<Table>,
    /// The link being read, if any.
    link: Option<usize>,
}

#[derive(Default)]
struct Table {
    align: Vec<Alignment>,
    rows: Vec<Vec<String>>,
    cell: String,
    row: Vec<String>,
}

/// How a chapter is rendered, beyond its width.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Options {
    /// Show the library's source excerpts whole instead of one line each.
    pub unfold: bool,
    /// Figures still being computed get a line saying so instead of waiting
    /// for them (the terminal's way; a test draws them at once).
    pub figures_later: bool,
    /// The book's folder, where its pictures are read to be drawn (`None`:
    /// a picture is one line naming it).
    pub images: Option<PathBuf>,
    /// No colour (`NO_COLOR`): the figures tell their curves apart by
    /// glyph, and say so.
    pub plain: bool,
}

/// Renders one chapter (`source` already with includes resolved) at `width`
/// columns (at least 20), library source folded.
pub fn render(source: &str, width: u16) -> Rendered {
    render_with(source, width, &Options::default())
}

/// [`render`] with `options`.
pub fn render_with(source: &str, width: u16, options: &Options) -> Rendered {
    let settings = options.clone();
    let source = normalise_math_delimiters(source);
    let mut options = pulldown_cmark::Options::empty();
    options.insert(pulldown_cmark::Options::ENABLE_TABLES);
    options.insert(pulldown_cmark::Options::ENABLE_MATH);
    options.insert(pulldown_cmark::Options::ENABLE_STRIKETHROUGH);
    options.insert(pulldown_cmark::Options::ENABLE_FOOTNOTES);
    let mut r = Renderer {
        options: settings,
        image: None,
        width: usize::from(width.max(20)),
        out: Rendered::default(),
        pieces: Vec::new(),
        styles: vec![Style::new()],
        prefix: Vec::new(),
        item_marker: None,
        lists: Vec::new(),
        code: None,
        heading: None,
        table: None,
        link: None,
    };
    for event in Parser::new_ext(&source, options) {
        r.event(event);
    }
    r.flush();
    while r.out.lines.last().is_some_and(|l| l.width() == 0) {
        r.out.lines.pop();
    }
    r.out
}

impl Renderer {
    fn style(&self) -> Style {
        *self.styles.last().unwrap_or(&Style::new())
    }

    fn push_style(&mut self, s: Style) {
        let merged = self.style().patch(s);
        self.styles.push(merged);
    }

    fn pop_style(&mut self) {
        if self.styles.len() > 1 {
            self.styles.pop();
        }
    }

    fn blank(&mut self) {
        if self.out.lines.last().is_some_and(|l| l.width() > 0) {
            self.out.lines.push(Line::default());
        }
    }

    fn text(&mut self, text: &str, style: Style) {
        if let Some(t) = self.table.as_mut() {
            t.cell.push_str(text);
            return;
        }
        // Split into words and single spaces so that wrapping can break there;
        // a named function stays on the line of its argument (cos θ).
        let mut word = String::new();
        for c in text.chars() {
            if (c == ' ' || c == '\n') && is_function_word(&word) {
                word.push(NBSP);
                continue;
            }
            if c == ' ' || c == '\n' {
                if !word.is_empty() {
                    self.pieces.push(Piece {
                        text: std::mem::take(&mut word),
                        style,
                        link: self.link,
                    });
                }
                self.pieces.push(Piece {
                    text: " ".into(),
                    style,
                    link: self.link,
                });
            } else {
                word.push(c);
            }
        }
        if !word.is_empty() {
            self.pieces.push(Piece {
                text: word,
                style,
                link: self.link,
            });
        }
    }

    fn line_prefix(&mut self, first: bool) -> String {
        let base: String = self.prefix.concat();
        if first && let Some(marker) = self.item_marker.take() {
            return format!("{base}{marker}");
        }
        if !self.lists.is_empty() {
            return format!("{base}  ");
        }
        base
    }

    /// Wraps the pending pieces into lines.
    fn flush(&mut self) {
        if self.pieces.is_empty() {
            return;
        }
        let pieces = std::mem::take(&mut self.pieces);
        let mut first = true;
        let mut prefix = self.line_prefix(first);
        let mut line: Vec<Span<'static>> = vec![Span::raw(prefix.clone())];
        let mut used = prefix.width();
        let room = self.width.saturating_sub(prefix.width()).max(1);
        // Words: the pieces between spaces, kept together (a code span and
        // the comma after it are one word; the line breaks at spaces only).
        let mut words: Vec<Vec<Piece>> = Vec::new();
        let mut spaces: Vec<Option<Style>> = Vec::new();
        let mut pending_space = None;
        for piece in split_too_long(pieces, room) {
            if piece.text == " " {
                pending_space = Some(piece.style);
                continue;
            }
            if words.is_empty() || pending_space.is_some() {
                spaces.push(pending_space.take());
                words.push(vec![piece]);
            } else if let Some(word) = words.last_mut() {
                word.push(piece);
            }
        }
        // The bytes of the line so far, to place the links' parts.
        let mut bytes = prefix.len();
        for (word, space) in words.into_iter().zip(spaces) {
            let w: usize = word.iter().map(|p| p.text.width()).sum();
            let gap = usize::from(space.is_some() && used > prefix.width());
            if used + gap + w > self.width && used > prefix.width() {
                self.out.lines.push(Line::from(std::mem::take(&mut line)));
                first = false;
                prefix = self.line_prefix(first);
                line.push(Span::raw(prefix.clone()));
                used = prefix.width();
                bytes = prefix.len();
                let joint = if space.is_some() { " " } else { "" };
                self.out.wraps.push((self.out.lines.len(), bytes, joint));
            } else if gap == 1 {
                line.push(Span::styled(" ", space.unwrap_or_default()));
                used += 1;
                bytes += 1;
            }
            for piece in word {
                used += piece.text.width();
                if let Some(id) = piece.link {
                    self.link_part(id, bytes..bytes + piece.text.len());
                }
                bytes += piece.text.len();
                line.push(Span::styled(piece.text, piece.style));
            }
        }
        let _ = first;
        self.out.lines.push(Line::from(line));
    }

    /// Records that link `id` is drawn at `range` of the line being built,
    /// one part with the part before when only a space is between them.
    fn link_part(&mut self, id: usize, range: std::ops::Range<usize>) {
        let line = self.out.lines.len();
        let Some(link) = self.out.links.get_mut(id) else {
            return;
        };
        match link.parts.last_mut() {
            Some((l, r)) if *l == line && r.end + 1 >= range.start => r.end = range.end,
            _ => link.parts.push((line, range)),
        }
    }

    fn display_math(&mut self, tex_source: &str) {
        self.flush();
        let converted = tex::to_unicode(tex_source);
        self.out.unknown_tex.extend(converted.unknown);
        let indent = format!("{}    ", self.prefix.concat());
        for row in converted.text.lines() {
            // Long rows are broken between terms like prose, with a deeper
            // indent: never inside a parenthesis, so never inside a
            // fraction's bracket (a group wider than the line is broken at
            // its own spaces).
            let mut current = indent.clone();
            let room = self.width.saturating_sub(indent.width() + 2).max(1);
            let groups = unbreakable_groups(row);
            let words: Vec<String> = groups
                .split(' ')
                .flat_map(|g| {
                    if g.width() > room {
                        g.split(NBSP).map(str::to_string).collect::<Vec<_>>()
                    } else {
                        vec![g.replace(NBSP, " ")]
                    }
                })
                .collect();
            for word in words.iter().map(String::as_str) {
                if current.width() + word.width() + 1 > self.width && !current.trim().is_empty() {
                    self.out
                        .lines
                        .push(Line::from(Span::styled(current.clone(), style::math())));
                    current = format!("{indent}  ");
                }
                if !current.trim().is_empty() {
                    current.push(' ');
                }
                current.push_str(word);
            }
            self.out
                .lines
                .push(Line::from(Span::styled(current, style::math())));
        }
    }

    fn event(&mut self, event: Event) {
        match event {
            Event::Start(tag) => self.start(tag),
            Event::End(tag) => self.end(tag),
            Event::Text(t) => {
                if let Some((_, code)) = self.code.as_mut() {
                    code.push_str(&t);
                } else if let Some((_, alt)) = self.image.as_mut() {
                    alt.push_str(&t);
                } else {
                    let s = self.style();
                    self.text(&prose_subscripts(&t), s);
                }
            }
            Event::Code(t) => {
                if let Some((_, alt)) = self.image.as_mut() {
                    alt.push_str(&t);
                    return;
                }
                // `spintop: …` (a space after the colon), not a path such
                // as `spintop::physics`.
                if let Some(settings) = t.strip_prefix("spintop: ") {
                    self.experiment(settings.trim());
                    return;
                }
                let s = self.style().patch(style::code());
                self.text(&t, s);
            }
            Event::InlineMath(t) => {
                let c = tex::to_unicode(&t);
                self.out.unknown_tex.extend(c.unknown);
                if let Some((_, alt)) = self.image.as_mut() {
                    alt.push_str(&c.text);
                    return;
                }
                let s = self.style().patch(style::math());
                // An equation in a sentence breaks only between its terms,
                // never inside a parenthesis (or a fraction's bracket).
                self.text(&unbreakable_groups(&c.text.replace('\n', " ")), s);
            }
            Event::DisplayMath(t) => {
                let t = t.to_string();
                self.display_math(&t);
                self.blank();
            }
            Event::Html(h) | Event::InlineHtml(h) => self.html(&h),
            Event::SoftBreak => {
                if let Some((_, alt)) = self.image.as_mut() {
                    alt.push(' ');
                    return;
                }
                let s = self.style();
                self.text(" ", s);
            }
            Event::HardBreak => self.flush(),
            Event::Rule => {
                self.flush();
                self.blank();
                let w = self.width.min(60);
                self.out
                    .lines
                    .push(Line::from(Span::styled("─".repeat(w), style::rule())));
                self.blank();
            }
            Event::FootnoteReference(name) => {
                let s = self.style();
                self.text(&format!("[{name}]"), s);
            }
            Event::TaskListMarker(done) => {
                let s = self.style();
                self.text(if done { "[x] " } else { "[ ] " }, s);
            }
        }
    }

    /// An experiment of the live view, written in the book as inline code
    /// `` `spintop: SETTINGS` `` (its caption is the text around it): the
    /// marker and the settings, and the line `x` scrolls to.
    fn experiment(&mut self, settings: &str) {
        let line = self.out.lines.len();
        self.out.experiments.push((line, settings.to_string()));
        self.pieces
            .push(Piece::new(" ▶ try this ", style::experiment()));
        self.pieces.push(Piece::new(" ", Style::new()));
        let s = self.style().patch(style::code());
        self.text(&format!("[{settings}]"), s);
    }

    fn html(&mut self, html: &str) {
        let h = html.trim();
        // An anchor of its own (`<a id="…">`): a link's target, as a heading is.
        if let Some(at) = h.find("<a id=\"") {
            let id = &h[at + "<a id=\"".len()..];
            if let Some(end) = id.find('"') {
                let line = self.out.lines.len();
                self.out.anchors.push((line, id[..end].to_string()));
            }
        }
        // An <img> (side-by-side figures in raw HTML) is drawn as a Markdown image is.
        let mut rest = h;
        while let Some(at) = rest.find("<img ") {
            let tag = &rest[at..rest[at..].find('>').map_or(rest.len(), |e| at + e)];
            let attr = |name: &str| {
                let key = format!("{name}=\"");
                tag.find(&key).and_then(|i| {
                    let v = &tag[i + key.len()..];
                    v.find('"').map(|e| v[..e].to_string())
                })
            };
            if let Some(src) = attr("src") {
                self.flush();
                self.figure(&src, &attr("alt").unwrap_or_default());
            }
            rest = &rest[at + 5..];
        }
        // A collapsible block's <summary> becomes a line of its own, marked
        // ▾ as an open block is: the terminal shows the block open.
        if let Some(start) = h.find("<summary>")
            && let Some(end) = h[start..].find("</summary>")
        {
            let text = h[start + "<summary>".len()..start + end].trim();
            self.flush();
            self.blank();
            // Word by word, so that a long summary wraps, never clipped.
            let style = style::heading(4);
            for (i, word) in format!("▾ {text}").split(' ').enumerate() {
                if i > 0 {
                    self.pieces.push(Piece::new(" ".to_string(), style));
                }
                self.pieces.push(Piece::new(word.to_string(), style));
            }
            self.flush();
            self.blank();
        }
        // Other HTML (comments, <br>, anchors) has no terminal form.
    }

    fn start(&mut self, tag: Tag) {
        match tag {
            Tag::Paragraph => {}
            Tag::Heading { level, .. } => {
                self.flush();
                self.blank();
                let n = match level {
                    HeadingLevel::H1 => 1,
                    HeadingLevel::H2 => 2,
                    HeadingLevel::H3 => 3,
                    HeadingLevel::H4 => 4,
                    HeadingLevel::H5 => 5,
                    HeadingLevel::H6 => 6,
                };
                self.heading = Some(n);
                self.push_style(style::heading(n));
            }
            Tag::BlockQuote(_) => {
                self.flush();
                self.prefix.push("│ ".into());
                self.push_style(style::quote());
            }
            Tag::CodeBlock(kind) => {
                self.flush();
                let lang = match kind {
                    CodeBlockKind::Fenced(l) => l.to_string(),
                    CodeBlockKind::Indented => String::new(),
                };
                self.code = Some((lang, String::new()));
            }
            Tag::List(start) => {
                self.flush();
                if self.lists.is_empty() {
                    self.blank();
                } else {
                    self.prefix.push("  ".into());
                }
                self.lists.push(start);
            }
            Tag::Item => {
                self.flush();
                let marker = match self.lists.last_mut() {
                    Some(Some(n)) => {
                        let m = format!("{n}. ");
                        *n += 1;
                        m
                    }
                    _ => "• ".to_string(),
                };
                self.item_marker = Some(marker);
            }
            Tag::Emphasis => self.push_style(Style::new().add_modifier(Modifier::ITALIC)),
            Tag::Strong => self.push_style(Style::new().add_modifier(Modifier::BOLD)),
            Tag::Strikethrough => self.push_style(Style::new().add_modifier(Modifier::CROSSED_OUT)),
            Tag::Link { dest_url, .. } => {
                self.push_style(style::link());
                self.link = Some(self.out.links.len());
                self.out.links.push(Link {
                    target: dest_url.to_string(),
                    parts: Vec::new(),
                });
            }
            Tag::Image { dest_url, .. } => {
                self.flush();
                self.image = Some((dest_url.to_string(), String::new()));
            }
            Tag::Table(align) => {
                self.flush();
                self.table = Some(Table {
                    align,
                    ..Table::default()
                });
            }
            Tag::TableHead | Tag::TableRow => {
                if let Some(t) = self.table.as_mut() {
                    t.row.clear();
                }
            }
            Tag::TableCell => {
                if let Some(t) = self.table.as_mut() {
                    t.cell.clear();
                }
            }
            _ => {}
        }
    }

    fn end(&mut self, tag: TagEnd) {
        match tag {
            TagEnd::Paragraph => {
                self.flush();
                if self.lists.is_empty() {
                    self.blank();
                }
            }
            TagEnd::Heading(_) => {
                let text: String = self.pieces.iter().map(|p| p.text.as_str()).collect();
                let level = self.heading.take().unwrap_or(1);
                let line = self.out.lines.len();
                self.flush();
                self.out
                    .headings
                    .push((line, level, text.trim().to_string()));
                self.pop_style();
                self.blank();
            }
            TagEnd::BlockQuote(_) => {
                self.flush();
                self.prefix.pop();
                self.pop_style();
                self.blank();
            }
            TagEnd::CodeBlock => {
                if let Some((lang, code)) = self.code.take() {
                    self.code_block(&lang, &code);
                }
            }
            TagEnd::List(_) => {
                self.flush();
                self.lists.pop();
                if !self.lists.is_empty() {
                    self.prefix.pop();
                } else {
                    self.blank();
                }
            }
            TagEnd::Item => self.flush(),
            TagEnd::Image => {
                if let Some((path, alt)) = self.image.take() {
                    self.figure(&path, &alt);
                }
            }
            TagEnd::Link => {
                self.link = None;
                self.pop_style();
            }
            TagEnd::Emphasis | TagEnd::Strong | TagEnd::Strikethrough => self.pop_style(),
            TagEnd::TableCell => {
                if let Some(t) = self.table.as_mut() {
                    let cell = std::mem::take(&mut t.cell);
                    t.row.push(cell.trim().to_string());
                }
            }
            TagEnd::TableHead | TagEnd::TableRow => {
                if let Some(t) = self.table.as_mut() {
                    let row = std::mem::take(&mut t.row);
                    t.rows.push(row);
                }
            }
            TagEnd::Table => {
                if let Some(t) = self.table.take() {
                    self.draw_table(t);
                }
            }
            _ => {}
        }
    }

    /// An image: Figures 1 and 2 drawn in place from the core's numbers,
    /// every other picture of the book drawn from its vectors (its SVG), each
    /// with its caption; without the book's folder, one line naming it.
    fn figure(&mut self, path: &str, alt: &str) {
        self.flush();
        self.blank();
        let caption = prose_subscripts(&without_colours(alt));
        let width = u16::try_from(self.width).unwrap_or(u16::MAX);
        let drawn = if let Some(number) = super::figures::number_of(path) {
            if self.options.figures_later && !super::figures::ready(number) {
                self.out.figures_pending = true;
            }
            Some(super::figures::lines(
                number,
                width,
                !self.options.figures_later,
                self.options.plain,
            ))
        } else {
            self.options
                .images
                .as_ref()
                .map(|book| super::diagrams::lines(&book.join(path), width))
        };
        match drawn {
            Some(lines) => {
                self.out.lines.extend(lines);
                self.pieces = caption
                    .split_whitespace()
                    .flat_map(|w| {
                        [
                            Piece::new(w, style::quote()),
                            Piece::new(" ", style::quote()),
                        ]
                    })
                    .collect();
            }
            None => {
                // The first sentence names it; the file is in the book.
                let name = caption
                    .split_once(". ")
                    .map_or(caption.as_str(), |(first, _)| first)
                    .trim_end_matches('.');
                let file = path.rsplit('/').next().unwrap_or(path);
                let mut pieces = vec![Piece::new("▣ diagram:", style::heading(4))];
                for w in name.split_whitespace() {
                    pieces.push(Piece::new(" ", style::quote()));
                    pieces.push(Piece::new(w, style::quote()));
                }
                for w in format!("(book/src/figures/{file})").split(' ') {
                    pieces.push(Piece::new(" ", style::quote()));
                    pieces.push(Piece::new(w, style::code()));
                }
                self.pieces = pieces;
            }
        }
        self.flush();
        self.blank();
    }

    fn code_block(&mut self, lang: &str, code: &str) {
        let is_rust = lang.is_empty() || lang.split(',').next().is_some_and(|l| l.trim() == "rust");
        let indent = format!("{}  ", self.prefix.concat());
        let usable = self.width.saturating_sub(indent.width()).max(10);
        let mut code = code.trim_end_matches('\n');
        // The library's own source: one line unless unfolded (`o`).
        if let Some(rest) = code.strip_prefix(FOLD) {
            let (name, body) = rest.split_once('\n').unwrap_or((rest, ""));
            let lines = body.lines().count();
            let mark = if self.options.unfold { "▾" } else { "▸" };
            let head = format!(
                "{mark} {name}: {lines} lines of library source{}",
                if self.options.unfold {
                    ""
                } else {
                    " (o shows them)"
                }
            );
            for line in wrap_code(&head, usable) {
                self.out.lines.push(Line::from(vec![
                    Span::raw(indent.clone()),
                    Span::styled(line, style::fold()),
                ]));
            }
            if !self.options.unfold {
                self.blank();
                return;
            }
            code = body;
        }
        for line in code.lines() {
            // rustdoc's hidden lines: `# code` and a lone `#`.
            if is_rust && (line.trim() == "#" || line.trim_start().starts_with("# ")) {
                continue;
            }
            let line = line.replace('\t', "    ");
            // Long lines are wrapped between tokens, the rest marked ↪.
            for (k, part) in wrap_code(&line, usable).into_iter().enumerate() {
                let mut spans = vec![Span::raw(indent.clone())];
                if k > 0 {
                    spans.push(Span::styled(CONTINUATION, style::rule()));
                }
                spans.push(Span::styled(part, style::code()));
                self.out.lines.push(Line::from(spans));
            }
        }
        self.blank();
    }
}

/// A heading's Markdown as plain text (emphasis, code and links as their
/// words, math as Unicode), for the contents and the search.
pub fn plain_inline(markdown: &str) -> String {
    let mut options = pulldown_cmark::Options::empty();
    options.insert(pulldown_cmark::Options::ENABLE_MATH);
    let mut out = String::new();
    for event in Parser::new_ext(&normalise_math_delimiters(markdown), options) {
        match event {
            Event::Text(t) | Event::Code(t) => out.push_str(&prose_subscripts(&t)),
            Event::InlineMath(t) | Event::DisplayMath(t) => out.push_str(&tex::to_unicode(&t).text),
            Event::SoftBreak | Event::HardBreak => out.push(' '),
            _ => {}
        }
    }
    out.trim().to_string()
}

/// The style of code (spans in it may hold backslashes legitimately).
pub fn code_style() -> Style {
    style::code()
}

/// The style of math, inline and displayed.
pub fn math_style() -> Style {
    style::math()
}

/// The plain text of rendered lines (for tests and `--list`).
pub fn plain(lines: &[Line]) -> String {
    lines
        .iter()
        .map(|l| {
            l.spans
                .iter()
                .map(|s| s.content.as_ref())
                .collect::<String>()
        })
        .collect::<Vec<_>>()
        .join("\n")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_collapsible_block_shows_its_summary_and_its_body() {
        let r = render(
            "<details>\n<summary>Derivation of (3.3)</summary>\n\nThe body, $\\dot x$.\n\n</details>\n",
            80,
        );
        let text = plain(&r.lines);
        assert!(text.contains("▾ Derivation of (3.3)"), "{text}");
        // A summary longer than the line wraps at its spaces, whole.
        let long = render(
            "<details>\n<summary>A summary much longer than the forty columns of this narrow screen</summary>\n\nBody.\n\n</details>\n",
            40,
        );
        let long = plain(&long.lines);
        for w in "A summary much longer than the forty columns of this narrow screen".split(' ') {
            let whole = long.lines().any(|l| l.split_whitespace().any(|x| x == w));
            assert!(whole, "“{w}” whole:\n{long}");
        }
        assert!(text.contains("The body, x\u{307}."), "{text}");
        assert!(
            !text.contains("<summary>") && !text.contains("details>"),
            "{text}"
        );
    }

    #[test]
    fn headings_lists_and_emphasis_lose_their_markup() {
        let r = render(
            "# Title\n\nSome *emphasis* and **strong** text.\n\n- one\n- two\n\n1. first\n2. second\n",
            40,
        );
        let text = plain(&r.lines);
        assert!(text.contains("Title"), "{text}");
        assert!(text.contains("• one"), "{text}");
        assert!(text.contains("2. second"), "{text}");
        assert!(!text.contains('*') && !text.contains('#'), "{text}");
        assert_eq!(r.headings[0].2, "Title");
    }

    #[test]
    fn math_of_both_kinds_becomes_unicode() {
        let r = render(
            "Inline $\\dot{\\Omega}_3 = 0$ and display:\n\n$$\\frac{1}{\\tau}$$\n\nand \\\\[ \\kappa \\\\]\n",
            60,
        );
        let text = plain(&r.lines);
        assert!(text.contains("Ω\u{307}₃ = 0"), "{text}");
        assert!(text.contains("1/τ"), "{text}");
        assert!(text.contains('κ'), "{text}");
        assert!(!text.contains('\\') && !text.contains('$'), "{text}");
    }

    #[test]
    fn lines_never_exceed_the_width() {
        let long = "word ".repeat(200);
        let r = render(
            &format!("{long}\n\n| a | b |\n|---|---|\n| {long} | x |\n"),
            30,
        );
        for line in &r.lines {
            assert!(line.width() <= 30, "{:?}", line);
        }
    }

    #[test]
    fn hidden_rust_lines_are_dropped_and_includes_resolved() {
        let r = render("```rust\n# use hidden;\nlet shown = 1;\n```\n", 40);
        let text = plain(&r.lines);
        assert!(
            text.contains("let shown") && !text.contains("hidden"),
            "{text}"
        );
        let dir = std::env::temp_dir().join(format!("spintop-include-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(
            dir.join("x.rs"),
            "a\n    // ANCHOR: part\n    fn kept() {}\n    // ANCHOR_END: part\nb\n",
        )
        .unwrap();
        let s = resolve_includes("```rust\n{{#include x.rs:part}}\n```", &dir);
        assert_eq!(s, "```rust\nfn kept() {}\n```");
        std::fs::remove_dir_all(&dir).ok();
    }

    /// A display block's line that starts `- ` is a minus, not a list item
    /// (the book's KaTeX reads the block before Markdown does).
    #[test]
    fn a_display_block_is_read_whole() {
        let r = render("Text:\n\n$$\na = b\n- c\n$$\n\nMore.\n", 60);
        let shown = plain(&r.lines);
        assert!(!shown.contains('•') && !shown.contains("$$"), "{shown}");
        assert!(
            shown.contains("a = b − c") || shown.contains("a = b - c"),
            "{shown}"
        );
    }

    #[test]
    fn experiments_are_found_and_shown() {
        let r = render("Text.\n\n- `spintop: ratio=1.5`: a flat top\n\nMore.\n", 40);
        assert_eq!(r.experiments.len(), 1);
        assert_eq!(r.experiments[0].1, "ratio=1.5");
        let shown = plain(&r.lines);
        assert!(
            shown.contains("try this") && shown.contains("[ratio=1.5]: a flat top"),
            "{shown}"
        );
        // The line recorded is the experiment's own.
        assert!(
            plain(&r.lines[r.experiments[0].0..]).starts_with("•"),
            "{shown}"
        );
        // Other inline code, a path in the crate, and HTML comments are not
        // experiments.
        let r = render(
            "`ratio=1.5`, `spintop::physics` and <!-- spintop: ratio=1.5 -->\n",
            40,
        );
        assert!(r.experiments.is_empty());
    }
}

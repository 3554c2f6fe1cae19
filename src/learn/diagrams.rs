//! The book's pictures drawn in the terminal, where the book's web page
//! shows its SVG: the diagrams the core draws from its own vectors
//! ([`spintop::plot::diagram`]: the top's frames, the Euler angles, the
//! cones, the shell) and the charts of the numerics chapters, read from the
//! very files the book shows (`book/src/figures/*.svg`, which a test keeps
//! equal to what the code draws now).
//!
//! The SVG the project writes uses a small part of the format: lines,
//! polylines, polygons, paths of straight segments, rectangles, circles and
//! text. Each is drawn on a Braille canvas (two by four dots a cell) scaled
//! to the text's width, in its colour, its proportions kept; faint grid
//! lines and the white background are left out, and a label that would
//! print over another is left out too, never printed across it.

use crate::live::widgets::Labels;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Style};
use ratatui::symbols::Marker;
use ratatui::text::{Line, Span};
use ratatui::widgets::Widget;
use ratatui::widgets::canvas::{Canvas, Line as CanvasLine};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// The tallest a picture is drawn, in rows: it stays within a page.
pub const MAX_ROWS: u16 = 20;

/// The largest picture file read (the book's largest is about 140 kB).
const MAX_BYTES: u64 = 4 << 20;

/// Why a picture could not be drawn.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum DiagramError {
    /// The file could not be read.
    #[error("cannot read {0}: {1}")]
    Read(String, String),
    /// The file is not SVG this reader understands.
    #[error("{0} is not an SVG picture: {1}")]
    Svg(String, String),
}

/// One stroke of the picture, in the SVG's own coordinates (y down).
#[derive(Debug, Clone, PartialEq)]
struct Stroke {
    points: Vec<(f64, f64)>,
    color: Color,
}

/// A label of the picture.
#[derive(Debug, Clone, PartialEq)]
struct Label {
    at: (f64, f64),
    anchor: Anchor,
    text: String,
    color: Color,
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Anchor {
    Start,
    Middle,
    End,
}

/// A picture read from SVG.
#[derive(Debug, Clone, PartialEq)]
struct Picture {
    size: (f64, f64),
    strokes: Vec<Stroke>,
    labels: Vec<Label>,
}

fn number(node: roxmltree::Node, name: &str) -> Option<f64> {
    node.attribute(name)?
        .trim()
        .trim_end_matches("px")
        .parse()
        .ok()
}

/// `#1f5fbf`, `black`, `none` … as a terminal colour (the nearest of the
/// sixteen), or `None` for no paint and for white (the paper's background).
fn paint(value: Option<&str>) -> Option<Color> {
    let v = value?.trim().to_lowercase();
    let (r, g, b) = match v.as_str() {
        "none" | "white" | "#fff" | "#ffffff" | "transparent" => return None,
        "black" | "#000" => (0, 0, 0),
        "red" => (255, 0, 0),
        "blue" => (0, 0, 255),
        "green" => (0, 128, 0),
        "grey" | "gray" => (128, 128, 128),
        hex if hex.starts_with('#') && hex.len() == 7 => {
            let c = |i: usize| u8::from_str_radix(&hex[i..i + 2], 16).unwrap_or(0);
            (c(1), c(3), c(5))
        }
        _ => (0, 0, 0),
    };
    let (r, g, b) = (i32::from(r), i32::from(g), i32::from(b));
    let (max, min) = (r.max(g).max(b), r.min(g).min(b));
    Some(if max - min < 40 {
        // Greys: black ink reads as the terminal's own text colour.
        if max < 100 { Color::Reset } else { Color::Gray }
    } else if r == max && g > 150 {
        Color::Yellow
    } else if r == max && b > g + 40 {
        Color::Magenta
    } else if r == max {
        Color::LightRed
    } else if g == max && b > 150 {
        Color::Cyan
    } else if g == max {
        Color::LightGreen
    } else if r > 120 && b == max {
        Color::Magenta
    } else {
        Color::LightBlue
    })
}

/// The points of a path of straight segments (M, L, H, V, Z, and their
/// relative forms); curves are not written by the project's SVG.
fn path_points(d: &str) -> Vec<Vec<(f64, f64)>> {
    let mut out: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut tokens = Vec::new();
    let mut current = String::new();
    for c in d.chars() {
        if c.is_ascii_alphabetic() && c != 'e' && c != 'E' {
            if !current.is_empty() {
                tokens.push(std::mem::take(&mut current));
            }
            tokens.push(c.to_string());
        } else if c == ','
            || c.is_whitespace()
            || (c == '-' && !current.is_empty() && !current.ends_with(['e', 'E']))
        {
            if !current.is_empty() {
                tokens.push(std::mem::take(&mut current));
            }
            if c == '-' {
                current.push(c);
            }
        } else {
            current.push(c);
        }
    }
    if !current.is_empty() {
        tokens.push(current);
    }
    let mut command = 'M';
    let mut at = (0.0, 0.0);
    let mut i = 0;
    let num = |k: usize| tokens.get(k).and_then(|t| t.parse::<f64>().ok());
    while i < tokens.len() {
        if let Some(c) = tokens[i].chars().next().filter(char::is_ascii_alphabetic) {
            command = c;
            i += 1;
            if matches!(command, 'Z' | 'z') {
                if let Some(first) = out.last().and_then(|p| p.first().copied()) {
                    if let Some(p) = out.last_mut() {
                        p.push(first);
                    }
                    at = first;
                }
                continue;
            }
        }
        let relative = command.is_ascii_lowercase();
        let base = if relative { at } else { (0.0, 0.0) };
        let (next, used) = match command.to_ascii_uppercase() {
            'M' | 'L' => match (num(i), num(i + 1)) {
                (Some(x), Some(y)) => ((base.0 + x, base.1 + y), 2),
                _ => break,
            },
            'H' => match num(i) {
                Some(x) => ((if relative { at.0 + x } else { x }, at.1), 1),
                None => break,
            },
            'V' => match num(i) {
                Some(y) => ((at.0, if relative { at.1 + y } else { y }), 1),
                None => break,
            },
            _ => break,
        };
        if command.eq_ignore_ascii_case(&'M') {
            out.push(vec![next]);
            // Pairs after a moveto are linetos.
            command = if relative { 'l' } else { 'L' };
        } else if let Some(p) = out.last_mut() {
            p.push(next);
        } else {
            out.push(vec![at, next]);
        }
        at = next;
        i += used;
    }
    out
}

fn points_attr(text: &str) -> Vec<(f64, f64)> {
    let n: Vec<f64> = text
        .split([',', ' ', '\n', '\t'])
        .filter_map(|t| t.trim().parse().ok())
        .collect();
    n.chunks_exact(2).map(|c| (c[0], c[1])).collect()
}

/// Whether an element is drawn: not hidden in `<defs>`, not faint.
fn visible(node: roxmltree::Node) -> bool {
    let faint = number(node, "opacity").is_some_and(|o| o < 0.3)
        || number(node, "stroke-opacity").is_some_and(|o| o < 0.3);
    !faint
        && !node
            .ancestors()
            .any(|a| matches!(a.tag_name().name(), "defs" | "marker" | "title"))
}

/// The strokes an element draws.
fn strokes_of(node: roxmltree::Node) -> Vec<Vec<(f64, f64)>> {
    let n = |name| number(node, name).unwrap_or(0.0);
    match node.tag_name().name() {
        "line" => vec![vec![(n("x1"), n("y1")), (n("x2"), n("y2"))]],
        "polyline" => vec![points_attr(node.attribute("points").unwrap_or(""))],
        "polygon" => {
            let mut p = points_attr(node.attribute("points").unwrap_or(""));
            if let Some(first) = p.first().copied() {
                p.push(first);
            }
            vec![p]
        }
        "path" => path_points(node.attribute("d").unwrap_or("")),
        "rect" => {
            let (x, y, w, h) = (n("x"), n("y"), n("width"), n("height"));
            vec![vec![(x, y), (x + w, y), (x + w, y + h), (x, y + h), (x, y)]]
        }
        "circle" => {
            let (cx, cy, r) = (n("cx"), n("cy"), n("r"));
            vec![
                (0..=24)
                    .map(|k| {
                        let a = f64::from(k) * std::f64::consts::TAU / 24.0;
                        (cx + r * a.cos(), cy + r * a.sin())
                    })
                    .collect(),
            ]
        }
        _ => Vec::new(),
    }
}

fn read_picture(path: &Path) -> Result<Picture, DiagramError> {
    let shown = path.display().to_string();
    let read_error = |e: String| DiagramError::Read(shown.clone(), e);
    let meta = std::fs::metadata(path).map_err(|e| read_error(e.to_string()))?;
    if !meta.is_file() || meta.len() > MAX_BYTES {
        return Err(read_error("not a picture file of the book".into()));
    }
    let text = std::fs::read_to_string(path).map_err(|e| read_error(e.to_string()))?;
    let doc = roxmltree::Document::parse(&text)
        .map_err(|e| DiagramError::Svg(shown.clone(), e.to_string()))?;
    let root = doc.root_element();
    if root.tag_name().name() != "svg" {
        return Err(DiagramError::Svg(shown, "its root is not <svg>".into()));
    }
    let view: Vec<f64> = root
        .attribute("viewBox")
        .map(|v| v.split([' ', ',']).filter_map(|t| t.parse().ok()).collect())
        .unwrap_or_default();
    let size = match view.as_slice() {
        [_, _, w, h] => (*w, *h),
        _ => (
            number(root, "width").unwrap_or(600.0),
            number(root, "height").unwrap_or(400.0),
        ),
    };
    let mut picture = Picture {
        size,
        strokes: Vec::new(),
        labels: Vec::new(),
    };
    for node in root.descendants().filter(|n| n.is_element() && visible(*n)) {
        if node.tag_name().name() == "text" {
            // Rotated labels (a chart's vertical axis title) are left out.
            if node.attribute("transform").is_some() {
                continue;
            }
            let text: String = node
                .descendants()
                .filter(|d| d.is_text())
                .filter_map(|d| d.text())
                .collect();
            let text = text.split_whitespace().collect::<Vec<_>>().join(" ");
            if text.is_empty() {
                continue;
            }
            picture.labels.push(Label {
                at: (
                    number(node, "x").unwrap_or(0.0),
                    number(node, "y").unwrap_or(0.0),
                ),
                anchor: match node.attribute("text-anchor") {
                    Some("middle") => Anchor::Middle,
                    Some("end") => Anchor::End,
                    _ => Anchor::Start,
                },
                text,
                color: paint(node.attribute("fill")).unwrap_or(Color::Reset),
            });
            continue;
        }
        let color = paint(node.attribute("stroke")).or_else(|| {
            paint(node.attribute("fill")).filter(|_| node.tag_name().name() == "circle")
        });
        let Some(color) = color else { continue };
        for points in strokes_of(node) {
            if points.len() >= 2 {
                picture.strokes.push(Stroke { points, color });
            }
        }
    }
    Ok(picture)
}

/// The picture as lines of at most `width` columns, its proportions kept
/// (a cell is about twice as tall as it is wide), at most [`MAX_ROWS`].
fn draw(picture: &Picture, width: u16) -> Vec<Line<'static>> {
    let (w, h) = picture.size;
    let aspect = if w > 0.0 { h / w } else { 1.0 };
    let width = width.max(10);
    let rows = ((f64::from(width) * aspect / 2.0).round() as u16).clamp(4, MAX_ROWS);
    let cols = ((f64::from(rows) * 2.0 / aspect).round() as u16).clamp(10, width);
    let area = Rect::new(0, 0, cols, rows);
    let mut buf = Buffer::empty(Rect::new(0, 0, width, rows));
    let (x_bounds, y_bounds) = ([0.0, w], [0.0, h]);
    let mut labels = Labels::new(x_bounds, y_bounds, (cols, rows));
    let cell_w = w / f64::from(cols.max(1));
    for l in &picture.labels {
        let chars = Span::raw(l.text.as_str()).width() as f64;
        let left = match l.anchor {
            Anchor::Start => l.at.0,
            Anchor::Middle => l.at.0 - 0.5 * chars * cell_w,
            Anchor::End => l.at.0 - chars * cell_w,
        };
        labels.add(
            left,
            h - l.at.1,
            Span::styled(l.text.clone(), Style::new().fg(l.color)),
        );
    }
    let strokes = picture.strokes.clone();
    Canvas::default()
        .marker(Marker::Braille)
        .x_bounds(x_bounds)
        .y_bounds(y_bounds)
        .paint(move |ctx| {
            for s in &strokes {
                for pair in s.points.windows(2) {
                    let (a, b) = (pair[0], pair[1]);
                    ctx.draw(&CanvasLine::new(a.0, h - a.1, b.0, h - b.1, s.color));
                }
            }
            labels.print(ctx);
        })
        .render(area, &mut buf);
    // Centred in the width given.
    let pad = " ".repeat(usize::from((width - cols) / 2));
    super::figures::to_lines(&buf)
        .into_iter()
        .map(|mut line| {
            if !line.spans.is_empty() {
                line.spans.insert(0, Span::raw(pad.clone()));
            }
            line
        })
        .collect()
}

/// The pictures drawn so far, by file and width.
type Drawn = HashMap<(PathBuf, u16), Vec<Line<'static>>>;

/// The picture at `path` drawn `width` columns wide at most; a picture
/// that cannot be read is one line saying why. Drawn once per width.
pub fn lines(path: &Path, width: u16) -> Vec<Line<'static>> {
    static DRAWN: Mutex<Option<Drawn>> = Mutex::new(None);
    let key = (path.to_path_buf(), width);
    if let Some(lines) = DRAWN
        .lock()
        .ok()
        .and_then(|d| d.as_ref().and_then(|m| m.get(&key).cloned()))
    {
        return lines;
    }
    let lines = match read_picture(path) {
        Ok(p) => draw(&p, width),
        Err(e) => vec![Line::from(Span::styled(
            format!("(the picture could not be drawn: {e})"),
            crate::term::theme::error(),
        ))],
    };
    if let Ok(mut d) = DRAWN.lock() {
        d.get_or_insert_with(HashMap::new)
            .insert(key, lines.clone());
    }
    lines
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_of_straight_segments_are_read() {
        assert_eq!(
            path_points("M0,0 L10,0 L10,10 z"),
            vec![vec![(0.0, 0.0), (10.0, 0.0), (10.0, 10.0), (0.0, 0.0)]]
        );
        assert_eq!(
            path_points("m 1 1 h 2 v -3"),
            vec![vec![(1.0, 1.0), (3.0, 1.0), (3.0, -2.0)]]
        );
        assert_eq!(
            path_points("M1e1,-2.5-3,4"),
            vec![vec![(10.0, -2.5), (-3.0, 4.0)]]
        );
    }

    #[test]
    fn colours_are_the_nearest_of_the_terminals() {
        assert_eq!(paint(Some("#ffffff")), None);
        assert_eq!(paint(Some("none")), None);
        assert_eq!(paint(Some("#1f5fbf")), Some(Color::LightBlue));
        assert_eq!(paint(Some("#c0392b")), Some(Color::LightRed));
        assert_eq!(paint(Some("#1e8449")), Some(Color::LightGreen));
        assert_eq!(paint(Some("#888888")), Some(Color::Gray));
        assert_eq!(paint(Some("#000000")), Some(Color::Reset));
    }
}

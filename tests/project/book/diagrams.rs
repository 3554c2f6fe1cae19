//! The book's diagrams: what the generator draws now, shown by a chapter,
//! right-handed, with cones on their rims and no label on another, read from
//! the SVG files themselves.

use super::{book_src, summary_chapters};
use std::collections::BTreeMap;
use std::fs;

/// The diagrams of the book: each is what `spintop::plot::diagram` draws now
/// (refresh with UPDATE_BOOK=1), is an SVG with a title, and is shown by a
/// chapter; the slow-manifold sketch is the one drawn by hand.
#[test]
fn book_diagrams_are_what_the_generator_draws_now_and_are_shown() {
    let update = std::env::var_os("UPDATE_BOOK").is_some();
    let mut text = String::new();
    for chapter in summary_chapters() {
        text.push_str(&fs::read_to_string(book_src().join(&chapter)).unwrap());
    }
    let mut problems = Vec::new();
    for d in spintop::plot::diagram::all() {
        let path = book_src().join(format!("figures/{}.svg", d.name));
        if update {
            fs::write(&path, &d.svg).unwrap();
        } else if fs::read_to_string(&path).unwrap_or_default() != d.svg {
            problems.push(format!(
                "the book's figures/{}.svg is not what the diagram generator draws now; run UPDATE_BOOK=1 cargo test -p spintop-app --test app project::",
                d.name
            ));
        }
        assert!(
            text.contains(&format!("(figures/{}.svg)", d.name)),
            "{}.svg is not shown in any chapter",
            d.name
        );
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
    let sketch = fs::read_to_string(book_src().join("figures/slow-manifold.svg")).unwrap();
    assert!(sketch.starts_with("<svg") && sketch.contains("<title>"));
    assert!(text.contains("(figures/slow-manifold.svg)"));
}

/// One element of an SVG: its name, attributes and text.
#[derive(Debug, Default, Clone)]
struct Element {
    name: String,
    attrs: Vec<(String, String)>,
    text: String,
}

impl Element {
    fn get(&self, key: &str) -> Option<&str> {
        self.attrs
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.as_str())
    }
    fn num(&self, key: &str) -> f64 {
        self.get(key)
            .and_then(|v| v.parse().ok())
            .unwrap_or_else(|| panic!("<{}> has no number {key}", self.name))
    }
    fn has_class(&self, class: &str) -> bool {
        self.get("class")
            .is_some_and(|c| c.split_whitespace().any(|x| x == class))
    }
}

/// The elements of an SVG in document order, each with the `data-frame` of
/// the `<g class="frame">` around it (the generator writes one tag per
/// element, so a small reader does; a malformed file fails loudly).
fn svg_elements(svg: &str) -> Vec<(Option<String>, Element)> {
    let mut out = Vec::new();
    let mut frame: Option<String> = None;
    let mut rest = svg;
    while let Some(start) = rest.find('<') {
        rest = &rest[start + 1..];
        let end = rest.find('>').expect("a tag ends");
        let tag = &rest[..end];
        rest = &rest[end + 1..];
        if tag.starts_with('/') {
            if tag == "/g" {
                frame = None;
            }
            continue;
        }
        let name: String = tag
            .chars()
            .take_while(|c| !c.is_whitespace() && *c != '/')
            .collect();
        let mut attrs = Vec::new();
        let mut a = &tag[name.len()..];
        while let Some(eq) = a.find("=\"") {
            let key = a[..eq].trim().to_string();
            let after = &a[eq + 2..];
            let close = after.find('"').expect("an attribute ends");
            attrs.push((key, after[..close].to_string()));
            a = &after[close + 1..];
        }
        let mut e = Element {
            name: name.clone(),
            attrs,
            text: String::new(),
        };
        if name == "text" || name == "title" {
            let close = rest.find('<').expect("text ends");
            e.text = rest[..close]
                .replace("&lt;", "<")
                .replace("&gt;", ">")
                .replace("&amp;", "&");
        }
        if name == "g" && e.has_class("frame") {
            frame = e.get("data-frame").map(str::to_string);
        }
        out.push((frame.clone(), e));
    }
    out
}

/// The page points of a path's `d` ("M x,y L x,y …").
fn path_points(d: &str) -> Vec<(f64, f64)> {
    d.split(['M', 'L'])
        .filter(|p| !p.trim().is_empty())
        .map(|p| {
            let (x, y) = p.trim().split_once(',').expect("x,y");
            (x.parse().unwrap(), y.parse().unwrap())
        })
        .collect()
}

/// A box on the page: left, top, right, bottom.
type PageBox = (f64, f64, f64, f64);

/// The box a label takes on the page, from its position, size and anchor
/// (an estimate on the generous side: 0.6 em per character, none for a
/// combining accent).
fn label_box(e: &Element) -> PageBox {
    let size = e.num("font-size");
    let width: f64 = e
        .text
        .chars()
        .map(|c| match c {
            '\u{300}'..='\u{36f}' => 0.0,
            ' ' => 0.3,
            _ => 0.6,
        })
        .sum::<f64>()
        * size;
    let x = e.num("x");
    let left = match e.get("text-anchor") {
        Some("middle") => x - width / 2.0,
        Some("end") => x - width,
        _ => x,
    };
    let y = e.num("y");
    (left, y - 0.8 * size, left + width, y + 0.25 * size)
}

/// Everything wrong with one diagram's geometry, read from its SVG alone.
fn diagram_problems(name: &str, elements: &[(Option<String>, Element)]) -> Vec<String> {
    [frame_problems, arc_problems, cone_problems, label_problems]
        .iter()
        .flat_map(|check| check(name, elements))
        .collect()
}

/// Frames: rebuild each axis as (dx, up, toward) and check the triple.
fn frame_problems(name: &str, elements: &[(Option<String>, Element)]) -> Vec<String> {
    let mut problems = Vec::new();
    let mut frames: BTreeMap<String, Vec<(String, [f64; 3])>> = BTreeMap::new();
    for (frame, e) in elements {
        if let (Some(frame), true) = (frame, e.has_class("axis")) {
            let v = [
                e.num("x2") - e.num("x1"),
                -(e.num("y2") - e.num("y1")),
                e.num("data-depth"),
            ];
            frames
                .entry(frame.clone())
                .or_default()
                .push((e.get("data-axis").unwrap_or("?").to_string(), v));
        }
    }
    if frames.is_empty() {
        problems.push(format!("{name}: no frame drawn"));
    }
    for (frame, axes) in &frames {
        if axes.len() != 3 {
            problems.push(format!("{name}: frame {frame} has {} axes", axes.len()));
            continue;
        }
        let unit = |v: [f64; 3]| {
            let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            [v[0] / n, v[1] / n, v[2] / n]
        };
        let (a, b, c) = (unit(axes[0].1), unit(axes[1].1), unit(axes[2].1));
        let dot = |p: [f64; 3], q: [f64; 3]| p[0] * q[0] + p[1] * q[1] + p[2] * q[2];
        for (p, q) in [(a, b), (b, c), (c, a)] {
            if dot(p, q).abs() > 0.02 {
                problems.push(format!("{name}: frame {frame} is not orthogonal"));
            }
        }
        let det = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
            + a[2] * (b[0] * c[1] - b[1] * c[0]);
        if det < 0.98 {
            problems.push(format!(
                "{name}: frame {frame} ({}, {}, {}) is left-handed on the page (det {det:.3})",
                axes[0].0, axes[1].0, axes[2].0
            ));
        }
        if frame == "lab" {
            // Seen from above: z goes up the page and leans toward the viewer.
            let z = axes[2].1;
            if !(z[1] > 0.0 && z[2] > 0.0) {
                problems.push(format!("{name}: the lab frame is not seen from above"));
            }
        }
    }
    problems
}

/// Arcs about lab z turn counterclockwise on the page, as seen from above.
fn arc_problems(name: &str, elements: &[(Option<String>, Element)]) -> Vec<String> {
    let mut problems = Vec::new();
    for (_, e) in elements {
        if e.has_class("arc") && e.get("data-about") == Some("z") {
            let pts = path_points(e.get("d").unwrap());
            let (cx, cy) = (e.num("data-cx"), e.num("data-cy"));
            let (s, t) = (pts[0], pts[pts.len() - 1]);
            // y down on the page: counterclockwise is a negative cross product.
            let cross = (s.0 - cx) * (t.1 - cy) - (s.1 - cy) * (t.0 - cx);
            if cross >= 0.0 {
                problems.push(format!("{name}: an arc about z turns clockwise"));
            }
        }
    }
    problems
}

/// Cones: each edge ends on its rim, and touches it there (the whole rim
/// on one side of the edge's line).
fn cone_problems(name: &str, elements: &[(Option<String>, Element)]) -> Vec<String> {
    let mut problems = Vec::new();
    let mut rims: BTreeMap<String, Vec<(f64, f64)>> = BTreeMap::new();
    for (_, e) in elements {
        if e.has_class("rim") {
            rims.entry(e.get("data-cone").unwrap().to_string())
                .or_default()
                .extend(path_points(e.get("d").unwrap()));
        }
    }
    for (_, e) in elements {
        if !e.has_class("cone-edge") {
            continue;
        }
        let cone = e.get("data-cone").unwrap();
        let Some(rim) = rims.get(cone) else {
            problems.push(format!("{name}: cone {cone} has an edge and no rim"));
            continue;
        };
        let (a, b) = ((e.num("x1"), e.num("y1")), (e.num("x2"), e.num("y2")));
        let gap = rim
            .windows(2)
            .map(|w| point_segment_distance(b, w[0], w[1]))
            .fold(f64::INFINITY, f64::min);
        if gap > 0.75 {
            problems.push(format!(
                "{name}: an edge of cone {cone} misses its rim by {gap:.2} px"
            ));
        }
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let len = dx.hypot(dy);
        let side = |p: (f64, f64)| (dx * (p.1 - a.1) - dy * (p.0 - a.0)) / len;
        let (lo, hi) = rim
            .iter()
            .map(|&p| side(p))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), s| {
                (l.min(s), h.max(s))
            });
        if lo < -0.75 && hi > 0.75 {
            problems.push(format!(
                "{name}: an edge of cone {cone} cuts across its rim"
            ));
        }
    }
    problems
}

/// Labels: no two overlap.
fn label_problems(name: &str, elements: &[(Option<String>, Element)]) -> Vec<String> {
    let mut problems = Vec::new();
    let labels: Vec<(&Element, PageBox)> = elements
        .iter()
        .filter(|(_, e)| e.name == "text" && e.has_class("label") && e.text.trim() != "+")
        .map(|(_, e)| (e, label_box(e)))
        .collect();
    for (i, (e, p)) in labels.iter().enumerate() {
        for (f, q) in &labels[i + 1..] {
            if p.0 < q.2 && q.0 < p.2 && p.1 < q.3 && q.1 < p.3 {
                problems.push(format!(
                    "{name}: labels '{}' and '{}' overlap",
                    e.text, f.text
                ));
            }
        }
    }
    problems
}

fn point_segment_distance(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let len2 = dx * dx + dy * dy;
    let t = if len2 == 0.0 {
        0.0
    } else {
        (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / len2).clamp(0.0, 1.0)
    };
    (p.0 - a.0 - t * dx).hypot(p.1 - a.1 - t * dy)
}

/// Every generated diagram in the book is right-handed, its cones meet their
/// rims, and its labels do not overlap: read from the SVG files themselves.
#[test]
fn book_diagrams_are_right_handed_with_cones_on_their_rims_and_no_overlapping_labels() {
    let mut problems = Vec::new();
    let mut cones = 0;
    for name in spintop::plot::diagram::NAMES {
        let svg = fs::read_to_string(book_src().join(format!("figures/{name}.svg"))).unwrap();
        cones += svg.matches("class=\"cone-edge\"").count();
        problems.extend(
            diagram_problems(name, &svg_elements(&svg))
                .into_iter()
                // The shell is a plane sketch: no frame to check.
                .filter(|p| !(name == "shell-model" && p.contains("no frame drawn"))),
        );
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
    assert_eq!(
        cones, 6,
        "the precession cone and the two cones of the free top"
    );
}

/// The checks can fail: a diagram mirrored left to right is left-handed and
/// its arcs about z turn the wrong way; a moved cone edge misses its rim; a
/// label put on top of another overlaps it.
#[test]
fn book_diagram_checks_catch_a_mirror_a_loose_edge_and_a_label_on_a_label() {
    let svg = fs::read_to_string(book_src().join("figures/precession-cone.svg")).unwrap();
    let elements = svg_elements(&svg);
    assert!(diagram_problems("precession-cone", &elements).is_empty());
    // Every page x mirrored (x -> 600 - x), the depths kept: a left-handed drawing.
    let mirrored: Vec<(Option<String>, Element)> = elements
        .iter()
        .map(|(f, e)| {
            let mut e = e.clone();
            for (k, v) in e.attrs.iter_mut() {
                if ["x1", "x2", "x", "data-cx"].contains(&k.as_str()) {
                    *v = format!("{:.1}", 600.0 - v.parse::<f64>().unwrap());
                } else if k == "d" && v.starts_with('M') && !v.contains('z') {
                    *v = path_points(v)
                        .iter()
                        .enumerate()
                        .map(|(i, p)| {
                            format!(
                                "{}{:.1},{:.1}",
                                if i == 0 { "M" } else { "L" },
                                600.0 - p.0,
                                p.1
                            )
                        })
                        .collect::<Vec<_>>()
                        .join(" ");
                }
            }
            (f.clone(), e)
        })
        .collect();
    let found = diagram_problems("mirror", &mirrored);
    assert!(found.iter().any(|p| p.contains("left-handed")), "{found:?}");
    assert!(found.iter().any(|p| p.contains("clockwise")), "{found:?}");
    // A cone edge whose end is moved 4 px off its rim, across the edge.
    let mut loose = elements.clone();
    let edge = loose
        .iter_mut()
        .find(|(_, e)| e.has_class("cone-edge"))
        .unwrap();
    let (x1, y1, x2, y2) = (
        edge.1.num("x1"),
        edge.1.num("y1"),
        edge.1.num("x2"),
        edge.1.num("y2"),
    );
    let len = (x2 - x1).hypot(y2 - y1);
    for (k, v) in edge.1.attrs.iter_mut() {
        match k.as_str() {
            "x2" => *v = format!("{:.1}", x2 - 4.0 * (y2 - y1) / len),
            "y2" => *v = format!("{:.1}", y2 + 4.0 * (x2 - x1) / len),
            _ => {}
        }
    }
    let found = diagram_problems("loose", &loose);
    assert!(
        found.iter().any(|p| p.contains("misses its rim")),
        "{found:?}"
    );
    // A second label on top of the first.
    let mut doubled = elements.clone();
    let first = doubled
        .iter()
        .find(|(_, e)| e.has_class("label"))
        .unwrap()
        .clone();
    doubled.push(first);
    let found = diagram_problems("doubled", &doubled);
    assert!(found.iter().any(|p| p.contains("overlap")), "{found:?}");
}

//! The book's structure: its chapters in `SUMMARY.md`'s order, a chapter
//! found by whatever the reader types (a section of the paper, the number
//! the header shows, a file name, a title), and each chapter's headings
//! with the anchors mdBook gives them.

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

    /// The chapter's scene (see [`super::scene::Scene::of`]).
    pub fn scene(&self) -> super::scene::Scene {
        super::scene::Scene::of(&self.file)
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

/// Finds a chapter by what the reader types, case-insensitive:
///
/// 1. the chapter's number as the header counts it (`9` for "chapter 9 of
///    25"; also `#9`, `chapter 9`): a bare whole number is always this;
/// 2. a section of the paper: `4.1`, `4.2`, `A`, or any section with its
///    sign or word (`§2`, `§5`, `section 5`, `sec 5`);
/// 3. its file name, with or without `.md` (`section-5`);
/// 4. its title, whole or a word-start of it (`numerical methods`,
///    `asymmetric`), when only one title fits.
pub fn find_chapter(chapters: &[Chapter], wanted: &str) -> Option<usize> {
    let w = wanted.trim().to_lowercase();
    let w = w.as_str();
    let number = w
        .strip_prefix('#')
        .or_else(|| w.strip_prefix("chapter "))
        .or_else(|| w.strip_prefix("ch"))
        .unwrap_or(w)
        .trim();
    if let Ok(n) = number.parse::<usize>() {
        return (1..=chapters.len()).contains(&n).then(|| n - 1);
    }
    let marked = w
        .strip_prefix('§')
        .or_else(|| w.strip_prefix("section "))
        .or_else(|| w.strip_prefix("sec "))
        .map(str::trim);
    // A bare number was taken above as the header's; a section written
    // bare is one no chapter number can be (4.1, 4.2, A).
    let section = marked.unwrap_or(w);
    if let Some(i) = chapters
        .iter()
        .position(|c| c.section().is_some_and(|s| s.eq_ignore_ascii_case(section)))
    {
        return Some(i);
    }
    if marked.is_some() {
        return None;
    }
    if let Some(i) = chapters.iter().position(|c| {
        let file = c.file.to_lowercase();
        file == w || file.strip_suffix(".md") == Some(w)
    }) {
        return Some(i);
    }
    if w.is_empty() {
        return None;
    }
    match titled(chapters, w).as_slice() {
        [one] => Some(*one),
        _ => None,
    }
}

/// The chapters whose titles hold `wanted` (lower-cased) as words: the one
/// titled so exactly, else every one a word of whose title starts with it.
fn titled(chapters: &[Chapter], w: &str) -> Vec<usize> {
    let titles: Vec<String> = chapters.iter().map(|c| c.title.to_lowercase()).collect();
    if let Some(i) = titles.iter().position(|t| t == w) {
        return vec![i];
    }
    (0..titles.len())
        .filter(|&i| {
            titles[i].starts_with(w)
                || titles[i].contains(&format!(" {w}"))
                || titles[i].contains(&format!(":{w}"))
        })
        .collect()
}

/// The chapters `wanted` could mean when [`find_chapter`] finds none for
/// it because more than one title holds it: "number title" of each.
pub fn candidates(chapters: &[Chapter], wanted: &str) -> Vec<String> {
    let w = wanted.trim().to_lowercase();
    if w.is_empty() {
        return Vec::new();
    }
    let fits = titled(chapters, &w);
    if fits.len() < 2 {
        return Vec::new();
    }
    fits.into_iter()
        .map(|i| format!("{} “{}”", i + 1, chapters[i].title))
        .collect()
}

/// The sections of the paper as `--chapter` takes them (`§2, §3, 4.1,
/// 4.2, §5, A`): a whole number bare would be a chapter's number.
pub fn section_names(chapters: &[Chapter]) -> String {
    chapters
        .iter()
        .filter_map(Chapter::section)
        .map(|s| {
            if s.parse::<usize>().is_ok() {
                format!("§{s}")
            } else {
                s.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// When `wanted` is a bare number that is also a section of the paper,
/// which chapter that section is and how to open it ("Section 5 is chapter
/// 7: --chapter §5 opens it"): the number opened the header's chapter.
pub fn ambiguity(chapters: &[Chapter], wanted: &str) -> Option<String> {
    let w = wanted.trim();
    let n: usize = w.parse().ok()?;
    let found = find_chapter(chapters, w)?;
    let section = chapters.iter().position(|c| c.section() == Some(w))?;
    (found != section).then(|| {
        format!(
            "chapter {n} of {}, as the header counts; Section {w} is chapter {} (--chapter §{w} or section-{w} opens it)",
            chapters.len(),
            section + 1
        )
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
                out.push((level, super::markdown::plain_inline(h.trim())));
                break;
            }
        }
    }
    out
}

/// The anchor mdBook gives a heading: lower case, spaces as dashes, only
/// letters, digits, `-` and `_` kept (`What auto chooses` →
/// `what-auto-chooses`).
pub fn slug(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter_map(|c| match c {
            ' ' => Some('-'),
            c if c.is_alphanumeric() || c == '-' || c == '_' => Some(c),
            _ => None,
        })
        .collect()
}

/// Where the reader was when a link or the contents took them elsewhere
/// (what Backspace goes back to).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Place {
    /// The chapter.
    pub(crate) chapter: usize,
    /// The first line shown, and the chapter's lines then (at another
    /// width the same fraction is shown).
    pub(crate) line: usize,
    pub(crate) total: usize,
    /// The link in focus then (the one followed).
    pub(crate) link: Option<usize>,
}

/// One line of the contents: a chapter, or one of its headings.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Entry {
    /// The chapter.
    pub chapter: usize,
    /// The heading (level, text), or `None` for the chapter itself.
    pub heading: Option<(u8, String)>,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn book() -> Vec<Chapter> {
        chapters(
            "# Summary\n[Preface](preface.md)\n# Part\n- [The question](question.md)\n\
             - [Section 2: two laws](section-2.md)\n- [Section 3: motion](section-3.md)\n\
             - [Section 4.2: the reduced top](section-4-2.md)\n- [Numerical methods](numerical-methods.md)\n\
             - [Where methods fail](where-methods-fail.md)\n- [Appendix: the shell](appendix.md)\n",
        )
    }

    #[test]
    fn a_chapter_is_found_by_section_number_file_or_title() {
        let b = book();
        assert_eq!(find_chapter(&b, "2"), Some(1), "the header's number wins");
        assert_eq!(find_chapter(&b, "§2"), Some(2), "a section by its sign");
        assert_eq!(find_chapter(&b, "4.2"), Some(4), "no chapter number is 4.2");
        assert_eq!(find_chapter(&b, "§4.2"), Some(4));
        assert_eq!(find_chapter(&b, "a"), Some(7));
        assert_eq!(find_chapter(&b, "Section 3"), Some(3));
        assert_eq!(find_chapter(&b, "section-3"), Some(3), "its file");
        assert_eq!(find_chapter(&b, "§4.1"), None, "no such section here");
        assert_eq!(find_chapter(&b, "6"), Some(5), "the header's number");
        assert_eq!(find_chapter(&b, "#2"), Some(1));
        assert_eq!(find_chapter(&b, "chapter 3"), Some(2));
        assert_eq!(find_chapter(&b, "Numerical-Methods.md"), Some(5));
        assert_eq!(find_chapter(&b, "NUMERICAL METHODS"), Some(5));
        assert_eq!(find_chapter(&b, "where"), Some(6));
        assert_eq!(find_chapter(&b, "methods"), None, "two titles fit");
        assert_eq!(find_chapter(&b, "99"), None);
        let note = ambiguity(&b, "3").unwrap();
        assert!(
            note.contains("Section 3 is chapter 4 (--chapter §3"),
            "{note}"
        );
        assert_eq!(find_chapter(&b, "§3"), Some(3), "as the note says");
        assert_eq!(ambiguity(&b, "6"), None, "no Section 6");
        assert_eq!(section_names(&b), "§2, §3, 4.2, A");
    }

    #[test]
    fn anchors_are_mdbooks() {
        assert_eq!(slug("What auto chooses"), "what-auto-chooses");
        assert_eq!(slug("The (4.12) model: Ω₀"), "the-412-model-ω₀");
    }
}

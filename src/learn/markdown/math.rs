//! The book's math delimiters made one kind before Markdown reads the text.

/// `\\[ … \\]` → `$$ … $$` and `\\( … \\)` → `$ … $`, outside code, so that
/// MathJax-style math (which needs doubled backslashes in mdBook's Markdown)
/// reaches the same math events as `$` math. A display block between lines
/// that are `$$` alone is joined into one line, as the book's KaTeX reads it
/// before Markdown does: a line of it that starts `- ` is no list item.
pub(super) fn normalise_math_delimiters(source: &str) -> String {
    let mut out = String::with_capacity(source.len());
    let mut in_fence = false;
    let mut display: Option<String> = None;
    for line in source.split_inclusive('\n') {
        if line.trim_start().starts_with("```") && display.is_none() {
            in_fence = !in_fence;
        }
        if !in_fence && line.trim() == "$$" {
            match display.take() {
                None => display = Some("$$".to_string()),
                Some(math) => {
                    out.push_str(&math);
                    out.push_str(" $$\n");
                }
            }
            continue;
        }
        if let Some(math) = &mut display {
            math.push(' ');
            math.push_str(line.trim());
            continue;
        }
        if in_fence {
            out.push_str(line);
        } else {
            out.push_str(
                &line
                    .replace(r"\\[", "$$")
                    .replace(r"\\]", "$$")
                    .replace(r"\\(", "$")
                    .replace(r"\\)", "$"),
            );
        }
    }
    if let Some(math) = display {
        out.push_str(&math);
    }
    out
}

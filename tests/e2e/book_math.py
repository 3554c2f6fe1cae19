"""The book's equations, rendered at build time and read offline in a browser.

Run after `mdbook build book` (`.ci/run` does both):

    python3 tests/e2e/book_math.py [--screenshots DIR]

Every page of the built book is opened from disk (file://) in headless
Chromium with every network request refused, and must hold:

- no raw TeX: no `$$`, `\\[`, `\\(` or a backslash command left in the text a
  reader sees, and no KaTeX error;
- the typeset equations as MathML that the browser lays out: every <math>
  element of a page has a real size on screen (a <math> the browser did not
  understand collapses to nothing);
- on the pages that carry them, the equations the book promises, by number:
  every numbered equation of the paper the book cites, (2.1)-(2.9),
  (3.1)-(3.5), (4.1)-(4.18), (A.1)-(A.3), on its chapter's page (ranges
  such as (4.2)-(4.4) typeset together). The Rust test
  `book_every_cited_equation_is_typeset` checks the same on the sources.

With --screenshots, a picture of each equation-bearing page is written there
(look at them: a check that passes on an unreadable page is no check).
"""

from __future__ import annotations

import pathlib
import re
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from browser import chromium  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]
BOOK = ROOT / "book" / "book"

# The equations each page must typeset, by their number in the paper.
PROMISED = {
    "section-2.html": ["(2.1)", "(2.2)", "(2.3), (2.4)", "(2.5)", "(2.6)", "(2.7)", "(2.8)", "(2.9)"],
    "section-3.html": ["(3.1)", "(3.2)", "(3.3)", "(3.4)", "(3.5)"],
    "section-4-1.html": ["(4.1)", "(4.2)–(4.4)", "(4.5), (4.6)", "(4.7)", "(4.8)", "(4.9)", "(4.10)", "(4.11)"],
    "section-4-2.html": ["(4.12)–(4.14)", "(4.15)", "(4.16)", "(4.17)", "(4.18)"],
    "appendix.html": ["(A.1)", "(A.2)", "(A.3)"],
    "solutions-section-3.html": [],
    "solutions-section-4-2.html": [],
}

RAW_TEX = re.compile(r"\$\$|\\\[|\\\(|\\(frac|dot|ddot|mathbf|boldsymbol|Omega|kappa|tau|left|right)\b")


def main() -> int:
    shots = None
    if "--screenshots" in sys.argv:
        shots = pathlib.Path(sys.argv[sys.argv.index("--screenshots") + 1])
        shots.mkdir(parents=True, exist_ok=True)
    pages = sorted(p for p in BOOK.glob("*.html") if p.name not in ("print.html", "404.html", "toc.html"))
    if not pages:
        print(f"book_math: no pages under {BOOK}: run `mdbook build book` first")
        return 1
    problems: list[str] = []
    total_math = 0
    # The built book references nothing outside itself: no remote script,
    # stylesheet, font or image (links to cite a source are fine).
    remote = re.compile(r"""<(?:script|link|img|iframe)[^>]*(?:src|href)=["']https?://|url\(\s*["']?https?://""")
    for path in sorted(BOOK.rglob("*")):
        if path.suffix in (".html", ".css", ".js") and path.is_file():
            for m in remote.finditer(path.read_text(errors="replace")):
                problems.append(f"{path.relative_to(BOOK)}: a remote reference: {m.group(0)[:80]}")
    with chromium(width=1100, height=1400) as page:
        # Offline: any request that is not a file on disk is refused.
        page.route(re.compile(r"^(?!file:).*"), lambda route: route.abort())
        for path in pages:
            page.goto(path.as_uri())
            text = page.inner_text("main")
            for m in RAW_TEX.finditer(text):
                # Code blocks may hold Rust, never TeX; inline code is checked too.
                context = text[max(0, m.start() - 40) : m.end() + 40].replace("\n", " ")
                problems.append(f"{path.name}: raw TeX on the page: ...{context}...")
            if "katex-error" in page.content() or "ParseError" in text:
                problems.append(f"{path.name}: a KaTeX error is on the page")
            sizes = page.eval_on_selector_all(
                "main math", "els => els.map(e => { const r = e.getBoundingClientRect(); return [r.width, r.height]; })"
            )
            total_math += len(sizes)
            if sizes:
                # The book's math font (accents above their letters, not in them).
                loaded = page.evaluate(
                    "document.fonts.ready.then(() => Array.from(document.fonts)"
                    ".some(f => f.family.replace(/\"/g, '') === 'SpintopMath' && f.status === 'loaded'))"
                )
                if not loaded:
                    problems.append(f"{path.name}: the math font SpintopMath did not load")
            flat = [s for s in sizes if s[0] < 2 or s[1] < 2]
            if flat:
                problems.append(f"{path.name}: {len(flat)} of {len(sizes)} <math> elements have no size on screen")
            for number in PROMISED.get(path.name, []):
                annotation = page.eval_on_selector_all(
                    "main math", "els => els.map(e => e.textContent).join(' ')"
                )
                if number not in annotation:
                    problems.append(f"{path.name}: equation {number} is not typeset")
            if shots is not None and path.name in PROMISED:
                page.screenshot(path=str(shots / f"{path.stem}.png"), full_page=False)
                first = page.query_selector("main math[display=block]")
                if first is not None:
                    first.scroll_into_view_if_needed()
                    page.screenshot(path=str(shots / f"{path.stem}-equation.png"))
    for p in problems:
        print(f"book_math: {p}")
    if problems:
        return 1
    print(f"book_math: {len(pages)} pages, {total_math} typeset formulas, no raw TeX, all laid out, offline")
    return 0


if __name__ == "__main__":
    sys.exit(main())

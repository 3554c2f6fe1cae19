"""The book's equations, rendered at build time and read offline in a browser.

Run after `mdbook build book` (`.ci/run` does both):

    python3 tests/e2e/book_math.py [--screenshots DIR]

Every page of the built book is opened from disk (file://) in headless
Chromium, 100 % zoom, with every request that is not a file refused and
counted, and must hold:

- nothing fetched: no request leaves the disk (KaTeX's stylesheet and fonts
  ship in the book, src/katex/), and no file references a remote script,
  stylesheet, font or image;
- no raw TeX: no `$$`, `\\[`, `\\(` or a backslash command left in the text a
  reader sees, and no KaTeX error;
- KaTeX's own layout: every formula has its HTML rendering (`.katex-html`,
  the MathML beside it is for screen readers) with a real size on screen, and
  KaTeX's fonts are loaded;
- bold where the TeX says bold: every symbol under `\\mathbf`, `\\boldsymbol`
  or the book's `\\bfrak` is drawn with font weight 700 in a bold face that
  loaded, and every formula whose TeX asks for bold has such a symbol;
- aligned rows aligned: in every aligned display, the '=' signs that open the
  cells of one column stand at the same x, within 1.5 px;
- accents in the math, not in the prose: no combining mark (the dot of Ω̇,
  the tilde of Ω̃₃) in the visible text outside a formula or code, where a
  browser's text font puts it beside the letter or nowhere;
- on the pages that carry them, the equations the book promises, by number:
  every numbered equation of the paper, (2.1)-(2.9), (3.1)-(3.5),
  (4.1)-(4.18), (A.1)-(A.3), on its chapter's page, each line of a numbered
  system with its own number. The Rust test
  `book_every_cited_equation_is_typeset` checks the same on the sources.

With --screenshots, Sections 3, 4.1, 4.2 and the appendix are saved whole, at
100 % zoom with every derivation (<details>) opened, and every other
equation-bearing page at its first display. Look at them: a check that passes
on an unreadable page is no check.
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
    "section-2.html": ["2.1", "2.2", "2.3", "2.4", "2.5", "2.6", "2.7", "2.8", "2.9"],
    "section-3.html": ["3.1", "3.2", "3.3", "3.4", "3.5"],
    "section-4-1.html": [f"4.{n}" for n in range(1, 12)],
    "section-4-2.html": [f"4.{n}" for n in range(12, 19)],
    "appendix.html": ["A.1", "A.2", "A.3"],
}
# Saved whole, derivations opened.
WHOLE = ["section-3.html", "section-4-1.html", "section-4-2.html", "appendix.html"]

RAW_TEX = re.compile(r"\$\$|\\\[|\\\(|\\(frac|dot|ddot|mathbf|boldsymbol|bfrak|Omega|kappa|tau|left|right|tag)\b")
COMBINING = re.compile("[\u0300-\u036f\u20d0-\u20ff]")
BOLD_TEX = re.compile(r"\\(mathbf|boldsymbol|bfrak)\b")

# Per formula: its TeX, whether its HTML has a size, how many bold-marked
# symbols it has and which of them are not drawn bold.
FORMULAS_JS = """
els => els.map(k => {
    const html = k.querySelector('.katex-html');
    const ann = k.querySelector('annotation');
    const r = html ? html.getBoundingClientRect() : {width: 0, height: 0};
    const bold = Array.from(k.querySelectorAll(
        '.katex-html .mathbf, .katex-html .boldsymbol, .katex-html .bfrak .mathfrak'));
    const thin = bold.filter(b => parseInt(getComputedStyle(b).fontWeight, 10) < 700)
        .map(b => b.textContent);
    const faces = Array.from(new Set(bold.map(b => getComputedStyle(b).fontFamily)));
    return {tex: ann ? ann.textContent : '', w: r.width, h: r.height,
            bold: bold.length, thin: thin, faces: faces};
})
"""

# Per aligned display: for each left-aligned column, the x of the '=' that
# opens each of its cells (the first relation of the cell, not a script's).
ALIGNED_JS = """
() => Array.from(document.querySelectorAll('main .katex-display .katex-html .mtable')).map(t => {
    const tex = (t.closest('.katex').querySelector('annotation') || {}).textContent || '';
    const columns = Array.from(t.querySelectorAll(':scope > .col-align-l')).map(col => {
        const cells = Array.from(col.querySelectorAll(':scope > .vlist-t > .vlist-r > .vlist > span'));
        return cells.map(cell => {
            const rel = cell.querySelector('.mrel:not(.mtight)');
            return rel && rel.textContent === '=' ? rel.getBoundingClientRect().left : null;
        }).filter(x => x !== null);
    });
    return {tex: tex, columns: columns};
})
"""

# The visible text outside formulas and code.
PROSE_JS = """
() => {
    const out = [];
    const walker = document.createTreeWalker(document.querySelector('main'), NodeFilter.SHOW_TEXT);
    while (walker.nextNode()) {
        const n = walker.currentNode;
        if (n.parentElement.closest('.katex, code, pre, script, style')) continue;
        out.push(n.textContent);
    }
    return out.join(' ');
}
"""

FACES_JS = """
() => document.fonts.ready.then(() => Array.from(document.fonts)
    .filter(f => f.status === 'loaded')
    .map(f => f.family.replace(/"/g, '') + ' ' + f.weight + ' ' + f.style))
"""


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
    counts = {"formulas": 0, "bold": 0, "aligned": 0, "rows": 0}
    # The built book references nothing outside itself: no remote script,
    # stylesheet, font or image (links to cite a source are fine).
    remote = re.compile(r"""<(?:script|link|img|iframe)[^>]*(?:src|href)=["']https?://|url\(\s*["']?https?://""")
    for path in sorted(BOOK.rglob("*")):
        if path.suffix in (".html", ".css", ".js") and path.is_file():
            for m in remote.finditer(path.read_text(errors="replace")):
                problems.append(f"{path.relative_to(BOOK)}: a remote reference: {m.group(0)[:80]}")
    refused: list[str] = []
    with chromium(width=1100, height=1400) as page:

        def refuse(route):
            refused.append(route.request.url)
            route.abort()

        # Offline: any request that is not a file on disk is refused, and counted.
        page.route(re.compile(r"^(?!file:).*"), refuse)
        for path in pages:
            before = len(refused)
            page.goto(path.as_uri())
            page.evaluate("document.fonts.ready.then(() => true)")
            if len(refused) > before:
                problems.append(f"{path.name}: {len(refused) - before} remote requests, e.g. {refused[before]}")
            text = page.inner_text("main")
            for m in RAW_TEX.finditer(text):
                # Code blocks may hold Rust, never TeX; inline code is checked too.
                context = text[max(0, m.start() - 40) : m.end() + 40].replace("\n", " ")
                problems.append(f"{path.name}: raw TeX on the page: ...{context}...")
            if "katex-error" in page.content() or "ParseError" in text:
                problems.append(f"{path.name}: a KaTeX error is on the page")
            formulas = page.eval_on_selector_all("main .katex", FORMULAS_JS)
            counts["formulas"] += len(formulas)
            if formulas:
                faces = page.evaluate(FACES_JS)
                if not any(f.startswith("KaTeX_Main 400") for f in faces):
                    problems.append(f"{path.name}: KaTeX's fonts did not load ({faces})")
            for f in formulas:
                if f["w"] < 2 or f["h"] < 2:
                    problems.append(f"{path.name}: a formula has no size on screen: {f['tex'][:60]}")
                if BOLD_TEX.search(f["tex"]) and f["bold"] == 0:
                    problems.append(f"{path.name}: bold in the TeX, none on screen: {f['tex'][:60]}")
                if f["thin"]:
                    problems.append(f"{path.name}: bold symbols drawn regular {f['thin']}: {f['tex'][:60]}")
                counts["bold"] += f["bold"]
                if f["bold"]:
                    loaded = page.evaluate(FACES_JS)
                    for family in f["faces"]:
                        name = family.split(",")[0].strip().strip('"')
                        if not any(x.startswith(f"{name} 700") for x in loaded):
                            problems.append(f"{path.name}: no bold face of {name} loaded: {f['tex'][:60]}")
            for display in page.evaluate(ALIGNED_JS):
                for xs in display["columns"]:
                    if len(xs) >= 2:
                        counts["aligned"] += 1
                        counts["rows"] += len(xs)
                        if max(xs) - min(xs) > 1.5:
                            problems.append(
                                f"{path.name}: '=' of an aligned display spread over {max(xs) - min(xs):.1f} px: "
                                f"{display['tex'][:60]}"
                            )
            prose = page.evaluate(PROSE_JS)
            for m in COMBINING.finditer(prose):
                context = prose[max(0, m.start() - 30) : m.end() + 30].replace("\n", " ")
                problems.append(f"{path.name}: a combining accent in the prose (write it as $...$): ...{context}...")
            if path.name in PROMISED:
                # One .tag per display; an aligned system's holds one number per row.
                tag_text = " ".join(
                    page.eval_on_selector_all("main .katex-display .tag", "els => els.map(e => e.textContent)")
                )
                tags = set(re.findall(r"\([^()]+\)", tag_text))
                for number in PROMISED[path.name]:
                    if f"({number})" not in tags:
                        problems.append(f"{path.name}: equation ({number}) is not typeset with its number")
            if shots is not None and path.name in WHOLE:
                page.evaluate("document.querySelectorAll('main details').forEach(d => d.open = true)")
                page.evaluate("document.fonts.ready.then(() => true)")
                page.screenshot(path=str(shots / f"{path.stem}.png"), full_page=True)
            elif shots is not None and formulas:
                first = page.query_selector("main .katex-display")
                if first is not None:
                    first.scroll_into_view_if_needed()
                    page.screenshot(path=str(shots / f"{path.stem}-equation.png"))
    for p in problems:
        print(f"book_math: {p}")
    if problems:
        return 1
    print(
        f"book_math: {len(pages)} pages, {counts['formulas']} formulas laid out by KaTeX, "
        f"{counts['bold']} bold symbols all bold, {counts['aligned']} aligned columns "
        f"({counts['rows']} rows) with their '=' within 1.5 px, no raw TeX, no accent in the prose, "
        "nothing fetched"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())

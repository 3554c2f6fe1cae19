"""`spintop book` in a real browser: ▶ runs the book's snippets locally.

Run after `cargo build --release` with mdbook and mdbook-katex installed
(`.ci/run` does all of it):

    python3 tests/e2e/book_server.py [--shots DIR]

It starts `spintop book` on a free port and, in headless Chromium:

1. opens Section 4.2 through the server and saves a screenshot;
2. presses ▶ on its first snippet and waits for the answer ("No output": the
   snippet's assertions held);
3. edits a snippet in its editor (a printed number), runs it, edits the
   number again and sees the output change;
4. runs a snippet that loops forever and sees the time-limit message;
5. opens the static build (file://) and sees ▶ explain how to run a snippet;

then sends every runnable snippet of every page to the server, as ▶ would,
and requires each to pass: the same snippets `cargo test` runs as doctests
(their count is checked against the `rust,editable` blocks of book/src).
Finally `spintop book` gets SIGINT and must exit 0.
"""

from __future__ import annotations

import json
import pathlib
import re
import signal
import subprocess
import sys
import time
import urllib.request

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from browser import chromium  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]
BINARY = ROOT / "target" / "release" / "spintop"


def start() -> tuple[subprocess.Popen, str]:
    if not BINARY.exists():
        raise SystemExit(f"book_server: {BINARY} is missing; run `cargo build --release` first")
    proc = subprocess.Popen([str(BINARY), "book"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    deadline = time.monotonic() + 600
    assert proc.stdout is not None
    while time.monotonic() < deadline:
        line = proc.stdout.readline()
        if not line:
            raise SystemExit(f"book_server: spintop book exited early ({proc.wait()})")
        print(f"  {line.rstrip()}")
        m = re.search(r"serving (http://127\.0\.0\.1:\d+/)", line)
        if m:
            return proc, m.group(1)
    raise SystemExit("book_server: spintop book did not start in 10 minutes")


def wait_result(page, pre, what: str, ready, limit: float = 900) -> str:
    start = time.monotonic()
    while True:
        text = pre.eval_on_selector(".result", "e => e.innerText") if pre.query_selector(".result") else ""
        if ready(text):
            return text
        if time.monotonic() - start > limit:
            raise SystemExit(f"book_server: timed out waiting for {what}; shown: {text!r}")
        time.sleep(0.25)


def finished(text: str) -> bool:
    return bool(text) and not text.startswith("Running") and not text.startswith("compiling")


def press(pre) -> None:
    """▶, as a reader presses it: mdBook shows a snippet's buttons on hover."""
    pre.hover()
    pre.query_selector(".play-button").click()


def set_code(page, pre, code: str) -> None:
    page.evaluate("([pre, code]) => window.ace.edit(pre.querySelector('code')).setValue(code, 1)", [pre, code])


def main() -> int:
    shots = ROOT / "target" / "book-server"
    if "--shots" in sys.argv:
        shots = pathlib.Path(sys.argv[sys.argv.index("--shots") + 1])
    shots.mkdir(parents=True, exist_ok=True)
    proc, url = start()
    try:
        with chromium(width=1200, height=1000) as page:
            # 1. Section 4.2 through the server.
            page.goto(url + "section-4-2.html")
            page.locator("pre.playground >> visible=true").first.wait_for(timeout=20000)
            page.screenshot(path=str(shots / "section-4-2.png"))
            token = page.evaluate("window.spintopBook && window.spintopBook.token")
            assert token and len(token) == 32, token
            # 2. ▶ on the first snippet in view (those in a closed derivation
            # are hidden; a cold first run builds spintop).
            pre = [p for p in page.query_selector_all("pre.playground") if p.is_visible()][0]
            pre.scroll_into_view_if_needed()
            started = time.monotonic()
            press(pre)
            shown = wait_result(page, pre, "the first snippet's answer", finished)
            print(f"book_server: first ▶ answered in {time.monotonic() - started:.1f} s: {shown!r}")
            assert shown == "No output", shown
            page.screenshot(path=str(shots / "section-4-2-run.png"))
            # 3. Edit a number, run, edit it again.
            code = "let n = 7;\nprintln!(\"6 times n = {}\", 6 * n);\n"
            set_code(page, pre, code)
            started = time.monotonic()
            press(pre)
            shown = wait_result(page, pre, "the edited snippet", lambda t: "6 times n" in t, 120)
            print(f"book_server: warm ▶ answered in {time.monotonic() - started:.1f} s: {shown!r}")
            assert shown.strip() == "6 times n = 42", shown
            set_code(page, pre, code.replace("7", "8"))
            press(pre)
            shown = wait_result(page, pre, "the changed output", lambda t: "= 48" in t, 120)
            assert shown.strip() == "6 times n = 48", shown
            # 4. A loop that never ends meets the time limit.
            set_code(page, pre, "println!(\"spinning\");\nloop { std::hint::spin_loop(); }\n")
            press(pre)
            shown = wait_result(page, pre, "the time-limit message", lambda t: "time limit" in t, 180)
            print(f"book_server: endless loop: {shown!r}")
            page.screenshot(path=str(shots / "section-4-2-time-limit.png"))
            # 5. The same page without the server (file://, `mdbook build book`):
            # ▶ says how to run the snippet instead of calling the public playground.
            static = ROOT / "book" / "book" / "section-4-2.html"
            if static.exists():
                page.goto(static.as_uri())
                page.locator("pre.playground >> visible=true").first.wait_for(timeout=20000)
                pre = [p for p in page.query_selector_all("pre.playground") if p.is_visible()][0]
                press(pre)
                shown = wait_result(page, pre, "the static page's explanation", lambda t: "spintop book" in t, 20)
                print(f"book_server: without the server, ▶ says: {shown!r}")
            # 6. Every snippet of every page, as ▶ sends it.
            pages = sorted(p.name for p in (ROOT / "target" / "spintop-book" / "site").glob("*.html")
                           if p.name not in ("print.html", "404.html", "toc.html", "index.html"))
            snippets: list[tuple[str, str]] = []
            for name in pages:
                page.goto(url + name)
                codes = page.eval_on_selector_all(
                    "pre.playground code",
                    "els => els.map(e => window.ace && e.classList.contains('editable') ? window.ace.edit(e).getValue() : e.textContent)",
                )
                snippets += [(name, c) for c in codes]
    finally:
        pass
    expected = sum(len(re.findall(r"^```rust,editable$", p.read_text(), re.M)) for p in (ROOT / "book" / "src").glob("*.md"))
    assert len(snippets) == expected, f"{len(snippets)} runnable snippets on the pages, {expected} doctests in book/src"
    failures = []
    times = []
    for name, code in snippets:
        started = time.monotonic()
        request = urllib.request.Request(
            url + "evaluate.json",
            data=json.dumps({"code": code, "edition": "2024"}).encode(),
            headers={"Content-Type": "application/json", "X-Spintop-Token": token, "Origin": url.rstrip("/")},
        )
        with urllib.request.urlopen(request, timeout=900) as response:
            answer = json.loads(response.read())
        times.append(time.monotonic() - started)
        if not answer.get("success"):
            failures.append(f"{name}: {answer.get('result', '')[:300]}")
    times.sort()
    print(f"book_server: {len(snippets)} snippets run through the server, "
          f"median {times[len(times) // 2]:.2f} s, slowest {times[-1]:.2f} s")
    proc.send_signal(signal.SIGINT)
    code = proc.wait(timeout=10)
    if failures:
        print("book_server: snippets that failed through the server:\n  " + "\n  ".join(failures))
        return 1
    assert code == 0, f"spintop book exited {code} on SIGINT"
    print(f"book_server: ok (screenshots in {shots})")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    finally:
        subprocess.run(["pkill", "-f", f"{BINARY} book"], capture_output=True)

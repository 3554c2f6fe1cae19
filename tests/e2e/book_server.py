"""`spintop book` in a real browser: ▶ runs the book's snippets locally.

Run after `cargo build --release` with mdbook and mdbook-katex installed
(`.ci/run` does all of it; SPINTOP_BINARY=target/debug/spintop uses a debug
build instead):

    python3 tests/e2e/book_server.py [--shots DIR]

It starts `spintop book` on a free port and, in headless Chromium:

0. opens the server's address without its token and sees the 403 page that
   says to open the printed address; then opens the printed address, as a
   reader does, and lands on the book at the address without the token;
   then overwrites the cookie (as another server's page on 127.0.0.1 can),
   sees the 403 page, pastes the address into its form and lands on the
   page it asked for;
1. opens Section 4.2 through the server and saves a screenshot;
2. once the background build has finished ("▶ is ready" in the terminal),
   presses ▶ on its first snippet and waits for the answer (no compiler error,
   panic or limit; the same answer again when warm), printing how long that
   first ▶ took, and how long the same ▶ takes again, warm;
3. edits a snippet in its editor (a printed number), runs it, edits the
   number again and sees the output change;
4. runs a snippet that loops forever and sees the time-limit message;
5. opens the static build (file://) and sees ▶ explain how to run a snippet;

then sends every runnable snippet of every page to the server, as ▶ would,
and requires each to pass: the same snippets `cargo test` runs as doctests
(their count is checked against the `rust,editable` blocks of book/src).
Finally `spintop book` gets SIGINT and must exit 0, saying it stopped.
"""

from __future__ import annotations

import json
import os
import pathlib
import queue
import re
import signal
import subprocess
import sys
import threading
import time
import urllib.error
import urllib.request

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from browser import chromium  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]
BINARY = pathlib.Path(os.environ.get("SPINTOP_BINARY", ROOT / "target" / "release" / "spintop")).resolve()


class Book:
    """`spintop book`, its terminal's lines read as they come."""

    def __init__(self) -> None:
        if not BINARY.exists():
            raise SystemExit(f"book_server: {BINARY} is missing; run `cargo build --release` first")
        self.proc = subprocess.Popen([str(BINARY), "book"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        self.lines: queue.Queue[str] = queue.Queue()
        threading.Thread(target=self._read, daemon=True).start()
        line = self.wait_line("serving http://", 600)
        m = re.search(r"serving (http://127\.0\.0\.1:\d+/)\?token=([0-9a-f]+)", line)
        assert m, line
        self.base, self.token = m.group(1), m.group(2)
        self.address = f"{self.base}?token={self.token}"

    def _read(self) -> None:
        assert self.proc.stdout is not None
        for line in self.proc.stdout:
            print(f"  {line.rstrip()}")
            self.lines.put(line)
        self.lines.put("")

    def wait_line(self, text: str, limit: float) -> str:
        deadline = time.monotonic() + limit
        while time.monotonic() < deadline:
            try:
                line = self.lines.get(timeout=max(0.1, deadline - time.monotonic()))
            except queue.Empty:
                break
            if not line:
                raise SystemExit(f"book_server: spintop book exited early ({self.proc.wait()})")
            if text in line:
                return line
        raise SystemExit(f"book_server: spintop book did not say {text!r} in {limit:.0f} s")


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
    book = Book()
    try:
        return check(book, shots)
    finally:
        if book.proc.poll() is None:
            # This server only (it kills what it started when it stops).
            book.proc.terminate()
            book.proc.wait(timeout=20)


def check(book: Book, shots: pathlib.Path) -> int:
    proc, url = book.proc, book.base
    with chromium(width=1200, height=1000) as page:
        # 0. Without the printed address, only a page saying to use it;
        # with it, the book, at the address without its token.
        response = page.goto(url)
        assert response is not None and response.status == 403, response
        assert "Open the address printed in the terminal" in page.inner_text("body")
        assert book.token not in page.content()
        page.goto(book.address)
        assert page.url == url, page.url
        assert "403" not in (page.title() or ""), page.title()
        # 0b. The cookie overwritten, as a page of another server on
        # 127.0.0.1 can (cookies do not separate ports): the 403 page takes
        # the printed address again in its form, and the book opens at the
        # page asked for.
        port = url.rstrip("/").rsplit(":", 1)[1]
        page.context.add_cookies([{"name": f"spintop-book-{port}", "value": "0" * 32, "url": url}])
        response = page.goto(url + "section-4-2.html")
        assert response is not None and response.status == 403, response
        assert "browser lost the key" in page.inner_text("body")
        page.screenshot(path=str(shots / "lost-cookie.png"))
        page.fill("#key", book.address)
        with page.expect_navigation():
            page.click("button[type=submit]")
        assert page.url == url + "section-4-2.html", page.url
        assert page.evaluate("window.spintopBook && window.spintopBook.token") == book.token
        print("book_server: a lost cookie was taken again by the 403 page's form")
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
        book.wait_line("▶ is ready", 900)
        started = time.monotonic()
        press(pre)
        shown = wait_result(page, pre, "the first snippet's answer", finished)
        print(f"book_server: first ▶ after the background build answered in {time.monotonic() - started:.2f} s: {shown!r}")
        # Whatever the first snippet prints (the book may change it), it ran:
        # no compiler error, no limit, and the warm run below says the same.
        for bad in ("error", "time limit", "panicked", "killed", "busy"):
            assert bad not in shown.lower(), shown
        first = shown
        # The same snippet again, warm, to compare with.
        page.evaluate("pre => { pre.querySelector('.result').innerText = ''; }", pre)
        started = time.monotonic()
        press(pre)
        shown = wait_result(page, pre, "the first snippet's answer again", finished)
        print(f"book_server: the same ▶ again (warm) answered in {time.monotonic() - started:.2f} s")
        assert shown == first, (shown, first)
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
    # Every Rust block mdBook makes runnable: editable ones and plain ones
    # (instructors.md shows the grade book's rows with a plain block).
    expected = sum(len(re.findall(r"^```rust(,editable)?$", p.read_text(), re.M)) for p in (ROOT / "book" / "src").glob("*.md"))
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
        try:
            with urllib.request.urlopen(request, timeout=900) as response:
                answer = json.loads(response.read())
            # A run longer than the server's first answer (a busy machine)
            # is followed as the page follows it.
            while answer.get("pending") or answer.get("done") is False:
                time.sleep(0.25)
                status = urllib.request.Request(url + "evaluate/status", headers={"X-Spintop-Token": token})
                with urllib.request.urlopen(status, timeout=60) as response:
                    answer = json.loads(response.read())
        except urllib.error.HTTPError as e:
            answer = {"result": f"HTTP {e.code}: {e.read().decode()}"}
        times.append(time.monotonic() - started)
        if not answer.get("success"):
            failures.append(f"{name}: {answer.get('result', '')[:300]}")
    times.sort()
    print(f"book_server: {len(snippets)} snippets run through the server, "
          f"median {times[len(times) // 2]:.2f} s, slowest {times[-1]:.2f} s")
    proc.send_signal(signal.SIGINT)
    code = proc.wait(timeout=10)
    book.wait_line("stopped (SIGINT)", 5)
    if failures:
        print("book_server: snippets that failed through the server:\n  " + "\n  ".join(failures))
        return 1
    assert code == 0, f"spintop book exited {code} on SIGINT"
    print(f"book_server: ok (screenshots in {shots})")
    return 0


if __name__ == "__main__":
    sys.exit(main())

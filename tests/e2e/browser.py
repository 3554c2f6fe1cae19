"""Headless Chromium for spintop's end-to-end tests of the book.

Every browser test under tests/e2e/ opens pages through `chromium()`: Debian's
Chromium (`apt-get install -y chromium`) driven by Playwright for Python
(`pip install -r tests/e2e/requirements.txt`), which drives the system browser
through `executable_path` and so never downloads a browser of its own.

The flags keep Chromium off the network: on these machines every outside
connection is refused, and Chromium's background services would otherwise try
many at a time.
"""

from __future__ import annotations

import contextlib
import os
import shutil
import tempfile

CHROMIUM_FLAGS = [
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]


def chromium_path() -> str:
    """The system Chromium, or a one-line reason to stop."""
    for candidate in (os.environ.get("SPINTOP_CHROMIUM"), "/usr/bin/chromium", shutil.which("chromium")):
        if candidate and os.path.exists(candidate):
            return candidate
    raise SystemExit("no Chromium found: apt-get install -y chromium (or set SPINTOP_CHROMIUM)")


@contextlib.contextmanager
def chromium(width: int = 1280, height: int = 900):
    """A fresh headless Chromium page (its own empty profile), closed on exit."""
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        raise SystemExit("Playwright for Python is missing: pip install -r tests/e2e/requirements.txt")
    profile = tempfile.mkdtemp(prefix="spintop-chromium-")
    try:
        with sync_playwright() as p:
            context = p.chromium.launch_persistent_context(
                profile,
                executable_path=chromium_path(),
                headless=True,
                args=CHROMIUM_FLAGS,
                viewport={"width": width, "height": height},
            )
            try:
                page = context.pages[0] if context.pages else context.new_page()
                yield page
            finally:
                context.close()
    finally:
        shutil.rmtree(profile, ignore_errors=True)

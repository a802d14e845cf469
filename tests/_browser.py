"""Where the browser test finds a Chromium, and what to do when there is none.

In order: ``$PENDULAB_CHROMIUM``; ``chromium``, ``chromium-browser``, ``google-chrome``
(or ``google-chrome-stable``) on ``PATH``; Playwright's own download. ``make test``
installs Debian's ``chromium`` with apt when none is on ``PATH``.
"""
from __future__ import annotations

import contextlib
import os
import shutil
from collections.abc import Iterator
from typing import Any

NAMES = ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable")

HOW_TO_GET_ONE = (
    "the browser test needs Chromium or Chrome, and none was found: install one "
    "(Debian/Ubuntu: `apt-get install chromium`; macOS: `brew install --cask chromium`; "
    "or Playwright's own: `python -m playwright install chromium`), "
    "or point PENDULAB_CHROMIUM at its executable"
)


def find_chromium(playwright=None) -> str:
    """The path of a Chromium to drive; ``playwright`` (a started ``sync_playwright()``) adds its own.

    Raises
    ------
    LookupError
        When there is none, with :data:`HOW_TO_GET_ONE` as the message.
    """
    chosen = os.environ.get("PENDULAB_CHROMIUM")
    if chosen:
        if not (os.path.isfile(chosen) and os.access(chosen, os.X_OK)):
            raise LookupError(f"PENDULAB_CHROMIUM = {chosen} is not an executable file")
        return chosen
    for name in NAMES:
        path = shutil.which(name)
        if path:
            return path
    if playwright is not None:
        own = playwright.chromium.executable_path
        if own and os.path.isfile(own):
            return own
    raise LookupError(HOW_TO_GET_ONE)


#: The five screens every layout test of the explorer runs at: a phone, a tablet upright and on
#: its side, a laptop and a full-HD projector (width, height in CSS px).
VIEWPORTS = [(390, 844), (768, 1024), (1024, 768), (1400, 900), (1920, 1080)]


#: Chromium's switches for the tests: headless, and no network of its own (QUIC, updates, sync).
ARGS = [
    "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
    "--disable-background-networking", "--disable-component-update", "--disable-sync",
]


@contextlib.contextmanager
def launched() -> Iterator[Any]:
    """A started Chromium (:func:`find_chromium`'s, driven by Playwright), closed on leaving."""
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path=find_chromium(p), args=ARGS)
        try:
            yield browser
        finally:
            browser.close()


#: Playwright's wait for each action and condition on a test's page (its own default is 30 s):
#: a hang guard, not a speed claim; a machine three times slower than ours, loaded, and a
#: first request that compiles must not reach it.
HANG_GUARD_MS = 90_000


def record_errors(pg: Any) -> Any:
    """``pg`` with ``pg.errors``: the page's uncaught exceptions and console errors, as they
    come; each of its waits bounded by :data:`HANG_GUARD_MS`."""
    pg.set_default_timeout(HANG_GUARD_MS)
    pg.errors = []
    pg.on("pageerror", lambda e: pg.errors.append(str(e)))
    pg.on("console", lambda m: pg.errors.append(m.text) if m.type == "error" else None)
    return pg

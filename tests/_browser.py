"""Where the browser test finds a Chromium, and what to do when there is none.

In order: ``$PENDULAB_CHROMIUM``; ``chromium``, ``chromium-browser``, ``google-chrome``
(or ``google-chrome-stable``) on ``PATH``; Playwright's own download. ``make test``
installs Debian's ``chromium`` with apt when none is on ``PATH``.
"""
from __future__ import annotations

import os
import shutil

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

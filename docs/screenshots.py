"""Write the explorer's screenshots of docs/explorer.md from the real server, in Chromium.

    PYTHONPATH=src python docs/screenshots.py

``explorer-projector.png`` (projector mode at 1920 x 1080) and ``explorer-pt.png`` (the page
in Portuguese at 1280 x 800), both in docs/, each reduced to a 256-colour palette by Pillow
so that it stays small. The server is ``pendulab serve`` in a child process
(tests/served.py) and the browser the one tests/_browser.py finds.
"""
from __future__ import annotations

import sys
from pathlib import Path

from PIL import Image

DOCS = Path(__file__).resolve().parent
sys.path.insert(0, str(DOCS.parent / "tests"))

from _browser import launched  # noqa: E402
from served import serve_in_child  # noqa: E402

#: name, query, viewport, what to wait for after the first render.
SHOTS = [
    ("explorer-projector.png", "view=projector&length=1&amplitude=60&unit=deg&step=1e-3&t_max=60&speed=1",
     (1920, 1080), "document.getElementById('gate').dataset.period"),
    ("explorer-pt.png", "lang=pt&length=1&amplitude=30&unit=deg&step=0.5&t_max=20&method=rk4",
     (1280, 800), "document.querySelector('#flags p[data-kind=energy-decay]')"),
]


def shoot(out: Path = DOCS) -> list[Path]:
    """Take each of :data:`SHOTS`; return the files written."""
    written = []
    with serve_in_child() as base, launched() as browser:
        for name, query, (width, height), ready in SHOTS:
            context = browser.new_context(viewport={"width": width, "height": height})
            try:
                pg = context.new_page()
                pg.goto(f"{base}/?{query}")
                pg.wait_for_function("document.body.dataset.shown === '1'", timeout=60_000)
                pg.wait_for_function(ready, timeout=60_000)
                pg.evaluate("window.scrollTo(0, 0)")
                pg.wait_for_timeout(400)
                path = out / name
                pg.screenshot(path=str(path))
                with Image.open(path) as im:
                    small = im.convert("RGB").quantize(colors=256, method=Image.Quantize.MEDIANCUT)
                small.save(path, optimize=True)
                written.append(path)
            finally:
                context.close()
    return written


if __name__ == "__main__":
    for p in shoot():
        print(f"{p.relative_to(DOCS.parent)}: {p.stat().st_size / 1000:.0f} kB")

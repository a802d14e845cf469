"""The Typst run: a template and its ``data.json`` in a folder, typeset to PDF bytes."""
from __future__ import annotations

import calendar
import json
import os
import shutil
from importlib import resources
from pathlib import Path
from typing import Any

#: The document date (PDF metadata): fixed so that the same inputs give the same bytes;
#: ``SOURCE_DATE_EPOCH`` (the reproducible-builds convention) overrides it.
DEFAULT_DATE = (2020, 1, 6)  # the coursework's deadline


def timestamp() -> int:
    """The document's date: ``SOURCE_DATE_EPOCH`` where set (checked), else :data:`DEFAULT_DATE`."""
    from ..core.inputs import source_date_epoch

    epoch = source_date_epoch(os.environ.get("SOURCE_DATE_EPOCH"))
    return calendar.timegm((*DEFAULT_DATE, 12, 0, 0)) if epoch is None else epoch


#: The scripts the embedded fonts cover (code point ranges): Latin, IPA, combining marks,
#: Greek, Cyrillic, Latin and Greek extended, punctuation.
EMBEDDED_RANGES = ((0x0000, 0x052F), (0x1E00, 0x1FFF), (0x2000, 0x206F))


#: The longest run of a name without a break opportunity: a column of the key or a line of
#: the cover holds it at any allowed length (80 characters of one word).
BREAK_EVERY = 12


def breakable(text: str, every: int = BREAK_EVERY) -> str:
    """``text`` with a zero-width space (a line-break opportunity, invisible) after each
    ``every`` characters of a run without spaces; never inside a letter's combining marks
    or a joined pair (ZWJ, ZWNJ)."""
    import unicodedata

    out: list[str] = []
    run = 0
    for c in text:
        if c.isspace():
            run = 0
        elif run >= every and not unicodedata.combining(c) and c not in "\u200c\u200d" and out[-1] not in "\u200c\u200d":
            out.append("\u200b")
            run = 0
        out.append(c)
        run += not c.isspace()
    return "".join(out)


def needs_system_fonts(texts: Any) -> bool:
    """Whether a text of ``texts`` (student names) has a letter beyond the embedded fonts'
    scripts (CJK, Arabic, Devanagari, ...): then the system's fonts are searched too."""
    return any(not any(lo <= ord(ch) <= hi for lo, hi in EMBEDDED_RANGES) for t in texts for ch in t)


def typeset(folder: Path, template: str, data: dict[str, Any], system_fonts: bool = False) -> bytes:
    """Write ``data.json`` and the packaged ``template`` into ``folder``; return the PDF.

    ``system_fonts``: also search the system's fonts (for names in other scripts); else
    only the embedded ones, so that the same inputs give the same PDF on every machine.
    """
    import typst

    (folder / "data.json").write_text(json.dumps(data, ensure_ascii=False, indent=1), encoding="utf-8")
    shutil.copyfile(str(resources.files(__package__).joinpath(template)), folder / template)
    return typst.compile(
        str(folder / template),
        root=str(folder),
        ignore_system_fonts=not system_fonts,
        timestamp=timestamp(),
    )

"""docs/performance.md holds the table benchmarks/workloads.py writes, in the shape it writes (not its numbers)."""
import importlib.util
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def workloads():
    spec = importlib.util.spec_from_file_location("workloads", ROOT / "benchmarks" / "workloads.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def section(text: str, w) -> list[str]:
    start, end = text.index(w.BEGIN) + len(w.BEGIN), text.index(w.END)
    return [line for line in text[start:end].splitlines() if line.startswith("|")]


def test_the_documented_table_is_the_scripts_shape():
    w = workloads()
    lines = section((ROOT / "docs" / "performance.md").read_text(), w)
    header = w.table([]).splitlines()
    assert lines[:2] == header
    assert len(lines) == 2 + len(w.ROWS)
    number = r"-?\d+(\.\d+)?(e[+-]\d+)?"
    for line, (what, peer) in zip(lines[2:], w.ROWS):
        cells = [c.strip() for c in line.strip("|").split("|")]
        assert cells[0] == what and cells[2] == peer, line
        assert re.fullmatch(number, cells[1]) and re.fullmatch(number, cells[3]), line
        assert re.fullmatch(r"\d+\.\d\dx", cells[4]), line


def test_write_replaces_only_the_text_between_the_markers(tmp_path):
    w = workloads()
    doc = tmp_path / "performance.md"
    doc.write_text(f"before\n{w.BEGIN}\nold table\n{w.END}\nafter\n")
    rows = [w.row(k, 1.5 * (k + 1), 3.0) for k in range(len(w.ROWS))]
    w.write(w.table(rows), doc)
    text = doc.read_text()
    assert text.startswith(f"before\n{w.BEGIN}\n") and text.endswith(f"{w.END}\nafter\n")
    assert "old table" not in text
    assert section(text, w)[2].endswith("| 0.50x |")
    assert not list(tmp_path.glob("*.tmp"))


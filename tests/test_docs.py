"""The documentation builds with warnings as errors: a broken cross-reference, a docstring
that documents a parameter its function no longer has (numpydoc PR02) or an unreadable
page fails here, as in ``make docs``."""
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_docs_build_without_warnings(tmp_path):
    out = tmp_path / "html"
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(filter(None, [str(ROOT / "src"), os.environ.get("PYTHONPATH")])))
    res = subprocess.run(
        [sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html",
         "-d", str(tmp_path / "doctrees"), str(ROOT / "docs"), str(out)],
        capture_output=True, text=True, env=env, timeout=600,
    )
    assert res.returncode == 0, res.stderr[-4000:]
    period = (out / "_api" / "pendulab.numerics.period.html").read_text()
    assert 'id="pendulab.numerics.period.agm_period"' in period  # the reference has the functions
    assert "Carvalhaes" in period  # and their numpy-style sections (References)
    tutorial = (out / "tutorial.html").read_text()
    assert "Problem 5" in tutorial and "<img" in tutorial  # the notebook with its figures
    guide = (out / "guide.html").read_text()
    assert 'id="install"' in guide and "_PENDULAB_COMPLETE" in guide
    coursework = (out / "coursework.html").read_text()
    assert "b_{k+1} = \\sqrt{a_k b_k}" in coursework  # (7), so that "(7)" can be followed
    assert "one name per quantity" in (out / "glossary.html").read_text()
    # Every page is in the table of contents (a page left out is a warning only for .rst).
    index = (out / "index.html").read_text()
    for page in sorted((ROOT / "docs").glob("*.md")):
        if page.stem != "index":
            assert f'href="{page.stem}.html"' in index, page.name

"""The tutorial notebook runs from top to bottom, in a fresh kernel, without an error."""
import os
from pathlib import Path

import mpmath
import nbformat
from nbclient import NotebookClient

from reference import G_TEXT, reference_period

ROOT = Path(__file__).resolve().parents[1]
TUTORIAL = ROOT / "examples" / "tutorial.ipynb"


def execute(path: Path = TUTORIAL) -> nbformat.NotebookNode:
    """Run every cell (the kernel sees this checkout's ``src`` first); raise on the first error."""
    nb = nbformat.read(path, as_version=4)
    env_path = os.pathsep.join(filter(None, [str(ROOT / "src"), os.environ.get("PYTHONPATH")]))
    os.environ["PYTHONPATH"] = env_path  # inherited by the kernel process
    NotebookClient(nb, timeout=600, kernel_name="python3", resources={"metadata": {"path": str(ROOT)}}).execute()
    return nb


def test_tutorial_runs(monkeypatch):
    monkeypatch.setenv("PYTHONPATH", os.environ.get("PYTHONPATH", ""))  # restored afterwards
    nb = execute()
    outputs = [o for c in nb.cells if c.cell_type == "code" for o in c.outputs]
    assert not [o for o in outputs if o.output_type == "error"]
    text = "\n".join(o.get("data", {}).get("text/plain", "") for o in outputs)
    # Problem 5's pendulum to 30 digits; reference: 4 sqrt(l/g) K(sin^2(2 pi/5)) in mpmath.
    with mpmath.workdps(60):
        ref = reference_period("3.5", 4 * mpmath.pi / 5, G_TEXT, dps=60)
    assert repr(mpmath.nstr(ref, 30, strip_zeros=False)) in text
    assert "0.796775" in text  # Figure 3 of the coursework: z1 = 0.796774928412 at t = 2.1
    assert any("image/png" in o.get("data", {}) for o in outputs)  # the figures were drawn
    html = "\n".join(o.get("data", {}).get("text/html", "") for o in outputs)
    assert "<caption>Problem3</caption>" in html and "<caption>GravityEstimate</caption>" in html


if __name__ == "__main__":  # refresh the outputs stored in the notebook (shown by the docs)
    nbformat.write(execute(), TUTORIAL)

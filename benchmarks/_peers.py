"""What the benchmarks share: the plain C loops (compiled here with ``cc -O2``), the timer and the table.

The C loops are equations (3) exactly as the numba kernels run them: ``taylor2`` stores
every point (as ``pendulab.engine.kernels.trajectory``), ``taylor2_return`` streams to the first
sign change of ``z2`` from + to - (as ``first_return``), and ``sweep`` runs that search for
many pendulums one after the other on one core (as a plain C program would).
"""
from __future__ import annotations

import ctypes
import importlib.util
import os
import resource
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from types import ModuleType

import numpy as np

C_SOURCE = r"""
#include <math.h>
void taylor2(double alpha, double c, double h, long n, double *z1, double *z2) {
    z1[0] = alpha; z2[0] = 0.0;
    for (long i = 0; i < n; i++) {
        double s = sin(z1[i]);
        z1[i + 1] = z1[i] + h * z2[i] + 0.5 * h * h * c * s;
        z2[i + 1] = z2[i] + h * c * s + 0.5 * h * h * c * z2[i] * cos(z1[i]);
    }
}
long taylor2_return(double alpha, double c, double h, long n) {
    double z1 = alpha, z2 = 0.0;
    for (long i = 0; i < n; i++) {
        double s = sin(z1);
        double z1n = z1 + h * z2 + 0.5 * h * h * c * s;
        double z2n = z2 + h * c * s + 0.5 * h * h * c * z2 * cos(z1);
        if (!(fabs(z1n) < M_PI)) return -i;
        if (z2 > 0.0 && z2n <= 0.0 && z1n > 0.0) return i;
        z1 = z1n; z2 = z2n;
    }
    return n;
}
void sweep(const double *alpha, const double *c, double h, const long *n, long m, long *j) {
    for (long p = 0; p < m; p++) j[p] = taylor2_return(alpha[p], c[p], h, n[p]);
}
"""


def build_c() -> ctypes.CDLL:
    """Compile :data:`C_SOURCE` with the system's ``cc -O2`` and load it. The folder goes once
    the library is loaded (the process keeps its mapping), so no run leaves one behind."""
    with tempfile.TemporaryDirectory(prefix="pendulab-bench-", ignore_cleanup_errors=True) as folder:
        src, lib = Path(folder) / "taylor2.c", Path(folder) / "taylor2.so"
        src.write_text(C_SOURCE)
        subprocess.run(["cc", "-O2", "-shared", "-fPIC", str(src), "-o", str(lib), "-lm"], check=True)
        dll = ctypes.CDLL(str(lib))
    dbl, pd, pl, lng = ctypes.c_double, ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_long), ctypes.c_long
    dll.taylor2.argtypes = [dbl, dbl, dbl, lng, pd, pd]
    dll.taylor2_return.argtypes = [dbl, dbl, dbl, lng]
    dll.taylor2_return.restype = lng
    dll.sweep.argtypes = [pd, pd, dbl, pl, lng, pl]
    return dll


def ptr(a: np.ndarray, kind=ctypes.c_double):
    return a.ctypes.data_as(ctypes.POINTER(kind))


def run(cmd: list[str], env: dict | None = None) -> tuple[float, float]:
    """Wall time and CPU time (user + sys) of one run of ``cmd``, s."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env)
    elapsed = time.perf_counter() - t
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return elapsed, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def load_against(src: str) -> ModuleType:
    """The package ``pendulab`` of the folder ``src`` (another checkout's ``src``), imported
    as ``pendulab_against``: the ``--against`` option of the benchmarks that time a change
    beside the code before it, in the same run."""
    root = Path(src) / "pendulab"
    spec = importlib.util.spec_from_file_location("pendulab_against", root / "__init__.py",
                                                  submodule_search_locations=[str(root)])
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules["pendulab_against"] = module
    spec.loader.exec_module(module)
    return module


def side_by_side(fns: dict[str, Callable[[], object]], repeat: int = 5,
                 clock: Callable[[], float] = time.perf_counter) -> dict[str, float]:
    """Best time of each function over ``repeat`` rounds, the functions taking turns.

    Taking turns exposes each to the same load; the best time is the least disturbed.
    ``clock``: wall time, or ``time.thread_time`` (this thread's CPU time) for a
    single-threaded kernel on a machine whose other work takes the core away from it.
    """
    for f in fns.values():
        f()  # warm: compiled or loaded from the cache, pages touched
    best = {k: float("inf") for k in fns}
    for _ in range(repeat):
        for k, f in fns.items():
            t = clock()
            f()
            best[k] = min(best[k], clock() - t)
    return best


def ratio(row: dict) -> float | None:
    """pendulab's value over the peer's: a rate (higher is better) or a time (lower is better)."""
    if row.get("peer") in (None, 0):
        return None
    return row["ours"] / row["peer"]


def write_between(path: Path, begin: str, end: str, text: str) -> None:
    """``text`` between the markers ``begin`` and ``end`` of the file ``path`` (atomically: a
    temporary file beside it, then a rename); the rest of the file as it was."""
    doc = path.read_text()
    start, stop = doc.index(begin) + len(begin), doc.index(end)
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text(doc[:start] + "\n" + text + "\n" + doc[stop:])
    os.replace(tmp, path)


def print_table(rows: list[dict]) -> None:
    """One line per row: what, ours, peer, ratio (higher is better for pendulab), target."""
    print(f"| {'what':66} | {'pendulab':>9} | {'peer':26} | {'peer value':>10} | {'ratio':>6} | {'target':11} |")
    print(f"|{'-' * 68}|{'-' * 11}|{'-' * 28}|{'-' * 12}|{'-' * 8}|{'-' * 13}|")
    for r in rows:
        rt = ratio(r)
        peer = "" if r.get("peer") is None else f"{r['peer']:.3g}"
        print(f"| {r['what']:66} | {r['ours']:>9.3g} | {r['peer_name']:26} | {peer:>10} | "
              f"{'' if rt is None else f'{rt:.2f}x':>6} | {r['target']:11} |")
        if r.get("note"):
            print(f"|   {r['note']} | | | | | |")

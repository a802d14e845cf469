"""The table a sweep returns, its summary, and its CSV or Parquet file."""
from __future__ import annotations

import math
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ...core.atomic import atomic_path, check_writable
from ...core.errors import InputError, shown
from ...core.methods import Status
from ...numerics.results import Result

#: Status of each pendulum, as :func:`pendulab.engine.kernels.first_return` reports it.
STATUS = tuple(s.name.lower() for s in Status)


@dataclass(frozen=True, eq=False)
class SweepResult(Result):
    """One row per (method, step, pendulum): the simulated period and its errors.

    Columns (all arrays of the same length): ``method`` (str), ``order``, ``step``,
    ``length``, ``amplitude`` (rad), ``period`` (AGM period (8), converged), ``status`` (one of
    :data:`STATUS`), ``steps`` (steps taken), ``linear``, ``cubic`` (period estimates; NaN
    unless ``status`` is ``"found"`` or ``"untrusted"``), ``linear_signed_error``, ``cubic_signed_error`` (``estimate - period``, signed),
    ``cubic_error_estimate`` (the interpolation error estimate of problem 3(d)); and ``g``
    (m/s^2), the same for every row.
    """

    columns: dict[str, np.ndarray]
    g: float

    def to_dict(self) -> dict[str, Any]:
        """Without the rows (:meth:`write` and :meth:`to_frame` give them): ``g`` and the
        :meth:`summary`, one entry per (method, step) (``pendulab sweep --json``)."""
        return {"g": self.g, "summary": self.summary()}

    def _columns(self) -> dict[str, np.ndarray]:
        return self.columns

    def __len__(self) -> int:
        return len(self.columns["amplitude"])

    def __getitem__(self, name: str) -> np.ndarray:
        return self.columns[name]

    def select(self, method: str, step: float) -> dict[str, np.ndarray]:
        """The rows of one (method, step) pair."""
        rows = (self.columns["method"] == method) & (self.columns["step"] == step)
        return {k: c[rows] for k, c in self.columns.items()}

    def summary(self) -> list[dict[str, Any]]:
        """Per (method, step): pendulums found, largest ``|cubic error|`` and relative error."""
        out = []
        keys = dict.fromkeys(zip(self.columns["method"].tolist(), self.columns["step"].tolist()))
        for method, step in keys:
            r = self.select(method, step)
            ok = r["status"] == "found"
            rel = np.abs(r["cubic_signed_error"][ok] / r["period"][ok])
            out.append(
                {
                    "method": method,
                    "order": int(r["order"][0]),
                    "step": step,
                    "pendulums": int(len(ok)),
                    "found": int(ok.sum()),
                    "max_abs_cubic_error": float(np.max(np.abs(r["cubic_signed_error"][ok]))) if ok.any() else math.nan,
                    "max_rel_cubic_error": float(rel.max()) if ok.any() else math.nan,
                    "pendulum_steps": int(r["steps"].sum()),
                }
            )
        return out

    def write(self, path: str | os.PathLike) -> Path:
        """Write the table atomically as CSV (``.csv``) or Parquet (``.parquet``)."""
        import pyarrow as pa

        p = check_writable("output", path)
        suffix = p.suffix.lower()
        if suffix not in (".csv", ".parquet"):
            raise InputError("output", shown(str(path)), "a file name ending in .csv or .parquet")
        table = pa.table(dict(self.columns))
        with atomic_path(p) as tmp:
            if suffix == ".csv":
                import pyarrow.csv as pacsv

                pacsv.write_csv(table, tmp)
            else:
                import pyarrow.parquet as pq

                pq.write_table(table, tmp)
        return p

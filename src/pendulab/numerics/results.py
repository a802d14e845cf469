"""What every result object of pendulab offers, the way scipy, xarray and pandas do it.

The results are frozen dataclasses that derive from :class:`Result`:

- their arrays are read-only and cannot be made writeable again (a result cannot be
  changed behind its back);
- ``==`` is identity and ``hash()`` works (``eq=False``: arrays have no single truth value);
- :meth:`Result.to_dict` gives the fields and the numbers derived from them as a ``dict``:
  what the command line prints with ``--json`` (a result whose JSON form differs, flat or
  without its bulk arrays, says so in its own ``to_dict``);
- :meth:`Result.to_frame` gives a pandas ``DataFrame`` (pandas is optional:
  ``pip install 'pendulab[pandas]'``); :func:`to_frame` does the same for a sequence of
  results, one row each (the rows of problems 3 and 5, a list of estimates);
- :meth:`Result.derived` gives the values computed from the fields (``cubic_error``, ...),
  which ``to_frame`` and the notebook view show after the fields;
- in Jupyter a result shows itself as a table of its fields (``_repr_html_``).
"""
from __future__ import annotations

import dataclasses
import html
import math
import sys
from collections.abc import Iterable, Mapping
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import numpy as np
    import pandas as pd

__all__ = ["Result", "to_frame"]


def _numpy() -> Any:
    """numpy where something has loaded it, else None: no field holds an array before numpy
    is loaded, so a result of plain numbers (the period's) never loads it (start-up time)."""
    return sys.modules.get("numpy")


def _numbers() -> tuple[type, ...]:
    """The scalar number types: Python's, and numpy's where it is loaded."""
    np = _numpy()
    return (bool, int, float) if np is None else (bool, int, float, np.number)


def _read_only(value: Any) -> Any:
    """An array that no one can write to: a copy in an immutable ``bytes`` buffer, which
    numpy refuses to flag writeable again (a read-only view could be). The caller's own
    array is left as it is; an array already sealed this way is kept without a copy."""
    import numpy as np

    if not isinstance(value, np.ndarray) or _sealed(value):
        return value
    if value.dtype.hasobject:  # no bytes for Python objects: a read-only view
        view = value.view()
        view.flags.writeable = False
        return view
    return np.frombuffer(value.tobytes(), dtype=value.dtype).reshape(value.shape)


def _sealed(value: np.ndarray) -> bool:
    """Whether ``value`` is read-only over memory that a ``bytes`` object owns."""
    import numpy as np

    base: Any = value
    while isinstance(base, np.ndarray):
        base = base.base
    return not value.flags.writeable and isinstance(base, bytes)


class Result:
    """Base of the frozen result dataclasses: read-only arrays, ``to_dict``, ``to_frame``, a notebook view.

    Subclasses are declared ``@dataclass(frozen=True, eq=False)``. A subclass whose rows
    are natural (a trajectory: one row per time) defines ``_columns()``; otherwise
    :meth:`to_frame` gives one row of the scalar fields.
    """

    __slots__ = ()

    def __post_init__(self) -> None:
        np = _numpy()
        if np is None:
            return
        for f in dataclasses.fields(self):  # type: ignore[arg-type]
            value = getattr(self, f.name)
            if isinstance(value, np.ndarray):
                new: Any = _read_only(value)
            elif isinstance(value, dict) and any(isinstance(v, np.ndarray) for v in value.values()):
                new = {k: _read_only(v) for k, v in value.items()}
            else:
                continue
            object.__setattr__(self, f.name, new)

    def to_dict(self) -> dict[str, Any]:
        """The fields, then the numbers derived from them (:meth:`derived`), as a ``dict``;
        nested results become dicts too, arrays stay arrays."""
        fields = {f.name: _plain(getattr(self, f.name)) for f in dataclasses.fields(self)}  # type: ignore[arg-type]
        return fields | self.derived()

    def to_frame(self) -> pd.DataFrame:
        """A pandas ``DataFrame``: the result's table, or one row of its scalar fields."""
        pd = _pandas()
        columns = self._columns()
        if columns is not None:
            return pd.DataFrame(columns)
        return pd.DataFrame([self._row()])

    def _columns(self) -> Mapping[str, Any] | None:
        return None

    def _row(self) -> dict[str, Any]:
        """The scalar fields (numbers, strings, pairs of numbers) of one table row, then the
        scalar derived values (:meth:`derived`)."""
        row: dict[str, Any] = {}
        for f in dataclasses.fields(self):  # type: ignore[arg-type]
            value = getattr(self, f.name)
            if _scalar(value):
                row[f.name] = value
            elif isinstance(value, tuple) and 0 < len(value) <= 3 and all(
                isinstance(v, _numbers()) for v in value
            ):
                for i, v in enumerate(value):
                    row[f"{f.name}_{i}"] = v
        return row | self.derived()

    def derived(self) -> dict[str, Any]:
        """The numbers computed from the fields (public properties such as ``cubic_error``),
        by name. Words are left to the presenters: a property that gives a sentence is not one."""
        out: dict[str, Any] = {}
        for name in _properties(type(self)):
            value = getattr(self, name)
            if isinstance(value, _numbers()) or value is None:
                out[name] = value
        return out

    def _repr_html_(self) -> str:
        def row(name: str, value: Any, note: str = "") -> str:
            return (f"<tr><th style='text-align:left'>{html.escape(name)}{note}</th>"
                    f"<td style='text-align:left'>{_html(value)}</td></tr>")

        rows = "".join(row(f.name, getattr(self, f.name)) for f in dataclasses.fields(self))  # type: ignore[arg-type]
        rows += "".join(row(name, value, " <small>(derived)</small>") for name, value in self.derived().items())
        return f"<table><caption>{type(self).__name__}</caption>{rows}</table>"


def to_frame(results: Iterable[Result]) -> pd.DataFrame:
    """A pandas ``DataFrame`` with one row per result (their scalar fields).

    Examples
    --------
    >>> from pendulab.jobs.problems import problem5
    >>> to_frame(problem5(ns=(10, 100)).rows).columns[:3].tolist()  # doctest: +SKIP
    ['n', 'period', 'error']
    """
    pd = _pandas()
    return pd.DataFrame([r._row() for r in results])


def _pandas() -> Any:
    from ..core.extras import require

    return require("pandas", "to_frame()")


def _scalar(value: Any) -> bool:
    return isinstance(value, (*_numbers(), str)) or value is None


def _properties(cls: type) -> list[str]:
    """The public properties of ``cls`` and its bases, in the order they are defined."""
    names: list[str] = []
    for klass in reversed(cls.__mro__):
        for name, attr in vars(klass).items():
            if isinstance(attr, property) and not name.startswith("_") and name not in names:
                names.append(name)
    return names


def _plain(value: Any) -> Any:
    if isinstance(value, Result):
        return value.to_dict()
    if isinstance(value, (tuple, list)) and value and all(isinstance(v, Result) for v in value):
        return [v.to_dict() for v in value]
    return value


def _html(value: Any) -> str:
    """A short, exact rendering of one field: floats in full (repr), arrays summarised."""
    if isinstance(value, Result):
        return f"<details><summary>{type(value).__name__}</summary>{value._repr_html_()}</details>"
    if isinstance(value, (tuple, list)) and value and all(isinstance(v, Result) for v in value):
        inner = "".join(v._repr_html_() for v in value)
        return f"<details><summary>{len(value)} × {type(value[0]).__name__}</summary>{inner}</details>"
    np = _numpy()
    if np is not None and isinstance(value, np.ndarray):
        body = np.array2string(value, threshold=6, edgeitems=2, floatmode="unique", separator=", ")
        return f"array {value.shape} {value.dtype}: <code>{html.escape(body)}</code>"
    if isinstance(value, dict):
        items = "".join(f"<li>{html.escape(str(k))}: {_html(v)}</li>" for k, v in value.items())
        return f"<ul>{items}</ul>"
    if isinstance(value, float) and math.isfinite(value):
        return f"<code>{value!r}</code>"
    if isinstance(value, (*_numbers(), tuple)):
        return f"<code>{html.escape(repr(value))}</code>"
    return html.escape(str(value))

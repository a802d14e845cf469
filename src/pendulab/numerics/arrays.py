"""numpy's conventions for the public functions that take arrays (:func:`elementwise`).

As numpy's ufuncs and scipy.special do, element by element:

- a NaN (a missing value: pandas' ``NaN``/``NA``) gives NaN in that element, the others
  are computed;
- any other bad element is refused with an :class:`~pendulab.core.errors.InputError` naming
  the first one by its index and value (``amplitude[3] = 4 is not allowed: ...``);
- a pandas ``Series`` gives a ``Series`` with its index and name; a masked array a masked
  array with the same mask (a masked element is missing, whatever its value);
- a scalar, a numpy scalar or a 0-d array gives a Python ``float``.

A function that returns a result object gets the same treatment in the result's arrays:
NaN where an input was missing, Python floats where every input was a scalar; a Series
or a masked array is taken as its values (missing where masked).
"""
from __future__ import annotations

import dataclasses
import functools
import inspect
import math
import numbers
import sys
from collections.abc import Callable
from typing import Any, TypeVar

from ..core.errors import InputError
from .results import Result

F = TypeVar("F", bound=Callable[..., Any])

__all__ = ["elementwise"]


def elementwise(**placeholders: float) -> Callable[[F], F]:
    """Give the function numpy's conventions for the array parameters named.

    ``placeholders``: parameter name -> a valid value computed in place of a missing element
    (and then replaced by NaN in the answer): ``elementwise(length=1.0, amplitude=0.0)``.
    """
    def decorate(func: F) -> F:
        signature = inspect.signature(func)
        slots = [(name, list(signature.parameters).index(name)) for name in placeholders]

        @functools.wraps(func)
        def wrapper(*args: Any, **kwargs: Any) -> Any:
            for name, i in slots:  # Python numbers, none NaN: the call as it is (a scalar's microseconds)
                x = args[i] if i < len(args) else kwargs.get(name)
                if (type(x) is not float and type(x) is not int) or x != x:
                    break
            else:
                out = func(*args, **kwargs)
                return _Inputs()._result(out) if isinstance(out, Result) else out
            bound = signature.bind(*args, **kwargs)
            given = _Inputs()
            for name, fill in placeholders.items():
                if name in bound.arguments:
                    bound.arguments[name] = given.take(name, bound.arguments[name], fill)
            try:
                out = func(*bound.args, **bound.kwargs)
            except InputError as exc:
                raise given.indexed(exc) from None
            return given.give(out)

        return wrapper  # type: ignore[return-value]

    return decorate


class _Inputs:
    """What the array arguments of one call were: their missing elements, Series, masks."""

    def __init__(self) -> None:
        self.scalar = True  # every array argument was a scalar
        self.missing_scalar = False  # a scalar argument was NaN
        self.missing: list[Any] = []  # boolean arrays: the missing elements of each argument
        self.masked = False
        self.series: tuple[Any, Any] | None = None  # (index, name) of the first Series
        self.arrays: dict[str, Any] = {}  # name -> the array computed on, for an error's index

    def take(self, name: str, x: Any, fill: float) -> Any:
        """The argument to compute on: NaN and masked elements replaced by ``fill``."""
        if x is None or isinstance(x, str) or (isinstance(x, numbers.Real) and not hasattr(x, "shape")):
            if isinstance(x, float) and math.isnan(x):
                self.missing_scalar = True
                return fill
            return x
        import numpy as np

        if _is_series(x):
            if self.series is None:
                self.series = (x.index, x.name)
            x = x.to_numpy(dtype=float, na_value=np.nan)
        if np.ma.isMaskedArray(x):
            mask = np.ma.getmaskarray(x)
            data = np.array(np.ma.getdata(x), dtype=float)
            data[mask] = np.nan
            self.masked = True
            x = data
        try:
            arr = np.asarray(x, dtype=float)
        except (TypeError, ValueError):
            return x  # not numbers: the function refuses it in its own words
        if arr.ndim == 0:
            value = float(arr)
            if math.isnan(value):
                self.missing_scalar = True
                return fill
            return value
        self.scalar = False
        nan = np.isnan(arr)
        if nan.any():
            self.missing.append(nan)
            arr = np.where(nan, fill, arr)
        self.arrays[name] = arr
        return arr

    def indexed(self, exc: InputError) -> InputError:
        """``exc`` naming the first element of its argument with its value, where it is an array's."""
        arr = self.arrays.get(exc.name)
        if arr is None or getattr(exc, "index", None) is not None:
            return exc
        import numpy as np

        try:
            at = np.flatnonzero(arr == float(exc.value))  # type: ignore[arg-type]
        except (TypeError, ValueError):
            return exc
        if not at.size:
            return exc
        index = tuple(int(i) for i in np.unravel_index(int(at[0]), arr.shape))
        return InputError(exc.name, exc.value, exc.allowed, mentions=exc.mentions, alternative=exc.alternative,
                          index=index)

    def give(self, out: Any) -> Any:
        """The answer in the form of the arguments: NaN where missing, a Series, a mask, a float."""
        if isinstance(out, Result):
            return self._result(out)
        if self.scalar:
            if self.missing_scalar and isinstance(out, numbers.Real):
                return math.nan
            return float(out) if isinstance(out, numbers.Real) else out
        import numpy as np

        if not isinstance(out, np.ndarray):
            return out
        missing = self._missing(out.shape)
        if missing is not None and missing.any():
            out = np.where(missing, np.nan, out)
        if self.masked:
            out = np.ma.masked_array(out, mask=np.zeros(out.shape, bool) if missing is None else missing)
        if self.series is not None and out.ndim == 1 and len(self.series[0]) == out.shape[0]:
            pd = sys.modules["pandas"]  # loaded: a Series was given
            out = pd.Series(out, index=self.series[0], name=self.series[1])
        return out

    def _missing(self, shape: tuple[int, ...]) -> Any:
        """Where the answer of that shape has a missing input element (broadcast), or None."""
        import numpy as np

        if not self.missing and not self.missing_scalar:
            return None
        missing = np.zeros(shape, bool)
        if self.missing_scalar:  # a scalar missing: every element
            missing[...] = True
        for m in self.missing:
            try:
                missing |= np.broadcast_to(m, shape)
            except ValueError:  # an array of the result that is not element by element
                return None
        return missing

    def _result(self, out: Result) -> Result:
        """A result's arrays with NaN where an input was missing; 0-d arrays as floats."""
        import numpy as np

        changes: dict[str, Any] = {}
        for f in dataclasses.fields(out):  # type: ignore[arg-type]
            value = getattr(out, f.name)
            if isinstance(value, np.ndarray):
                changes[f.name] = self._array(value)
            elif isinstance(value, np.floating) and self.scalar:
                changes[f.name] = math.nan if self.missing_scalar else float(value)
            elif isinstance(value, dict) and value and all(isinstance(v, np.ndarray) for v in value.values()):
                changes[f.name] = {k: self._array(v) for k, v in value.items()}
        changes = {k: v for k, v in changes.items() if v is not getattr(out, k)}
        return dataclasses.replace(out, **changes) if changes else out  # type: ignore[type-var]

    def _array(self, value: Any) -> Any:
        import numpy as np

        if value.dtype.kind != "f":
            return value
        if self.scalar and value.ndim == 0:
            return math.nan if self.missing_scalar else float(value)
        missing = self._missing(value.shape) if value.ndim else None
        if missing is None or not missing.any():
            return value
        return np.where(missing, np.nan, value)


def _is_series(x: Any) -> bool:
    """Whether ``x`` is a pandas Series (pandas is not imported to find out: it is loaded if
    someone made one)."""
    pd = sys.modules.get("pandas")
    return pd is not None and isinstance(x, pd.Series)

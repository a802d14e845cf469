"""Optional dependencies: import one, or say in one line which extra installs it; and a
package's names loaded on first use (:func:`lazy`).

The core (``pip install pendulab``) computes periods and simulations with numpy, scipy,
mpmath, numba and click; the rest comes with the extras of ``pyproject.toml``.
"""
from __future__ import annotations

import importlib
import importlib.util
import sys
from types import ModuleType

from .errors import MissingExtraError

TYPE_CHECKING = False  # typing unimported: ``import pendulab`` loads this module (see pendulab/__init__.py)
if TYPE_CHECKING:
    from collections.abc import Callable
    from typing import Any

#: Top-level package -> the extra of pyproject.toml that installs it.
EXTRA_OF = {
    "matplotlib": "report",
    "typst": "report",
    "fastapi": "web",
    "uvicorn": "web",
    "orjson": "web",
    "swagger_ui_bundle": "web",
    "pyarrow": "sweep",
    "dask": "dask",
    "distributed": "dask",
    "pandas": "pandas",
}


def require(module: str, purpose: str) -> ModuleType:
    """Import ``module``; when its package is missing raise :class:`MissingExtraError`.

    Parameters
    ----------
    module : str
        A module of one of the packages in :data:`EXTRA_OF` (``"pyarrow.parquet"``).
    purpose : str
        What needs it, in words (``"writing .parquet files"``); the message starts with it.
    """
    top = module.partition(".")[0]
    try:
        return importlib.import_module(module)
    except ModuleNotFoundError as exc:
        # Only the package itself being absent is "not installed"; a broken install re-raises.
        if not _absent(top):
            raise
        extra = EXTRA_OF[top]
        raise MissingExtraError(
            f"{purpose} needs {top}, which is not installed: {install_command(extra)}",
            name=top,
        ) from exc


def install_command(extra: str) -> str:
    """The command that installs ``pendulab[extra]`` into the Python running this one, the way
    this copy was installed: ``.venv/bin/python -m pip install -e '.[pandas]'`` for a clone
    (its ``src/`` beside ``pyproject.toml``), ``pip install 'pendulab[pandas]'`` for a package."""
    import os
    from pathlib import Path

    here = Path(__file__).resolve().parents[2]  # .../src (a clone) or .../site-packages
    root = here.parent
    if here.name != "src" or not (root / "pyproject.toml").is_file():
        return f"pip install 'pendulab[{extra}]'"

    def shown(path: Path) -> str:  # relative to the working folder where it lies inside it
        try:
            rel = os.path.relpath(path)
        except ValueError:  # another drive
            return str(path)
        return rel if not rel.startswith("..") else str(path)

    python = shown(Path(sys.executable)) if sys.executable else "python"
    if "/" not in python and os.sep not in python:
        python = sys.executable
    return f"{python} -m pip install -e '{shown(root)}[{extra}]'"


def _absent(package: str) -> bool:
    """True when ``package`` cannot be imported at all (``None`` in ``sys.modules`` blocks it)."""
    if package in sys.modules:
        return sys.modules[package] is None
    return importlib.util.find_spec(package) is None


def lazy(package: str, where: dict[str, str], names: list[str]) -> tuple[Callable[[str], Any], Callable[[], list[str]]]:
    """A package's ``__getattr__`` and ``__dir__`` (PEP 562) that import ``where[name]``, the
    submodule defining ``name``, on first use and keep the value in the package's namespace."""
    namespace = vars(sys.modules[package])

    def getattr_(name: str) -> Any:
        if name in where:
            value = getattr(importlib.import_module(f"{package}.{where[name]}"), name)
            namespace[name] = value
            return value
        raise AttributeError(f"module {package!r} has no attribute {name!r}")

    def dir_() -> list[str]:  # the public names only: not the module's helpers (TYPE_CHECKING, lazy)
        return sorted(names)

    return getattr_, dir_

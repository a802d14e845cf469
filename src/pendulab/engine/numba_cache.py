"""Where numba caches the compiled kernels, and what happens when it cannot.

numba keeps compiled kernels beside the source (``__pycache__``) or in the user's cache
folder; where neither is writable (a read-only install run by a service account whose
home is not writable), ``cache=True`` fails at import ("no locator available"). Then
:func:`setup` points numba at a private folder in the temporary directory, or, where that
fails too, turns caching off (each process compiles), and says which in one line on
stderr. A cache file that cannot be read back (truncated, or garbage) is treated as
missing: the kernel is compiled again and the file rewritten, instead of an
``UnpicklingError`` on every run. Called by :mod:`pendulab.engine.agm`, the first module with
kernels, before them.

numba keeps a cached kernel while the text of the file that defines it is unchanged, but a
kernel also holds what it inlines from other files (``mean.agm`` in ``agm_means``, the step
of ``engine.kernels`` in the sweep's lanes, ``methods``' codes): a cached kernel of this package is
kept only while every file of :data:`KERNEL_SOURCES` is unchanged too.
"""
from __future__ import annotations

import contextlib
import hashlib
import os
import sys
import tempfile
from typing import Any

from numba.core import caching
from numba.core import config as _config
from numba.core import dispatcher as _dispatcher

config: Any = _config  # CACHE_DIR is set at numba's import, from NUMBA_CACHE_DIR

_DONE: list[str] = []

#: The package's files that compiled code is made of: the modules with kernels and,
#: transitively, the package modules they import (tests/test_layers.py checks the list).
KERNEL_SOURCES = (
    "core/errors.py", "core/interrupt.py", "core/methods.py",
    "engine/agm.py", "engine/fold.py", "engine/kernels.py", "engine/lanes.py",
    "engine/mean.py", "engine/numba_cache.py",
)
#: The package's folder: KERNEL_SOURCES are relative to it.
_PACKAGE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def _sources_digest() -> bytes:
    """SHA-256 of the text of every file of :data:`KERNEL_SOURCES` (a missing one counts as empty)."""
    digest = hashlib.sha256()
    for name in KERNEL_SOURCES:
        digest.update(name.encode())
        with contextlib.suppress(OSError), open(os.path.join(_PACKAGE, name), "rb") as f:
            digest.update(hashlib.sha256(f.read()).digest())
    return digest.digest()


def _stamp_kernels_by_their_sources() -> None:
    """A kernel of this package is cached under the digest of its own file and of
    :data:`KERNEL_SOURCES`: editing a file it inlines compiles it again."""
    mixin: Any = caching._SourceFileBackedLocatorMixin
    own = mixin.get_source_stamp
    sources = _sources_digest()

    def get_source_stamp(self: Any) -> Any:
        stamp = own(self)
        if os.path.abspath(self._py_file).startswith(_PACKAGE + os.sep):
            return (stamp, sources)
        return stamp

    mixin.get_source_stamp = get_source_stamp


def _usable(py_file: str) -> bool:
    """Whether one of numba's cache locators can cache a function of ``py_file`` (each tries
    to create its folder and a file in it)."""
    def probe() -> None:  # any function: the locators read its first line number only
        pass

    locators: list[Any] = caching.CacheImpl._locator_classes
    return any(cls.from_function(probe, py_file) is not None for cls in locators)


def _tolerate_corrupt_files() -> None:
    """An index or data file that fails to unpickle reads as absent (numba then compiles
    and overwrites it); numba itself lets only a missing file pass."""
    index_file = caching.IndexDataCacheFile
    load_index, load_data = index_file._load_index, index_file._load_data

    def _load_index(self):
        try:
            return load_index(self)
        except Exception:
            return {}

    def _load_data(self, name):
        try:
            return load_data(self, name)
        except OSError:
            raise
        except Exception as exc:
            raise OSError(f"unreadable numba cache file {name!r}: {exc}") from None

    index_file._load_index, index_file._load_data = _load_index, _load_data  # type: ignore[method-assign]

    # A cache file that cannot be replaced (a folder in its place, a read-only file system):
    # the kernel compiled in this process runs, and one note says it is not kept.
    save = caching.Cache.save_overload
    told: list[bool] = []

    def save_overload(self, sig, data):
        try:
            save(self, sig, data)
        except OSError as exc:
            if not told:
                told.append(True)
                with contextlib.suppress(OSError, ValueError):
                    print(f"pendulab: note: a compiled kernel cannot be cached ({exc.strerror or exc}: "
                          f"{exc.filename}); it is compiled again on the next run", file=sys.stderr)

    caching.Cache.save_overload = save_overload  # type: ignore[method-assign]


def setup(py_file: str) -> str:
    """Make ``cache=True`` work for the kernels of ``py_file``; return what was done:
    ``"default"``, ``"temporary"`` (a folder in the temporary directory) or ``"off"``."""
    if _DONE:
        return _DONE[0]
    _tolerate_corrupt_files()
    _stamp_kernels_by_their_sources()
    how = "default"
    if not _usable(py_file):
        uid = os.getuid() if hasattr(os, "getuid") else 0
        try:  # gettempdir raises where no temporary folder is writable: then caching is off
            folder = os.path.join(tempfile.gettempdir(), f"pendulab-numba-cache-{uid}")
            os.makedirs(folder, mode=0o700, exist_ok=True)
            st = os.lstat(folder)  # ours, and not a link another user planted in a shared /tmp
            mine = st.st_uid == uid and not os.path.islink(folder)
        except OSError:
            mine = False
        config.CACHE_DIR = folder if mine else ""
        if mine and _usable(py_file):
            how = "temporary"
            note = f"compiled kernels are cached in {folder} (the package's folder and the user's cache folder are not writable)"
        else:
            config.CACHE_DIR = ""
            how = "off"
            # No folder can hold a cache: the dispatchers keep numba's null cache (compiled
            # once per process) instead of failing at import.
            _dispatcher.Dispatcher.enable_caching = lambda self: None  # type: ignore[method-assign]
            note = "no writable folder for compiled kernels: each run compiles them (seconds)"
        with contextlib.suppress(OSError):
            print(f"pendulab: note: {note}; set NUMBA_CACHE_DIR to a writable folder to choose", file=sys.stderr)
    _DONE.append(how)
    return how

"""numba's cache of the package's kernels: a kernel compiled from several files is compiled
again when any of them changes, not only its own (numba checks its own file only)."""
from __future__ import annotations

import shutil
from pathlib import Path

from numba.core import caching

from pendulab.engine import kernels, numba_cache


def test_a_kernel_is_stamped_with_the_files_it_inlines(tmp_path, monkeypatch):
    """The stamp of a cached kernel changes with ``mean.py`` (inlined into ``agm_means``)
    and stays with a file outside :data:`KERNEL_SOURCES`."""
    package = Path(numba_cache.__file__).parents[1]
    copy = tmp_path / "pendulab"
    shutil.copytree(package, copy, ignore=shutil.ignore_patterns("__pycache__"))
    monkeypatch.setattr(numba_cache, "_PACKAGE", str(copy))
    before = numba_cache._sources_digest()
    (copy / "cli" / "core.py").write_text("# another command line\n")
    assert numba_cache._sources_digest() == before
    (copy / "engine" / "mean.py").write_text((copy / "engine" / "mean.py").read_text() + "\n# an edit\n")
    assert numba_cache._sources_digest() != before


def test_the_locator_of_a_package_kernel_gives_the_combined_stamp():
    """The stamp numba writes beside ``agm_means`` holds the sources' digest; a function of
    another file keeps numba's own stamp."""
    locator = caching.InTreeCacheLocator(kernels.agm_means.py_func, kernels.__file__)
    stamp = locator.get_source_stamp()
    assert isinstance(stamp, tuple) and stamp[1] == numba_cache._sources_digest()
    other = caching.InTreeCacheLocator(test_a_kernel_is_stamped_with_the_files_it_inlines, __file__)
    assert isinstance(other.get_source_stamp(), bytes)

"""The background warm-up compiles exactly the specialisations the library then calls."""
from pendulab.engine import kernels
from pendulab.engine.warm import warm_kernels
from pendulab.numerics.crossing import estimate_period
from pendulab.numerics.simulation import simulate

KERNELS = ("drive", "search_return")


def test_warm_up_covers_the_library_calls():
    thread = warm_kernels()
    thread.join(timeout=600)
    assert not thread.is_alive()
    assert warm_kernels() is thread  # once per process
    warmed = {k: set(getattr(kernels, k).signatures) for k in KERNELS}
    assert all(warmed.values())
    estimate_period(1.0, 1.0, 1e-2)
    simulate(2.0, 0.5, 0.01, 1.0)
    simulate(2.0, 0.5, 0.01, 1.0, stride=10)
    # No call needed a specialisation the warm-up did not compile.
    assert {k: set(getattr(kernels, k).signatures) for k in KERNELS} == warmed

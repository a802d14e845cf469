"""The compiled kernels (numba): one trajectory driver, one period search, the AGM in double
and double-double precision, the sweep's lock-step lanes, the explorer's fold, their warm-up
and numba's cache. Above ``core`` only."""

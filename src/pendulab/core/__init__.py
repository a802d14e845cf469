"""The base layer: errors, ``Exact``, the coursework's cases, the method registry, the parser
of what a person types, the validators of what the library is given, atomic files, optional
imports and signals deferred around kernels. It imports nothing else of the package."""

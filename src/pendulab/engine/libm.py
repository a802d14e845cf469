"""``sin`` and ``cos`` for the numba kernels: direct calls of the C library's functions.

Each step of (3) is two calls, ``sin`` and ``cos``, and little else (about 60 cycles), so
the way they are called shows. numba lowers ``math.sin`` and ``math.cos`` to LLVM's
intrinsics, and then

* LLVM merges a ``sin(x)`` and a ``cos(x)`` of the same ``x`` into one ``sincos``, which
  on this project's machine (x86-64, glibc 2.36) is no faster than ``sin`` then ``cos``
  and at problem 3's amplitude up to 5% slower: it runs about 20% fewer instructions
  (cachegrind), but the ``sin`` that the next step waits for comes only with the ``cos``;
* numba links ``sin`` to a bridge of its own (``numba_sin``, which jumps to ``sin``
  through the C library's PLT): one call, two jumps.

:data:`sin` and :data:`cos` call the functions of the process's C library (the very
ones ``math.sin`` and ``math.cos`` call) at their resolved addresses, under names LLVM
does not know (so nothing is merged). The results are bit for bit those of ``math.sin``
and ``math.cos`` (tests/test_libm.py). Where the process exposes no ``sin`` (Windows:
``ctypes.CDLL(None)`` fails), the names point at numba's own bridge, which is what
``math.sin`` in a kernel calls. The names are registered with LLVM when this module is
imported, before any kernel is compiled or loaded from numba's cache (which keeps the
name, not the address).
"""
from __future__ import annotations

import ctypes

import llvmlite.binding as llvm  # type: ignore[import-untyped]
from llvmlite import ir
from numba import types
from numba.extending import intrinsic


def _address(name: str) -> int:
    """The address of the C library's ``name`` in this process, or numba's bridge to it."""
    try:
        address = ctypes.cast(getattr(ctypes.CDLL(None), name), ctypes.c_void_p).value
    except (OSError, TypeError, AttributeError):  # no dlopen(NULL) (Windows), or no such symbol
        address = None
    if not address:
        from numba import _helperlib

        address = _helperlib.c_helpers[name]  # type: ignore[attr-defined]  # no stub
    return int(address)


def _c_function(name: str):
    """An intrinsic ``f(x) -> float64`` that calls the C library's ``name`` directly."""
    symbol = f"pendulab_libm_{name}"
    llvm.add_symbol(symbol, _address(name))

    def call(typingctx, x):
        if not isinstance(x, (types.Float, types.Integer)):
            return None

        def codegen(context, builder, signature, args):
            value = context.cast(builder, args[0], signature.args[0], types.float64)
            fn = builder.module.globals.get(symbol)
            if fn is None:
                fn = ir.Function(builder.module, ir.FunctionType(ir.DoubleType(), [ir.DoubleType()]), symbol)
                fn.attributes.add("nounwind")
            return builder.call(fn, [value])

        return types.float64(x), codegen

    call.__name__ = call.__qualname__ = name  # the intrinsic's name in numba's messages
    return intrinsic(call)


#: ``sin(x)``: the C library's, as ``math.sin``; never merged with a ``cos`` into ``sincos``.
sin = _c_function("sin")
#: ``cos(x)``: the C library's, as ``math.cos``; never merged with a ``sin`` into ``sincos``.
cos = _c_function("cos")

"""Leaf models handed to compiled loops by address: one compiled function per model.

A model of :mod:`.atmosphere`, :mod:`.wind` or :mod:`.drag_coefficient` is one
numba-compiled function of its kind's signature, which evaluates the model's
equations from its parameters array at a set of points (altitudes, Reynolds
numbers) into output arrays, and its parameters.  The loops of its module
(and through them the NumPy methods of the model classes and the solvers'
kernels) take the function as the address of its compiled code, an integer:
an argument numba reads as cheaply as a float, where a function object
(numba's first-class function type) costs 17-45 us per call of a kernel to
unbox (numba 0.68, measured), a third of an FE time step of the default
case.  :func:`caller` turns the address back into a function of the
signature inside compiled code.  One call per set of points, not per point:
a call through an address is not inlined (per point, a two-profile wind at
40 altitudes took 3.5 instead of 1.6 us).  The kernels take a model's
address, parameters and constant as separate arguments, not as a tuple: a
tuple holding an array costs about 0.25 us more to read per call (measured).

An address holds in the process that compiled (or loaded) the function only:
a model computes its ``compiled`` form when asked, so it is the model that
travels to another process, never that form.  :func:`caller` and
:func:`address` use numba's layout of a first-class function value (its
``jit_addr``, the entry of numba's calling convention); the models' tests
run every function through them.

The functions and loops compile when first called, not when imported, and
are cached on disk next to their modules (numba's ``cache=True``).  A
solver's kernel caches the loops it calls with it (numba checks a cache
against its own source file only), but not the models' functions, which it
calls by address: a model edited is a model compiled again.
"""

from __future__ import annotations

import functools

import numba
from numba.core import cgutils, types
from numba.core.typing.templates import Signature
from numba.experimental.function_type import _get_jit_address
from numba.extending import intrinsic


def jit(func):
    """``func`` compiled by numba in nopython mode on first use (cached on disk;
    NumPy's error model: a division by zero gives inf, not an exception)."""
    return numba.njit(cache=True, error_model="numpy")(func)


@functools.cache
def address(function, signature: Signature) -> int:
    """The entry point of ``function`` (a :func:`jit` function) compiled for
    ``signature`` (compiled now, or loaded from the cache, if it was not)."""
    function.compile(signature)
    return _get_jit_address(function, signature)


def caller(signature: Signature):
    """A compiled-code function ``call(address)`` giving the function of
    ``signature`` at that address (:func:`address`), to be called there."""
    function_type = types.FunctionType(signature)

    @intrinsic
    def call(typingctx, address_type):
        def codegen(context, builder, sig, args):
            fn = cgutils.create_struct_proxy(function_type)(context, builder)
            fn.jit_addr = builder.inttoptr(args[0], context.get_value_type(types.voidptr))
            return fn._getvalue()
        return function_type(types.intp), codegen

    return call

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
calls by address: a model edited is a model compiled again.  Whether numba's
cache holds a module's functions as its source is now is read from the
cache's index files, without importing the module (:func:`cached`), and the
compiles of a block are shown as they happen (:func:`compiling`, from
numba's compile events, which fire on a cache miss only).
"""

from __future__ import annotations

import importlib.util
import pickle
import sys
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path

import numba
from numba.core import caching, cgutils, event, types
from numba.core.typing.templates import Signature
from numba.experimental.function_type import _get_jit_address
from numba.extending import intrinsic

from fem_tether.core.progress import Progress


def jit(func):
    """``func`` compiled by numba in nopython mode on first use (cached on disk;
    NumPy's error model: a division by zero gives inf, not an exception)."""
    return numba.njit(cache=True, error_model="numpy")(func)


#: The addresses :func:`address` gave, by the identities of the function and the signature
#: (with both, which keep those identities theirs).
_ADDRESSES: dict[tuple[int, int], tuple[int, object, Signature]] = {}


def address(function, signature: Signature) -> int:
    """The entry point of ``function`` (a :func:`jit` function) compiled for
    ``signature`` (compiled now, or loaded from the cache, if it was not).
    Remembered by the objects' identities: hashing a numba signature costs
    several µs, and a model's NumPy method asks for its address at every call."""
    key = (id(function), id(signature))
    known = _ADDRESSES.get(key)
    if known is None:
        function.compile(signature)
        known = _ADDRESSES[key] = (_get_jit_address(function, signature), function, signature)
    return known[0]


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


def _locator(source: str):
    """numba's cache locator of the functions of the file ``source``: the first of
    its locators that applies, as numba picks it (NUMBA_CACHE_DIR, else
    ``__pycache__`` beside the source if writable, else the user's cache); None
    if none does (numba then cannot cache them)."""
    kinds: list = caching.CacheImpl._locator_classes
    for kind in kinds:
        locator = kind.from_function(_locator, source)
        if locator is not None:
            return locator
    return None


def cached(module: str) -> bool:
    """Whether numba's cache holds functions of ``module`` compiled from its source
    as it is now: an index file of one of them (``<file>.<function>-<line>.pyXY.nbi``)
    where numba looks (:func:`_locator`), written by this numba for this source
    (its stamp, a hash of its content).  Reads index files only, until a fresh
    one: the module is not imported (that would compile it).  With numba's
    compiler off (``NUMBA_DISABLE_JIT``) nothing compiles: True."""
    if getattr(numba.config, "DISABLE_JIT", False):      # numba sets its settings at import
        return True
    spec = importlib.util.find_spec(module)
    source = spec.origin if spec else None
    locator = _locator(source) if source else None
    if source is None or locator is None:
        return False
    stamp = locator.get_source_stamp()
    tag = f"py{sys.version_info.major}{sys.version_info.minor}{getattr(sys, 'abiflags', '')}"
    for index in Path(locator.get_cache_path()).glob(f"{Path(source).stem}.*.{tag}.nbi"):
        try:
            with open(index, "rb") as f:
                if pickle.load(f) == numba.__version__ and pickle.loads(f.read())[0] == stamp:
                    return True
        except Exception:        # an index being replaced, or unreadable: numba's to rewrite
            continue
    return False


@contextmanager
def compiling(expected: dict[str, tuple[int, float]], notice: str,
              elsewhere_s: float = 0.0) -> Iterator[Callable[[], None]]:
    """Show numba's compiles of the block as progress on stderr
    (:class:`~fem_tether.core.progress.Progress`): ``notice`` at once, then the
    compiles done of ``expected`` (module -> its compiles and their seconds),
    the ETA weighed by those seconds.  ``elsewhere_s``: the seconds other
    processes compile meanwhile, which the block waits for at its end (one more
    step of the count, the time they take beyond this process's).  Yields
    what redraws the progress (the elapsed time) while the block waits.  On a
    terminal the notice is a line of its own above the bar (too long to share
    its line)."""
    here_s = sum(s for _, s in expected.values())
    total = sum(n for n, _ in expected.values()) + (elsewhere_s > 0.0)
    seconds = max(here_s, elsewhere_s)
    bar = Progress(total, notice)
    if bar.tty:
        bar.stream.write(notice + "\n")
        bar.label = "compiling"
    count, spent = 0, 0.0

    def redraw() -> None:
        bar.update(min(count, total - 1), (min(spent, seconds), seconds))

    class Compiled(event.Listener):
        def on_start(self, ev) -> None:
            pass

        def on_end(self, ev) -> None:
            nonlocal count, spent
            share = expected.get(ev.data["dispatcher"].py_func.__module__)
            if share is not None:
                count, spent = count + 1, spent + share[1] / share[0]
                redraw()

    bar.start(0, (0.0, seconds))
    try:
        with event.install_listener("numba:compile", Compiled()):
            yield redraw
        bar.update(total, (seconds, seconds))
    finally:
        bar.close()

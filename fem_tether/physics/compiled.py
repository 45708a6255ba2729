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
calls by address: a model edited is a model compiled again.  Which compiles
of a module's functions numba's cache holds as its source is now is read from
the cache's index files, without importing the module (:func:`held`; what a
run would compile of them: :func:`missing`); the compiles of a block are shown
as they happen (:func:`compiling`, from numba's compile events, which fire on
a cache miss only) and measured (:func:`recording`).
"""

from __future__ import annotations

import importlib.util
import pickle
import sys
import time
from collections.abc import Callable, Iterator, Mapping
from contextlib import contextmanager
from dataclasses import dataclass
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


def held(module: str) -> dict[str, int]:
    """The compiles (signatures) numba's cache holds of each function of ``module``
    (by its qualified name) compiled from its source as it is now: the entries of the
    function's index file (``<file>.<function>-<line>.pyXY.nbi``) where numba looks
    (:func:`_locator`), written by this numba for this source (its stamp, a hash
    of its content); 0 for a function whose index is of another source or numba (a
    function compiled before).  Reads index files only: the module is not imported (that
    would compile it)."""
    spec = importlib.util.find_spec(module)
    source = spec.origin if spec else None
    locator = _locator(source) if source else None
    if source is None or locator is None:
        return {}
    stamp = locator.get_source_stamp()
    tag = f".py{sys.version_info.major}{sys.version_info.minor}{getattr(sys, 'abiflags', '')}.nbi"
    stem = Path(source).stem + "."
    compiles: dict[str, int] = {}
    for index in Path(locator.get_cache_path()).glob(f"{stem}*{tag}"):
        function = index.name[len(stem):-len(tag)].rpartition("-")[0]
        compiles.setdefault(function, 0)
        try:
            with open(index, "rb") as f:
                if pickle.load(f) != numba.__version__:
                    continue
                index_stamp, overloads = pickle.loads(f.read())
        except Exception:        # an index being replaced, or unreadable: numba's to rewrite
            continue
        if index_stamp == stamp:
            compiles[function] += len(overloads)
    return compiles


def missing(module: str, compiles: Mapping[str, tuple[int, float]]) -> dict[str, tuple[int, float]]:
    """Of ``compiles`` (function of ``module`` -> the compiles a run makes of it and
    their seconds), those numba's cache does not hold (:func:`held`), with their
    share of the seconds: a function holding fewer compiles than the run makes
    compiles the rest (numba keys its cache by signature, which an index does not
    say without unpickling numba's types, so any compile held counts as one of
    the run's).  With numba's compiler off (``NUMBA_DISABLE_JIT``) nothing compiles."""
    if getattr(numba.config, "DISABLE_JIT", False):      # numba sets its settings at import
        return {}
    there = held(module)
    lacking = {f: (n - there.get(f, 0), seconds_s) for f, (n, seconds_s) in compiles.items()}
    return {f: (n, seconds_s * n / compiles[f][0]) for f, (n, seconds_s) in lacking.items() if n > 0}


#: A compiled function by its module and qualified name.
Function = tuple[str, str]


def _function(ev) -> Function:
    py_func = ev.data["dispatcher"].py_func
    return py_func.__module__, py_func.__qualname__


@contextmanager
def compiling(expected: Mapping[Function, tuple[int, float]], notice: str, seconds_s: float,
              elsewhere: bool = False) -> Iterator[Callable[[], None]]:
    """Show numba's compiles of the block as progress on stderr
    (:class:`~fem_tether.core.progress.Progress`): ``notice`` at once, then the
    compiles done of ``expected`` (function -> its compiles to come and their seconds,
    :func:`missing`), the ETA weighed by those seconds, the block taking ``seconds_s``.
    ``elsewhere``: other processes compile meanwhile, and the block waits for them at
    its end (one more step of the count; they may compile some of ``expected``, numba's
    cache being theirs too, so the count may then jump at the end).  Yields
    what redraws the progress (the elapsed time) while the block waits.  On a
    terminal the notice is a line of its own above the bar (too long to share
    its line)."""
    here_s = sum(s for _, s in expected.values())
    total = sum(n for n, _ in expected.values()) + elsewhere
    bar = Progress(total, notice)
    if bar.tty:
        bar.stream.write(notice + "\n")
        bar.label = "compiling"
    count, spent = 0, 0.0

    def redraw() -> None:
        bar.update(min(count, total - 1), (min(spent / here_s if here_s else 1.0, 1.0) * seconds_s, seconds_s))

    class Compiled(event.Listener):
        def on_start(self, ev) -> None:
            pass

        def on_end(self, ev) -> None:
            nonlocal count, spent
            share = expected.get(_function(ev))
            if share is not None:
                count, spent = count + 1, spent + share[1] / share[0]
                redraw()

    bar.start(0, (0.0, seconds_s))
    try:
        with event.install_listener("numba:compile", Compiled()):
            yield redraw
        bar.update(total, (seconds_s, seconds_s))
    finally:
        bar.close()


@dataclass
class Compile:
    """One compile numba made (a function for one signature): when it started and ended
    (``time.perf_counter``) and the CPU seconds of this thread it took, its own (without the
    compiles of the functions of ``package`` inside it, with numba's own, :func:`recording`)."""

    function: Function
    start_s: float
    end_s: float = 0.0
    cpu_s: float = 0.0


@contextmanager
def recording(package: str = "fem_tether") -> Iterator[list[Compile]]:
    """The compiles of functions of ``package`` in the block, in the order they
    ended: the measure of a first run (:data:`fem_tether.tether.kernels.FIRST_COMPILE`).
    A compile of one of numba's functions (its library's overloads, compiled into
    the function that calls them) counts as the CPU time of the compile of ``package``
    it happens in; CPU time, not the wall clock, so that other processes on the
    machine do not count."""
    done: list[Compile] = []
    open_: list[tuple[Compile | None, float, list[float]]] = []        # the compile, its CPU start, inside

    class Recorder(event.Listener):
        def on_start(self, ev) -> None:
            function = _function(ev)
            ours = function[0].split(".")[0] == package
            open_.append((Compile(function, time.perf_counter()) if ours else None, time.thread_time(), [0.0]))

        def on_end(self, ev) -> None:
            compile_, cpu_start, inside = open_.pop()
            took_s = time.thread_time() - cpu_start
            if compile_ is not None:
                compile_.end_s, compile_.cpu_s = time.perf_counter(), took_s - inside[0]
                done.append(compile_)
            if open_:
                open_[-1][2][0] += took_s if compile_ is not None else inside[0]

    with event.install_listener("numba:compile", Recorder()):
        yield done

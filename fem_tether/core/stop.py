"""One stop for every rank: an interrupt or a failure on any MPI rank ends them all.

A rank that is interrupted (Ctrl-C, or a signal to that rank alone) or fails
tells every other rank, over a communicator of its own, its exit code and the
one line to print.  Each rank's watcher thread polls for that message and
interrupts its main thread, which raises :class:`KeyboardInterrupt` wherever
it is (between two bytecodes; a compiled kernel call finishes first).  The
package calls no blocking collective: the ranks wait for each other and
exchange values point to point, in an interruptible loop (:func:`sync`,
:func:`share`, :func:`collect`, :func:`exchange`), so no rank waits for one
that stopped.  The CLI then prints one line on rank 0 and every rank exits
with the same code (:func:`exit_code`).

Ctrl-C is remembered until the command has stopped, and the long loops ask
for it (:func:`checkpoint`): Python drops a ``KeyboardInterrupt`` raised
inside a finaliser.  Ctrl-C while the libraries load (before any rank could
tell the others) is held back (:func:`defer_interrupts`) until the command
starts inside its guard, so that it too stops every rank.

Without MPI (one process) :func:`guard` does nothing.
"""

from __future__ import annotations

import _thread
import pickle
import signal
import sys
import threading
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import TypeVar, cast

T = TypeVar("T")

#: Exit codes: a user's mistake, a failed solve (or a defect), an interrupt.
EXIT_USAGE, EXIT_FAILED, EXIT_INTERRUPTED = 2, 1, 130

#: Tag of the stop message on the guard's own communicator.
STOP_TAG = 17

#: How often the watcher looks for a stop message, and rank 0 for the others' word that they stopped [s].
POLL_S = 0.05
#: A waiting rank's first pause between its looks for its message [s], doubled after each look up
#: to :data:`WAIT_MAX_S` (:func:`wait`): a message that comes at once is seen within a millisecond
#: or two, one that comes late within 10 ms, at a hundred looks a second (a look: microseconds).
#: With a fixed 50 ms pause each handover between the ranks (the main job's five syncs and its
#: flight's handoff) was seen 25 ms late on average, while the other rank waited (issue 33).
WAIT_FIRST_S = 0.001
WAIT_MAX_S = 0.01

#: How long a stopping rank waits for its stop messages to leave [s].
SEND_TIMEOUT_S = 5.0


class RemoteStop(KeyboardInterrupt):
    """Another rank stopped this one: its exit code and the line to print."""

    def __init__(self, rank: int, code: int, line: str):
        self.rank, self.code, self.line = rank, code, line
        super().__init__(line)


class _Watcher:
    """The stop channel of one communicator: announce a stop, and notice one."""

    def __init__(self, comm):
        self.comm = comm.Dup()           # its messages never meet the package's own
        self.received: RemoteStop | None = None
        self.announced = False
        self._armed = threading.Lock()
        self._done = threading.Event()
        self._thread = threading.Thread(target=self._watch, name="fem-tether stop watcher", daemon=True)
        self._thread.start()

    def _watch(self) -> None:
        from mpi4py import MPI

        while not self._done.wait(POLL_S):
            status = MPI.Status()
            if self.comm.Iprobe(source=MPI.ANY_SOURCE, tag=STOP_TAG, status=status):
                code, line = self.comm.recv(source=status.Get_source(), tag=STOP_TAG)
                with self._armed:
                    if self._done.is_set() or self.announced:
                        return
                    self.received = RemoteStop(status.Get_source(), code, line)
                    _thread.interrupt_main()
                return

    def announce(self, code: int, line: str) -> None:
        """Tell every other rank to stop (once, unless this rank was told)."""
        with self._armed:
            if self.received is not None or self.announced:
                return
            self.announced = True
        rank = self.comm.Get_rank()
        requests = [self.comm.isend((code, line), dest=r, tag=STOP_TAG)
                    for r in range(self.comm.Get_size()) if r != rank]
        deadline = time.monotonic() + SEND_TIMEOUT_S
        while requests and time.monotonic() < deadline:
            requests = [r for r in requests if not r.Test()]
            time.sleep(0.01)

    def close(self) -> None:
        with self._armed:
            self._done.set()
        self._thread.join()


_active: dict[int, _Watcher] = {}


def exit_code(exc: BaseException) -> tuple[int, str]:
    """The exit code and the one line the CLI prints for ``exc``."""
    from fem_tether.core.errors import InputError, SolverDivergedError

    if isinstance(exc, RemoteStop):
        return exc.code, exc.line
    if isinstance(exc, KeyboardInterrupt) or (interrupted() and not isinstance(exc, (InputError, OSError))):
        why = str(exc) if isinstance(exc, KeyboardInterrupt) else ""
        return EXIT_INTERRUPTED, f"fem-tether: interrupted{f': {why}' if why else ''}"
    if isinstance(exc, InputError):
        return EXIT_USAGE, f"fem-tether: error: {exc}"
    if isinstance(exc, SolverDivergedError):
        return EXIT_FAILED, f"fem-tether: solver failed: {exc}"
    if isinstance(exc, OSError):
        where = f"{exc.filename}: " if exc.filename else ""
        return EXIT_USAGE, f"fem-tether: error: {where}{exc.strerror or exc}"
    return EXIT_FAILED, f"fem-tether: internal error: {type(exc).__name__}: {exc}"


@contextmanager
def guard(comm) -> Iterator[None]:
    """Stop every rank of ``comm`` when any of them stops inside the block
    (and, on any number of ranks, let Ctrl-C stop the block: :func:`interruptible`).

    An exception leaving the block on this rank is announced to the others
    (with its exit code and line) and re-raised; a stop announced by another
    rank arrives here as :class:`RemoteStop` (a ``KeyboardInterrupt``, so
    what catches Ctrl-C to keep its parts catches it too).  Nested guards of
    one communicator share one watcher."""
    if comm is None or comm.Get_size() == 1 or id(comm) in _active:
        with interruptible():
            yield
        return
    watcher = _active[id(comm)] = _Watcher(comm)
    try:
        with interruptible():
            yield
    except BaseException as exc:
        told = watcher.received
        if told is not None and not (told.code == EXIT_INTERRUPTED and isinstance(exc, KeyboardInterrupt)):
            raise told from None     # an interrupt keeps this rank's words (what it kept)
        watcher.announce(*exit_code(exc))
        raise
    finally:
        del _active[id(comm)]
        watcher.close()


def sync(comm, idle: Callable[[], object] | None = None) -> None:
    """Wait, interruptibly, until every rank of ``comm`` has come here (before a
    blocking collective, so that a rank that stopped cannot leave it waiting):
    each rank's word to rank 0, then rank 0's to each.  Point-to-point, not a
    barrier, so that a rank stopped here cancels what it waits for instead of
    leaving a collective pending (which MPI reports when the process ends, and
    which the ranks' next collective would be matched with).  ``idle()`` is
    called between the looks (rank 0 may work on while the others finish)."""
    if comm.Get_size() == 1:
        return
    if comm.Get_rank() == 0:
        for rank in range(1, comm.Get_size()):
            receive(comm.Irecv(bytearray(1), source=rank, tag=SYNC_TAG), idle)
        for rank in range(1, comm.Get_size()):
            wait(comm.Isend(bytearray(1), dest=rank, tag=SYNC_TAG))
    else:
        wait(comm.Isend(bytearray(1), dest=0, tag=SYNC_TAG))
        receive(comm.Irecv(bytearray(1), source=0, tag=SYNC_TAG), idle)


#: The tags of a rank's word to rank 0 that it has stopped (:func:`arrived`), of rank 0's word
#: to the others that it has finished (:func:`finish`), of its exit code (:func:`agree`), of
#: the words of :func:`sync` and of the values :func:`share` and :func:`collect` carry.
ARRIVED_TAG, FINISHED_TAG, CODE_TAG, SYNC_TAG, VALUE_TAG = 18, 19, 20, 24, 25


def share(comm, value: T | None) -> T:
    """Rank 0's ``value`` on every rank of ``comm`` (a broadcast; the other ranks' ``value``,
    ``None``, is not read), sent point to point and
    waited for stoppably (:func:`_send`, :func:`_receive`): the package's broadcasts.  A
    blocking collective after :func:`sync` was not enough: a rank interrupted once its
    sync had ended left the others inside the collective, which no stop ends (measured:
    a study's ranks hung in ``allreduce`` when Ctrl-C came to rank 1 as it left the sync
    of its phase's end, 2 of 9 runs, and at the first run with another process on the
    machine)."""
    if comm.Get_size() == 1:
        return cast(T, value)
    if comm.Get_rank() == 0:
        payload = pickle.dumps(value, protocol=pickle.HIGHEST_PROTOCOL)
        for rank in range(1, comm.Get_size()):
            _send(comm, payload, rank)
        return cast(T, value)
    return pickle.loads(_receive(comm, 0))


def collect(comm, value: T) -> list[T] | None:
    """Every rank's ``value`` on rank 0, in rank order (a gather; ``None`` on the other
    ranks), sent point to point and waited for stoppably as :func:`share`'s."""
    if comm.Get_size() == 1:
        return [value]
    if comm.Get_rank() != 0:
        _send(comm, pickle.dumps(value, protocol=pickle.HIGHEST_PROTOCOL), 0)
        return None
    return [value, *(pickle.loads(_receive(comm, rank)) for rank in range(1, comm.Get_size()))]


def exchange(comm, value: T) -> list[T]:
    """Every rank's ``value`` on every rank, in rank order (an allgather): :func:`collect`
    on rank 0, then :func:`share`."""
    return share(comm, collect(comm, value))


def _send(comm, payload: bytes, rank: int) -> None:
    """``payload`` to ``rank``: its length, then its bytes (:data:`VALUE_TAG`; messages of one
    tag between two ranks arrive in the order they were sent)."""
    wait(comm.Isend(bytearray(len(payload).to_bytes(8, "little")), dest=rank, tag=VALUE_TAG))
    wait(comm.Isend(payload, dest=rank, tag=VALUE_TAG))


def _receive(comm, rank: int) -> bytes:
    """The bytes :func:`_send` sends from ``rank``, each wait cancelled if this rank stops."""
    size = bytearray(8)
    receive(comm.Irecv(size, source=rank, tag=VALUE_TAG))
    payload = bytearray(int.from_bytes(size, "little"))
    receive(comm.Irecv(payload, source=rank, tag=VALUE_TAG))
    return bytes(payload)

#: How long rank 0 waits for the other ranks' word that they have stopped [s].
ARRIVAL_S = 5.0


def arrived(comm, within_s: float = ARRIVAL_S) -> None:
    """Every rank of ``comm`` tells rank 0 that it has stopped, and rank 0 waits,
    stoppable, until each has or ``within_s`` has passed: what the ranks left
    on disk is then final (a part another rank was committing when the stop
    came is in it).  Point-to-point, not a barrier: a rank stopped inside a
    collective (:func:`sync`) leaves it pending, and a new collective would be
    matched with it.  Bounded, so that a rank that cannot stop (inside a
    blocking call) does not keep rank 0, whose exit ends the job, waiting."""
    if comm.Get_rank() != 0:
        wait(comm.Isend(bytearray(1), dest=0, tag=ARRIVED_TAG))
        return
    words = [comm.Irecv(bytearray(1), source=rank, tag=ARRIVED_TAG) for rank in range(1, comm.Get_size())]
    deadline = time.monotonic() + within_s
    while not all(word.Test() for word in words):
        if time.monotonic() > deadline:
            for word in words:
                if not word.Test():
                    word.Cancel()
            return
        checkpoint()
        time.sleep(POLL_S)


def finish(comm) -> None:
    """The ranks done with a command wait here, stoppably, for rank 0 to be done too: rank 0
    tells every other rank.  Point-to-point, not a barrier: were rank 0 to fail while the others
    sat in a barrier, they would stop inside it and leave it pending, and the ranks' next
    collective would be matched with it and hang (measured: a study whose file rank 0 failed
    to write hung every rank)."""
    if comm.Get_rank() == 0:
        for rank in range(1, comm.Get_size()):
            wait(comm.Isend(bytearray(1), dest=rank, tag=FINISHED_TAG))
    else:
        receive(comm.Irecv(bytearray(1), source=0, tag=FINISHED_TAG))


def agree(comm, code: int) -> int:
    """Rank 0's ``code`` on every rank, sent point-to-point and waited for stoppably: a rank
    stopped inside a collective (:func:`sync`) has left it pending, and a collective here
    would be matched with it."""
    if comm.Get_rank() == 0:
        for rank in range(1, comm.Get_size()):
            wait(comm.Isend(bytearray(code.to_bytes(4, "little", signed=True)), dest=rank, tag=CODE_TAG))
        return code
    word = bytearray(4)
    receive(comm.Irecv(word, source=0, tag=CODE_TAG))
    return int.from_bytes(word, "little", signed=True)


def receive(request, idle: Callable[[], object] | None = None) -> None:
    """:func:`wait` for a receive, cancelled if this rank stops meanwhile (MPI would find it
    pending when the process ends): every wait of the package for a message."""
    try:
        wait(request, idle)
    except BaseException:
        request.Cancel()
        request.Wait()                   # a cancelled receive completes at once
        raise


def wait(request, idle: Callable[[], object] | None = None) -> None:
    """Wait for the MPI ``request`` asleep (not spinning on a core another rank
    may need) and stoppable (:func:`checkpoint`), calling ``idle()`` between the looks,
    the pauses growing from :data:`WAIT_FIRST_S` to :data:`WAIT_MAX_S`."""
    pause_s = WAIT_FIRST_S
    while not request.Test():
        checkpoint()
        if idle is not None:
            idle()
        time.sleep(pause_s)
        pause_s = min(2.0 * pause_s, WAIT_MAX_S)


def _importing(frame) -> bool:
    """Whether ``frame`` runs inside an import (a module's body being executed)."""
    while frame is not None:
        if frame.f_code.co_filename.startswith("<frozen importlib"):
            return True
        frame = frame.f_back
    return False


class _Interrupts:
    """Ctrl-C, remembered until the command has stopped: Python drops a
    ``KeyboardInterrupt`` raised inside a finaliser (h5py's weak references
    run them often), so the loops that run long ask again (:func:`checkpoint`).
    One that comes during an import is only remembered: raised there, it
    leaves the library half-imported (numba then fails with an ImportError),
    so the next checkpoint raises it; a second one raises at once, and what
    fails after it counts as interrupted (:func:`exit_code`)."""

    def __init__(self):
        self.seen = False
        self.raising = False
        self.ever = False

    def __call__(self, signum, frame) -> None:
        again, self.seen, self.ever = self.seen, True, True
        if self.raising and (again or not _importing(frame)):    # a second Ctrl-C insists
            raise KeyboardInterrupt


_interrupts = _Interrupts()


def _quiet_after_interrupts(hook):
    """``hook`` for the finalisers' errors (``sys.unraisablehook``), except
    a ``KeyboardInterrupt`` one dropped (it is asked for again) and, once
    Ctrl-C has come, every one: an interrupt inside a library's constructor
    leaves a half-built object whose finaliser then fails (measured: llvmlite's
    ``PassBuilder`` without ``_as_parameter_``, a traceback after the one line)."""
    def on_unraisable(unraisable) -> None:
        if not (issubclass(unraisable.exc_type, KeyboardInterrupt) or _interrupts.ever):
            hook(unraisable)
    return on_unraisable


def defer_interrupts() -> None:
    """Until the command starts (:func:`interruptible`), remember Ctrl-C instead
    of raising it (while the libraries load, before any rank can tell the
    others).  A process started with SIGINT ignored (``nohup``, a background
    job) keeps ignoring it."""
    if signal.getsignal(signal.SIGINT) is not signal.SIG_IGN:
        signal.signal(signal.SIGINT, _interrupts)
        sys.unraisablehook = _quiet_after_interrupts(sys.unraisablehook)   # for the command's whole life


def checkpoint() -> None:
    """Raise ``KeyboardInterrupt`` if Ctrl-C came and was not yet acted on."""
    if _interrupts.seen and _interrupts.raising:
        raise KeyboardInterrupt


def interrupted() -> bool:
    """Whether Ctrl-C came and was not yet acted on (what fails after it, a
    half-imported library, was interrupted)."""
    return _interrupts.seen


def clear() -> None:
    """The interrupt has been acted on (the command ended)."""
    _interrupts.seen = False


@contextmanager
def interruptible() -> Iterator[None]:
    """Ctrl-C raises ``KeyboardInterrupt`` in the block, now if one came while
    deferred, and again at every :func:`checkpoint` until :func:`clear`."""
    if threading.current_thread() is not threading.main_thread() or _interrupts.raising:
        yield
        return
    if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:     # started ignoring it: keep ignoring
        yield
        return
    previous = signal.signal(signal.SIGINT, _interrupts)
    hook = sys.unraisablehook
    sys.unraisablehook = _quiet_after_interrupts(hook)
    _interrupts.raising = True
    try:
        checkpoint()
        yield
        checkpoint()                     # one a finaliser dropped is not lost: the block ends interrupted
    finally:
        _interrupts.raising = False
        sys.unraisablehook = hook
        signal.signal(signal.SIGINT, previous)

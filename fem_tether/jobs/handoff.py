"""Work rank 0 hands to another MPI rank, and the result handed back.

Rank 0 sends what to do (:func:`hand`) and goes on with its own work; the
other rank, waiting for it (:func:`serve`), does it and sends back the
result, or the exception it raised, which rank 0 raises as its own when it
takes the result (the other rank's traceback added as a note), as if it had
done the work itself.  Point-to-point, never a collective (the ranks not
involved are elsewhere), and every wait is stoppable
(:func:`fem_tether.core.stop.checkpoint`): a rank that stops stops the other
(:func:`fem_tether.core.stop.guard`), so neither waits for ever.
"""

from __future__ import annotations

import importlib
import pickle
import time
import traceback
from collections.abc import Callable, Sequence
from typing import Any

from fem_tether.core.stop import checkpoint, wait

#: The tags of the work and of its result (the stop messages have a communicator of their own).
WORK_TAG, RESULT_TAG = 21, 22

#: How often a waiting rank looks for the message it waits for [s] (asleep in between).
POLL_S = 0.01


def _receive(comm, source: int, tag: int) -> Any:
    """The next message from ``source`` with ``tag``, waited for stoppably."""
    while not comm.Iprobe(source=source, tag=tag):
        checkpoint()
        time.sleep(POLL_S)
    return comm.recv(source=source, tag=tag)


def _send(comm, message: Any, dest: int, tag: int) -> None:
    """Send ``message`` and wait, stoppably, until it has left."""
    wait(comm.isend(message, dest=dest, tag=tag))


def _portable(exc: Exception) -> Exception:
    """``exc`` if it survives pickling, else a RuntimeError saying what it was."""
    try:
        pickle.loads(pickle.dumps(exc))
        return exc
    except Exception:
        return RuntimeError(f"{type(exc).__name__}: {exc}")


def serve(comm, do: Callable[[Any], Any], imports: Sequence[str] = ()) -> None:
    """On a rank other than 0: import ``imports`` (while rank 0 prepares the work), wait for
    rank 0's work, do it (``do(work)``) and send back its result, or the exception it raised
    with its traceback."""
    for module in imports:
        importlib.import_module(module)
    work = _receive(comm, 0, WORK_TAG)
    try:
        result = ("done", do(work), "")
    except Exception as exc:
        result = ("raised", _portable(exc), traceback.format_exc())
    _send(comm, result, 0, RESULT_TAG)


def hand(comm, rank: int, work: Any) -> Callable[[], Any]:
    """On rank 0: send ``work`` to ``rank`` (:func:`serve`); the function that waits for its
    result and returns it, or raises the exception the work raised there."""
    _send(comm, work, rank, WORK_TAG)

    def result() -> Any:
        outcome, value, where = _receive(comm, rank, RESULT_TAG)
        if outcome == "raised":
            value.add_note(f"raised on MPI rank {rank}:\n{where}")
            raise value
        return value
    return result


"""Work rank 0 hands to another MPI rank, and the result handed back.

Rank 0 sends what to do (:func:`hand`) and goes on with its own work; the
other rank, waiting for it (:func:`serve`), does it and sends back the
result, or the exception it raised, which rank 0 raises as its own when it
takes the result (the other rank's traceback added as a note), as if it had
done the work itself.  Point-to-point, never a collective (the ranks not
involved are elsewhere), and every wait is stoppable
(:func:`fem_tether.core.stop.receive`, :func:`~fem_tether.core.stop.wait`): a rank that stops stops the other
(:func:`fem_tether.core.stop.guard`), so neither waits for ever.
"""

from __future__ import annotations

import importlib
import pickle
import traceback
from collections.abc import Callable, Sequence
from typing import Any

from fem_tether.core.stop import receive, wait

#: The tags of the work and of its result (the stop messages have a communicator of their own).
WORK_TAG, RESULT_TAG = 21, 22

#: The bytes of a message's length, sent before the message.
LENGTH_BYTES = 8


def _receive(comm, source: int, tag: int) -> Any:
    """The next message from ``source`` with ``tag``: its length, then its pickled bytes,
    each a posted receive waited for stoppably (:func:`fem_tether.core.stop.receive`; mpi4py's
    receive of an object posted without a buffer holds 32 KiB at most, mpi4py 4.1)."""
    length = bytearray(LENGTH_BYTES)
    receive(comm.Irecv(length, source=source, tag=tag))
    message = bytearray(int.from_bytes(length, "little"))
    receive(comm.Irecv(message, source=source, tag=tag))
    return pickle.loads(message)


def _send(comm, message: Any, dest: int, tag: int) -> None:
    """Send ``message`` (its length, then its pickled bytes: :func:`_receive`) and wait,
    stoppably, until it has left."""
    data = pickle.dumps(message, protocol=pickle.HIGHEST_PROTOCOL)
    wait(comm.Isend(len(data).to_bytes(LENGTH_BYTES, "little"), dest=dest, tag=tag))
    wait(comm.Isend(data, dest=dest, tag=tag))


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


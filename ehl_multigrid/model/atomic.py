"""Files written whole or not at all: every file goes through a hidden temporary name in its
own folder and a rename (:func:`atomic_path`, :func:`write_text_atomic`, :func:`atomic_savefig`);
the temporary names carry the writer's PID (``.<name>.pid<PID>.<random>.tmp``) so that a dead
writer's leftovers can be told from a live one's. :func:`deferred_signals` holds a stop request
while finished files are moved into place; :func:`fault_point` is the fault-injection hook of the
tests.
"""

from __future__ import annotations

import contextlib
import os
import signal
import tempfile
import threading
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any


def default_file_mode() -> int:
    """The mode a new file gets under the process's umask (``0o666 & ~umask``), for files
    created through :func:`tempfile.mkstemp` (always 0600) before they are renamed into place."""
    mask = _umask()
    return 0o666 & ~mask


def _umask() -> int:
    try:  # Linux: read it without changing it (thread-safe)
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except (OSError, ValueError):
        pass
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def temp_name_prefix(path: str | os.PathLike) -> str:
    """Prefix of the temporary files of ``path``: hidden, with the writing process's PID so
    that :func:`remove_leftovers` can tell a dead writer's file from a live one's."""
    return f".{Path(path).name}.pid{os.getpid()}."


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike, keep_suffix: bool = False) -> Iterator[Path]:
    """A temporary path beside ``path`` to write to; renamed to ``path`` (with the user's usual
    file mode) when the block ends normally, deleted when it raises, so ``path`` is either the
    complete new file or untouched. ``keep_suffix``: the temporary name ends with the suffix
    of ``path`` too (writers that choose the format by it, such as Pillow's GIF writer).

    Examples
    --------
    >>> import tempfile
    >>> d = Path(tempfile.mkdtemp())
    >>> with atomic_path(d / "a.txt") as tmp:
    ...     _ = tmp.write_text("done")
    >>> sorted(p.name for p in d.iterdir())
    ['a.txt']
    """
    path = Path(path)
    fd, tmp = tempfile.mkstemp(prefix=temp_name_prefix(path),
                               suffix=".tmp" + (path.suffix if keep_suffix else ""), dir=path.parent)
    os.close(fd)
    try:
        yield Path(tmp)
        fault_point("rename")
        os.chmod(tmp, default_file_mode())  # mkstemp creates 0600
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


def write_text_atomic(path: str | os.PathLike, text: str) -> Path:
    """Write ``text`` to ``path`` through a temporary file beside it and a rename, with the
    user's usual file mode; a crash never leaves a half-written file."""
    path = Path(path)
    with atomic_path(path) as tmp, open(tmp, "w", newline="") as f:
        f.write(text)
    return path


def atomic_savefig(fig: Any, path: str | os.PathLike, **kwargs: Any) -> Path:
    """``fig.savefig(path, **kwargs)`` through a temporary file and a rename: an interrupted
    save never leaves a truncated image under ``path``. The format comes from the suffix of
    ``path`` unless ``format`` is given (matplotlib's default format for a name without one).
    Every figure of the application is saved through it."""
    path = Path(path)
    if "format" not in kwargs:  # the temporary name's suffix is .tmp: say which format
        import matplotlib

        kwargs["format"] = path.suffix.lstrip(".").lower() or matplotlib.rcParams["savefig.format"]
    with atomic_path(path) as tmp:
        fig.savefig(tmp, **kwargs)
        fault_point("savefig")
    return path


@contextlib.contextmanager
def deferred_signals() -> Iterator[None]:
    """Hold SIGTERM and SIGINT while the block runs (moving finished files into place) and
    act on them after it: a stop request never leaves a set of outputs half moved. SIGKILL
    cannot be held; the files are then either moved or still in the staging folder.

    Only the main thread can change signal handlers; elsewhere the block runs unguarded.
    """
    signums = (signal.SIGTERM, signal.SIGINT)
    if threading.current_thread() is not threading.main_thread() or any(
            signal.getsignal(s) is None for s in signums):  # a handler not set from Python
        yield
        return
    pending: list[int] = []

    def hold(signum: int, frame: Any) -> None:
        pending.append(signum)

    previous = {s: signal.signal(s, hold) for s in signums}
    try:
        yield
    finally:
        for s, handler in previous.items():
            signal.signal(s, handler)
        if pending:
            handler = previous[pending[0]]
            if callable(handler):
                handler(pending[0], None)  # the cli's handlers raise Terminated / KeyboardInterrupt
            elif handler == signal.SIG_DFL:
                signal.raise_signal(pending[0])


#: Environment variables of the fault-injection hook (tests/app/test_fault_injection.py).
FAULT_ENV = ("EHL_FAULT_AT", "EHL_FAULT_SIGNAL", "EHL_FAULT_COUNT")
_fault_hits: dict[str, int] = {}


def fault_point(name: str) -> None:
    """Test hook: when the environment variable ``EHL_FAULT_AT`` equals ``name``, the process
    sends itself ``EHL_FAULT_SIGNAL`` (``TERM``, the default, or ``KILL``) the
    ``EHL_FAULT_COUNT``-th time (default 1) it reaches this point. Unset, it does nothing.

    Points: ``savefig`` (a figure written to its temporary file, not yet renamed), ``rename``
    (any atomic write, before its rename), ``h5`` (an HDF5 result written, not yet renamed),
    ``publish`` (a staged file moved into place, the others not yet), ``run.stage.<name>``
    (``ehl run`` starts the stage ``<name>``), ``run.publish`` (``ehl run`` about to move its
    files), ``solve.plots`` (``ehl solve`` about to plot), ``sweep.case`` (``ehl sweep``
    collected a finished case), ``sweep.table`` (``ehl sweep`` about to write its table).
    """
    if os.environ.get("EHL_FAULT_AT") != name:
        return
    _fault_hits[name] = _fault_hits.get(name, 0) + 1
    if _fault_hits[name] != int(os.environ.get("EHL_FAULT_COUNT", "1")):
        return
    sig = os.environ.get("EHL_FAULT_SIGNAL", "TERM").upper().removeprefix("SIG")
    os.kill(os.getpid(), getattr(signal, f"SIG{sig}"))
    time.sleep(0.05)  # SIGKILL: do not go on to the next statement before it lands

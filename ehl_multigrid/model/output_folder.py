"""One writer per output folder, staged publishing, and the leftovers of dead writers.

A command writing into a folder holds :func:`output_lock` (``fcntl.flock`` on
``<folder>/.ehl.lock``, deleted when the command ends): a second one is refused at once, naming
the PID that holds it. On taking the lock, the temporary files and staging folders of dead
writers are removed (:func:`remove_leftovers`; the PID in the name tells a dead writer from a
live one). A command that writes several files for one result stages them in a hidden folder
``.ehl-run-<stem>.pid<PID>.<random>`` inside the output folder and moves the complete ones into
place together (:class:`StagedOutputs`).
"""

from __future__ import annotations

import contextlib
import errno
import os
import re
import shutil
import tempfile
import threading
import time
import warnings
from collections.abc import Iterable, Iterator
from pathlib import Path
from typing import Any

try:
    import fcntl
except ImportError:  # not POSIX: output folders are not locked (output_lock warns)
    fcntl = None  # type: ignore[assignment]

from .atomic import deferred_signals, fault_point
from .errors import InputError
from .paths import output_file, record_outputs, safe_stem

#: Name of the lock file of an output folder (removed by its holder when it is done; a killed
#: holder's file stays, unlocked, until the next command into the folder).
LOCK_NAME = ".ehl.lock"
#: Prefix of the hidden staging folders (``.ehl-run-<stem>.pid<PID>.<random>``).
STAGING_PREFIX = ".ehl-run-"
#: Leftovers without a PID in their name (written by earlier versions) are removed when they
#: have not changed for this many seconds.
UNTAGGED_STALE_S = 60.0

# ``.<name>.pid<PID>.<random>.tmp[.<suffix>]`` and ``.ehl-run-<stem>.pid<PID>.<random>``
_TAGGED_TMP = re.compile(r"^\..+\.pid(\d+)\.[A-Za-z0-9_]+\.tmp(\.[A-Za-z0-9]+)?$")
_TAGGED_STAGING = re.compile(r"^\.ehl-run-.*\.pid(\d+)\.[A-Za-z0-9_]+$")
# names of earlier versions: ``.<name>.<random>.tmp``, ``tmp<random>.h5.tmp``, manifests'
# ``..ehl-files-<stem>.json.<random>``, ``.ehl-write-probe-<random>``, ``.ehl-run-<stem>-<random>``
_UNTAGGED_FILE = re.compile(r"^(\..+\.[a-z0-9_]{8}\.tmp|tmp[a-z0-9_]{8}\.h5\.tmp"
                            r"|\.\.ehl-(files|run)-.+\.json\.[a-z0-9_]{8}|\.ehl-write-probe-[a-z0-9_]{8})$")
_UNTAGGED_STAGING = re.compile(r"^\.ehl-run-.+-[a-z0-9_]{8}$")

_held: dict[Path, list[Any]] = {}  # lock files this process holds: path -> [fd, depth]
_held_guard = threading.Lock()


def staging_dir(folder: str | os.PathLike, stem: str) -> Path:
    """A new hidden staging folder ``.ehl-run-<stem>.pid<PID>.<random>`` inside ``folder``."""
    return Path(tempfile.mkdtemp(prefix=f"{STAGING_PREFIX}{safe_stem(stem)}.pid{os.getpid()}.",
                                 dir=folder))


class OutputLocked(InputError):
    """Another process holds the lock of the output folder (exit code 2)."""


@contextlib.contextmanager
def output_lock(folder: str | os.PathLike, command: str = "ehl",
                subfolders: Iterable[str] = ()) -> Iterator[list[tuple[Path, int]]]:
    """Hold the exclusive advisory lock of the output folder ``folder`` while the block runs.

    The lock is ``fcntl.flock`` on ``<folder>/.ehl.lock``, taken without waiting: when another
    process holds it, :class:`OutputLocked` (an :class:`InputError`, exit code 2) names the
    folder and that process's PID. The operating system releases the lock of a process that
    dies, however it dies. The holder deletes the lock file before releasing it; a process that
    locked the file just before it was deleted sees that it no longer is the folder's lock
    file and tries again. Nested use in one process is allowed (the inner one does nothing).
    The folder is created if missing.

    On taking the lock, the leftovers of dead writers in ``folder`` and its ``subfolders`` are
    removed (:func:`remove_leftovers`); the block receives the list of ``(path, bytes)``
    removed.
    """
    folder = Path(folder)
    lock_path = (folder / LOCK_NAME).resolve()
    with _held_guard:
        held = _held.get(lock_path)
        if held is not None:
            held[1] += 1
    if held is not None:
        try:
            yield []
        finally:
            with _held_guard:
                held[1] -= 1
        return
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InputError(f"--out {str(folder)!r} is not a writable folder ({exc.strerror or exc})") from None
    fd, locked = _acquire(lock_path, folder)
    with _held_guard:
        _held[lock_path] = [fd, 1]
    try:
        os.ftruncate(fd, 0)
        os.lseek(fd, 0, os.SEEK_SET)
        os.write(fd, f"{os.getpid()} {command}\n".encode())
        removed = remove_leftovers(folder)
        for sub in subfolders:
            if (folder / sub).is_dir():
                removed += remove_leftovers(folder / sub)
        yield removed
    finally:
        with _held_guard:
            _held.pop(lock_path, None)
        if locked:
            with contextlib.suppress(OSError):
                os.unlink(lock_path)  # while still holding it (see _acquire)
        os.close(fd)  # releases the flock


def _acquire(lock_path: Path, folder: Path) -> tuple[int, bool]:
    """Open and flock the lock file ``lock_path``; ``(fd, locked)``, ``locked`` False on a file
    system without flock (the command then runs unguarded, with a warning)."""
    if fcntl is None:
        warnings.warn(f"--out {str(folder)!r}: no file locks on this system; concurrent commands into "
                      f"it are not refused", stacklevel=4)
        return os.open(lock_path, os.O_RDWR | os.O_CREAT, 0o666), False
    for _ in range(100):
        try:
            fd = os.open(lock_path, os.O_RDWR | os.O_CREAT, 0o666)
        except OSError as exc:
            raise InputError(f"--out {str(folder)!r}: cannot create the lock file {LOCK_NAME} "
                             f"({exc.strerror or exc})") from None
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            holder = _lock_holder(fd)
            os.close(fd)
            raise OutputLocked(f"--out {str(folder)!r} is in use by another ehl process ({holder}); "
                               f"wait for it to end or write into another folder") from None
        except OSError as exc:
            os.close(fd)
            if exc.errno not in (errno.ENOLCK, errno.EOPNOTSUPP, errno.ENOSYS, errno.EINVAL):
                raise
            warnings.warn(f"--out {str(folder)!r}: the file system does not support locks "
                          f"({exc.strerror}); concurrent commands into it are not refused", stacklevel=4)
            return os.open(lock_path, os.O_RDWR | os.O_CREAT, 0o666), False
        try:  # the holder before us may have deleted the file we locked: then it is not the lock
            if os.fstat(fd).st_ino == os.stat(lock_path).st_ino:
                return fd, True
        except FileNotFoundError:
            pass
        os.close(fd)
    raise InputError(f"--out {str(folder)!r}: could not take the lock file {LOCK_NAME} (it keeps being "
                     f"replaced)")


def _lock_holder(fd: int) -> str:
    """``"PID 1234: ehl run"`` from the lock file (what its holder wrote), or what is known."""
    try:
        os.lseek(fd, 0, os.SEEK_SET)
        text = os.read(fd, 200).decode(errors="replace").strip()
    except OSError:
        text = ""
    pid, _, command = text.partition(" ")
    if pid.isdigit():
        return f"PID {pid}: {command}" if command else f"PID {pid}"
    return "PID not yet recorded"


def remove_leftovers(folder: str | os.PathLike) -> list[tuple[Path, int]]:
    """Remove from ``folder`` the temporary files and staging folders of writers that are no
    longer running; return ``(path, bytes)`` of each removed one.

    A name with ``.pid<PID>.`` (this version's :func:`atomic_path`, :func:`staging_dir`) is
    removed when that process no longer exists, or when it started after the leftover was last
    changed (its PID was reused). Leftovers of earlier versions, which carry no PID, are removed
    when they have not changed for :data:`UNTAGGED_STALE_S` seconds. Call it while holding
    :func:`output_lock`. Nothing else (user files, results, manifests, the lock) is touched.
    """
    folder = Path(folder)
    removed: list[tuple[Path, int]] = []
    try:
        entries = list(os.scandir(folder))
    except OSError:
        return removed
    now = time.time()
    for entry in entries:
        name = entry.name
        try:
            is_dir = entry.is_dir(follow_symlinks=False)
            is_file = entry.is_file(follow_symlinks=False)
            mtime = entry.stat(follow_symlinks=False).st_mtime
        except OSError:
            continue
        tagged = (_TAGGED_STAGING if is_dir else _TAGGED_TMP).match(name) if (is_dir or is_file) else None
        if tagged is not None:
            stale = not _writer_alive(int(tagged.group(1)), mtime)
        elif is_dir and _UNTAGGED_STAGING.match(name) or is_file and _UNTAGGED_FILE.match(name):
            stale = now - mtime > UNTAGGED_STALE_S
        else:
            continue
        if not stale:
            continue
        size = _tree_size(Path(entry.path)) if is_dir else _size(Path(entry.path))
        try:
            if is_dir:
                shutil.rmtree(entry.path)
            else:
                os.unlink(entry.path)
        except OSError:
            continue
        removed.append((Path(entry.path), size))
    return removed


def _size(path: Path) -> int:
    try:
        return path.stat().st_size
    except OSError:
        return 0


def _tree_size(path: Path) -> int:
    total = 0
    for root, _dirs, files in os.walk(path):
        total += sum(_size(Path(root) / f) for f in files)
    return total


def _writer_alive(pid: int, changed: float) -> bool:
    """Whether process ``pid`` may still be writing a leftover last changed at ``changed``
    (epoch seconds): it exists and did not start after that (a reused PID)."""
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        pass  # another user's process: it exists
    except OSError:
        return True
    started = _process_start(pid)
    return started is None or started <= changed + 1.0


def _process_start(pid: int) -> float | None:
    """Start time of process ``pid`` in epoch seconds (Linux ``/proc``), or None."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            fields = f.read().rsplit(")", 1)[1].split()
        ticks = int(fields[19])  # field 22 of proc(5): start time after boot, in clock ticks
        with open("/proc/stat") as f:
            boot = next(int(line.split()[1]) for line in f if line.startswith("btime"))
        return boot + ticks / os.sysconf("SC_CLK_TCK")
    except (OSError, ValueError, IndexError, StopIteration):
        return None



class StagedOutputs:
    """The files of one result, written into a hidden staging folder inside ``folder`` and
    moved into place together by :meth:`publish`, which also records them in
    ``.ehl-files-<stem>.json`` and deletes the files of the stem's previous run that the new
    set does not replace (:func:`record_outputs`).

    Only files passed to :meth:`done` are published: a file whose writer was interrupted never
    reaches ``folder``. As a context manager the complete files are published when the block
    ends, also when it raises (a stop during plotting keeps the result written before it),
    and the staging folder is removed.

    Examples
    --------
    >>> import tempfile
    >>> d = Path(tempfile.mkdtemp())
    >>> with StagedOutputs(d, "r") as st:
    ...     _ = st.done(write_text_atomic(st.path("r.csv"), "x"))
    ...     _ = st.path("r_partial.png").write_text("never finished")
    >>> sorted(p.name for p in d.iterdir() if not p.name.startswith("."))
    ['r.csv']
    """

    def __init__(self, folder: str | os.PathLike, stem: str) -> None:
        self.folder = Path(folder)
        self.stem = stem
        self.dir = staging_dir(self.folder, stem)
        self.names: list[str] = []
        self.published: list[Path] = []

    def path(self, name: str) -> Path:
        """Where to write the file ``name`` (inside the staging folder)."""
        return output_file(self.dir, Path(name).stem, Path(name).suffix)

    def final(self, path: str | os.PathLike) -> Path:
        """The place in ``folder`` of the staged file ``path``."""
        return self.folder / Path(path).name

    def done(self, path: str | os.PathLike) -> Path:
        """Mark the staged file ``path`` complete; return its final place."""
        name = Path(path).name
        if Path(path).resolve().parent != self.dir.resolve():
            raise ValueError(f"{path} is not in the staging folder {self.dir}")
        if name not in self.names:
            self.names.append(name)
        return self.final(name)

    def publish(self) -> list[Path]:
        """Move the complete files into ``folder``, record them, remove the staging folder;
        return their final paths."""
        with deferred_signals():
            finals = []
            for name in self.names:
                if (self.dir / name).is_file():
                    os.replace(self.dir / name, self.folder / name)
                    finals.append(self.folder / name)
                    fault_point("publish")
            if finals:
                record_outputs(self.folder, self.stem, finals)
            shutil.rmtree(self.dir, ignore_errors=True)
        self.published = finals
        return finals

    def __enter__(self) -> StagedOutputs:
        return self

    def __exit__(self, *exc: Any) -> None:
        self.publish()

"""Output paths that stay where the user asked: file names made from scene names, output folders
checked for writability before any work, and files written with the user's normal permissions.

A scene's ``name`` is a label, not a path: ``"/abs/path"`` or ``"../../x"`` must never make a
result land outside ``--out``. :func:`safe_stem` turns any label into one safe file-name stem and
:func:`output_file` joins it to the folder and checks that the result stays inside.

Nothing is written half-way and nothing is left behind:

* every file goes through a temporary name in its own folder and a rename
  (:func:`atomic_path`, :func:`write_text_atomic`, :func:`atomic_savefig`); the temporary names
  are hidden and carry the writer's PID (``.<name>.pid<PID>.<random>.tmp``);
* a command that writes several files for one result stages them in a hidden folder
  ``.ehl-run-<stem>.pid<PID>.<random>`` inside the output folder and moves the complete ones
  into place together (:class:`StagedOutputs`);
* a command writing into a folder holds :func:`output_lock` (``fcntl.flock`` on
  ``<folder>/.ehl.lock``, deleted when the command ends): a second one is refused at once,
  naming the PID that holds it. On taking the lock, the temporary files and staging folders of
  dead writers are removed (:func:`remove_leftovers`; the PID in the name tells a dead writer
  from a live one).
"""

from __future__ import annotations

import contextlib
import errno
import hashlib
import json
import os
import re
import shutil
import signal
import tempfile
import threading
import time
import warnings
from collections.abc import Iterable, Iterator
from pathlib import Path
from typing import Any

from .errors import InputError

try:
    import fcntl
except ImportError:  # not POSIX: output folders are not locked (output_lock warns)
    fcntl = None  # type: ignore[assignment]

#: Longest stem :func:`safe_stem` returns (file systems allow 255 bytes per name; suffixes such
#: as ``_interference.png`` and temporary-file prefixes need room).
MAX_STEM = 120

_UNSAFE = re.compile(r"[^A-Za-z0-9._+=-]+")

def safe_stem(name: str, default: str = "scene") -> str:
    """A file-name stem for the label ``name``: letters, digits and ``. _ + = -`` only, no
    leading dot, at most :data:`MAX_STEM` characters (a long name keeps a short hash of the
    whole so two long names stay distinct); ``default`` when nothing usable is left.

    Examples
    --------
    >>> safe_stem("../../etc/passwd")
    'etc_passwd'
    >>> safe_stem("ball on disc, 1 GPa")
    'ball_on_disc_1_GPa'
    >>> safe_stem("..")
    'scene'
    """
    stem = _UNSAFE.sub("_", str(name)).strip("._-")
    stem = re.sub(r"_+", "_", stem)
    if not stem:
        return default
    if len(stem) > MAX_STEM:
        digest = hashlib.sha256(str(name).encode("utf-8", "surrogatepass")).hexdigest()[:10]
        stem = f"{stem[: MAX_STEM - 11]}_{digest}"
    return stem


def output_file(outdir: str | os.PathLike, stem: str, suffix: str = "") -> Path:
    """``outdir / (safe_stem(stem) + suffix)``, guaranteed to lie inside ``outdir``."""
    folder = Path(outdir)
    path = folder / f"{safe_stem(stem)}{suffix}"
    if path.resolve().parent != folder.resolve():
        raise InputError(f"output name {stem!r}{suffix} would leave the output folder {str(folder)!r}")
    return path


#: Manifest of the files one command wrote for one result stem in an output folder.
OUTPUTS_MANIFEST = ".ehl-files-{stem}.json"


def record_outputs(folder: str | os.PathLike, stem: str, files: Any) -> list[Path]:
    """Record the files a command wrote for the result ``<stem>`` in ``folder`` and delete
    those the previous run of the same stem recorded and this one did not write again
    (figures of an earlier run with plots, after a run with ``--no-plots``; an old CSV), so
    nothing stale stays beside a new result. Only recorded files are ever deleted: a file
    the user put in the folder is not touched. Returns the deleted paths.

    Examples
    --------
    >>> import tempfile
    >>> d = Path(tempfile.mkdtemp())
    >>> for n in ("r.h5", "r_maps.png", "r_notes.png"):
    ...     _ = (d / n).write_text("x")
    >>> record_outputs(d, "r", [d / "r.h5", d / "r_maps.png"])
    []
    >>> [p.name for p in record_outputs(d, "r", [d / "r.h5"])]
    ['r_maps.png']
    >>> sorted(p.name for p in d.iterdir() if not p.name.startswith("."))
    ['r.h5', 'r_notes.png']
    """
    folder = Path(folder)
    here = folder.resolve()
    new = sorted({Path(f).name for f in files if Path(f).resolve().parent == here})
    manifest = folder / OUTPUTS_MANIFEST.format(stem=safe_stem(stem))
    old = _manifest_names(manifest)
    stale = sorted(old - set(new))
    # the manifest first (it names only files that exist, and what is being removed), then the
    # deletions: a crash between the two leaves no file that no manifest knows about
    write_text_atomic(manifest, json.dumps({"stem": stem, "files": new, "removing": stale}))
    return _remove_plain_files(folder, stale)


def _manifest_names(manifest: Path) -> set[str]:
    """The files (and the ones being removed) that a manifest of an earlier run lists."""
    try:
        data = json.loads(manifest.read_text())
        return set(data.get("files", [])) | set(data.get("removing", []))
    except (OSError, ValueError, AttributeError, TypeError):
        return set()


def _remove_plain_files(folder: Path, names: Iterable[str]) -> list[Path]:
    """Delete the files ``folder/name`` (plain names inside the folder only); return them."""
    removed = []
    for name in sorted(names):
        target = folder / name
        if Path(name).name == name and target.is_file():
            try:
                target.unlink()
                removed.append(target)
            except OSError:
                pass
    return removed


def writable_dir(path: str | os.PathLike, field: str = "--out") -> Path:
    """Create the folder ``path`` if needed and prove it is writable by writing a probe file;
    raise :class:`InputError` naming ``field`` otherwise. Called before any computation, so a
    read-only or mistyped output folder costs nothing."""
    folder = Path(path)
    try:
        if folder.exists() and not folder.is_dir():
            raise InputError(f"{field} {str(folder)!r} is a file, not a folder")
        folder.mkdir(parents=True, exist_ok=True)
        fd, probe = tempfile.mkstemp(prefix=f".ehl-write-probe.pid{os.getpid()}.", suffix=".tmp",
                                     dir=folder)
        os.close(fd)
        os.unlink(probe)
    except InputError:
        raise
    except OSError as exc:
        reason = exc.strerror or type(exc).__name__
        raise InputError(f"{field} {str(folder)!r} is not a writable folder ({reason})") from None
    return folder


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


# -- staging, locking, leftovers ------------------------------------------------------------------

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

    def discard(self) -> None:
        """Remove the staging folder without publishing anything."""
        shutil.rmtree(self.dir, ignore_errors=True)

    def __enter__(self) -> StagedOutputs:
        return self

    def __exit__(self, *exc: Any) -> None:
        self.publish()


# -- fault injection (tests) ----------------------------------------------------------------------

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

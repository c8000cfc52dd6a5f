"""Output paths that stay where the user asked: file names made from scene names, output folders
checked for writability before any work, and files written with the user's normal permissions.

A scene's ``name`` is a label, not a path: ``"/abs/path"`` or ``"../../x"`` must never make a
result land outside ``--out``. :func:`safe_stem` turns any label into one safe file-name stem and
:func:`output_file` joins it to the folder and checks that the result stays inside.
"""

from __future__ import annotations

import hashlib
import os
import re
import tempfile
import time
from pathlib import Path

from .errors import InputError

#: Longest stem :func:`safe_stem` returns (file systems allow 255 bytes per name; suffixes such
#: as ``_interference.png`` and temporary-file prefixes need room).
MAX_STEM = 120

_UNSAFE = re.compile(r"[^A-Za-z0-9._+=-]+")

#: Files that accompany a result ``<stem>.h5`` in its folder: ``<stem>.<ext>`` and
#: ``<stem>_<anything>.<ext>`` (figures, animations, profile tables).
COMPANION_SUFFIXES = (".png", ".gif", ".mp4", ".svg", ".pdf", ".csv")
#: When this module was imported (before any result of this process was written): a companion
#: written since then is this run's own.
_PROCESS_START = time.time()
#: Margin for file systems that store whole seconds (FAT: two): a companion within it is kept.
_COARSE_MTIME_MARGIN = 2.0


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


def remove_stale_companions(result_path: str | os.PathLike) -> list[Path]:
    """Delete the figures and tables that an earlier run wrote beside ``result_path``
    (``<stem>.h5``), so that nothing stale stays beside a new result; return what was deleted.

    A companion is ``<stem>.<ext>`` or ``<stem>_<anything>.<ext>`` with ``ext`` in
    :data:`COMPANION_SUFFIXES`, older than this process, and not claimed by a longer result
    stem of the same folder (``<stem>_tehl_maps.png`` belongs to ``<stem>_tehl.h5`` when that
    exists). Call it when the new result is written, before its own figures.

    Examples
    --------
    >>> import tempfile, os
    >>> d = Path(tempfile.mkdtemp())
    >>> for n in ("a.h5", "a_maps.png", "a_b.h5", "a_b_maps.png"):
    ...     _ = (d / n).write_text("x"); os.utime(d / n, (0, 0))
    >>> [p.name for p in remove_stale_companions(d / "a.h5")]
    ['a_maps.png']
    """
    path = Path(result_path)
    folder, stem = path.parent, path.stem
    if not folder.is_dir():
        return []
    stems = sorted((p.stem for p in folder.glob("*.h5")), key=len, reverse=True)
    removed = []
    for p in folder.iterdir():
        name = p.name
        if p.suffix.lower() not in COMPANION_SUFFIXES or not p.is_file():
            continue
        base = name[: -len(p.suffix)]
        if not (base == stem or base.startswith(stem + "_")):
            continue
        owner = next((s for s in stems if base == s or base.startswith(s + "_")), stem)
        if owner != stem:
            continue
        try:
            mtime = p.stat().st_mtime
            margin = _COARSE_MTIME_MARGIN if mtime == int(mtime) else 0.0
            if mtime >= _PROCESS_START - margin:
                continue
            p.unlink()
        except OSError:
            continue
        removed.append(p)
    return sorted(removed)


def writable_dir(path: str | os.PathLike, field: str = "--out") -> Path:
    """Create the folder ``path`` if needed and prove it is writable by writing a probe file;
    raise :class:`InputError` naming ``field`` otherwise. Called before any computation, so a
    read-only or mistyped output folder costs nothing."""
    folder = Path(path)
    try:
        if folder.exists() and not folder.is_dir():
            raise InputError(f"{field} {str(folder)!r} is a file, not a folder")
        folder.mkdir(parents=True, exist_ok=True)
        fd, probe = tempfile.mkstemp(prefix=".ehl-write-probe-", dir=folder)
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


def write_text_atomic(path: str | os.PathLike, text: str) -> Path:
    """Write ``text`` to ``path`` through a temporary file beside it and a rename, with the
    user's usual file mode; a crash never leaves a half-written file."""
    path = Path(path)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "w", newline="") as f:
            f.write(text)
        os.chmod(tmp, default_file_mode())
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
    return path

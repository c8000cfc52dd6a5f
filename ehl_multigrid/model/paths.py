"""Output paths that stay where the user asked: file names made from scene names, output
folders checked for writability before any work, and the record of the files each result wrote.

A scene's ``name`` is a label, not a path: ``"/abs/path"`` or ``"../../x"`` must never make a
result land outside ``--out``. :func:`safe_stem` turns any label into one safe file-name stem and
:func:`output_file` joins it to the folder and checks that the result stays inside.
:func:`record_outputs` keeps nothing stale beside a new result. Writing itself is atomic
(:mod:`ehl_multigrid.model.atomic`); one writer per folder (:mod:`ehl_multigrid.model.output_folder`).
"""

from __future__ import annotations

import hashlib
import json
import os
import re
import tempfile
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from .atomic import write_text_atomic
from .errors import InputError

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

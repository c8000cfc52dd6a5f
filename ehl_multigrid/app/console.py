"""Console helpers that every ``ehl`` subcommand shares, including the ones the layers above
add: the common options, progress on stderr, printing a payload as a table or as one JSON
object, and running a command under the lock of its output folder.

Progress goes to stderr only (stdout may carry the ``--json`` payload): a tqdm bar when stderr
is a terminal, plain lines at most every :data:`LINE_INTERVAL_S` seconds otherwise (a log file,
a pipe, a batch system), such as ``ehl solve: grid 1025 points, cycle 3, residual 2.1e-07
(12.3 s)``. ``EHL_PROGRESS=off`` silences it, ``EHL_PROGRESS=lines`` or ``bar`` forces a kind;
``EHL_PROGRESS_INTERVAL`` sets the seconds between lines.

A leaf module: it imports nothing from the rest of the application.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import math
import os
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np


def add_common_options(p: argparse.ArgumentParser, out_default: str = "ehl_out") -> None:
    """Options every subcommand that writes results shares: ``--json``, ``--out``, ``--no-plots``."""
    p.add_argument("--json", action="store_true", help="print the main scalars as one JSON object")
    p.add_argument("--out", default=out_default, help="output folder for HDF5 and PNG (default: %(default)s)")
    p.add_argument("--no-plots", action="store_true", help="skip PNG output")


#: Seconds between two progress lines when stderr is not a terminal.
LINE_INTERVAL_S = 10.0


def accuracy_argument(text: str) -> float | None:
    """``--accuracy``: a relative error in [1e-5, 0.5], or ``none``."""
    if text.strip().lower() == "none":
        return None
    try:
        v = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"accuracy = {text!r} is not a number or 'none'") from None
    if not 1e-5 <= v <= 0.5:
        raise argparse.ArgumentTypeError(f"accuracy = {v:g} is outside the allowed range [1e-05, 0.5] "
                                         f"(relative error) or 'none'")
    return v


def progress_mode() -> str:
    """``"bar"`` (stderr is a terminal), ``"lines"`` (anything else) or ``"off"``; the
    environment variable ``EHL_PROGRESS`` (``off``/``0``, ``lines``, ``bar``) overrides."""
    env = os.environ.get("EHL_PROGRESS", "").strip().lower()
    if env in ("off", "0", "no", "false", "none"):
        return "off"
    if env in ("lines", "bar"):
        return env
    try:
        return "bar" if sys.stderr.isatty() else "lines"
    except (AttributeError, ValueError):  # stderr replaced or closed
        return "lines"


class Progress:
    """Progress of one command on stderr: a tqdm bar on a terminal, plain lines otherwise.

    Parameters
    ----------
    label : str
        What runs, the start of every line (``"ehl solve"``, ``"ehl run default"``).
    total : int or None
        Number of steps (stages, cases), or None for a solve whose length is not known.
    unit : str
        Name of a step (``"stages"``, ``"cases"``).
    initial : int
        Steps already done (a resumed sweep).
    enabled : bool
        False: nothing is shown.
    interval : float or None
        Seconds between two lines of :meth:`status` (``EHL_PROGRESS_INTERVAL``, else
        :data:`LINE_INTERVAL_S`).
    clock : callable
        Seconds of a monotonic clock (tests pass their own).

    Examples
    --------
    >>> import io, sys
    >>> err, sys.stderr = sys.stderr, io.StringIO()
    >>> with Progress("ehl demo", total=2, unit="stages") as p:
    ...     p.status("stage 1/2 film", force=True)
    ...     p.advance()
    ...     p.status("rate-limited: not shown")
    ...     p.advance()
    >>> lines, sys.stderr = sys.stderr.getvalue().splitlines(), err
    >>> [ln.split(" (")[0] for ln in lines]
    ['ehl demo: stage 1/2 film', 'ehl demo: 2/2 stages']
    """

    def __init__(self, label: str, total: int | None = None, unit: str = "", initial: int = 0,
                 enabled: bool = True, interval: float | None = None,
                 clock: Callable[[], float] = time.perf_counter) -> None:
        self.label = label
        self.total = total
        self.unit = unit
        self.done = initial
        self.mode = progress_mode() if enabled else "off"
        if interval is None:
            try:
                interval = float(os.environ.get("EHL_PROGRESS_INTERVAL", LINE_INTERVAL_S))
            except ValueError:
                interval = LINE_INTERVAL_S
        self.interval = max(0.0, interval)
        self.clock = clock
        self.t0 = clock()
        self._last_line = -math.inf
        self._bar: Any = None
        if self.mode == "bar":
            from tqdm import tqdm

            fmt = None if total is not None else "{desc}: {postfix} [{elapsed}]"
            # a bar without a total (a solve) is a status line: it goes when the work is done
            self._bar = tqdm(total=total, initial=initial, desc=label, unit=unit or "it",
                             file=sys.stderr, bar_format=fmt, dynamic_ncols=True, leave=total is not None)

    def _line(self, text: str) -> None:
        print(f"{self.label}: {text} ({self.clock() - self.t0:.1f} s)", file=sys.stderr, flush=True)
        self._last_line = self.clock()

    def status(self, text: str, force: bool = False) -> None:
        """What is being done now: the bar's postfix on a terminal; otherwise a line, unless
        the last one is less than ``interval`` seconds old (``force``: always)."""
        if self.mode == "bar":
            self._bar.set_postfix_str(text, refresh=True)
        elif self.mode == "lines" and (force or self.clock() - self._last_line >= self.interval):
            self._line(text)

    def say(self, text: str) -> None:
        """A line that is always shown (a solve of an accuracy sequence, a warning)."""
        if self.mode == "bar":
            self._bar.write(f"  ... {text}", file=sys.stderr)
        elif self.mode == "lines":
            print(f"{self.label}: {text}", file=sys.stderr, flush=True)
            self._last_line = self.clock()

    def advance(self, n: int = 1, text: str = "") -> None:
        """``n`` more steps done; ``text`` says what (a line at the interval, and at the end)."""
        self.done += n
        if self.mode == "bar":
            self._bar.update(n)
            if text:
                self._bar.set_postfix_str(text, refresh=False)
        elif self.mode == "lines":
            last = self.total is not None and self.done >= self.total
            count = f"{self.done}/{self.total} {self.unit}" if self.total is not None else f"{self.done} {self.unit}"
            self.status(f"{count}{', ' + text if text else ''}", force=last)

    def solver_callback(self, info: dict[str, Any]) -> None:
        """The per-cycle ``callback`` of the multigrid solvers (grid, cycle, residual, load
        error) as a rate-limited status."""
        parts = [f"grid {info.get('points', '?')} points"]
        if info.get("cycle") is not None:
            parts.append(f"cycle {info['cycle']}")
        for key, name in (("residual", "residual"), ("load_error", "load error")):
            v = info.get(key)
            if isinstance(v, (int, float)) and math.isfinite(v):
                parts.append(f"{name} {v:.2g}")
        self.status(", ".join(parts))

    def close(self) -> None:
        if self._bar is not None:
            self._bar.close()
            self._bar = None

    def __enter__(self) -> Progress:
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()


def progress_printer(args: argparse.Namespace, label: str = "ehl solve") -> Callable[[str], None] | None:
    """A printer of an accuracy sequence's progress lines (one per solve of the sequence:
    grid, box, estimate, seconds so far) on stderr, on a terminal or not, ``--json`` or not
    (stdout is left to the payload); None when progress is off (``EHL_PROGRESS=off``).
    ``ehl solve`` uses a :class:`Progress` for these lines and the solver's cycles."""
    mode = progress_mode()
    if mode == "off":
        return None

    def show(text: str) -> None:
        print(f"  ... {text}" if mode == "bar" else f"{label}: {text}", file=sys.stderr, flush=True)

    return show


def report_leftovers(command: str, removed: list[tuple[Path, int]]) -> None:
    """One stderr line naming the leftovers of interrupted runs that a command removed."""
    if removed:
        size = sum(b for _, b in removed)
        names = ", ".join(p.name for p, _ in removed[:3]) + (", ..." if len(removed) > 3 else "")
        print(f"{command}: removed {len(removed)} leftover(s) of interrupted runs "
              f"({size / 1e3:.1f} kB: {names})", file=sys.stderr, flush=True)


def locked_command(func: Callable[[argparse.Namespace], Any], command: str) -> Callable[[argparse.Namespace], Any]:
    """``func(args)`` run under the lock of its output folder ``args.out``
    (:func:`~ehl_multigrid.model.output_folder.output_lock`): a second command into the same folder is
    refused at once (exit code 2), and the leftovers of dead runs there are removed first.
    For the ``func`` of a subcommand: ``p.set_defaults(func=locked_command(run, "ehl x"))``."""
    from ..model.output_folder import output_lock
    from ..model.paths import writable_dir

    def run(args: argparse.Namespace) -> Any:
        created = not os.path.exists(args.out)
        out = writable_dir(args.out)
        try:
            with output_lock(out, command) as removed:
                report_leftovers(command, removed)
                return func(args)
        finally:
            if created:
                # a command refused or failed before it wrote anything leaves no empty folder
                with contextlib.suppress(OSError):
                    os.rmdir(out)

    run.__name__ = getattr(func, "__name__", "run")
    run.__doc__ = func.__doc__
    return run


def jsonable(obj: Any) -> Any:
    """Turn numpy scalars/arrays into plain types; non-finite floats become ``None``."""
    if isinstance(obj, dict):
        return {str(k): jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [jsonable(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return jsonable(obj.tolist())
    if isinstance(obj, (np.bool_, bool)):
        return bool(obj)
    if isinstance(obj, np.integer):
        return int(obj)
    if isinstance(obj, (float, np.floating)):
        f = float(obj)
        return f if math.isfinite(f) else None
    return obj


def print_payload(payload: dict[str, Any]) -> None:
    """Print ``payload`` as one line of JSON."""
    print(json.dumps(jsonable(payload), indent=None, sort_keys=False))


def print_table(payload: dict[str, Any], prefix: str = "") -> None:
    """Print ``payload`` as aligned ``key  value`` lines, each after ``prefix`` (``"#"``: TOML
    comments); long sequences are summarised."""
    width = max((len(k) for k in payload), default=0)
    for k, v in payload.items():
        if isinstance(v, float):
            s = f"{v:.6g}"
        elif isinstance(v, (list, tuple, np.ndarray)) and len(v) > 8:
            s = f"[{len(v)} values: {v[0]:.4g} ... {v[-1]:.4g}]"
        else:
            s = str(v)
        print(f"{prefix}  {k:<{width}}  {s}")

"""Console helpers that every ``ehl`` subcommand shares, including the ones the layers above
add: the common options, and printing a payload as a table or as one JSON object.

A leaf module: it imports nothing from the rest of the application.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from collections.abc import Callable
from typing import Any

import numpy as np


def add_common_options(p: argparse.ArgumentParser, out_default: str = "ehl_out") -> None:
    """Options every subcommand that writes results shares: ``--json``, ``--out``, ``--no-plots``."""
    p.add_argument("--json", action="store_true", help="print the main scalars as one JSON object")
    p.add_argument("--out", default=out_default, help="output folder for HDF5 and PNG (default: %(default)s)")
    p.add_argument("--no-plots", action="store_true", help="skip PNG output")


def progress_printer(args: argparse.Namespace) -> Callable[[str], None] | None:
    """A printer of an accuracy sequence's progress lines (to stderr, on a terminal only and
    not with ``--json``): a solve that refines for minutes shows what it is doing."""
    if getattr(args, "json", False) or not sys.stderr.isatty():
        return None

    def show(text: str) -> None:
        print(f"  ... {text}", file=sys.stderr, flush=True)

    return show


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


def print_table(payload: dict[str, Any]) -> None:
    """Print ``payload`` as aligned ``key  value`` lines; long sequences are summarised."""
    width = max((len(k) for k in payload), default=0)
    for k, v in payload.items():
        if isinstance(v, float):
            s = f"{v:.6g}"
        elif isinstance(v, (list, tuple, np.ndarray)) and len(v) > 8:
            s = f"[{len(v)} values: {v[0]:.4g} ... {v[-1]:.4g}]"
        else:
            s = str(v)
        print(f"  {k:<{width}}  {s}")

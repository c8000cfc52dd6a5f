"""Shared helpers of the mixed-lubrication validation scripts (output folder, compact JSON)."""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir as study_dir  # noqa: E402

OUT = study_dir("mixed")


def clean(obj: Any, digits: int = 6) -> Any:
    """Plain JSON types, floats rounded to ``digits`` significant digits, non-finite -> None."""
    if isinstance(obj, dict):
        return {str(k): clean(v, digits) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [clean(v, digits) for v in obj]
    if isinstance(obj, np.ndarray):
        return clean(obj.tolist(), digits)
    if isinstance(obj, (bool, np.bool_)):
        return bool(obj)
    if isinstance(obj, (int, np.integer)):
        return int(obj)
    if isinstance(obj, (float, np.floating)):
        f = float(obj)
        if not math.isfinite(f):
            return None
        return float(f"{f:.{digits}g}")
    return obj


def out_dir(quick: bool = False) -> Path:
    """``build/validation/mixed/`` for full runs, ``build/validation/mixed/quick/`` for quick runs."""
    path = OUT / "quick" if quick else OUT
    path.mkdir(parents=True, exist_ok=True)
    return path


def write_json(name: str, data: dict, quick: bool = False) -> Path:
    path = out_dir(quick) / name
    path.write_text(json.dumps(clean(data), separators=(",", ":")))
    return path


def plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as pyplot

    return pyplot

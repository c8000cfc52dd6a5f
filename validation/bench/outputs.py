"""Where the bench studies write: ``build/validation/bench/<stem>.json`` (the data) beside ``build/validation/bench/<stem>.md`` (the table)."""

from __future__ import annotations

import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir  # noqa: E402

OUT = out_dir("bench")


def write_study(stem: str, data: dict, lines: list[str]) -> Path:
    """Write ``data`` as JSON and ``lines`` as Markdown under ``build/validation/bench/``; return the stem's path."""
    path = OUT / stem
    path.with_suffix(".json").write_text(json.dumps(data, indent=1))
    path.with_suffix(".md").write_text("\n".join(lines) + "\n")
    print(f"wrote {path}.json/.md")
    return path

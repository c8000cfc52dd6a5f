"""Where the bench studies write: ``out/<stem>.json`` (the data) beside ``out/<stem>.md`` (the table)."""

from __future__ import annotations

import json
from pathlib import Path

OUT = Path(__file__).resolve().parent / "out"


def write_study(stem: str, data: dict, lines: list[str]) -> Path:
    """Write ``data`` as JSON and ``lines`` as Markdown under ``out/``; return the stem's path."""
    OUT.mkdir(exist_ok=True)
    path = OUT / stem
    path.with_suffix(".json").write_text(json.dumps(data, indent=1))
    path.with_suffix(".md").write_text("\n".join(lines) + "\n")
    print(f"wrote {path}.json/.md")
    return path

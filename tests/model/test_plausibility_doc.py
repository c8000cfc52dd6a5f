"""docs/inputs.md lists every plausible range the code checks, with the code's numbers."""

from __future__ import annotations

from pathlib import Path

import pytest

from ehl_multigrid.model.plausibility import PLAUSIBLE

DOC = Path(__file__).resolve().parents[2] / "docs" / "inputs.md"


@pytest.mark.skipif(not DOC.exists(), reason="docs/ not beside the package (installed elsewhere)")
def test_every_plausible_range_is_documented_with_its_numbers() -> None:
    text = DOC.read_text()
    for key, p in PLAUSIBLE.items():
        row = f"| `{key}` | {p.lo:g} to {p.hi:g} | {p.unit} |"
        assert row in text, f"docs/inputs.md lacks or misstates the range of {key}: {row}"

"""docs/api.md stays true: every Python example in it runs as written."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

DOC = Path(__file__).resolve().parents[2] / "docs" / "api.md"
BLOCKS = re.findall(r"```python\n(.*?)```", DOC.read_text(), re.S)


def test_the_api_doc_has_an_example_for_each_physics():
    sections = {s.split(":")[0].split()[0]: s for s in DOC.read_text().split("\n### ")[1:]}
    for physics in ("steady", "starved", "thermal", "transient"):
        assert "```python" in sections[physics], physics


@pytest.mark.parametrize("block", BLOCKS, ids=[f"example{i}" for i in range(len(BLOCKS))])
def test_each_example_of_the_api_doc_runs(block, capsys):
    exec(compile(block, str(DOC), "exec"), {})
    assert capsys.readouterr().out.strip()

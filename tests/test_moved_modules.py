"""Old import paths of moved modules keep working for one release, with a DeprecationWarning
that names the new path, and give the very module object of the new path."""

from __future__ import annotations

import importlib
import subprocess
import sys
import textwrap

import pytest

from ehl_multigrid._moved import MOVED


def _run(code: str) -> subprocess.CompletedProcess:
    """Run ``code`` in a fresh interpreter (the moved modules must not be imported yet)."""
    return subprocess.run([sys.executable, "-W", "error::DeprecationWarning", "-c", textwrap.dedent(code)],
                          capture_output=True, text=True)


@pytest.mark.parametrize("old", sorted(MOVED))
def test_old_path_warns_naming_the_new_one_and_returns_the_new_module(old: str) -> None:
    new = MOVED[old]
    # forget an earlier import of the old name so that this one goes through the finder
    sys.modules.pop(old, None)
    parent, child = old.rsplit(".", 1)
    vars(importlib.import_module(parent)).pop(child, None)
    with pytest.warns(DeprecationWarning, match=rf"{old} moved to {new}"):
        mod = importlib.import_module(old)
    assert mod is importlib.import_module(new)
    assert mod.__name__ == new
    assert mod.__spec__.name == new  # the new module keeps its own spec (reload, pickling)


def test_import_forms_of_an_old_path_all_give_the_new_module() -> None:
    code = """
        import warnings
        warnings.simplefilter("ignore", DeprecationWarning)
        import ehl_multigrid.scene
        from ehl_multigrid.scene import load_scene
        from ehl_multigrid import hertz
        import ehl_multigrid.model.scene as new_scene
        import ehl_multigrid.model.hertz as new_hertz
        assert ehl_multigrid.scene is new_scene
        assert load_scene is new_scene.load_scene
        assert hertz is new_hertz
        print("ok")
    """
    r = _run(code)
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == "ok"


def test_warning_points_at_the_importing_line() -> None:
    code = """
        import warnings
        with warnings.catch_warnings(record=True) as w:
            warnings.simplefilter("always")
            from ehl_multigrid.fits import moes_line_central  # line 5
        print(w[0].category.__name__, w[0].filename, w[0].lineno)
    """
    r = _run(code)
    assert r.returncode == 0, r.stderr
    assert r.stdout.split() == ["DeprecationWarning", "<string>", "5"]


def test_new_paths_import_without_any_warning() -> None:
    code = "import importlib\n" + "".join(f"importlib.import_module({new!r})\n" for new in MOVED.values())
    r = _run(code)
    assert r.returncode == 0, r.stderr


def test_unknown_module_under_the_package_still_fails_to_import() -> None:
    with pytest.raises(ModuleNotFoundError):
        importlib.import_module("ehl_multigrid.no_such_module")

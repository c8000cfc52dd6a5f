"""The layers as the tree shows them: every import of every module (module level and inside
functions, read with ``ast``) goes down the arrows

    ehl_multigrid.model  <-  ehl_multigrid.line / .point / .multigrid  <-  ehl_multigrid.app
                         <-  thermal  <-  mixed

and no module imports itself round a cycle. thermal and mixed use the application only
through its two leaf modules, ``app.console`` and ``app.stages``."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("ehl_multigrid", "thermal", "mixed")
NUMERICAL = ("ehl_multigrid.line", "ehl_multigrid.point", "ehl_multigrid.multigrid", "ehl_multigrid.starved",
             "ehl_multigrid.front", "ehl_multigrid.solution")
APP_LEAVES = {"ehl_multigrid.app.console", "ehl_multigrid.app.stages"}


def module_name(path: Path) -> str:
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def imports_of(source: str, module: str, is_package: bool, known: set[str]) -> list[tuple[str, int]]:
    """``(imported module, line)`` for every import statement anywhere in ``source``.

    ``from pkg import name`` counts as an import of ``pkg.name`` when that is a module of the
    project, else of ``pkg``; relative imports are resolved against ``module``.
    """
    package = module if is_package else module.rpartition(".")[0]
    out = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            out += [(a.name, node.lineno) for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                parts = package.split(".")
                base = ".".join(parts[: len(parts) - (node.level - 1)])
                target = f"{base}.{node.module}" if node.module else base
            else:
                target = node.module
            for a in node.names:
                sub = f"{target}.{a.name}"
                out.append((sub if sub in known else target, node.lineno))
    return out


def project_graph() -> dict[str, list[tuple[str, int]]]:
    """Module -> its imports of project modules (with line numbers)."""
    files = {module_name(p): p for pkg in PACKAGES for p in (ROOT / pkg).rglob("*.py")}
    known = set(files)
    graph = {}
    for mod, path in files.items():
        found = imports_of(path.read_text(), mod, path.name == "__init__.py", known)
        graph[mod] = [(t, line) for t, line in found if t.split(".")[0] in PACKAGES]
    return graph


def within(module: str, *packages: str) -> bool:
    return any(module == p or module.startswith(p + ".") for p in packages)


def violations(graph, importer: tuple[str, ...], forbidden, allowed=lambda t: False) -> list[str]:
    return [f"{mod} line {line} imports {t}" for mod, edges in sorted(graph.items())
            if within(mod, *importer) for t, line in edges if forbidden(t) and not allowed(t)]


def cycles(graph) -> list[list[str]]:
    """Strongly connected components with more than one module, or a module importing itself
    (Tarjan's algorithm)."""
    adj = {m: sorted({t for t, _ in edges if t in graph}) for m, edges in graph.items()}
    index, low, stack, on, out = {}, {}, [], set(), []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in adj[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1 or v in adj[v]:
                out.append(sorted(comp))

    for v in sorted(adj):
        if v not in index:
            visit(v)
    return out


@pytest.fixture(scope="module")
def graph():
    return project_graph()


def test_reader_sees_function_level_and_relative_imports():
    src = "from . import b\nfrom ..x import y\ndef f():\n    import thermal.line\n    from .c import d\n"
    found = imports_of(src, "p.q.a", False, known={"p.q.b"})
    assert [t for t, _ in found] == ["p.q.b", "p.x", "thermal.line", "p.q.c"]


def test_cycle_finder_finds_a_planted_cycle():
    g = {"a": [("b", 1)], "b": [("c", 1)], "c": [("a", 1)], "d": [("a", 1)]}
    assert cycles(g) == [["a", "b", "c"]]


@pytest.mark.xdist_group("layers_graph")
def test_graph_covers_the_three_packages(graph):
    assert {"ehl_multigrid.app.cli", "ehl_multigrid.model.scene", "thermal.traction",
            "mixed.surface.cli"} <= set(graph)
    assert "ehl_multigrid.app.mainjob" in {t for t, _ in graph["ehl_multigrid.app.cli"]}


@pytest.mark.xdist_group("layers_graph")
def test_no_import_cycles(graph):
    assert cycles(graph) == []


@pytest.mark.xdist_group("layers_graph")
def test_model_imports_nothing_above_it(graph):
    above = NUMERICAL + ("ehl_multigrid.app", "thermal", "mixed")
    assert violations(graph, ("ehl_multigrid.model",), lambda t: within(t, *above)) == []


@pytest.mark.xdist_group("layers_graph")
def test_numerical_packages_never_import_the_application_or_the_layers_above(graph):
    above = ("ehl_multigrid.app", "thermal", "mixed")
    assert violations(graph, NUMERICAL, lambda t: within(t, *above)) == []


@pytest.mark.xdist_group("layers_graph")
def test_multilevel_core_never_imports_a_contact(graph):
    # the core is shared: line and point specialise it, never the other way round
    contacts = ("ehl_multigrid.line", "ehl_multigrid.point")
    assert violations(graph, ("ehl_multigrid.multigrid",), lambda t: within(t, *contacts)) == []


@pytest.mark.xdist_group("layers_graph")
def test_contacts_do_not_import_each_other(graph):
    assert violations(graph, ("ehl_multigrid.line",), lambda t: within(t, "ehl_multigrid.point")) == []
    assert violations(graph, ("ehl_multigrid.point",), lambda t: within(t, "ehl_multigrid.line")) == []


@pytest.mark.xdist_group("layers_graph")
def test_thermal_never_imports_mixed(graph):
    assert violations(graph, ("thermal",), lambda t: within(t, "mixed")) == []


@pytest.mark.xdist_group("layers_graph")
def test_thermal_and_mixed_use_only_the_application_leaves(graph):
    assert violations(graph, ("thermal", "mixed"), lambda t: within(t, "ehl_multigrid.app"),
                      allowed=lambda t: t in APP_LEAVES) == []


@pytest.mark.xdist_group("layers_graph")
def test_application_leaves_import_nothing_else_from_the_application(graph):
    assert violations(graph, tuple(APP_LEAVES), lambda t: within(t, "ehl_multigrid.app")) == []

"""The package's layers: folders ranked bottom to top, imports only downward, no circles.

The rule (docs/architecture.md): a module may import modules of its own
folder or of a lower folder (:data:`LAYERS`), never one of a higher folder,
and the import graph has no circle.  Imports under ``if TYPE_CHECKING:`` are
annotations only and are not counted.  ``tether/fd`` imports nothing of
``tether/fe`` (the two discretisations are the cross-check of each other).
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "fem_tether"

#: folders of the package, bottom to top; the entry modules at the top of the package come last
LAYERS = ("core", "physics", "systems", "costs", "config", "tether", "performance", "design", "uncertainty", "io",
          "jobs", "validation", "report", "commands", "")


def module_name(path: Path) -> str:
    parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _runtime_imports(tree: ast.Module):
    """The import nodes of a module outside ``if TYPE_CHECKING:`` blocks."""
    skip = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test):
            skip.update(id(n) for n in ast.walk(node))
    return [n for n in ast.walk(tree) if isinstance(n, (ast.Import, ast.ImportFrom)) and id(n) not in skip]


def import_graph() -> dict[str, set[str]]:
    """Module -> the package's modules it imports (a name imported from a package
    counts as its submodule where there is one)."""
    modules = {module_name(p): p for p in PACKAGE.rglob("*.py")}
    graph = {}
    for name, path in modules.items():
        targets = set()
        for node in _runtime_imports(ast.parse(path.read_text(encoding="utf-8"))):
            assert not (isinstance(node, ast.ImportFrom) and node.level), f"{name}: relative import"
            if isinstance(node, ast.Import):
                candidates = [a.name for a in node.names]
            else:
                submodules = [f"{node.module}.{a.name}" for a in node.names]
                # a name that is not a submodule is the package's (or module's) own
                candidates = submodules + ([node.module] if not all(s in modules for s in submodules) else [])
            for target in candidates:
                while target and target not in modules:
                    target = target.rpartition(".")[0]
                if target.startswith("fem_tether") and target != name:
                    targets.add(target)
        graph[name] = targets
    return graph


def layer(module: str) -> int:
    """Rank of a module's folder in :data:`LAYERS` (the package's own top: the last)."""
    parts = module.split(".")
    return LAYERS.index(parts[1] if len(parts) > 2 or (len(parts) == 2 and parts[1] in LAYERS) else "")


def back_imports(graph) -> list[str]:
    """``a -> b`` where b's folder is above a's."""
    return sorted(f"{a} -> {b}" for a, targets in graph.items() for b in targets
                  if b != "fem_tether" and layer(b) > layer(a))


def circles(graph) -> list[list[str]]:
    """The import graph's strongly connected components of more than one module (Tarjan)."""
    index, low, stack, on, found = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in graph[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for v in graph:
        if v not in index:
            visit(v)
    return found


def test_every_folder_has_a_layer():
    folders = {p.name for p in PACKAGE.iterdir() if p.is_dir() and (p / "__init__.py").exists()}
    assert folders == set(LAYERS) - {""}


def test_the_top_holds_only_the_entry_modules():
    assert sorted(p.name for p in PACKAGE.glob("*.py")) == ["__init__.py", "__main__.py", "cli.py"]


def test_imports_point_down_the_layers():
    assert back_imports(import_graph()) == []


def test_no_import_circles():
    assert circles(import_graph()) == []


def test_fd_imports_nothing_of_fe():
    graph = import_graph()
    assert [f"{a} -> {b}" for a in graph if a.startswith("fem_tether.tether.fd")
            for b in graph[a] if b.startswith("fem_tether.tether.fe")] == []


def test_the_rule_catches_a_back_import():
    graph = {"fem_tether.physics.wind": {"fem_tether.config.model"}, "fem_tether.config.model": set()}
    assert back_imports(graph) == ["fem_tether.physics.wind -> fem_tether.config.model"]
    assert circles({"a": {"b"}, "b": {"a"}}) == [["a", "b"]]


@pytest.mark.parametrize("module", ["fem_tether.cli", "fem_tether.config.model"])
def test_layer_of_a_module(module):
    assert layer(module) == (LAYERS.index("") if module == "fem_tether.cli" else LAYERS.index("config"))

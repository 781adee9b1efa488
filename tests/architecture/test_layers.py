"""The declared layers of robosolve (docs/architecture.md), checked on the source.

Every `import` of every module is read from the AST (function-level imports included) and

* each module belongs to a declared layer (a new package must be declared here and in
  docs/architecture.md);
* a module imports only its own layer or lower ones: load -> model -> engines -> solvers
  -> render -> run/grading/variants -> cli, with errors/core/questions below everything;
* the engines (kinematics, ik, dynamics, motion, geometry) are pure math: besides each
  other they import only core and errors (no question, no context, no model);
* no import circle between modules.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[2] / "robosolve"

# layer rank of each top-level part of the package
LAYERS = {
    "robosolve": 0, "errors": 0, "core": 0, "questions": 0,
    "load": 1,
    "model": 2,
    "kinematics": 3, "ik": 3, "dynamics": 3, "motion": 3, "geometry": 3,
    "solvers": 4,
    "render": 5,
    "run": 6, "grading": 6, "variants": 6,
    "cli": 7, "__main__": 7,
}
ENGINES = {"kinematics", "ik", "dynamics", "motion", "geometry"}
ENGINE_MAY_IMPORT = ENGINES | {"core", "errors"}


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts)


def _part(module: str) -> str:
    """The layer key of a module: its first component below `robosolve`."""
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else "robosolve"


def import_graph() -> dict[str, list[tuple[str, int]]]:
    """module -> [(imported robosolve module, line)], every import statement included."""
    files = {_module_name(p): p for p in sorted(PACKAGE.rglob("*.py"))}
    graph = {}
    for name, path in files.items():
        package = name if path.name == "__init__.py" else name.rpartition(".")[0]
        edges = []
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), str(path))):
            if isinstance(node, ast.Import):
                targets = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom):
                if node.level:
                    base = package.split(".")[:len(package.split(".")) - node.level + 1]
                    mod = ".".join(base + ([node.module] if node.module else []))
                else:
                    mod = node.module or ""
                # `from pkg import sub` imports the submodule when there is one
                targets = [mod] + [f"{mod}.{a.name}" for a in node.names
                                   if f"{mod}.{a.name}" in files]
            else:
                continue
            for t in targets:
                while t and t not in files and "." in t:   # `import a.b.c` of a module a.b
                    t = t.rpartition(".")[0]
                if t in files and t != name:
                    edges.append((t, node.lineno))
        graph[name] = edges
    return graph


GRAPH = import_graph()


def test_every_module_has_a_declared_layer():
    unknown = sorted(m for m in GRAPH if _part(m) not in LAYERS)
    assert not unknown, ("modules outside the declared layers (declare them in "
                         f"tests/architecture/test_layers.py and docs/architecture.md): {unknown}")


def test_imports_go_down_the_layers():
    bad = []
    for mod, edges in GRAPH.items():
        for target, line in edges:
            a, b = _part(mod), _part(target)
            if a in LAYERS and b in LAYERS and LAYERS[b] > LAYERS[a]:
                bad.append(f"{mod}:{line} imports {target} (layer {b} is above {a})")
    assert not bad, "\n".join(bad)


def test_engines_are_pure_math():
    bad = [f"{mod}:{line} imports {target}"
           for mod, edges in GRAPH.items() if _part(mod) in ENGINES
           for target, line in edges if _part(target) not in ENGINE_MAY_IMPORT]
    assert not bad, "\n".join(bad)


def test_no_solver_imports_render():
    bad = [f"{mod}:{line} imports {target}"
           for mod, edges in GRAPH.items() if _part(mod) == "solvers"
           for target, line in edges if _part(target) == "render"]
    assert not bad, "\n".join(bad)


def _cycles(graph) -> list[list[str]]:
    """Strongly connected components with more than one module (Tarjan)."""
    index, low, stack, on, out = {}, {}, [], set(), []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w, _ in graph.get(v, []):
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
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def test_no_import_circles():
    assert _cycles(GRAPH) == []


def test_the_checks_can_fail():
    """The walker sees function-level imports and the cycle finder finds a circle."""
    assert ("robosolve.solvers.base", 0) not in GRAPH["robosolve.errors"]
    fake = {"a": [("b", 1)], "b": [("c", 2)], "c": [("a", 3)], "d": [("a", 1)]}
    assert _cycles(fake) == [["a", "b", "c"]]
    func_level = [e for e in GRAPH["robosolve.run.pipeline"] if e[0] == "robosolve.model"]
    assert func_level, "the function-level import of robosolve.model in pipeline.py is seen"


@pytest.mark.parametrize("path", ["robosolve/dynamics/examples.py", "robosolve/dynamics/reference.py"])
def test_fixtures_live_outside_the_package(path):
    assert not (PACKAGE.parent / path).exists()

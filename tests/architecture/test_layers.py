"""The declared layers of robosolve (docs/architecture.md), checked on the source.

Every `import` of every module is read from the AST (function-level imports included) and

* each module belongs to a declared layer (a new package must be declared here and in
  docs/architecture.md);
* a module imports only its own layer or lower ones: load -> model -> engines -> solvers
  -> render -> run/grading/variants -> cli, with errors/core below everything and the
  question types (questions/) beside the loader;
* the engines (kinematics, ik, dynamics, motion, simulation, geometry) are pure math: besides each
  other they import only core and errors (no question, no context, no model);
* no import circle between modules.
"""

from __future__ import annotations

import ast
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[2] / "robosolve"

# layer rank of each top-level part of the package
LAYERS = {
    "robosolve": 0, "errors": 0, "core": 0,
    # the question types sit with the loader: a type module names its option validators
    # (load/validators.py) and the loader reads the registry
    "load": 1, "questions": 1,
    "model": 2,
    "kinematics": 3, "ik": 3, "dynamics": 3, "motion": 3, "simulation": 3, "geometry": 3,
    "solvers": 4,
    "render": 5,
    "run": 6, "grading": 6, "variants": 6, "papers": 6,
    "cli": 7, "__main__": 7,
}
ENGINES = {"kinematics", "ik", "dynamics", "motion", "simulation", "geometry"}
ENGINE_MAY_IMPORT = ENGINES | {"core", "errors"}


def _part(module: str) -> str:
    """The layer key of a module: its first component below `robosolve`."""
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else "robosolve"


def _module_name_in(path: Path, package: Path) -> str:
    parts = list(path.relative_to(package.parent).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts)


def import_graph(package: Path = PACKAGE) -> dict[str, list[tuple[str, int]]]:
    """module -> [(imported robosolve module, line)], every import statement included."""
    files = {_module_name_in(p, package): p for p in sorted(package.rglob("*.py"))}
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


def layer_violations(graph) -> list[str]:
    bad = []
    for mod, edges in graph.items():
        for target, line in edges:
            a, b = _part(mod), _part(target)
            if a in LAYERS and b in LAYERS and LAYERS[b] > LAYERS[a]:
                bad.append(f"{mod}:{line} imports {target} (layer {b} is above {a})")
    return bad


def test_imports_go_down_the_layers():
    bad = layer_violations(GRAPH)
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


def test_the_checks_can_fail(tmp_path):
    """On a small package: the walker sees a function-level import with its line, the layer
    check reports it and the cycle finder finds the circle it closes."""
    pkg = tmp_path / "robosolve"
    (pkg / "solvers").mkdir(parents=True)
    (pkg / "__init__.py").write_text("")
    (pkg / "errors.py").write_text('"""doc"""\n\n\ndef f():\n    from robosolve.solvers import base\n')
    (pkg / "solvers" / "__init__.py").write_text("")
    (pkg / "solvers" / "base.py").write_text("import os\nimport robosolve.errors\n")
    graph = import_graph(pkg)
    assert graph["robosolve.errors"] == [("robosolve.solvers", 5), ("robosolve.solvers.base", 5)]
    assert graph["robosolve.solvers.base"] == [("robosolve.errors", 2)]
    assert layer_violations(graph) == [
        "robosolve.errors:5 imports robosolve.solvers (layer solvers is above errors)",
        "robosolve.errors:5 imports robosolve.solvers.base (layer solvers is above errors)"]
    assert _cycles(graph) == [["robosolve.errors", "robosolve.solvers.base"]]
    fake = {"a": [("b", 1)], "b": [("c", 2)], "c": [("a", 3)], "d": [("a", 1)]}
    assert _cycles(fake) == [["a", "b", "c"]]
    func_level = [e for e in GRAPH["robosolve.run.pipeline"] if e[0] == "robosolve.model"]
    assert func_level, "the function-level import of robosolve.model in pipeline.py is seen"


# what only the tests may use: the test runner, the test fixtures, the reference libraries
TEST_ONLY = ("tests", "pytest", "hypothesis", "roboticstoolbox", "pinocchio", "spatialmath")


def test_fixtures_live_outside_the_package():
    """No module of the package imports the tests, their fixtures or the reference libraries
    they check against (the fixtures live in tests/support/, the references in the tests)."""
    bad = []
    for path in sorted(PACKAGE.rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), str(path))):
            names = ([a.name for a in node.names] if isinstance(node, ast.Import)
                     else [node.module or ""] if isinstance(node, ast.ImportFrom) and not node.level else [])
            bad += [f"{path.relative_to(PACKAGE.parent)}:{node.lineno} imports {n}"
                    for n in names if n.split(".")[0] in TEST_ONLY]
    assert not bad, "\n".join(bad)
    assert (PACKAGE.parent / "tests" / "support" / "robots.py").is_file()

"""The package's layers point one way:

    sim <- annotations <- expert <- tasks <- episodes <- envs / datasets_build / eval / validity / policies <- cli

Every import in the package (module level, inside functions and under TYPE_CHECKING) is read from
the source; a module may import its own layer and the layers below, never one above (type-only
imports included), and no group of modules may import each other in a cycle at run time. ``python -m pytest tests/test_layers.py -s`` prints the
layer-to-layer import counts."""

import ast
import collections
import subprocess
import sys
from pathlib import Path

PACKAGE = "lerobot_activearena"
ROOT = Path(__file__).resolve().parents[1] / PACKAGE
LAYERS = {  # rank: a module may import ranks <= its own
    "sim": 0,
    "annotations": 1,
    "expert": 2,
    "tasks": 3,
    "episodes": 4,  # the episode stepper and the expert's episodes
    "sharding": 5,  # datatrove plumbing shared by the sharded jobs
    "envs": 5,
    "datasets_build": 5,
    "eval": 5,
    "validity": 5,  # adversaries and the suite that runs them
    "policies": 5,
    "cli": 6,
}


def _module_name(path: Path) -> str:
    parts = path.relative_to(ROOT.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _modules() -> dict[str, Path]:
    return {_module_name(p): p for p in ROOT.rglob("*.py")}


def _resolve(importer: str, is_package: bool, node: ast.ImportFrom, modules: dict) -> list[str]:
    """The package modules an ``from ... import ...`` names (a submodule when a name is one)."""
    if node.level:
        base = importer.split(".") if is_package else importer.split(".")[:-1]
        base = base[: len(base) - (node.level - 1)]
        target = ".".join(base + ([node.module] if node.module else []))
    else:
        target = node.module or ""
    if not target.startswith(PACKAGE):
        return []
    out = []
    for alias in node.names:
        sub = f"{target}.{alias.name}"
        out.append(sub if sub in modules else target)
    return out


def _type_checking_nodes(tree: ast.AST) -> set[int]:
    """ids of the import nodes under ``if TYPE_CHECKING:`` (annotations only, no runtime import)."""
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.If) and getattr(node.test, "id", None) == "TYPE_CHECKING":
            out |= {id(n) for stmt in node.body for n in ast.walk(stmt)}
    return out


def import_graph(runtime_only: bool = False) -> dict[str, set[str]]:
    """module -> package modules it imports; ``runtime_only`` leaves out TYPE_CHECKING imports."""
    modules = _modules()
    graph: dict[str, set[str]] = {m: set() for m in modules}
    for name, path in modules.items():
        tree = ast.parse(path.read_text(), str(path))
        skip = _type_checking_nodes(tree) if runtime_only else set()
        for node in ast.walk(tree):
            if id(node) in skip:
                continue
            if isinstance(node, ast.ImportFrom):
                targets = _resolve(name, path.name == "__init__.py", node, modules)
            elif isinstance(node, ast.Import):
                targets = [a.name for a in node.names if a.name.startswith(PACKAGE)]
            else:
                continue
            graph[name] |= {t for t in targets if t in modules and t != name}
    return graph


def layer(module: str) -> str | None:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else None  # None: the package's own __init__


def _cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components with more than one module (Tarjan)."""
    index, low, stack, on_stack, out = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in graph[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    sys.setrecursionlimit(10_000)
    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def test_every_module_belongs_to_a_layer():
    unknown = {layer(m) for m in import_graph() if layer(m) is not None} - set(LAYERS)
    assert not unknown, f"modules outside the declared layers: {unknown}; add them to LAYERS"


def test_no_module_imports_a_higher_layer():
    graph = import_graph()
    counts = collections.Counter()
    upward = []
    for mod, targets in sorted(graph.items()):
        for t in sorted(targets):
            a, b = layer(mod), layer(t)
            if a is None or b is None:
                continue
            counts[(a, b)] += 1
            if LAYERS[b] > LAYERS[a]:  # peers may import each other; the cycle test keeps that one-way
                upward.append(f"{mod} -> {t}")
    print("\nimports between layers (importer -> imported: count)")
    for (a, b), n in sorted(counts.items(), key=lambda kv: (LAYERS[kv[0][0]], kv[0])):
        print(f"  {a:>15} -> {b:<15} {n}")
    assert not upward, "imports against the layer order:\n" + "\n".join(upward)


def test_no_import_cycles():
    cycles = _cycles(import_graph(runtime_only=True))
    assert not cycles, "modules that import each other in a cycle: " + "; ".join(
        " <-> ".join(c) for c in cycles
    )


def test_the_simulator_imports_neither_torch_nor_lerobot():
    code = (
        "import sys, lerobot_activearena.sim.simulator, lerobot_activearena.episodes.rollout; "
        "print(sorted(m for m in ('torch', 'lerobot', 'transformers') if m in sys.modules))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr[-2000:]
    assert out.stdout.strip() == "[]", f"sim-only workers import {out.stdout.strip()}"

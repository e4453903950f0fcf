"""The house rules of the layout (issue 25): layers import downwards only, no import cycles, small modules.

The import graph is read from the source (``ast``), not from a running interpreter, so lazy
imports inside functions count too.  Layers, lowest first (docs/architecture.md):

    suslov.kernel, suslov.recipes, suslov.outdir, suslov.manifest, suslov.loader   (numerics, constructions, I/O)
    suslov.executor, suslov.runtime, suslov.validated               (shared machinery)
    generated                                                        (the emitted module)
    suslov.simulator                                                 (scenes, sweeps, figures, CLI)
    derivations.core < derivations.sections < derivations.registry, derivations.proofs < derivations.output
    suslov.build                                                     (the build's entry point, [build] extra)

and nothing in ``suslov`` or ``generated`` imports ``derivations`` except ``suslov.build``, which is the
derivations' own entry point shipped inside the namespace; the template holds at most 250
lines; no Python module of the project holds more than about 500.
"""
import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
PACKAGES = ("derivations", "suslov", "generated")


def modules() -> dict:
    found = {}
    for package in PACKAGES:
        for path in sorted((ROOT / package).rglob("*.py")):
            parts = path.relative_to(ROOT).with_suffix("").parts
            name = ".".join(parts[:-1] if parts[-1] == "__init__" else parts)
            found[name] = path
    return found


def imports(name: str, path: Path, known: dict) -> set:
    package = name if path.name == "__init__.py" else name.rsplit(".", 1)[0]
    out = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            out.update(a.name for a in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                anchor = package.split(".")[:len(package.split(".")) - node.level + 1]
                base = ".".join(anchor + ([base] if base else []))
            out.add(base)
            out.update(f"{base}.{a.name}" for a in node.names)
    return {m for m in out if m in known and m != name}


MODULES = modules()   # walked once: each module's imports are looked up in it
GRAPH = {name: imports(name, path, MODULES) for name, path in MODULES.items()}


def test_no_module_pair_imports_each_other_and_no_cycle():
    index, low, stack, on, cycles, counter = {}, {}, [], set(), [], [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in GRAPH[v]:
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
                cycles.append(sorted(component))

    for v in GRAPH:
        if v not in index:
            visit(v)
    assert cycles == []


def floor(name: str) -> int:
    order = [("suslov.build", 10), ("derivations.output", 9), ("derivations.registry", 8), ("derivations.proofs", 8),
             ("derivations.sections", 7),
             ("derivations.core", 6), ("derivations", 6), ("suslov.simulator", 5), ("generated", 4),
             ("suslov.validated", 3), ("suslov.runtime", 3), ("suslov.executor", 2), ("suslov.loader", 1),
             ("suslov.outdir", 0), ("suslov.manifest", 0), ("suslov.acl", 0), ("suslov.kernel", 0), ("suslov.recipes", 0),
             ("suslov.interrupts", 0), ("suslov.extras", 0), ("suslov.cli", 5), ("suslov", 5)]
    for prefix, level in order:
        if name == prefix or name.startswith(prefix + "."):
            return level
    raise AssertionError(f"{name}: in no layer")


def test_layers_import_downwards_only():
    upward = [(a, b) for a, targets in GRAPH.items() for b in targets
              if floor(b) > floor(a) and not (a == "suslov" and b.startswith("suslov."))]
    assert upward == []


def test_runtime_never_imports_the_symbolic_layer():
    offenders = [(a, b) for a, targets in GRAPH.items() for b in targets
                 if a.split(".")[0] in ("suslov", "generated") and b.startswith("derivations")
                 and not (a == "suslov.build" or a.startswith("suslov.build."))]
    assert offenders == []


@pytest.mark.parametrize("name", sorted(MODULES))
def test_modules_are_small(name):
    lines = MODULES[name].read_text(encoding="utf-8").count("\n")
    assert lines <= 520, f"{name}: {lines} lines"


def test_template_holds_what_is_emitted():
    assert (ROOT / "templates" / "suslov_formulas.py.j2").read_text(encoding="utf-8").count("\n") <= 250

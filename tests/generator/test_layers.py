"""The generator's modules import one way: load -> resolve -> check -> emit, never back.

Each module belongs to a layer and imports only from its own layer or the ones below; imports
under `if TYPE_CHECKING:` (annotations only) do not count. A cycle is an error too."""

from __future__ import annotations

import ast
from pathlib import Path

GENERATOR = Path(__file__).resolve().parents[2] / "generator"

# Bottom to top.
LAYERS = [
    {"paths", "errors", "numbers", "rules", "cache"},     # rules: the checks' ids; cache: kept between runs
    {"field_types"},                                      # what differs by field type
    {"model"},                                            # the typed spec
    {"loader", "migrate", "naming", "selection"},         # reading YAML (an older schema's too); naming and picking sentences
    {"names", "names_c", "names_rust", "pairing", "rust_features"},   # what the model implies, per language
    {"reference", "reference_ais", "reference_binary", "reference_rtcm3"},   # the reference decoders
    {"resolve"},
    {"checks", "checks_payload", "checks_binary", "checks_rtcm3"},
    {"build", "diff", "reconcile", "scaffold"},           # load, resolve and check a spec; compare specs; new files
    {"emit"},                                             # what the emitters share
    {"emit_vectors", "emit_python", "emit_python_ais", "emit_python_ubx", "emit_python_rtcm3", "emit_python_apps", "emit_c", "emit_c_ais", "emit_c_rtcm3", "emit_rust",
     "emit_rust_ais", "emit_rust_rtcm3", "emit_rust_ubx", "emit_docs", "emit_ubx_config", "emit_framing",
     "emit_packaging", "emit_c_ubx"},
    {"render", "cli", "__main__", "__init__"},            # the drivers
]
LAYER = {module: n for n, layer in enumerate(LAYERS) for module in layer}


def _is_type_checking(node: ast.If) -> bool:
    test = node.test
    return isinstance(test, ast.Name) and test.id == "TYPE_CHECKING" or \
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING"


def imports(source: str) -> set[str]:
    """The generator modules a module's source imports at run time."""
    found: set[str] = set()

    def visit(node: ast.AST) -> None:
        if isinstance(node, ast.If) and _is_type_checking(node):
            for child in node.orelse:
                visit(child)
            return
        if isinstance(node, ast.ImportFrom) and node.level == 1:
            found.update([node.module.split(".")[0]] if node.module else [a.name for a in node.names])
        elif isinstance(node, ast.ImportFrom) and (node.module or "").startswith("generator."):
            found.add(node.module.split(".")[1])
        for child in ast.iter_child_nodes(node):
            visit(child)

    visit(ast.parse(source))
    return found


def graph() -> dict[str, set[str]]:
    return {p.stem: imports(p.read_text(encoding="utf-8")) for p in sorted(GENERATOR.glob("*.py"))}


def test_every_module_has_a_layer() -> None:
    assert set(graph()) - set(LAYER) == set(), "add the new module to LAYERS"


def test_imports_go_down() -> None:
    upward = [f"{module} (layer {LAYER[module]}) imports {dep} (layer {LAYER[dep]})"
              for module, deps in graph().items() for dep in sorted(deps) if LAYER[dep] > LAYER[module]]
    assert upward == []


def test_no_cycles() -> None:
    deps = graph()
    done: set[str] = set()

    def walk(module: str, path: list[str]) -> None:
        assert module not in path, " -> ".join(path[path.index(module):] + [module])
        if module in done:
            return
        for dep in sorted(deps[module]):
            walk(dep, path + [module])
        done.add(module)

    for module in deps:
        walk(module, [])


def test_checks_import_no_emitter() -> None:
    # the example the rule is for: an upward import is caught
    source = (GENERATOR / "checks.py").read_text(encoding="utf-8") + "\nfrom .emit_c import member\n"
    assert "emit_c" in imports(source) and LAYER["emit_c"] > LAYER["checks"]

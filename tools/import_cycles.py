"""List the import cycles among the repository's modules, local (function-level) imports included.

    python tools/import_cycles.py            # exits 1 if any cycle exists
    python tools/import_cycles.py --top      # module-level imports only (what Python itself would trip on)

A cycle kept from failing by moving one import into a function is still a cycle: the two modules cannot
be understood, tested or moved apart. Each cycle is printed with the edges that close it; an edge marked
``(local)`` is an import inside a function. Packages count as their ``__init__`` module; tests are left out.
"""

from __future__ import annotations

import argparse
import ast
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
_SKIPPED = {".venv", ".venv-numpy2", "tests", "build", "dist", "__pycache__", ".git"}


def module_name(path: Path) -> str:
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts) or "__init__"


def _resolve(current: str, is_package: bool, node: ast.ImportFrom) -> str:
    if node.level == 0:
        return node.module or ""
    base = current.split(".") if is_package else current.split(".")[:-1]
    base = base[: len(base) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


def import_edges(modules: dict[str, Path], top_only: bool) -> dict[str, dict[str, bool]]:
    """``{importer: {imported: local}}`` for imports between modules of the repository (``local``: the
    import sits inside a function or class body, not at module level)."""
    edges: dict[str, dict[str, bool]] = {name: {} for name in modules}
    for name, path in modules.items():
        tree = ast.parse(path.read_text(), str(path))
        top_level = {id(node) for node in tree.body}
        for node in ast.walk(tree):
            if isinstance(node, ast.Import):
                targets = [alias.name for alias in node.names]
            elif isinstance(node, ast.ImportFrom):
                base = _resolve(name, path.name == "__init__.py", node)
                # ``from pkg import module`` imports the submodule; ``from module import name`` the module.
                targets = [f"{base}.{alias.name}" if f"{base}.{alias.name}" in modules else base
                           for alias in node.names]
            else:
                continue
            local = id(node) not in top_level and not _inside_type_checking(tree, node)
            if top_only and local:
                continue
            for target in targets:
                while target and target not in modules:
                    target = target.rpartition(".")[0]
                if target and target != name and not name.startswith(target + "."):
                    edges[name][target] = edges[name].get(target, True) and local
    return edges


def _inside_type_checking(tree: ast.Module, node: ast.AST) -> bool:
    return any(isinstance(top, ast.If) and "TYPE_CHECKING" in ast.unparse(top.test) and node in ast.walk(top)
               for top in tree.body)


def cycles(edges: dict[str, dict[str, bool]]) -> list[list[str]]:
    """Strongly connected components with more than one module (Tarjan), each sorted."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: list[list[str]] = []

    def visit(node: str) -> None:
        index[node] = low[node] = len(index)
        stack.append(node)
        on_stack.add(node)
        for target in edges[node]:
            if target not in index:
                visit(target)
                low[node] = min(low[node], low[target])
            elif target in on_stack:
                low[node] = min(low[node], index[target])
        if low[node] == index[node]:
            component = []
            while True:
                member = stack.pop()
                on_stack.discard(member)
                component.append(member)
                if member == node:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    sys.setrecursionlimit(10000)
    for node in sorted(edges):
        if node not in index:
            visit(node)
    return sorted(found)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--top", action="store_true", help="module-level imports only")
    args = parser.parse_args(argv)
    modules = {module_name(path): path for path in sorted(ROOT.rglob("*.py"))
               if not _SKIPPED & set(path.relative_to(ROOT).parts)}
    edges = import_edges(modules, args.top)
    found = cycles(edges)
    for component in found:
        print("cycle: " + ", ".join(component))
        for importer in component:
            for target, local in sorted(edges[importer].items()):
                if target in component:
                    print(f"    {importer} -> {target}" + (" (local)" if local else ""))
    print(f"{len(found)} import cycle(s) among {len(modules)} modules")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())

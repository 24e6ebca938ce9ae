"""The import graph of each package has no cycle, and no module hides an import.

Every module of the package is parsed (its source is never run) and every import counts:
at module level and inside functions alike, only those under ``if TYPE_CHECKING:`` are left
out (they never run).  An edge goes from the importing module to the module it imports:

- ``import a.b.c`` imports ``a.b.c``; ``from a.b import c`` imports the submodule ``a.b.c``
  when there is one, else the package ``a.b`` (its ``__init__``);
- relative imports (``from . import x``, ``from ..m import y``) are resolved against the
  importing module's package;
- the packages that Python initialises on the way (``a.b`` for ``import a.b.c``) are
  imported too, except those that hold the importing module: they are initialised before
  it whoever imports it first (else every module would import its package's ``__init__``).

Beside the cycles, two ways of hiding a dependency fail the test: an import by a string
(``importlib.import_module``, ``__import__``) that may name a module of the project, and a
private name (``_name``) taken from another module of the project, by ``from m import _name``
or ``m._name``.  A private *module* (``_fast.py``) is its package's own: a module of the same
package may import it.
"""

from __future__ import annotations

import ast
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import networkx as nx
import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("assur", "synthesis")


@dataclass(frozen=True)
class Module:
    """One module of a package: its dotted name, file and parsed source."""

    name: str
    path: Path
    tree: ast.Module
    is_package: bool

    @property
    def package(self) -> str:
        """The package that relative imports in this module start from."""
        return self.name if self.is_package else self.name.rpartition(".")[0]


@dataclass(frozen=True)
class Found:
    """A place in a module's source: the module, the line, and what is there."""

    module: str
    line: int
    what: str

    def __str__(self) -> str:
        return f"{self.module}:{self.line}: {self.what}"


def modules_of(package: str, root: Path = ROOT) -> dict[str, Module]:
    """Every module of ``package`` under ``root``, by dotted name."""
    found: dict[str, Module] = {}
    for path in sorted((root / package).rglob("*.py")):
        parts = path.relative_to(root).with_suffix("").parts
        is_package = parts[-1] == "__init__"
        name = ".".join(parts[:-1] if is_package else parts)
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
        found[name] = Module(name, path, tree, is_package)
    return found


def _is_type_checking(test: ast.expr) -> bool:
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING")


def run_nodes(tree: ast.AST) -> Iterator[ast.AST]:
    """Every node of ``tree`` that may run: all but the bodies of ``if TYPE_CHECKING:``."""
    for node in ast.iter_child_nodes(tree):
        if isinstance(node, ast.If) and _is_type_checking(node.test):
            for other in node.orelse:
                yield other
                yield from run_nodes(other)
            continue
        yield node
        yield from run_nodes(node)


def _absolute(module: Module, node: ast.ImportFrom) -> str:
    """The absolute name of the module a ``from … import`` reads from."""
    if node.level == 0:
        assert node.module is not None
        return node.module
    base = module.package.split(".")
    base = base[:len(base) - (node.level - 1)]
    return ".".join([*base, *([node.module] if node.module else [])])


def imports_of(module: Module, names: set[str]) -> Iterator[tuple[str, ast.stmt]]:
    """The modules of ``names`` that ``module`` imports, each with its import statement."""
    for node in run_nodes(module.tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name in names:
                    yield alias.name, node
        elif isinstance(node, ast.ImportFrom):
            source = _absolute(module, node)
            for alias in node.names:
                sub = f"{source}.{alias.name}"
                if sub in names:
                    yield sub, node
                elif source in names:
                    yield source, node


def _parents(name: str) -> list[str]:
    """The packages that hold a module, outermost first (``a``, ``a.b`` for ``a.b.c``)."""
    parts = name.split(".")
    return [".".join(parts[:k]) for k in range(1, len(parts))]


def import_graph(modules: dict[str, Module]) -> nx.DiGraph:
    """Module → module it imports, for the modules of one package.

    Importing ``a.b.c`` also runs the ``__init__`` of ``a.b`` (and of ``a``): an edge goes to
    each package on the way that does not hold the importing module (those that hold it are
    initialised before it, whoever imports it first).
    """
    graph = nx.DiGraph()
    graph.add_nodes_from(modules)
    names = set(modules)
    for module in modules.values():
        own = {module.name, *_parents(module.name)}
        for target, node in imports_of(module, names):
            for reached in (*_parents(target), target):
                if reached in names and reached not in own:
                    graph.add_edge(module.name, reached, line=node.lineno)
    return graph


def _project(name: str) -> bool:
    return name.split(".")[0] in PACKAGES or name.startswith(".")


def string_imports(module: Module) -> Iterator[Found]:
    """Imports by a string (``import_module``, ``__import__``) that may name a project module.

    A literal naming another library is allowed; a literal of the project, an f-string that
    starts with the project's name, and a name known only when the program runs are not.
    """
    for node in run_nodes(module.tree):
        if not isinstance(node, ast.Call) or not node.args:
            continue
        func = node.func
        called = (func.attr if isinstance(func, ast.Attribute)
                  else func.id if isinstance(func, ast.Name) else "")
        if called not in ("import_module", "__import__"):
            continue
        arg = node.args[0]
        if isinstance(arg, ast.Constant) and isinstance(arg.value, str):
            hidden = _project(arg.value)
        elif isinstance(arg, ast.JoinedStr) and arg.values and isinstance(
                arg.values[0], ast.Constant):
            hidden = _project(str(arg.values[0].value))
        else:
            hidden = True
        if hidden:
            yield Found(module.name, node.lineno, f"{called}({ast.unparse(arg)})")


def _private(name: str) -> bool:
    return name.startswith("_") and not name.startswith("__")


def private_names(module: Module, modules: dict[str, Module]) -> Iterator[Found]:
    """Private names of other project modules that ``module`` uses.

    ``from m import _name`` and ``m._name`` (``m`` an imported project module), except a
    private submodule of the importing module's own package.
    """
    aliases: dict[str, str] = {}
    for node in run_nodes(module.tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name in modules and alias.asname:
                    aliases[alias.asname] = alias.name
        elif isinstance(node, ast.ImportFrom):
            source = _absolute(module, node)
            if not _project(source) or source == module.name:
                continue
            for alias in node.names:
                sub = f"{source}.{alias.name}"
                if sub in modules:
                    aliases[alias.asname or alias.name] = sub
                if _private(alias.name) and not (sub in modules and source == module.package):
                    yield Found(module.name, node.lineno, f"from {source} import {alias.name}")
    for node in run_nodes(module.tree):
        if (isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name)
                and node.value.id in aliases and _private(node.attr)):
            target = aliases[node.value.id]
            if f"{target}.{node.attr}" not in modules or target != module.package:
                yield Found(module.name, node.lineno, f"{node.value.id}.{node.attr}")


@pytest.fixture(scope="module", params=PACKAGES)
def package(request: pytest.FixtureRequest) -> dict[str, Module]:
    return modules_of(request.param)


def knots(graph: nx.DiGraph) -> list[list[str]]:
    """One cycle of each knot of mutually importing modules, as the lines of its imports."""
    found = []
    for component in nx.strongly_connected_components(graph):
        if len(component) > 1:
            cycle = nx.find_cycle(graph.subgraph(component))
            found.append([f"{a} imports {b} (line {graph.edges[a, b]['line']})"
                          for a, b in cycle])
    return sorted(found)


def test_the_package_has_no_import_cycle(package: dict[str, Module]) -> None:
    graph = import_graph(package)
    found = knots(graph)
    members = [sorted(c) for c in nx.strongly_connected_components(graph) if len(c) > 1]
    assert not found, "import cycles, in knots of " + "; ".join(map(", ".join, members)) \
        + ":\n" + "\n".join("  " + "\n    ".join(cycle) for cycle in found)


def test_no_module_imports_the_project_by_a_string(package: dict[str, Module]) -> None:
    found = [str(f) for module in package.values() for f in string_imports(module)]
    assert not found, "imports by a string:\n  " + "\n  ".join(found)


def test_no_module_uses_a_private_name_of_another(package: dict[str, Module]) -> None:
    found = [str(f) for module in package.values() for f in private_names(module, package)]
    assert not found, "private names of other modules:\n  " + "\n  ".join(found)


def test_the_data_of_assur_imports_no_behaviour() -> None:
    """The chain and the kinds are data: the code that uses them imports them, never the
    reverse (their sentences come from the text catalogue, their errors from ``errors``)."""
    graph = import_graph(modules_of("assur"))
    assert set(graph.successors("assur.kinds")) == {"assur.text"}
    assert set(graph.successors("assur.model")) == {"assur.errors"}


# ------------------------------------------------------------- the reading of the source


def _write(root: Path, files: dict[str, str]) -> dict[str, Module]:
    for name, text in files.items():
        path = root / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
    return modules_of("assur", root)


def test_imports_in_functions_and_relative_imports_count(tmp_path: Path) -> None:
    modules = _write(tmp_path, {
        "assur/__init__.py": "from assur.a import f\n",
        "assur/a.py": "def f():\n    from .sub import b\n    return b\n",
        "assur/sub/__init__.py": "",
        "assur/sub/b.py": "from typing import TYPE_CHECKING\n"
                          "if TYPE_CHECKING:\n    from assur import a\n"
                          "else:\n    from .. import c\n",
        "assur/c.py": "import assur.sub\nfrom assur import a as first\n",
    })
    graph = import_graph(modules)
    assert set(graph.edges) == {("assur", "assur.a"), ("assur.a", "assur.sub.b"),
                                ("assur.a", "assur.sub"),
                                ("assur.sub.b", "assur.c"), ("assur.c", "assur.sub"),
                                ("assur.c", "assur.a")}
    assert nx.find_cycle(graph) is not None


def test_a_package_on_the_way_is_imported_unless_it_holds_the_importer(tmp_path: Path) -> None:
    modules = _write(tmp_path, {
        "assur/__init__.py": "from assur import model\n",
        "assur/model.py": "from assur.forces.data import Mass\n",
        "assur/forces/__init__.py": "from assur.forces.table import read\n",
        "assur/forces/data.py": "Mass = 1\n",
        "assur/forces/table.py": "from assur.forces import data\nfrom assur.model import Chain\n",
    })
    graph = import_graph(modules)
    assert set(graph.edges) == {
        ("assur", "assur.model"), ("assur.model", "assur.forces.data"),
        ("assur.model", "assur.forces"), ("assur.forces", "assur.forces.table"),
        ("assur.forces.table", "assur.forces.data"), ("assur.forces.table", "assur.model")}
    assert knots(graph) == [["assur.forces imports assur.forces.table (line 1)",
                             "assur.forces.table imports assur.model (line 2)",
                             "assur.model imports assur.forces (line 1)"]]


def test_the_guarded_import_makes_no_edge(tmp_path: Path) -> None:
    modules = _write(tmp_path, {
        "assur/__init__.py": "",
        "assur/a.py": "import assur.b\n",
        "assur/b.py": "import typing\nif typing.TYPE_CHECKING:\n    import assur.a\n",
    })
    assert set(import_graph(modules).edges) == {("assur.a", "assur.b")}


def test_string_imports_and_private_names_are_found(tmp_path: Path) -> None:
    modules = _write(tmp_path, {
        "assur/__init__.py": "",
        "assur/_fast.py": "_K = 1\n",
        "assur/a.py": "import importlib\nimport assur.b as bee\nfrom assur import _fast\n"
                      "def f(name):\n"
                      "    importlib.import_module('yaml')\n"
                      "    importlib.import_module('assur.b')\n"
                      "    importlib.import_module(f'assur.{name}')\n"
                      "    __import__(name)\n"
                      "    return bee._hidden, _fast._K\n",
        "assur/b.py": "from assur.a import _g\n_hidden = 1\n",
    })
    hidden = [f.what for module in modules.values() for f in string_imports(module)]
    assert hidden == ["import_module('assur.b')", "import_module(f'assur.{name}')",
                      "__import__(name)"]
    private = [str(f) for module in modules.values() for f in private_names(module, modules)]
    assert private == ["assur.a:9: bee._hidden", "assur.a:9: _fast._K",
                       "assur.b:1: from assur.a import _g"]

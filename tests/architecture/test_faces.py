"""The engine's public faces say what is public, and the rest of the code goes through them (issue 40 item 2).

A face is a package's ``__init__``. Three checks:

1. each face exports exactly the names its docstring lists: ``__all__`` equals the names of the docstring's
   "Exports" section (a bullet's names are the ````name```` literals before its description's colon);
2. each name a subpackage face exports is used outside its package: imported (from the face or by module path) or
   read as an attribute of the face by app/, bench/, scripts/, examples/, the Python examples of README.md and docs/,
   another engine package, or the top face ``engine`` (which re-exports from the faces). The top face is the
   library's documented API (README: "the public names are listed in engine/__init__.py"): its names are exempt
   from use, but each must be one of its own modules' names (``engine.case``, ``engine.errors``, ...) or a subpackage
   face's export, so that the top face is composed from the faces;
3. app/, bench/, scripts/, examples/ and the docs' examples import the engine only through faces (an AST scan),
   except the imports listed in :data:`INTERNALS`, each with its reason;
4. no face exports a name that two of its package's modules define (the face would bind one of them).

On the code before this change each failed: no face's docstring had an "Exports" list; ``engine.models`` exported
130 names, ``TOL``, ``HALF_PI`` and ``ARRAY`` among the 110 nobody outside the package used; 91 of the 179 import
statements of app/, bench/, scripts/ and examples/ reached below a face; ``engine.models`` exported ``solve`` (three
modules define one), ``engine.road`` ``GOVERNED_BY`` (two).
"""

from __future__ import annotations

import ast
import functools
import importlib
import re
from collections import defaultdict

import pytest

from tests.architecture.engine_imports import (
    CALLERS,
    FACES,
    ROOT,
    below_face,
    doc_files,
    face_of,
    imports,
    python_files,
)

#: imports below a face that are allowed, (file, module) -> why: benches that time a model's internal stages
INTERNALS = {
    ("bench/bench_engine.py", "engine.models.trailer3d"): "times the 3D model's stages (geometry, closures, iteration)",
    ("bench/bench_engine.py", "engine.models.trailer3d_davies"): "times the Davies reference path against the fast one",
    ("bench/bench_combination.py", "engine.models.combination"): "clears the roll model's private cache between runs",
    ("bench/bench_combination.py", "engine.models.roll_tree"): "times the solve of the roll equations on their tree",
}

_BULLET = re.compile(r"^\s*[-*] (.*?)(?=^\s*[-*] |^\s*$|\Z)", re.M | re.S)
_LITERAL = re.compile(r"``(\w+)``")


def listed(face: str) -> list[str]:
    """The names the face's docstring lists in its "Exports" section, in order, repeats kept."""
    doc = importlib.import_module(face).__doc__ or ""
    _, found, section = doc.partition("\nExports (")
    if not found:
        return []
    names = []
    for bullet in _BULLET.finditer(section):
        # "``a``, ``b``: what they are; ``c``: what it is" -> a, b, c
        for clause in " ".join(bullet.group(1).split()).split("; "):
            head, colon, _ = clause.partition(": ")
            if colon:
                names += _LITERAL.findall(head)
    return names


def _package(path: str) -> str | None:
    """The engine face whose package holds the file (None outside the engine)."""
    if not path.startswith("engine/"):
        return None
    module = path.removesuffix(".py").removesuffix("/__init__").replace("/", ".")
    return face_of(module)


@functools.cache
def uses() -> dict[str, dict[str, set[str]]]:
    """face -> exported name -> the files outside its package that use it."""
    files = python_files(*CALLERS, "engine") + doc_files()
    found: dict[str, dict[str, set[str]]] = defaultdict(lambda: defaultdict(set))
    for imp in imports(files):
        face = face_of(imp.module)
        if imp.name is None or _package(imp.path) == face:
            continue
        if imp.module in FACES and f"{imp.module}.{imp.name}" in FACES:  # ``from engine import road``: see below
            continue
        found[face][imp.name].add(imp.path)
    # a face bound to a name (``from engine import road as adv``) and read as an attribute (``adv.TREATMENTS``)
    for path in python_files(*CALLERS):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        aliases = {}
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom) and node.module in FACES and not node.level:
                for alias in node.names:
                    if f"{node.module}.{alias.name}" in FACES:
                        aliases[alias.asname or alias.name] = f"{node.module}.{alias.name}"
        for node in ast.walk(tree):
            if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id in aliases:
                found[aliases[node.value.id]][node.attr].add(path.relative_to(ROOT).as_posix())
    return found


@pytest.mark.parametrize("face", FACES)
def test_a_face_exports_exactly_the_names_its_docstring_lists(face):
    module = importlib.import_module(face)
    exported = list(getattr(module, "__all__", ()))
    names = listed(face)
    assert names, f"{face}'s docstring has no 'Exports (...)' list of its names"
    assert len(set(names)) == len(names), f"{face}'s docstring lists a name twice"
    assert len(set(exported)) == len(exported), f"{face}.__all__ holds a name twice"
    assert set(exported) == set(names), (
        f"{face}: exported, not listed: {sorted(set(exported) - set(names))}; "
        f"listed, not exported: {sorted(set(names) - set(exported))}"
    )
    missing = [n for n in exported if not hasattr(module, n)]
    assert not missing, f"{face}.__all__ names what the face does not bind: {missing}"


@pytest.mark.parametrize("face", [f for f in FACES if f != "engine"])
def test_every_name_a_subpackage_face_exports_is_used_outside_its_package(face):
    used = uses()[face]
    unused = sorted(n for n in importlib.import_module(face).__all__ if not used.get(n))
    assert not unused, f"{face} exports names nothing outside its package uses (drop them from the face): {unused}"


@pytest.mark.parametrize("face", [f for f in FACES if f != "engine"])
def test_no_face_exports_a_name_two_of_its_modules_define(face):
    """A name two modules of a package define (each its own ``GOVERNED_BY``) is ambiguous on the face: the face binds
    one, and a caller that took the other from its module would silently get the wrong one through the face."""
    package = ROOT / face.replace(".", "/")
    homes: dict[str, list[str]] = defaultdict(list)
    for path in sorted(package.glob("*.py")):
        if path.name == "__init__.py":
            continue
        for node in ast.parse(path.read_text(encoding="utf-8")).body:
            if isinstance(node, ast.FunctionDef | ast.ClassDef):
                names = [node.name]
            elif isinstance(node, ast.Assign):
                names = [t.id for t in node.targets if isinstance(t, ast.Name)]
            elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
                names = [node.target.id]
            else:
                continue
            for name in names:
                homes[name].append(path.stem)
    exported = importlib.import_module(face).__all__
    twice = {n: homes[n] for n in exported if len(set(homes[n])) > 1}
    assert not twice, f"{face} exports names defined in more than one of its modules: {twice}"


#: the engine's own modules (not subpackages) whose names the top face re-exports
TOP_MODULES = ("engine.case", "engine.domain", "engine.errors", "engine.results")


def test_the_top_face_is_composed_from_its_own_modules_and_the_faces():
    engine = importlib.import_module("engine")
    sources = [importlib.import_module(m) for m in (*FACES[1:], *TOP_MODULES)]
    stray = [
        name
        for name in engine.__all__
        if name != "ENGINE_VERSION"  # defined by the top face itself
        and not any(getattr(source, name, None) is getattr(engine, name) for source in sources)
    ]
    assert not stray, f"the top face re-exports names that neither a face nor its own modules hold: {stray}"
    from_faces = {n for n in engine.__all__ for face in sources[: len(FACES) - 1] if n in face.__all__}
    assert from_faces, "the top face re-exports nothing of the faces"


def _target(imp) -> tuple[str, str]:
    """(file, the module the import reaches): a face's submodule counts as that submodule."""
    return imp.path, f"{imp.module}.{imp.name}" if imp.module in FACES else imp.module


def test_callers_import_the_engine_only_through_its_faces():
    below = [
        f"{imp.path}:{imp.line}: from {imp.module} import {imp.name}"
        for imp in imports(python_files(*CALLERS) + doc_files())
        if below_face(imp)
        and (imp.path, f"{imp.module}.{imp.name}" if imp.module in FACES else imp.module) not in INTERNALS
    ]
    assert not below, "imports below an engine face (import from the face instead):\n" + "\n".join(below)


def test_the_allowed_internal_imports_are_still_there():
    """An exception no longer needed is removed, not left to excuse a new one."""
    found = {_target(imp) for imp in imports(python_files(*CALLERS)) if below_face(imp)}
    assert set(INTERNALS) <= found, sorted(set(INTERNALS) - found)

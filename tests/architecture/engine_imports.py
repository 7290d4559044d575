"""Every import of the engine in the repository, read from the source (AST), and the engine's package faces.

A *face* is a package's ``__init__``: what it re-exports (its ``__all__``) is what the rest of the code may use of it.
:func:`imports` yields each ``from engine... import name`` and ``import engine...`` of the files given (relative imports
resolved; imports inside functions included); Markdown files contribute their Python code blocks (the docs' examples
are callers too). :func:`below_face` tells an import that reaches past a face: from a module that is not a face
(``engine.models.trailer3d``), or of a face's submodule (``from engine.builder import combination``).
"""

from __future__ import annotations

import ast
import importlib
import importlib.util
import inspect
import re
from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

#: the engine's faces: the top package (the library's documented API) and each subpackage's ``__init__``
FACES = (
    "engine",
    "engine.mechanics",
    "engine.vehicle",
    "engine.models",
    "engine.builder",
    "engine.road",
    "engine.route",
    "engine.dynamics",
)

#: code that must reach the engine through its faces (tests may import internals by their module path)
CALLERS = ("app", "bench", "scripts", "examples")

_CODE_BLOCK = re.compile(r"^```python\n(.*?)^```", re.M | re.S)


@dataclass(frozen=True)
class Import:
    path: str  # relative to the repository root
    line: int
    module: str  # absolute: ``engine.models.threshold``
    name: str | None  # the imported name (``from module import name``); None for ``import module``


def _module_name(path: Path) -> list[str]:
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    return parts[:-1] if parts[-1] == "__init__" else parts


def _parse(path: Path) -> Iterator[tuple[ast.AST, int]]:
    """The syntax trees of a file: a Python file's, or each Python code block of a Markdown file (with its first
    line's number, so a finding names the line)."""
    text = path.read_text(encoding="utf-8")
    if path.suffix == ".py":
        yield ast.parse(text, filename=str(path)), 0
        return
    for block in _CODE_BLOCK.finditer(text):
        try:
            yield ast.parse(block.group(1)), text.count("\n", 0, block.start(1))
        except SyntaxError:  # a session transcript or a fragment, not a program
            continue


def imports(files: Iterable[Path]) -> Iterator[Import]:
    """Each import of ``engine`` (or below it) in the files."""
    for path in files:
        rel = path.relative_to(ROOT).as_posix()
        package = _module_name(path) if path.name == "__init__.py" else _module_name(path)[:-1]
        for tree, offset in _parse(path):
            for node in ast.walk(tree):
                if isinstance(node, ast.ImportFrom):
                    module = node.module or ""
                    if node.level:  # relative: from the file's package, one level up per extra dot
                        base = package[: len(package) - (node.level - 1)]
                        module = ".".join([*base, module] if module else base)
                    if module == "engine" or module.startswith("engine."):
                        for alias in node.names:
                            yield Import(rel, offset + node.lineno, module, alias.name)
                elif isinstance(node, ast.Import):
                    for alias in node.names:
                        if alias.name == "engine" or alias.name.startswith("engine."):
                            yield Import(rel, offset + node.lineno, alias.name, None)


def face_of(module: str) -> str:
    """The innermost face whose package holds the module."""
    return max((f for f in FACES if module == f or module.startswith(f + ".")), key=len)


def below_face(imp: Import) -> bool:
    """Whether the import reaches past a face: its module is not a face, or it imports a face's submodule that is not
    itself a face (``from engine.models import threshold``)."""
    if imp.module not in FACES:
        return True
    if imp.name is None or f"{imp.module}.{imp.name}" in FACES:
        return False
    # the name as the face binds it: ``engine.road.min_radius`` is the function the face re-exports, not its module
    bound = getattr(importlib.import_module(imp.module), imp.name, None)
    if bound is None:  # a submodule not imported yet
        return importlib.util.find_spec(f"{imp.module}.{imp.name}") is not None
    return inspect.ismodule(bound)


def python_files(*tops: str) -> list[Path]:
    """The Python files under the given top-level directories of the repository."""
    return sorted(p for top in tops for p in (ROOT / top).rglob("*.py") if "__pycache__" not in p.parts)


def doc_files() -> list[Path]:
    """The Markdown documents whose Python examples are callers of the engine: the README and docs/."""
    return [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]

"""Sphinx configuration of the API reference built from the docstrings (scripts/build_api_reference.py).

Nitpicky: every cross-reference in a docstring (``:mod:``, ``:func:``, ``:class:``, ``:data:``, ...) must name a
module or object of ``engine`` or ``app`` that exists, or the build fails. A name a package re-exports
(``engine.vehicle.Vehicle``, defined in ``engine.vehicle.record``) is a good reference: it resolves to where the
object is defined. References into other libraries are not checked (no network: no intersphinx inventories).
"""

from __future__ import annotations

import importlib
import inspect
import re

project = "rollover"
extensions = ["sphinx.ext.autodoc"]

nitpicky = True
# objects of other libraries (numpy, pydantic, fastapi, the standard library) named in the docstrings: not checked
nitpick_ignore_regex = [(r"py:.*", r"(?!engine\b|app\b)[A-Za-z_][\w.]*")]
# the numpydoc "References" sections define their citations whether or not the text cites each one
suppress_warnings = ["ref.footnote"]

# every member, documented or not, private too: a docstring may refer to any of them. The package faces' __all__
# is not followed: each object is documented once, where it is defined
autodoc_default_options = {"members": True, "undoc-members": True, "private-members": True, "ignore-module-all": True}
autodoc_member_order = "bysource"
# signatures without their annotations: the docstrings name units and types; other libraries' types in the
# annotations would only be references this build does not check
autodoc_typehints = "none"

_SECTION = re.compile(r"^\s*-{3,}\s*$")


_ENTRY = re.compile(r"^(\s*)([A-Za-z_*][\w, .*]*?) : (.*)$")


def _indent(line: str) -> int:
    return len(line) - len(line.lstrip())


def _entries(block: list[str]) -> list[str] | None:
    """A block of numpydoc entries (``name : text``, continuation lines indented further) as a definition list
    (``name``, then the text and its continuation indented under it); None when the block is not one."""
    base = _indent(block[0])
    out = []
    for line in block:
        if _indent(line) > base:
            out.append(line)
            continue
        m = _ENTRY.match(line)
        if m is None or _indent(line) != base:
            return None
        out += [f"{m.group(1)}{m.group(2)}", f"{m.group(1)}    {m.group(3)}"]
    return out


def _numpydoc_sections(app, what, name, obj, options, lines: list[str]) -> None:
    """numpydoc as plain reST: ``|`` as text (the docstrings' absolute values and norms), section titles (``Parameters``
    over a line of dashes) as rubrics (a docstring may not hold section titles), and a block of entries (``name : text
    [unit]``) a definition list whose text is text, never looked up as a type (the project's entries put the description
    where numpydoc puts a type)."""
    for i, line in enumerate(lines):  # |x| is an absolute value or a norm here, never a reST substitution
        if "|" in line and not line.lstrip().startswith(("|", "+")):
            lines[i] = line.replace("|", "\\|")
    for i in range(len(lines) - 1):
        if _SECTION.match(lines[i + 1]) and lines[i].strip() and len(lines[i + 1].strip()) >= len(lines[i].strip()):
            lines[i], lines[i + 1] = f"{' ' * _indent(lines[i])}.. rubric:: {lines[i].strip()}", ""
    out, block = [], []
    for line in [*lines, ""]:
        if line.strip():
            block.append(line)
            continue
        if block:
            out += _entries(block) or block
            block = []
        out.append(line)
    lines[:] = out[:-1]


def _target(name: str):
    """The object a dotted name imports to (a module, or an attribute of one), or None."""
    parts = name.split(".")
    for i in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:i]))
        except ImportError:
            continue
        for p in parts[i:]:
            if not hasattr(obj, p):
                return None
            obj = getattr(obj, p)
        return obj
    return None


def _reexported(app, env, node, contnode):
    """A reference to a name of ``engine`` or ``app`` that exists but is not documented under that name (a package
    face's re-export, a module constant): linked to where the object is defined when that is documented, else left
    as text. A name that does not import stays missing, and nitpicky reports it."""
    if node.get("refdomain") != "py":
        return None
    target = node.get("reftarget", "")
    module = node.get("py:module") or ""
    candidates = [target] if target.startswith(("engine.", "app.")) or target in ("engine", "app") else []
    if module and not candidates:
        candidates = [f"{module}.{target}"]
    for name in candidates:
        obj = _target(name)
        if obj is None:
            continue
        domain = env.get_domain("py")
        defined = getattr(obj, "__module__", None), getattr(obj, "__qualname__", None)
        if all(defined) and isinstance(defined[0], str) and isinstance(defined[1], str):
            canonical = f"{defined[0]}.{defined[1]}"
            node["reftarget"] = canonical
            found = domain.resolve_any_xref(env, node["refdoc"], app.builder, canonical, node, contnode)
            if found:
                return found[0][1]
        return contnode
    return None


def _skip_aliases(app, what, name, obj, skip, options):
    """A module-level name bound to a class defined under another name (``VehicleSpecIn = MODELS["VehicleSpec"]``)
    is not documented again: the class is, where it is defined (a reference to the alias still resolves there).
    Nor is an attribute whose only doc is another library's class docstring."""
    if isinstance(obj, type) and getattr(obj, "__name__", name) != name.rsplit(".", 1)[-1]:
        return True
    if not callable(obj) and _foreign(type(obj)) and inspect.getdoc(obj) == inspect.getdoc(type(obj)):
        return True  # an instance of another library's class (SQLAlchemy's MetaData): its doc would be theirs
    return None


def _foreign(cls: type) -> bool:
    return not str(getattr(cls, "__module__", "")).startswith(("engine", "app", "builtins"))


def setup(app):
    app.connect("autodoc-process-docstring", _numpydoc_sections)
    app.connect("autodoc-skip-member", _skip_aliases)
    app.connect("missing-reference", _reexported)

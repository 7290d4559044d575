"""Build the API reference of ``engine`` and ``app`` from their docstrings with Sphinx (autodoc, napoleon), nitpicky:
a docstring's cross-reference to a module or object that does not exist fails the build.

    python scripts/build_api_reference.py                   # check (the dummy builder: no output written)
    python scripts/build_api_reference.py --html build/api  # the reference as HTML

One page per module (every module of both packages, found by walking them), written to a temporary source directory
beside ``docs/reference/conf.py``; warnings are errors (``-W --keep-going``: every one is listed). Exit status 0
when the reference builds without a warning.
"""

from __future__ import annotations

import argparse
import importlib.util
import pkgutil
import shutil
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("engine", "app")
#: modules that are not part of the reference: the database migrations (Alembic scripts run by the migrator); the
#: compiled modules (app.formats._rowwriter, app.formats._xsectscan) are left out too: their docstrings are C strings
SKIP_PREFIXES = ("app.db.migrations",)


def modules() -> list[str]:
    """Every module and package of :data:`PACKAGES`, sorted."""
    sys.path.insert(0, str(ROOT))
    found = []
    for name in PACKAGES:
        package = __import__(name)
        found.append(name)
        for info in pkgutil.walk_packages(package.__path__, prefix=f"{name}."):
            if info.name.startswith(SKIP_PREFIXES) or info.name.rsplit(".", 1)[-1].startswith("__"):
                continue
            spec = importlib.util.find_spec(info.name)
            if spec is not None and str(spec.origin).endswith(".py"):  # a compiled module's docstrings are C's
                found.append(info.name)
    return sorted(found)


def write_sources(src: Path, names: list[str]) -> None:
    shutil.copy(ROOT / "docs" / "reference" / "conf.py", src / "conf.py")
    toc = "\n".join(f"   {n}" for n in names)
    (src / "index.rst").write_text(f"API reference\n=============\n\n.. toctree::\n   :maxdepth: 1\n\n{toc}\n")
    for n in names:
        title = f"``{n}``"
        (src / f"{n}.rst").write_text(f"{title}\n{'=' * len(title)}\n\n.. automodule:: {n}\n")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--html", type=Path, help="write the reference as HTML here (default: check only)")
    args = parser.parse_args(argv)
    from sphinx.cmd.build import build_main

    with tempfile.TemporaryDirectory() as tmp:
        src, out = Path(tmp) / "src", Path(tmp) / "out"
        src.mkdir()
        write_sources(src, modules())
        builder, target = ("html", args.html) if args.html else ("dummy", out)
        return build_main(["-b", builder, "-n", "-W", "--keep-going", "-q", "-E", str(src), str(target)])


if __name__ == "__main__":
    sys.exit(main())

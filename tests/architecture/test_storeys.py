"""The storeys' import contracts hold (issue 40, "How good").

``pyproject.toml`` ``[tool.importlinter]`` states them: the engine never imports the service; inside the engine a
package imports only the storeys below it (errors < domain, bracket < vehicle, mechanics < case, results < models <
builder, road, dynamics < route); inside the service the features sit above the shared machinery and import each other
only downwards. The check is Import Linter's own (``lint-imports``), run here so that the suite is the CI gate; its
report is the failure message.

Before the builder moved to ``engine.builder`` (it lived in ``engine.vehicle.builder`` and imported the models, which
import the vehicle package), the engine's contract was broken: ``engine.vehicle is not allowed to import
engine.models: engine.vehicle.builder.build -> engine.models.registry``.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import importlinter  # noqa: F401  (in the locked test set: a missing linter fails, never skips)
import pytest

from tests.architecture.engine_imports import ROOT

CHECK = "import sys\nfrom importlinter.cli import lint_imports\nsys.exit(lint_imports(no_cache=True, no_logo=True))\n"


def _lint(root: Path) -> subprocess.CompletedProcess:
    """``lint-imports`` on the packages and the configuration under ``root`` (its packages imported from there)."""
    env = {**os.environ, "PYTHONPATH": str(root)}
    return subprocess.run(
        [sys.executable, "-c", CHECK], cwd=root, env=env, capture_output=True, text=True, timeout=600, check=False
    )


def test_every_import_contract_is_kept():
    run = _lint(ROOT)
    assert run.returncode == 0, run.stdout + run.stderr
    # all three contracts ran (one dropped from the configuration would not fail the run)
    assert "3 kept, 0 broken" in run.stdout, run.stdout


@pytest.mark.parametrize(
    ("module", "line", "broken"),
    [
        # the engine reaching for the service
        ("engine/road/curves.py", "import app.settings", "The engine never imports the service"),
        # the cycle the builder's move removed: a vehicle module using the models
        ("engine/vehicle/record.py", "import engine.models.threshold", "The engine's storeys"),
        # a shared module using a feature, and a feature using one above it
        ("app/http/problems.py", "import app.srt.schemas", "The service's storeys"),
        ("app/srt/schemas.py", "import app.alignments.schemas", "The service's storeys"),
    ],
)
def test_a_planted_import_across_a_storey_breaks_its_contract(tmp_path, module, line, broken):
    """The contracts are not lenient: a copy of the packages with one upward import fails the named contract."""
    for package in ("engine", "app"):
        shutil.copytree(ROOT / package, tmp_path / package, ignore=shutil.ignore_patterns("__pycache__", "*.so"))
    shutil.copy(ROOT / "pyproject.toml", tmp_path / "pyproject.toml")
    target = tmp_path / module
    target.write_text(target.read_text(encoding="utf-8") + f"\n{line}  # planted\n", encoding="utf-8")
    run = _lint(tmp_path)
    assert run.returncode != 0, run.stdout
    assert f"{broken}" in run.stdout.split("Broken contracts")[-1], run.stdout

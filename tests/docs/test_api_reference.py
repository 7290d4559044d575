"""The API reference builds from the docstrings with every cross-reference resolved (issue 40 item 3).

scripts/build_api_reference.py runs Sphinx (autodoc, nitpicky, warnings as errors) over every module of ``engine``
and ``app``. Before this, 35 docstring references named modules that no longer exist (``engine.assessment``,
``engine.standards``, ``engine.vehicles``, ``engine.builder``, ...) and nothing noticed. The second test shows the
build is not lenient: a reference to a module that does not exist fails it, while one to a name a package face
re-exports (``engine.vehicle.Vehicle``, defined in ``engine.vehicle.record``) does not.
"""

from __future__ import annotations

import importlib.util
import sys
import textwrap
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

pytestmark = pytest.mark.slow


def _script():
    spec = importlib.util.spec_from_file_location("build_api_reference", ROOT / "scripts" / "build_api_reference.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_reference_of_every_module_builds_without_a_warning():
    pytest.importorskip("sphinx")
    script = _script()
    names = script.modules()
    assert {"engine.road.standards", "engine.vehicle.record", "app.jobs.router", "app.http.strictjson"} <= set(names)
    assert script.main([]) == 0


@pytest.mark.parametrize(
    ("reference", "fails"),
    [
        (":func:`engine.standards.min_radius_m`", True),  # a module that was removed
        (":mod:`engine.vehicles`", True),
        (":class:`engine.vehicle.NoSuchThing`", True),  # a face without that name
        (":class:`engine.vehicle.Vehicle`", False),  # re-exported by the face, defined in engine.vehicle.record
        (":func:`engine.road.min_radius.min_radius_m`", False),
        (":class:`numpy.ndarray`", False),  # another library's: not checked
    ],
)
def test_a_broken_reference_fails_the_build(tmp_path, monkeypatch, reference, fails):
    pytest.importorskip("sphinx")
    from sphinx.cmd.build import build_main

    package = tmp_path / "pkg"
    package.mkdir()
    (package / "probe_refs.py").write_text(f'"""A docstring that names {reference}."""\n')
    monkeypatch.syspath_prepend(str(package))
    src = tmp_path / "src"
    src.mkdir()
    (src / "conf.py").write_text((ROOT / "docs" / "reference" / "conf.py").read_text())
    (src / "index.rst").write_text(textwrap.dedent("Probe\n=====\n\n.. automodule:: probe_refs\n"))
    status = build_main(["-b", "dummy", "-n", "-W", "-q", "-E", str(src), str(tmp_path / "out")])
    sys.modules.pop("probe_refs", None)
    assert (status != 0) is fails, reference

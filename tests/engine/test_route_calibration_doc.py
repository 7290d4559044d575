"""docs/routes.md's calibration tables (white and correlated noise) are what bench/route_accuracy.py renders from its
last ``--write`` run's stored figures (bench/route_calibration.json), so the doc cannot drift from the run by
hand-copying. The bench itself is not run here (it takes a minute or two): ``python bench/route_accuracy.py --write``
refreshes both."""

from __future__ import annotations

import importlib.util
import json
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
BENCH = ROOT / "bench" / "route_accuracy.py"


def bench_module():
    spec = importlib.util.spec_from_file_location("route_accuracy", BENCH)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_doc_table_is_the_rendering_of_the_stored_figures():
    bench = bench_module()
    doc = bench.DOC.read_text(encoding="utf-8")
    figures = json.loads(bench.FIGURES.read_text(encoding="utf-8"))
    for (start, end), render in (
        ((bench.START, bench.END), bench.render_table),
        ((bench.CORR_START, bench.CORR_END), bench.render_correlated),
    ):
        assert doc.count(start) == 1 and doc.count(end) == 1
        block = doc.split(start, 1)[1].split(end, 1)[0]
        assert block == "\n" + render(figures) + "\n"


def test_the_stored_figures_hold_every_cell_with_its_columns():
    bench = bench_module()
    figures = json.loads(bench.FIGURES.read_text(encoding="utf-8"))
    cells = figures["cells"]
    simple = {(c["radius_m"], c["deflection_deg"], c["sigma_m"]) for c in cells if c["kind"] == "simple"}
    spiralled = {(c["radius_m"], c["arc_m"], c["spiral_m"], c["sigma_m"]) for c in cells if c["kind"] == "spiralled"}
    assert simple == {(r, d, s) for r in bench.CAL_RADII for d in bench.CAL_DEFLECTIONS for s in bench.CAL_NOISE}
    assert spiralled == {(*geometry, s) for geometry in bench.SPIRALLED for s in bench.CAL_NOISE}
    correlated = {(c["radius_m"], c["deflection_deg"], c["sigma_m"], c["corr_m"]) for c in figures["correlated"]}
    assert correlated == {
        (r, d, s, bench.CORRELATED_M)
        for r in bench.CAL_RADII
        for d in bench.CAL_DEFLECTIONS
        for s in bench.CORRELATED_NOISE
    }
    for c in cells + figures["correlated"]:
        assert c["tracks"] == figures["tracks"] and 0 <= c["covered"] <= c["found"] <= c["tracks"]
        if c["found"] >= 3:  # coverage, stated/observed, mean bias, lower / true radius
            assert {"coverage", "ratio", "bias", "lower", "observed", "stated", "sd_z"} <= set(c)
            assert c["coverage"] == c["covered"] / c["found"]

"""The combination presets: valid, every value sourced, the thesis's trailers unchanged inside them."""

from __future__ import annotations

import dataclasses
import math

import pytest

from engine import Case, get_preset, rollover_threshold
from engine.models.combination import rigid_srt, solve_combination
from engine.vehicle.combination import G_M_PER_S2, roll_coupled_units, validate_combination
from engine.vehicle.combination_presets import COMBINATION_INFO, COMBINATION_SOURCES, COMBINATIONS, get_combination

IDS = ["tractor-semitrailer-table15", "btrain-table16", "adouble", "truck-trailer"]  # ../shared/DESIGN.md


def test_the_contract_ids_are_there():
    assert set(IDS) == set(COMBINATIONS) == set(COMBINATION_INFO) == set(COMBINATION_SOURCES)


def _numeric_paths(obj, path):
    if dataclasses.is_dataclass(obj):
        for f in dataclasses.fields(obj):
            if f.name in ("id", "title", "steer", "last_unit_record"):
                continue
            yield from _numeric_paths(getattr(obj, f.name), f"{path}.{f.name}")
    elif isinstance(obj, tuple):
        for i, v in enumerate(obj):
            yield from _numeric_paths(v, f"{path}[{i}]")
    elif isinstance(obj, int | float) and not isinstance(obj, bool):
        yield path


@pytest.mark.parametrize("cid", IDS)
def test_every_value_of_a_preset_names_its_source(cid):
    c = get_combination(cid)
    validate_combination(c)
    sources = COMBINATION_SOURCES[cid]
    paths = [p for p in _numeric_paths(c, "combination") if not p.endswith("front_llt_ratio")]
    missing = [p for p in paths if p not in sources]
    assert not missing, missing
    assert all(s.strip() for s in sources.values())


@pytest.mark.parametrize(("cid", "table"), [("tractor-semitrailer-table15", "table15-semitrailer"),
                                            ("btrain-table16", "table16-btrain")])  # fmt: skip
def test_the_thesis_trailer_keeps_its_weight_and_cg(cid, table):
    c, v = get_combination(cid), get_preset(table)
    last = c.last_unit
    g = last.groups[0]
    unsprung = g.axles * g.unsprung_mass_kg
    total = last.sprung_mass_kg + unsprung
    assert total * G_M_PER_S2 / 1000 == pytest.approx(v.weight_kn, rel=1e-12)  # W of the table
    h = (last.sprung_mass_kg * last.cg_height_m + unsprung * g.unsprung_cg_height_m) / total
    x = (last.sprung_mass_kg * last.cg_position_m + unsprung * g.position_m) / total
    assert h == pytest.approx(v.rolling_radius_m + v.suspension_height_m + v.cg_height_above_chassis_m, rel=1e-12)
    assert x == pytest.approx(v.front_axle_to_cg_m, rel=1e-12)
    assert g.roll_stiffness_knm_per_rad == pytest.approx(v.suspension_stiffness_kn_per_m * v.spring_separation_m**2 / 2)


@pytest.mark.parametrize(("cid", "table"), [("tractor-semitrailer-table15", "table15-semitrailer"),
                                            ("btrain-table16", "table16-btrain")])  # fmt: skip
def test_the_3d_model_of_the_last_unit_with_the_tables_ratio_is_the_thesis_model(cid, table):
    v = get_preset(table)
    c = dataclasses.replace(get_combination(cid), front_llt_ratio=v.front_llt_ratio)
    assert rollover_threshold(Case(c, model="3d")).srt == rollover_threshold(Case(v)).srt  # the explicit override
    computed = rollover_threshold(Case(get_combination(cid), model="3d"))
    ratio = solve_combination(get_combination(cid)).last_unit_front_llt_ratio
    assert computed.notes[0].startswith(f"front_llt_ratio = {ratio:.4f}")
    assert computed.srt == rollover_threshold(Case(v.replace(front_llt_ratio=ratio))).srt


@pytest.mark.parametrize("cid", IDS)
def test_each_roll_coupled_unit_holds_less_than_its_rigid_limit(cid):
    c = get_combination(cid)
    detail = solve_combination(c)
    assert len(detail.roll_coupled_units) == len(roll_coupled_units(c))
    for r, rigid in zip(detail.roll_coupled_units, rigid_srt(c), strict=True):
        assert 0.2 < r.srt < rigid
        assert r.lift_sequence and all(0 < e.ay_g <= r.srt + 1e-12 for e in r.lift_sequence)
        assert math.isclose(r.srt, max(e.ay_g for e in r.lift_sequence)) or r.limit != "rollover"
    assert detail.governing == min(
        range(len(detail.roll_coupled_units)), key=lambda k: detail.roll_coupled_units[k].srt
    )


def test_the_presets_table_of_docs_combinations_is_what_the_engine_computes():
    """docs/combinations.md's table is printed by scripts/combination_table.py: a model or preset change that moves
    a figure fails here until the doc is regenerated (python scripts/combination_table.py --write)."""
    import subprocess
    import sys
    from pathlib import Path

    root = Path(__file__).resolve().parents[2]
    done = subprocess.run(
        [sys.executable, str(root / "scripts" / "combination_table.py")], capture_output=True, text=True, cwd=root
    )
    assert done.returncode == 0, done.stderr[-2000:]
    doc = (root / "docs" / "combinations.md").read_text(encoding="utf-8")
    assert done.stdout.strip() in doc

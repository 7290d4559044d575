"""SRT targets are judged on the level-road SRT (issue 23 item 1).

The 0.35 g / 0.40 g targets (Australia's PBS scheme, New Zealand's SRT rule) are level-road SRTs. A bank raises the
case's own threshold (``srt``, the curve's, which the curve speed and the rollover radius use) but not the vehicle's
verdict: every response with ``targets`` carries ``level_road_srt`` (the same vehicle, load, model and parameters
with bank and slope zero) and judges each target on it (``judged_on``).

The expected numbers are independent of the verdict code: the level SRT is the ``srt`` of a separate request with
the road left out (or the engine's :func:`engine.models.rollover_threshold` of the level case), and the targets are
the service defaults (0.35 g, 0.40 g).
"""

from __future__ import annotations

import math

import pytest

from app.vehicles.resolve import vehicle_preset
from engine.case import Case
from engine.models import rollover_threshold

BTRAIN = "table16-btrain"  # Table 16 B-train: 0.339 g on a level road (3d, full stage)
COMBINATION = "btrain-table16"  # the same B-train as a whole combination (GET /v1/combinations)
BANK6 = {"bank_percent": 6.0, "slope_percent": 0.0}
DEFAULTS = {"general": 0.35, "dangerous_goods": 0.40}


def post(client, path, body, status=200):
    r = client.post(path, json=body)
    assert r.status_code == status, r.text
    return r.json()


def srt_of(client, body):
    return post(client, "/v1/srt", body)


def assert_judged_on(targets, level):
    """Each target checked against ``level`` (the service defaults, in order of increasing target)."""
    assert [(t["name"], t["target_g"]) for t in targets] == sorted(DEFAULTS.items(), key=lambda kv: kv[1])
    for t in targets:
        assert t["judged_on"] == "level_road_srt"
        assert t["meets"] == (level >= t["target_g"])
        assert t["margin_g"] == level - t["target_g"]


def test_the_issue_btrain_on_a_6_percent_bank_fails_both_targets_on_its_level_srt(shared_client):
    banked = srt_of(shared_client, {"vehicle": BTRAIN, "road": BANK6})
    level = srt_of(shared_client, {"vehicle": BTRAIN})
    # the bank lifts the curve's threshold above both targets...
    assert banked["srt"] > 0.40
    # ...but the verdict is the level road's, the SRT of the same request without the bank
    assert banked["level_road_srt"] == level["srt"] < 0.35
    assert_judged_on(banked["targets"], level["srt"])
    assert [t["meets"] for t in banked["targets"]] == [False, False]
    # the engine's own level case agrees (not through the service's verdict code)
    engine_level = rollover_threshold(Case(vehicle_preset(BTRAIN), "3d")).srt
    assert banked["level_road_srt"] == pytest.approx(engine_level, rel=1e-12)
    # the curve's own threshold stays the case's: the tilt angle is of srt, not of the level SRT
    assert banked["tilt_table_angle_deg"] == pytest.approx(math.degrees(math.atan(banked["srt"])), rel=1e-12)


@pytest.mark.parametrize(
    "body",
    [
        {"vehicle": BTRAIN},
        {"vehicle": BTRAIN, "model": "2d"},
        {"vehicle": BTRAIN, "model": "rigid"},
        {"vehicle": BTRAIN, "model": "rill"},
        {"vehicle": BTRAIN, "stage": "tires-suspension"},
        {"vehicle": COMBINATION},
        {"vehicle": BTRAIN, "load": {"lateral_offset_m": 0.1, "overweight_percent": 10}},
    ],
)
def test_on_a_level_road_level_road_srt_is_srt_exactly(shared_client, body):
    out = srt_of(shared_client, body)
    assert out["level_road_srt"] == out["srt"]
    assert_judged_on(out["targets"], out["srt"])


def test_level_road_srt_keeps_the_load_the_model_and_its_parameters(shared_client):
    load = {"lateral_offset_m": 0.15, "vertical_offset_m": 0.2, "overweight_percent": 10}
    case = {"vehicle": BTRAIN, "rear_llt_limit": 0.8, "trailer_angle_deg": 5.0, "load": load}
    banked = srt_of(shared_client, {**case, "road": {"bank_percent": 8.0, "slope_percent": -4.0}})
    level = srt_of(shared_client, case)
    unloaded = srt_of(shared_client, {"vehicle": BTRAIN})
    assert banked["level_road_srt"] == level["srt"]
    assert level["srt"] < unloaded["srt"]  # the load case is kept: outward d1, raised d3, overweight lower it
    assert_judged_on(banked["targets"], level["srt"])
    # a 2D request keeps its model
    two_d = srt_of(shared_client, {**case, "model": "2d", "trailer_angle_deg": 0.0, "road": BANK6})
    assert two_d["level_road_srt"] == srt_of(shared_client, {**case, "model": "2d", "trailer_angle_deg": 0.0})["srt"]


def test_a_slope_alone_is_not_level_either(shared_client):
    sloped = srt_of(shared_client, {"vehicle": BTRAIN, "road": {"bank_percent": 0.0, "slope_percent": 6.0}})
    level = srt_of(shared_client, {"vehicle": BTRAIN})
    assert sloped["srt"] != level["srt"]
    assert sloped["level_road_srt"] == level["srt"]


def test_the_curve_srt_rises_with_the_bank_and_the_verdict_does_not_move(shared_client):
    outs = [srt_of(shared_client, {"vehicle": BTRAIN, "road": {"bank_percent": e}}) for e in (0, 2, 4, 6, 8)]
    srts = [o["srt"] for o in outs]
    assert srts == sorted(srts) and len(set(srts)) == 5  # strictly rising with the bank
    assert {o["level_road_srt"] for o in outs} == {srts[0]}
    assert {tuple((t["meets"], t["margin_g"]) for t in o["targets"]) for o in outs} == {
        tuple((srts[0] >= g, srts[0] - g) for g in (0.35, 0.40))
    }


def test_the_whole_combination_model_on_a_bank(shared_client):
    banked = srt_of(shared_client, {"vehicle": COMBINATION, "road": BANK6})
    level = srt_of(shared_client, {"vehicle": COMBINATION})
    assert banked["model"] == level["model"] == "combination"
    assert banked["srt"] > 0.40 and level["srt"] < 0.35
    assert banked["level_road_srt"] == level["srt"]
    assert_judged_on(banked["targets"], level["srt"])
    # the governing roll-coupled unit's SRT is the banked one (the curve's), beside the level verdict
    assert banked["srt"] == min(u["srt"] for u in banked["roll_coupled_units"])


def test_a_combination_with_the_3d_model_of_its_last_unit(shared_client):
    banked = srt_of(shared_client, {"vehicle": COMBINATION, "model": "3d", "road": BANK6})
    level = srt_of(shared_client, {"vehicle": COMBINATION, "model": "3d"})
    assert banked["srt"] > level["srt"]
    assert banked["level_road_srt"] == level["srt"]
    assert_judged_on(banked["targets"], level["srt"])


def test_min_radius_uses_the_banked_srt_and_judges_on_the_level_one(shared_client):
    out = post(
        shared_client, "/v1/min-radius", {"vehicle": BTRAIN, "design_speed_kmh": 60.0, "superelevation_percent": 6.0}
    )
    banked = srt_of(shared_client, {"vehicle": BTRAIN, "road": BANK6})
    level = srt_of(shared_client, {"vehicle": BTRAIN})
    assert out["srt"] == banked["srt"] > 0.40
    assert out["rollover_min_radius_m"] == pytest.approx(60.0**2 / (127 * banked["srt"]), rel=1e-12)  # Eq. 9.3
    assert out["level_road_srt"] == out["srt_result"]["level_road_srt"] == level["srt"]
    assert_judged_on(out["srt_result"]["targets"], level["srt"])
    assert [t["meets"] for t in out["srt_result"]["targets"]] == [False, False]


def test_curve_speed_judges_on_the_level_srt_and_a_given_srt_has_none(shared_client):
    out = post(shared_client, "/v1/curve-speed", {"vehicle": BTRAIN, "radius_m": 100.0, "road": BANK6})
    level = srt_of(shared_client, {"vehicle": BTRAIN})
    assert out["max_speed_kmh"] == pytest.approx(math.sqrt(127 * out["srt"] * 100.0), rel=1e-12)  # Eq. 9.1
    assert out["srt"] > out["level_road_srt"] == level["srt"]
    assert_judged_on(out["srt_result"]["targets"], level["srt"])
    given = post(shared_client, "/v1/curve-speed", {"srt": 0.41, "radius_m": 100.0})
    assert given["level_road_srt"] is None and given["srt_result"] is None


def test_sweep_rows_are_judged_on_each_rows_level_case(shared_client):
    grid = {"bank_percent": [0.0, 6.0], "overweight_percent": [0.0, 20.0]}
    out = post(shared_client, "/v1/srt/sweep", {"vehicle": BTRAIN, "grid": grid})
    for row in out["rows"]:
        load = {"overweight_percent": row["overweight_percent"]}
        level = srt_of(shared_client, {"vehicle": BTRAIN, "load": load})["srt"]
        assert row["level_road_srt"] == pytest.approx(level, rel=1e-9)
        for t in row["targets"]:
            assert t["judged_on"] == "level_road_srt"
            assert t["meets"] == (row["level_road_srt"] >= t["target_g"])
            assert t["margin_g"] == row["level_road_srt"] - t["target_g"]
    by = {(r["bank_percent"], r["overweight_percent"]): r for r in out["rows"]}
    assert by[(6.0, 0.0)]["srt"] > 0.40 and not by[(6.0, 0.0)]["targets"][0]["meets"]
    assert by[(6.0, 0.0)]["level_road_srt"] == by[(0.0, 0.0)]["srt"]  # the level grid holds the bank-0 rows
    assert by[(6.0, 20.0)]["level_road_srt"] == by[(0.0, 20.0)]["srt"]
    assert by[(0.0, 20.0)]["srt"] < by[(0.0, 0.0)]["srt"]  # overweight lowers the level SRT


def test_sweep_around_a_banked_base_case(shared_client):
    out = post(shared_client, "/v1/srt/sweep", {"vehicle": BTRAIN, "road": BANK6, "grid": {"rear_llt_limit": [0.6, 1]}})
    for row in out["rows"]:
        level = srt_of(shared_client, {"vehicle": BTRAIN, "rear_llt_limit": row["rear_llt_limit"]})["srt"]
        banked = srt_of(shared_client, {"vehicle": BTRAIN, "rear_llt_limit": row["rear_llt_limit"], "road": BANK6})
        assert row["srt"] == pytest.approx(banked["srt"], rel=1e-9)
        assert row["level_road_srt"] == pytest.approx(level, rel=1e-9)


def test_alignment_rows_are_judged_on_the_vehicles_level_srt(shared_client):
    curves = [
        {"id": "C1", "radius_m": 120.0, "superelevation_percent": 8.0, "grade_percent": -4.0},
        {"id": "C2", "radius_m": 350.0, "superelevation_percent": 6.0, "grade_percent": 0.0},
        {"id": "C3", "radius_m": 600.0, "superelevation_percent": 0.0, "grade_percent": 0.0},
    ]
    out = post(shared_client, "/v1/alignments/assess", {"vehicle": BTRAIN, "curves": curves})
    level = srt_of(shared_client, {"vehicle": BTRAIN})["srt"]
    rows = out["vehicles"][0]["rows"]
    assert rows[1]["srt_g"] > 0.40  # the 6 % curve's own threshold
    assert rows[2]["srt_g"] == pytest.approx(level, rel=1e-9)  # the level curve
    for row in rows:
        assert row["level_road_srt"] == pytest.approx(level, rel=1e-12)
        assert_judged_on(row["targets"], row["level_road_srt"])
        assert [t["meets"] for t in row["targets"]] == [False, False]
    csv = shared_client.post(
        "/v1/alignments/assess", json={"vehicle": BTRAIN, "curves": curves}, headers={"Accept": "text/csv"}
    )
    header, *lines = csv.text.splitlines()
    names = header.split(",")
    assert names[names.index("srt_g") + 1] == "level_road_srt"
    for line in lines:
        cells = dict(zip(names, line.split(","), strict=True))
        assert float(cells["level_road_srt"]) == rows[0]["level_road_srt"]
        assert cells["meets_general"] == "false"


def test_a_limit_on_a_banked_road_is_searched_where_the_targets_are_judged(shared_client):
    # the default limit_on = level_road: the limit of a banked request is the level request's limit (the same search
    # on the same level case), so at the limit the targets meet exactly as a certifier reads them
    body = {"vehicle": BTRAIN, "road": BANK6, "parameter": "overweight_percent", "target_srt_g": 0.33}
    out = post(shared_client, "/v1/srt/limits", body)
    limit = out["limit"]
    assert out["limit_on"] == "level_road" and limit["status"] == "found"
    flat = post(shared_client, "/v1/srt/limits", {**body, "road": {"bank_percent": 0.0}})["limit"]
    assert limit["value"] == flat["value"] and limit["srt_at_limit"] == flat["srt_at_limit"]
    assert limit["level_road_srt"] == limit["srt_at_limit"] == pytest.approx(0.33, abs=1e-5)
    assert limit["level_road_srt"] >= 0.33  # a found limit meets its target (engine/bracket.py)
    # the curve's own threshold at that load: POST /v1/srt on the bank, higher than the level one (Eq. 9.1's bank)
    banked = srt_of(shared_client, {"vehicle": BTRAIN, "road": BANK6, "load": {"overweight_percent": limit["value"]}})
    assert limit["road_srt"] == pytest.approx(banked["srt"], rel=1e-12) and limit["road_srt"] > limit["srt_at_limit"]
    assert flat["road_srt"] == flat["level_road_srt"] == flat["srt_at_limit"]
    for t in limit["targets"]:
        assert t["judged_on"] == "level_road_srt" and t["margin_g"] == limit["level_road_srt"] - t["target_g"]


def test_a_limit_on_the_road_itself_is_the_curves_own(shared_client):
    body = {"vehicle": BTRAIN, "road": BANK6, "parameter": "overweight_percent", "target_srt_g": 0.40}
    out = post(shared_client, "/v1/srt/limits", {**body, "limit_on": "road"})
    limit = out["limit"]
    assert out["limit_on"] == "road" and limit["status"] == "found"
    assert limit["road_srt"] == limit["srt_at_limit"] == pytest.approx(0.40, abs=1e-5)
    level = srt_of(shared_client, {"vehicle": BTRAIN, "load": {"overweight_percent": limit["value"]}})["srt"]
    assert limit["level_road_srt"] == pytest.approx(level, rel=1e-12)
    assert limit["level_road_srt"] < limit["srt_at_limit"]  # the bank allows more than the targets do
    # judged on the level road: this load misses 0.40 g there, and the answer says so
    assert [t["meets"] for t in limit["targets"] if t["target_g"] == 0.40] in ([], [False])
    # the level-road default: no overweight of the range makes this B-train (0.339 g level) reach 0.40 g
    default = post(shared_client, "/v1/srt/limits", body)["limit"]
    assert default["status"] == "never-met" and default["value"] is None and default["targets"] == []
    # the CG-height table over overweights: every found row on its own basis, the level one the stricter
    cg = {**body, "parameter": "cg_height_above_chassis_m", "target_srt_g": 0.33}
    on_road = post(shared_client, "/v1/srt/limits", {**cg, "limit_on": "road"})["table"]
    on_level = post(shared_client, "/v1/srt/limits", cg)["table"]
    found = [(r, lv) for r, lv in zip(on_road, on_level, strict=True) if r["status"] == lv["status"] == "found"]
    assert found
    for r, lv in found:
        assert r["srt_at_limit"] == pytest.approx(0.33, abs=1e-5)
        assert lv["srt_at_limit"] == pytest.approx(0.33, abs=1e-5)
        assert lv["value"] < r["value"]


def test_the_level_case_is_cached_and_keyed_apart(client):
    banked = client.post("/v1/srt", json={"vehicle": BTRAIN, "road": BANK6})
    level = client.post("/v1/srt", json={"vehicle": BTRAIN})
    assert banked.headers["x-cache"] == level.headers["x-cache"] == "miss"
    assert banked.headers["etag"] != level.headers["etag"]
    again = client.post("/v1/srt", json={"vehicle": BTRAIN, "road": BANK6})
    assert again.headers["x-cache"] == "hit" and again.content == banked.content
    # the level case the banked answer solved is in the process's memo of engine results: one entry per case
    from app.compute.cache import cache_key
    from app.srt.schemas import SrtRequest
    from app.srt.service import level_case, resolve_case

    case = resolve_case(SrtRequest.model_validate({"vehicle": BTRAIN, "road": BANK6}), vehicle_preset(BTRAIN))
    memo = client.app.state.cache.objects
    key = cache_key("engine-result", {**level_case(case).to_dict(), "curve_points": None})
    assert memo[key].srt == level.json()["srt"]

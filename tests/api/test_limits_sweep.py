"""POST /v1/srt/limits (inverse limits) and POST /v1/srt/sweep (grids), through HTTP.

The limits are checked by feeding them back to /v1/srt (the SRT there must be the target) and by the SRT on
either side of them; the sweep rows against single /v1/srt answers and the thesis's Table 17; a large sweep is
streamed, byte for byte the document pydantic writes for it.
"""

from __future__ import annotations

import csv
import io
import itertools

import orjson
import pytest

from app.srt.sweep_schemas import SweepGrid, SweepResult
from engine.models.threshold import SWEEP_AXES

BTRAIN = "table16-btrain"


def same_targets(a: list[dict], b: list[dict]) -> bool:
    """Equal target checks, margins to 1e-9 g (a batch solve and a single one agree to round-off)."""
    return [(t["name"], t["target_g"], t["meets"]) for t in a] == [
        (t["name"], t["target_g"], t["meets"]) for t in b
    ] and all(x["margin_g"] == pytest.approx(y["margin_g"], abs=1e-9) for x, y in zip(a, b, strict=True))


def post(client, path, body, status=200, **kwargs):
    r = client.post(path, json=body, **kwargs)
    assert r.status_code == status, r.text
    return r


def srt_of(client, body) -> float:
    return post(client, "/v1/srt", body).json()["srt"]


@pytest.fixture(scope="module")
def btrain_record(shared_client):
    record = shared_client.get(f"/v1/vehicles/{BTRAIN}").json()
    for k in ("id", "title", "source", "models"):
        record.pop(k)
    return record


def case_with(record, parameter, value, load=None):
    """The /v1/srt body of the B-train with one parameter set to ``value``."""
    load = dict(load or {})
    if parameter in ("cg_height_above_chassis_m", "spring_separation_m"):
        return {"vehicle": {**record, parameter: value}, "load": load}
    return {"vehicle": BTRAIN, "load": {**load, parameter: value}}


# ------------------------------------------------------------------------------------------ limits


@pytest.mark.parametrize(
    ("parameter", "target", "kind", "unit"),
    [
        ("cg_height_above_chassis_m", 0.30, "max", "m"),
        ("overweight_percent", 0.35, "max", "%"),
        ("lateral_offset_m", 0.30, "max", "m"),
        ("spring_separation_m", 0.30, "min", "m"),
    ],
)
def test_a_limit_fed_back_to_srt_gives_the_target(shared_client, btrain_record, parameter, target, kind, unit):
    body = {"vehicle": BTRAIN, "parameter": parameter, "target_srt_g": target}
    out = post(shared_client, "/v1/srt/limits", body).json()
    assert (out["parameter"], out["kind"], out["unit"], out["target_srt_g"]) == (parameter, kind, unit, target)
    limit = out["limit"]
    assert limit["status"] == "found" and limit["range_min"] < limit["value"] < limit["range_max"]
    # the limit meets the target and lies within the search's tolerance (1e-6 of the parameter's unit) of the
    # crossing: its SRT within 1e-6 g above the target (every slope here is below 1 g per unit)
    assert target <= limit["srt_at_limit"] <= target + 1e-6
    value = limit["value"]
    assert srt_of(shared_client, case_with(btrain_record, parameter, value)) == pytest.approx(target, abs=1e-5)
    # past the limit the target is missed, short of it met (max: past = larger; min: past = smaller)
    step = 0.01 * (out["limit"]["range_max"] - out["limit"]["range_min"])
    past, short = (value + step, value - step) if kind == "max" else (value - step, value + step)
    assert srt_of(shared_client, case_with(btrain_record, parameter, past)) < target
    assert srt_of(shared_client, case_with(btrain_record, parameter, short)) > target


def test_the_limit_table_falls_with_overweight_and_each_row_is_exact(shared_client, btrain_record):
    body = {"vehicle": BTRAIN, "parameter": "cg_height_above_chassis_m", "target_srt_g": 0.30}
    out = post(shared_client, "/v1/srt/limits", body).json()
    table = out["table"]
    assert [r["overweight_percent"] for r in table] == [0, 5, 10, 15, 20]  # the default overweights
    assert all(r["status"] == "found" and r["error"] is None for r in table)
    values = [r["value"] for r in table]
    assert all(b < a for a, b in itertools.pairwise(values))  # heavier -> lower acceptable CG
    assert table[0]["value"] == pytest.approx(out["limit"]["value"], rel=1e-9)  # the base case is overweight 0
    row = table[-1]
    fed_back = case_with(btrain_record, "cg_height_above_chassis_m", row["value"], {"overweight_percent": 20})
    assert srt_of(shared_client, fed_back) == pytest.approx(0.30, abs=1e-5)
    # Table 16: the B-train's CG height above the chassis is 1.356 m
    assert out["current_value"] == 1.356 and out["symbol"] == "l12"


def test_the_limit_reports_targets_and_the_tilt_angle_of_its_srt(shared_client):
    body = {"vehicle": BTRAIN, "parameter": "lateral_offset_m", "target_srt_g": 0.3, "targets": {"fleet": 0.28}}
    limit = post(shared_client, "/v1/srt/limits", body).json()["limit"]
    (check,) = limit["targets"]
    assert check["name"] == "fleet" and check["meets"] is True
    assert check["margin_g"] == pytest.approx(0.02, abs=1e-9)
    assert limit["tilt_table_angle_deg"] == pytest.approx(16.6992, abs=1e-4)  # atan(0.3) = 16.6992 deg


@pytest.mark.parametrize("parameter", ["cg_height_above_chassis_m", "lateral_offset_m", "spring_separation_m"])
def test_a_found_limit_meets_the_target_it_was_searched_for(shared_client, parameter):
    """On a level road the limit for the general target (0.35 g) is judged "meets" by its own check: its SRT is at
    or above the target, never a hair below it (Brent's root may fall on either side of the crossing)."""
    limit = post(shared_client, "/v1/srt/limits", {"vehicle": BTRAIN, "parameter": parameter}).json()["limit"]
    assert limit["status"] == "found"
    assert limit["srt_at_limit"] >= 0.35 and limit["srt_at_limit"] == pytest.approx(0.35, abs=1e-6)
    general = next(t for t in limit["targets"] if t["name"] == "general")
    assert general["meets"] is True and general["margin_g"] >= 0.0


def test_always_met_and_never_met(shared_client):
    # at 0.30 g even 50 % overweight is fine (the B-train's SRT hardly depends on the weight)
    out = post(
        shared_client, "/v1/srt/limits", {"vehicle": BTRAIN, "parameter": "overweight_percent", "target_srt_g": 0.3}
    ).json()
    assert out["limit"]["status"] == "always-met"
    assert out["limit"]["value"] == out["limit"]["range_max"] == 50
    assert out["limit"]["srt_at_limit"] > 0.3
    assert out["table"] is None  # no table over overweights for the overweight itself
    # 1.5 g is out of reach whatever the CG height
    out = post(
        shared_client,
        "/v1/srt/limits",
        {"vehicle": BTRAIN, "parameter": "cg_height_above_chassis_m", "target_srt_g": 1.5, "overweights_percent": [0]},
    ).json()
    assert out["limit"]["status"] == "never-met"
    assert out["limit"]["value"] is None and out["limit"]["srt_at_limit"] is None
    assert out["limit"]["targets"] == [] and out["limit"]["tilt_table_angle_deg"] is None
    assert out["table"][0]["status"] == "never-met" and out["table"][0]["value"] is None


def test_the_default_target_is_the_configured_general_one(shared_client):
    a = post(shared_client, "/v1/srt/limits", {"vehicle": BTRAIN, "parameter": "lateral_offset_m"})
    b = post(
        shared_client, "/v1/srt/limits", {"vehicle": BTRAIN, "parameter": "lateral_offset_m", "target_srt_g": 0.35}
    )
    assert a.json()["target_srt_g"] == 0.35
    assert b.headers["x-cache"] == "hit" and b.headers["etag"] == a.headers["etag"]


def test_limit_errors_name_the_field(shared_client):
    body = {"vehicle": BTRAIN, "parameter": "overweight_percent", "overweights_percent": [0, 10]}
    p = post(shared_client, "/v1/srt/limits", body, 422).json()
    assert p["errors"][0]["field"] == "overweights_percent"
    p = post(shared_client, "/v1/srt/limits", {"vehicle": BTRAIN, "parameter": "wheelbase_m"}, 422).json()
    assert p["errors"][0]["field"] == "parameter"
    body = {"vehicle": BTRAIN, "parameter": "lateral_offset_m", "overweights_percent": [0] * 26}
    assert post(shared_client, "/v1/srt/limits", body, 422).json()["errors"][0]["field"] == "overweights_percent"
    # the 3d model on the 2D Table 14 record: the missing vehicle field, not the searched parameter
    body = {"vehicle": "table14-semitrailer", "parameter": "lateral_offset_m"}
    p = post(shared_client, "/v1/srt/limits", body, 422).json()
    assert p["type"].endswith("missing-parameter") and p["errors"][0]["field"] == "vehicle.front_track_m"


# ------------------------------------------------------------------------------------------- sweep

TABLE17 = {"vehicle": BTRAIN, "rear_llt_limit": 0.6, "grid": {"bank_percent": [0, 8], "slope_percent": [-4, 0, 4]}}


def test_the_grid_axes_are_the_engines():
    assert set(SweepGrid.model_fields) == set(SWEEP_AXES)


def test_sweep_rows_are_the_single_srt_results_in_product_order(shared_client):
    out = post(shared_client, "/v1/srt/sweep", TABLE17).json()
    assert out["axes"] == ["bank_percent", "slope_percent"] and out["cases"] == 6 and out["refused"] == 0
    assert [(r["bank_percent"], r["slope_percent"]) for r in out["rows"]] == [
        (0, -4),
        (0, 0),
        (0, 4),
        (8, -4),
        (8, 0),
        (8, 4),
    ]
    for row in out["rows"]:
        assert set(row) == {
            "bank_percent",
            "slope_percent",
            "srt",
            "level_road_srt",
            "roll_angle_deg",
            "tilt_table_angle_deg",
        } | {
            "targets",
            "error",
        }
        single = post(
            shared_client,
            "/v1/srt",
            {
                "vehicle": BTRAIN,
                "rear_llt_limit": 0.6,
                "road": {"bank_percent": row["bank_percent"], "slope_percent": row["slope_percent"]},
            },
        ).json()
        assert row["srt"] == pytest.approx(single["srt"], rel=1e-9)
        assert row["roll_angle_deg"] == pytest.approx(single["roll_angle_deg"], rel=1e-6)
        assert same_targets(row["targets"], single["targets"])
        assert row["tilt_table_angle_deg"] == pytest.approx(single["tilt_table_angle_deg"], rel=1e-9)
    # Table 17 (LLT 0.6): flat 0.202 g, 8 % bank 0.285 g (+-2 %)
    flat = {(r["bank_percent"], r["slope_percent"]): r["srt"] for r in out["rows"]}
    assert flat[(0, 0)] == pytest.approx(0.202, rel=0.02) and flat[(8, 0)] == pytest.approx(0.285, rel=0.02)


def test_sweep_csv_has_a_header_and_the_json_values(client):
    as_json = post(client, "/v1/srt/sweep", TABLE17)
    as_csv = post(client, "/v1/srt/sweep", TABLE17, headers={"Accept": "text/csv"})
    assert as_csv.headers["content-type"].startswith("text/csv")
    assert as_csv.headers["vary"] == "Accept" and as_json.headers["vary"] == "Accept"
    assert as_csv.headers["etag"] != as_json.headers["etag"]  # two representations, two entity tags
    rows = list(csv.DictReader(io.StringIO(as_csv.text)))
    assert list(rows[0]) == [
        "bank_percent",
        "slope_percent",
        "srt",
        "level_road_srt",
        "roll_angle_deg",
        "tilt_table_angle_deg",
        "meets_general",
        "margin_general_g",
        "meets_dangerous_goods",
        "margin_dangerous_goods_g",
        "error",
    ]
    expected = as_json.json()["rows"]
    assert len(rows) == len(expected) == 6
    for got, want in zip(rows, expected, strict=True):
        assert float(got["srt"]) == want["srt"]  # full precision both ways
        assert float(got["bank_percent"]) == want["bank_percent"]
        assert got["meets_general"] == ("true" if want["targets"][0]["meets"] else "false")
        assert float(got["margin_dangerous_goods_g"]) == want["targets"][1]["margin_g"]
        assert got["error"] == ""
    again = post(client, "/v1/srt/sweep", TABLE17, headers={"Accept": "text/csv"})
    assert again.headers["x-cache"] == "hit" and again.content == as_csv.content


@pytest.mark.parametrize(
    ("accept", "is_csv"),
    [
        (None, False),
        ("*/*", False),
        ("application/json", False),
        ("text/csv", True),
        ("text/*", True),
        ("text/csv;q=0.5, application/json", False),
        ("application/json;q=0.1, text/csv", True),
        ("text/csv, application/json", False),  # a tie: JSON
    ],
)
def test_accept_negotiation(shared_client, accept, is_csv):
    headers = {"Accept": accept} if accept else {}
    r = post(shared_client, "/v1/srt/sweep", {"vehicle": BTRAIN, "grid": {"bank_percent": [0]}}, headers=headers)
    assert r.headers["content-type"].startswith("text/csv" if is_csv else "application/json")


def test_a_refused_case_keeps_its_row(shared_client):
    # d1 = 1.0 m is beyond the B-train's half track (0.93 m): that case is refused, the other answered
    out = post(shared_client, "/v1/srt/sweep", {"vehicle": BTRAIN, "grid": {"lateral_offset_m": [0, 1.0]}}).json()
    assert out["cases"] == 2 and out["refused"] == 1
    ok, refused = out["rows"]
    assert ok["srt"] > 0 and ok["error"] is None
    assert refused["lateral_offset_m"] == 1.0 and refused["srt"] is None and refused["targets"] == []
    assert "half track" in refused["error"]


def test_axis_order_is_fixed_whatever_the_json_order(client):
    a = post(client, "/v1/srt/sweep", {"vehicle": BTRAIN, "grid": {"slope_percent": [0, 4], "bank_percent": [0, 8]}})
    b = post(client, "/v1/srt/sweep", {"vehicle": BTRAIN, "grid": {"bank_percent": [0, 8], "slope_percent": [0, 4]}})
    assert a.json()["axes"] == ["bank_percent", "slope_percent"]
    assert b.headers["x-cache"] == "hit" and b.content == a.content


def test_the_grid_overrides_the_base_case(shared_client):
    flat = srt_of(shared_client, {"vehicle": BTRAIN})
    out = post(
        shared_client, "/v1/srt/sweep", {"vehicle": BTRAIN, "road": {"bank_percent": 6}, "grid": {"bank_percent": [0]}}
    ).json()
    assert out["rows"][0]["srt"] == pytest.approx(flat, rel=1e-9)


@pytest.mark.parametrize(
    ("grid", "field", "words"),
    [
        ({"wind_speed": [1]}, "grid.wind_speed", "unknown field 'wind_speed'"),
        ({}, "grid", "at least one axis"),
        ({"bank_percent": list(range(-20, 20)), "slope_percent": list(range(-20, 20)), "vertical_offset_m": [0] * 13},
         "grid", "20800 cases"),
        ({"bank_percent": [0.0] * 201}, "grid.bank_percent", "at most 200"),
        ({"bank_percent": [25]}, "grid.bank_percent.0", "less than or equal to 20"),
        ({"rear_llt_limit": []}, "grid.rear_llt_limit", "at least 1"),
    ],
)  # fmt: skip
def test_sweep_errors_name_the_field(shared_client, grid, field, words):
    p = post(shared_client, "/v1/srt/sweep", {"vehicle": BTRAIN, "grid": grid}, 422).json()
    errors = {e["field"]: e["message"] for e in p["errors"]}
    assert field in errors, errors
    assert words in errors[field]


# ------------------------------------------------------------------------------------------ streaming

#: 2 banks x 3 slopes x 2 d1 = 12 cases; the 6 with d1 = 1.0 m are refused (beyond the half track, 0.93 m)
CHUNKED = {
    "vehicle": BTRAIN,
    "rear_llt_limit": 0.6,
    "targets": {"general": 0.35, "tight": 0.2},
    "grid": {"bank_percent": [0, 8], "slope_percent": [-4, 0, 4], "lateral_offset_m": [0.1, 1.0]},
}
CASES = 12


def sweep_bytes(client, accept: str) -> tuple[bytes, dict]:
    with client.stream("POST", "/v1/srt/sweep", json=CHUNKED, headers={"accept": accept}) as r:
        assert r.status_code == 200, r.read()
        return b"".join(r.iter_raw()), dict(r.headers)


@pytest.mark.parametrize("accept", ["application/json", "text/csv"])
def test_a_sweep_rendered_in_several_chunks_is_one_whole_cached_body(monkeypatch, accept):
    import app.srt.sweep_service as service_tools

    from .conftest import make_client

    monkeypatch.setattr(service_tools, "ROWS_PER_CHUNK", 5)  # several chunks, the last one short
    with make_client() as client:  # a cache of its own: the answer is computed
        body, headers = sweep_bytes(client, accept)
        assert headers["x-cache"] == "miss" and headers["vary"] == "Accept"
        assert headers["content-type"].startswith(accept)
        assert headers["content-length"] == str(len(body))  # whole: one body with its length
        again, again_headers = sweep_bytes(client, accept)
        assert again == body and again_headers["x-cache"] == "hit" and again_headers["etag"] == headers["etag"]
    if accept == "application/json":
        # byte for byte the document pydantic writes for the same result: the chunked renderer is not a variant
        assert SweepResult.model_validate_json(body).model_dump_json(exclude_unset=True).encode() == body
        out = orjson.loads(body)
        assert out["cases"] == CASES and out["refused"] == 6 and len(out["rows"]) == CASES
        assert [r["lateral_offset_m"] for r in out["rows"][:4]] == [0.1, 1.0] * 2  # the last axis varies fastest
        for row in out["rows"]:
            refused = row["lateral_offset_m"] == 1.0
            assert (row["error"] is not None, row["srt"] is None, row["targets"] == []) == (refused,) * 3
    else:
        rows = list(csv.DictReader(io.StringIO(body.decode())))
        assert len(rows) == CASES
        assert list(rows[0])[-5:] == ["meets_tight", "margin_tight_g", "meets_general", "margin_general_g", "error"]


def test_a_sweep_row_is_the_single_srt_answer(client):
    rows = post(client, "/v1/srt/sweep", TABLE17).json()["rows"]
    single = post(client, "/v1/srt", {"vehicle": BTRAIN, "rear_llt_limit": 0.6, "road": {"bank_percent": 8}}).json()
    (row,) = [r for r in rows if r["bank_percent"] == 8 and r["slope_percent"] == 0]
    assert row["srt"] == pytest.approx(single["srt"], rel=1e-9)
    assert row["tilt_table_angle_deg"] == pytest.approx(single["tilt_table_angle_deg"], rel=1e-9)
    assert same_targets(row["targets"], single["targets"])


def test_each_form_of_a_sweep_is_solved_once_and_then_answered_from_the_cache(client):
    from prometheus_client import REGISTRY

    def solves() -> float:
        labels = {"operation": "srt-sweep", "model": "3d"}
        return REGISTRY.get_sample_value("rollover_solve_seconds_count", labels) or 0.0

    before = solves()
    body = {"vehicle": BTRAIN, "grid": {"bank_percent": [0, 1, 2]}}
    assert post(client, "/v1/srt/sweep", body).headers["x-cache"] == "miss"
    as_csv = post(client, "/v1/srt/sweep", body, headers={"Accept": "text/csv"})
    assert as_csv.headers["x-cache"] == "miss"  # its own body and key
    assert solves() - before == 2
    for accept in ("application/json", "text/csv"):  # each form again: its cached body, no solve
        assert post(client, "/v1/srt/sweep", body, headers={"Accept": accept}).headers["x-cache"] == "hit"
    assert solves() - before == 2

"""Combinations over HTTP: the presets, a combination wherever a vehicle is taken, its errors (../shared/DESIGN.md)."""

from __future__ import annotations

import math
import tempfile

import pytest

from engine import Case, get_combination, rollover_threshold
from engine.models.combination import rigid_srt, solve_combination
from engine.vehicle import COMBINATION_SOURCES

from .conftest import make_client

IDS = ["tractor-semitrailer-table15", "btrain-table16", "adouble", "truck-trailer"]


def test_the_presets_are_listed_and_each_names_its_sources(shared_client):
    listed = shared_client.get("/v1/combinations").json()
    assert [c["id"] for c in listed] == IDS
    a = next(c for c in listed if c["id"] == "adouble")
    assert a["roll_coupled_units"] == [["tractor", "trailer1"], ["dolly", "trailer2"]]
    one = shared_client.get("/v1/combinations/btrain-table16").json()
    assert one["sources"] == COMBINATION_SOURCES["btrain-table16"]
    assert one["combination"]["units"][2]["groups"][0]["track_m"] == 1.86  # Table 16's t3
    r = shared_client.get("/v1/combinations/nope")
    assert r.status_code == 404 and "btrain-table16" in r.json()["detail"]


@pytest.mark.parametrize("cid", IDS)
def test_srt_of_a_combination_is_the_governing_roll_coupled_unit(shared_client, cid):
    body = shared_client.post("/v1/srt", json={"vehicle": cid}).json()
    detail = solve_combination(get_combination(cid))
    assert body["model"] == "combination"
    assert body["srt"] == min(r.srt for r in detail.roll_coupled_units)
    assert [r["units"] for r in body["roll_coupled_units"]] == [list(r.units) for r in detail.roll_coupled_units]
    ays = [e["ay_g"] for e in body["lift_sequence"]]
    assert ays == sorted(ays) and len(ays) == sum(len(r.lift_sequence) for r in detail.roll_coupled_units)
    assert body["governing_unit"] == detail.governing
    assert body["last_unit_front_llt_ratio"] == detail.last_unit_front_llt_ratio
    for target in body["targets"]:
        assert target["meets"] == (body["srt"] >= target["target_g"])


def test_the_3d_model_of_a_combination_takes_the_computed_ratio_and_rigid_the_rigid_units(shared_client):
    c = get_combination("btrain-table16")
    body = shared_client.post("/v1/srt", json={"vehicle": "btrain-table16", "model": "3d"}).json()
    assert body["srt"] == rollover_threshold(Case(c, model="3d")).srt
    assert body["notes"][0].startswith("front_llt_ratio = ")
    rigid = shared_client.post("/v1/srt", json={"vehicle": "btrain-table16", "model": "rigid"}).json()
    assert rigid["srt"] == min(rigid_srt(c))


def test_a_combination_given_in_full_is_the_preset_and_shares_its_cache_entry(client):
    comb = client.get("/v1/combinations/adouble").json()["combination"]
    by_id = client.post("/v1/srt", json={"vehicle": "adouble", "road": {"bank_percent": 4.0}})
    in_full = client.post("/v1/srt", json={"vehicle": {"combination": comb}, "road": {"bank_percent": 4.0}})
    assert in_full.json()["srt"] == by_id.json()["srt"]
    assert in_full.headers["etag"] == by_id.headers["etag"] and in_full.headers["x-cache"] == "hit"


def test_road_design_and_batches_take_a_combination(shared_client):
    srt = shared_client.post("/v1/srt", json={"vehicle": "truck-trailer"}).json()["srt"]
    speed = shared_client.post("/v1/curve-speed", json={"vehicle": "truck-trailer", "radius_m": 100.0}).json()
    assert speed["max_speed_kmh"] == pytest.approx(math.sqrt(127 * srt * 100.0), rel=1e-12)  # Eq. 9.1
    radius = shared_client.post(
        "/v1/min-radius", json={"vehicle": "truck-trailer", "design_speed_kmh": 80.0, "superelevation_percent": 0.0}
    ).json()
    assert radius["rollover_min_radius_m"] == pytest.approx(80.0**2 / (127 * srt), rel=1e-12)  # Eq. 9.3
    curves = [{"id": "C1", "radius_m": 150.0, "superelevation_percent": 6.0, "posted_speed_kmh": 70.0}]
    rows = shared_client.post("/v1/alignments/assess", json={"vehicles": ["btrain-table16", "table16-btrain"],
                                                              "curves": curves}).json()  # fmt: skip
    combination_row, trailer_row = (v["rows"][0] for v in rows["vehicles"])
    banked = shared_client.post("/v1/srt", json={"vehicle": "btrain-table16", "road": {"bank_percent": 6.0}}).json()
    assert combination_row["srt_g"] == banked["srt"]
    assert trailer_row["srt_g"] != combination_row["srt_g"]
    sweep = shared_client.post("/v1/srt/sweep", json={"vehicle": "adouble", "grid": {"bank_percent": [0, 6]}}).json()
    level = shared_client.post("/v1/srt", json={"vehicle": "adouble"}).json()["srt"]
    assert sweep["model"] == "combination" and sweep["rows"][0]["srt"] == level
    limit = shared_client.post(
        "/v1/srt/limits", json={"vehicle": "btrain-table16", "target_srt_g": 0.32, "parameter": "overweight_percent"}
    ).json()
    assert limit["limit"]["status"] == "found" and limit["limit"]["srt_at_limit"] == pytest.approx(0.32, abs=1e-6)


def test_routes_and_jobs_take_a_combination_and_answer_what_the_alignment_answers(shared_client):
    """A route (JSON-wrapped and raw GPX) and an alignment job with a combination preset: the route's curves are
    assessed with the combination's SRT on each curve's bank and grade (the same as /v1/srt there), and the job's
    result is the synchronous alignment answer byte for byte."""
    from pathlib import Path

    from tests.jobs.conftest import wait_for

    gpx = (Path(__file__).resolve().parents[2] / "examples" / "road.gpx").read_text(encoding="utf-8")
    options = {"superelevation_percent": 7.5, "posted_speed_kmh": 60.0}
    wrapped = shared_client.post("/v1/routes/assess", json={"vehicle": "btrain-table16", "gpx": gpx, **options})
    assert wrapped.status_code == 200, wrapped.text
    raw = shared_client.post(
        "/v1/routes/assess/gpx?vehicle=btrain-table16&superelevation_percent=7.5&posted_speed_kmh=60",
        content=gpx.encode(),
        headers={"Content-Type": "application/gpx+xml"},
    )
    assert raw.status_code == 200 and raw.content == wrapped.content
    curves = wrapped.json()["curves"]
    assert len(curves) == 2
    for c in curves:
        a = c["assessment"]
        grade = c["grade_percent"] or 0.0
        road = {"bank_percent": 7.5, "slope_percent": grade}
        assert (
            a["srt_g"] == shared_client.post("/v1/srt", json={"vehicle": "btrain-table16", "road": road}).json()["srt"]
        )
    rows = [{"id": "C1", "radius_m": 150.0, "superelevation_percent": 6.0, "posted_speed_kmh": 70.0}]
    request = {"vehicle": "adouble", "curves": rows}
    sync = shared_client.post("/v1/alignments/assess", json=request)
    job = shared_client.post("/v1/jobs", json={"operation": "alignments.assess", "request": request})
    assert job.status_code == 202, job.text
    location = job.headers["Location"]
    assert wait_for(shared_client, location)["status"] == "done"
    result = shared_client.get(f"{location}/result")
    assert result.status_code == 200 and result.content == sync.content


def test_impossible_combinations_are_422_naming_the_field_as_typed(shared_client):
    comb = shared_client.get("/v1/combinations/btrain-table16").json()["combination"]
    comb["units"][1]["sprung_mass_kg"] = 31.5  # someone's tonnes
    r = shared_client.post("/v1/srt", json={"vehicle": {"combination": comb}})
    assert r.status_code == 422 and "tonnes" in r.json()["detail"]
    assert r.json()["errors"][0]["field"] == "vehicle.combination.units.1.sprung_mass_kg"
    comb = shared_client.get("/v1/combinations/adouble").json()["combination"]
    comb["units"] = comb["units"][:3]
    comb["couplings"] = comb["couplings"][:2]
    r = shared_client.post("/v1/srt", json={"vehicle": {"combination": comb}})
    assert r.status_code == 422 and "dolly carrying nothing" in r.json()["detail"]
    r = shared_client.post("/v1/srt", json={"vehicle": "btrain-table16", "trailer_angle_deg": 10.0})
    assert r.status_code == 422 and r.json()["errors"][0]["field"] == "trailer_angle_deg"


def test_a_saved_combination_is_used_by_id_and_in_a_fleet():
    from app.settings import Settings

    key = "combination-key-0123456789"
    with tempfile.TemporaryDirectory() as tmp:
        settings = Settings(cache_backend="memory", api_keys=key, database_url=f"sqlite:///{tmp}/c.db")
        with make_client(settings) as c:
            auth = {"Authorization": f"Bearer {key}"}
            comb = c.get("/v1/combinations/btrain-table16").json()["combination"]
            saved = c.post("/v1/vehicles", json={"title": "B-double", "vehicle": {"combination": comb}}, headers=auth)
            assert saved.status_code == 201 and saved.json()["kind"] == "combination"
            vid = saved.json()["id"]
            assert c.get(f"/v1/vehicles/{vid}", headers=auth).json()["vehicle"] == {"combination": comb}
            by_id = c.post("/v1/srt", json={"vehicle": vid}, headers=auth).json()
            assert by_id["srt"] == c.post("/v1/srt", json={"vehicle": "btrain-table16"}).json()["srt"]
            fleet = c.post("/v1/fleets", json={"title": "f", "vehicles": [vid, "adouble"]}, headers=auth)
            assert fleet.status_code == 201


def test_a_saved_combination_spec_is_built_on_use_and_refused_on_save_when_it_cannot_be_built():
    """A combination in measurable terms is saved as sent (kind combination_spec), answers what the same spec sent
    inline answers, and a spec the builder refuses is a 422 naming the field under vehicle.combination_spec."""
    from app.settings import Settings
    from app.vehicle_forms.combination_builder_schemas import EXAMPLE_COMBINATION_SPEC

    key = "combination-key-0123456789"
    with tempfile.TemporaryDirectory() as tmp:
        settings = Settings(cache_backend="memory", api_keys=key, database_url=f"sqlite:///{tmp}/c.db")
        with make_client(settings) as c:
            auth = {"Authorization": f"Bearer {key}"}
            body = {"title": "Built", "vehicle": {"combination_spec": EXAMPLE_COMBINATION_SPEC}}
            saved = c.post("/v1/vehicles", json=body, headers=auth)
            assert saved.status_code == 201, saved.text
            assert saved.json()["kind"] == "combination_spec"
            vid = saved.json()["id"]
            stored = c.get(f"/v1/vehicles/{vid}", headers=auth).json()["vehicle"]
            assert stored == {"combination_spec": EXAMPLE_COMBINATION_SPEC}
            inline = c.post("/v1/srt", json={"vehicle": {"combination_spec": EXAMPLE_COMBINATION_SPEC}}).json()
            assert c.post("/v1/srt", json={"vehicle": vid}, headers=auth).json()["srt"] == inline["srt"]
            tractor = EXAMPLE_COMBINATION_SPEC["units"][0]
            tonnes = {**tractor, "tare": {**tractor["tare"], "mass_kg": 7.5}}  # 7.5 t typed as kg
            bad = {**EXAMPLE_COMBINATION_SPEC, "units": [tonnes, *EXAMPLE_COMBINATION_SPEC["units"][1:]]}
            refused = c.post("/v1/vehicles", json={"title": "t", "vehicle": {"combination_spec": bad}}, headers=auth)
            assert refused.status_code == 422, refused.text
            fields = [e["field"] for e in refused.json()["errors"]]
            assert any(f.startswith("vehicle.combination_spec.units") and "tare" in f for f in fields), fields

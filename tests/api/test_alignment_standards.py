"""The alignment assessment with a design standard (AASHTO 2018 by default), derived superelevations, the
standard's minimum radius per curve, and large answers streamed byte for byte as the whole ones."""

from __future__ import annotations

import csv
import io
import math

import numpy as np
import orjson
import pytest

from app.alignments.schemas import AlignmentResult

PATH = "/v1/alignments/assess"
BTRAIN = "table16-btrain"
# AASHTO Green Book (2018) Table 3-7 metric f_max (transcription cited in engine/standards.py): speed -> f_max
AASHTO_F = {
    20: 0.35,
    30: 0.28,
    40: 0.23,
    50: 0.19,
    60: 0.17,
    70: 0.15,
    80: 0.14,
    90: 0.13,
    100: 0.12,
    110: 0.11,
    120: 0.09,
}


def f_aashto(v: float) -> float:
    v = min(max(v, 20.0), 120.0)
    return float(np.interp(v, sorted(AASHTO_F), [AASHTO_F[k] for k in sorted(AASHTO_F)]))


def post(client, body, status=200, **headers):
    r = client.post(PATH, json=body, headers=headers)
    assert r.status_code == status, r.text
    return r


def test_the_default_standard_is_aashto_2018_and_its_f_max_sets_the_side_friction_speed(shared_client):
    curves = [{"id": f"K{r}", "radius_m": float(r), "superelevation_percent": 6.0} for r in (60, 150, 400, 1200)]
    out = post(shared_client, {"vehicle": BTRAIN, "curves": curves}).json()
    assert out["design_standard"] == "aashto-2018" and out["side_friction_bound"] is None
    for row in out["vehicles"][0]["rows"]:
        v, f = row["side_friction_speed_kmh"], f_aashto(row["side_friction_speed_kmh"])
        assert row["side_friction"] == pytest.approx(f, abs=1e-12)
        assert v == pytest.approx(math.sqrt(127 * row["radius_m"] * (0.06 + f)), rel=1e-9)  # Eq. 9.2 for V


def test_a_curve_at_aashtos_minimum_radius_is_not_rated_below_its_design_speed(shared_client):
    """The issue's case: a curve at AASHTO's R_min for 60 km/h (e_max 8 %, f_max 0.17: 3600 / (127 x 0.25) =
    113.4 m) used to be rated 57.7 km/h by Table 21's low bound. With AASHTO it is good for 60 km/h."""
    r_min = 60.0**2 / (127 * (0.08 + 0.17))
    curve = {"id": "K", "radius_m": math.ceil(r_min), "superelevation_percent": 8.0, "posted_speed_kmh": 60.0}
    out = post(shared_client, {"vehicle": BTRAIN, "curves": [curve], "max_superelevation_percent": 8.0}).json()
    row = out["vehicles"][0]["rows"][0]
    assert row["side_friction_speed_kmh"] >= 60.0
    assert row["standard_min_radius_m"] == 113.0  # Table 3-7 (NYSDOT M2-14), rounded to the metre
    assert row["meets_standard_min_radius"] is True
    published = {**curve, "radius_m": 113.0}  # the issue's case: Table 3-7's rounded R_min
    old = post(shared_client, {"vehicle": BTRAIN, "curves": [published], "design_standard": "thesis-table21"}).json()
    assert old["vehicles"][0]["rows"][0]["side_friction_speed_kmh"] == pytest.approx(57.7, abs=0.05)


def test_a_curve_below_the_standards_minimum_radius_is_counted(shared_client):
    curves = [
        {"id": "tight", "radius_m": 100.0, "superelevation_percent": 8.0, "posted_speed_kmh": 60.0},  # < 113 m
        {"id": "ok", "radius_m": 300.0, "superelevation_percent": 6.0, "posted_speed_kmh": 60.0},
        {"id": "no speed", "radius_m": 300.0, "superelevation_percent": 6.0},
    ]
    out = post(shared_client, {"vehicle": BTRAIN, "curves": curves, "max_superelevation_percent": 8.0}).json()
    tight, ok, no_speed = out["vehicles"][0]["rows"]
    assert (tight["meets_standard_min_radius"], ok["meets_standard_min_radius"]) == (False, True)
    assert no_speed["meets_standard_min_radius"] is None and no_speed["standard_min_radius_m"] is None
    assert out["vehicles"][0]["summary"]["below_standard_min_radius"] == 1


def test_a_missing_superelevation_is_derived_from_the_standards_distribution(shared_client):
    # DNER/DNIT IPR-706, e = e_max (2 R_min/R - R_min^2/R^2): 80 km/h, e_max 8 %, R 1000 m -> 3.25 %
    # (worked case H-01 of TheVoidDweller/road-geometric-design-tool, R_min 229.06 m by Eq. 9.2 with f 0.14)
    curves = [
        {"id": "D", "radius_m": 1000.0, "posted_speed_kmh": 80.0},
        {"id": "G", "radius_m": 1000.0, "superelevation_percent": 5.0, "posted_speed_kmh": 80.0},
    ]
    body = {"vehicle": BTRAIN, "curves": curves, "design_standard": "dnit-1999", "max_superelevation_percent": 8.0}
    derived, given = post(shared_client, body).json()["vehicles"][0]["rows"]
    assert derived["superelevation_source"] == "derived" and given["superelevation_source"] == "given"
    assert derived["superelevation_percent"] == pytest.approx(3.25, abs=0.005)
    # its SRT is the one on that bank
    srt = shared_client.post(
        "/v1/srt", json={"vehicle": BTRAIN, "road": {"bank_percent": derived["superelevation_percent"]}}
    ).json()["srt"]
    assert derived["srt_g"] == pytest.approx(srt, rel=1e-9)


def test_a_curve_sharper_than_the_distributions_minimum_is_assessed_on_e_max_not_refused(shared_client):
    # AASHTO 2018 Table 3-7 at 80 km/h, e_max 8 %: f_max 0.14, R_min 229 m. A 150 m curve has no design
    # superelevation: it is assessed on e_max (the most the road has), fails the standard's minimum radius, and the
    # rest of the alignment is assessed as usual
    text = "id,radius_m,posted_speed_kmh\nK1,150,80\nK2,600,80\n"
    out = post(shared_client, {"vehicle": BTRAIN, "csv": text, "max_superelevation_percent": 8.0}).json()
    k1, k2 = out["vehicles"][0]["rows"]
    assert k1["superelevation_percent"] == 8.0 and k1["superelevation_source"] == "derived"
    assert k1["meets_standard_min_radius"] is False and k1["standard_min_radius_m"] == 229.0
    assert k1["side_friction_speed_kmh"] == pytest.approx(
        math.sqrt(127 * 150 * (0.08 + f_aashto(k1["side_friction_speed_kmh"]))), rel=1e-6
    )
    assert k1["flagged"]  # its safe speed is below the posted 80 km/h
    assert k2["meets_standard_min_radius"] is True and 0 < k2["superelevation_percent"] < 8.0


def test_a_missing_superelevation_without_e_max_is_refused_naming_the_curve(shared_client):
    body = {"vehicle": BTRAIN, "curves": [{"id": "D", "radius_m": 1000.0, "posted_speed_kmh": 80.0}]}
    p = post(shared_client, body, 422).json()
    assert p["errors"][0]["field"] == "curves.0.superelevation_percent" and "'D'" in p["detail"]


def test_side_friction_bound_applies_to_table21_only(shared_client):
    body = {"vehicle": BTRAIN, "curves": [{"id": "a", "radius_m": 200.0, "superelevation_percent": 4.0}]}
    p = post(shared_client, {**body, "design_standard": "aashto-2018", "side_friction_bound": "high"}, 422).json()
    assert p["errors"][0]["field"] == "side_friction_bound"
    out = post(shared_client, {**body, "design_standard": "thesis-table21", "side_friction_bound": "high"}).json()
    assert out["side_friction_bound"] == "high"
    # a bound alone selects the only standard that has one (the previous version's requests keep their meaning)
    alone = post(shared_client, {**body, "side_friction_bound": "high"}).json()
    assert alone["design_standard"] == "thesis-table21" and alone["vehicles"] == out["vehicles"]


# ------------------------------------------------------------------------------------------ streaming


def many_curves(n: int, seed: int = 3) -> list[dict]:
    rng = np.random.default_rng(seed)
    return [
        {
            "id": f"C{i}",
            "radius_m": float(np.round(rng.uniform(40, 2000), 2)),
            "superelevation_percent": float(rng.integers(0, 9)),
            "grade_percent": float(rng.integers(-6, 7)),
            **({"posted_speed_kmh": float(rng.choice([50, 70, 90]))} if i % 3 else {}),
        }
        for i in range(n)
    ]


@pytest.mark.parametrize("accept", ["application/json", "text/csv"])
def test_an_answer_of_several_chunks_is_one_whole_body_as_pydantic_writes(client, accept, monkeypatch):
    from app.alignments import rows

    monkeypatch.setattr(rows, "ROWS_PER_CHUNK", 1_000)  # chunks of a size the synchronous limit holds several of
    curves = many_curves(2 * rows.ROWS_PER_CHUNK + 700)  # two vehicles: chunks of each, the last ones short
    body = {"vehicles": [BTRAIN, "table23-semitrailer"], "curves": curves, "rear_llt_limit": 0.6}
    r = client.post(PATH, json=body, headers={"accept": accept})
    assert r.status_code == 200 and r.headers["x-cache"] == "miss"
    assert r.headers["content-length"] == str(len(r.content))
    again = client.post(PATH, json=body, headers={"accept": accept})
    assert (
        again.headers["x-cache"] == "hit" and again.content == r.content and again.headers["etag"] == r.headers["etag"]
    )
    if accept == "application/json":
        # byte for byte the document pydantic writes for the same result: the chunked renderer is not a variant
        assert AlignmentResult.model_validate_json(r.content).model_dump_json().encode() == r.content
        out = orjson.loads(r.content)
        assert [len(v["rows"]) for v in out["vehicles"]] == [len(curves)] * 2
    else:
        rows = list(csv.DictReader(io.StringIO(r.content.decode())))
        assert len(rows) == 2 * len(curves)
        assert rows[0]["id"] == "C0" and rows[len(curves)]["vehicle_index"] == "1"


def test_a_small_answer_is_the_same_bytes_as_pydantic_writes(shared_client):
    curves = [*many_curves(40, seed=5), {"id": "bad", "radius_m": 100.0, "superelevation_percent": -20.0}]
    body = {"vehicle": BTRAIN, "curves": curves, "load": {"lateral_offset_m": 0.3}, "rear_llt_limit": 0.6}
    r = post(shared_client, body)
    assert r.headers["content-length"] == str(len(r.content))
    assert AlignmentResult.model_validate_json(r.content).model_dump_json().encode() == r.content
    assert orjson.loads(r.content)["vehicles"][0]["rows"][-1]["error"]  # a refused row rendered too

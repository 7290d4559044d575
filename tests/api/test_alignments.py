"""POST /v1/alignments/assess through HTTP, against independent numbers.

* the rollover speed is sqrt(127 SRT R) (Eq. 9.1) with the SRT that /v1/srt gives on the curve's bank and grade;
* the side-friction speed solves V = sqrt(127 R (0.01 e + f(V))) with f from Table 21 (low bound, linear in V,
  AASHTO 2003 / DNIT 2009, restated here), clamped to the table's 30-120 km/h;
* safe = min of the two, margin = safe - posted, flagged iff margin < 0;
* curves sharing superelevation and grade share one SRT solve;
* the same curves as JSON, CSV and LandXML give the same rows.
"""

from __future__ import annotations

import csv
import dataclasses
import io
import math

import numpy as np
import orjson
import pytest

from app.alignments.rows import csv_columns, csv_rows, flatten_advice, json_rows
from app.alignments.rows import rows as _rows
from app.alignments.service import parse_json_request, resolve_alignment, solve_alignment
from app.formats.tables import Text, csv_lines_cellwise, flatten_targets
from app.settings import Settings
from app.vehicles.resolve import resolve_request_given

BTRAIN = "table16-btrain"
PATH = "/v1/alignments/assess"

# Table 21, low bound: design speed [km/h] -> f
TABLE21_LOW = {30: 0.17, 40: 0.17, 50: 0.16, 60: 0.15, 70: 0.14, 80: 0.14, 90: 0.13, 100: 0.12, 110: 0.11, 120: 0.09}


def f_low(v: float) -> float:
    v = min(max(v, 30.0), 120.0)
    speeds = sorted(TABLE21_LOW)
    return float(np.interp(v, speeds, [TABLE21_LOW[s] for s in speeds]))


def same_targets(a: list[dict], b: list[dict]) -> bool:
    """Equal target checks, margins to 1e-9 g (a batch solve and a single one agree to round-off)."""
    return [(t["name"], t["target_g"], t["meets"]) for t in a] == [
        (t["name"], t["target_g"], t["meets"]) for t in b
    ] and all(x["margin_g"] == pytest.approx(y["margin_g"], abs=1e-9) for x, y in zip(a, b, strict=True))


def post(client, body, status=200, **kwargs):
    r = client.post(PATH, json=body, **kwargs)
    assert r.status_code == status, r.text
    return r


def rows_of(out, vehicle=0):
    return out["vehicles"][vehicle]["rows"]


CURVES = [
    {"id": "C1", "radius_m": 120.0, "superelevation_percent": 8.0, "grade_percent": -4.0, "posted_speed_kmh": 70.0},
    {"id": "C2", "radius_m": 350.0, "superelevation_percent": 6.0, "grade_percent": 0.0, "posted_speed_kmh": 90.0},
    {"id": "C3", "radius_m": 600.0, "superelevation_percent": 8.0, "grade_percent": -4.0, "posted_speed_kmh": 100.0},
    {"id": "C4", "radius_m": 20.0, "superelevation_percent": 2.0, "grade_percent": 3.0},  # tighter than Table 21
    {"id": "C5", "radius_m": 2500.0, "superelevation_percent": 6.0, "grade_percent": 0.0, "posted_speed_kmh": 110.0},
]
# the thesis's Table 21 at its low bound (the assessment's checks below use TABLE21_LOW)
BASE = {"vehicle": BTRAIN, "rear_llt_limit": 0.6, "curves": CURVES, "design_standard": "thesis-table21"}


@pytest.fixture(scope="module")
def assessed(shared_client):
    return post(shared_client, BASE).json()


def test_rollover_speed_is_eq_9_1_with_the_srt_on_that_bank_and_grade(shared_client, assessed):
    for row, curve in zip(rows_of(assessed), CURVES, strict=True):
        road = {"bank_percent": curve["superelevation_percent"], "slope_percent": curve["grade_percent"]}
        single = shared_client.post("/v1/srt", json={"vehicle": BTRAIN, "rear_llt_limit": 0.6, "road": road}).json()
        assert row["srt_g"] == pytest.approx(single["srt"], rel=1e-9)
        assert row["rollover_speed_kmh"] == pytest.approx(math.sqrt(127 * single["srt"] * curve["radius_m"]), rel=1e-9)
        assert same_targets(row["targets"], single["targets"])
        assert row["tilt_table_angle_deg"] == pytest.approx(math.degrees(math.atan(row["srt_g"])), rel=1e-12)
    # Table 17: 0.285 g on an 8 % bank, flat, LLT 0.6; 4 % downhill lowers it
    assert rows_of(assessed)[0]["srt_g"] < 0.285


def test_side_friction_speed_solves_its_implicit_equation_with_table21(assessed):
    for row, curve in zip(rows_of(assessed), CURVES, strict=True):
        v, r, e = row["side_friction_speed_kmh"], curve["radius_m"], curve["superelevation_percent"]
        f = f_low(v)
        assert row["side_friction"] == pytest.approx(f, abs=1e-12)
        assert v == pytest.approx(math.sqrt(127 * r * (0.01 * e + f)), rel=1e-9)
    tight, wide = rows_of(assessed)[3], rows_of(assessed)[4]
    assert tight["side_friction_speed_kmh"] < 30 and tight["side_friction"] == 0.17  # clamped to f(30)
    assert wide["side_friction_speed_kmh"] > 120 and wide["side_friction"] == 0.09  # clamped to f(120)


def test_safe_speed_governing_margin_and_flag(assessed):
    for row, curve in zip(rows_of(assessed), CURVES, strict=True):
        roll, fric = row["rollover_speed_kmh"], row["side_friction_speed_kmh"]
        assert row["safe_speed_kmh"] == min(roll, fric)
        assert row["governed_by"] == ("rollover" if roll < fric else "side-friction")
        posted = curve.get("posted_speed_kmh")
        assert row["posted_speed_kmh"] == posted
        if posted is None:
            assert row["margin_kmh"] is None and row["flagged"] is False
        else:
            assert row["margin_kmh"] == pytest.approx(row["safe_speed_kmh"] - posted, abs=1e-12)
            assert row["flagged"] == (row["margin_kmh"] < 0)
    flags = [r["flagged"] for r in rows_of(assessed)]
    assert any(flags) and not all(flags)  # the data exercise both branches
    summary = assessed["vehicles"][0]["summary"]
    assert summary["curves"] == 5 and summary["flagged"] == sum(flags) and summary["refused"] == 0
    margins = [r["margin_kmh"] for r in rows_of(assessed) if r["margin_kmh"] is not None]
    assert summary["min_margin_kmh"] == min(margins)
    assert summary["min_safe_speed_kmh"] == min(r["safe_speed_kmh"] for r in rows_of(assessed))


def test_curves_sharing_bank_and_grade_share_one_solve(assessed):
    rows = rows_of(assessed)
    assert rows[0]["srt_g"] == rows[2]["srt_g"]  # C1 and C3: 8 % / -4 %, radii 120 and 600 m
    assert rows[1]["srt_g"] == rows[4]["srt_g"]  # C2 and C5: 6 % / 0 %
    assert assessed["vehicles"][0]["summary"]["distinct_srt_solves"] == 3  # (8, -4), (6, 0), (2, 3)


def test_rollover_governs_a_high_load_on_a_tight_curve(shared_client):
    # the B-train with its CG 0.5 m higher (LLT 0.6): one SRT, but f(V) rises as V falls, so side friction governs
    # the 300 m curve and rollover the 60 m one
    body = {
        "vehicle": BTRAIN,
        "rear_llt_limit": 0.6,
        "load": {"vertical_offset_m": 0.5},
        "design_standard": "thesis-table21",
        "curves": [
            {"id": "wide", "radius_m": 300.0, "superelevation_percent": 4.0},
            {"id": "tight", "radius_m": 60.0, "superelevation_percent": 4.0},
        ],
    }
    out = post(shared_client, body).json()
    wide, tight = rows_of(out)
    assert wide["srt_g"] == tight["srt_g"]
    assert (wide["governed_by"], tight["governed_by"]) == ("side-friction", "rollover")
    # rollover governs iff SRT < 0.01 e + f(V) at the side-friction speed (Eq. 9.1 against Eq. 9.2)
    assert tight["srt_g"] < 0.04 + f_low(tight["side_friction_speed_kmh"])
    assert wide["srt_g"] > 0.04 + f_low(wide["side_friction_speed_kmh"])
    s = out["vehicles"][0]["summary"]
    assert (s["governed_by_rollover"], s["governed_by_side_friction"], s["distinct_srt_solves"]) == (1, 1, 1)


def to_csv_text(curves) -> str:
    lines = ["id,radius_m,superelevation_percent,grade_percent,posted_speed_kmh"]
    for c in curves:
        posted = c.get("posted_speed_kmh")
        lines.append(
            f"{c['id']},{c['radius_m']},{c['superelevation_percent']},{c.get('grade_percent', 0)},"
            f"{'' if posted is None else posted}"
        )
    return "\n".join(lines) + "\n"


def to_landxml(curves) -> str:
    items = "".join(
        f'<Curve rot="cw" radius="{c["radius_m"]}" length="50" staStart="{100 * k}" name="{c["id"]}"/>'
        for k, c in enumerate(curves)
    )
    return (
        '<?xml version="1.0"?><LandXML xmlns="http://www.landxml.org/schema/LandXML-1.2" version="1.2">'
        f'<Alignments><Alignment name="A1"><CoordGeom>{items}</CoordGeom></Alignment></Alignments></LandXML>'
    )


ADVICE_FIELDS = (
    "advisory_speed_kmh",
    "treatment",
    "truck_rollover_warning",
    "approach_speed_kmh",
    "required_deceleration_mps2",
    "profile_reason",
)


def test_csv_and_landxml_give_the_same_rows_as_json(shared_client, assessed):
    table21 = {"design_standard": "thesis-table21"}
    by_csv = post(shared_client, {"vehicle": BTRAIN, "rear_llt_limit": 0.6, "csv": to_csv_text(CURVES), **table21})
    # the same rows; the CSV answer also names the dialect it was read in (and so has a key of its own)
    assert by_csv.json()["csv_dialect"] == {"separator": ",", "decimal": ".", "bom": False, "line_ending": "LF"}
    assert {**by_csv.json(), "csv_dialect": None} == assessed
    # the same curves in the same dialect resolve to the same request: one cache entry, one ETag
    again = post(shared_client, {"vehicle": BTRAIN, "rear_llt_limit": 0.6, "csv": to_csv_text(CURVES), **table21})
    assert by_csv.headers["etag"] == again.headers["etag"] and again.headers["x-cache"] == "hit"
    overrides = {
        c["id"]: {
            "superelevation_percent": c["superelevation_percent"],
            "grade_percent": c["grade_percent"],
            **({"posted_speed_kmh": c["posted_speed_kmh"]} if "posted_speed_kmh" in c else {}),
        }
        for c in CURVES
    }
    landxml = {"document": to_landxml(CURVES), "curve_overrides": overrides}
    by_xml = post(shared_client, {"vehicle": BTRAIN, "rear_llt_limit": 0.6, "landxml": landxml, **table21}).json()
    # a road file's rows add the bend's facts (each curve here an arc of 50 m turning right, one after another)
    bend = ("station_m", "distance_m", "bend_start_m", "bend_end_m", "direction", "arc_length_m", "deflection_deg")
    bend += ("spiral_in_m", "spiral_out_m", "compound", "reverse", "grade_min_percent", "grade_max_percent")
    for x, j, k in zip(rows_of(by_xml), rows_of(assessed), range(5), strict=True):
        assert x["station_m"] == 100.0 * k and all(j[name] is None for name in bend)
        assert (x["distance_m"], x["arc_length_m"], x["direction"]) == (50.0 * k, 50.0, "right")
        assert x["deflection_deg"] == pytest.approx(math.degrees(50.0 / x["radius_m"]), rel=1e-12)
        assert x["grade_source"] == j["grade_source"] == "request"
        # the advice differs by design: the file's stations place the curves (a profile, and curves within 600 ft
        # sharing one sign: TxDOT), its deflections enter the Design Method; JSON curves have no stations
        assert j["approach_speed_kmh"] is None and j["profile_reason"] is not None
        assert (x["approach_speed_kmh"] is None) == (x["profile_reason"] is not None)
        assert {**x, **dict.fromkeys(bend + ADVICE_FIELDS)} == {**j, **dict.fromkeys(ADVICE_FIELDS)}


def test_landxml_defaults_apply_to_every_curve(shared_client):
    landxml = {"document": to_landxml(CURVES[:2]), "superelevation_percent": 6.0, "grade_percent": -2.0}
    out = post(shared_client, {"vehicle": BTRAIN, "landxml": landxml}).json()
    assert [(r["superelevation_percent"], r["grade_percent"], r["posted_speed_kmh"]) for r in rows_of(out)] == [
        (6.0, -2.0, None),
        (6.0, -2.0, None),
    ]


def test_several_vehicles_each_get_every_curve(shared_client):
    two = post(shared_client, {"vehicles": [BTRAIN, "table23-semitrailer"], "rear_llt_limit": 0.6, "curves": CURVES})
    out = two.json()
    assert [(v["index"], v["preset"]) for v in out["vehicles"]] == [(0, BTRAIN), (1, "table23-semitrailer")]
    alone = post(shared_client, {"vehicle": "table23-semitrailer", "rear_llt_limit": 0.6, "curves": CURVES}).json()
    assert rows_of(out, 1) == rows_of(alone)
    assert rows_of(out, 0)[0]["srt_g"] != rows_of(out, 1)[0]["srt_g"]


def test_csv_answer_has_a_header_and_a_row_per_vehicle_and_curve(shared_client):
    body = {"vehicles": [BTRAIN, "table23-semitrailer"], "rear_llt_limit": 0.6, "curves": CURVES}
    as_json = post(shared_client, body).json()
    r = post(shared_client, body, headers={"Accept": "text/csv"})
    assert r.headers["content-type"].startswith("text/csv") and r.headers["vary"] == "Accept"
    table = list(csv.DictReader(io.StringIO(r.text)))
    assert list(table[0])[:5] == ["vehicle_index", "vehicle_preset", "vehicle_saved_id", "id", "station_m"]
    assert {"srt_g", "rollover_speed_kmh", "side_friction_speed_kmh", "safe_speed_kmh", "margin_kmh"} <= set(table[0])
    assert {"meets_general", "margin_general_g", "meets_dangerous_goods", "margin_dangerous_goods_g"} <= set(table[0])
    assert len(table) == 2 * len(CURVES)
    for got, (k, want) in zip(table, [(v["index"], r) for v in as_json["vehicles"] for r in v["rows"]], strict=True):
        assert int(got["vehicle_index"]) == k and got["id"] == want["id"]
        assert float(got["safe_speed_kmh"]) == want["safe_speed_kmh"]
        assert got["flagged"] == ("true" if want["flagged"] else "false")
        assert got["posted_speed_kmh"] == ("" if want["posted_speed_kmh"] is None else repr(want["posted_speed_kmh"]))


def test_a_refused_case_keeps_its_row(shared_client):
    # an adverse 20 % crossfall with a rear LLT limit of 0.2: the limit is passed at rest, no SRT; the row stays
    body = {
        "vehicle": BTRAIN,
        "rear_llt_limit": 0.2,
        "curves": [
            {"id": "ok", "radius_m": 200.0, "superelevation_percent": 6.0},
            {"id": "adverse", "radius_m": 200.0, "superelevation_percent": -20.0, "posted_speed_kmh": 50.0},
        ],
    }
    out = post(shared_client, body).json()
    ok, bad = rows_of(out)
    assert ok["srt_g"] > 0 and ok["error"] is None
    assert bad["srt_g"] is None and bad["safe_speed_kmh"] is None and bad["targets"] == []
    assert "at rest" in bad["error"]
    assert out["vehicles"][0]["summary"]["refused"] == 1


def test_cached_by_the_curves(client):
    first = post(client, BASE)
    assert first.headers["x-cache"] == "miss" and post(client, BASE).headers["x-cache"] == "hit"
    changed = {**BASE, "curves": [{**CURVES[0], "radius_m": 121.0}, *CURVES[1:]]}
    other = post(client, changed)
    assert other.headers["x-cache"] == "miss" and other.headers["etag"] != first.headers["etag"]


# ------------------------------------------------------------------------------------------ errors


def problem(r, status=422):
    assert r.status_code == status, r.text
    assert r.headers["content-type"] == "application/problem+json"
    return r.json()


@pytest.mark.parametrize(
    ("body", "field"),
    [
        ({"vehicle": BTRAIN, "curves": [{**CURVES[0], "radius_m": 0}]}, "curves.0.radius_m"),
        ({"vehicle": BTRAIN, "curves": [CURVES[0], {**CURVES[1], "id": "C1"}]}, "curves.1.id"),
        ({"vehicle": BTRAIN, "curves": CURVES, "csv": "id,radius_m,superelevation_percent\nA,1,1\n"}, "csv"),
        ({"vehicle": BTRAIN}, "curves"),
        ({"vehicle": BTRAIN, "vehicles": [BTRAIN], "curves": CURVES}, "vehicles"),
        ({"curves": CURVES}, "vehicle"),
        ({"vehicles": [BTRAIN] * 11, "curves": CURVES}, "vehicles"),
        ({"vehicle": BTRAIN, "curves": CURVES, "road": {"bank_percent": 4}}, "road"),
    ],
)
def test_request_errors_name_the_field(shared_client, body, field):
    p = problem(shared_client.post(PATH, json=body))
    assert field in [e["field"] for e in p["errors"]], p


@pytest.mark.parametrize(
    ("text", "location", "field", "words"),
    [
        ("id,radius_m,superelevation_percent\nA,100,2\nB,0,3\n", "row 3", "csv.radius_m", "outside [5, 100000] m"),
        ("id,radius_m,grade_percent\nA,100,2\n", "row 2", "csv.superelevation_percent", "max_superelevation_percent"),
        ("id,grade_percent\nA,2\n", "row 1 (header)", "csv.radius_m", "missing column"),
        ("id,radius_m,superelevation_percent\nA,100,2\nB,100\n", "row 3", "csv", "has 2 fields"),
        ("id,radius_m,superelevation_percent\nA,abc,2\n", "row 2", "csv.radius_m", "not a number"),
        ("id,radius_m,superelevation_percent,posted_speed_kmh\nA,100,2,250\n", "row 2", "csv.posted_speed_kmh", "200"),
    ],
)
def test_csv_errors_name_the_row_and_column(shared_client, text, location, field, words):
    p = problem(shared_client.post(PATH, json={"vehicle": BTRAIN, "csv": text}))
    assert p["type"] == "urn:rollover:problem:invalid-alignment"
    (error,) = p["errors"]
    assert (error["location"], error["field"]) == (location, field)
    assert words in error["message"] and location in p["detail"]


@pytest.mark.parametrize(
    ("landxml", "location", "field"),
    [
        ({"document": "<LandXML><Alignments><Alignment", "superelevation_percent": 4}, "LandXML line 1, column ",
         "landxml.document"),
        ({"document": to_landxml(CURVES[:2]).replace('radius="350.0" ', ""), "superelevation_percent": 4},
         "Alignment 'A1' CoordGeom Curve #2 ('C2')", "landxml.document.radius"),
        ({"document": to_landxml(CURVES[:2]).replace('radius="350.0"', 'radius="0"'), "superelevation_percent": 4},
         "Alignment 'A1' CoordGeom Curve #2 ('C2')", "landxml.document.radius"),
        ({"document": to_landxml(CURVES[:2])}, "Alignment 'A1' CoordGeom Curve #1 ('C1')",
         "landxml.document.superelevation_percent"),
        ({"document": to_landxml(CURVES[:2]), "superelevation_percent": 4, "curve_overrides": {"K9": {}}}, None,
         "landxml.curve_overrides"),
        ({"document": "<Foo/>", "superelevation_percent": 4}, "LandXML", "landxml.document"),
    ],
)  # fmt: skip
def test_landxml_errors_name_the_element(shared_client, landxml, location, field):
    p = problem(shared_client.post(PATH, json={"vehicle": BTRAIN, "landxml": landxml}))
    assert p["type"] == "urn:rollover:problem:invalid-alignment"
    (error,) = p["errors"]
    assert error["field"] == field
    if location is None:
        assert error["location"] is None and "K9" in error["message"]
    else:
        assert error["location"].startswith(location)


def test_an_engine_refusal_names_the_vehicle_among_several(shared_client):
    # the 3d model needs the front group that the 2D Table 14 record leaves null
    p = problem(shared_client.post(PATH, json={"vehicles": [BTRAIN, "table14-semitrailer"], "curves": CURVES}))
    assert p["type"] == "urn:rollover:problem:missing-parameter"
    assert p["errors"][0]["field"] == "vehicles.1.front_track_m"


def test_too_many_rows(shared_client):
    # 1,001 curves (within the curve limit) of 10 vehicles: 10,010 rows, past the rows'
    text = "id,radius_m,superelevation_percent\n" + "".join(f"C{i},100,{i % 10}\n" for i in range(1_001))
    p = problem(shared_client.post(PATH, json={"vehicles": [BTRAIN] * 10, "csv": text}))
    assert p["errors"][0]["field"] == "vehicles" and "10010 rows; at most 10000" in p["errors"][0]["message"]


# ------------------------------------------------------------------------------- raw file uploads


def upload(client, kind, text, query, status=200, **headers):
    content_type = {"csv": "text/csv", "landxml": "application/xml"}[kind]
    data = text if isinstance(text, bytes) else text.encode()
    r = client.post(f"{PATH}/{kind}?{query}", content=data, headers={"Content-Type": content_type, **headers})
    assert r.status_code == status, r.text
    return r


def test_a_csv_upload_is_the_json_csv_request(shared_client, assessed):
    # a spreadsheet's UTF-8 BOM is not part of the first column's name
    query = "vehicle=table16-btrain&rear_llt_limit=0.6&design_standard=thesis-table21"
    r = upload(shared_client, "csv", "\ufeff" + to_csv_text(CURVES), query)
    assert r.json()["csv_dialect"]["bom"] is True
    assert {**r.json(), "csv_dialect": None} == assessed
    json_csv = {**BASE, "curves": None, "csv": "\ufeff" + to_csv_text(CURVES)}
    json_csv.pop("curves")
    assert r.headers["etag"] == post(shared_client, json_csv).headers["etag"]  # one cache entry for both forms
    as_csv = upload(shared_client, "csv", to_csv_text(CURVES), query, Accept="text/csv")
    assert as_csv.headers["content-type"].startswith("text/csv") and len(as_csv.text.splitlines()) == 1 + len(CURVES)


def test_a_landxml_upload_takes_the_defaults_from_the_query(shared_client):
    query = "vehicle=table16-btrain&vehicle=table23-semitrailer&superelevation_percent=6&grade_percent=-2"
    raw = upload(shared_client, "landxml", to_landxml(CURVES[:2]), query).json()
    landxml = {"document": to_landxml(CURVES[:2]), "superelevation_percent": 6.0, "grade_percent": -2.0}
    body = {"vehicles": [BTRAIN, "table23-semitrailer"], "landxml": landxml}
    assert raw == post(shared_client, body).json()
    assert [(v["preset"], len(v["rows"])) for v in raw["vehicles"]] == [(BTRAIN, 2), ("table23-semitrailer", 2)]
    assert [r["station_m"] for r in rows_of(raw)] == [0.0, 100.0]


@pytest.mark.parametrize(
    ("kind", "text", "query", "field", "location"),
    [
        ("csv", "id,radius_m,superelevation_percent\nA,100,2\nB,0,3\n", "vehicle=table16-btrain", "body.radius_m",
         "row 3"),
        ("csv", "id,radius_m\nA,100\n", "vehicle=table16-btrain", "body.superelevation_percent", "row 2"),
        ("csv", b"id,radius_m,superelevation_percent\nA,100,\xff\n", "vehicle=table16-btrain", "body", None),
        ("csv", "", "vehicle=table16-btrain", "body", None),
        ("landxml", "<LandXML><Alignments><Alignment", "vehicle=table16-btrain&superelevation_percent=4", "body",
         "LandXML line 1, column "),
        ("landxml", to_landxml(CURVES[:1]), "vehicle=table16-btrain", "body.superelevation_percent",
         "Alignment 'A1' CoordGeom Curve #1 ('C1')"),
    ],
)  # fmt: skip
def test_upload_errors_name_the_row_or_element(shared_client, kind, text, query, field, location):
    p = problem(upload(shared_client, kind, text, query, 422))
    assert p["type"] == "urn:rollover:problem:invalid-alignment"
    (error,) = p["errors"]
    assert error["field"] == field and error["loc"] == ["body"]
    if location is None:
        assert error["location"] is None
    else:
        assert error["location"].startswith(location)


@pytest.mark.parametrize(
    ("kind", "query", "field", "words"),
    [
        ("csv", "rear_llt_limit=0.6", "vehicle", "Field required"),
        ("csv", "vehicle=table16-btrain&superelevation_percent=4", "superelevation_percent", "Extra inputs"),
        ("csv", "vehicle=table16-btrain&rear_llt_limit=abc", "rear_llt_limit", "valid number"),
        ("csv", "vehicle=table16-btrain&lateral_offset_m=nan", "lateral_offset_m", "finite number"),
        ("landxml", "vehicle=table16-btrain&posted_speed_kmh=300", "posted_speed_kmh", "less than or equal to 200"),
        ("csv", "&".join(["vehicle=table16-btrain"] * 11), "vehicle", "at most 10"),
    ],
)
def test_upload_query_errors_name_the_parameter(shared_client, kind, query, field, words):
    text = to_csv_text(CURVES) if kind == "csv" else to_landxml(CURVES)
    p = problem(upload(shared_client, kind, text, query, 422))
    errors = {e["field"]: (e["message"], e["loc"]) for e in p["errors"]}
    assert field in errors, errors
    assert words in errors[field][0] and errors[field][1] == ["query", field]


# ------------------------------------------------------------------------------------ hostile curve ids

FORMULAS = ['=HYPERLINK("http://x","y")', "+1+1", "-2+3", "@SUM(A1:A2)"]


def test_csv_answers_neutralise_spreadsheet_formulas_in_ids(shared_client):
    """OWASP CSV injection: a cell that begins with = + - @ is prefixed with a quote (and quoted), so a spreadsheet
    shows it as text; numbers (a negative grade) are left alone."""
    import csv as csvmod
    import io

    curves = [{"id": f, "radius_m": 150.0, "superelevation_percent": 6.0, "grade_percent": -2.0} for f in FORMULAS]
    buf = io.StringIO()
    writer = csvmod.writer(buf)
    writer.writerow(["id", "radius_m", "superelevation_percent", "grade_percent"])
    writer.writerows([c["id"], 150, 6, -2] for c in curves)
    for body in ({"vehicle": BTRAIN, "curves": curves}, {"vehicle": BTRAIN, "csv": buf.getvalue()}):
        r = shared_client.post(PATH, json=body, headers={"accept": "text/csv"})
        assert r.status_code == 200, r.text
        rows = list(csvmod.DictReader(io.StringIO(r.text)))
        assert [row["id"] for row in rows] == ["'" + f for f in FORMULAS]
        assert all(row["grade_percent"] == "-2.0" for row in rows)
        for line in r.text.splitlines()[1:]:
            assert not line.startswith(("=", "+", "-", "@"))


@pytest.mark.parametrize("bad", ["a\x00b", "\x1b[31mred", "tab\tbed", "cr\rid", "\x9bcsi"])
def test_control_characters_are_refused_in_ids_in_every_form(shared_client, bad):
    # JSON: the schema's pattern; CSV and LandXML: the readers, naming the row / element
    p = problem(
        shared_client.post(
            PATH, json={"vehicle": BTRAIN, "curves": [{"id": bad, "radius_m": 100.0, "superelevation_percent": 4.0}]}
        )
    )
    assert p["errors"][0]["field"] == "curves.0.id"
    csv_text = "id,radius_m,superelevation_percent\n" + f'"{bad}",100,4\n'
    p = problem(shared_client.post(PATH, json={"vehicle": BTRAIN, "csv": csv_text}))
    assert p["errors"][0]["location"] == "row 2" and "control character" in p["errors"][0]["message"]
    # in XML a literal tab in an attribute is normalised to a space: a real one is written as a reference
    escaped = "".join(f"&#{ord(ch)};" if ord(ch) < 32 or 0x7F <= ord(ch) <= 0x9F else ch for ch in bad)
    doc = to_landxml([{"id": "K1", "radius_m": 100.0, "superelevation_percent": 4.0}]).replace(
        'name="K1"', f'name="{escaped}"'
    )
    r = shared_client.post(PATH, json={"vehicle": BTRAIN, "landxml": {"document": doc, "superelevation_percent": 4.0}})
    assert r.status_code == 422


@pytest.mark.parametrize("form", ["json", "csv", "landxml"])
def test_one_id_length_limit_in_every_form(shared_client, form):
    long_id = "K" * 101
    curve = {"id": long_id, "radius_m": 100.0, "superelevation_percent": 4.0}
    body = {
        "json": {"vehicle": BTRAIN, "curves": [curve]},
        "csv": {"vehicle": BTRAIN, "csv": to_csv_text([curve])},
        "landxml": {"vehicle": BTRAIN, "landxml": {"document": to_landxml([curve]), "superelevation_percent": 4.0}},
    }[form]
    p = problem(shared_client.post(PATH, json=body))
    assert "100" in p["errors"][0]["message"]
    ok = {**curve, "id": "K" * 100}
    body100 = {
        "json": {"vehicle": BTRAIN, "curves": [ok]},
        "csv": {"vehicle": BTRAIN, "csv": to_csv_text([ok])},
        "landxml": {"vehicle": BTRAIN, "landxml": {"document": to_landxml([ok]), "superelevation_percent": 4.0}},
    }[form]
    assert shared_client.post(PATH, json=body100).status_code == 200


@pytest.mark.parametrize("radius", ["1e308", "1e-320", "4.9", "inf"])
@pytest.mark.parametrize("form", ["csv", "landxml"])
def test_uploads_apply_the_json_forms_bounds(shared_client, radius, form):
    """A radius the JSON form refuses is refused in the uploads too, with the row or element, never a 500 or an
    absurd speed (1e308 used to overflow to inf; 1e-320 used to give 5e-160 km/h)."""
    if form == "csv":
        text = f"id,radius_m,superelevation_percent\nK1,{radius},4\n"
        r = shared_client.post(f"{PATH}/csv?vehicle={BTRAIN}", content=text, headers={"content-type": "text/csv"})
    else:
        doc = to_landxml([{"id": "K1", "radius_m": 100.0, "superelevation_percent": 4.0}]).replace(
            'radius="100.0"', f'radius="{radius}"'
        )
        r = shared_client.post(
            f"{PATH}/landxml?vehicle={BTRAIN}&superelevation_percent=4",
            content=doc,
            headers={"content-type": "application/xml"},
        )
    p = problem(r)
    assert p["errors"][0]["field"] in ("body.radius_m", "body.radius")
    json_form = (
        shared_client.post(
            PATH,
            json={
                "vehicle": BTRAIN,
                "curves": [{"id": "K1", "radius_m": float(radius), "superelevation_percent": 4.0}],
            },
        )
        if radius != "inf"
        else None
    )
    if json_form is not None:
        assert json_form.status_code == 422


def _every_kind_of_row():
    """An answer of two vehicles over rows of every kind: given and derived superelevation, with and without a
    posted speed, a station or none, refused (no SRT: no targets, no speeds, an error), a curve below the standard's
    minimum radius, three targets (two equal), an id that needs quoting."""
    curves = [
        {"id": "C1", "radius_m": 120.0, "superelevation_percent": 8.0, "grade_percent": -4.0, "posted_speed_kmh": 70.0},
        {"id": "C2", "radius_m": 350.0, "posted_speed_kmh": 90.0},  # derived from the distribution (e_max given)
        {"id": 'C,"3"', "radius_m": 600.0, "superelevation_percent": 8.0, "grade_percent": -4.0},  # no posted speed
        # adverse crossfall past the rear LLT limit at rest: refused
        {"id": "C4", "radius_m": 200.0, "superelevation_percent": -20.0, "posted_speed_kmh": 50.0},
        {"id": "=C5", "radius_m": 25.0, "superelevation_percent": 2.0, "grade_percent": 3.0, "posted_speed_kmh": 80.0},
    ]
    body = {
        "vehicles": [BTRAIN, "table23-semitrailer"],
        "rear_llt_limit": 0.2,
        "max_superelevation_percent": 8.0,
        "targets": {"a": 0.3, "b": 0.45, "c": 0.3},
        "curves": curves,
    }
    req, table = parse_json_request(orjson.dumps(body))
    table = dataclasses.replace(table, station_m=np.array([0.0, 150.5, np.nan, 900.0, 1200.0]))  # as from LandXML
    return solve_alignment(resolve_alignment(resolve_request_given(req), table, Settings()))


def test_csv_written_by_blocks_of_columns_is_the_rows_written_cell_by_cell():
    """The CSV writer (app.alignments.rows.csv_rows: blocks of number columns in one call, the flags, texts and target
    checks written once) against the cell-by-cell reference (app.formats.tables.csv_lines_cellwise) of the rows as
    dicts with their targets flattened, on rows of every kind, whole and sliced."""
    answer = _every_kind_of_row()
    columns = csv_columns(answer.resolved)
    for v in answer.vehicles:
        for start, stop in ((0, 5), (1, 4), (4, 5)):
            flat = [flatten_targets(flatten_advice(r)) for r in _rows(answer, v, start, stop)]
            extra = {"vehicle_index": v.index, "vehicle_preset": Text(v.preset), "vehicle_saved_id": None}
            cells = [[extra[c] if c in extra else r.get(c) for r in flat] for c in columns]
            cells = [[Text(x) if isinstance(x, str) else x for x in col] for col in cells]
            assert csv_rows(answer, v, start, stop, columns) == csv_lines_cellwise(cells)
    rows = list(csv.reader(io.StringIO(csv_rows(answer, answer.vehicles[0], 0, 5, columns).decode())))
    assert rows[4][columns.index("id")] == "'=C5" and rows[2][columns.index("id")] == 'C,"3"'
    assert rows[3][columns.index("srt_g")] == "" and rows[3][columns.index("error")]


def test_rows_written_by_columns_are_the_rows_as_dicts_byte_for_byte():
    """The JSON writer (app.alignments.rows.json_rows: column by column, a nan written as null, the texts, flags and
    target checks written once) against orjson's JSON of the rows as dicts (the form the routes and the schema use),
    on rows of every kind (:func:`_every_kind_of_row`)."""
    answer = _every_kind_of_row()
    for v in answer.vehicles:
        rows = _rows(answer, v, 0, 5)
        assert json_rows(answer, v, 0, 5) == orjson.dumps(rows)[1:-1]
        assert json_rows(answer, v, 1, 4) == orjson.dumps(rows[1:4])[1:-1]
        assert rows[1]["superelevation_source"] == "derived" and rows[2]["station_m"] is None
        assert rows[3]["error"] and rows[3]["targets"] == [] and rows[3]["tilt_table_angle_deg"] is None
        assert rows[4]["meets_standard_min_radius"] is False and rows[0]["meets_standard_min_radius"] is not None
        assert [t["name"] for t in rows[0]["targets"]] == ["a", "c", "b"]

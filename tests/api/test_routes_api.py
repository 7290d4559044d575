"""POST /v1/routes/assess on synthetic routes laid out exactly (tests/synthetic_routes.py: tangents, clothoids and
arcs put on the WGS84 ellipsoid with GeographicLib's geodesic direct problem), with GPS-like noise.

Expected numbers are the designed radii, chainages and grades of the synthetic route, and the alignment endpoint's
own answer for the same curve (a curve gets the same assessment from geometry as from a table).
"""

from __future__ import annotations

import csv
import io
import math

import numpy as np
import pytest

from engine.road import max_curve_speed_kmh
from tests.api.conftest import ROOT
from tests.synthetic_routes import Arc, Tangent, curve_spans, gauss_markov, layout, spiral_curve, to_lonlat

PATH = "/v1/routes/assess"
BTRAIN = "table16-btrain"
# 4 km: a 250 m left curve with 60 m spirals and a 600 m right curve, between tangents. The arcs are long enough
# for 5 % with 3 m of noise at 10 m spacing: a circle fit over an arc of length L with n vertices has a curvature
# standard error of about 2 sigma sqrt(180 / n) / L^2 (least squares of the middle ordinate), 4.8 % of 1/600 m for a
# 400 m arc but 0.9 % for 800 m
ELEMENTS = [
    Tangent(800.0),
    *spiral_curve(250.0, 300.0, 60.0, "left"),
    Tangent(700.0),
    Arc(600.0, 800.0, "right"),
    Tangent(1300.0),
]
GRADE = 0.03  # a steady 3 % climb in the direction of travel


def route(lat0: float, noise_m: float = 0.0, spacing_m: float = 10.0, seed: int = 1) -> list[list[float]]:
    x, y, s = layout(ELEMENTS, spacing_m)
    rng = np.random.default_rng(seed)
    x, y = x + rng.normal(0, noise_m, x.size), y + rng.normal(0, noise_m, y.size)
    lon, lat = to_lonlat(x, y, lat0)
    z = 300.0 + GRADE * s
    return [[float(a), float(b), float(c)] for a, b, c in zip(lon, lat, z, strict=True)]


def feature_collection(coords, **props) -> dict:
    geometry = {"type": "LineString", "coordinates": coords}
    return {"type": "FeatureCollection", "features": [{"type": "Feature", "properties": props, "geometry": geometry}]}


def gpx(coords) -> str:
    points = "".join(f'<trkpt lat="{la!r}" lon="{lo!r}"><ele>{z!r}</ele></trkpt>' for lo, la, z in coords)
    return f'<gpx version="1.1" xmlns="http://www.topografix.com/GPX/1/1"><trk><name>R</name><trkseg>{points}</trkseg></trk></gpx>'


def post(client, body, status=200, **headers):
    r = client.post(PATH, json=body, headers=headers)
    assert r.status_code == status, r.text
    return r


@pytest.mark.parametrize(("lat0", "noise", "tolerance"), [(45.0, 0.0, 0.01), (-35.0, 2.5, 0.05), (60.0, 3.0, 0.05)])
def test_curves_found_with_their_radius_chainage_direction_and_grade(shared_client, lat0, noise, tolerance):
    body = {"vehicle": BTRAIN, "geojson": feature_collection(route(lat0, noise)), "superelevation_percent": 6.0}
    out = post(shared_client, body).json()
    curves = out["curves"]
    assert [c["direction"] for c in curves] == ["left", "right"]  # no phantom curve on the tangents
    for c, radius, (start, end) in zip(curves, (250.0, 600.0), curve_spans(ELEMENTS), strict=True):
        assert c["radius_m"] == pytest.approx(radius, rel=tolerance)
        assert c["grade_percent"] == pytest.approx(100 * GRADE, abs=0.3)
        assert c["start_m"] == pytest.approx(start, abs=60) and c["end_m"] == pytest.approx(end, abs=60)
    assert out["length_m"] == pytest.approx(sum(e.length_m for e in ELEMENTS), rel=0.01)
    # each curve's vertices are the route's own over the curve
    first = curves[0]
    assert (
        len(first["coordinates"]) >= 3 and len(first["coordinates"]) == first["vertices"][1] - first["vertices"][0] + 1
    )


def test_each_part_names_its_noise_and_whether_it_is_correlated(shared_client):
    """``parts[].noise_corr_m``: 0 for a surveyed centreline and for white noise; for a receiver's drift (Gauss-Markov
    errors correlated over 50 m, lag-one correlation exp(-10 / 50) at 10 m spacing) a correlation length of that
    order, the estimate's own accuracy being the engine tests' (tests/engine/test_route_noise.py)."""
    x, y, s = layout(ELEMENTS, 10.0)
    rng = np.random.default_rng(11)
    rho = math.exp(-10.0 / 50.0)
    drifted = x + gauss_markov(rng, x.size, 3.0, rho), y + gauss_markov(rng, y.size, 3.0, rho)
    lon, lat = to_lonlat(*drifted, 45.0)
    correlated = [[float(a), float(b), float(c)] for a, b, c in zip(lon, lat, 300.0 + GRADE * s, strict=True)]
    parts = {}
    for name, coords in (("survey", route(45.0)), ("white", route(45.0, 3.0)), ("drift", correlated)):
        body = {"vehicle": BTRAIN, "geojson": feature_collection(coords), "superelevation_percent": 6.0}
        (parts[name],) = post(shared_client, body).json()["parts"]
    assert parts["survey"]["noise_m"] < 1e-6 and parts["survey"]["noise_corr_m"] == 0.0  # rounding of the layout
    assert parts["white"]["noise_m"] == pytest.approx(3.0, rel=0.25) and parts["white"]["noise_corr_m"] == 0.0
    assert parts["drift"]["noise_m"] == pytest.approx(3.0, rel=0.5)
    assert 50.0 / 3 < parts["drift"]["noise_corr_m"] < 50.0 * 3


def test_the_geojson_answer_is_a_feature_collection_of_the_same_curves(shared_client):
    body = {"vehicle": BTRAIN, "geojson": feature_collection(route(45.0, 2.0)), "superelevation_percent": 6.0}
    plain = post(shared_client, body).json()["curves"]
    r = post(shared_client, body, accept="application/geo+json")
    assert r.headers["content-type"] == "application/geo+json" and r.headers["vary"] == "Accept"
    doc = r.json()
    assert doc["type"] == "FeatureCollection" and len(doc["features"]) == len(plain) == 2
    for f, c in zip(doc["features"], plain, strict=True):  # RFC 7946: a LineString of [lon, lat(, ele)]
        assert f["type"] == "Feature" and f["geometry"] == {"type": "LineString", "coordinates": c["coordinates"]}
        assert f["properties"] == {k: v for k, v in c.items() if k != "coordinates"}
    assert r.headers["etag"] != post(shared_client, body).headers["etag"]  # its own representation


def test_the_assessment_is_the_alignments(shared_client):
    body = {"vehicle": BTRAIN, "geojson": feature_collection(route(45.0)), "superelevation_percent": 6.0,
            "posted_speed_kmh": 80.0, "rear_llt_limit": 0.6}  # fmt: skip
    curves = post(shared_client, body).json()["curves"]
    table = [
        {"id": c["id"], "radius_m": c["radius_lower_m"], "superelevation_percent": 6.0,
         "grade_percent": c["grade_percent"], "posted_speed_kmh": 80.0}
        for c in curves
    ]  # fmt: skip
    rows = shared_client.post(
        "/v1/alignments/assess", json={"vehicle": BTRAIN, "curves": table, "rear_llt_limit": 0.6}
    ).json()["vehicles"][0]["rows"]
    for c, row in zip(curves, rows, strict=True):
        got = c["assessment"]
        for k in ("srt_g", "safe_speed_kmh", "rollover_speed_kmh", "side_friction_speed_kmh", "margin_kmh", "flagged"):
            assert got[k] == row[k], k
    assert curves[0]["assessment"]["flagged"]  # 250 m at 6 %: the B-train's safe speed is below 80 km/h


@pytest.mark.parametrize("noise", [2.5, 3.0])
def test_both_radii_and_the_safe_speed_from_the_lower_one(shared_client, noise):
    body = {"vehicle": BTRAIN, "geojson": feature_collection(route(45.0, noise)), "superelevation_percent": 6.0}
    for c in post(shared_client, body).json()["curves"]:
        assert c["radius_std_m"] > 0 and c["radius_lower_m"] < c["radius_m"]
        row = c["assessment"]
        assert row["radius_m"] == c["radius_lower_m"]  # the row is assessed at the conservative radius
        # Eq. 9.1 by hand: V = sqrt(127 SRT R), with the curve's own SRT and the lower radius
        by_hand = float(max_curve_speed_kmh(row["srt_g"], c["radius_lower_m"]))
        assert row["rollover_speed_kmh"] == pytest.approx(by_hand, rel=1e-12)
        assert by_hand < float(max_curve_speed_kmh(row["srt_g"], c["radius_m"]))  # noise lowers the speed
        assert row["safe_speed_kmh"] == min(row["rollover_speed_kmh"], row["side_friction_speed_kmh"])


def test_noiseless_route_the_lower_radius_is_the_fit_and_the_design(shared_client):
    body = {"vehicle": BTRAIN, "geojson": feature_collection(route(45.0)), "superelevation_percent": 6.0}
    for c, radius in zip(post(shared_client, body).json()["curves"], (250.0, 600.0), strict=True):
        assert c["radius_lower_m"] <= c["radius_m"]
        assert c["radius_lower_m"] == pytest.approx(c["radius_m"], rel=1e-3)
        assert c["radius_lower_m"] == pytest.approx(radius, rel=0.01)  # the designed radius (noiseless tolerance)


def test_csv_and_geojson_carry_both_radii_as_the_json(shared_client):
    body = {"vehicle": BTRAIN, "geojson": feature_collection(route(-35.0, 2.5)), "superelevation_percent": 6.0}
    curves = post(shared_client, body).json()["curves"]
    rows = list(csv.DictReader(io.StringIO(post(shared_client, body, accept="text/csv").text)))
    features = post(shared_client, body, accept="application/geo+json").json()["features"]
    assert len(rows) == len(features) == len(curves) == 2
    for c, r, f in zip(curves, rows, features, strict=True):
        for k in ("radius_m", "radius_lower_m", "radius_std_m"):
            assert float(r[k]) == pytest.approx(c[k], rel=1e-9) and f["properties"][k] == c[k], k
        assert float(r["safe_speed_kmh"]) == pytest.approx(c["assessment"]["safe_speed_kmh"], rel=1e-9)


def test_the_spec_describes_both_radii(shared_client):
    props = shared_client.get("/openapi.json").json()["components"]["schemas"]["RouteCurve"]["properties"]
    lower, std = props["radius_lower_m"]["description"], props["radius_std_m"]["description"]
    assert "95 %" in lower and "Unit: m." in lower and "R_lower" in lower  # confidence level, unit, symbol
    assert "Unit: m." in std and "sigma_R" in std and "radius_lower_m" in props["radius_m"]["description"]


def test_gpx_and_geojson_give_the_same_curves(shared_client):
    coords = route(-35.0, 2.0)
    a = post(shared_client, {"vehicle": BTRAIN, "geojson": feature_collection(coords), "superelevation_percent": 4})
    b = post(shared_client, {"vehicle": BTRAIN, "gpx": gpx(coords), "superelevation_percent": 4})
    fa, fb = (r.json()["curves"] for r in (a, b))
    assert [f["radius_m"] for f in fa] == [f["radius_m"] for f in fb]
    assert [f["assessment"] | {"id": None} for f in fa] == [f["assessment"] | {"id": None} for f in fb]


def test_superelevation_from_the_feature_the_request_or_the_standard(shared_client):
    coords = route(45.0)
    p = post(shared_client, {"vehicle": BTRAIN, "geojson": feature_collection(coords)}, 422).json()
    assert p["errors"][0]["field"] == "superelevation_percent" and "max_superelevation_percent" in p["detail"]
    derived = post(shared_client, {"vehicle": BTRAIN, "geojson": feature_collection(coords, posted_speed_kmh=70),
                                   "max_superelevation_percent": 8})  # fmt: skip
    rows = [c["assessment"] for c in derived.json()["curves"]]
    assert all(r["superelevation_source"] == "derived" for r in rows)
    e = [r["superelevation_percent"] for r in rows]
    assert e[0] > e[1] > 0  # the sharper curve gets more superelevation (AASHTO Method 5)
    given = post(shared_client, {"vehicle": BTRAIN, "geojson": feature_collection(coords, superelevation_percent=5),
                                 "superelevation_percent": 2, "max_superelevation_percent": 8})  # fmt: skip
    assert {c["assessment"]["superelevation_percent"] for c in given.json()["curves"]} == {5}


def test_several_vehicles_and_csv(shared_client):
    body = {"vehicles": [BTRAIN, "table23-semitrailer"], "geojson": feature_collection(route(45.0)),
            "superelevation_percent": 6}  # fmt: skip
    out = post(shared_client, body).json()
    for p in out["curves"]:
        speeds = [v["safe_speed_kmh"] for v in p["vehicles"]]
        assert (
            p["assessment"] == p["vehicles"][p["governing_vehicle"]] and min(speeds) == speeds[p["governing_vehicle"]]
        )
    text = post(shared_client, body, accept="text/csv").text
    rows = list(csv.DictReader(io.StringIO(text)))
    assert len(rows) == 2 * len(out["curves"])
    assert {r["vehicle_preset"] for r in rows} == {BTRAIN, "table23-semitrailer"} and rows[0]["direction"] == "left"


@pytest.mark.parametrize(
    ("coords", "field", "words"),
    [
        ([[10.0, 45.0]], "geojson.features.0.geometry.coordinates", "at least 2"),
        ([[10.0, 45.0], [10.001, 45.0], [45.0, 100.0]], "geojson.features.0.geometry.coordinates.2", "latitude"),
        ([[10.0, 45.0], [10.001, 45.0], [10.5, 45.0]], "geojson.features.0.geometry.coordinates.2", "jumps"),
    ],
)
def test_bad_geometry_names_the_feature_and_the_vertex(shared_client, coords, field, words):
    body = {"vehicle": BTRAIN, "geojson": feature_collection(coords), "superelevation_percent": 6}
    p = post(shared_client, body, 422).json()
    assert p["type"].endswith("invalid-route") and p["errors"][0]["field"] == field and words in p["detail"]


def test_the_synchronous_request_reads_up_to_its_vertex_limit_and_points_past_it_to_a_job(shared_client):
    from app.formats.route_io import MAX_VERTICES
    from app.routes.schemas import MAX_SYNC_VERTICES

    page = (ROOT / "app/web/js/alignment.js").read_text()
    assert f"jobVertices: {MAX_SYNC_VERTICES}" in page  # the page sends a larger route as a job, not to a 422
    line = route(45.0, spacing_m=0.19)  # the 4 km of ELEMENTS, logged every 0.19 m: 21,053 vertices
    body = {
        "vehicle": BTRAIN,
        "geojson": feature_collection(line[: MAX_SYNC_VERTICES + 1]),
        "superelevation_percent": 6,
    }
    p = post(shared_client, body, 422).json()
    assert p["type"].endswith("invalid-route") and p["errors"][0]["field"] == "geojson.features.0.geometry.coordinates"
    assert f"more than {MAX_SYNC_VERTICES:,} vertices" in p["detail"] and f"{MAX_VERTICES:,} vertices" in p["detail"]
    body["geojson"] = feature_collection(line[:MAX_SYNC_VERTICES])  # at the limit: read, both curves found
    assert len(post(shared_client, body).json()["curves"]) == 2


def test_bad_gpx_names_the_point(shared_client):
    text = gpx(route(45.0)[:5]).replace('lat="', 'lat="9', 1)  # the first point's latitude becomes 9xx
    p = post(shared_client, {"vehicle": BTRAIN, "gpx": text, "superelevation_percent": 6}, 422).json()
    assert p["errors"][0]["field"] == "gpx" and "trkpt[1]" in p["errors"][0]["location"]


def test_a_curve_error_names_the_route_requests_own_field_and_the_curve(shared_client):
    # no posted speed anywhere and no superelevation: the distribution cannot be read for the first curve; the route
    # request has no `curves`, so the error names its `posted_speed_kmh` and the curve by its id
    body = {"vehicle": BTRAIN, "geojson": feature_collection(route(45.0)), "max_superelevation_percent": 8}
    p = post(shared_client, body, 422).json()
    e = p["errors"][0]
    assert e["field"] == "posted_speed_kmh" and e["loc"] == ["body", "posted_speed_kmh"]
    assert "the route's curve features[0]-C1" in p["detail"]


def test_a_route_of_two_parts_has_a_speed_profile_per_part_each_as_the_part_alone(shared_client):
    """Two unconnected line parts (issue 43): each part's curves get the profile figures, the vehicle's profile is
    each part's own, one after the other (each point naming its part, its stations along that part) and equal to
    the profile of the same part sent alone: nothing runs across the gap between them."""
    first, second = route(45.0), route(46.0)
    both = feature_collection(first)
    both["features"].append({"type": "Feature", "properties": {}, "geometry": {"type": "LineString",
                             "coordinates": second}})  # fmt: skip
    body = {"vehicle": BTRAIN, "superelevation_percent": 6.0, "posted_speed_kmh": 90.0}
    out = post(shared_client, {**body, "geojson": both}).json()
    parts = [p["part"] for p in out["parts"]]
    assert len(parts) == 2 and all(p["curves"] == 2 for p in out["parts"])
    (vehicle,) = out["vehicles"]
    assert vehicle["speed_profile_notes"] == []
    for c in out["curves"]:  # every curve has its approach figures, none a reason for having none
        a = c["assessment"]
        assert a["profile_reason"] is None and a["approach_speed_kmh"] is not None, a
    points = vehicle["speed_profile"]
    assert [p["part"] for p in points] == sorted((p["part"] for p in points), key=parts.index)
    for k, coords in enumerate((first, second)):
        (alone,) = post(shared_client, {**body, "geojson": feature_collection(coords)}).json()["vehicles"]
        mine = [(p["station_m"], p["speed_kmh"]) for p in points if p["part"] == parts[k]]
        assert mine == [(p["station_m"], p["speed_kmh"]) for p in alone["speed_profile"]]
        assert all(p["part"] == "features[0]" for p in alone["speed_profile"])
        stations = [s for s, _ in mine]
        assert stations == sorted(stations) and stations[0] < 1000.0  # along its own part: it restarts

"""The advice each assessed curve carries (app/alignments/advice.py; issue 43 item 3): invariants against independent
answers.

- a row's advisory speed is POST /v1/advisory-speed's for the same curve (a second route to the same method), and
  every shown advisory is a multiple of the plaque's increment (5 mph: FHWA-SA-11-22 / TxDOT; 10 km/h: assumed);
- the truck's profile never exceeds the desired (posted) speed, nor a curve's safe or advisory speed inside it;
- the approach speed is the profile's speed where braking for the curve starts, never above the desired speed;
- the CSV's and GeoJSON's flat cells are the JSON rows' advice;
- the options' 422s (10-130 km/h, NCHRP Report 774's 15 ft/s^2, the units).
"""

from __future__ import annotations

import csv
import io
import random

import numpy as np
import pytest

from tests.api.test_routes_api import feature_collection, route
from tests.landxml_writer import landxml
from tests.road.test_landxml_files import _design

BTRAIN = "table16-btrain"
MPH = 1.609344  # km per international mile (exact)
POSTED = 90.0


def _road(seed: int = 11, n_bends: int = 8) -> dict:
    design = _design(random.Random(seed), n_bends=n_bends)
    return {
        "vehicle": BTRAIN,
        "landxml": {"document": landxml(design), "superelevation_percent": 5.0, "posted_speed_kmh": POSTED},
    }


def _post(client, body, status=200, path="/v1/alignments/assess", **kwargs):
    r = client.post(path, json=body, **kwargs)
    assert r.status_code == status, r.text
    return r


@pytest.mark.parametrize(("units", "increment_kmh"), [("us", 5 * MPH), ("metric", 10.0)])
def test_each_shown_advisory_is_a_multiple_of_the_plaques_increment(client, units, increment_kmh):
    out = _post(client, {**_road(), "units": units}).json()
    assert out["advisory"]["units"] == units
    shown = [r["advisory_speed_kmh"] for r in out["vehicles"][0]["rows"]]
    assert shown and all(x is not None for x in shown)
    for x in shown:
        k = x / increment_kmh
        assert k == pytest.approx(round(k), abs=1e-9)


def test_a_rows_advisory_is_the_advisory_speed_endpoints(client):
    """One curve without stations (no shared sign): the row's advisory, treatment and W1-13 recommendation are POST
    /v1/advisory-speed's for the same radius, superelevation, grade, posted speed and vehicle."""
    for radius, e, grade, posted in ((150.0, 6.0, 0.0, 100.0), (90.0, 8.0, -4.0, 70.0), (400.0, 4.0, 3.0, 110.0)):
        curve = {"radius_m": radius, "superelevation_percent": e, "grade_percent": grade, "posted_speed_kmh": posted}
        row = _post(client, {"vehicle": BTRAIN, "curves": [{"id": "A", **curve}]}).json()["vehicles"][0]["rows"][0]
        one = _post(client, {"vehicle": BTRAIN, **curve}, path="/v1/advisory-speed").json()
        assert row["advisory_speed_kmh"] == one["advisory_speed_kmh"]
        assert row["treatment"]["devices"] == one["treatment"]["devices"]
        assert row["truck_rollover_warning"]["recommended"] == one["truck_rollover_warning"]["recommended"]
        # no stations in a JSON curve list: no profile, the row says why
        assert row["approach_speed_kmh"] is None and row["profile_reason"]


def test_the_profile_stays_under_the_desired_safe_and_advisory_speeds(client):
    out = _post(client, {**_road(seed=5, n_bends=10), "deceleration_mps2": 2.0}).json()
    v = out["vehicles"][0]
    profile = v["speed_profile"]
    assert len(profile) > 2 and v["speed_profile_notes"] == []
    stations = np.array([p["station_m"] for p in profile])
    speeds = np.array([p["speed_kmh"] for p in profile])
    assert np.all(np.diff(stations) >= -1e-9)
    assert speeds.max() <= POSTED + 1e-9  # the posted speed is the tangents' desired speed
    for row in v["rows"]:
        start, end = row["bend_start_m"], row["bend_end_m"]
        cap = min(POSTED, row["safe_speed_kmh"], row["advisory_speed_kmh"])
        # v^2 is linear between the profile's points: a curve's own points bound it inside the curve (stations are
        # written to the millimetre: app/alignments/advice.py)
        inside = (stations >= start - 1e-3) & (stations <= end + 1e-3)
        assert inside.any()
        assert speeds[inside].max() <= cap + 1e-6
        assert row["approach_speed_kmh"] <= POSTED + 1e-9
        if row["required_deceleration_mps2"] is None:
            assert row["profile_reason"]
        else:
            assert row["required_deceleration_mps2"] >= 0


def test_csv_and_geojson_cells_are_the_json_rows_advice(client):
    body = _road(seed=3)
    rows = _post(client, body).json()["vehicles"][0]["rows"]
    text = _post(client, body, headers={"Accept": "text/csv"}).text
    table = list(csv.DictReader(io.StringIO(text)))
    assert len(table) == len(rows)
    for row, cells in zip(rows, table, strict=True):
        assert cells["treatment_devices"] == ";".join(row["treatment"]["devices"])
        assert cells["truck_rollover_warning"] == str(row["truck_rollover_warning"]["recommended"]).lower()
        assert float(cells["advisory_speed_kmh"]) == row["advisory_speed_kmh"]
        assert (cells["approach_speed_kmh"] == "") is (row["approach_speed_kmh"] is None)


def test_a_routes_geojson_carries_the_advice_flat(client):
    """A GIS colours the features by ``treatment_devices``: the governing row's own treatment where one vehicle."""
    geojson = feature_collection(route(45.0))
    body = {"vehicle": BTRAIN, "geojson": geojson, "superelevation_percent": 6.0, "posted_speed_kmh": 80.0}
    doc = _post(client, body, path="/v1/routes/assess", headers={"Accept": "application/geo+json"}).json()
    assert doc["advisory"]["units"] == "us" and doc["features"]
    for f in doc["features"]:
        p = f["properties"]
        a = p["assessment"]
        assert p["treatment_devices"] == (";".join(a["treatment"]["devices"]) or None)
        assert p["advisory_speed_kmh"] == a["advisory_speed_kmh"]
        assert p["truck_rollover_warning"] is a["truck_rollover_warning"]["recommended"]


@pytest.mark.parametrize(
    ("option", "value"),
    [
        ("deceleration_mps2", 15 * 0.3048 + 0.01),  # beyond NCHRP Report 774's 15 ft/s^2
        ("deceleration_mps2", 0.0),
        ("desired_speed_kmh", 135.0),  # outside 10-130 km/h
        ("desired_speed_kmh", 5.0),
        ("units", "imperial"),
    ],
)
def test_bad_options_are_422_naming_the_field(client, option, value):
    r = _post(client, {**_road(), option: value}, status=422)
    problem = r.json()
    assert option in r.text and problem["status"] == 422


def _series(svg: str, name: str) -> tuple[np.ndarray, np.ndarray]:
    """A series' plotted values, read back from its data-x / data-y (app/formats/svg.py)."""
    import re

    m = re.search(r'data-name="' + re.escape(name) + r'">.*?data-x="([^"]*)" data-y="([^"]*)"', svg, re.S)
    assert m, name
    return np.array(m.group(1).split(), dtype=float), np.array(m.group(2).split(), dtype=float)


def test_the_speed_profile_plot_draws_the_answers_profile_and_speeds(client):
    from app.plots.service import SERIES_ADVISORY, SERIES_POSTED, SERIES_PROFILE, SERIES_SAFE

    body = _road(seed=5, n_bends=6)
    out = _post(client, body).json()["vehicles"][0]
    r = _post(client, body, path="/v1/plots/speed-profile")
    assert r.headers["content-type"] == "image/svg+xml"
    svg = r.text
    x, y = _series(svg, SERIES_PROFILE)
    assert x == pytest.approx([p["station_m"] for p in out["speed_profile"]], rel=1e-5)
    assert y == pytest.approx([p["speed_kmh"] for p in out["speed_profile"]], rel=1e-5)
    for name, field in ((SERIES_SAFE, "safe_speed_kmh"), (SERIES_ADVISORY, "advisory_speed_kmh")):
        xs, ys = _series(svg, name)  # start, end, gap per curve
        assert xs[0::3] == pytest.approx([row["bend_start_m"] for row in out["rows"]], rel=1e-5)
        assert ys[0::3] == pytest.approx([row[field] for row in out["rows"]], rel=1e-5)
        assert np.isnan(ys[2::3]).all()
    _, posted = _series(svg, SERIES_POSTED)
    assert posted[0::3] == pytest.approx([POSTED] * len(out["rows"]))
    # curves without stations have no profile: a 422 naming the curves, with the reason
    curves = {"vehicle": BTRAIN, "curves": [{"id": "A", "radius_m": 150.0, "superelevation_percent": 6.0}]}
    problem = _post(client, curves, status=422, path="/v1/plots/speed-profile").json()
    assert problem["errors"][0]["field"] == "curves" and "no speed profile" in problem["detail"]


def test_the_answer_says_which_method_set_the_rows_speeds(client):
    """Without a measured car speed every row's advisory speed is the 2009 ball-bank criterion's: the answer names it
    with its source and status, and why the primary Design Method gives none, once (docs/advisory.md). Each row's
    speed is recomputed here from the criterion's bands (16/14/12 deg from 0/25/35 mph): the side friction a
    ball-bank angle stands for, atan(f) + 5 deg/g x f = angle (Brent's root, not the engine's bisection), the
    point-mass speed sqrt(127 R (e + f)) in the first band that holds it (or that band's lower edge), then the metric
    plaque: down to a multiple of 10 km/h."""
    import math

    from scipy.optimize import brentq

    from engine.road import BALL_BANK_2009, BODY_ROLL_DEG_PER_G

    curves = [(150, 6), (600, 4), (60, 8), (1200, 2)]
    body = {
        "vehicle": "table16-btrain",
        "units": "metric",
        "curves": [
            {"id": f"C{k}", "radius_m": r, "superelevation_percent": e, "posted_speed_kmh": 100}
            for k, (r, e) in enumerate(curves)
        ],
    }
    out = client.post("/v1/alignments/assess", json=body).json()
    adv = out["advisory"]
    assert adv["method"] == BALL_BANK_2009.id == "ball-bank-2009"
    assert "MUTCD 2009" in adv["method_source"] and adv["method_source"].endswith("unverified")
    assert adv["primary_method"].startswith("Design Method") and "unverified" in adv["primary_method"]
    edges = [1.609344 * mph for mph in BALL_BANK_2009.edges_mph] + [math.inf]
    assert BALL_BANK_2009.values == (16.0, 14.0, 12.0) and BODY_ROLL_DEG_PER_G == 5.0
    shown = []
    for r, e in curves:
        for k, angle in enumerate(BALL_BANK_2009.values):
            f = brentq(lambda f, a=angle: math.degrees(math.atan(f)) + 5.0 * f - a, 0.0, 1.0, xtol=1e-14)
            v = math.sqrt(127.0 * r * (e / 100 + f))
            if v < edges[k + 1]:
                v = max(v, edges[k])
                break
        shown.append(max(10.0, 10.0 * math.floor(v / 10.0 + 1e-9)))
    rows = {row["id"]: row["advisory_speed_kmh"] for row in out["vehicles"][0]["rows"]}
    assert [rows[f"C{k}"] for k in range(len(curves))] == pytest.approx(shown, abs=1e-9)

"""The calculator page against the builder, component library, design standards, superelevation, routes, jobs and
payload-table endpoints, end to end in headless chromium against a real uvicorn server.

Expected numbers come from closed forms worked here (Eq. 9.2, the DNIT superelevation distribution, the geometry
of a synthetic route), published table cells (cited at each assertion), or the public API called directly for the
same case -- never from the page itself.
"""

from __future__ import annotations

import json
import math
from urllib.parse import parse_qs, quote, urlsplit

import numpy as np
import pytest
from selenium.webdriver.support.ui import Select, WebDriverWait

from tests.synthetic_routes import Arc, Tangent, curve_spans, layout, to_lonlat

#: the page shows the SRT with three decimals: it can differ from the API's value by half a unit of the last one
DISPLAY_G = 0.0005

#: the spec the builder form's initial boxes make (app/web/index.html), without the tyre and suspension choices
FORM_SPEC = {
    "unit_type": "semitrailer",
    "rear": {"axles": 3, "tyres_per_axle": 4, "track_m": 1.86, "centre_from_kingpin_m": 8.7},
    "front": {"axles": 2, "tyres_per_axle": 4, "track_m": 1.86, "centre_from_kingpin_m": 0.2},
    "tare": {"mass_kg": 8000, "cg_height_m": 1.1, "cg_from_kingpin_m": 6},
    "payloads": [{"mass_kg": 24000, "deck_height_m": 1.4, "load_height_m": 3.6, "distribution": "uniform"}],
    "deck": {"front_from_kingpin_m": -1, "length_m": 13},
}


def with_components(tyre_id: str, suspension_id: str) -> dict:
    return {**FORM_SPEC, "rear": {**FORM_SPEC["rear"], "tyre": {"id": tyre_id}, "suspension": {"type": suspension_id}}}


def table_rows(page, selector: str) -> list[list[str]]:
    """The cells' texts of the rows matched by ``selector`` (read in one script: tables can be long)."""
    script = """return Array.from(document.querySelectorAll(arguments[0]))
      .map((tr) => Array.from(tr.cells).map((td) => td.textContent.trim()));"""
    return page.driver.execute_script(script, selector)


def curve_rows(page) -> list[dict]:
    """The assessed curves table as dicts keyed by the API field of each column, with the row's class."""
    script = """
      const keys = Array.from(document.querySelectorAll('#curves-table thead button.sort')).map((b) => b.dataset.key);
      const cells = (tr) => Array.from(tr.cells).map((td, i) => [keys[i], td.textContent.trim()]);
      return Array.from(document.querySelectorAll('#curves-table tbody tr'))
        .map((tr) => Object.assign({row_class: tr.className}, Object.fromEntries(cells(tr))));
    """
    return page.driver.execute_script(script)


def choose_builder(page) -> None:
    page.find('input[name="source"][value="build"]').click()
    assert page.find("#builder").is_displayed()


def ok(response):
    assert response.status_code == 200, response.text
    return response.json()


# ------------------------------------------------------------------------------------------- the builder


def test_the_builder_form_with_library_components_gives_the_srt_of_its_spec(page, api):
    components = ok(api.get("/v1/components"))
    page.open()
    choose_builder(page)
    # the choices are the library's, and a fresh form starts with each list's first entry
    tyres = [o.get_attribute("value") for o in page.find_all("#b-rear-tyre option")]
    suspensions = [o.get_attribute("value") for o in page.find_all("#b-rear-susp option")]
    assert tyres == ["", *[t["id"] for t in components["tyres"]]]
    assert suspensions == ["", *[s["id"] for s in components["suspensions"]]]
    assert Select(page.find("#b-rear-tyre")).first_selected_option.get_attribute("value") == tyres[1]
    # another tyre and suspension than the defaults: the last of each list
    tyre, suspension = components["tyres"][-1], components["suspensions"][-1]
    Select(page.find("#b-rear-tyre")).select_by_value(tyre["id"])
    Select(page.find("#b-rear-susp")).select_by_value(suspension["id"])
    assert str(tyre["loaded_radius_m"]["value"]) in page.find("#b-rear-tyre-lr").get_attribute("placeholder")
    page.run("computations", lambda: page.find("#build-button").click())
    spec = with_components(tyre["id"], suspension["id"])
    # the spec the page built is in its link, and its SRT is the API's for the same spec
    sent = json.loads(parse_qs(urlsplit(page.driver.current_url).query)["spec"][0])
    assert sent == spec
    expected = ok(api.post("/v1/srt", json={"vehicle": {"spec": spec}}))["srt"]
    assert page.srt_g() == pytest.approx(expected, abs=DISPLAY_G)
    # the derivation table: the record's lr and kT are the library tyre's, kLs the suspension's, method "library"
    # (each record field by its label: rolling_radius_m is "Rolling radius [m]")
    derivation = {cells[0]: cells for cells in table_rows(page, "#build-result table tbody tr")}
    assert float(derivation["Rolling radius [m]"][1]) == pytest.approx(tyre["loaded_radius_m"]["value"], rel=1e-5)
    assert float(derivation["Tire stiffness [kN/m]"][1]) == pytest.approx(tyre["stiffness_kn_per_m"]["value"])
    assert float(derivation["Suspension stiffness [kN/m]"][1]) == suspension["stiffness_kn_per_m"]["value"]
    assert derivation["Rolling radius [m]"][3] == "library"
    assert derivation["Rolling radius [m]"][5] == tyre["loaded_radius_m"]["source"]


def test_builder_errors_are_shown_at_the_builder_boxes(page):
    page.open()
    choose_builder(page)
    page.type("#b-rear-track", "-1")
    page.run("computations", lambda: page.find("#build-button").click())
    assert page.find("#b-rear-track").get_attribute("aria-invalid") == "true"
    assert "spec.rear.track_m must be above 0" in page.field_error("#b-rear-track")
    assert page.find("#results-body").is_displayed() is False  # nothing computed
    # no library tyre and no loaded radius: the service asks for one at the loaded-radius box
    page.type("#b-rear-track", "1.86")
    Select(page.find("#b-rear-tyre")).select_by_value("")
    page.run("computations", lambda: page.find("#build-button").click())
    assert page.find("#b-rear-track").get_attribute("aria-invalid") is None
    assert page.find("#b-rear-tyre-lr").get_attribute("aria-invalid") == "true"
    assert "rolling_radius_m (lr) is unknown" in page.field_error("#b-rear-tyre-lr")


def test_a_pasted_spec_with_an_error_is_refused_at_the_record_box_naming_the_spec_field(page):
    bad = {"spec": {**with_components("thesis-michelin-xza", "thesis-steel-leaf"), "rear": {"axles": 3}}}
    page.open("?record=" + quote(json.dumps(bad)))
    message = page.field_error("#record-json")
    assert page.find("#record-json").get_attribute("aria-invalid") == "true"
    assert "spec.rear.track_m" in message  # the spec path the service names (Field required)


def test_the_payload_table_of_a_built_vehicle_is_the_apis(page, api):
    components = ok(api.get("/v1/components"))
    spec = with_components(components["tyres"][0]["id"], components["suspensions"][0]["id"])
    page.open()
    choose_builder(page)  # the form's defaults, with the library's first tyre and suspension
    page.run("computations", lambda: page.find("#build-button").click())
    page.type("#limit-target", "0.35")
    page.run("limits", lambda: page.find("#limits-compute").click())
    expected = ok(api.post("/v1/vehicles/payload-table", json={"spec": spec, "target_srt_g": 0.35}))
    srt = ok(api.post("/v1/srt", json={"vehicle": {"spec": spec}}))["srt"]
    assert f"SRT of the spec as built {srt:.3f} g" in page.text("#payload-info")
    assert page.srt_g() == pytest.approx(srt, abs=DISPLAY_G)  # the page's case is the level road, 3D model
    shown = table_rows(page, "#payload-tables .scroll-box:first-child tbody tr")
    assert [c[0] for c in shown] == [f"{r['load_height_m']:.2f}" for r in expected["by_load_height"]]
    found = 0
    for cells, row in zip(shown, expected["by_load_height"], strict=True):
        limit = row["limit"]
        if limit["status"] == "found":
            found += 1
            assert cells[1] == f"{limit['value']:.0f}"
            assert cells[2] == "0.350"  # at the limit the SRT is the target
        elif limit["status"] == "always-met":
            assert cells[1].startswith("\u2265") and float(cells[2]) >= 0.35
    assert found >= 1  # at 3.6 m (the spec's load height) the 24 t payload is below 0.35 g: a limit is found
    # invariant: the higher the load, the smaller the largest payload
    masses = [r["limit"]["value"] for r in expected["by_load_height"]]
    assert masses == sorted(masses, reverse=True)
    heights = table_rows(page, "#payload-tables .scroll-box:last-child tbody tr")
    assert len(heights) == len(expected["by_payload_mass"])


def test_the_acceptable_load_on_a_banked_road_is_the_level_roads(page, api):
    # the targets are judged on the level road (DESIGN.md), so the page's acceptable-load table on a 6 % bank is
    # the level road's table, and says so; the banked road's own limits are larger (the bank raises the SRT)
    page.open("?vehicle=table16-btrain&bank_percent=6")
    page.type("#limit-target", "0.33")
    page.run("limits", lambda: page.find("#limits-compute").click())
    assert "on a level road" in page.text("#limits-result")
    body = {"vehicle": "table16-btrain", "parameter": "cg_height_above_chassis_m", "target_srt_g": 0.33}
    level = ok(api.post("/v1/srt/limits", json=body))["table"]
    on_road = ok(api.post("/v1/srt/limits", json={**body, "road": {"bank_percent": 6}, "limit_on": "road"}))["table"]
    shown = table_rows(page, "#limits-result tbody tr")
    assert [c[0] for c in shown] == [f"{r['overweight_percent']:.0f}" for r in level]
    found = 0
    for cells, row, banked in zip(shown, level, on_road, strict=True):
        if row["status"] == "found":
            found += 1
            assert cells[1] == f"{row['value']:.3f}" and cells[3] == "0.330"
            assert banked["status"] != "found" or banked["value"] > row["value"]
    assert found >= 1


# ------------------------------------------------------------------------------------------- road design


def test_dnit_1999_changes_the_minimum_radius_table_and_plot_to_the_apis(page, api):
    page.open("?vehicle=table16-btrain")
    aashto_plot = page.find("#road-results svg").get_attribute("outerHTML")
    aashto_rows = table_rows(page, "#road-results table tbody tr")
    Select(page.find("#standard")).select_by_value("dnit-1999")
    page.run("computations", lambda: page.find("#road-compute").click())
    assert parse_qs(urlsplit(page.driver.current_url).query)["design_standard"] == ["dnit-1999"]
    standard = ok(api.get("/v1/design-standards/dnit-1999"))
    assert standard["title"] in page.text("#road-results p")
    rows = table_rows(page, "#road-results table tbody tr")
    assert rows != aashto_rows and page.find("#road-results svg").get_attribute("outerHTML") != aashto_plot
    assert [float(r[0]) for r in rows] == standard["speeds_kmh"]  # 30-120 km/h, every 10
    # DNER IPR-706 (1999) Quadro 5.4.3.2, e_max = 8 %: the published R_min, which is Eq. 9.2 with Quadro 5.4.3.1's
    # f_max rounded to 5 m (80 km/h: f = 0.14, R_min = 230 m)
    published = standard["min_radius_table"]["8"]
    assert published["80"] == 230.0
    for cells in rows:
        v, f, r92 = float(cells[0]), float(cells[5]), float(cells[3])
        assert r92 == pytest.approx(v**2 / (127 * (0.08 + f)), abs=0.501)  # Eq. 9.2, shown to 1 m
        assert 5 * round(r92 / 5) == published[f"{v:.0f}"]
        answer = ok(api.post("/v1/min-radius", json={"vehicle": "table16-btrain", "design_standard": "dnit-1999",
                                                    "design_speed_kmh": v, "superelevation_percent": 8}))  # fmt: skip
        assert cells[1:] == [
            f"{answer['governing_min_radius_m']:.0f}",
            answer["governed_by"].replace("-", " "),  # in words: "side friction"
            f"{answer['side_friction_min_radius_m']:.0f}",
            f"{answer['rollover_min_radius_m']:.0f}",
            f"{answer['side_friction']:.3f}",
        ]


def superelevation_shown(page) -> tuple[float, float, float, float]:
    """e [%], f, f_max and Rmin [m] as the line shows them (it names the radius, speed and e_max they are for)."""
    text = page.text("#super-result")
    e = float(text.split(": superelevation ")[1].split(" %")[0])
    f = float(text.split("leaving side friction ")[1].split(" ")[0])
    f_max = float(text.split("maximum side friction at ")[1].split(": ")[1].split(")")[0])
    r_min = float(text.split("minimum radius at ")[1].split(": ")[1].split(" m")[0].replace(",", ""))
    return e, f, f_max, r_min


def test_the_superelevation_of_a_curve_for_the_chosen_standard(page, api):
    page.open("?vehicle=table16-btrain")
    for box, text in (("#se-speed", "80"), ("#se-radius", "400"), ("#se-emax", "8")):
        page.type(box, text)
    page.run("superelevations", lambda: page.find("#super-compute").click())
    e, f, f_max, r_min = superelevation_shown(page)
    # AASHTO 2018 Table 3-7 (metric) at 80 km/h: f_max = 0.14, R_min = 229 m for e_max = 8 %
    assert f_max == 0.14
    assert r_min == pytest.approx(80**2 / (127 * (0.08 + 0.14)), abs=0.5) and r_min == 229  # shown to 1 m
    # the curve's balance (Eq. 9.2 at R): e + f = V^2 / (127 R); e shown to 0.01 %, f to 0.001
    assert e / 100 + f == pytest.approx(80**2 / (127 * 400), abs=0.00005 + 0.0005)
    body = {"design_speed_kmh": 80, "radius_m": 400, "max_superelevation_percent": 8}
    answer = ok(api.post("/v1/superelevation", json=body))
    assert (e, f) == (round(answer["superelevation_percent"], 2), round(answer["side_friction"], 3))
    # the table by radius: from R_min (e = e_max, f = f_max) down, each row balanced, e falling with the radius
    rows = [[float(c) for c in cells] for cells in table_rows(page, "#super-table tbody tr")]
    assert rows[0] == [r_min, 8.0, 0.14]
    for radius, e_row, f_row in rows:
        # e to 0.01 %, f to 0.001, R to 1 m (0.5 m at R >= 229 m: V^2 / (127 R^2) x 0.5 <= 0.0005)
        assert e_row / 100 + f_row == pytest.approx(80**2 / (127 * radius), abs=0.00005 + 0.0005 + 0.0005)
    assert [r[1] for r in rows] == sorted((r[1] for r in rows), reverse=True) and len(rows) > 2
    # DNIT 1999: e = e_max (2 R_min / R - R_min^2 / R^2) with R_min of Eq. 9.2 (f = 0.14 at 80 km/h)
    Select(page.find("#standard")).select_by_value("dnit-1999")
    page.run("superelevations", lambda: page.find("#super-compute").click())
    e_dnit, _, _, _ = superelevation_shown(page)
    rmin = 80**2 / (127 * (0.08 + 0.14))
    assert e_dnit == pytest.approx(8 * (2 * rmin / 400 - (rmin / 400) ** 2), abs=0.005)
    # below R_min: refused at the radius box
    page.type("#se-radius", "100")
    page.run("superelevations", lambda: page.find("#super-compute").click())
    assert page.find("#se-radius").get_attribute("aria-invalid") == "true"
    assert "below the minimum radius" in page.field_error("#se-radius")


# ------------------------------------------------------------------------------------------- a GPX route

#: a straight, a 150 m left arc 250 m long, a straight; vertices every 10 m with 1 m of GPS-like noise
ROUTE = [Tangent(400.0), Arc(150.0, 250.0, "left"), Tangent(400.0)]
ROUTE_RADIUS_M = 150.0


def gpx_track(noise_m: float = 1.0, seed: int = 1, lat0: float = -27.6) -> str:
    x, y, _ = layout(ROUTE, 10.0)
    rng = np.random.default_rng(seed)
    x, y = x + rng.normal(0, noise_m, x.size), y + rng.normal(0, noise_m, y.size)
    lon, lat = to_lonlat(x, y, lat0)
    points = "".join(f'<trkpt lat="{float(b)!r}" lon="{float(a)!r}"/>' for a, b in zip(lon, lat, strict=True))
    return (
        '<?xml version="1.0"?><gpx version="1.1" creator="test" xmlns="http://www.topografix.com/GPX/1/1">'
        f"<trk><name>Test road</name><trkseg>{points}</trkseg></trk></gpx>"
    )


def test_an_uploaded_gpx_route_shows_its_curve_radius_within_its_uncertainty_and_flagged(page, api, tmp_path):
    text = gpx_track()
    path = tmp_path / "route.gpx"
    path.write_text(text)
    page.open("?vehicle=table16-btrain")
    page.find("#alignment-file").send_keys(str(path))
    page.type("#al-posted", "80")
    page.type("#al-e", "6")
    page.run("assessments", lambda: page.find("#alignment-assess").click())
    rows = curve_rows(page)
    assert len(rows) == 1  # no phantom curve on the straights
    row = rows[0]
    radius, std = float(row["radius_m"]), float(row["radius_std_m"])
    # the designed radius within three of the service's own standard errors (and the display's 0.05 m)
    assert std > 0 and abs(radius - ROUTE_RADIUS_M) <= 3 * std + 0.5  # shown to 1 m
    ((start, _end),) = curve_spans(ROUTE)
    assert float(row["station_m"]) == pytest.approx(start, abs=60)  # as tests/api/test_routes_api.py
    assert row["direction"] == "left"
    # flagged: at 80 km/h and over, AASHTO Table 3-7 gives f <= 0.14, so the side-friction speed is at most
    # sqrt(127 x 150 x (0.06 + 0.14)) = 61.7 km/h < 80 (and for any speed above 60 km/h, f <= 0.17: <= 66.2 km/h)
    assert "flagged" in row["row_class"] and float(row["safe_speed_kmh"]) < math.sqrt(127 * 150 * (0.06 + 0.17))
    assert page.text("#alignment-summary").startswith("1 curves, 1 flagged")
    assert len(page.find_all("#alignment-results svg polyline.curve.flagged")) == 1
    # the row is the API's answer to the same request
    body = {"vehicle": "table16-btrain", "gpx": text, "posted_speed_kmh": 80, "superelevation_percent": 6}
    answer = ok(api.post("/v1/routes/assess", json=body))  # the page sends only what was typed
    props = answer["curves"][0]
    assert row["radius_m"] == f"{props['radius_m']:.0f}" and row["radius_std_m"] == f"{props['radius_std_m']:.1f}"
    assert row["safe_speed_kmh"] == f"{props['assessment']['safe_speed_kmh']:.1f}"
    # the GeoJSON download is the same request again, with Accept: application/geo+json
    page.network()
    page.find("#download-json").click()
    WebDriverWait(page.driver, 30).until(
        lambda _: any(urlsplit(u).path == "/v1/routes/assess" for u in page.network()[0].values())
    )
    assert not [m for m in page.console() if "SEVERE" in m or "Error" in m]


# ------------------------------------------------------------------------------------------- a job


def large_csv(rows: int) -> str:
    lines = ["id,radius_m,superelevation_percent,grade_percent,posted_speed_kmh"]
    lines += [f"C{i},{40 + (i * 37) % 1500},{i % 9},0,{50 + 10 * (i % 5)}" for i in range(rows)]
    return "\n".join(lines) + "\n"


#: the page's job threshold (5,000 curves; app/web/js/alignment.js `settings`) lowered for these tests, so a job
#: is a few seconds shorter and the behaviour the same
JOB_ROWS = 50


def lower_the_job_size(page, rows: int = JOB_ROWS) -> None:
    page.driver.execute_script(
        "const n = arguments[0]; return import('/web/js/alignment.js').then((m) => { m.settings.jobRows = n; });",
        rows,
    )


def test_a_large_alignment_runs_as_a_job_with_a_progress_bar_to_100_percent(page, api, live_server, tmp_path):
    text = large_csv(JOB_ROWS + 10)  # above the page's job size
    path = tmp_path / "large.csv"
    path.write_text(text)
    page.open("?vehicle=table16-btrain")
    lower_the_job_size(page)
    page.find("#catalog-box summary").click()  # the jobs of a deployment with keys are the key's own
    page.type("#api-key", live_server.key)
    page.find("#alignment-file").send_keys(str(path))
    page.network()
    page.run("assessments", lambda: page.find("#alignment-assess").click(), timeout_s=180)
    assert page.find("#alignment-progress-box").is_displayed()
    assert float(page.find("#alignment-progress").get_attribute("value")) == 1.0
    assert page.text("#alignment-progress-text") == f"100 % ({JOB_ROWS + 10} of {JOB_ROWS + 10} rows; job done)"
    sent, _ = page.network()
    paths = {urlsplit(u).path for u in sent.values()}
    assert "/v1/jobs" in paths and "/v1/alignments/assess" not in paths
    # (the result is read by the page's curves worker, whose requests this log does not list)
    # the same table as the synchronous answer
    answer = ok(api.post("/v1/alignments/assess", json={"vehicle": "table16-btrain", "csv": text}))
    expected = answer["vehicles"][0]
    assert page.text("#alignment-summary").startswith(
        f"{JOB_ROWS + 10} curves, {expected['summary']['flagged']} flagged"
    )
    rows = curve_rows(page)
    # the flagged curves first, smallest margin first, then the others in the file's order
    flagged = sorted((r for r in expected["rows"] if r["flagged"]), key=lambda r: r["margin_kmh"])
    order = flagged + [r for r in expected["rows"] if not r["flagged"]]
    # one page of 25 rows on screen (app/web/js/curves.js `settings.pageRows`), the count of all beside it
    assert page.text("#curves-shown") == f"Rows 1\u201325 of {JOB_ROWS + 10}"
    order = order[:25]
    assert [r["id"] for r in rows] == [r["id"] for r in order]
    assert [("flagged" in r["row_class"]) for r in rows] == [r["flagged"] for r in order]
    assert [r["safe_speed_kmh"] for r in rows] == [f"{r['safe_speed_kmh']:.1f}" for r in order]


# ------------------------------------------------------------------------------------------- a saved fleet

FLEET_CSV = """id,radius_m,superelevation_percent,grade_percent,posted_speed_kmh
K1,60,4,0,60
K2,300,6,0,80
K3,1200,6,0,100
"""


def test_an_alignment_and_a_route_are_assessed_for_each_vehicle_of_a_saved_fleet(page, api, live_server, tmp_path):
    key = {"Authorization": f"Bearer {live_server.key}"}
    vehicles = ["table16-btrain", "table15-semitrailer"]
    fleet = api.post("/v1/fleets", json={"title": "Page fleet", "vehicles": vehicles}, headers=key)
    assert fleet.status_code == 201, fleet.text
    fleet_id = fleet.json()["id"]
    csv_path, gpx_path = tmp_path / "fleet.csv", tmp_path / "route.gpx"
    csv_path.write_text(FLEET_CSV)
    gpx_path.write_text(gpx_track())
    page.open("?vehicle=table16-btrain")
    page.type("#al-fleet", fleet_id)
    page.find("#alignment-file").send_keys(str(csv_path))
    # a fleet needs the bearer key: refused at the key's box before any request
    page.run("assessments", lambda: page.find("#alignment-assess").click())
    assert "bearer key" in page.field_error("#api-key")
    page.type("#api-key", live_server.key)
    # the fleet picker: the key's fleets listed, the one chosen fills the fleet box
    page.find("#al-fleet").clear()
    page.run("fleets", lambda: page.find("#fleet-list").click())
    picker = Select(page.find("#fleet-choice"))
    assert "Page fleet (2 vehicles: table16-btrain, table15-semitrailer)" in [o.text for o in picker.options]
    picker.select_by_value(fleet_id)
    assert page.find("#al-fleet").get_attribute("value") == fleet_id
    page.run("assessments", lambda: page.find("#alignment-assess").click())
    body = {"fleet": fleet_id, "csv": FLEET_CSV}
    answer = ok(api.post("/v1/alignments/assess", json=body, headers=key))
    choice = Select(page.find("#al-vehicle-shown"))
    assert [o.text for o in choice.options] == vehicles
    for i, name in enumerate(vehicles):
        choice.select_by_index(i)
        rows = curve_rows(page)
        expected = answer["vehicles"][i]["rows"]
        assert [r["safe_speed_kmh"] for r in rows] == [f"{r['safe_speed_kmh']:.1f}" for r in expected]
        assert [("flagged" in r["row_class"]) for r in rows] == [r["flagged"] for r in expected]
        assert f"for {name}" in page.text("#alignment-summary")
    # a route: a GPX track gives no superelevation and no posted speed. The page says so beside the boxes that
    # supply them, before any request: first the superelevation (or a maximum to derive it from), then, with a
    # maximum typed, the posted speed the derivation needs
    page.find("#alignment-file").send_keys(str(gpx_path))
    WebDriverWait(page.driver, 10).until(lambda _: "gives no superelevation" in page.field_error("#al-e"))
    page.network()
    page.run("assessments", lambda: page.find("#alignment-assess").click())
    assert not [u for u in page.network()[0].values() if urlsplit(u).path.endswith("/assess")]
    page.type("#al-emax", "8")
    page.find("#al-posted").click()  # the maximum's change is read when its box is left
    WebDriverWait(page.driver, 10).until(lambda _: "no posted speed" in page.field_error("#al-posted"))
    assert "gives no superelevation" not in page.field_error("#al-e")
    # each curve by its governing vehicle (the lowest safe speed), named in the Vehicle column. 60 km/h: with a
    # superelevation from the distribution a curve below the standard's R_min for its speed refuses the whole
    # route (AASHTO 2018 Table 3-7, e_max 8 %: 229 m at 80 km/h, 113 m at 60 km/h; the arc is 150 m)
    page.type("#al-posted", "60")
    page.run("assessments", lambda: page.find("#alignment-assess").click())
    body = {"fleet": fleet_id, "gpx": gpx_path.read_text(), "posted_speed_kmh": 60, "max_superelevation_percent": 8}
    route = ok(api.post("/v1/routes/assess", json=body, headers=key))
    (props,) = route["curves"]
    safe = [v["safe_speed_kmh"] for v in props["vehicles"]]
    assert props["governing_vehicle"] == safe.index(min(safe))
    (row,) = curve_rows(page)
    assert row["vehicle"] == vehicles[props["governing_vehicle"]]
    assert row["safe_speed_kmh"] == f"{min(safe):.1f}"


def test_without_the_key_a_large_alignment_is_assessed_in_one_request(page, live_server, tmp_path):
    # this server has bearer keys: its jobs are a key's own (401 without one), the synchronous endpoint is open
    text = large_csv(JOB_ROWS + 1)
    path = tmp_path / "large.csv"
    path.write_text(text)
    page.open("?vehicle=table16-btrain")
    lower_the_job_size(page)
    assert page.find("#api-key").get_attribute("value") == ""
    page.find("#alignment-file").send_keys(str(path))
    page.network()
    page.run("assessments", lambda: page.find("#alignment-assess").click(), timeout_s=180)
    sent, _ = page.network()
    paths = [urlsplit(u).path for u in sent.values()]
    assert "/v1/jobs" in paths and "/v1/alignments/assess" in paths  # tried, refused, then one request
    assert "a job needs the bearer key" in page.text("#alignment-progress-text")
    assert page.text("#alignment-summary").startswith(f"{JOB_ROWS + 1} curves")
    assert page.find_all("#alignment-error") and not page.find("#alignment-error").is_displayed()


def test_the_cancel_button_cancels_a_job_before_it_ends(page, api, live_server, tmp_path):
    # the page's job is held in the queue behind a long one (a 1,000,000-case sweep on the server's one job
    # thread; an alignment job alone ends in well under a second since its pairs are solved once), then cancelled
    # from the page: the page stops polling, says so, draws no table, and the service has the job cancelled
    auth = {"Authorization": f"Bearer {live_server.key}"}
    grid = {
        "bank_percent": [i * 0.05 for i in range(200)],
        "slope_percent": [i * 0.04 - 4 for i in range(200)],
        "overweight_percent": list(range(25)),
    }
    blocker = api.post(
        "/v1/jobs",
        json={"operation": "srt.sweep", "request": {"vehicle": "table16-btrain", "grid": grid}},
        headers=auth,
    )
    assert blocker.status_code == 202, blocker.text
    try:
        path = tmp_path / "huge.csv"
        path.write_text(large_csv(20_000))
        page.open("?vehicle=table16-btrain")
        page.find("#catalog-box summary").click()
        page.type("#api-key", live_server.key)
        page.find("#alignment-file").send_keys(str(path))
        page.network()

        def submit_and_cancel():
            page.find("#alignment-assess").click()
            WebDriverWait(page.driver, 60).until(lambda _: page.find("#alignment-cancel").is_displayed())
            page.find("#alignment-cancel").click()

        page.run("assessments", submit_and_cancel, timeout_s=120)
        assert "cancelled" in page.text("#alignment-error")
        assert page.find_all("#curves-table") == [] and not page.find("#alignment-cancel").is_displayed()
        sent, _ = page.network()
        (job,) = {urlsplit(u).path for u in sent.values() if urlsplit(u).path.startswith("/v1/jobs/job_")}
        assert ok(api.get(job, headers=auth))["status"] == "cancelled"
    finally:
        api.delete(blocker.headers["Location"], headers=auth)


def test_a_route_above_the_synchronous_size_runs_as_a_job(page, api, live_server, tmp_path):
    text = gpx_track()
    path = tmp_path / "route.gpx"
    path.write_text(text)
    page.open("?vehicle=table16-btrain")
    page.driver.execute_script(  # the page's route job size (20,000 vertices) below this track's ~100
        "return import('/web/js/alignment.js').then((m) => { m.settings.jobVertices = 10; });"
    )
    page.find("#catalog-box summary").click()
    page.type("#api-key", live_server.key)
    page.find("#alignment-file").send_keys(str(path))
    page.type("#al-posted", "80")
    page.type("#al-e", "6")
    page.network()
    page.run("assessments", lambda: page.find("#alignment-assess").click(), timeout_s=120)
    sent, _ = page.network()
    paths = {urlsplit(u).path for u in sent.values()}
    assert "/v1/jobs" in paths and "/v1/routes/assess" not in paths
    assert page.text("#alignment-progress-text").startswith("100 %")
    assert page.text("#alignment-progress-text").endswith("vertices; job done)")
    # the same curve as the synchronous answer (test_an_uploaded_gpx_route_shows_its_curve_radius_...)
    body = {"vehicle": "table16-btrain", "gpx": text, "posted_speed_kmh": 80, "superelevation_percent": 6}
    answer = ok(api.post("/v1/routes/assess", json=body))  # the page sends only what was typed
    (row,) = curve_rows(page)
    assert row["safe_speed_kmh"] == f"{answer['curves'][0]['assessment']['safe_speed_kmh']:.1f}"
    # the downloads of a job read what the job keeps: its CSV from the service, its curves as the service's GeoJSON
    downloads = tmp_path / "downloads"
    downloads.mkdir()
    page.driver.execute_cdp_cmd("Browser.setDownloadBehavior", {"behavior": "allow", "downloadPath": str(downloads)})
    page.network()
    page.find("#download-json").click()
    page.find("#download-csv").click()
    WebDriverWait(page.driver, 30).until(
        lambda _: {p.name for p in downloads.iterdir()} >= {"route-curves.geojson", "route-curves.csv"}
    )
    sent, _ = page.network()
    assert "/v1/routes/assess" not in {urlsplit(u).path for u in sent.values()}  # not the synchronous request
    geojson = ok(api.post("/v1/routes/assess", json=body, headers={"Accept": "application/geo+json"}))
    assert json.loads((downloads / "route-curves.geojson").read_text()) == geojson
    assert (downloads / "route-curves.csv").read_text().count("\n") == 1 + len(answer["curves"])

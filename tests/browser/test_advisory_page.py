"""Advisory speeds on the page and the printout (issue 43, "Where users see it"): every assessed curve's advisory speed
in the plaque's increment, its treatment in words, the W1-13 truck rollover warning and the speed profile's figures
in the curves' table, its filter and the downloads; the speed profile's plot with what it depends on; the primary
method said to be unverified in words; a second printed table of the same curves; the advisory speed of one curve
beside its maximum speed.

The expected values come from the public API answering the same request, and from the plaque's definition (a US
plaque is a multiple of 5 mph, 1 mph = 1.609344 km/h exactly), never from the page.
"""

from __future__ import annotations

import csv
import io
import json
from pathlib import Path

import pytest
from selenium.webdriver.support.ui import WebDriverWait

from .harness import wait_until_computed
from .test_road_printout import print_pdf, runs, squeeze

pytestmark = [pytest.mark.browser, pytest.mark.slow]

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
MPH = 1.609344  # km per international mile, by definition

#: the sign's and the profile's columns, as the screen and the printout head them
SIGN_HEADINGS = [
    "Advisory speed (plaque)", "Treatment (signs)", "W1-13 truck rollover warning", "Approach speed [km/h]",
    "Required deceleration [m/s\u00b2]", "Why no profile figure",
]  # fmt: skip

CELL = """
const keys = Array.from(document.querySelectorAll('#curves-table thead button.sort')).map((b) => b.dataset.key);
return Array.from(document.querySelectorAll('#curves-table tbody tr')).map((tr) => {
  const row = {};
  keys.forEach((k, i) => { row[k] = tr.cells[i].textContent; });
  return row;
});
"""


def wait_js(page, condition: str, timeout_s: float = 60) -> None:
    WebDriverWait(page.driver, timeout_s, poll_frequency=0.25).until(
        lambda _: page.driver.execute_script(f"return Boolean({condition})")
    )


def plaque_mph(kmh: float) -> int:
    mph = kmh / MPH
    assert abs(mph - round(mph)) < 1e-9 and round(mph) % 5 == 0, kmh  # the plaque's increment (5 mph)
    return round(mph)


def test_a_road_file_shows_filters_downloads_and_prints_its_advisory_speeds(page, api, tmp_path):
    page.open("?vehicle=table16-btrain")
    page.find("#alignment-file").send_keys(str(EXAMPLES / "alignment-feet.xml"))
    page.type("#al-posted", "90")
    page.run("assessments", lambda: page.find("#alignment-assess").click(), timeout_s=120)
    document = (EXAMPLES / "alignment-feet.xml").read_text()
    request = {"vehicle": "table16-btrain", "landxml": {"document": document, "posted_speed_kmh": 90}}
    answer = api.post("/v1/alignments/assess", json=request)
    assert answer.status_code == 200, answer.text
    result = answer.json()
    rows = {r["id"]: r for r in result["vehicles"][0]["rows"]}
    assert result["advisory"]["units"] == "us"

    # the table: every curve's plaque (mph, and km/h), its devices in words, its W1-13 flag, its approach speed
    shown = {r["id"]: r for r in page.driver.execute_script(CELL)}
    assert set(shown) == set(rows)
    for key, row in rows.items():
        cells = shown[key]
        kmh = row["advisory_speed_kmh"]
        assert cells["advisory_speed_kmh"] == f"{plaque_mph(kmh)} mph ({kmh:.1f} km/h)"
        devices = row["treatment"]["devices"]
        assert cells["treatment_devices"] == ("; ".join(devices) if devices else "none called for")
        recommended = row["truck_rollover_warning"]["recommended"]
        assert cells["truck_rollover_warning"] == ("\u26a0 recommended" if recommended else "not recommended")
        assert cells["approach_speed_kmh"] == f"{row['approach_speed_kmh']:.1f}"
        assert cells["required_deceleration_mps2"] == f"{row['required_deceleration_mps2']:.2f}"
    labels = [b.text for b in page.find_all("#curves-table thead button.sort")]
    for heading in SIGN_HEADINGS:
        assert heading in labels
    assert not any("_" in label for label in labels)  # words, not field names

    # the signs to post, counted from the API's rows; the primary method in words, with no speed of its own
    signed = [r for r in rows.values() if r["treatment"]["devices"]]
    assert signed  # the sample's K2 calls for a plaque at 90 km/h posted
    line = page.text("#alignment-signs .signs-line")
    for device in {d for r in signed for d in r["treatment"]["devices"]}:
        n = sum(device in r["treatment"]["devices"] for r in rows.values())
        assert f"{device} at {n} curve{'s' if n > 1 else ''}" in line
    notes = page.text("#alignment-signs .method-notes")
    # in the service's own words: which method set the speeds, and why the primary one gives none
    assert "Primary method unverified" in notes and "no speed is computed from it" in notes
    assert result["advisory"]["primary_method"] in notes and result["advisory"]["method_source"] in notes
    assert result["advisory"]["treatment_source"] in notes

    # the filter: the curves whose treatment calls for signs
    page.driver.execute_script(
        "const s = document.querySelector('#curves-filter'); s.value = 'signed'; s.dispatchEvent(new Event('change'));"
    )
    wait_js(page, f"document.querySelector('#curves-shown').textContent.endsWith('of {len(signed):,}')")
    assert sorted(r["id"] for r in page.driver.execute_script(CELL)) == sorted(r["id"] for r in signed)

    # the speed profile: the service's plot of the same request, and what it depends on
    profile = page.find("#speed-profile")
    plot = profile.find_element("css selector", "svg")
    assert plot.get_attribute("aria-label") == "Truck speed profile against station"
    caption = profile.find_element("css selector", "figcaption").text
    assert "each curve's posted speed" in caption and "3.048 m/s\u00b2 (10 ft/s\u00b2)" in caption

    # the downloads are the service's answers: both carry the advisory fields
    downloads = tmp_path / "downloads"
    downloads.mkdir()
    page.driver.execute_cdp_cmd("Browser.setDownloadBehavior", {"behavior": "allow", "downloadPath": str(downloads)})
    saves = (("#download-csv", "alignment-feet-curves.csv"), ("#download-json", "alignment-feet-assessment.json"))
    for button, name in saves:
        page.driver.execute_script(f"document.querySelector('{button}').click()")
        saved = downloads / name
        WebDriverWait(page.driver, 60).until(lambda _, s=saved: s.exists() and not list(downloads.glob("*.crdownload")))
    table = list(csv.DictReader(io.StringIO((downloads / "alignment-feet-curves.csv").read_text())))
    advised = {k: r["advisory_speed_kmh"] for k, r in rows.items()}
    assert {r["id"]: float(r["advisory_speed_kmh"]) for r in table} == advised
    assert all("treatment_devices" in r and "truck_rollover_warning" in r for r in table)
    saved_json = json.loads((downloads / "alignment-feet-assessment.json").read_text())
    assert saved_json["advisory"] == result["advisory"]

    # the printout: the signs' table on a page of its own, the plot, the method's words; nothing beyond the edge
    pdf = list(print_pdf(page).pages)
    road = [p for p in pdf if float(p.mediabox.width) > float(p.mediabox.height)]
    body = squeeze("".join(p.extract_text() for p in road))
    assert squeeze("Signs and the truck's speed profile") in body
    for heading in SIGN_HEADINGS:
        assert squeeze(heading) in body, heading
    assert squeeze("The truck's speed profile.") in body and squeeze("Primary method unverified") in body
    for row in rows.values():
        assert squeeze(f"{plaque_mph(row['advisory_speed_kmh'])} mph") in body
    for p in road:
        assert all(0 <= x < float(p.mediabox.width) - 20 for x, _ in runs(p))


def test_one_curve_shows_its_advisory_speed_beside_its_maximum_speed(page, api):
    page.open("?vehicle=table16-btrain&bank_percent=6&radius_m=200")
    page.type("#speed-posted", "90")
    page.run("computations", lambda: page.find("#speed-compute").click(), timeout_s=120)
    # the link keeps the posted speed: opened again, it shows the same line
    link = page.driver.current_url
    assert "posted_speed_kmh=90" in link
    page.driver.get(link)
    wait_until_computed(page.driver)
    answer = api.post(
        "/v1/advisory-speed",
        json={"vehicle": "table16-btrain", "radius_m": 200, "superelevation_percent": 6, "posted_speed_kmh": 90},
    )
    assert answer.status_code == 200, answer.text
    out = answer.json()
    mph = plaque_mph(out["advisory_speed_kmh"])
    assert mph == out["advisory_speed_mph"]
    line = page.text("#advisory-line")
    assert line.startswith(f"Posted 90 km/h: advisory speed {mph} mph ({out['advisory_speed_kmh']:.1f} km/h), set by")
    # each method's speed; the ones the answer gives none (the unverified primary method) say so in words
    cells = page.driver.execute_script(
        "return Array.from(document.querySelectorAll('#advisory-result tbody tr')).map((tr) =>"
        " Array.from(tr.cells).map((c) => c.textContent));"
    )
    assert len(cells) == len(out["methods"])
    for method, row in zip(out["methods"], cells, strict=True):
        if method["speed_kmh"] is None:
            assert row[1] == "unverified: no speed"
        else:
            assert row[1] == f"{method['speed_kmh']:.1f}"
        assert row[2] == ("verified" if method["verified"] else "unverified")
    assert any(m["id"] == "design-method" and m["speed_kmh"] is None for m in out["methods"])
    body = squeeze("".join(p.extract_text() for p in print_pdf(page).pages))
    assert squeeze(f"advisory speed {mph} mph") in body and squeeze("unverified: no speed") in body


def test_a_route_draws_its_speed_profile_from_its_answer(page, api):
    """The service plots an alignment's request only; a route's profile is drawn on the page from the answer's
    `speed_profile`: one vertex a profile point, in the same order (chainage increasing), with what it depends on."""
    page.open("?vehicle=table16-btrain")
    page.find("#alignment-file").send_keys(str(EXAMPLES / "road.gpx"))
    page.type("#al-e", "7.5")  # examples/README.md: the GPX sample's superelevation and posted speed
    page.type("#al-posted", "70")
    page.run("assessments", lambda: page.find("#alignment-assess").click(), timeout_s=120)
    document = (EXAMPLES / "road.gpx").read_text()
    body = {"vehicle": "table16-btrain", "gpx": document, "superelevation_percent": 7.5, "posted_speed_kmh": 70}
    answer = api.post("/v1/routes/assess", json=body)
    assert answer.status_code == 200, answer.text
    profile = answer.json()["vehicles"][0]["speed_profile"]
    assert len(profile) >= 2
    svg = page.find("#speed-profile svg")
    assert svg.get_attribute("aria-label") == "Truck speed profile against chainage (route)"
    points = page.driver.execute_script(
        "return document.querySelector('#speed-profile svg polyline').getAttribute('points').split(' ')"
        ".map((p) => p.split(',').map(Number));"
    )
    assert len(points) == len(profile)
    xs = [x for x, _ in points]
    assert xs == sorted(xs)
    # the drawn heights keep the profile's order of speeds (a lower speed is drawn lower: a larger y)
    for (_, ya), (_, yb), a, b in zip(points, points[1:], profile, profile[1:], strict=False):
        if a["speed_kmh"] < b["speed_kmh"]:
            assert ya > yb
        elif a["speed_kmh"] > b["speed_kmh"]:
            assert ya < yb
    caption = page.text("#speed-profile figcaption")
    assert "each curve's posted speed" in caption and "m/s\u00b2" in caption
    assert squeeze("Truck speed profile along the route") in squeeze(
        "".join(p.extract_text() for p in print_pdf(page).pages)
    )

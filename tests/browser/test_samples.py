"""Samples that work as they are (issue 41, point 4), at window widths 1366 and 390: every file of examples/ chosen
on the page with its defaults. The CSV tables carry their superelevation, grade and posted speed and are assessed
as they are; the LandXML, GPX and GeoJSON files carry none, and the page says so beside the box that supplies it,
in words and once, before any request -- then assesses them with the values examples/README.md gives (K1: 7.5 %,
70 km/h). A file that is not text is said to be so. The page sends only what the user typed.

The expected rows come from the public API answering the same request, never from the page.
"""

from __future__ import annotations

import json
from pathlib import Path
from urllib.parse import urlsplit

import pytest
from selenium.webdriver.support.ui import WebDriverWait

from .harness import ROOT

pytestmark = [pytest.mark.browser, pytest.mark.slow]

EXAMPLES = ROOT / "examples"
#: the page's start: its default vehicle, a combination, solved with the whole-combination model
DEFAULTS = {"vehicle": "tractor-semitrailer-table15", "model": "combination"}


def curve_rows(page) -> list[dict]:
    """The curves' table as dicts keyed by each column's API field (read in one script)."""
    script = """
      const keys = Array.from(document.querySelectorAll('#curves-table thead button.sort')).map((b) => b.dataset.key);
      return Array.from(document.querySelectorAll('#curves-table tbody tr')).map((tr) =>
        Object.fromEntries(Array.from(tr.cells).map((td, i) => [keys[i], td.textContent.trim()])));
    """
    return page.driver.execute_script(script)


def choose(page, path: Path) -> None:
    page.find("#alignment-file").send_keys(str(path))


def assess_requests(page) -> list[str]:
    return [u for u in page.network()[0].values() if urlsplit(u).path.endswith("/assess")]


def notes_saying(page, words: str) -> int:
    return page.driver.execute_script(
        "return Array.from(document.querySelectorAll('.file-note, .field-error, .form-error'))"
        ".filter((n) => n.textContent.includes(arguments[0])).length",
        words,
    )


def expect_rows(page, answer_rows: list[dict]) -> None:
    """The page's rows are the API's: each curve by the file's id, its safe speed and margin as shown."""
    shown = {r["id"]: r for r in curve_rows(page)}
    assert set(shown) == {r["id"] for r in answer_rows}
    for r in answer_rows:
        assert shown[r["id"]]["safe_speed_kmh"] == f"{r['safe_speed_kmh']:.1f}"
        if r.get("margin_kmh") is not None:
            assert shown[r["id"]]["margin_kmh"].replace("\u2212", "-") == f"{r['margin_kmh']:+.1f}"


@pytest.fixture(params=[1366, 390], ids=["desktop", "phone"])
def width(request, page):
    page.driver.set_window_size(request.param, 900)
    return request.param


@pytest.mark.parametrize("name", ["curves-comma.csv", "curves-semicolon.csv", "curves-tab.tsv"])
def test_a_sample_table_is_assessed_with_the_page_defaults(page, api, width, name):
    text = (EXAMPLES / name).read_text(encoding="utf-8-sig")
    page.open()
    choose(page, EXAMPLES / name)
    WebDriverWait(page.driver, 10).until(lambda _: page.text("#alignment-file-info"))
    assert "with superelevations, posted speeds, grades" in page.text("#alignment-file-info")
    assert not page.find_all(".file-note")  # it needs nothing
    page.run("assessments", lambda: page.find("#alignment-assess").click())
    answer = api.post("/v1/alignments/assess", json={**DEFAULTS, "csv": text})
    assert answer.status_code == 200, answer.text
    expect_rows(page, answer.json()["vehicles"][0]["rows"])
    # named in road order (the file's order: no stations), the file's id beside
    assert [(r["name"], r["id"]) for r in sorted(curve_rows(page), key=lambda r: r["name"])] == [
        ("C1", "K1"),
        ("C2", "K2"),
    ]
    # found by its name or the file's id
    page.type("#curves-find", "K2")
    WebDriverWait(page.driver, 10).until(lambda _: [r["id"] for r in curve_rows(page)] == ["K2"])
    page.type("#curves-find", "c1")
    WebDriverWait(page.driver, 10).until(lambda _: [r["id"] for r in curve_rows(page)] == ["K1"])


@pytest.mark.parametrize("name", ["alignment.xml", "road.gpx", "road.geojson"])
def test_a_sample_without_superelevation_says_so_before_the_request_then_is_assessed(page, api, width, name):
    path = EXAMPLES / name
    text = path.read_text()
    page.open()
    page.network()
    choose(page, path)
    WebDriverWait(page.driver, 10).until(lambda _: "gives no superelevation" in page.field_error("#al-e"))
    assert notes_saying(page, "gives no superelevation") == 1
    # assessing anyway: nothing is sent, and the note stays once, at its box
    page.run("assessments", lambda: page.find("#alignment-assess").click())
    assert assess_requests(page) == []
    assert notes_saying(page, "gives no superelevation") == 1
    assert page.driver.switch_to.active_element.get_attribute("id") == "al-e"
    # the values examples/README.md gives for K1: 7.5 % and 70 km/h
    page.type("#al-e", "7.5")
    page.type("#al-posted", "70")
    page.run("assessments", lambda: page.find("#alignment-assess").click())
    assert not page.find("#alignment-error").is_displayed()
    if name == "alignment.xml":
        body = {**DEFAULTS, "landxml": {"document": text, "superelevation_percent": 7.5, "posted_speed_kmh": 70}}
        answer = api.post("/v1/alignments/assess", json=body)
        assert answer.status_code == 200, answer.text
        expect_rows(page, answer.json()["vehicles"][0]["rows"])
    else:
        kind = "gpx" if name.endswith(".gpx") else "geojson"
        document = text if kind == "gpx" else json.loads(text)
        body = {**DEFAULTS, kind: document, "superelevation_percent": 7.5, "posted_speed_kmh": 70}
        answer = api.post("/v1/routes/assess", json=body)
        assert answer.status_code == 200, answer.text
        rows = [{**c["assessment"], "id": c["id"], "start_m": c["start_m"]} for c in answer.json()["curves"]]
        expect_rows(page, rows)
        # C1, C2 in road order: by station (README: K1 from chainage 300 m, K2 from 830 m)
        named = {r["name"]: r for r in curve_rows(page)}
        assert set(named) == {"C1", "C2"}
        assert float(named["C1"]["station_m"].replace(",", "")) < float(named["C2"]["station_m"].replace(",", ""))


def test_a_file_that_is_not_text_is_said_to_be_so(page, tmp_path, width):
    path = tmp_path / "photo.csv"
    path.write_bytes(b"\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR" + bytes(range(256)) * 4)  # a PNG renamed .csv
    page.open()
    page.network()
    choose(page, path)
    WebDriverWait(page.driver, 10).until(lambda _: "is not a text file" in page.field_error("#alignment-file"))
    page.run("assessments", lambda: page.find("#alignment-assess").click())
    assert assess_requests(page) == []
    assert notes_saying(page, "is not a text file") == 1

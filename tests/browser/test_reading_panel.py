"""What was read from a road file (issue 39 item 8): after an upload the page shows a "Read from the file" panel above
the results, and the printout carries it on the road's first page, at window widths 1366 and 390.

The expected unit, profile and skipped parts come from the public API answering the same request (its `reading`),
and from the files themselves: examples/alignment-feet.xml declares `<Imperial linearUnit="foot">` with a `Design`
profile and `Superelevation` elements (examples/make_examples.py); examples/drive.gpx holds GPSBabel's empty
`ACTIVE LOG` track and a router's `<rte>` beside the track (docs/routes.md, Empty parts and Routers' `<rte>`).
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from .test_road_printout import print_pdf, squeeze

pytestmark = [pytest.mark.browser, pytest.mark.slow]

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def upload(page, name: str | Path, superelevation: str | None = None) -> str:
    """Uploads an example by name, or any file by its path, and returns the reading panel's text."""
    page.find("#alignment-file").send_keys(str(name if isinstance(name, Path) else EXAMPLES / name))
    if superelevation is not None:
        page.type("#al-e", superelevation)
    page.run("assessments", lambda: page.find("#alignment-assess").click(), timeout_s=120)
    return page.text("#alignment-results section.reading")


def first_road_page(page) -> str:
    """The text of the printout's first A4 landscape page (the road's first page), squeezed."""
    pages = list(print_pdf(page).pages)
    road = [p for p in pages if float(p.mediabox.width) > float(p.mediabox.height)]
    assert road
    return squeeze(road[0].extract_text())


@pytest.mark.parametrize("width", [1366, 390])
def test_a_landxml_in_feet_shows_and_prints_what_was_read(page, api, width):
    page.driver.set_window_size(width, 900)
    page.open("?vehicle=table16-btrain")
    panel = upload(page, "alignment-feet.xml")
    document = (EXAMPLES / "alignment-feet.xml").read_text()
    answer = api.post("/v1/alignments/assess", json={"vehicle": "table16-btrain", "landxml": {"document": document}})
    assert answer.status_code == 200, answer.text
    reading = answer.json()["reading"]
    assert reading["linear_unit"] == "foot" and reading["profile"] == "Design"  # what the file declares
    assert reading["superelevation_from"] == "file"

    assert panel.startswith("Read from the file")
    assert "feet (international foot, 0.3048 m)" in panel
    assert reading["format"] in panel and reading["writer"] in panel
    assert f"Profile used\n{reading['profile']}" in panel or f"Profile used {reading['profile']}" in panel
    assert "the file (its superelevation elements" in panel  # in words, not `file`
    for name in reading["alignments"]:
        assert name in panel
    for kind, n in reading["elements"].items():
        assert f"{kind} {n}" in panel
    assert "Nothing in the file was skipped." in panel and not reading["skipped"]
    # labels in words, not the answer's snake_case field names
    labels = [n.text for n in page.find_all("#alignment-results section.reading dt")]
    assert labels == [
        "Format", "Written by", "Length unit", "Alignment read", "Elements read", "Profile used", "Superelevation from",
    ]  # fmt: skip
    # above the results
    order = page.driver.execute_script(
        "const box = document.querySelector('#alignment-results');"
        "return [box.querySelector('section.reading'), box.querySelector('#alignment-summary')]"
        ".map((n) => Array.from(box.querySelectorAll('*')).indexOf(n));"
    )
    assert 0 <= order[0] < order[1]
    # the panel fits the window (no sideways scrolling of the page at 390 px)
    assert page.driver.execute_script("return document.documentElement.scrollWidth <= window.innerWidth")

    printed = first_road_page(page)
    assert squeeze("Read from the file") in printed
    assert squeeze("feet (international foot, 0.3048 m)") in printed and squeeze("Design") in printed


@pytest.mark.parametrize("width", [1366, 390])
def test_a_gpx_shows_and_prints_its_skipped_parts_with_why(page, api, width):
    page.driver.set_window_size(width, 900)
    page.open("?vehicle=table16-btrain")
    panel = upload(page, "drive.gpx", superelevation="4")
    document = (EXAMPLES / "drive.gpx").read_text()
    body = {"vehicle": "table16-btrain", "gpx": document, "superelevation_percent": 4}
    answer = api.post("/v1/routes/assess", json=body)
    assert answer.status_code == 200, answer.text
    reading = answer.json()["reading"]
    whats = [s["what"] for s in reading["skipped"]]
    # the file's empty GPSBabel track and its router's turn points (docs/routes.md)
    assert any("ACTIVE LOG" in w for w in whats) and any(w.startswith("rte[") for w in whats)

    assert panel.startswith("Read from the file")
    assert "Length unit\nmetres" in panel or "Length unit metres" in panel
    assert f"Profile used\n{reading['profile']}" in panel or f"Profile used {reading['profile']}" in panel
    assert "the superelevation typed in this form" in panel
    assert f"Skipped ({len(whats)}), and why:" in panel
    for item in reading["skipped"]:
        assert f"{item['what']}: {item['why']}" in panel

    printed = first_road_page(page)
    assert squeeze("Read from the file") in printed and squeeze("metres") in printed
    for item in reading["skipped"]:
        assert squeeze(item["what"]) in printed


@pytest.mark.parametrize("width", [1366, 390])
def test_an_ifc_file_is_accepted_and_shows_what_was_read(page, api, width):
    page.driver.set_window_size(width, 900)
    page.open("?vehicle=table16-btrain")
    assert ".ifc" in page.find("#alignment-file").get_attribute("accept").split(",")
    panel = upload(page, "road.ifc")
    # the page's line under the file box: two circular arcs, K1 and K2 (examples/README.md, road.ifc)
    assert page.text("#alignment-file-info").startswith(
        "road.ifc: an IFC 4.3 alignment, 2 curves, with superelevations"
    )
    document = (EXAMPLES / "road.ifc").read_text()
    answer = api.post("/v1/alignments/assess", json={"vehicle": "table16-btrain", "ifc": {"document": document}})
    assert answer.status_code == 200, answer.text
    result = answer.json()
    reading = result["reading"]
    # its cant read as the cross slope (docs/uploads.md, IFC 4.3), the zero-length closing segments skipped
    assert reading["superelevation_from"] == "cross-sections" and reading["skipped"]

    assert panel.startswith("Read from the file") and reading["format"] in panel
    assert "Length unit\nmetres" in panel or "Length unit metres" in panel
    assert "the file's cross sections (their cross slopes)" in panel
    for kind, n in reading["elements"].items():
        assert f"{kind} {n}" in panel
    texts = [n.get_attribute("textContent") for n in page.find_all("#alignment-results section.reading .skipped li")]
    assert texts == [f"{s['what']}: {s['why']}" for s in reading["skipped"]]
    # the page's curves are the API's
    assert page.text("#alignment-summary").startswith(f"{len(result['vehicles'][0]['rows'])} curves")


def test_an_alignment_job_shows_and_prints_what_was_read(page, api, live_server):
    """A road file assessed as a job (issue 39 point 9): its rows are read as CSV, which holds no `reading`; the page
    reads the head of the job's JSON result (its `reading` and `advisory`, written before the rows) and shows the
    same panel as the synchronous answer's, and the plaques in the answer's units."""
    page.open("?vehicle=table16-btrain")
    # the page's job size (5,000 curves) lowered, so this two-curve file goes through POST /v1/jobs
    page.driver.execute_script("return import('/web/js/alignment.js').then((m) => { m.settings.jobRows = 1; });")
    page.find("#catalog-box summary").click()  # the jobs of a deployment with keys are the key's own
    page.type("#api-key", live_server.key)
    page.network()
    panel = upload(page, "alignment-feet.xml")
    assert page.text("#alignment-progress-text").endswith("job done)")
    sent, _ = page.network()
    assert any(u.endswith("/v1/jobs") for u in sent.values())
    assert not any(u.endswith("/v1/alignments/assess") for u in sent.values())

    document = (EXAMPLES / "alignment-feet.xml").read_text()
    answer = api.post("/v1/alignments/assess", json={"vehicle": "table16-btrain", "landxml": {"document": document}})
    assert answer.status_code == 200, answer.text
    reading = answer.json()["reading"]
    assert panel.startswith("Read from the file")
    assert "feet (international foot, 0.3048 m)" in panel and reading["format"] in panel
    assert f"Profile used\n{reading['profile']}" in panel or f"Profile used {reading['profile']}" in panel
    for kind, n in reading["elements"].items():
        assert f"{kind} {n}" in panel
    # the plaques in the answer's units (US: mph beside km/h), read from the same head
    cells = page.driver.execute_script(
        "const keys = Array.from(document.querySelectorAll('#curves-table thead button.sort'))"
        ".map((b) => b.dataset.key);"
        "return Array.from(document.querySelectorAll('#curves-table tbody tr')).map((tr) =>"
        " tr.cells[keys.indexOf('advisory_speed_kmh')].textContent);"
    )
    assert cells and all(" mph (" in c for c in cells)
    assert squeeze("Read from the file") in first_road_page(page)


def test_what_the_reader_assumed_is_shown_and_printed(page, api, tmp_path):
    """An IFC file whose alignment name is written in raw UTF-8 (ISO 10303-21 asks for \\X2\\ escapes) and with no
    STATION referent: the name is read whole and the reading's two notes (docs/uploads.md) are listed on the page and
    on paper, word for word as the API gives them."""
    text = (EXAMPLES / "road.ifc").read_text()
    (name,) = [
        n
        for n in api.post(
            "/v1/alignments/assess", json={"vehicle": "table16-btrain", "ifc": {"document": text}}
        ).json()["reading"]["alignments"]
    ]
    path = tmp_path / "road-raw-utf8.ifc"
    path.write_bytes(text.replace(f"'{name}'", "'Rodovia São José'").encode("utf-8"))
    assert "São" in path.read_text(encoding="utf-8")
    page.open("?vehicle=table16-btrain")
    panel = upload(page, path)
    answer = api.post(
        "/v1/alignments/assess",
        json={"vehicle": "table16-btrain", "ifc": {"document": path.read_text(encoding="utf-8")}},
    ).json()
    notes = answer["reading"]["notes"]
    assert answer["reading"]["alignments"] == ["Rodovia São José"]
    assert any("outside ASCII" in n for n in notes)
    assert "Assumed where the file is silent:" in panel and "Rodovia São José" in panel
    shown = [n.get_attribute("textContent") for n in page.find_all("#alignment-results section.reading .notes li")]
    assert shown == notes
    printed = first_road_page(page)
    assert all(squeeze(n) in printed for n in notes)


def test_a_typed_record_that_reads_plausibly_in_tonnes_warns_above_the_road_results(page, api):
    """An alignment assessed for a pasted record of 50 "kN" (a light trailer, or 50 t typed as kN): the answer's
    per-vehicle warning is shown above the curves in the service's words; the preset alone shows none."""
    page.open("?vehicle=table16-btrain")
    upload(page, "alignment-feet.xml")
    assert page.find_all("#alignment-warnings") == []
    for selector in ('input[name="source"][value="record"]', "#record-from-preset"):
        # back up the page, clear of the sticky compute bar
        node = page.find(selector)
        page.driver.execute_script("arguments[0].scrollIntoView({block: 'center'})", node)
        node.click()
    record = json.loads(page.find("#record-json").get_attribute("value"))
    page.type("#record-json", json.dumps({**record, "weight_kn": 50}))
    page.run("assessments", lambda: page.find("#alignment-assess").click(), timeout_s=120)
    document = (EXAMPLES / "alignment-feet.xml").read_text()
    answer = api.post(
        "/v1/alignments/assess", json={"vehicle": {**record, "weight_kn": 50}, "landxml": {"document": document}}
    ).json()
    (warning,) = answer["vehicles"][0]["warnings"]
    assert warning["field"] == "vehicle.weight_kn"
    assert page.text("#alignment-warnings li") == f"{warning['field']}: {warning['message']}"

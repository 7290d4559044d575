"""The calculator page guides its user (issue 23 item 3, issue 20 item 5): results marked stale the moment an input
changes or a request fails, the combinations drawn with each roll-coupled unit's SRT and the lift-off sequence, the
verdict in plain words first, Compute always in view, tables whose key columns stay readable, and a printout in
words with units. Each test runs at a desktop (1366 x 900) and a phone (390 x 844) viewport.

Expected numbers come from the public API called directly for the same case -- never from the page itself.
"""

from __future__ import annotations

import contextlib
import json
import unicodedata
from urllib.parse import quote

from selenium.webdriver.support.ui import WebDriverWait

DESKTOP = (1366, 900)
PHONE = (390, 844)


@contextlib.contextmanager
def viewport(page, size):
    """The page's viewport at ``size`` (a phone: a mobile device of that CSS width)."""
    width, height = size
    page.driver.execute_cdp_cmd(
        "Emulation.setDeviceMetricsOverride",
        {"width": width, "height": height, "deviceScaleFactor": 1, "mobile": width < 600},
    )
    try:
        yield
    finally:
        page.driver.execute_cdp_cmd("Emulation.clearDeviceMetricsOverride", {})


def in_viewport(page, selector: str) -> bool:
    """Whether the element is displayed and wholly inside the visible viewport (as scrolled now)."""
    return page.driver.execute_script(
        """const r = document.querySelector(arguments[0]).getBoundingClientRect();
        return r.width > 0 && r.height > 0 && r.top >= 0 && r.left >= 0
          && r.bottom <= window.innerHeight && r.right <= document.documentElement.clientWidth;""",
        selector,
    )


def cells(page, selector: str) -> list[list[str]]:
    """The cells' texts of the rows matched by ``selector`` (read in one script)."""
    script = """return Array.from(document.querySelectorAll(arguments[0]))
      .map((tr) => Array.from(tr.cells).map((td) => td.textContent.trim()));"""
    return page.driver.execute_script(script, selector)


def ok(response):
    assert response.status_code == 200, response.text
    return response.json()


# ------------------------------------------------------------------------------------------- stale results


def test_results_are_marked_stale_when_an_input_changes_or_a_request_fails(page):
    with viewport(page, DESKTOP):
        page.open("?vehicle=table16-btrain&radius_m=80")
        assert page.find("#results-body").get_attribute("data-stale") is None
        assert page.find_all(".stale-banner") == []
        page.type("#bank", "6")  # an edit, not yet computed: every panel that depends on it is marked
        for name, panel in (("srt", "#results-body"), ("design", "#road-results"), ("speed", "#speed-result")):
            assert page.find(panel).get_attribute("data-stale") == "true", name
            assert f"stale-{name}" in page.find(panel).get_attribute("aria-describedby")
            assert page.text(f"#stale-{name}") == "Stale \u2014 inputs changed, press Compute"
        assert float(page.find("#results-body").value_of_css_property("opacity")) < 0.6  # greyed
        # a refused input (bank 60 %): the previous result stays marked, now saying the request failed
        page.type("#bank", "60")
        page.run("computations", lambda: page.find("#compute").click())
        assert page.find("#bank").get_attribute("aria-invalid") == "true"
        assert "request failed" in page.text("#stale-srt")
        assert page.find("#results-body").get_attribute("data-stale") == "true"
        # corrected and computed: fresh again, no banner
        page.type("#bank", "0")
        page.run("computations", lambda: page.find("#compute").click())
        assert page.find_all(".stale-banner") == [] and not page.find("#bar-stale").is_displayed()
        assert page.find("#results-body").get_attribute("data-stale") is None
        # a builder error: the previous SRT is marked as the last request's failure
        page.find('input[name="source"][value="build"]').click()
        assert page.find("#results-body").get_attribute("data-stale") == "true"
        page.type("#b-rear-track", "-1")
        page.run("computations", lambda: page.find("#build-button").click())
        assert page.find("#b-rear-track").get_attribute("aria-invalid") == "true"
        assert "request failed" in page.text("#stale-srt")
        assert page.find("#stale-design").is_displayed()
    with viewport(page, PHONE):  # the same page on a phone: the banner at the result, "(stale)" in the top bar
        page.driver.execute_script("document.querySelector('#stale-srt').scrollIntoView()")
        assert in_viewport(page, "#stale-srt") and in_viewport(page, "#bar-stale")
        assert page.text("#bar-stale") == "(stale)"


# ------------------------------------------------------------------------------------------- combinations


def test_the_default_vehicle_is_a_combination_computed_as_a_whole(page, api):
    page.open()
    assert page.find("#preset").get_attribute("value") == "tractor-semitrailer-table15"
    assert page.find("#model").get_attribute("value") == "combination"
    assert page.find_all("#preset-view svg")  # drawn before anything is computed
    page.run("computations", lambda: page.find("#compute").click())
    expected = ok(api.post("/v1/srt", json={"vehicle": "tractor-semitrailer-table15"}))
    assert page.text("#srt-value") == f"{expected['srt']:.3f} g"
    assert len(page.find_all("#units-table tbody tr")) == len(expected["roll_coupled_units"])
    # the same combination pasted as {"combination": {...}} (the record box, started from the preset)
    page.find('input[name="source"][value="record"]').click()
    page.find("#record-from-preset").click()
    WebDriverWait(page.driver, 10).until(lambda _: '"combination"' in page.find("#record-json").get_attribute("value"))
    assert page.find("#model").get_attribute("value") == "combination"
    page.run("computations", lambda: page.find("#compute").click())
    assert page.text("#srt-value") == f"{expected['srt']:.3f} g"
    assert page.find_all("#combination-result svg g.unit.governing")


def test_a_combination_shows_each_roll_coupled_unit_the_lift_off_sequence_and_the_governing_unit(page, api):
    expected = ok(api.post("/v1/srt", json={"vehicle": "adouble"}))
    detail = ok(api.get("/v1/combinations/adouble"))["combination"]
    with viewport(page, DESKTOP):
        page.open("?vehicle=adouble")
        assert page.text("#srt-value") == f"{expected['srt']:.3f} g"
        units = expected["roll_coupled_units"]
        governing = expected["governing_unit"]
        assert len(units) == 2  # the A-dolly's pintle cuts the A-double in two
        rows = page.find_all("#units-table tbody tr")
        assert [r.find_elements("css selector", "td")[2].text for r in rows] == [f"{u['srt']:.3f}" for u in units]
        assert "governing" in rows[governing].get_attribute("class")
        names = " + ".join(units[governing]["units"])
        assert page.text("#governing-unit") == (
            f"Governed by roll-coupled unit {governing + 1} of 2 ({names}), SRT {units[governing]['srt']:.3f} g."
        )
        assert cells(page, "#lift-table tbody tr") == [
            [str(i + 1), s["unit"], s["group"], f"{s['ay_g']:.3f}"] for i, s in enumerate(expected["lift_sequence"])
        ]
        # the side view: one box per unit, a wheel per axle, a mark per coupling; the governing units highlighted
        svg = "#combination-result svg"
        assert [g.get_attribute("data-unit") for g in page.find_all(f"{svg} g.unit")] == [
            u["id"] for u in detail["units"]
        ]
        axles = sum(g["axles"] for u in detail["units"] for g in u["groups"])
        assert len(page.find_all(f"{svg} circle.wheel")) == axles
        assert len(page.find_all(f"{svg} .coupling")) == len(detail["couplings"])
        highlighted = {g.get_attribute("data-unit") for g in page.find_all(f"{svg} g.unit.governing")}
        assert highlighted == set(units[governing]["units"])
        assert page.find(svg).is_displayed()
    with viewport(page, PHONE):  # on a phone: the drawing and the tables fit the screen's width
        assert page.find(svg).is_displayed() and page.find(svg).size["width"] <= PHONE[0]
        assert page.driver.execute_script(
            "return document.documentElement.scrollWidth <= document.documentElement.clientWidth"
        )


# ------------------------------------------------------------------------------------------- the verdict


def test_the_verdict_comes_first_in_plain_words_and_the_thesis_notation_folded(page, api):
    expected = ok(api.post("/v1/srt", json={"vehicle": "table16-btrain"}))
    general, dangerous = expected["targets"]
    plain = [
        f"\u2717 Below the 0.35 g general target by {-general['margin_g']:.3f} g.",
        f"\u2717 Below the 0.40 g dangerous goods target by {-dangerous['margin_g']:.3f} g.",
    ]
    with viewport(page, DESKTOP):
        page.open("?vehicle=table16-btrain")
        assert [li.text for li in page.find_all("#verdict-plain li")] == plain
        # the thesis's notation second, folded: shown on request
        assert not page.find("#result-facts").is_displayed()
        page.find("#result-details summary").click()
        assert page.find("#result-facts").is_displayed() and "Fz17" in page.text("#result-facts")
        page.find("#result-details summary").click()
    with viewport(page, PHONE):
        page.driver.execute_script("document.querySelector('#verdict-plain').scrollIntoView()")
        assert in_viewport(page, "#verdict-plain") and [li.text for li in page.find_all("#verdict-plain li")] == plain
        assert not page.find("#result-facts").is_displayed()


def test_a_level_road_srt_is_shown_beside_the_curves_threshold_and_numbers_are_rounded(page, api):
    # the service judges targets on the level-road SRT (issue 23 item 1); the page shows both when they differ
    body = {"vehicle": "btrain-table16", "road": {"bank_percent": 6}}
    answer = ok(api.post("/v1/srt", json=body))
    page.open("?vehicle=btrain-table16&bank_percent=6")
    assert page.text("#srt-value") == f"{answer['srt']:.3f} g"
    if "level_road_srt" in answer:
        assert page.text("#level-srt-value") == f"{answer['level_road_srt']:.3f} g"
        assert page.text("#level-srt-line").startswith("Level-road SRT (judged against targets)")
        assert page.text("#srt-label") == "This curve's threshold with its bank and grade"
    else:  # a service without it: as before, one threshold
        assert not page.find("#level-srt-line").is_displayed()
    # an answer with both (and float tails) as the page renders it: both labelled, every number rounded
    fake = {
        **answer,
        "srt": 0.41303990805744695,
        "level_road_srt": 0.3475292046860783,
        "rear_llt_limit": 0.9999999999999994,
        "targets": [
            {"name": "general", "target_g": 0.35, "meets": False, "margin_g": -0.002470795313921699,
             "judged_on": "level_road_srt"},
            {"name": "dangerous_goods", "target_g": 0.4000000000000001, "meets": False,
             "margin_g": -0.05247079531392171, "judged_on": "level_road_srt"},
        ],
    }  # fmt: skip
    page.driver.execute_async_script(
        "const done = arguments[1]; import('/web/js/results.js').then((m) => { m.showResult(arguments[0], null);"
        " done(); });",
        fake,
    )
    assert page.text("#level-srt-value") == "0.348 g" and page.text("#srt-value") == "0.413 g"
    assert page.text("#srt-label") == "This curve's threshold with its bank and grade"
    assert [li.text for li in page.find_all("#verdict-plain li")] == [
        "\u2717 Below the 0.35 g general target by 0.002 g (on the level-road SRT).",
        "\u2717 Below the 0.40 g dangerous goods target by 0.052 g (on the level-road SRT).",
    ]
    assert "rear LLT limit 1)" in page.find("#result-facts").get_attribute("textContent")
    assert "0.9999" not in page.find("#results-body").get_attribute("textContent")


# ------------------------------------------------------------------------------------------- layout

CURVES_CSV = """id,radius_m,superelevation_percent,grade_percent,posted_speed_kmh
WIDE,2000,6,0,60
TIGHT,40,0,0,90
"""


def readable(page, selector: str) -> bool:
    """Whether the element, scrolled to vertically, shows whole inside its table's region and the viewport without
    scrolling the table sideways."""
    return page.driver.execute_script(
        """const e = document.querySelector(arguments[0]);
        window.scrollTo(0, e.getBoundingClientRect().top + window.scrollY - 200);
        const r = e.getBoundingClientRect();
        const wrap = e.closest('.table-wrap').getBoundingClientRect();
        return e.closest('.table-wrap').scrollLeft === 0 && r.width > 0 && r.left >= wrap.left - 0.5
          && r.right <= wrap.right + 0.5 && r.right <= document.documentElement.clientWidth;""",
        selector,
    )


def check_layout(page, width: int) -> None:
    # the result's headline is at the top, with Compute, whatever the width
    page.driver.execute_script("window.scrollTo(0, 0)")
    assert in_viewport(page, "#compute") and in_viewport(page, "#bar-srt")
    assert page.text("#bar-srt") == page.text("#srt-value")
    page.driver.execute_script("window.scrollTo(0, document.documentElement.scrollHeight)")
    assert in_viewport(page, "#compute")  # sticky: still in view at the bottom of the page
    page.find("#jump-result").click()  # one tap to the result, past the whole form on a phone
    assert in_viewport(page, "#srt-value")
    # nothing wider than the screen: wide tables scroll inside their region
    assert page.driver.execute_script(
        "return document.documentElement.scrollWidth <= document.documentElement.clientWidth"
    )
    assert page.find("#srt-value").size["width"] <= width and page.find("#compute").size["width"] <= width
    # the minimum-radius table: the governing radius and what governs it without scrolling sideways
    heads = page.find_all("#road-results thead th")
    assert [h.get_attribute("textContent") for h in heads[:3]] == ["V [km/h]", "Governing R [m]", "Governed by"]
    for i in (1, 2, 3):
        assert readable(page, f"#road-results thead th:nth-child({i})"), (width, i)
    # the alignment table: the flag and the margin next to the curve's name
    keys = [b.get_attribute("data-key") for b in page.find_all("#curves-table thead button.sort")]
    assert keys[:3] == ["name", "flagged", "margin_kmh"]
    for i in (1, 2, 3):
        assert readable(page, f"#curves-table thead th:nth-child({i})"), (width, i)
    assert readable(page, "#curves-table tbody tr:nth-child(1) td:nth-child(2)")  # TIGHT: flagged, so first
    assert page.find("#curves-table tbody tr:nth-child(1) td:nth-child(2)").text == "\u26a0 flagged"


def test_compute_stays_in_view_the_result_is_one_tap_away_and_key_columns_are_readable(page, tmp_path):
    path = tmp_path / "curves.csv"
    path.write_text(CURVES_CSV)
    with viewport(page, DESKTOP):
        page.open("?vehicle=table16-btrain")
        page.find("#alignment-file").send_keys(str(path))
        page.run("assessments", lambda: page.find("#alignment-assess").click())
        check_layout(page, DESKTOP[0])
    with viewport(page, PHONE):
        check_layout(page, PHONE[0])


# ------------------------------------------------------------------------------------------- the printout


def printed(page) -> str:
    import base64
    import io

    from pypdf import PdfReader
    from selenium.webdriver.common.print_page_options import PrintOptions

    options = PrintOptions()
    options.page_width, options.page_height = 21.0, 29.7  # A4 [cm]
    pdf = PdfReader(io.BytesIO(base64.b64decode(page.driver.print_page(options))))
    text = " ".join(" ".join(p.extract_text().split()) for p in pdf.pages)
    return unicodedata.normalize("NFKC", text)  # the PDF's ligatures (ff, fi) as letters


def test_the_printout_of_a_combination_says_which_unit_governs_in_words_with_units(page, api):
    expected = ok(api.post("/v1/srt", json={"vehicle": "adouble"}))
    units = expected["roll_coupled_units"]
    governing = units[expected["governing_unit"]]
    page.open("?vehicle=adouble")
    text = printed(page)
    names = " + ".join(governing["units"])
    assert f"Governed by roll-coupled unit {expected['governing_unit'] + 1} of 2 ({names}), SRT" in text
    assert "Sprung mass [kg]" in text and "CG height [m]" in text and "pintle" in text
    assert "Lift-off sequence" in text and "null" not in text and "sprung_mass_kg" not in text


def test_a_vehicle_below_a_target_is_offered_its_payload_table_and_the_printout_holds_the_tables_shown(
    page, api, tmp_path
):
    components = ok(api.get("/v1/components"))
    tyre, suspension = components["tyres"][0]["id"], components["suspensions"][0]["id"]
    spec = {
        "unit_type": "semitrailer",
        "rear": {"axles": 3, "tyres_per_axle": 4, "track_m": 1.86, "centre_from_kingpin_m": 8.7,
                 "tyre": {"id": tyre}, "suspension": {"type": suspension}},
        "front": {"axles": 2, "tyres_per_axle": 4, "track_m": 1.86, "centre_from_kingpin_m": 0.2},
        "tare": {"mass_kg": 8000, "cg_height_m": 1.1, "cg_from_kingpin_m": 6},
        "payloads": [{"mass_kg": 24000, "deck_height_m": 1.4, "load_height_m": 3.6, "distribution": "uniform"}],
        "deck": {"front_from_kingpin_m": -1, "length_m": 13},
    }  # fmt: skip
    answer = ok(api.post("/v1/srt", json={"vehicle": {"spec": spec}}))
    assert not answer["targets"][0]["meets"]  # 24 t up to 3.6 m: below 0.35 g (tests/browser/test_builder_road_routes)
    with viewport(page, PHONE):  # offered in the result itself on a phone too
        page.open("?spec=" + quote(json.dumps(spec)))
        page.driver.execute_script("document.querySelector('#payload-offer').scrollIntoView({block: 'center'})")
        assert in_viewport(page, "#payload-offer-button")
    with viewport(page, DESKTOP):
        # offered in the result itself, not behind the CG-height form further down
        assert page.find("#payload-offer").is_displayed()
        assert page.text("#payload-offer-button") == "Acceptable payload table for 0.35 g"
        page.driver.execute_script("document.querySelector('#payload-offer').scrollIntoView({block: 'center'})")
        page.run("limits", lambda: page.find("#payload-offer-button").click())
        assert page.find("#payload-tables").is_displayed()
        expected = ok(api.post("/v1/vehicles/payload-table", json={"spec": spec, "target_srt_g": 0.35}))
        first = cells(page, "#payload-tables .scroll-box:first-child tbody tr")
        assert [c[0] for c in first] == [f"{r['load_height_m']:.2f}" for r in expected["by_load_height"]]
        # the button may sit just under the sticky compute bar after the payload table's scroll: centred first
        page.driver.execute_script("document.querySelector('#super-compute').scrollIntoView({block: 'center'})")
        page.run("superelevations", lambda: page.find("#super-compute").click())
        path = tmp_path / "curves.csv"
        path.write_text(CURVES_CSV)
        page.find("#alignment-file").send_keys(str(path))
        page.run("assessments", lambda: page.find("#alignment-assess").click())
        text = printed(page)
    assert "Acceptable payload of the built vehicle" in text and "Largest payload [kg]" in text
    assert "Design superelevation of a curve" in text and "Superelevation by radius" not in text.split("Alignment")[-1]
    assert "Alignment" in text and "TIGHT" in text and "flagged" in text
    assert "Mass (weight W / g):" in text.replace(": ", ":")


def test_each_unit_of_a_combination_can_be_edited(page, api):
    detail = ok(api.get("/v1/combinations/tractor-semitrailer-table15"))["combination"]
    page.open("?vehicle=tractor-semitrailer-table15")
    before = page.text("#srt-value")
    page.find("#units-editor summary").click()
    page.type("#unit-1-cg_height_m", "2.4")  # the semitrailer's CG raised (Table 15's is lower)
    assert page.find("#results-body").get_attribute("data-stale") == "true"
    page.run("computations", lambda: page.find("#compute").click())
    edited = json.loads(json.dumps(detail))
    edited["units"][1]["cg_height_m"] = 2.4
    expected = ok(api.post("/v1/srt", json={"vehicle": {"combination": edited}}))
    assert page.text("#srt-value") == f"{expected['srt']:.3f} g" != before
    assert expected["srt"] < ok(api.post("/v1/srt", json={"vehicle": "tractor-semitrailer-table15"}))["srt"]
    # an impossible mass is refused at its box (the service's plausibility bounds)
    page.type("#unit-1-sprung_mass_kg", "-5")
    page.run("computations", lambda: page.find("#compute").click())
    assert page.find("#unit-1-sprung_mass_kg").get_attribute("aria-invalid") == "true"
    assert "is not plausible for the sprung mass" in page.field_error("#unit-1-sprung_mass_kg")

"""The dynamics section (issue 42, point 5): a combination's PBS screening on the page -- the caveat first, a table of
the measures with value, unit, limit and whether the limit was read ("limit unverified" in words where the rules
could not be read, never a number), the plots of the lane change, the frequency response and the low-speed turn --
and printed on A4 (DevTools Page.printToPDF read back with pypdf: every heading and measure on paper, nothing beyond
the paper's edge).

The expected values come from the public API answering the same request, never from the page.
"""

from __future__ import annotations

import re

import pytest

from .test_road_printout import print_pdf, runs, squeeze

pytestmark = [pytest.mark.browser, pytest.mark.slow]

HEADINGS = ["Measure", "Value", "Unit", "Limit by level", "Level met", "Source"]

#: the plots' titles as the service writes them (their <title>), for the A-double preset
PLOTS = {
    "/v1/dynamics/plots/lane-change": "lane-change",
    "/v1/dynamics/plots/frequency-response": "frequency-response",
    "/v1/dynamics/plots/low-speed-turn": "low-speed-turn",
}

A4 = (595.3, 841.9)  # pt


def title_of(svg: str) -> str:
    return re.search(r"<title>(.*?)</title>", svg, re.S).group(1).strip()


def table_rows(page) -> list[list[str]]:
    return page.driver.execute_script(
        "return Array.from(document.querySelectorAll('#dyn-results table tbody tr')).map((tr) =>"
        " Array.from(tr.cells).map((c) => c.textContent));"
    )


@pytest.mark.parametrize("width", [1366, 390])
def test_a_combination_is_screened_shown_and_printed_on_a4(page, api, width):
    page.driver.set_window_size(width, 900)
    page.open("?vehicle=adouble")
    page.run("screenings", lambda: page.find("#dynamics-compute").click(), timeout_s=120)
    answer = api.post("/v1/pbs", json={"vehicle": "adouble"})
    assert answer.status_code == 200, answer.text
    result = answer.json()
    assert result["screening"] is True

    # the caveat first, with the answer's own words
    first = page.driver.execute_script("return document.querySelector('#dyn-results').firstElementChild.id")
    assert first == "dyn-caveat"
    caveat = page.text("#dyn-caveat")
    assert caveat.lower().startswith(result["note"].lower())  # "indicative screening, not a certification"
    assert "linear passive" in caveat

    # the table: one row a measure, its value as the API gives it, its limit said unverified where it was not read
    heads = [h.text for h in page.find_all("#dyn-results table thead th")]
    assert heads == HEADINGS
    rows = table_rows(page)
    assert len(rows) == len(result["standards"])
    for standard, row in zip(result["standards"], rows, strict=True):
        digits = 2 if standard["unit"] == "m" else 3
        if standard["value"] is None:
            assert row[1].startswith("none")
        else:
            assert float(row[1]) == pytest.approx(standard["value"], abs=0.5 * 10**-digits)
        read = [lim for lim in standard["limits"] if lim["verified"] and lim["limit"] is not None]
        if not read:
            assert row[3].startswith("limit unverified") and not re.search(r"\d+\.\d", row[3])
        else:
            for lim in read:
                assert f"level {lim['level']}" in row[3]
        if standard["level"] is None:
            assert row[4] == "none judged (no verified limit)"
        assert row[5] == standard["source"]
    assert not any("_" in row[0] for row in rows)  # names in words
    conditions = page.text("#dyn-results .dyn-conditions")
    # nothing typed: the three defaults the answer marks unverified, named in words
    assert len(result["conditions"]["unverified_defaults_used"]) == 3
    assert "unverified: lane change speed, lane change amplitude, pulse steer speed" in conditions

    # the three plots: the service's SVG for the same combination
    labels = [s.get_attribute("aria-label") for s in page.find_all("#dyn-results figure svg")]
    expected = []
    for path in PLOTS:
        svg = api.post(path, json={"vehicle": "adouble"})
        assert svg.status_code == 200, svg.text
        expected.append(title_of(svg.text))
    assert labels == expected

    # on paper: A4 pages of their own, the caveat, every heading and measure, nothing beyond the right edge
    pages = list(print_pdf(page).pages)
    mine = [p for p in pages if squeeze("Dynamics: PBS screening") in squeeze(p.extract_text())]
    assert mine
    start = pages.index(mine[0])
    dyn = [p for p in pages[start:] if abs(float(p.mediabox.width) - A4[0]) < 1]
    assert all(abs(float(p.mediabox.height) - A4[1]) < 1 for p in dyn)
    text = squeeze("".join(p.extract_text() for p in dyn))
    assert squeeze(result["note"]).lower() in text.lower() and squeeze("linear passive") in text
    for heading in HEADINGS:
        assert squeeze(heading) in text, heading
    for row in rows:
        assert squeeze(row[0]) in text and squeeze(row[3]) in text
    for standard in result["standards"]:
        assert squeeze(standard["source"]) in text
    for p in dyn:
        right = float(p.mediabox.width)
        assert all(0 <= x < right - 20 for x, _ in runs(p))


def test_a_vehicle_of_one_unit_is_told_to_choose_a_combination(page, api):
    page.open("?vehicle=table16-btrain")
    page.run("screenings", lambda: page.find("#dynamics-compute").click(), timeout_s=120)
    assert "need a combination" in page.field_error("#dyn-vehicle")
    assert not table_rows(page)
    # a preset of the section's own list is screened instead
    page.driver.execute_script(
        "const s = document.querySelector('#dyn-vehicle'); s.value = 'btrain-table16';"
        " s.dispatchEvent(new Event('change'));"
    )
    page.run("screenings", lambda: page.find("#dynamics-compute").click(), timeout_s=120)
    result = api.post("/v1/pbs", json={"vehicle": "btrain-table16"}).json()
    assert len(table_rows(page)) == len(result["standards"])

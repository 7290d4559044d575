"""The printout of a road's assessment (issue 41, point 1), printed to PDF by chromium (DevTools Page.printToPDF)
and read back with pypdf: every column that carries the verdict is on paper, at window widths 1366 and 390, the
summary comes first, the flagged curves are printed worst first, and a line says how many curves the CSV holds.

The expected curves and their order come from the public API answering the same request (the rows sorted here by
their margin), never from the page.
"""

from __future__ import annotations

import base64
import io
import re
import unicodedata

import pytest
from pypdf import PdfReader

pytestmark = [pytest.mark.browser, pytest.mark.slow]

#: the page prints at most this many curves (app/web/js/curves.js `settings.printRows`)
PRINT_ROWS = 500

#: the headings of the columns that carry the verdict, as a reader finds them on paper
VERDICT_HEADINGS = [
    "Curve", "Flag", "Margin [km/h]", "Safe speed [km/h]", "Posted [km/h]", "Governed by", "Id in the file",
    "Radius R [m]", "Superelevation e [%]", "Grade [%]", "SRT [g]", "Rollover speed [km/h]",
    "Side-friction speed [km/h]", "Standard's Rmin [m]", "Meets Rmin",
]  # fmt: skip

#: the headings of the second printed table (the same curves: their sign and the truck's speed profile), which
#: starts on a page of its own (the first fills A4 landscape's width)
SIGN_HEADINGS = [
    "Curve", "Id in the file", "Posted [km/h]", "Safe speed [km/h]", "Advisory speed (plaque)", "Treatment (signs)",
    "W1-13 truck rollover warning", "Approach speed [km/h]", "Required deceleration [m/s\u00b2]",
    "Why no profile figure",
]  # fmt: skip
SIGNS_TITLE = "Signs and the truck's speed profile"


def road_csv(rows: int) -> str:
    """A synthetic road: radii 40-1,540 m, superelevation 0-8 %, grades -3..+3 %, posted 50-90 km/h."""
    lines = ["id,radius_m,superelevation_percent,grade_percent,posted_speed_kmh"]
    lines += [f"K{i},{40 + (i * 37) % 1500},{i % 9},{(i % 7) - 3},{50 + 10 * (i % 5)}" for i in range(rows)]
    return "\n".join(lines) + "\n"


def squeeze(text: str) -> str:
    """Text without its line breaks and spaces, ligatures unfolded (pypdf reads "fl" as one glyph)."""
    return re.sub(r"\s+", "", unicodedata.normalize("NFKC", text))


def print_pdf(page) -> PdfReader:
    out = page.driver.execute_cdp_cmd("Page.printToPDF", {"preferCSSPageSize": True, "printBackground": False})
    return PdfReader(io.BytesIO(base64.b64decode(out["data"])))


def runs(pdf_page) -> list[tuple[float, str]]:
    """(x of its start [pt], text) of every text run of a page."""
    found = []

    def visit(text, cm, tm, _font, _size):
        if text.strip():
            found.append((tm[4] * cm[0] + tm[5] * cm[2] + cm[4], text))

    pdf_page.extract_text(visitor_text=visit)
    return found


def assess(page, tmp_path, text: str, name: str = "road.csv") -> None:
    path = tmp_path / name
    path.write_text(text)
    page.find("#alignment-file").send_keys(str(path))
    page.run("assessments", lambda: page.find("#alignment-assess").click(), timeout_s=120)


def request_of(text: str) -> dict:
    """The request the page sends for a CSV with its defaults (nothing typed in the alignment's boxes)."""
    return {"vehicle": "table16-btrain", "csv": text}


def expected_order(rows: list[dict]) -> list[str]:
    """The printout's order: the flagged curves by margin, smallest first (ties in file order), then the others in
    file order (a CSV without stations: its order is the road's)."""
    flagged = sorted((r for r in rows if r["flagged"]), key=lambda r: r["margin_kmh"])
    return [r["id"] for r in flagged] + [r["id"] for r in rows if not r["flagged"]]


@pytest.mark.parametrize("width", [1366, 390])
def test_the_printout_holds_every_verdict_column_and_the_worst_curve_first(page, api, tmp_path, width):
    total = 1200
    text = road_csv(total)
    page.driver.set_window_size(width, 900)
    page.open("?vehicle=table16-btrain")
    assess(page, tmp_path, text)
    # the API's answer to the request the page sends
    answer = api.post("/v1/alignments/assess", json=request_of(text))
    assert answer.status_code == 200, answer.text
    rows = answer.json()["vehicles"][0]["rows"]
    order = expected_order(rows)
    worst = min(rows, key=lambda r: r["margin_kmh"])
    flagged = sum(r["flagged"] for r in rows)
    assert 0 < flagged < PRINT_ROWS  # the file has both kinds, and room is left for unflagged ones

    # the printout's table, in the document: the API's order, cut at PRINT_ROWS
    printed_ids = page.driver.execute_script(
        "return Array.from(document.querySelectorAll('#summary-extras table.curves-print')).map((t) => {"
        "const col = Array.from(t.tHead.rows[0].cells).findIndex((c) => c.textContent === 'Id in the file');"
        "return Array.from(t.tBodies[0].rows).map((r) => r.cells[col].textContent); });"
    )
    # the curves' table, then the signs' table of the same curves in the same order
    assert printed_ids == [order[:PRINT_ROWS], order[:PRINT_ROWS]]

    pdf = print_pdf(page)
    pages = list(pdf.pages)
    first = squeeze(pages[0].extract_text())
    # the summary first: the file, the vehicle, the counts and the worst curve's margin and id
    assert squeeze("road.csv") in first and "table16-btrain" in first
    assert squeeze(f"{total:,} curves, {flagged:,} flagged") in first
    assert squeeze(f"smallest margin \u2212{abs(worst['margin_kmh']):.1f} km/h") in first
    assert f"id{worst['id']}" in first

    # the curves on A4 landscape pages (842 x 595 pt), every heading on each, no text beyond the paper's edge
    road = [p for p in pages if float(p.mediabox.width) > float(p.mediabox.height)]
    assert road and all(abs(float(p.mediabox.width) - 841.9) < 1 for p in road)
    # the curves' pages, then (from its title) the signs' pages: each page repeats its own table's headings
    texts = [squeeze(p.extract_text()) for p in road]
    signs_from = next(i for i, t in enumerate(texts) if squeeze(SIGNS_TITLE) in t)
    assert 1 < signs_from < len(texts)
    for i, text in enumerate(texts[1:], start=1):
        for heading in VERDICT_HEADINGS if i < signs_from else SIGN_HEADINGS:
            assert squeeze(heading) in text, (width, i, heading)
    for p in road:
        right = float(p.mediabox.width)
        assert all(0 <= x < right - 20 for x, _ in runs(p)), width
    body = squeeze("".join(p.extract_text() for p in road))
    # the worst curve is printed, before the second worst; the last column is filled on every printed row
    assert body.index(f"{worst['id']}") < body.index(f"{order[1]}")
    meets = [t.strip() for p in road for _, t in runs(p) if t.strip() in ("yes", "no")]
    assert len(meets) == PRINT_ROWS
    assert squeeze(f"The other {total - PRINT_ROWS:,} curves are in the CSV download (road-curves.csv)") in body


def test_a_small_road_is_printed_whole_flagged_first(page, api, tmp_path):
    text = road_csv(40)
    page.open("?vehicle=table16-btrain")
    assess(page, tmp_path, text, "small.csv")
    answer = api.post("/v1/alignments/assess", json=request_of(text))
    rows = answer.json()["vehicles"][0]["rows"]
    body = squeeze("".join(p.extract_text() for p in print_pdf(page).pages))
    flagged = sum(r["flagged"] for r in rows)
    assert squeeze(f"All 40 curves are printed: the {flagged} flagged ones first") in body
    assert "CSVdownload" not in body


def test_every_computed_line_names_its_inputs(page):
    """The curve speed names its radius, bank and grade; the superelevation line its radius, speed and e_max."""
    page.open("?vehicle=table16-btrain&bank_percent=4&radius_m=300")
    line = page.text("#speed-result")
    assert line.startswith("On a curve of radius 300 m with bank (superelevation) 4 % and grade 0 %")
    page.type("#se-radius", "400")
    page.type("#se-speed", "80")
    page.run("superelevations", lambda: page.find("#super-compute").click())
    line = page.text("#super-result")
    assert line.startswith("A curve of radius 400 m at 80 km/h (maximum superelevation 8 %)")
    body = squeeze("".join(p.extract_text() for p in print_pdf(page).pages))
    assert squeeze("A curve of radius 400 m at 80 km/h") in body
    assert squeeze("Radius 300 m with bank (superelevation) 4 % and grade 0 %") in body

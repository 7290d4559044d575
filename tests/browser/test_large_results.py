"""Results of any size without a frozen tab (issue 41, point 2): an alignment of 20,000 and 200,000 curves assessed
as a job, its table shown a page at a time (flagged curves first), sorted, filtered and paged, and the printout
built -- while a PerformanceObserver for 'longtask' records every main-thread task over 50 ms. No task may last
100 ms or more. The figures are printed (``-s``) for the note. A long task's duration is wall-clock time: on a
machine whose cores are shared far beyond their number, the page's tasks (a few milliseconds to a few tens of CPU)
stretch with the wait for a core.

The expected counts and order come from the rows' own closed forms where the file decides them, and from the API's
job result otherwise, never from the page.
"""

from __future__ import annotations

import csv
import io

import pytest
from selenium.webdriver.support.ui import WebDriverWait

pytestmark = [pytest.mark.browser, pytest.mark.slow]

#: the longest main-thread task allowed [ms] (issue 41: "the main thread is never blocked for more than 100 ms")
LONG_TASK_MS = 100
#: rows on one page of the table (app/web/js/curves.js `settings.pageRows`)
PAGE_ROWS = 25

OBSERVE = """
window.__longTasks = [];
new PerformanceObserver((list) => {
  for (const e of list.getEntries()) window.__longTasks.push(Math.round(e.duration));
}).observe({ type: 'longtask' });
"""


#: the first row's cell of a column, by the column's API field (read in one script: the table is redrawn as it pages)
FIRST_CELL = """
const keys = Array.from(document.querySelectorAll('#curves-table thead button.sort')).map((b) => b.dataset.key);
return document.querySelector('#curves-table tbody tr').cells[keys.indexOf(arguments[0])].textContent;
"""


def road(rows: int) -> str:
    """A CSV road of ``rows`` curves: radii 40-1,540 m, superelevation 0-8 %, level, posted 50-90 km/h (few distinct
    superelevations, so the service solves the SRT a few times only)."""
    lines = ["id,radius_m,superelevation_percent,grade_percent,posted_speed_kmh"]
    lines += [f"R{i},{40 + (i * 37) % 1500},{i % 9},0,{50 + 10 * (i % 5)}" for i in range(rows)]
    return "\n".join(lines) + "\n"


def job_csv(api, key: str, text: str) -> list[dict]:
    """The same request as a job through the API; its result as CSV rows."""
    headers = {"Authorization": f"Bearer {key}"}
    body = {
        "operation": "alignments.assess",
        "request": {"vehicle": "table16-btrain", "csv": text},
    }
    submitted = api.post("/v1/jobs", json=body, headers=headers)
    assert submitted.status_code == 202, submitted.text
    location = submitted.headers["Location"]
    WebDriverWait(None, 300, poll_frequency=0.5).until(
        lambda _: api.get(location, headers=headers).json()["status"] == "done"
    )
    result = api.get(f"{location}/result", headers={**headers, "Accept": "text/csv"})
    return list(csv.DictReader(io.StringIO(result.text)))


def wait_js(page, condition: str, timeout_s: float = 120) -> None:
    """Wait until a JavaScript expression holds, read with one small script a poll (WebDriver's own element reads
    run on the page's main thread too, and some force a layout: they would be counted as the page's tasks)."""
    WebDriverWait(page.driver, timeout_s, poll_frequency=0.25).until(
        lambda _: page.driver.execute_script(f"return Boolean({condition})")
    )


def text_of(page, selector: str) -> str:
    return page.driver.execute_script("return document.querySelector(arguments[0]).textContent", selector)


@pytest.mark.parametrize("rows", [20_000, 200_000], ids=["20k", "200k"])
def test_a_large_result_never_blocks_the_page_for_100_ms(page, api, live_server, tmp_path, rows):
    text = road(rows)
    path = tmp_path / "large.csv"
    path.write_text(text)
    page.open("?vehicle=table16-btrain")
    page.find("#catalog-box summary").click()
    page.type("#api-key", live_server.key)
    page.find("#alignment-file").send_keys(str(path))
    before = page.count("assessments")
    page.driver.execute_script(OBSERVE)
    # assessed as a job, the first page drawn and the printout built (in pieces, after the first page)
    page.driver.execute_script("document.querySelector('#alignment-assess').click()")
    wait_js(page, f"Number(document.body.dataset.assessments) > {before}", timeout_s=600)
    wait_js(page, "document.querySelector('#summary-extras table.curves-print tbody tr')")
    tasks = page.driver.execute_script("return window.__longTasks.splice(0)")

    expected = job_csv(api, live_server.key, text)
    assert len(expected) == rows
    assert not page.find("#alignment-error").is_displayed()
    flagged = [r for r in expected if r["flagged"] == "true"]
    assert page.text("#alignment-summary").startswith(f"{rows:,} curves, {len(flagged):,} flagged")
    assert page.text("#curves-shown") == f"Rows 1\u2013{PAGE_ROWS} of {rows:,}"
    shown = page.find_all("#curves-table tbody tr")
    assert len(shown) == PAGE_ROWS  # one page on screen, whatever the size
    worst = sorted(flagged, key=lambda r: float(r["margin_kmh"]))
    assert [r.get_attribute("data-id") for r in shown[:10]] == [r["id"] for r in worst[:10]]

    # the user's own order and filter, and the last page (the tasks counted again from here)
    page.driver.execute_script("window.__longTasks.splice(0)")
    page.driver.execute_script("document.querySelector('#curves-table button[data-key=\"radius_m\"]').click()")
    wait_js(page, 'document.querySelector(\'#curves-table th[aria-sort="ascending"] button[data-key="radius_m"]\')')
    first_radius = page.driver.execute_script(FIRST_CELL, "radius_m")
    page.driver.execute_script(
        "const s = document.querySelector('#curves-filter'); s.value = 'flagged'; s.dispatchEvent(new Event('change'));"
    )
    wait_js(page, f"document.querySelector('#curves-shown').textContent.endsWith('of {len(flagged):,}')")
    page.driver.execute_script("document.querySelector('#curves-last').click()")
    last_first = (len(flagged) - 1) // PAGE_ROWS * PAGE_ROWS + 1
    wait_js(page, f"document.querySelector('#curves-shown').textContent.startsWith('Rows {last_first:,}')")
    tasks += page.driver.execute_script("return window.__longTasks.splice(0)")
    assert float(first_radius.replace(",", "")) == min(float(r["radius_m"]) for r in expected)
    assert text_of(page, "#curves-shown") == f"Rows {last_first:,}\u2013{len(flagged):,} of {len(flagged):,}"

    print(f"\n{rows:,} rows: {len(tasks)} long tasks (> 50 ms), longest {max(tasks, default=0)} ms: {tasks}")
    assert max(tasks, default=0) < LONG_TASK_MS, tasks

    # the CSV download holds the whole result, read again from the job (the synchronous request is above its size)
    downloads = tmp_path / "downloads"
    downloads.mkdir()
    page.driver.execute_cdp_cmd("Browser.setDownloadBehavior", {"behavior": "allow", "downloadPath": str(downloads)})
    page.driver.execute_script("document.querySelector('#download-csv').click()")
    saved = downloads / "large-curves.csv"
    WebDriverWait(page.driver, 120).until(lambda _: saved.exists() and not list(downloads.glob("*.crdownload")))
    assert len(list(csv.DictReader(io.StringIO(saved.read_text())))) == rows

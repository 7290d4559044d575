"""Words, units, names (issue 41, point 5), at window widths 1366 and 390: messages in plain words with their unit
and the value typed; labels instead of snake_case and model ids on screen and on paper; thousands separators;
every table readable (no column clipped without a visible cue to scroll); /redoc loading nothing from another host.

The bounds in the messages come from the API's own answer to the same value (its problem details), never from the
page.
"""

from __future__ import annotations

import contextlib
import re
from urllib.parse import urlsplit

import pytest
from selenium.common.exceptions import TimeoutException
from selenium.webdriver.support.ui import WebDriverWait

pytestmark = [pytest.mark.browser, pytest.mark.slow]

#: the API's field names the issue found on screen and paper, and the framework's words
SNAKE = ["front_llt_ratio", "dangerous_goods", "f_max", "side-friction", "superelevation_percent", "posted_speed_kmh"]
FRAMEWORK = ["Input should", "String should"]

ROAD_CSV = "id,radius_m,superelevation_percent,grade_percent,posted_speed_kmh\nK1,1500,4,0,100\nK2,60,2,0,70\n"


@pytest.fixture(params=[1366, 390], ids=["desktop", "phone"])
def width(request, page):
    page.driver.set_window_size(request.param, 900)
    return request.param


def bound(api, body: dict, field: str) -> str:
    """The number the API's own message gives for a refused field (e.g. "... greater than or equal to 5")."""
    problem = api.post("/v1/curve-speed", json=body).json()
    (item,) = [e for e in problem["errors"] if e["field"] == field]
    return re.search(r"-?\d+(?:\.\d+)?", item["message"]).group(0)


def test_a_refused_value_is_said_in_words_with_its_unit_and_the_value_typed(page, api, width):
    least = bound(api, {"vehicle": "table16-btrain", "radius_m": -50}, "radius_m")
    page.open("?vehicle=table16-btrain")
    page.type("#radius", "-50")
    page.run("computations", lambda: page.find("#speed-compute").click())
    assert page.field_error("#radius") == f"Radius must be at least {least} m; you typed -50"
    page.type("#radius", "abc")
    page.run("computations", lambda: page.find("#speed-compute").click())
    assert page.field_error("#radius") == "Radius must be a number (in m); you typed abc"
    body = page.text("body")
    assert not [w for w in FRAMEWORK if w in body]


def test_labels_and_thousands_separators_on_screen_and_paper(page, api, tmp_path, width):
    page.open("?vehicle=table16-btrain&radius_m=300")
    # the models by name, never by id
    names = {m["id"]: m["name"] for m in api.get("/v1/models").json()}
    options = [o.text for o in page.find_all("#model option")]
    assert options == list(names.values()) and not set(options) & set(names)
    path = tmp_path / "road.csv"
    path.write_text(ROAD_CSV)
    page.find("#alignment-file").send_keys(str(path))
    page.run("assessments", lambda: page.find("#alignment-assess").click())
    page.type("#se-radius", "1200")
    page.run("superelevations", lambda: page.find("#super-compute").click())
    # what is printed: the summary (its link aside: a link's parameters are the API's names by design), and the
    # sections on screen; the service's SVG figures aside (their text is the plot endpoint's, not the page's)
    words = """
      const s = document.querySelector(arguments[0]).cloneNode(true);
      s.querySelectorAll('a, svg, code').forEach((n) => n.remove());  // code: a file's column names as it spells them
      return s.textContent;
    """
    printed = page.driver.execute_script(words, "#summary")
    screen = " ".join(
        page.driver.execute_script(words, s) for s in ("#results-section", "#road-section", "#alignment-section")
    )
    for text in (printed, screen):
        assert not [w for w in SNAKE if w in text], [w for w in SNAKE if w in text]
        assert not re.search(r"\((3d|2d|combination|rigid)\)", text)
    model = names[api.post("/v1/srt", json={"vehicle": "table16-btrain"}).json()["model"]]
    assert f"Model{model}" in printed  # the case's model by its name
    # thousands separators: a radius of 1,500 m, the vehicle's mass in kg, on screen and on paper
    assert "1,500" in screen and "1,500" in printed
    assert re.search(r"\d,\d{3} kg", printed)


def test_every_table_is_readable_or_says_it_scrolls(page, tmp_path, width):
    page.open("?vehicle=tractor-semitrailer-table15&radius_m=300")
    path = tmp_path / "road.csv"
    path.write_text(ROAD_CSV)
    page.find("#alignment-file").send_keys(str(path))
    page.run("assessments", lambda: page.find("#alignment-assess").click())
    # the curve's advisory speed by method, and the combination's PBS screening: tables of long source texts
    page.type("#speed-posted", "90")
    page.driver.execute_script("document.querySelector('#speed-compute').scrollIntoView({block: 'center'})")
    page.run("computations", lambda: page.find("#speed-compute").click(), timeout_s=120)
    page.driver.execute_script("document.querySelector('#dynamics-compute').scrollIntoView({block: 'center'})")
    page.run("screenings", lambda: page.find("#dynamics-compute").click(), timeout_s=120)
    assert page.find_all("#advisory-result table") and page.find_all("#dyn-results table")
    # a cue follows its box's overflow through a ResizeObserver, whose callback runs a frame after the layout:
    # the check is read again until it holds (or the wait ends and the last reading fails the test)
    check = """
        const out = [];
        for (const t of document.querySelectorAll('main table')) {
          if (!t.offsetParent || t.closest('.summary')) continue;  // hidden, or on paper only
          const box = t.closest('.table-wrap');
          if (!box) {
            if (t.getBoundingClientRect().right > document.documentElement.clientWidth + 1) out.push(t.id || 'table');
            continue;
          }
          if (box.scrollWidth <= box.clientWidth + 1) continue;  // whole
          const cue = box.previousElementSibling;
          const shown = cue && cue.classList.contains('scroll-cue') && !cue.hidden && cue.offsetParent !== null;
          if (!shown) out.push((t.id || box.getAttribute('aria-label') || 'table') + ' without a cue');
        }
        return out;
        """
    clipped: list[str] = []

    def settled(_) -> bool:
        clipped[:] = page.driver.execute_script(check)
        return not clipped

    with contextlib.suppress(TimeoutException):
        WebDriverWait(page.driver, 10).until(settled)
    assert clipped == [], (width, clipped)
    # the page never scrolls sideways as a whole
    assert page.driver.execute_script(
        "return document.documentElement.scrollWidth <= document.documentElement.clientWidth"
    )


def test_redoc_loads_nothing_from_another_host(page, live_server):
    page.driver.get(f"{live_server.url}/redoc")
    WebDriverWait(page.driver, 60).until(
        lambda d: d.execute_script(
            "return document.querySelector('redoc') && document.body.innerText.includes('rollover')"
        )
    )
    WebDriverWait(page.driver, 10).until(lambda d: d.execute_script("return document.readyState") == "complete")
    sent, blocked = page.network()
    own = urlsplit(live_server.url).netloc
    outside = {u for u in sent.values() if urlsplit(u).scheme in ("http", "https") and urlsplit(u).netloc != own}
    # ReDoc's bundle names its logo on cdn.redoc.ly: refused by the page's policy before any request
    unblocked = {u for rid, u in sent.items() if u in outside and rid not in blocked}
    assert unblocked == set(), unblocked

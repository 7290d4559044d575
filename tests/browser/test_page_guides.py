"""The calculator page guides its user (issue 23 item 3, issue 20 item 5): results marked stale the moment an input
changes or a request fails, the combinations drawn with each roll-coupled unit's SRT and the lift-off sequence, the
verdict in plain words first, Compute always in view, tables whose key columns stay readable, and a printout in
words with units. Each test runs at a desktop (1366 x 900) and a phone (390 x 844) viewport.

Expected numbers come from the public API called directly for the same case -- never from the page itself.
"""

from __future__ import annotations

import contextlib

import pytest

DESKTOP = (1366, 900)
PHONE = (390, 844)
WIDTHS = pytest.mark.parametrize("size", [DESKTOP, PHONE], ids=["1366x900", "390x844"])


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


def ok(response):
    assert response.status_code == 200, response.text
    return response.json()


# ------------------------------------------------------------------------------------------- stale results


@WIDTHS
def test_results_are_marked_stale_when_an_input_changes_or_a_request_fails(page, size):
    with viewport(page, size):
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
        assert page.find_all(".stale-banner") == []
        assert page.find("#results-body").get_attribute("data-stale") is None
        if size == PHONE:
            return
        # a builder error: the previous SRT is marked as the last request's failure
        page.find('input[name="source"][value="build"]').click()
        assert page.find("#results-body").get_attribute("data-stale") == "true"
        page.type("#b-rear-track", "-1")
        page.run("computations", lambda: page.find("#build-button").click())
        assert page.find("#b-rear-track").get_attribute("aria-invalid") == "true"
        assert "request failed" in page.text("#stale-srt")
        assert page.find("#stale-design").is_displayed()

"""The combination editor's folded "For the dynamics (optional)" boxes per unit and per axle group (issue 42, item 2):
labelled from the OpenAPI document (the fields' one definition), sent in the spec, and the dynamics section saying
which of the model's values were given and where. Expected values come from the public API, never from the page."""

from __future__ import annotations

import json
from urllib.parse import parse_qs, urlsplit

import pytest
from selenium.webdriver.support.ui import WebDriverWait

from .test_combination_builder_page import box_id, open_editor, set_box

pytestmark = [pytest.mark.browser, pytest.mark.slow]


def given_rows(page) -> list[list[str]]:
    return page.driver.execute_script(
        "return Array.from(document.querySelectorAll('#dyn-results .dyn-given table tbody tr')).map((tr) =>"
        " Array.from(tr.cells).map((c) => c.textContent));"
    )


def fold(page, selector: str, open_: bool) -> None:
    """Open or close a fold (a click on its summary may land on the sticky compute bar)."""
    page.driver.execute_script("arguments[0].open = arguments[1];", page.find(selector), open_)


def test_dynamic_data_typed_in_the_editor_reaches_the_screening_and_is_shown_as_given(page, api):
    schemas = api.get("/openapi.json").json()["components"]["schemas"]
    open_editor(page)
    unit = "#cb-units .cb-unit[data-unit='1']"
    # folded at first; its labels are the schema's descriptions (first clause) with their units
    details = page.find(f"{unit} > details.cb-dynamics")
    assert details.get_attribute("open") is None
    labels = page.driver.execute_script(
        "return Array.from(arguments[0].querySelectorAll('label')).map((l) => l.textContent);", details
    )
    props = schemas["UnitDynamicsSpec"]["properties"]
    assert len(labels) == len(props)
    yaw = props["yaw_inertia_kgm2"]["description"]
    assert labels[list(props).index("yaw_inertia_kgm2")] == yaw.split(";")[0] + " [kg m^2]"
    fold(page, f"{unit} > details.cb-dynamics", True)
    set_box(page, "units.1.dynamics.yaw_inertia_kgm2", "400000")
    set_box(page, "units.1.dynamics.width_m", "2.55")
    fold(page, f"{unit} .cb-group details.cb-dynamics", True)
    set_box(page, "units.1.axle_groups.0.dynamics.tyre_type", "openpbs-constant")
    assert (
        page.find(box_id("units.1.axle_groups.0.dynamics.cornering_coefficient_per_rad")).get_attribute("value") == ""
    )
    page.run("computations", lambda: page.find("#cb-compute").click())
    assert page.text("#case-error") == ""
    spec = json.loads(parse_qs(urlsplit(page.driver.current_url).query)["combination_spec"][0])
    assert spec["units"][1]["dynamics"] == {"yaw_inertia_kgm2": 400000, "width_m": 2.55}
    assert spec["units"][1]["axle_groups"][0]["dynamics"] == {"tyre_type": "openpbs-constant"}
    assert "dynamics" not in spec["units"][0]  # nothing typed: nothing sent

    page.run("screenings", lambda: page.find("#dynamics-compute").click(), timeout_s=120)
    answer = api.post("/v1/pbs", json={"vehicle": {"combination_spec": spec}})
    assert answer.status_code == 200, answer.text
    p = answer.json()["parameters"]
    expected = []
    for u in p["units"]:
        for name in ("yaw_inertia_kgm2", "roll_inertia_kgm2", "front_overhang_m", "rear_extent_m", "width_m"):
            if u[name]["source"].startswith("given"):
                expected.append((u["unit"], "", name, u[name]["source"].removeprefix("given in ").split(" ")[0]))
    for g in p["groups"]:
        for name in ("cornering_coefficient_per_rad", "axle_spacing_m", "tyre_type"):
            if g[name]["source"].startswith("given"):
                expected.append(
                    (g["unit"], g["group"], name, g[name]["source"].removeprefix("given in ").split(":")[0])
                )
    rows = given_rows(page)
    assert [(r[0], r[1], r[4]) for r in rows] == [(e[0], e[1], e[3]) for e in expected]
    assert ("trailer", "", "vehicle.combination_spec.units[1].dynamics.width_m") in [(r[0], r[1], r[4]) for r in rows]
    width = next(r for r in rows if r[4].endswith("dynamics.width_m"))
    assert width[2] == "Width [m]" and float(width[3]) == 2.55
    tyre = next(r for r in rows if r[4].endswith("dynamics.tyre_type"))
    assert tyre[3] == "openpbs-constant"
    # a box's refusal is shown at its box, its fold opened
    page.open()
    open_editor(page)
    fold(page, f"{unit} > details.cb-dynamics", True)
    set_box(page, "units.1.dynamics.yaw_inertia_kgm2", "10")
    fold(page, f"{unit} > details.cb-dynamics", False)
    page.run("computations", lambda: page.find("#cb-compute").click())
    WebDriverWait(page.driver, 10).until(lambda _: page.find(f"{unit} > details.cb-dynamics").get_attribute("open"))
    assert "is below the point-mass bound" in page.field_error(box_id("units.1.dynamics.yaw_inertia_kgm2"))

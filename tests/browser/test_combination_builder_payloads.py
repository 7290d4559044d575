"""The combination editor's payload kinds (a tank, a sloping deck) and the tare's rear-group load
(app/web/js/combobuilder.js) in a real browser against a real server.

Expected numbers come from the public API called directly by the test for the same spec (``POST /v1/srt`` with
``"vehicle": {"combination_spec": ...}``, ``POST /v1/combinations/build``) -- never from the page itself. The
specs are the service's example combination (app/vehicles/combination_builder_schemas.py) with its deck load
replaced; the tank, deck and weighbridge values are round illustrative numbers within the engine's checks
(engine/builder/payloads.py), not measured data.
"""

from __future__ import annotations

import copy
import json
from urllib.parse import parse_qs, urlencode, urlsplit

import pytest
from selenium.webdriver.support.ui import Select

from .test_combination_builder_page import (
    DISPLAY_G,
    TYPED,
    api_ok,
    assert_editor_fits,
    box_id,
    chosen,
    compute,
    leaves,
    open_editor,
    set_box,
    start_from,
)

#: the example's 22 t as a liquid in an elliptical tank, 80 % full by volume
TANK = {
    "mass_kg": 22000,
    "tank": {"shape": "elliptical", "height_m": 2.0, "bottom_height_m": 1.2, "fill_fraction": 0.8},
}
#: the example's 22 t of mixed freight on a deck sloping down to the rear, 12 m long from 0.2 m behind the kingpin
SLOPED = {
    "mass_kg": 22000,
    "deck_height_m": 1.4,
    "deck_height_rear_m": 1.1,
    "load_height_m": 2.8,
    "load_height_rear_m": 2.4,
    "distribution": "mixed-freight",
    "front_from_kingpin_m": 0.2,
    "length_m": 12,
}


def with_payload(payload: dict | None = None, tare: dict | None = None) -> dict:
    """The example spec (the other tests' TYPED) with the semitrailer's payload and/or tare replaced."""
    spec = copy.deepcopy(TYPED)
    if payload is not None:
        spec["units"][1]["payloads"] = [copy.deepcopy(payload)]
    if tare is not None:
        spec["units"][1]["tare"] = copy.deepcopy(tare)
    return spec


#: the example's semitrailer tare by its weighbridge load on the axle group instead of its CG position
REAR_LOAD_TARE = {"mass_kg": 7500, "cg_height_m": 1.1, "rear_group_load_kg": 3500}

CASES = {
    "tank": (with_payload(TANK), "tank"),
    "sloped": (with_payload(SLOPED), "sloped"),
    "rear-group-load": (with_payload(tare=REAR_LOAD_TARE), "deck"),
}


def same(shown: str, value) -> bool:
    """A box's text is the spec's value (a number as a number: 2.0 is shown as 2)."""
    if isinstance(value, int | float):
        return float(shown) == pytest.approx(value, rel=1e-12)
    return shown == str(value)


def sent_spec(page) -> dict:
    """The spec the page sent (its link holds it)."""
    return json.loads(parse_qs(urlsplit(page.driver.current_url).query)["combination_spec"][0])


def editor_spec(page) -> dict:
    """The spec the editor's boxes describe, as the page posts it (the page's own readSpec)."""
    return page.driver.execute_async_script(
        "const done = arguments[0];"
        "import('/web/js/combobuilder.js').then((m) => done(JSON.parse(JSON.stringify(m.readSpec()))));"
    )


def expected_srt(api, spec: dict) -> float:
    return api_ok(api, "/v1/srt", {"vehicle": {"combination_spec": spec}, "model": "combination"})["srt"]


def choose_kind(page, path: str, kind: str) -> None:
    """Choose how payload ``path`` (``units.1.payloads.0``) gives its height; the editor redraws its boxes."""
    Select(page.find(box_id(path) + "-kind")).select_by_value(kind)
    assert page.find(f"{box_id(path)}-kind").get_attribute("value") == kind


# ------------------------------------------------------------------------------------------- typed


@pytest.mark.parametrize("width", [1366, 390])
@pytest.mark.parametrize("case", list(CASES))
def test_a_payload_kind_or_rear_group_load_typed_in_the_editor_has_the_apis_srt(page, api, case, width):
    spec, kind = CASES[case]
    page.driver.set_window_size(width, 900)
    open_editor(page)
    start_from(page, "scratch")
    page.find("#cb-units .cb-unit[data-unit='1'] .cb-add-payload").click()
    choose_kind(page, "units.1.payloads.0", kind)
    for path, value in leaves(spec):
        set_box(page, path, value)
    compute(page)
    assert page.text("#case-error") == ""
    # the page sent the spec as typed, and its SRT is the API's for that spec
    assert sent_spec(page) == spec
    srt = expected_srt(api, spec)
    assert page.srt_g() == pytest.approx(srt, abs=DISPLAY_G)
    # and the payload or tare as typed matters: the example's deck load and CG position give another SRT
    assert abs(expected_srt(api, TYPED) - srt) > 2 * DISPLAY_G
    # the build's masses (shown) are the API's for the spec
    built = api_ok(api, "/v1/combinations/build", {"combination_spec": spec})
    assert page.text("#cb-gross") == f"Built: gross mass {built['gross_mass_kg']:,.0f} kg in 2 units."


# ------------------------------------------------------------------------------------------- a link


@pytest.mark.parametrize("width", [1366, 390])
def test_a_link_with_a_tank_a_sloping_deck_and_a_rear_group_load_shows_them_in_their_boxes(page, api, width):
    spec = with_payload(TANK, REAR_LOAD_TARE)
    spec["units"][1]["payloads"].append({**SLOPED, "mass_kg": 2000, "deck_height_m": 1.3})
    spec["units"][1]["title"] = "Tanker, 3 compartments"  # a unit's description and a group's name have boxes too
    spec["units"][1]["axle_groups"][0]["id"] = "tri-axle"
    page.driver.set_window_size(width, 900)
    page.open("?" + urlencode({"combination_spec": json.dumps(spec)}))
    assert page.find('input[name="source"][value="combo"]').is_selected()
    # every value has its box, none is only "kept from the spec"
    for path, value in leaves(spec):
        box = page.find(box_id(path))
        assert box.is_displayed(), path
        assert same(box.get_attribute("value"), value), path
    assert "Kept from the spec" not in page.text("#cb-units .cb-unit[data-unit='1'] > .hint")
    assert chosen(page, "units.1.payloads.0.tank.shape") == "elliptical"
    assert page.find(box_id("units.1.payloads.0") + "-kind").get_attribute("value") == "tank"
    assert page.find(box_id("units.1.payloads.1") + "-kind").get_attribute("value") == "sloped"
    # the boxes are labelled with their unit
    for path, label in (
        ("units.1.payloads.0.tank.height_m", "Tank inside height [m]"),
        ("units.1.payloads.0.tank.fill_fraction", "Or: fill by volume, fraction full [-]"),
        ("units.1.payloads.1.deck_height_rear_m", "Deck height at the load's rear [m]"),
        ("units.1.tare.rear_group_load_kg", "Or: tare load on the axle group [kg]"),
    ):
        assert page.text(f"label[for='{box_id(path)[1:]}']") == label
    # the link computed the spec, with the API's SRT
    assert page.srt_g() == pytest.approx(expected_srt(api, spec), abs=DISPLAY_G)
    # editing a box changes what is sent
    set_box(page, "units.1.payloads.0.tank.fill_fraction", "0.5")
    set_box(page, "units.1.tare.rear_group_load_kg", "4000")
    set_box(page, "units.1.payloads.1.load_height_rear_m", "2.2")
    compute(page)
    edited = copy.deepcopy(spec)
    edited["units"][1]["payloads"][0]["tank"]["fill_fraction"] = 0.5
    edited["units"][1]["tare"]["rear_group_load_kg"] = 4000
    edited["units"][1]["payloads"][1]["load_height_rear_m"] = 2.2
    assert sent_spec(page) == edited
    assert page.srt_g() == pytest.approx(expected_srt(api, edited), abs=DISPLAY_G)
    # the editor fits the width with the new boxes
    assert_editor_fits(page)


def test_another_way_of_giving_the_height_shows_its_boxes_and_drops_the_others(page):
    page.open("?" + urlencode({"combination_spec": json.dumps(with_payload(TANK))}))
    p = "units.1.payloads.0"
    choose_kind(page, p, "deck")
    assert page.find_all(box_id(f"{p}.tank.height_m")) == []
    assert page.find(box_id(f"{p}.deck_height_m")).get_attribute("value") == ""
    assert chosen(page, f"{p}.distribution") == "uniform"
    # the choice has the focus again after the redraw, and the mass is kept
    assert page.driver.switch_to.active_element.get_attribute("id") == box_id(p)[1:] + "-kind"
    assert page.find(box_id(f"{p}.mass_kg")).get_attribute("value") == "22000"
    # a way chosen survives a redraw with its boxes still empty (a payload added elsewhere)
    choose_kind(page, p, "sloped")
    page.find("#cb-units .cb-unit[data-unit='1'] .cb-add-payload").click()
    assert page.find(box_id(p) + "-kind").get_attribute("value") == "sloped"
    assert page.find(box_id(f"{p}.deck_height_rear_m")).is_displayed()
    assert page.find_all(box_id(f"{p}.cg_from_kingpin_m")) == []  # a sloping deck's CG is its load's centroid
    choose_kind(page, p, "cg")
    assert page.find(box_id(f"{p}.cg_height_m")).is_displayed()
    assert page.find_all(box_id(f"{p}.deck_height_m")) == []


# ------------------------------------------------------------------------------------------- errors


@pytest.mark.parametrize("width", [1366, 390])
@pytest.mark.parametrize(
    ("field", "value"), [("fill_fraction", 1.5), ("height_m", -2.0)], ids=["fill-over-1", "negative-height"]
)
def test_an_invalid_tank_value_shows_the_apis_problem_at_that_box(page, api, field, value, width):
    spec = with_payload(TANK)
    page.driver.set_window_size(width, 900)
    page.open("?" + urlencode({"combination_spec": json.dumps(spec)}))
    path = f"units.1.payloads.0.tank.{field}"
    set_box(page, path, value)
    compute(page)
    spec["units"][1]["payloads"][0]["tank"][field] = value
    assert editor_spec(page) == spec  # the spec the page posted (a refused one is not written to the link)
    # the same spec through the API: its problem names the tank's field, and the page shows it at that box
    r = api.post("/v1/combinations/build", json={"combination_spec": spec})
    assert r.status_code == 422, r.text
    [error] = r.json()["errors"]
    assert error["field"].replace("[", ".").replace("]", "") == f"combination_spec.{path}"
    assert error["message"] in page.field_error(box_id(path))
    assert page.find(box_id(path)).get_attribute("aria-invalid") == "true"
    assert page.driver.switch_to.active_element.get_attribute("id") == box_id(path)[1:]
    assert len(page.find_all('#cb-editor [aria-invalid="true"]')) == 1


def test_a_tank_without_its_fill_is_refused_at_the_liquid_depth_box(page, api):
    """The engine takes exactly one of the liquid depth and the fill fraction (payloads._tank_cg)."""
    spec = with_payload(TANK)
    page.open("?" + urlencode({"combination_spec": json.dumps(spec)}))
    set_box(page, "units.1.payloads.0.tank.fill_fraction", "")
    compute(page)
    del spec["units"][1]["payloads"][0]["tank"]["fill_fraction"]
    assert editor_spec(page) == spec
    r = api.post("/v1/combinations/build", json={"combination_spec": spec})
    assert r.status_code == 422, r.text
    [error] = r.json()["errors"]
    assert "fill_fraction" in error["message"]
    assert error["message"] in page.field_error(box_id("units.1.payloads.0.tank.fill_height_m"))


def test_a_rear_group_load_with_the_tare_cg_position_too_is_refused_at_the_position_box(page, api):
    """The engine takes exactly one of the tare CG position and the rear-group load (payloads.tare_item)."""
    open_editor(page)
    set_box(page, "units.1.tare.rear_group_load_kg", "20000")
    compute(page)
    r = api.post("/v1/combinations/build", json={"combination_spec": sent_spec_of_table15(page, 20000)})
    assert r.status_code == 422, r.text
    [error] = r.json()["errors"]
    assert error["message"] in page.field_error(box_id("units.1.tare.cg_from_kingpin_m"))
    assert "rear_group_load_kg" in error["message"]


def sent_spec_of_table15(page, rear_kg: float) -> dict:
    spec = page.driver.execute_async_script(
        "const done = arguments[0]; import('/web/js/combobuilder.js').then((m) => done(m.TABLE15_SPEC));"
    )
    spec["units"][1]["tare"]["rear_group_load_kg"] = rear_kg
    return spec

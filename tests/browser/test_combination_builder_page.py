"""The page's "Build the combination" editor (app/web/js/combobuilder.js) in a real browser against a real server.

Expected numbers come from the public API called directly by the test for the same spec (``POST
/v1/combinations/build``, ``POST /v1/srt`` with ``"vehicle": {"combination_spec": ...}``) or for the preset the
editor restates (``POST /v1/srt`` with the preset's id) -- never from the page itself.
"""

from __future__ import annotations

import copy
import json
import re
from urllib.parse import parse_qs, urlsplit

import pytest
from selenium.webdriver.support.ui import Select, WebDriverWait

#: the page shows an SRT with three decimals: half a unit of the last one
DISPLAY_G = 0.0005

#: a tractor and a semitrailer as the test types them into the editor (the service's example spec, its numbers)
TYPED = {
    "units": [
        {
            "kind": "tractor",
            "axle_groups": [
                {"axles": 1, "tyres_per_axle": 2, "track_m": 2.03, "position_m": 0, "tyre": {"size": "295/80R22.5"},
                 "suspension": {"type": "trucksim-steer-leaf-5.5t"}},
                {"axles": 2, "tyres_per_axle": 4, "track_m": 1.863, "position_m": 4.3, "axle_spacing_m": 1.3,
                 "tyre": {"size": "295/80R22.5"}, "suspension": {"type": "trucksim-tandem-leaf-15.5t"}},
            ],
            "tare": {"mass_kg": 8000, "cg_height_m": 1.0, "cg_from_kingpin_m": 1.9},
        },
        {
            "kind": "semitrailer",
            "axle_groups": [
                {"axles": 3, "tyres_per_axle": 4, "track_m": 1.863, "position_m": 9.5, "tyre": {"size": "295/80R22.5"},
                 "suspension": {"type": "trucksim-trailer-leaf-18t"}},
            ],
            "tare": {"mass_kg": 7500, "cg_height_m": 1.1, "cg_from_kingpin_m": 6.0},
            "deck": {"front_from_kingpin_m": -1.2, "length_m": 13.6},
            "payloads": [{"mass_kg": 22000, "deck_height_m": 1.3, "load_height_m": 2.6, "distribution": "uniform"}],
        },
    ],
    "couplings": [{"kind": "fifth-wheel", "position_m": 4.0, "height_m": 1.1, "fifth_wheel": "trucksim-fifth-wheel"}],
}  # fmt: skip


def box_id(path: str) -> str:
    """The editor's box for a spec path (``units.1.tare.mass_kg`` -> ``#cb-units-1-tare-mass_kg``)."""
    return "#cb-" + path.replace(".", "-")


def leaves(node, prefix=""):
    """(spec path, value) of every number and text of a spec."""
    if isinstance(node, dict):
        for k, v in node.items():
            yield from leaves(v, f"{prefix}.{k}" if prefix else k)
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield from leaves(v, f"{prefix}.{i}")
    else:
        yield prefix, node


def open_editor(page):
    page.open()
    page.find('input[name="source"][value="combo"]').click()
    WebDriverWait(page.driver, 10).until(lambda _: page.find("#cb-editor").is_displayed())


def start_from(page, choice: str) -> None:
    Select(page.find("#cb-start")).select_by_value(choice)
    before = page.find("#cb-units").get_attribute("innerHTML")
    page.find("#cb-start-button").click()
    WebDriverWait(page.driver, 20).until(lambda _: page.text("#cb-start-info") != "")
    assert page.find("#cb-units").get_attribute("innerHTML") != before or choice == "table15"


def set_box(page, path: str, value) -> None:
    box = page.find(box_id(path))
    if box.tag_name == "select":
        Select(box).select_by_value(str(value))
    else:
        box.clear()
        box.send_keys(str(value))


def chosen(page, path: str) -> str:
    return Select(page.find(box_id(path))).first_selected_option.get_attribute("value")


def compute(page) -> None:
    page.run("computations", lambda: page.find("#cb-compute").click())


def api_ok(api, path: str, body: dict) -> dict:
    r = api.post(path, json=body)
    assert r.status_code == 200, r.text
    return r.json()


def shown_srt(text: str) -> float:
    m = re.search(r"SRT (\d\.\d{3}) g", text)
    assert m, text
    return float(m.group(1))


# ------------------------------------------------------------------------------------------- building


def test_a_tractor_semitrailer_built_from_scratch_shows_the_apis_governing_srt(page, api):
    open_editor(page)
    start_from(page, "scratch")
    # from scratch: a tractor and a semitrailer, one coupling, empty boxes but for the axles
    assert len(page.find_all("#cb-units .cb-unit")) == 2 and len(page.find_all("#cb-units .cb-coupling")) == 1
    assert page.find(box_id("units.0.tare.mass_kg")).get_attribute("value") == ""
    page.find("#cb-units .cb-unit[data-unit='1'] .cb-add-payload").click()
    for path, value in leaves(TYPED):
        set_box(page, path, value)
    compute(page)
    assert page.text("#case-error") == ""
    # the page sent the spec as typed (its link holds it), and the service built and solved it
    link = parse_qs(urlsplit(page.driver.current_url).query)
    assert json.loads(link["combination_spec"][0]) == TYPED
    built = api_ok(api, "/v1/combinations/build", {"combination_spec": TYPED})
    expected = api_ok(api, "/v1/srt", {"vehicle": {"combination_spec": TYPED}, "model": "combination"})
    governing = expected["roll_coupled_units"][expected["governing_unit"]]
    # the governing SRT shown is the API's (to the three decimals shown), in the result and in the printout
    assert shown_srt(page.text("#governing-unit")) == pytest.approx(governing["srt"], abs=DISPLAY_G)
    assert page.srt_g() == pytest.approx(expected["srt"], abs=DISPLAY_G)
    assert " + ".join(governing["units"]) in page.text("#governing-unit")
    summary = page.find("#summary-governing").get_attribute("textContent")
    assert shown_srt(summary) == pytest.approx(governing["srt"], abs=DISPLAY_G)
    # the drawing is of the built units; the build's gross mass is shown
    drawn = [g.get_attribute("data-unit") for g in page.find_all("#combination-result g.unit")]
    assert drawn == [u["id"] for u in built["combination"]["units"]]
    assert page.text("#cb-gross") == f"Built: gross mass {built['gross_mass_kg']:,.0f} kg in 2 units."
    rows = page.find_all("#units-table tbody tr")
    assert len(rows) == len(expected["roll_coupled_units"])
    # the link reopens the editor with that spec and computes it again
    page.open(f"?{urlsplit(page.driver.current_url).query}")
    assert page.find('input[name="source"][value="combo"]').is_selected()
    assert page.find(box_id("units.1.payloads.0.mass_kg")).get_attribute("value") == "22000"
    assert shown_srt(page.text("#governing-unit")) == pytest.approx(governing["srt"], abs=DISPLAY_G)


def test_a_preset_restated_unit_by_unit_has_the_presets_srt(page, api):
    """The A-double preset, restated by the editor as measurable data (tare = sprung mass + axles), solves to the
    preset's own SRT; removing its last unit leaves a tractor, a semitrailer and a dolly joined by two couplings."""
    open_editor(page)
    start_from(page, "preset:adouble")
    assert len(page.find_all("#cb-units .cb-unit")) == 4
    compute(page)
    assert page.text("#case-error") == ""
    preset = api_ok(api, "/v1/srt", {"vehicle": "adouble", "model": "combination"})
    # the editor's values are rounded to 6 significant figures: the SRT to the three decimals shown
    assert page.srt_g() == pytest.approx(preset["srt"], abs=DISPLAY_G + 1e-4)
    # the preset's group ids are in their boxes and in the spec the page sent; nothing is only kept from the spec
    record = api.get("/v1/combinations/adouble").json()["combination"]
    sent = json.loads(parse_qs(urlsplit(page.driver.current_url).query)["combination_spec"][0])
    ids = [[g["id"] for g in u["groups"]] for u in record["units"]]
    assert [[g.get("id") for g in u["axle_groups"]] for u in sent["units"]] == ids
    for i, unit_ids in enumerate(ids):
        for j, gid in enumerate(unit_ids):
            assert page.find(box_id(f"units.{i}.axle_groups.{j}.id")).get_attribute("value") == gid
        assert "Kept from the spec" not in page.text(f"#cb-units .cb-unit[data-unit='{i}'] > .hint")
    page.find("#cb-units .cb-unit[data-unit='3'] .cb-remove-unit").click()
    kinds = [chosen(page, f"units.{i}.kind") for i in range(3)]
    assert kinds == ["tractor", "semitrailer", "dolly"]
    assert len(page.find_all("#cb-units .cb-coupling")) == 2
    # a unit added at the rear brings the coupling that usually joins it (a semitrailer on the dolly: fifth wheel)
    Select(page.find("#cb-add-kind")).select_by_value("semitrailer")
    page.find("#cb-add").click()
    assert len(page.find_all("#cb-units .cb-unit")) == 4
    assert chosen(page, "couplings.2.kind") == "fifth-wheel"


# ------------------------------------------------------------------------------------------- errors, staleness


def test_a_tare_typed_in_tonnes_shows_the_apis_problem_at_that_box(page, api):
    open_editor(page)
    set_box(page, "units.1.tare.mass_kg", "7.5")
    compute(page)
    # the same spec through the API: its problem names the field, and the page shows its message at that box
    spec = _table15_with_tare(page, 7.5)
    r = api.post("/v1/combinations/build", json={"combination_spec": spec})
    assert r.status_code == 422, r.text
    [error] = r.json()["errors"]
    assert error["field"] == "combination_spec.units.1.tare.mass_kg"
    assert "in tonnes?" in error["message"]
    note = page.field_error(box_id("units.1.tare.mass_kg"))
    assert error["message"] in note
    assert page.find(box_id("units.1.tare.mass_kg")).get_attribute("aria-invalid") == "true"
    # the box has the focus, and no other box is marked
    assert page.driver.switch_to.active_element.get_attribute("id") == box_id("units.1.tare.mass_kg")[1:]
    assert len(page.find_all('#cb-editor [aria-invalid="true"]')) == 1


def test_a_tyre_size_without_data_is_refused_at_its_box_with_the_sizes_that_have_data(page, api):
    open_editor(page)
    set_box(page, "units.0.axle_groups.0.tyre.size", "12R19.5")
    compute(page)
    r = api.post(
        "/v1/combinations/build",
        json={"combination_spec": _table15_with(page, ("units", 0, "axle_groups", 0, "tyre", "size"), "12R19.5")},
    )
    assert r.status_code == 422, r.text
    [error] = r.json()["errors"]
    assert error["message"] in page.field_error(box_id("units.0.axle_groups.0.tyre.size"))
    listed = error["message"].split("sizes with data: ")[1].split(" (or give")[0].split(", ")
    suggested = {o.get_attribute("value") for o in page.find_all("#cb-tyre-sizes option")}
    assert set(listed) <= suggested


def _table15_with(page, where: tuple, value) -> dict:
    spec = _table15_with_tare(page, None)
    node = spec
    for k in where[:-1]:
        node = node[k]
    node[where[-1]] = value
    return spec


def _table15_with_tare(page, tare_kg: float | None) -> dict:
    """The editor's default spec as its boxes hold it (read from the page's own module, then the test's change)."""
    spec = page.driver.execute_async_script(
        "const done = arguments[0]; import('/web/js/combobuilder.js').then((m) => done(m.TABLE15_SPEC));"
    )
    spec = copy.deepcopy(spec)
    if tare_kg is not None:
        spec["units"][1]["tare"]["mass_kg"] = tare_kg
    return spec


def test_editing_a_box_marks_the_result_stale(page):
    open_editor(page)
    compute(page)
    assert page.find("#results-body").get_attribute("data-stale") is None
    assert page.find("#cb-result").get_attribute("data-stale") is None
    set_box(page, "units.1.tare.cg_height_m", "2.1")
    assert page.find("#results-body").get_attribute("data-stale") == "true"
    assert page.find("#cb-result").get_attribute("data-stale") == "true"
    assert "inputs changed" in page.text("#stale-combo")
    assert page.find("#bar-stale").is_displayed()
    # computing again: fresh
    compute(page)
    assert page.find("#results-body").get_attribute("data-stale") is None
    # a structural edit (a payload added) marks it stale too
    page.find("#cb-units .cb-unit[data-unit='1'] .cb-add-payload").click()
    assert page.find("#results-body").get_attribute("data-stale") == "true"


# ------------------------------------------------------------------------------------------- widths


def assert_editor_fits(page) -> None:
    """Neither the page nor the editor scrolls sideways, and no control sticks out of the editor."""
    fits = page.driver.execute_script(
        "const e = document.querySelector('#cb-editor'); const r = e.getBoundingClientRect();"
        "const out = [...e.querySelectorAll('input, select, button, label, legend')]"
        "  .filter((n) => n.getBoundingClientRect().right > r.right + 0.5).map((n) => n.id || n.textContent);"
        "return {page: document.documentElement.scrollWidth <= document.documentElement.clientWidth,"
        "  editor: e.scrollWidth <= e.clientWidth, out};"
    )
    assert fits == {"page": True, "editor": True, "out": []}


@pytest.mark.parametrize("width", [1366, 390])
def test_the_editor_has_no_horizontal_overflow(page, width):
    page.driver.set_window_size(width, 900)
    open_editor(page)
    start_from(page, "preset:btrain-table16")
    for d in page.find_all("#cb-editor details"):
        page.driver.execute_script("arguments[0].open = true", d)
    page.find("#cb-units .cb-unit[data-unit='2'] .cb-add-payload").click()
    assert_editor_fits(page)

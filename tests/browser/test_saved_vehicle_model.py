"""One number per vehicle (issue 41, point 3): every preset saved from the page and loaded back as a saved vehicle
keeps the model its kind defaults to (a combination: the combination model), on the page, in the link it builds and
in an assessment -- its SRT is the API's for the saved id, and the preset's.

The expected SRTs come from the public API (POST /v1/srt with the saved id and no model: the service's default for
the vehicle's kind), never from the page.
"""

from __future__ import annotations

import pytest
from selenium.webdriver.support.ui import Select, WebDriverWait

pytestmark = [pytest.mark.browser, pytest.mark.slow]

#: the page shows the SRT with three decimals: it can differ from the API's value by half a unit of the last one
DISPLAY_G = 0.0005


def presets(api) -> list[str]:
    combinations = [c["id"] for c in api.get("/v1/combinations").json()]
    return combinations + [p["id"] for p in api.get("/v1/vehicles").json()]


def save_preset(page, preset: str, key: str) -> str:
    """The preset chosen on the page, computed and saved under the key; its saved id."""
    page.open(f"?vehicle={preset}")
    page.find("#catalog-box summary").click()
    page.type("#api-key", key)
    page.type("#save-title", f"Saved {preset}")
    page.find("#save-vehicle").click()
    WebDriverWait(page.driver, 30).until(lambda _: page.text("#save-info").startswith("Saved as veh_"))
    return page.text("#save-info").split()[2]


def test_every_preset_saved_and_loaded_back_keeps_its_srt(page, api, live_server):
    auth = {"Authorization": f"Bearer {live_server.key}"}
    checked = []
    for preset in presets(api):
        page.driver.set_window_size(1366, 900)
        vehicle_id = save_preset(page, preset, live_server.key)
        preset_model = Select(page.find("#model")).first_selected_option.get_attribute("value")
        preset_srt = api.post("/v1/srt", json={"vehicle": preset, "model": preset_model}).json()["srt"]
        assert page.srt_g() == pytest.approx(preset_srt, abs=DISPLAY_G), preset
        saved = api.post("/v1/srt", json={"vehicle": vehicle_id}, headers=auth)
        if saved.status_code == 422:
            # a preset the service's default model cannot solve (table14-semitrailer: 2D only) has no number without
            # a model, at the API either: the one the preset was computed with is chosen by hand below
            saved = api.post("/v1/srt", json={"vehicle": vehicle_id, "model": preset_model}, headers=auth)
            page_model = preset_model
        else:
            page_model = None
        saved = saved.json()
        assert saved["srt"] == pytest.approx(preset_srt, rel=1e-9), preset  # the API: one number per vehicle

        # loaded back: "Saved vehicle", the id, the key typed; the model is the kind's (nothing chosen by hand)
        page.open(f"?vehicle={vehicle_id}")
        page.driver.execute_script("document.querySelector('#catalog-box').open = true")  # the key's box
        page.type("#api-key", live_server.key)
        page.find("#saved-load").click()
        title = f"Saved {preset}"
        WebDriverWait(page.driver, 30).until(lambda _, title=title: page.text("#saved-info").startswith(title))
        if page_model:
            Select(page.find("#model")).select_by_value(page_model)
        model = Select(page.find("#model")).first_selected_option.get_attribute("value")
        assert model == saved["model"], preset
        page.run("computations", lambda: page.find("#compute").click())
        assert page.srt_g() == pytest.approx(saved["srt"], abs=DISPLAY_G), preset

        # the link the page built: the same number when opened again with the key
        link = page.driver.current_url
        assert vehicle_id in link and live_server.key not in link
        page.driver.get(link)
        WebDriverWait(page.driver, 60).until(
            lambda d: d.find_element("tag name", "body").get_attribute("data-computed") == "true"
        )
        page.driver.execute_script("document.querySelector('#catalog-box').open = true")  # the key's box
        page.type("#api-key", live_server.key)
        page.run("computations", lambda: page.find("#compute").click())
        assert page.srt_g() == pytest.approx(saved["srt"], abs=DISPLAY_G), preset
        assert Select(page.find("#model")).first_selected_option.get_attribute("value") == saved["model"]
        checked.append((preset, saved["model"]))
    # the combinations and the thesis's presets were all there
    assert {m for _, m in checked} >= {"combination", "3d"}

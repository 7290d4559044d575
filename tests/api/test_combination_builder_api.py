"""The combination builder over HTTP: POST /v1/combinations/build and {"combination_spec": ...} as a vehicle.

The expected combination is the preset tractor-semitrailer-table15 (GET /v1/combinations/{id}), restated in
measurable terms from its published sources in tests/engine/test_combination_builder.py; its expected SRT is the
preset's through POST /v1/srt; the axle loads must sum to the total mass x g (force balance).
"""

from __future__ import annotations

import copy
import re

import pytest

from tests.engine.test_combination_builder import BAD, table15_spec

PRESET = "tractor-semitrailer-table15"


def post(client, path, body, status=200):
    r = client.post(path, json=body)
    assert r.status_code == status, r.text
    return r


def dotted(field: str) -> str:
    """The service's errors[].field form of an engine path: ``units[1].tare`` -> ``units.1.tare``."""
    return re.sub(r"\[(\d+)\]", r".\1", field)


def close(a, b) -> bool:
    if isinstance(a, dict):
        return set(a) == set(b) and all(close(a[k], b[k]) for k in a)
    if isinstance(a, list):
        return len(a) == len(b) and all(close(x, y) for x, y in zip(a, b, strict=True))
    if isinstance(a, float) and isinstance(b, float | int) and not isinstance(b, bool):
        return a == pytest.approx(b, rel=1e-12, abs=1e-12)
    return a == b


def test_the_build_rebuilds_the_preset_and_says_where_each_value_comes_from(shared_client):
    built = post(shared_client, "/v1/combinations/build", {"combination_spec": table15_spec()}).json()
    preset = shared_client.get(f"/v1/combinations/{PRESET}").json()["combination"]
    untitled = [{k: v for k, v in u.items() if k != "title"} for u in built["combination"]["units"]]
    # the only difference: the units' titles (none given)
    assert close(untitled, [{k: v for k, v in u.items() if k != "title"} for u in preset["units"]])
    assert close(built["combination"]["couplings"], preset["couplings"])
    d = built["derivation"]["units[0].groups[1].roll_stiffness_knm_per_rad"]
    assert d["method"] == "library" and "8.5t Leaf" in d["source"]
    assert d["spec_path"] == "combination_spec.units[0].axle_groups[1].suspension.type"
    for d in built["derivation"].values():
        assert d["method"] in ("given", "computed", "library", "default") and d["source"]
    # force balance: the axle loads carry every tare and payload (Eq. 4.27 along the chain)
    total = sum(a["load_kn"] for a in built["axle_loads"])
    assert total == pytest.approx(built["gross_mass_kg"] * 9.81 / 1000.0, rel=1e-12)
    assert built["gross_mass_kg"] == pytest.approx(5496.0 + 364.147e3 / 9.81, rel=1e-12)  # TruckSim + Table 15
    # the trailer's sprung mass: Table 15's W / g less three 445 kg axles
    assert built["units"][1]["sprung_mass_kg"] == pytest.approx(364.147e3 / 9.81 - 3 * 445.0, rel=1e-12)


def test_a_combination_spec_is_a_vehicle_with_the_presets_srt(shared_client):
    by_spec = post(shared_client, "/v1/srt", {"vehicle": {"combination_spec": table15_spec()}}).json()
    by_id = post(shared_client, "/v1/srt", {"vehicle": PRESET}).json()
    assert by_spec["model"] == "combination"
    assert by_spec["srt"] == pytest.approx(by_id["srt"], rel=1e-12)
    record = post(shared_client, "/v1/combinations/build", {"combination_spec": table15_spec()}).json()["combination"]
    by_record = post(shared_client, "/v1/srt", {"vehicle": {"combination": record}}).json()
    assert by_record["srt"] == by_spec["srt"]  # the built record is itself a vehicle
    speed = post(shared_client, "/v1/curve-speed", {"vehicle": {"combination_spec": table15_spec()}, "radius_m": 100})
    assert speed.json()["srt"] == pytest.approx(by_id["srt"], rel=1e-12)
    # the 3D model of the last unit: the spec's last unit gets Table 15's record back, LLTf/LLTr from the combination
    three_d = post(shared_client, "/v1/srt", {"vehicle": {"combination_spec": table15_spec()}, "model": "3d"}).json()
    preset_3d = post(shared_client, "/v1/srt", {"vehicle": PRESET, "model": "3d"}).json()
    assert three_d["model"] == "3d" and three_d["srt"] == pytest.approx(preset_3d["srt"], rel=1e-9)
    built = post(shared_client, "/v1/combinations/build", {"combination_spec": table15_spec()}).json()
    assert any("3D model" in n and "semitrailer" in n for n in built["notes"])


def test_the_build_is_cached_and_its_key_holds_every_input(client):
    body = {"combination_spec": table15_spec()}
    first, again = post(client, "/v1/combinations/build", body), post(client, "/v1/combinations/build", body)
    assert (first.headers["x-cache"], again.headers["x-cache"]) == ("miss", "hit")
    assert first.headers["etag"] == again.headers["etag"] and first.content == again.content
    other = copy.deepcopy(body)
    other["combination_spec"]["couplings"][0]["height_m"] = 1.1
    changed = post(client, "/v1/combinations/build", other)
    assert changed.headers["x-cache"] == "miss" and changed.headers["etag"] != first.headers["etag"]
    srt_a = post(client, "/v1/srt", {"vehicle": body})
    srt_b = post(client, "/v1/srt", {"vehicle": other})
    assert srt_a.headers["etag"] != srt_b.headers["etag"]


@pytest.mark.parametrize(("make", "field", "words"), BAD, ids=[b[1].split(".", 1)[1] for b in BAD])
def test_bad_input_is_a_422_naming_the_field(shared_client, make, field, words):
    r = post(shared_client, "/v1/combinations/build", {"combination_spec": make()}, 422)
    p = r.json()
    assert r.headers["content-type"].startswith("application/problem+json")
    assert p["errors"][0]["field"] == dotted(field)
    if field.endswith(("suspension.type", "fifth_wheel")):  # the schema lists the library's ids
        assert "Input should be 'trucksim-" in p["detail"]
    elif field.endswith("colour"):  # the schema refuses an unknown field, naming it
        assert "unknown field 'colour'" in p["detail"]
    else:
        assert words in p["detail"]
    r = post(shared_client, "/v1/srt", {"vehicle": {"combination_spec": make()}}, 422)
    assert r.json()["errors"][0]["field"] == dotted(f"vehicle.{field}")


def test_a_tare_in_tonnes_says_so(shared_client):
    spec = table15_spec()
    spec["units"][1]["tare"]["mass_kg"] = 31.5
    p = post(shared_client, "/v1/combinations/build", {"combination_spec": spec}, 422).json()
    assert "in tonnes? (31.5 tonnes would be 31500 kg)" in p["detail"]


def test_the_payload_table_takes_a_combination_spec_and_refuses_both_or_neither(shared_client):
    """POST /v1/vehicles/payload-table with a combination: the table of its loaded unit, the SRT of the spec as
    /v1/srt answers it for the same combination_spec; exactly one of spec and combination_spec."""
    from app.vehicle_forms.builder_schemas import EXAMPLE_SPEC
    from app.vehicle_forms.combination_builder_schemas import EXAMPLE_COMBINATION_SPEC

    body = {"combination_spec": EXAMPLE_COMBINATION_SPEC, "target_srt_g": 0.55, "rows": 2}
    table = shared_client.post("/v1/vehicles/payload-table", json=body)
    assert table.status_code == 200, table.text
    out = table.json()
    srt = shared_client.post("/v1/srt", json={"vehicle": {"combination_spec": EXAMPLE_COMBINATION_SPEC}}).json()
    assert out["unit_index"] == 1 and out["srt_of_spec_g"] == srt["srt"]
    assert shared_client.post("/v1/vehicles/payload-table", json={**body, "spec": EXAMPLE_SPEC}).status_code == 422
    single = shared_client.post("/v1/vehicles/payload-table", json={"spec": EXAMPLE_SPEC, "target_srt_g": 0.45})
    assert single.status_code == 200 and single.json()["unit_index"] is None
    wrong = shared_client.post("/v1/vehicles/payload-table", json={**body, "unit_index": 5})
    assert wrong.status_code == 422 and wrong.json()["errors"][0]["field"] == "unit_index"


@pytest.mark.parametrize("mass", [22, 5, 0.5])
def test_a_payload_typed_in_tonnes_is_refused_as_in_a_single_unit_spec(shared_client, mass):
    """Issue 40 item 5: a combination spec's payload of 22 (or 5, or 0.5) kg was accepted and lifted the example's
    SRT from 0.503 to 0.846 g, while the single-unit spec refused it "in tonnes?". The same range now judges both
    (RANGES["payload_mass_kg"], 100-60,000 kg, its reason in engine.vehicle.plausibility)."""
    from app.vehicle_forms.combination_builder_schemas import EXAMPLE_COMBINATION_SPEC

    spec = copy.deepcopy(EXAMPLE_COMBINATION_SPEC)
    spec["units"][1]["payloads"][0]["mass_kg"] = mass
    for path, body in (("/v1/combinations/build", {"combination_spec": spec}),
                       ("/v1/srt", {"vehicle": {"combination_spec": spec}})):  # fmt: skip
        p = post(shared_client, path, body, 422).json()
        field = "combination_spec.units.1.payloads.0.mass_kg"
        assert p["errors"][0]["field"] == (field if path.endswith("build") else f"vehicle.{field}")
        assert f"= {mass:g} kg for a payload (payload 0): in tonnes? ({mass:g} tonnes would be" in p["detail"]


@pytest.mark.parametrize(
    ("where", "value", "slip"),
    [
        (["units", 1, "axle_groups", 0, "axle_spacing_m"], 1310, "millimetres"),
        (["units", 1, "axle_groups", 0, "tyre", "loaded_radius_m"], 490, "millimetres"),
        (["units", 1, "deck", "length_m"], 13600, "millimetres"),
        (["units", 1, "payloads", 0, "length_m"], 13600, "millimetres"),
    ],
)
def test_every_measurable_input_of_a_combination_spec_is_judged_by_its_range(shared_client, where, value, slip):
    """Inputs the combination builder took unchecked (an axle spacing, a load's length) or judged by another
    quantity's range (a tyre radius as any height, a deck length as a position up to 30 m)."""
    from app.vehicle_forms.combination_builder_schemas import EXAMPLE_COMBINATION_SPEC

    spec = copy.deepcopy(EXAMPLE_COMBINATION_SPEC)
    d = spec
    for key in where[:-1]:
        d = d[key]
    d[where[-1]] = value
    p = post(shared_client, "/v1/combinations/build", {"combination_spec": spec}, 422).json()
    assert p["errors"][0]["field"] == "combination_spec." + ".".join(map(str, where))
    assert f"in {slip}?" in p["detail"], p["detail"]

"""A combination spec's data for the yaw-roll model over HTTP (issue 42, item 2): the dynamics endpoints take it from
the vehicle; given there or in the request's `dynamics` field it is the same model; given in both it is refused; it is
in the dynamics answers' keys and not in the static SRT's; a saved spec keeps it."""

from __future__ import annotations

import copy

import pytest

from app.settings import Settings
from app.vehicle_forms.combination_builder_schemas import EXAMPLE_COMBINATION_SPEC
from engine.dynamics import GROUP_DATA_DOCS, UNIT_DATA_DOCS

from .conftest import make_client

KEY = "owner-key-" + "a" * 24


def spec(trailer_iz: float = 4.0e5) -> dict:
    s = copy.deepcopy(EXAMPLE_COMBINATION_SPEC)
    s["units"][1]["dynamics"] = {"yaw_inertia_kgm2": trailer_iz, "width_m": 2.55}
    s["units"][1]["axle_groups"][0]["dynamics"] = {"cornering_coefficient_per_rad": 5.0}
    return s


def bare() -> dict:
    """The same spec with no data for the yaw-roll model (the groups' axle spacings, which it also takes, removed)."""
    s = copy.deepcopy(EXAMPLE_COMBINATION_SPEC)
    for u in s["units"]:
        for g in u["axle_groups"]:
            g.pop("axle_spacing_m", None)
    return s


def test_the_spec_schema_offers_every_field_of_the_one_definition(shared_client):
    schemas = shared_client.get("/openapi.json").json()["components"]["schemas"]
    assert set(schemas["UnitDynamicsSpec"]["properties"]) == set(UNIT_DATA_DOCS)
    # the group's axle spacing is the group's own axle_spacing_m: not a second time
    assert set(schemas["GroupDynamicsSpec"]["properties"]) == set(GROUP_DATA_DOCS) - {"axle_spacing_m"}
    width = schemas["UnitDynamicsSpec"]["properties"]["width_m"]
    low, high = UNIT_DATA_DOCS["width_m"][2:]
    assert any(x.get("minimum") == low and x.get("maximum") == high for x in width["anyOf"])


def test_the_spec_and_the_request_field_give_the_same_model(shared_client):
    """The data typed in the spec, or the built record with the same data in the request's `dynamics`: the same
    eigenvalues and RA; the sources say where each value was typed."""
    by_spec = shared_client.post("/v1/dynamics/pulse-steer", json={"vehicle": {"combination_spec": spec()}})
    assert by_spec.status_code == 200, by_spec.text
    built = shared_client.post("/v1/combinations/build", json={"combination_spec": spec()}).json()
    assert built["dynamics"]["units"] == [{"unit": "semitrailer", "yaw_inertia_kgm2": 4.0e5, "width_m": 2.55}]
    by_field = shared_client.post("/v1/dynamics/pulse-steer", json={"vehicle": {"combination": built["combination"]},
                                                                     "dynamics": built["dynamics"]})  # fmt: skip
    assert by_field.status_code == 200, by_field.text
    a, b = by_spec.json(), by_field.json()
    assert a["eigenvalues"] == b["eigenvalues"] and a["yaw_damping_ratio"] == b["yaw_damping_ratio"]
    ua, ub = a["parameters"]["units"][1], b["parameters"]["units"][1]
    assert ua["width_m"] == {"value": 2.55, "unit": "m",
                             "source": "given in vehicle.combination_spec.units[1].dynamics.width_m"}  # fmt: skip
    assert ub["width_m"]["source"] == "given in dynamics.units[0].width_m"
    assert ua["yaw_inertia_kgm2"]["value"] == ub["yaw_inertia_kgm2"]["value"]
    assert ua["yaw_inertia_kgm2"]["source"].startswith("given in vehicle.combination_spec.units[1].dynamics.")
    ga = a["parameters"]["groups"][2]
    assert ga["cornering_coefficient_per_rad"]["source"] == (
        "given in vehicle.combination_spec.units[1].axle_groups[0].dynamics.cornering_coefficient_per_rad"
    )
    spacing = "given in vehicle.combination_spec.units[1].axle_groups[0].axle_spacing_m"
    assert ga["axle_spacing_m"] == {"value": 1.31, "unit": "m", "source": spacing}
    assert a["parameters"]["units"][0]["width_m"]["source"].startswith("estimated")


def test_the_vehicle_and_the_request_field_merge_and_may_not_both_give_one_value(shared_client):
    body = {
        "vehicle": {"combination_spec": spec()},
        "dynamics": {"units": [{"unit": "semitrailer", "roll_inertia_kgm2": 3e4}]},
    }
    r = shared_client.post("/v1/dynamics/stability", json=body)
    assert r.status_code == 200, r.text
    u = r.json()["parameters"]["units"][1]
    assert u["roll_inertia_kgm2"]["source"] == "given in dynamics.units[0].roll_inertia_kgm2"
    assert u["width_m"]["source"] == "given in vehicle.combination_spec.units[1].dynamics.width_m"
    body["dynamics"]["units"][0]["width_m"] = 2.55  # the same value: still two places
    r = shared_client.post("/v1/dynamics/stability", json=body)
    assert r.status_code == 422
    err = r.json()["errors"][0]
    assert err["field"] == "dynamics.units.0.width_m"
    assert "vehicle.combination_spec.units[1].dynamics.width_m" in err["message"]


def test_one_dynamic_field_changes_the_dynamics_key_and_not_the_static_srt(shared_client):
    srt = [shared_client.post("/v1/srt", json={"vehicle": {"combination_spec": s}}) for s in
           (bare(), spec(4.0e5), spec(5.0e5))]  # fmt: skip
    assert [r.status_code for r in srt] == [200] * 3
    assert [r.headers["X-Cache"] for r in srt] == ["miss", "hit", "hit"]  # one key: the record's
    assert len({r.headers["ETag"] for r in srt}) == 1 and len({r.content for r in srt}) == 1
    dyn = [shared_client.post("/v1/dynamics/lane-change", json={"vehicle": {"combination_spec": s}}) for s in
           (spec(4.0e5), spec(5.0e5))]  # fmt: skip
    assert [r.headers["X-Cache"] for r in dyn] == ["miss", "miss"]
    assert dyn[0].headers["ETag"] != dyn[1].headers["ETag"]
    assert dyn[0].json()["rearward_amplification"] != dyn[1].json()["rearward_amplification"]


def test_a_spec_without_dynamic_data_answers_as_its_record(shared_client):
    """No dynamic field: the spec's answer is the record's (and the preset-style estimates), key for key."""
    built = shared_client.post("/v1/combinations/build", json={"combination_spec": bare()}).json()
    assert built["dynamics"] == {"units": [], "groups": []}
    a = shared_client.post("/v1/dynamics/stability", json={"vehicle": {"combination_spec": bare()}})
    b = shared_client.post("/v1/dynamics/stability", json={"vehicle": {"combination": built["combination"]}})
    assert b.headers["X-Cache"] == "hit" and a.content == b.content


@pytest.mark.parametrize(
    ("where", "data", "field"),
    [
        # the schema's bounds (the one definition's)
        ("unit", {"width_m": 5.0}, "combination_spec.units.1.dynamics.width_m"),
        ("group", {"tyre_type": "nope"}, "combination_spec.units.1.axle_groups.0.dynamics.tyre_type"),
        ("group", {"axle_spacing_m": 1.3}, "combination_spec.units.1.axle_groups.0.dynamics.axle_spacing_m"),
        # the model's checks, when the spec is built: below the point-mass bound of the unit's own masses
        ("unit", {"yaw_inertia_kgm2": 10.0}, "combination_spec.units.1.dynamics.yaw_inertia_kgm2"),
        ("group", {"tyre_type": "openpbs-constant", "cornering_coefficient_per_rad": 5.0},
         "combination_spec.units.1.axle_groups.0.dynamics.tyre_type"),
    ],
)  # fmt: skip
def test_impossible_data_is_refused_naming_the_spec_field(shared_client, where, data, field):
    s = copy.deepcopy(EXAMPLE_COMBINATION_SPEC)
    (s["units"][1] if where == "unit" else s["units"][1]["axle_groups"][0])["dynamics"] = data
    r = shared_client.post("/v1/combinations/build", json={"combination_spec": s})
    assert r.status_code == 422, r.text
    assert [e["field"] for e in r.json()["errors"]] == [field]
    r = shared_client.post("/v1/dynamics/stability", json={"vehicle": {"combination_spec": s}})
    assert r.status_code == 422 and r.json()["errors"][0]["field"] == f"vehicle.{field}"


def test_a_saved_spec_keeps_its_dynamic_data(tmp_path):
    settings = Settings(cache_backend="memory", database_url=f"sqlite:///{tmp_path / 'r.db'}", api_keys=KEY)
    auth = {"Authorization": f"Bearer {KEY}"}
    with make_client(settings) as c:
        r = c.post(
            "/v1/vehicles", json={"title": "with inertia", "vehicle": {"combination_spec": spec()}}, headers=auth
        )
        assert r.status_code == 201, r.text
        saved = r.json()
        assert saved["kind"] == "combination_spec" and saved["vehicle"]["combination_spec"] == spec()
        got = c.get(f"/v1/vehicles/{saved['id']}", headers=auth).json()
        assert got["vehicle"]["combination_spec"]["units"][1]["dynamics"] == {
            "yaw_inertia_kgm2": 4.0e5,
            "width_m": 2.55,
        }
        r = c.post("/v1/dynamics/stability", json={"vehicle": saved["id"]}, headers=auth)
        assert r.status_code == 200, r.text
        u = r.json()["parameters"]["units"][1]
        place = f"vehicle (saved vehicle {saved['id']}: combination_spec.units[1].dynamics.width_m)"
        assert u["width_m"] == {"value": 2.55, "unit": "m", "source": f"given in {place}"}
        # editing one dynamic field of the saved spec changes the answer (its key holds the data, not the id)
        put = c.put(
            f"/v1/vehicles/{saved['id']}",
            json={"title": "with inertia", "vehicle": {"combination_spec": spec(5e5)}},
            headers={**auth, "If-Match": c.get(f"/v1/vehicles/{saved['id']}", headers=auth).headers["ETag"]},
        )
        assert put.status_code == 200, put.text
        again = c.post("/v1/dynamics/stability", json={"vehicle": saved["id"]}, headers=auth)
        assert again.json()["parameters"]["units"][1]["yaw_inertia_kgm2"] != u["yaw_inertia_kgm2"]


def test_a_saved_specs_values_are_named_where_the_request_gave_the_saved_id(tmp_path):
    """The request typed ``"vehicle": "veh_..."``: a problem on a value stored in the saved spec names ``vehicle``
    (no ``vehicle.combination_spec...`` is in the request), its message the saved vehicle and the stored path; the
    same spec typed in the request keeps naming the spec's field."""
    settings = Settings(cache_backend="memory", database_url=f"sqlite:///{tmp_path / 'r.db'}", api_keys=KEY)
    auth = {"Authorization": f"Bearer {KEY}"}
    s = copy.deepcopy(EXAMPLE_COMBINATION_SPEC)
    s["units"][1]["dynamics"] = {"width_m": 2.55}
    s["units"][1]["axle_groups"][0]["dynamics"] = {"tyre_type": "trucksim-3000kg"}
    group = {"unit": "semitrailer", "group": "semitrailer", "cornering_coefficient_per_rad": 5.0}
    with make_client(settings) as c:
        vid = c.post("/v1/vehicles", json={"title": "t", "vehicle": {"combination_spec": s}}, headers=auth).json()["id"]
        stored = f"vehicle (saved vehicle {vid}: combination_spec.units[1]"
        # a tyre type stored in the saved spec beside a coefficient given in the request
        r = c.post("/v1/dynamics/stability", json={"vehicle": vid, "dynamics": {"groups": [group]}}, headers=auth)
        assert r.status_code == 422, r.text
        (err,) = r.json()["errors"]
        assert err["field"] == "vehicle" and err["loc"] == ["body", "vehicle"]
        assert err["message"].startswith(f"{stored}.axle_groups[0].dynamics.tyre_type) and "
                                         "dynamics.groups[0].cornering_coefficient_per_rad: give one")  # fmt: skip
        # a width in both: the request's field, the saved spec's place in its message
        unit = {"unit": "semitrailer", "width_m": 2.55}
        r = c.post("/v1/dynamics/stability", json={"vehicle": vid, "dynamics": {"units": [unit]}}, headers=auth)
        assert r.status_code == 422, r.text
        (err,) = r.json()["errors"]
        assert err["field"] == "dynamics.units.0.width_m"
        assert f"{stored}.dynamics.width_m)" in err["message"] and "vehicle.combination_spec" not in err["message"]
        # the spec typed in the request: its own field
        r = c.post("/v1/dynamics/stability", json={"vehicle": {"combination_spec": s}, "dynamics": {"groups": [group]}})
        (err,) = r.json()["errors"]
        assert err["field"] == "vehicle.combination_spec.units.1.axle_groups.0.dynamics.tyre_type"
        assert err["message"].startswith("vehicle.combination_spec.units[1].axle_groups[0].dynamics.tyre_type and ")

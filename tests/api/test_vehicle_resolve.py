"""A vehicle reference becomes an engine record in one step (:mod:`app.vehicles.resolve`), before the service.

Checked here: every form a vehicle takes (preset, saved vehicle, fleet member, record, spec, combination,
combination spec) resolves to the engine record the engine's own functions give for it (the builders, the preset
tables, ``Vehicle.from_dict``: an independent second route), through the srt, alignment, dynamics and advisory
endpoints; each request is resolved once, each vehicle once; the validated request reaches the service unchanged,
with no engine object in it; and the catalog does not import the vehicles feature.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest
from pydantic import BaseModel

import app.advisory.router
import app.alignments.service
import app.dynamics.router
import app.srt.router
import app.vehicles.resolve as resolve_module
from app.vehicle_forms.builder_schemas import EXAMPLE_SPEC
from app.vehicle_forms.combination_builder_schemas import EXAMPLE_COMBINATION_SPEC
from engine.builder import CombinationSpec, VehicleSpec, build_combination, build_vehicle
from engine.vehicle import Combination, Vehicle, get_combination, get_preset

from .conftest import make_client
from .test_catalog import BTRAIN, K1, auth, settings

APP = Path(__file__).resolve().parents[2] / "app"
SEMI = "table23-semitrailer"
COMBINATION = "btrain-table16"
CURVES = [{"id": "C1", "radius_m": 120.0, "superelevation_percent": 6.0, "posted_speed_kmh": 70.0}]
ADVISORY = {"radius_m": 150.0, "superelevation_percent": 6.0, "deflection_deg": 40.0, "posted_speed_kmh": 100.0}


@pytest.fixture
def cat(tmp_path):
    with make_client(settings(f"sqlite:///{tmp_path}/catalog.db")) as c:
        yield c


@pytest.fixture
def seen(monkeypatch):
    """Every :class:`VehicleRequest` the routers hand a service, and how often a vehicle was resolved."""
    calls: dict[str, list] = {"requests": [], "vehicles": []}
    real_request, real_given, real_stored = (
        resolve_module.resolve_request,
        resolve_module.resolve_given,
        resolve_module._stored,
    )

    async def resolve_request(request, body, settings):
        before = body.model_dump()
        vr = await real_request(request, body, settings)
        assert vr.body is body and body.model_dump() == before  # the request is handed on unchanged
        calls["requests"].append(vr)
        return vr

    def counted(real):
        def wrapper(*args):
            out = real(*args)
            calls["vehicles"].append(out.where)
            return out

        return wrapper

    monkeypatch.setattr(resolve_module, "resolve_given", counted(real_given))
    monkeypatch.setattr(resolve_module, "_stored", counted(real_stored))
    for module in (app.srt.router, app.alignments.service, app.dynamics.router, app.advisory.router):
        monkeypatch.setattr(module, "resolve_request", resolve_request)
    return calls


def _record(c, preset: str) -> dict:
    body = c.get(f"/v1/vehicles/{preset}").json()
    return {k: v for k, v in body.items() if k in Vehicle.__dataclass_fields__}


def _save(c, vehicle) -> str:
    r = c.post("/v1/vehicles", json={"title": "saved", "vehicle": vehicle}, headers=auth(K1))
    assert r.status_code == 201, r.text
    return r.json()["id"]


def _post(c, path: str, body: dict) -> dict:
    r = c.post(path, json=body, headers=auth(K1))
    assert r.status_code == 200, r.text
    return r.json()


def _engine_objects(value) -> list:
    """Engine records anywhere in a request (there must be none)."""
    if isinstance(value, Vehicle | Combination):
        return [value]
    if isinstance(value, BaseModel):
        return _engine_objects([getattr(value, k) for k in type(value).model_fields])
    if isinstance(value, list | tuple):
        return [x for v in value for x in _engine_objects(v)]
    if isinstance(value, dict):
        return _engine_objects(list(value.values()))
    return []


def test_every_form_resolves_to_the_engines_record_once_in_srt_and_alignments(cat, seen):
    raised = {**_record(cat, BTRAIN), "cg_height_above_chassis_m": 1.4}
    saved_record, saved_spec = _save(cat, raised), _save(cat, {"spec": EXAMPLE_SPEC})
    built = build_vehicle(VehicleSpec.from_dict(EXAMPLE_SPEC)).vehicle
    combined = build_combination(CombinationSpec.from_dict(EXAMPLE_COMBINATION_SPEC)).combination
    # (the reference, its kind, the engine record the engine's own functions give, preset id, saved id)
    cases = [
        (BTRAIN, "preset", get_preset(BTRAIN), BTRAIN, None),
        (COMBINATION, "preset", get_combination(COMBINATION), COMBINATION, None),
        (raised, "record", Vehicle.from_dict(raised), None, None),
        ({"spec": EXAMPLE_SPEC}, "spec", built, None, None),
        (
            get_combination(COMBINATION).to_dict(),  # {"combination": {...}}
            "combination",
            get_combination(COMBINATION),
            None,
            None,
        ),
        ({"combination_spec": EXAMPLE_COMBINATION_SPEC}, "combination_spec", combined, None, None),
        (saved_record, "saved", Vehicle.from_dict(raised), None, saved_record),
        (saved_spec, "saved", built, None, saved_spec),
    ]
    for ref, kind, expected, preset, saved_id in cases:
        for path, body in (
            ("/v1/srt", {"vehicle": ref}),
            ("/v1/alignments/assess", {"vehicle": ref, "curves": CURVES}),
        ):
            seen["requests"].clear()
            seen["vehicles"].clear()
            _post(cat, path, body)
            assert len(seen["requests"]) == 1 and seen["vehicles"] == ["vehicle"], (path, kind)
            (v,) = seen["requests"][0].vehicles
            assert (v.where, v.kind, v.preset, v.saved_id) == ("vehicle", kind, preset, saved_id)
            assert v.vehicle.to_dict() == expected.to_dict(), (path, kind)
            assert _engine_objects(seen["requests"][0].body) == []


def test_a_fleet_resolves_each_member_once_and_leaves_the_request_as_sent(cat, seen):
    raised = {**_record(cat, BTRAIN), "cg_height_above_chassis_m": 1.4}
    vid = _save(cat, raised)
    fid = cat.post("/v1/fleets", json={"title": "f", "vehicles": [SEMI, vid]}, headers=auth(K1)).json()["id"]
    out = _post(cat, "/v1/alignments/assess", {"fleet": fid, "curves": CURVES})
    assert [(v["preset"], v["saved_vehicle_id"]) for v in out["vehicles"]] == [(SEMI, None), (None, vid)]
    (vr,) = seen["requests"]
    assert seen["vehicles"] == ["fleet[0]", "fleet[1]"]
    assert vr.body.fleet == fid and vr.body.vehicles is None and vr.body.vehicle is None  # not rewritten
    assert [(v.where, v.kind, v.preset, v.saved_id) for v in vr.vehicles] == [
        ("fleet[0]", "preset", SEMI, None),
        ("fleet[1]", "saved", None, vid),
    ]
    assert vr.vehicles[0].vehicle == get_preset(SEMI) and vr.vehicles[1].vehicle == Vehicle.from_dict(raised)


def test_dynamics_and_advisory_take_the_same_step(cat, seen):
    vid = _save(cat, {"combination_spec": EXAMPLE_COMBINATION_SPEC})
    combined = build_combination(CombinationSpec.from_dict(EXAMPLE_COMBINATION_SPEC)).combination
    for ref in (vid, {"combination_spec": EXAMPLE_COMBINATION_SPEC}):
        seen["requests"].clear()
        _post(cat, "/v1/dynamics/stability", {"vehicle": ref})
        (vr,) = seen["requests"]
        assert vr.vehicle.vehicle.to_dict() == combined.to_dict() and _engine_objects(vr.body) == []
    seen["requests"].clear()
    seen["vehicles"].clear()
    out = _post(cat, "/v1/advisory-speed", {**ADVISORY, "vehicles": [BTRAIN, {"spec": EXAMPLE_SPEC}, vid]})
    (vr,) = seen["requests"]
    assert seen["vehicles"] == ["vehicles[0]", "vehicles[1]", "vehicles[2]"]
    assert [v.kind for v in vr.vehicles] == ["preset", "spec", "saved"]
    assert vr.vehicles[2].vehicle.to_dict() == combined.to_dict()
    assert len([m for m in out["methods"] if m["id"] == "rollover"]) == 3


def test_a_typed_records_warnings_name_where_it_was_typed():
    from app.srt.schemas import SrtRequest
    from engine.vehicle.plausibility import record_warnings

    with make_client() as c:
        record = {**_record(c, SEMI), "weight_kn": 60.0}  # a light trailer, or 60 t typed as kN
    vr = resolve_module.resolve_request_given(SrtRequest.model_validate({"vehicle": record}))
    expected = record_warnings(Vehicle.from_dict(record), "vehicle.")
    assert expected and list(vr.vehicle.warnings) == expected  # the engine's own check, named as typed
    assert resolve_module.resolve_request_given(SrtRequest.model_validate({"vehicle": SEMI})).vehicle.warnings == ()


@pytest.mark.parametrize(
    ("path", "extra"),
    [("/v1/srt", None), ("/v1/alignments/assess", {"curves": CURVES}), ("/v1/advisory-speed", ADVISORY)],
)
def test_a_record_typed_in_the_wrong_unit_is_named_where_it_was_typed(shared_client, path, extra):
    record = {**_record(shared_client, BTRAIN), "weight_kn": 31.5}  # 31.5 t typed as kN
    body = {"vehicle": record} if extra is None else {**extra, "vehicles": [BTRAIN, record]}
    r = shared_client.post(path, json=body)
    field = "vehicle.weight_kn" if extra is None else "vehicles.1.weight_kn"
    assert r.status_code == 422 and [e["field"] for e in r.json()["errors"]] == [field], r.text
    assert "in tonnes?" in r.json()["detail"]


def _imports(package: Path) -> set[str]:
    out = set()
    for path in package.rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(), str(path))):
            if isinstance(node, ast.ImportFrom) and node.module:
                out.add(node.module)
            elif isinstance(node, ast.Import):
                out.update(a.name for a in node.names)
    return out


def test_the_catalog_does_not_import_the_vehicles_feature():
    assert not {m for m in _imports(APP / "catalog") if m == "app.vehicles" or m.startswith("app.vehicles.")}


def test_the_vehicle_forms_import_no_feature():
    """The forms sit below the features (the catalog and the vehicles feature both import them)."""
    app_imports = {m for m in _imports(APP / "vehicle_forms") if m.startswith("app.")}
    assert {m.split(".")[1] for m in app_imports} <= {"http", "vehicle_forms"}

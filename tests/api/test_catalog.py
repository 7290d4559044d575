"""Saved vehicles and fleets over HTTP, on a SQLite file and on a real PostgreSQL server (``database_url``).

Covers: the CRUD round trip, ETag / If-Match (428, 412, ``*``, weak tags), the authorization matrix for every
verb, keyset pagination (stable under inserts, ties on the timestamp), the per-key limits, fleet membership,
rows damaged in the database (refused, logged, repairable), the presets staying public and read-only, and that a
key is never stored or logged.
"""

from __future__ import annotations

import asyncio
import hashlib
import json
from datetime import UTC, datetime

import pytest
from sqlalchemy import text
from structlog.testing import capture_logs

from app.catalog import service as catalog
from app.catalog.auth import owner_of
from app.catalog.service import CatalogProblem, resolve_fleet, resolve_saved_vehicle
from app.db import Database, repo
from app.settings import Settings
from app.vehicle_forms.schemas import METADATA_FIELDS

from .conftest import a_spec, make_client

K1 = "owner-key-" + "a" * 24
K2 = "other-key-" + "b" * 24
WRONG = "wrong-key-" + "c" * 24
BTRAIN = "table16-btrain"


def settings(url: str, **kw) -> Settings:
    return Settings(cache_backend="memory", database_url=url, api_keys=f"{K1},{K2}", **kw)


def auth(key: str, **headers: str) -> dict[str, str]:
    return {"Authorization": f"Bearer {key}", **headers}


@pytest.fixture
def cat(database_url):
    with make_client(settings(database_url)) as c:
        yield c


@pytest.fixture(scope="module")
def presets():
    """The preset records as GET /v1/vehicles/{id} serves them (metadata dropped): the thesis tables."""
    with make_client() as c:
        out = {}
        for p in ("table14-semitrailer", BTRAIN):
            body = c.get(f"/v1/vehicles/{p}").json()
            out[p] = {k: v for k, v in body.items() if k not in METADATA_FIELDS}
        return out


def save(c, record, title="trailer", key=K1):
    r = c.post("/v1/vehicles", json={"title": title, "vehicle": record}, headers=auth(key))
    assert r.status_code == 201, r.text
    return r.json()


def fleet(c, members, title="fleet", key=K1):
    r = c.post("/v1/fleets", json={"title": title, "vehicles": members}, headers=auth(key))
    assert r.status_code == 201, r.text
    return r.json()


# ------------------------------------------------------------------------------------------ round trip
def test_crud_round_trip(cat, presets):
    record = presets[BTRAIN]
    r = cat.post("/v1/vehicles", json={"title": "B-train rear unit", "vehicle": record}, headers=auth(K1))
    assert r.status_code == 201
    created = r.json()
    vid = created["id"]
    assert r.headers["location"] == f"/v1/vehicles/{vid}"
    assert r.headers["etag"] == '"1"' and created["version"] == 1
    assert created["kind"] == "record" and created["title"] == "B-train rear unit"
    assert created["vehicle"] == record  # stored exactly as the preset's record (Table 16: W = 355.22 kN)
    assert created["vehicle"]["weight_kn"] == 355.22
    assert created["created_at"] == created["updated_at"]
    assert created.pop("warnings") == []  # 355.22 t typed as kN would be 3,484 kN: no second reading

    got = cat.get(r.headers["location"], headers=auth(K1))
    assert got.status_code == 200 and got.json() == created and got.headers["etag"] == '"1"'

    changed = {**record, "cg_height_above_chassis_m": 1.5}
    r = cat.put(
        f"/v1/vehicles/{vid}",
        json={"title": "raised load", "vehicle": changed},
        headers=auth(K1, **{"If-Match": '"1"'}),
    )
    assert r.status_code == 200, r.text
    updated = r.json()
    assert r.headers["etag"] == '"2"' and updated["version"] == 2
    assert updated["vehicle"]["cg_height_above_chassis_m"] == 1.5 and updated["title"] == "raised load"
    assert updated["created_at"] == created["created_at"] and updated["updated_at"] > created["updated_at"]
    assert updated.pop("warnings") == []
    assert cat.get(f"/v1/vehicles/{vid}", headers=auth(K1)).json() == updated

    assert cat.delete(f"/v1/vehicles/{vid}", headers=auth(K1, **{"If-Match": '"2"'})).status_code == 204
    gone = cat.get(f"/v1/vehicles/{vid}", headers=auth(K1))
    assert gone.status_code == 404 and gone.json()["type"] == "urn:rollover:problem:not-found"
    assert vid in gone.json()["detail"]
    assert cat.delete(f"/v1/vehicles/{vid}", headers=auth(K1)).status_code == 404
    assert cat.put(
        f"/v1/vehicles/{vid}", json={"title": "x", "vehicle": record}, headers=auth(K1, **{"If-Match": "*"})
    ).status_code == 404  # fmt: skip


def test_saving_a_record_answers_its_input_warnings_as_a_computation_would(cat):
    # Table 23's semitrailer typed with weight_kn 50: a light trailer's 50 kN (5.1 t) or 50 t typed as kN
    # (50 x 9.80665 = 490.3 kN, standard gravity, CGPM 1901); neither reading can be refused, so the save names
    # the field as the request typed it and both readings, as POST /v1/srt answers the same record
    record = cat.get("/v1/vehicles/table23-semitrailer").json()
    record = {k: v for k, v in record.items() if k not in METADATA_FIELDS}
    light = {**record, "weight_kn": 50.0}
    srt = cat.post("/v1/srt", json={"vehicle": light, "model": "3d"})
    assert srt.status_code == 200, srt.text
    created = save(cat, light)
    assert created["warnings"] == srt.json()["warnings"]
    (w,) = created["warnings"]
    assert w["field"] == "vehicle.weight_kn" and w["value"] == 50.0 and w["unit"] == "kN"
    assert w["other_unit"] == "tonnes" and w["other_reading"] == pytest.approx(50.0 * 9.80665, rel=1e-12)

    path = f"/v1/vehicles/{created['id']}"
    got = cat.get(path, headers=auth(K1)).json()
    assert "warnings" not in got and got == {k: v for k, v in created.items() if k != "warnings"}

    # Table 23's own weight (392.13 kN) reads only in kN; the replacement answers its own (empty) warnings
    r = cat.put(path, json={"title": "t", "vehicle": record}, headers=auth(K1, **{"If-Match": '"1"'}))
    assert r.status_code == 200 and r.json()["warnings"] == [], r.text
    r = cat.put(path, json={"title": "t", "vehicle": light}, headers=auth(K1, **{"If-Match": '"2"'}))
    assert r.status_code == 200 and [w["field"] for w in r.json()["warnings"]] == ["vehicle.weight_kn"], r.text
    # a builder spec computes its own weight: nothing typed to warn of
    assert save(cat, a_spec())["warnings"] == []
    # a combination's last_unit_record (Table 15's, its weight typed 50) warns named inside the combination
    combination = cat.get("/v1/combinations/tractor-semitrailer-table15").json()["combination"]
    combination["last_unit_record"]["weight_kn"] = 50.0
    saved = save(cat, {"combination": combination})
    assert [w["field"] for w in saved["warnings"]] == ["vehicle.combination.last_unit_record.weight_kn"]


def test_a_2d_record_and_a_spec_can_be_saved(cat, presets):
    two_d = save(cat, presets["table14-semitrailer"], "Table 14 (2D)")  # no 3D fields: MissingParameter allowed
    assert two_d["vehicle"]["front_axles"] is None and two_d["kind"] == "record"
    spec = a_spec("from the builder")
    saved = save(cat, spec, "spec")
    assert saved["kind"] == "spec" and saved["vehicle"] == spec
    assert cat.get(f"/v1/vehicles/{saved['id']}", headers=auth(K1)).json()["vehicle"] == spec


@pytest.mark.parametrize(
    ("change", "field"),
    [
        # Rill's condition (Eq. 2.17): kLs b^2 / 2 must exceed W l12, else the body falls over at rest
        ({"spring_separation_m": 0.35}, "vehicle.suspension_stiffness_kn_per_m"),  # 5400 x 0.35^2 / 2 < 250 x 1.356
        # the CG must lie between the kingpin and the rear group (Table 8 geometry; Table 16 wheelbase 4.26 m)
        ({"front_axle_to_cg_m": 5.0}, "vehicle.front_axle_to_cg_m"),
        # track = axle width at rest (Sec. 4.1.1)
        ({"rear_track_m": 2.5}, "vehicle.rear_track_m"),
        # a unit slip: 31.5 t typed as kN (a heavy vehicle is over 3.5 t = 34.3 kN; engine.vehicle.plausibility)
        ({"weight_kn": 31.5}, "vehicle.weight_kn"),
    ],
)
def test_the_engine_refuses_an_impossible_record_naming_the_field(cat, presets, change, field):
    r = cat.post("/v1/vehicles", json={"title": "bad", "vehicle": {**presets[BTRAIN], **change}}, headers=auth(K1))
    assert r.status_code == 422
    problem = r.json()
    assert problem["type"] == "urn:rollover:problem:invalid-vehicle"
    assert [e["field"] for e in problem["errors"]] == [field]


def test_a_2d_record_is_still_checked(cat, presets):
    r = cat.post(
        "/v1/vehicles",
        json={"title": "bad 2D", "vehicle": {**presets["table14-semitrailer"], "rear_track_m": 2.5}},
        headers=auth(K1),
    )
    assert r.status_code == 422 and r.json()["errors"][0]["field"] == "vehicle.rear_track_m"


def test_schema_errors_name_the_field(cat, presets):
    r = cat.post("/v1/vehicles", json={"title": "x", "vehicle": {**presets[BTRAIN], "weight_kn": -1}}, headers=auth(K1))
    assert r.status_code == 422 and r.json()["errors"][0]["field"] == "vehicle.weight_kn"
    r = cat.post("/v1/vehicles", json={"title": "x", "vehicle": {"spec": 5}}, headers=auth(K1))
    assert r.status_code == 422 and r.json()["errors"][0]["field"] == "vehicle.spec"
    r = cat.post("/v1/vehicles", json={"title": "", "vehicle": presets[BTRAIN]}, headers=auth(K1))
    assert r.status_code == 422 and r.json()["errors"][0]["field"] == "title"
    r = cat.post("/v1/vehicles", json={"title": "a preset id is not a body", "vehicle": BTRAIN}, headers=auth(K1))
    assert r.status_code == 422 and r.json()["errors"][0]["field"] == "vehicle"
    # the parser accepts NaN; JSON cannot store it, so it is refused (not silently written as null)
    nan = json.dumps({"title": "nan", "vehicle": a_spec()}).replace('"mass_kg": 8000.0', '"mass_kg": NaN')
    r = cat.post("/v1/vehicles", content=nan.encode(), headers=auth(K1, **{"Content-Type": "application/json"}))
    assert r.status_code == 422 and r.json()["errors"][0]["field"] == "vehicle.spec.tare.mass_kg"
    spec = a_spec()
    spec["spec"]["rear"] = {**spec["spec"]["rear"], "axles": -(2**63) - 1}
    huge = cat.post("/v1/vehicles", json={"title": "big int", "vehicle": spec}, headers=auth(K1))
    assert huge.status_code == 422 and huge.json()["errors"][0]["field"] == "vehicle.spec.rear.axles"
    # a spec the builder refuses is refused when saved, naming the spec field and the reason
    spec = a_spec()
    spec["spec"]["payloads"] = [{**spec["spec"]["payloads"][0], "load_height_m": 1.0}]  # below the 1.25 m deck
    r = cat.post("/v1/vehicles", json={"title": "load below deck", "vehicle": spec}, headers=auth(K1))
    assert r.status_code == 422 and r.json()["errors"][0]["field"] == "vehicle.spec.payloads.0.load_height_m"


# ------------------------------------------------------------------------------------------- If-Match
def test_if_match_required_stale_and_wildcard(cat, presets):
    vid = save(cat, presets[BTRAIN])["id"]
    body = {"title": "v2", "vehicle": presets[BTRAIN]}
    missing = cat.put(f"/v1/vehicles/{vid}", json=body, headers=auth(K1))
    assert missing.status_code == 428
    assert missing.json()["type"] == "urn:rollover:problem:precondition-required"
    for stale in ('"2"', 'W/"1"', "1", '"abc"'):  # a future version, a weak tag, unquoted, garbage
        r = cat.put(f"/v1/vehicles/{vid}", json=body, headers=auth(K1, **{"If-Match": stale}))
        assert r.status_code == 412, stale
        assert r.json()["type"] == "urn:rollover:problem:precondition-failed"
    assert cat.get(f"/v1/vehicles/{vid}", headers=auth(K1)).json()["version"] == 1  # nothing changed
    ok = cat.put(f"/v1/vehicles/{vid}", json=body, headers=auth(K1, **{"If-Match": '"7", "1"'}))  # a list
    assert ok.status_code == 200 and ok.headers["etag"] == '"2"'
    again = cat.put(f"/v1/vehicles/{vid}", json=body, headers=auth(K1, **{"If-Match": '"1"'}))  # lost update
    assert again.status_code == 412
    star = cat.put(f"/v1/vehicles/{vid}", json=body, headers=auth(K1, **{"If-Match": "*"}))
    assert star.status_code == 200 and star.json()["version"] == 3
    assert cat.delete(f"/v1/vehicles/{vid}", headers=auth(K1, **{"If-Match": '"2"'})).status_code == 412
    assert cat.delete(f"/v1/vehicles/{vid}", headers=auth(K1, **{"If-Match": '"3"'})).status_code == 204


def test_fleet_if_match(cat):
    f = fleet(cat, [BTRAIN])
    body = {"title": "renamed", "vehicles": [BTRAIN, "table22-truck"]}
    assert cat.put(f"/v1/fleets/{f['id']}", json=body, headers=auth(K1)).status_code == 428
    assert cat.put(f"/v1/fleets/{f['id']}", json=body, headers=auth(K1, **{"If-Match": '"9"'})).status_code == 412
    r = cat.put(f"/v1/fleets/{f['id']}", json=body, headers=auth(K1, **{"If-Match": '"1"'}))
    assert r.status_code == 200 and r.headers["etag"] == '"2"' and r.json()["vehicles"] == [BTRAIN, "table22-truck"]
    assert cat.delete(f"/v1/fleets/{f['id']}", headers=auth(K1, **{"If-Match": '"1"'})).status_code == 412
    assert cat.delete(f"/v1/fleets/{f['id']}", headers=auth(K1)).status_code == 204
    assert cat.get(f"/v1/fleets/{f['id']}", headers=auth(K1)).status_code == 404


# ------------------------------------------------------------------------------------ authorization
def _operations(c, presets):
    """Every catalog operation, each on its own fresh resources of K1: (name, method, path, kwargs, owner status)."""
    record = presets[BTRAIN]
    used = save(c, record, "in a fleet")["id"]
    free = save(c, record, "free")["id"]
    f = fleet(c, [used, BTRAIN])["id"]
    if_match = {"If-Match": '"1"'}
    put_vehicle = {"json": {"title": "t", "vehicle": record}, "h": if_match}
    return [
        ("create vehicle", "POST", "/v1/vehicles", {"json": {"title": "t", "vehicle": record}}, 201),
        ("list vehicles", "GET", "/v1/vehicles/saved", {}, 200),
        ("get vehicle", "GET", f"/v1/vehicles/{free}", {}, 200),
        ("replace vehicle", "PUT", f"/v1/vehicles/{free}", put_vehicle, 200),
        ("delete vehicle", "DELETE", f"/v1/vehicles/{free}", {}, 204),
        ("create fleet", "POST", "/v1/fleets", {"json": {"title": "t", "vehicles": [used]}}, 201),
        ("list fleets", "GET", "/v1/fleets", {}, 200),
        ("get fleet", "GET", f"/v1/fleets/{f}", {}, 200),
        ("replace fleet", "PUT", f"/v1/fleets/{f}", {"json": {"title": "t", "vehicles": [BTRAIN]}, "h": if_match}, 200),
        ("delete fleet", "DELETE", f"/v1/fleets/{f}", {}, 204),
    ]  # fmt: skip


def _call(c, method, path, kwargs, headers):
    return c.request(method, path, json=kwargs.get("json"), headers={**kwargs.get("h", {}), **headers})


@pytest.mark.parametrize("caller", ["owner", "other key", "no key", "wrong key"])
def test_authorization_matrix(cat, presets, caller):
    headers = {"owner": auth(K1), "other key": auth(K2), "no key": {}, "wrong key": auth(WRONG)}[caller]
    seen = {}
    for name, method, path, kwargs, _ in _operations(cat, presets):
        before = cat.get(path, headers=auth(K1)).json() if method in ("PUT", "DELETE") else None
        r = _call(cat, method, path, kwargs, headers)
        seen[name] = r.status_code
        if caller in ("no key", "wrong key"):
            challenge = r.headers["www-authenticate"]
            assert challenge.startswith("Bearer ") and ('error="invalid_token"' in challenge) == (caller == "wrong key")
            assert r.json()["type"] == "urn:rollover:problem:unauthorized"
        if caller == "other key" and method == "GET" and path.endswith(("/saved", "/fleets")):
            owned = {i["id"] for i in cat.get(path, headers=auth(K1)).json()["items"]}
            assert owned and not owned & {i["id"] for i in r.json()["items"]}  # K2 sees none of K1's
        if before is not None and caller != "owner":  # the attempt changed nothing
            assert cat.get(path, headers=auth(K1)).json() == before
    expected = {
        "owner": {name: status for name, _, _, _, status in _operations(cat, presets)},
        # another key: its own lists and creations work; K1's ids do not exist for it (404, also as a member)
        "other key": {
            "create vehicle": 201, "list vehicles": 200, "get vehicle": 404, "replace vehicle": 404,
            "delete vehicle": 404, "create fleet": 404, "list fleets": 200, "get fleet": 404,
            "replace fleet": 404, "delete fleet": 404,
        },
        "no key": dict.fromkeys(seen, 401),
        "wrong key": dict.fromkeys(seen, 401),
    }[caller]  # fmt: skip
    assert seen == expected


def test_no_keys_configured_disables_the_catalog_without_touching_the_disk(tmp_path, presets):
    db_file = tmp_path / "never.db"
    with make_client(Settings(cache_backend="memory", database_url=f"sqlite:///{db_file}")) as c:
        statuses = set()
        for method, path, body in [
            ("POST", "/v1/vehicles", {"title": "t", "vehicle": presets[BTRAIN]}),
            ("GET", "/v1/vehicles/saved", None),
            ("GET", "/v1/vehicles/veh_" + "a" * 22, None),
            ("PUT", "/v1/vehicles/veh_" + "a" * 22, {"title": "t", "vehicle": presets[BTRAIN]}),
            ("DELETE", "/v1/vehicles/veh_" + "a" * 22, None),
            ("POST", "/v1/fleets", {"title": "t", "vehicles": [BTRAIN]}),
            ("GET", "/v1/fleets", None),
            ("GET", "/v1/fleets/flt_" + "a" * 22, None),
            ("PUT", "/v1/fleets/flt_" + "a" * 22, {"title": "t", "vehicles": [BTRAIN]}),
            ("DELETE", "/v1/fleets/flt_" + "a" * 22, None),
        ]:
            for headers in ({}, auth(K1)):
                r = c.request(method, path, json=body, headers={**headers, "If-Match": '"1"'})
                statuses.add(r.status_code)
                assert r.json()["type"] == "urn:rollover:problem:catalog-disabled"
                assert "ROLLOVER_API_KEYS" in r.json()["detail"]
        assert statuses == {403}
        # the presets and the computations stay open
        assert c.get(f"/v1/vehicles/{BTRAIN}").status_code == 200
        assert c.post("/v1/srt", json={"vehicle": BTRAIN, "model": "rigid"}).status_code == 200
    assert not db_file.exists()


# ----------------------------------------------------------------------------- presets and path ids
def test_presets_stay_public_and_read_only(cat, presets):
    assert [v["id"] for v in cat.get("/v1/vehicles").json()][:1] == ["table14-semitrailer"]
    assert cat.get(f"/v1/vehicles/{BTRAIN}").json()["weight_kn"] == 355.22  # Table 16, no key needed
    assert cat.get("/v1/vehicles/table99-nothing").status_code == 404  # unknown preset, as before
    for headers in ({}, auth(K1)):
        for method in ("PUT", "DELETE"):
            r = cat.request(
                method, f"/v1/vehicles/{BTRAIN}", json={"title": "t", "vehicle": presets[BTRAIN]}, headers=headers
            )
            assert r.status_code == 405 and r.headers["allow"] == "GET"
            assert r.json()["type"] == "urn:rollover:problem:read-only"
    assert cat.get(f"/v1/vehicles/{BTRAIN}").json()["weight_kn"] == 355.22


def test_saved_ids_are_unguessable_and_malformed_ids_are_refused(cat, presets):
    ids = {save(cat, presets[BTRAIN], f"n{i}")["id"] for i in range(5)}
    assert len(ids) == 5
    assert all(catalog.SAVED_VEHICLE_ID.match(i) for i in ids)
    f = fleet(cat, [BTRAIN])["id"]
    assert catalog.FLEET_ID.match(f)
    body = {"title": "t", "vehicle": presets[BTRAIN]}
    # /v1/vehicles/{id} also serves presets, so its spec has no id pattern: an id that cannot be saved names none
    for method, path in [
        ("GET", "/v1/vehicles/veh_short"),
        ("PUT", "/v1/vehicles/garbage"),
        ("DELETE", "/v1/vehicles/veh_" + "!" * 22),
    ]:
        r = cat.request(method, path, json=body, headers=auth(K1, **{"If-Match": "*"}))
        assert r.status_code == 404, (method, path, r.text)
        assert r.json()["type"] == "urn:rollover:problem:not-found"
        assert "pattern ^veh_" in r.json()["detail"]
    # a fleet's path states its pattern: 422 naming the id
    for method, path in [("GET", "/v1/fleets/flt_x"), ("DELETE", "/v1/fleets/" + "a" * 26)]:
        r = cat.request(method, path, json=body, headers=auth(K1, **{"If-Match": "*"}))
        assert r.status_code == 422, (method, path, r.text)
        assert [e["field"] for e in r.json()["errors"]] == ["id"]
    # a literal path under /v1/vehicles is not an id: PUT/DELETE on it is 405 with what it allows
    for path, allow in [("/v1/vehicles/saved", "GET"), ("/v1/vehicles/build", "POST")]:
        r = cat.request("PUT", path, json=body, headers=auth(K1, **{"If-Match": "*"}))
        assert r.status_code == 405, (path, r.text)
        assert r.headers["allow"] == allow


# ---------------------------------------------------------------------------------------- pagination
def _pages(c, path, limit, key=K1):
    pages, cursor = [], None
    while True:
        params = {"limit": limit, **({"cursor": cursor} if cursor else {})}
        r = c.get(path, params=params, headers=auth(key))
        assert r.status_code == 200, r.text
        pages.append([i["id"] for i in r.json()["items"]])
        cursor = r.json()["next_cursor"]
        if cursor is None:
            return pages


def test_pagination_in_creation_order(cat):
    made = [save(cat, a_spec(i), f"v{i}")["id"] for i in range(7)]
    assert _pages(cat, "/v1/vehicles/saved", 3) == [made[0:3], made[3:6], made[6:7]]
    assert _pages(cat, "/v1/vehicles/saved", 7) == [made]
    assert _pages(cat, "/v1/vehicles/saved", 200) == [made]
    assert _pages(cat, "/v1/vehicles/saved", 3, key=K2) == [[]]
    fleets = [fleet(cat, [BTRAIN], f"f{i}")["id"] for i in range(3)]
    assert _pages(cat, "/v1/fleets", 2) == [fleets[:2], fleets[2:]]
    assert cat.get("/v1/vehicles/saved", params={"limit": 0}, headers=auth(K1)).status_code == 422
    assert cat.get("/v1/vehicles/saved", params={"limit": 201}, headers=auth(K1)).status_code == 422
    unknown = cat.get("/v1/vehicles/saved", params={"offset": 3}, headers=auth(K1))
    assert unknown.status_code == 422 and unknown.json()["errors"][0]["field"] == "offset"
    bad = cat.get("/v1/vehicles/saved", params={"cursor": "not-a-cursor"}, headers=auth(K1))
    assert bad.status_code == 422 and bad.json()["errors"][0]["field"] == "cursor"
    # a fleet cursor is not a vehicle cursor
    r = cat.get("/v1/fleets", params={"limit": 1}, headers=auth(K1)).json()["next_cursor"]
    assert cat.get("/v1/vehicles/saved", params={"cursor": r}, headers=auth(K1)).status_code == 422


def test_pagination_has_no_duplicates_or_misses_under_inserts_and_deletes(cat):
    made = [save(cat, a_spec(i), f"v{i}")["id"] for i in range(9)]
    seen, cursor, added, deleted = [], None, [], None
    while True:
        params = {"limit": 2, **({"cursor": cursor} if cursor else {})}
        page = cat.get("/v1/vehicles/saved", params=params, headers=auth(K1)).json()
        seen += [i["id"] for i in page["items"]]
        # between pages, another client adds vehicles, and deletes one already seen
        added += [save(cat, a_spec(f"late {len(added)}"), "late")["id"] for _ in range(2)]
        if deleted is None:
            deleted = seen[0]
            assert cat.delete(f"/v1/vehicles/{deleted}", headers=auth(K1)).status_code == 204
        cursor = page["next_cursor"]
        if cursor is None or len(added) > 8:
            break
    while cursor is not None:  # drain without further inserts
        page = cat.get("/v1/vehicles/saved", params={"limit": 2, "cursor": cursor}, headers=auth(K1)).json()
        seen += [i["id"] for i in page["items"]]
        cursor = page["next_cursor"]
    assert len(seen) == len(set(seen))  # no duplicates
    assert seen[: len(made)] == made  # every vehicle that existed at the start, once, in order
    assert set(seen[len(made) :]) <= set(added)  # then only vehicles added meanwhile, in creation order
    assert seen[len(made) :] == [a for a in added if a in seen[len(made) :]]


def test_pagination_breaks_timestamp_ties_by_id(database_url, monkeypatch):
    # every row created in the same microsecond: the keyset (created_at, id) still pages through each once
    instant = datetime(2026, 1, 1, 12, 0, 0, 123456, tzinfo=UTC)
    monkeypatch.setattr(repo, "utcnow", lambda: instant)
    with make_client(settings(database_url)) as c:
        made = [save(c, a_spec(i), f"v{i}")["id"] for i in range(6)]
        pages = _pages(c, "/v1/vehicles/saved", 4)
    assert [len(p) for p in pages] == [4, 2]
    assert [i for p in pages for i in p] == sorted(made)


# -------------------------------------------------------------------------------------------- limits
def test_per_key_limits(database_url, presets):
    small = settings(
        database_url,
        catalog_max_vehicles=2,
        catalog_max_fleets=1,
        catalog_max_vehicle_bytes=1000,
        catalog_max_fleet_members=2,
    )
    with make_client(small) as c:
        first = save(c, presets[BTRAIN], "one")  # a full record is about 800 bytes as stored
        save(c, a_spec(2), "two")
        r = c.post("/v1/vehicles", json={"title": "three", "vehicle": a_spec(3)}, headers=auth(K1))
        assert r.status_code == 409
        problem = r.json()
        assert problem["type"] == "urn:rollover:problem:limit-reached"
        assert problem["limit"] == {"setting": "ROLLOVER_CATALOG_MAX_VEHICLES", "max": 2}
        save(c, a_spec(1), "K2's first", key=K2)  # the limit is per key
        assert c.delete(f"/v1/vehicles/{first['id']}", headers=auth(K1)).status_code == 204
        third = save(c, a_spec(3), "three")  # room again after a delete

        big = a_spec("x" * 100, payloads=10)  # a long title and ten deck loads: over 1000 bytes as stored
        r = c.post("/v1/vehicles", json={"title": "big", "vehicle": big}, headers=auth(K2))
        assert r.status_code == 413
        assert r.json()["limit"] == {"setting": "ROLLOVER_CATALOG_MAX_VEHICLE_BYTES", "max": 1000}
        assert r.json()["errors"][0]["field"] == "vehicle"
        r = c.put(
            f"/v1/vehicles/{third['id']}", json={"title": "big", "vehicle": big}, headers=auth(K1, **{"If-Match": "*"})
        )
        assert r.status_code == 413  # fmt: skip

        r = c.post(
            "/v1/fleets", json={"title": "f", "vehicles": [BTRAIN, "table22-truck", third["id"]]}, headers=auth(K1)
        )
        assert r.status_code == 422  # fmt: skip
        assert r.json()["type"] == "urn:rollover:problem:too-many-members"
        assert r.json()["limit"] == {"setting": "ROLLOVER_CATALOG_MAX_FLEET_MEMBERS", "max": 2}
        fleet(c, [BTRAIN, third["id"]])
        r = c.post("/v1/fleets", json={"title": "f2", "vehicles": [BTRAIN]}, headers=auth(K1))
        assert r.status_code == 409 and r.json()["limit"] == {"setting": "ROLLOVER_CATALOG_MAX_FLEETS", "max": 1}


# ---------------------------------------------------------------------------------- fleet membership
def test_fleet_membership_is_checked_and_protected(cat, presets):
    mine = save(cat, presets[BTRAIN], "mine")["id"]
    theirs = save(cat, presets[BTRAIN], "theirs", key=K2)["id"]
    absent = "veh_" + "A" * 22

    r = cat.post("/v1/fleets", json={"title": "f", "vehicles": [BTRAIN, theirs, mine, absent]}, headers=auth(K1))
    assert r.status_code == 404
    assert [e["field"] for e in r.json()["errors"]] == ["vehicles.1", "vehicles.3"]  # another key's = missing
    r = cat.post("/v1/fleets", json={"title": "f", "vehicles": [mine, "table99-nothing"]}, headers=auth(K1))
    assert r.status_code == 404 and [e["field"] for e in r.json()["errors"]] == ["vehicles.1"]
    assert BTRAIN in r.json()["known"]
    r = cat.post("/v1/fleets", json={"title": "f", "vehicles": [mine, "veh_bad", mine]}, headers=auth(K1))
    assert r.status_code == 422 and [e["field"] for e in r.json()["errors"]] == ["vehicles.1"]  # the schema's pattern
    r = cat.post("/v1/fleets", json={"title": "f", "vehicles": [mine, BTRAIN, mine]}, headers=auth(K1))
    assert r.status_code == 422 and [e["field"] for e in r.json()["errors"]] == ["vehicles.2"]  # uniqueItems
    r = cat.post("/v1/fleets", json={"title": "f", "vehicles": []}, headers=auth(K1))
    assert r.status_code == 422
    assert cat.get("/v1/fleets", headers=auth(K1)).json()["items"] == []  # nothing half-created

    f = fleet(cat, [mine, BTRAIN], "haulers")
    assert f["vehicles"] == [mine, BTRAIN] and f["version"] == 1
    r = cat.delete(f"/v1/vehicles/{mine}", headers=auth(K1))
    assert r.status_code == 409
    assert r.json()["type"] == "urn:rollover:problem:vehicle-in-use" and r.json()["fleets"] == [f["id"]]
    assert f["id"] in r.json()["detail"]
    # a PUT that would add a missing member changes nothing
    r = cat.put(
        f"/v1/fleets/{f['id']}", json={"title": "x", "vehicles": [absent]}, headers=auth(K1, **{"If-Match": "*"})
    )
    assert r.status_code == 404 and cat.get(f"/v1/fleets/{f['id']}", headers=auth(K1)).json() == f  # fmt: skip
    r = cat.put(
        f"/v1/fleets/{f['id']}", json={"title": "h", "vehicles": [BTRAIN]}, headers=auth(K1, **{"If-Match": '"1"'})
    )
    assert r.status_code == 200  # fmt: skip
    assert cat.delete(f"/v1/vehicles/{mine}", headers=auth(K1)).status_code == 204
    # deleting a fleet leaves its vehicles
    g = fleet(cat, [theirs], key=K2)
    assert cat.delete(f"/v1/fleets/{g['id']}", headers=auth(K2)).status_code == 204
    assert cat.get(f"/v1/vehicles/{theirs}", headers=auth(K2)).status_code == 200


def test_resolvers_for_the_computations(cat, presets):
    db = cat.app.state.db
    record = presets[BTRAIN]
    vid = save(cat, record)["id"]
    body = a_spec("resolved")
    spec = save(cat, body)["id"]
    fid = fleet(cat, [spec, BTRAIN, vid])["id"]
    owner, other = owner_of(K1), owner_of(K2)
    assert asyncio.run(resolve_saved_vehicle(db, owner, vid)) == record
    assert asyncio.run(resolve_saved_vehicle(db, owner, spec)) == body
    assert asyncio.run(resolve_fleet(db, owner, fid)) == [(spec, body), (BTRAIN, None), (vid, record)]
    for call in (
        resolve_saved_vehicle(db, other, vid),
        resolve_saved_vehicle(db, owner, "veh_" + "Z" * 22),
        resolve_saved_vehicle(db, owner, "garbage"),
        resolve_fleet(db, other, fid),
    ):
        with pytest.raises(CatalogProblem) as info:
            asyncio.run(call)
        assert info.value.status == 404 and info.value.extra["id"] in info.value.detail


# ------------------------------------------------------------------------------------ damaged rows
CORRUPTIONS = {
    "not JSON": ("body", "{not json"),
    "schema": ("body", None),  # filled in: the record with a negative weight
    "physics": ("body", None),  # the record failing Rill's condition (Eq. 2.17)
    "kind": ("kind", "spec"),  # a record body under kind=spec
    "title": ("title", ""),
    "version": ("version", 0),
}


def _damage(url: str, id: str, column: str, value) -> None:
    db = Database(url)
    try:
        with db.engine.begin() as c:
            if db.dialect == "postgresql" and column == "version":  # the CHECK constraint guards it: drop it
                c.execute(text("ALTER TABLE vehicles DROP CONSTRAINT ck_vehicles_version"))
            if db.dialect == "sqlite" and column == "version":
                c.exec_driver_sql("PRAGMA ignore_check_constraints=ON")
            c.execute(text(f"UPDATE vehicles SET {column} = :v WHERE id = :id"), {"v": value, "id": id})
    finally:
        db.dispose()


@pytest.mark.parametrize("damage", sorted(CORRUPTIONS))
def test_a_damaged_row_is_refused_logged_and_repairable(database_url, presets, damage):
    import orjson

    record = presets[BTRAIN]
    column, value = CORRUPTIONS[damage]
    if damage == "schema":
        value = orjson.dumps({**record, "weight_kn": -5.0}).decode()
    if damage == "physics":
        value = orjson.dumps({**record, "spring_separation_m": 0.1}).decode()
    with make_client(settings(database_url)) as c:
        good = save(c, record, "good")
        bad = save(c, record, "to be damaged")
        _damage(database_url, bad["id"], column, value)
        with capture_logs() as logs:
            r = c.get(f"/v1/vehicles/{bad['id']}", headers=auth(K1))
            page = c.get("/v1/vehicles/saved", headers=auth(K1)).json()
        assert r.status_code == 409, r.text
        assert r.json()["type"] == "urn:rollover:problem:stored-record-invalid"
        assert bad["id"] in r.json()["detail"]
        assert [e["id"] for e in logs if e["event"] == "catalog_invalid_row"] == [bad["id"], bad["id"]]
        # the listing serves the sound rows and names the damaged one
        assert [i["id"] for i in page["items"]] == [good["id"]] and page["unreadable"] == [bad["id"]]
        with pytest.raises(CatalogProblem) as info:
            asyncio.run(resolve_saved_vehicle(c.app.state.db, owner_of(K1), bad["id"]))
        assert info.value.status == 409
        # the owner repairs it with the ETag the 409 carries (when the version itself is sound)
        etag = r.headers.get("etag", "*")
        assert damage == "version" or etag == '"1"'
        fixed = c.put(
            f"/v1/vehicles/{bad['id']}",
            json={"title": "fixed", "vehicle": record},
            headers=auth(K1, **{"If-Match": etag}),
        )
        assert fixed.status_code == 200 and fixed.json()["vehicle"] == record


def test_a_damaged_sqlite_timestamp_is_a_409_not_a_500(tmp_path, presets):
    url = f"sqlite:///{tmp_path / 'r.db'}"
    with make_client(settings(url)) as c:
        vid = save(c, presets[BTRAIN])["id"]
        _damage(url, vid, "created_at", "yesterday-ish")
        r = c.get(f"/v1/vehicles/{vid}", headers=auth(K1))
        assert r.status_code == 409 and r.json()["type"] == "urn:rollover:problem:stored-record-invalid"
        page = c.get("/v1/vehicles/saved", headers=auth(K1))  # the driver cannot read the page: 409 too
        assert page.status_code == 409 and page.json()["type"] == "urn:rollover:problem:stored-record-invalid"
        assert c.delete(f"/v1/vehicles/{vid}", headers=auth(K1)).status_code == 204  # and the owner can remove it


def test_a_damaged_fleet_is_refused(database_url):
    with make_client(settings(database_url)) as c:
        f = fleet(c, [BTRAIN])
        db = Database(database_url)
        try:
            with db.engine.begin() as conn:
                conn.execute(text("UPDATE fleets SET title = '' WHERE id = :id"), {"id": f["id"]})
        finally:
            db.dispose()
        r = c.get(f"/v1/fleets/{f['id']}", headers=auth(K1))
        assert r.status_code == 409 and r.headers["etag"] == '"1"'
        assert c.get("/v1/fleets", headers=auth(K1)).json()["unreadable"] == [f["id"]]


def test_a_database_that_stops_answering_is_a_503(tmp_path, presets):
    from .conftest import free_port

    with make_client(settings(f"sqlite:///{tmp_path / 'r.db'}")) as c:
        vid = save(c, presets[BTRAIN])["id"]
        c.app.state.db.dispose()
        c.app.state.db = Database(f"postgresql+psycopg://postgres@127.0.0.1:{free_port()}/gone")  # nothing listens
        r = c.get(f"/v1/vehicles/{vid}", headers=auth(K1))
        assert r.status_code == 503 and r.headers["retry-after"] == "5"
        assert r.json()["type"] == "urn:rollover:problem:database-unavailable"
        assert c.get(f"/v1/vehicles/{BTRAIN}").status_code == 200  # presets still answer


# --------------------------------------------------------------------------------- keys and secrets
def test_a_key_is_never_stored_or_logged(database_url, tmp_path, presets):
    with capture_logs() as logs, make_client(settings(database_url)) as c:
        vid = save(c, presets[BTRAIN])["id"]
        fleet(c, [vid])
        c.get("/v1/vehicles/saved", headers=auth(WRONG))
        c.get(f"/v1/vehicles/{vid}", headers=auth(K2))
    db = Database(database_url)
    try:
        with db.engine.connect() as conn:
            owners = {row[0] for row in conn.execute(text("SELECT owner FROM vehicles UNION SELECT owner FROM fleets"))}
            rows = [
                r for t in ("vehicles", "fleets", "fleet_members") for r in conn.execute(text(f"SELECT * FROM {t}"))
            ]
            dump = " ".join(str(v) for row in rows for v in row)
    finally:
        db.dispose()
    assert owners == {hashlib.sha256(b"rollover-owner-v1\x00" + K1.encode()).hexdigest()}
    assert K1 not in dump
    if database_url.startswith("sqlite"):
        raw = b"".join(p.read_bytes() for p in tmp_path.glob("rollover.db*"))
        assert raw and K1.encode() not in raw
    text_logs = repr(logs)
    for key in (K1, K2, WRONG):
        assert key not in text_logs


def test_short_keys_are_refused_without_echoing_them():
    with pytest.raises(ValueError) as info:
        Settings(api_keys=f"{K1},tooshort")
    assert "key #2" in str(info.value) and "tooshort" not in str(info.value) and K1 not in str(info.value)

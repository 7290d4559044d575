"""The in-process result cache: X-Cache and ETag, what the key covers, and the size bound."""

from __future__ import annotations

import hashlib

import orjson
import pytest

import app.compute.cache
import app.srt.service
import engine.models.threshold
from app.settings import Settings

from .conftest import make_client

BTRAIN = "table16-btrain"
RIGID = {"vehicle": BTRAIN, "model": "rigid"}


def test_miss_then_hit_with_the_same_etag_and_body(client):
    first = client.post("/v1/srt", json=RIGID)
    second = client.post("/v1/srt", json=RIGID)
    assert first.headers["x-cache"] == "miss" and second.headers["x-cache"] == "hit"
    assert first.headers["etag"] == second.headers["etag"]
    assert first.content == second.content


@pytest.mark.parametrize("path", ["/v1/srt", "/v1/curve-speed", "/v1/min-radius"])
def test_every_computed_response_carries_etag_and_x_cache(client, path):
    body = {
        "/v1/srt": RIGID,
        "/v1/curve-speed": {"radius_m": 80, "srt": 0.3364},
        "/v1/min-radius": {"design_speed_kmh": 60, "superelevation_percent": 8, "srt": 0.3},
    }[path]
    r = client.post(path, json=body)
    assert r.status_code == 200
    assert r.headers["x-cache"] == "miss"
    assert r.headers["etag"].startswith('"') and r.headers["etag"].endswith('"')
    assert client.post(path, json=body).headers["x-cache"] == "hit"


def test_the_etag_is_the_sha256_of_the_canonical_resolved_request_with_the_engine_version(client):
    from engine import ENGINE_VERSION

    etag = client.post("/v1/srt", json=RIGID).headers["etag"].strip('"')
    record = client.get(f"/v1/vehicles/{BTRAIN}").json()
    for k in ("id", "title", "source", "models"):
        record.pop(k)
    resolved = {
        "engine_version": ENGINE_VERSION,
        "op": "srt",
        "vehicle": record,
        "model": "rigid",
        "stage": "full",
        "road": {"bank_percent": 0.0, "slope_percent": 0.0},
        "trailer_angle_deg": 0.0,
        "load": {
            "lateral_offset_m": 0.0,
            "longitudinal_offset_m": 0.0,
            "vertical_offset_m": 0.0,
            "overweight_percent": 0.0,
        },
        "rear_llt_limit": 1.0,
        "include_curves": False,
        "curve_points": None,
        # the body reports the SRT against the targets, so they are in the key (the configured defaults here)
        "targets": {"general": 0.35, "dangerous_goods": 0.40},
        # and what they are judged on (the level-road SRT): a body cached when verdicts used the case's own SRT
        # has another key, so a shared cache never serves it again
        "targets_judged_on": "level_road_srt",
    }
    digest = hashlib.sha256(orjson.dumps(resolved, option=orjson.OPT_SORT_KEYS)).hexdigest()
    assert etag == f"{ENGINE_VERSION}:srt:{digest}"


def test_defaults_given_or_omitted_share_one_entry(client):
    explicit = {
        "vehicle": BTRAIN,
        "model": "rigid",
        "stage": "full",
        "road": {"bank_percent": 0, "slope_percent": -0.0},
        "trailer_angle_deg": 0,
        "load": {"lateral_offset_m": 0.0},
        "rear_llt_limit": 1,
        "include_curves": False,
        "curve_points": 7,  # changes nothing without curves
    }
    assert client.post("/v1/srt", json=RIGID).headers["x-cache"] == "miss"
    r = client.post("/v1/srt", json=explicit)
    assert r.headers["x-cache"] == "hit"


def test_any_change_of_input_is_a_new_entry(client):
    base = client.post("/v1/srt", json={"vehicle": BTRAIN, "model": "rigid-bank", "road": {"bank_percent": 2}})
    other = client.post("/v1/srt", json={"vehicle": BTRAIN, "model": "rigid-bank", "road": {"bank_percent": 2.5}})
    assert other.headers["x-cache"] == "miss"
    assert other.headers["etag"] != base.headers["etag"]
    assert other.json()["srt"] == pytest.approx(base.json()["srt"] + 0.005)
    record = client.get(f"/v1/vehicles/{BTRAIN}").json()
    record["cg_height_above_chassis_m"] = 1.4
    edited = client.post("/v1/srt", json={"vehicle": record, "model": "rigid"})
    assert edited.headers["x-cache"] == "miss"
    assert edited.json()["srt"] == pytest.approx(0.93 / (0.704 + 1.4))


def test_a_new_engine_version_never_serves_a_stale_answer(client, monkeypatch):
    old = client.post("/v1/srt", json=RIGID)
    monkeypatch.setattr(app.compute.cache, "ENGINE_VERSION", "9.9.9")
    new = client.post("/v1/srt", json=RIGID)
    assert new.headers["x-cache"] == "miss"
    assert new.headers["etag"].startswith('"9.9.9:srt:') and new.headers["etag"] != old.headers["etag"]


def test_the_lru_is_bounded(monkeypatch):
    with make_client(Settings(cache_backend="memory", cache_max_entries=2)) as c:
        bodies = [{"vehicle": BTRAIN, "model": "rigid", "load": {"vertical_offset_m": d}} for d in (0.0, 0.1, 0.2)]
        for b in bodies:
            assert c.post("/v1/srt", json=b).headers["x-cache"] == "miss"
        assert c.get("/healthz").json()["cache_entries"] == 2
        assert c.post("/v1/srt", json=bodies[2]).headers["x-cache"] == "hit"
        assert c.post("/v1/srt", json=bodies[0]).headers["x-cache"] == "miss"  # the oldest was evicted


def test_curve_speed_reuses_the_cached_srt(client, monkeypatch):
    # the SRT request inside /v1/curve-speed resolves to the same key as /v1/srt with the same fields
    calls = []
    # a one-threshold solve (app.compute.coalescer hands it to the engine)
    real = engine.models.threshold.rollover_threshold

    def counting(*args, **kwargs):
        calls.append(args)
        return real(*args, **kwargs)

    monkeypatch.setattr(engine.models.threshold, "rollover_threshold", counting)
    srt = client.post("/v1/srt", json={"vehicle": BTRAIN, "model": "navin"})
    assert len(calls) == 1
    out = client.post("/v1/curve-speed", json={"radius_m": 100, "vehicle": BTRAIN, "model": "navin"})
    assert out.headers["x-cache"] == "miss"  # the curve-speed answer is new ...
    assert len(calls) == 1  # ... but its SRT came from the cache
    assert out.json()["srt_result"] == srt.json()


def test_errors_are_not_cached(client):
    body = {"vehicle": BTRAIN, "load": {"lateral_offset_m": 0.95}}
    assert client.post("/v1/srt", json=body).status_code == 422
    r = client.post("/v1/srt", json=body)
    assert r.status_code == 422 and "x-cache" not in r.headers


def test_the_lru_is_bounded_in_bytes_too():
    bodies = [{"vehicle": BTRAIN, "model": "rigid", "load": {"vertical_offset_m": d}} for d in (0.0, 0.1, 0.2)]
    with make_client() as c:
        size = len(c.post("/v1/srt", json=bodies[0]).content)
    # room for two of these bodies (they differ by a few bytes at most), not three
    with make_client(Settings(cache_backend="memory", cache_max_bytes=int(2.5 * size))) as c:
        for b in bodies:
            assert c.post("/v1/srt", json=b).headers["x-cache"] == "miss"
        assert c.get("/healthz").json()["cache_entries"] == 2
        assert c.post("/v1/srt", json=bodies[0]).headers["x-cache"] == "miss"  # the oldest was evicted


def test_a_body_over_the_entry_limit_is_not_cached():
    with make_client(Settings(cache_backend="memory", cache_max_entry_bytes=100)) as c:
        assert c.post("/v1/srt", json=RIGID).headers["x-cache"] == "miss"
        r = c.post("/v1/srt", json=RIGID)
        assert r.status_code == 200 and r.headers["x-cache"] == "miss"
        assert c.get("/healthz").json()["cache_entries"] == 0

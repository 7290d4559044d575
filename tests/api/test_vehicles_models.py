"""GET /v1/vehicles, GET /v1/vehicles/{id}, GET /v1/models, GET /healthz, GET /metrics."""

from __future__ import annotations

import pytest

from engine.vehicle.presets import PRESETS

PRESET_IDS = ["table14-semitrailer", "table15-semitrailer", "table16-btrain", "table22-truck", "table23-semitrailer"]


def test_vehicle_list_has_the_five_thesis_presets_as_full_records(shared_client):
    r = shared_client.get("/v1/vehicles")
    assert r.status_code == 200
    items = r.json()
    assert [v["id"] for v in items] == PRESET_IDS
    for item in items:
        # every field of the engine record is there (null where the table does not give it)
        assert set(PRESETS[item["id"]].to_dict()) <= set(item)
        assert {"title", "source", "models"} <= set(item)


def test_btrain_record_carries_table16_values(shared_client):
    r = shared_client.get("/v1/vehicles/table16-btrain")
    assert r.status_code == 200
    v = r.json()
    # Table 16 (thesis Ch. 9): W 355.22 kN, t 1.86 m, 2 + 3 axles, kf 7500 kN/m, l12 1.356 m, L 4.26 m, a 3.0 m
    assert v["weight_kn"] == 355.22
    assert v["rear_track_m"] == v["front_track_m"] == 1.86
    assert (v["front_axles"], v["rear_axles"]) == (2, 3)
    assert v["fifth_wheel_stiffness_kn_per_m"] == 7500.0
    assert v["cg_height_above_chassis_m"] == 1.356
    assert (v["wheelbase_m"], v["front_axle_to_cg_m"]) == (4.26, 3.0)
    assert v["front_llt_ratio"] == 0.7  # Kamnik et al. (2003)


def test_table14_leaves_the_front_group_null(shared_client):
    v = shared_client.get("/v1/vehicles/table14-semitrailer").json()
    # Table 14 is a 2D vehicle: one axle group, no fifth wheel, no wheelbase
    assert v["front_axles"] is None and v["wheelbase_m"] is None and v["fifth_wheel_stiffness_kn_per_m"] is None
    assert v["weight_kn"] == 250.0 and v["cg_height_above_chassis_m"] == 1.346
    assert "3d" not in v["models"]


def test_unknown_preset_is_a_404_problem_listing_the_known_ids(shared_client):
    r = shared_client.get("/v1/vehicles/table99-nothing")
    assert r.status_code == 404
    assert r.headers["content-type"] == "application/problem+json"
    p = r.json()
    assert p["status"] == 404 and p["type"].endswith("unknown-preset")
    assert "table99-nothing" in p["detail"]
    assert p["known"] == sorted(PRESET_IDS)


def test_a_fetched_preset_can_be_posted_back_as_a_record(shared_client):
    record = shared_client.get("/v1/vehicles/table16-btrain").json()  # with id/title/source/models
    by_record = shared_client.post("/v1/srt", json={"vehicle": record, "model": "rigid"})
    by_id = shared_client.post("/v1/srt", json={"vehicle": "table16-btrain", "model": "rigid"})
    assert by_record.status_code == by_id.status_code == 200
    assert by_record.json() == by_id.json()
    # the preset expanded to its record and the record itself are the same resolved request: same key
    assert by_record.headers["etag"] == by_id.headers["etag"]


def test_models_lists_the_ten_models_with_equations_and_references(shared_client):
    r = shared_client.get("/v1/models")
    assert r.status_code == 200
    models = {m["id"]: m for m in r.json()}
    thesis = {"3d", "2d", "rigid", "rigid-bank", "winkler", "rill", "chang", "gillespie", "navin"}
    assert set(models) == {*thesis, "combination"}  # the nine of the thesis and the whole-combination model
    assert models["rigid"]["equation"] == "Eq. 2.6"
    assert models["rill"]["equation"] == "Eq. 2.20"
    assert models["navin"]["reference"].startswith("Navin")
    assert models["3d"]["default"] and not models["2d"]["default"]
    assert models["3d"]["curves"] and not models["gillespie"]["curves"]
    assert "bank" in models["rigid-bank"]["takes"] and "bank" not in models["rigid"]["takes"]


def test_healthz(shared_client):
    r = shared_client.get("/healthz")
    assert r.status_code == 200
    body = r.json()
    assert body["status"] == "ok" and body["cache_backend"] == "memory" and body["redis"] is None


@pytest.mark.parametrize("path", ["/v1/nothing", "/v1/srt/extra"])
def test_unknown_routes_are_problems_too(shared_client, path):
    r = shared_client.get(path)
    assert r.status_code in (404, 405)
    assert r.headers["content-type"] == "application/problem+json"
    assert r.json()["status"] == r.status_code


def test_metrics_count_solves_and_cache_lookups(client):
    body = {"vehicle": "table16-btrain", "model": "gillespie"}
    client.post("/v1/srt", json=body)
    client.post("/v1/srt", json=body)
    r = client.get("/metrics")
    assert r.status_code == 200
    assert r.headers["content-type"].startswith("text/plain")
    text = r.text
    assert 'rollover_solve_seconds_count{model="gillespie",operation="srt"}' in text
    assert 'rollover_cache_lookups_total{operation="srt",result="local"}' in text
    assert 'rollover_cache_lookups_total{operation="srt",result="miss"}' in text
    assert 'http_requests_total{handler="/v1/srt",method="POST",status="2xx"}' in text  # app.http.request_metrics


@pytest.mark.parametrize("enabled", [True, False])
def test_the_metrics_setting_installs_the_http_instrumentation_or_not(enabled):
    from app.main import create_app
    from app.settings import Settings

    from .conftest import make_client

    app = create_app(Settings(cache_backend="memory", metrics=enabled))
    names = [m.cls.__name__ for m in app.user_middleware]
    assert ("HttpMetricsMiddleware" in names) is enabled
    assert "FastPathMiddleware" in names and "BodyLimitMiddleware" in names
    with make_client(Settings(cache_backend="memory", metrics=enabled)) as c:
        before = _sample(c.get("/metrics").text, HEALTHZ_OK)  # process-wide counters: compare before and after
        assert c.get("/healthz").status_code == 200
        # the service's own counters are served either way
        assert c.post("/v1/srt", json={"vehicle": "table16-btrain", "model": "rigid"}).status_code == 200
        text = c.get("/metrics").text
        assert "rollover_cache_lookups_total" in text
        assert _sample(text, HEALTHZ_OK) == before + (1 if enabled else 0)


HEALTHZ_OK = 'http_requests_total{handler="/healthz",method="GET",status="2xx"}'


def _sample(text: str, series: str) -> float:
    values = [float(line.rsplit(" ", 1)[1]) for line in text.splitlines() if line.startswith(series + " ")]
    return values[0] if values else 0.0


def test_http_metrics_name_the_route_template_not_the_path(client):
    """handler is the route's template (one series for every vehicle id), a path no route matches is "none" (a scan
    cannot create a series per path), /metrics is not counted, the status is grouped by class."""
    series = {
        "vehicle": 'http_requests_total{handler="/v1/vehicles/{id}",method="GET",status="2xx"}',
        "missing": 'http_requests_total{handler="/v1/vehicles/{id}",method="GET",status="4xx"}',
        "none": 'http_requests_total{handler="none",method="GET",status="4xx"}',
        "latency": 'http_request_duration_seconds_count{handler="/v1/vehicles/{id}",method="GET"}',
    }
    before = {k: _sample(client.get("/metrics").text, s) for k, s in series.items()}
    assert client.get("/v1/vehicles/table16-btrain").status_code == 200
    assert client.get("/v1/vehicles/table14-semitrailer").status_code == 200
    assert client.get("/v1/vehicles/no-such-vehicle").status_code == 404
    assert client.get("/wp-admin/setup.php").status_code == 404
    text = client.get("/metrics").text
    after = {k: _sample(text, s) for k, s in series.items()}
    assert {k: after[k] - before[k] for k in series} == {"vehicle": 2, "missing": 1, "none": 1, "latency": 3}
    assert 'handler="/metrics"' not in text and "/v1/vehicles/table16-btrain" not in text

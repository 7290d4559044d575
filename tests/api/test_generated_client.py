"""Generate a Python client from the committed spec with openapi-python-client and call a live uvicorn with it."""

from __future__ import annotations

import importlib
import os
import shutil
import subprocess
import sys
import time

import httpx
import pytest

from .conftest import ROOT, free_port


@pytest.fixture(scope="module")
def server():
    port = free_port()
    env = {**os.environ, "ROLLOVER_CACHE_BACKEND": "memory"}
    proc = subprocess.Popen(
        [sys.executable, "-m", "uvicorn", "app.main:app", "--host", "127.0.0.1", "--port", str(port)],
        cwd=ROOT,
        env=env,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
    )
    url = f"http://127.0.0.1:{port}"
    deadline = time.monotonic() + 60
    while True:
        try:
            if httpx.get(f"{url}/healthz", timeout=1).status_code == 200:
                break
        except httpx.HTTPError:
            pass
        if proc.poll() is not None or time.monotonic() > deadline:
            proc.kill()
            pytest.fail(f"uvicorn did not start: {proc.stderr.read().decode()[-2000:]}")
        time.sleep(0.1)
    yield url
    proc.terminate()
    try:
        proc.wait(timeout=10)
    except subprocess.TimeoutExpired:
        proc.kill()


@pytest.fixture(scope="module")
def client_package(tmp_path_factory):
    out = tmp_path_factory.mktemp("client")
    # the console script when it is on the PATH, else the module (same package, installed by the test extra)
    exe = shutil.which("openapi-python-client")
    cmd = [exe] if exe else [sys.executable, "-m", "openapi_python_client"]
    done = subprocess.run(
        [*cmd, "generate", "--path", str(ROOT / "openapi" / "openapi.json"), "--output-path", str(out / "gen")],
        cwd=out,
        capture_output=True,
        text=True,
    )
    assert done.returncode == 0, done.stdout + done.stderr
    packages = [p for p in (out / "gen").iterdir() if (p / "__init__.py").exists()]
    assert len(packages) == 1, packages
    sys.path.insert(0, str(out / "gen"))
    try:
        yield packages[0].name
    finally:
        sys.path.remove(str(out / "gen"))


def test_generated_client_calls_the_live_server(server, client_package):
    pkg = client_package
    Client = importlib.import_module(pkg).Client
    api = f"{pkg}.api"
    healthz = importlib.import_module(f"{api}.health.health_healthz")
    list_vehicles = importlib.import_module(f"{api}.vehicles.vehicles_list_vehicles")
    get_vehicle = importlib.import_module(f"{api}.vehicles.vehicles_get_vehicle")
    compute_srt = importlib.import_module(f"{api}.srt.srt_compute_srt")
    curve_speed = importlib.import_module(f"{api}.road.road_curve_speed")
    models = importlib.import_module(f"{pkg}.models")

    client = Client(base_url=server, raise_on_unexpected_status=True)

    health = healthz.sync(client=client)
    assert health.status == "ok" or getattr(health.status, "value", None) == "ok"

    vehicles = list_vehicles.sync(client=client)
    assert "table16-btrain" in [v.id for v in vehicles]

    btrain = get_vehicle.sync(client=client, id="table16-btrain")
    assert btrain.weight_kn == 355.22  # Table 16

    # rigid B-train: t/2h = 0.93 / 2.06 (Eq. 2.6)
    request = models.SrtRequest.from_dict({"vehicle": "table16-btrain", "model": "rigid"})
    detailed = compute_srt.sync_detailed(client=client, body=request)
    assert detailed.status_code == 200
    assert detailed.headers["x-cache"] == "miss" and detailed.headers["etag"]
    assert detailed.parsed.srt == pytest.approx(0.93 / 2.06)

    # Table 18: SRT 0.3364 at R = 80 m -> 58.5 km/h (Eq. 9.1)
    speed = curve_speed.sync(client=client, body=models.CurveSpeedRequest.from_dict({"radius_m": 80, "srt": 0.3364}))
    assert speed.max_speed_kmh == pytest.approx(58.5, abs=0.05)

    # the road-design operations: an inverse limit fed back as a vehicle record gives the target SRT
    srt_limits = importlib.import_module(f"{api}.srt.srt_limits")
    srt_sweep = importlib.import_module(f"{api}.srt.srt_sweep")
    assess = importlib.import_module(f"{api}.alignments.alignments_assess")
    plot_roll = importlib.import_module(f"{api}.plots.plots_roll")
    limits = srt_limits.sync(
        client=client,
        body=models.LimitsRequest.from_dict(
            {"vehicle": "table16-btrain", "parameter": "cg_height_above_chassis_m", "target_srt_g": 0.3}
        ),
    )
    assert limits.limit.status == "found" or getattr(limits.limit.status, "value", None) == "found"
    record = {k: v for k, v in btrain.to_dict().items() if k not in ("id", "title", "source", "models")}
    record["cg_height_above_chassis_m"] = limits.limit.value
    check = compute_srt.sync(client=client, body=models.SrtRequest.from_dict({"vehicle": record}))
    assert check.srt == pytest.approx(0.3, abs=1e-5)
    table17 = {"vehicle": "table16-btrain", "rear_llt_limit": 0.6, "grid": {"bank_percent": [0, 8]}}
    swept = srt_sweep.sync(client=client, body=models.SweepRequest.from_dict(table17))
    assert [row.bank_percent for row in swept.rows] == [0, 8]
    assert swept.rows[1].srt == pytest.approx(0.285, rel=0.02)  # Table 17: 8 % bank, LLT 0.6
    csv_text = "id,radius_m,superelevation_percent\nC1,120,8\nC2,600,8\n"
    assessed = assess.sync(
        client=client, body=models.AlignmentRequest.from_dict({"vehicle": "table16-btrain", "csv": csv_text})
    )
    rows = assessed.vehicles[0].rows
    assert [r.id for r in rows] == ["C1", "C2"] and rows[0].srt_g == rows[1].srt_g
    svg = plot_roll.sync_detailed(client=Client(base_url=server), body=models.PlotRequest.from_dict(
        {"vehicle": "table16-btrain"}))  # fmt: skip
    assert svg.status_code == 200 and svg.content.startswith(b"<svg") and svg.headers["x-cache"] == "miss"

    # an unknown preset comes back as the declared problem (404)
    missing = get_vehicle.sync_detailed(client=Client(base_url=server), id="nope")
    assert missing.status_code == 404
    assert missing.parsed.status == 404 and "nope" in missing.parsed.detail

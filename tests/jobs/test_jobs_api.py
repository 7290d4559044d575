"""/v1/jobs on the embedded (in-process) backend: results byte-identical to the synchronous endpoints, the summary
over parts, progress, cancellation, owners, expiry, refusals at submission, stored state that does not verify."""

from __future__ import annotations

import json
import math
import time

import numpy as np
import orjson
import pytest
from structlog.testing import capture_logs

from app.jobs import op_alignments
from app.jobs.columns import ColumnsError, pack_columns, unpack_columns
from app.jobs.op_alignments import RESULT_SCHEMA, unpack_result
from app.jobs.store import PREFIX, RAW_FRAGMENT_TYPE
from app.settings import Settings

from .conftest import job_and_sync, make_client, random_curves, run, submit, wait_for

KEY_A = "key-a-0123456789abcdef"
KEY_B = "key-b-0123456789abcdef"
SWEEP = {
    "vehicle": "table16-btrain",
    "rear_llt_limit": 0.6,
    "grid": {"bank_percent": [0, 2, 4, 6, 8], "slope_percent": [-4, 0, 4], "overweight_percent": [0, 10, 20, 30]},
}


# ------------------------------------------------------------------------------- byte-identical results


@pytest.mark.parametrize("accept", [None, "text/csv"])
def test_alignment_result_is_the_synchronous_answer_byte_for_byte(accept):
    """Two vehicles, 3,000 curves split into parts of 500 rows (250 curves): the job's JSON and CSV are the bytes
    POST /v1/alignments/assess answers, with the same ETag (its cache key)."""
    req = {"vehicles": ["table16-btrain", "table23-semitrailer"], "curves": random_curves(3000, seed=2)}
    status, job, sync = job_and_sync(req, accept, 500, 12)
    assert status["done"] == status["total"] == 6000 and status["unit"] == "rows"
    assert job.headers["content-type"] == sync.headers["content-type"]
    assert job.headers["etag"] == sync.headers["etag"]
    assert job.content == sync.content


@pytest.mark.parametrize("accept", [None, "text/csv"])
def test_alignment_result_with_ids_of_every_kind_is_the_synchronous_answer(accept):
    """Ids that CSV must escape or neutralise (a quote, a formula prefix) or JSON must escape (a quote, a backslash),
    and ids of several bytes a character, in parts of 250 curves: the first part holds the odd ones, the next
    plain ASCII and the last plain UTF-8 (a part's stored ids are written as slices of one blob where they need no
    escape, else one by one): the same bytes as the synchronous answer."""
    odd = ['say "hi"', "=SUM(A1)", "+1", "-3", "@x", "back\\slash", " lead", "x,y"]
    curves = random_curves(750, seed=7)
    for k, c in enumerate(curves):
        if k < 250:
            c["id"] = f"{odd[k % len(odd)]}{k}"
        elif k >= 500:
            c["id"] = f"Kurve-ä-曲線-{k}-🚛"
    req = {"vehicles": ["table16-btrain", "table23-semitrailer"], "curves": curves}
    _, job, sync = job_and_sync(req, accept, 500, 3)
    assert job.content == sync.content
    assert ('"say ""hi""0"' if accept else '"say \\"hi\\"0"').encode() in job.content
    assert "Kurve-ä-曲線-500-🚛".encode() in job.content


def test_alignment_csv_document_job_matches_synchronous_upload():
    """Curves sent as CSV text: the same answer as the synchronous request with the same CSV."""
    rows = random_curves(1200, seed=5)
    text = "id,radius_m,superelevation_percent,grade_percent,posted_speed_kmh\n" + "".join(
        f"{c['id']},{c['radius_m']},{c['superelevation_percent']},{c['grade_percent']},{c['posted_speed_kmh']}\n"
        for c in rows
    )
    req = {"vehicle": "table15-semitrailer", "csv": text}
    with make_client(Settings(jobs_part_size=400)) as c:
        location, status = run(c, "alignments.assess", req)
        assert status["status"] == "done" and status["parts"]["total"] == 3
        assert c.get(location + "/result").content == c.post("/v1/alignments/assess", json=req).content


@pytest.mark.parametrize("accept", [None, "text/csv"])
def test_sweep_result_is_the_synchronous_answer_byte_for_byte(accept):
    """60 cases in blocks of 12 (the last two axes whole), parts of 2 blocks: the sync sweep's bytes."""
    headers = {"accept": accept} if accept else None
    with make_client(Settings(jobs_part_size=25)) as c:
        location, status = run(c, "srt.sweep", SWEEP)
        assert status["status"] == "done" and status["parts"]["total"] == 3 and status["total"] == 60
        job = c.get(location + "/result", headers=headers)
        sync = c.post("/v1/srt/sweep", json=SWEEP, headers=headers)
    assert job.headers["etag"] == sync.headers["etag"]
    assert job.content == sync.content


def test_a_sweep_larger_than_the_synchronous_limit_runs_as_a_job():
    """200 x 101 = 20,200 cases: refused by POST /v1/srt/sweep (at most 10,000), a job of 2 parts here."""
    req = {
        "vehicle": "table16-btrain",
        "model": "rigid",
        "grid": {"bank_percent": [i / 10 for i in range(200)], "overweight_percent": [i / 4 for i in range(101)]},
    }
    with make_client() as c:
        assert c.post("/v1/srt/sweep", json=req).status_code == 422
        location, status = run(c, "srt.sweep", req)
        assert status["status"] == "done" and status["total"] == 20_200 and status["parts"]["total"] == 2
        body = orjson.loads(c.get(location + "/result").content)
    assert body["cases"] == len(body["rows"]) == 20_200
    # the product order, first axis slowest: row i has bank i // 101 / 10 and overweight i % 101
    for i in (0, 100, 101, 10_099, 20_199):
        assert body["rows"][i]["bank_percent"] == (i // 101) / 10
        assert body["rows"][i]["overweight_percent"] == (i % 101) / 4


# ------------------------------------------------------------------------------------- the summary


def test_summary_over_parts_counts_each_distinct_pair_once():
    """1,000 curves drawing from 7 superelevation/grade pairs, in 10 parts that all share them: the summary's
    distinct SRT solves is 7 (counted over the alignment, not summed over parts: 70), its counts and minimums are
    those of all the rows (checked against the rows themselves), and the whole summary equals the synchronous one."""
    curves = random_curves(1000, seed=11, pairs=7)
    pairs = {(c["superelevation_percent"], c["grade_percent"]) for c in curves}
    req = {"vehicle": "table16-btrain", "curves": curves}
    with make_client(Settings(jobs_part_size=100)) as c:
        location, status = run(c, "alignments.assess", req)
        assert status["parts"]["total"] == 10
        job = orjson.loads(c.get(location + "/result").content)
        sync = orjson.loads(c.post("/v1/alignments/assess", json=req).content)
    (vehicle,) = job["vehicles"]
    summary, rows = vehicle["summary"], vehicle["rows"]
    assert summary["distinct_srt_solves"] == len(pairs) == 7
    assert summary["curves"] == len(rows) == 1000
    assert summary["flagged"] == sum(r["flagged"] for r in rows)
    assert summary["governed_by_rollover"] == sum(r["governed_by"] == "rollover" for r in rows)
    assert summary["governed_by_side_friction"] == sum(r["governed_by"] == "side-friction" for r in rows)
    assert summary["min_margin_kmh"] == min(r["margin_kmh"] for r in rows if r["margin_kmh"] is not None)
    assert summary["min_safe_speed_kmh"] == min(r["safe_speed_kmh"] for r in rows if r["safe_speed_kmh"] is not None)
    assert vehicle["summary"] == sync["vehicles"][0]["summary"]


# ------------------------------------------------------------------------------------------- progress


def _slow_chunks(monkeypatch, seconds: float) -> None:
    """Each chunk's solve in a part takes ``seconds`` longer (the parts only gather their SRTs: they are quick)."""
    assess = op_alignments.assess_table

    def slow(*args, **kw):
        time.sleep(seconds)
        return assess(*args, **kw)

    monkeypatch.setattr(op_alignments, "assess_table", slow)


def test_progress_increases_while_a_part_is_solved(monkeypatch):
    """One part of 20,000 rows solved in chunks of 10,000 (5,000 curves of two vehicles), each slowed down: the
    status shows the progress between 0 and 1 while that part runs (no part done yet), never going down, counting
    the rows solved (a chunk's), then 1."""
    _slow_chunks(monkeypatch, 0.2)
    req = {"vehicles": ["table16-btrain", "table23-semitrailer"], "curves": random_curves(10_000, seed=3)}
    with make_client() as c:
        location = submit(c, "alignments.assess", req).headers["location"]
        seen = []
        while True:
            s = c.get(location).json()
            seen.append((s["progress"], s["parts"]["done"], s["done"]))
            if s["status"] == "done":
                break
            time.sleep(0.01)
    progress = [p for p, _, _ in seen]
    assert progress == sorted(progress) and progress[-1] == 1.0
    during = [p for p, parts_done, _ in seen if 0 < p < 1 and parts_done == 0]
    assert during, seen
    assert all(d % 10_000 == 0 for p, _, d in seen if 0 < p < 1)  # reported at chunk boundaries


def test_healthz_answers_while_a_job_runs():
    req = {"vehicles": ["table16-btrain", "table23-semitrailer"], "curves": random_curves(10_000, seed=4)}
    with make_client() as c:
        location = submit(c, "alignments.assess", req).headers["location"]
        assert c.get(location).json()["status"] in ("queued", "running")
        assert c.get("/healthz").status_code == 200
        wait_for(c, location)


# ----------------------------------------------------------------------------------------- cancelling


def test_cancel_a_queued_job_never_starts_and_a_running_one_stops(monkeypatch):
    """One worker thread: job A runs, job B waits. Cancelling B: 202 `cancelled`, none of its parts ever starts.
    Cancelling A: it stops at its next chunk, its unfinished parts never finish. Their results are 409. (Each chunk's
    solve is slowed down to 0.3 s: the parts only gather their SRTs and would finish before the test could look.)"""
    _slow_chunks(monkeypatch, 0.3)
    big = {"vehicles": ["table16-btrain", "table23-semitrailer"], "curves": random_curves(20_000, seed=6)}
    with make_client(Settings(jobs_part_size=10_000, jobs_workers=1)) as c:
        a = submit(c, "alignments.assess", big).headers["location"]
        b = submit(c, "alignments.assess", big).headers["location"]
        wait_for(c, a, statuses=("running",))
        r = c.delete(b)
        assert r.status_code == 202 and r.json()["status"] == "cancelled" and r.json()["finished_at"] is not None
        r = c.delete(a)
        assert r.status_code == 202 and r.json()["status"] == "cancelled"
        time.sleep(1.0)  # a part in flight reaches its next chunk boundary and stops
        sa, sb = c.get(a).json(), c.get(b).json()
        assert sb["status"] == "cancelled" and sb["started_at"] is None and sb["done"] == 0
        assert sa["status"] == "cancelled" and sa["parts"]["done"] < sa["parts"]["total"]
        time.sleep(1.0)
        assert c.get(a).json()["parts"]["done"] == sa["parts"]["done"]  # nothing finished after the stop
        r = c.get(b + "/result")
        assert r.status_code == 409 and r.json()["job_status"] == "cancelled"
        assert r.json()["type"] == "urn:rollover:problem:job-not-done"


def test_result_before_done_is_409_saying_the_status_and_delete_of_a_finished_job_discards_it():
    req = {"vehicles": ["table16-btrain", "table23-semitrailer"], "curves": random_curves(10_000, seed=7)}
    with make_client() as c:
        location = submit(c, "alignments.assess", req).headers["location"]
        r = c.get(location + "/result")
        assert r.status_code == 409 and r.json()["job_status"] in ("queued", "running")
        assert r.headers["content-type"] == "application/problem+json"
        wait_for(c, location)
        assert c.delete(location).status_code == 204
        assert c.get(location).status_code == 404


# ------------------------------------------------------------------------------------------------ owners


def test_jobs_are_visible_to_their_key_only(tmp_path):
    settings = Settings(api_keys=f"{KEY_A},{KEY_B}", database_url=f"sqlite:///{tmp_path}/catalog.db")
    a, b = {"Authorization": f"Bearer {KEY_A}"}, {"Authorization": f"Bearer {KEY_B}"}
    with make_client(settings) as c:
        assert submit(c, "srt.sweep", SWEEP).status_code == 401  # keys configured: a key is needed
        location, status = run(c, "srt.sweep", SWEEP, headers=a)
        assert status["status"] == "done"
        for path in (location, location + "/result"):
            assert c.get(path, headers=a).status_code == 200
            other = c.get(path, headers=b)
            assert other.status_code == 404 and other.json()["type"] == "urn:rollover:problem:job-not-found"
            assert c.get(path).status_code == 401
        assert c.delete(location, headers=b).status_code == 404
        assert c.get(location, headers=a).status_code == 200  # B's delete did nothing


def test_a_job_takes_the_callers_saved_vehicles_and_fleets(tmp_path):
    """Saved vehicles and fleets are read with the submitting key, at submission (the stored job holds records):
    the result is the synchronous answer for the same fleet and key; another key's fleet is a 404 naming it."""
    settings = Settings(api_keys=f"{KEY_A},{KEY_B}", database_url=f"sqlite:///{tmp_path}/catalog.db")
    a, b = {"Authorization": f"Bearer {KEY_A}"}, {"Authorization": f"Bearer {KEY_B}"}
    with make_client(settings) as c:
        record = {**c.get("/v1/vehicles/table16-btrain").json(), "cg_height_above_chassis_m": 1.5}
        record = {k: v for k, v in record.items() if v is not None}
        saved = c.post("/v1/vehicles", json={"title": "raised", "vehicle": record}, headers=a)
        assert saved.status_code == 201, saved.text
        vid = saved.json()["id"]
        fid = c.post("/v1/fleets", json={"title": "f", "vehicles": ["table16-btrain", vid]}, headers=a).json()["id"]
        req = {"fleet": fid, "curves": random_curves(300, seed=4)}
        location, status = run(c, "alignments.assess", req, headers=a)
        assert status["status"] == "done"
        job = c.get(location + "/result", headers=a)
        sync = c.post("/v1/alignments/assess", json=req, headers=a)
        assert job.status_code == sync.status_code == 200 and job.content == sync.content
        assert [v["saved_vehicle_id"] for v in job.json()["vehicles"]] == [None, vid]
        other = submit(c, "alignments.assess", req, headers=b)
        assert other.status_code == 404 and other.json()["id"] == fid
        sweep = run(c, "srt.sweep", {**SWEEP, "vehicle": vid}, headers=a)[1]
        assert sweep["status"] == "done"
        assert submit(c, "srt.sweep", {**SWEEP, "vehicle": vid}, headers=b).status_code == 404


def test_without_keys_a_job_needs_none_and_unknown_ids_are_404():
    with make_client() as c:
        _, status = run(c, "srt.sweep", SWEEP)
        assert status["status"] == "done"
        assert status["id"].startswith("job_") and len(status["id"]) == 4 + 22
        for path in ("/v1/jobs/job_AAAAAAAAAAAAAAAAAAAAAA", "/v1/jobs/nope/result", "/v1/jobs/job_x"):
            r = c.get(path)
            assert r.status_code == 404 and r.headers["content-type"] == "application/problem+json"


# ------------------------------------------------------------------------------------------------- expiry


def test_a_finished_job_expires_after_the_ttl():
    with make_client(Settings(jobs_result_ttl_s=1)) as c:
        location, status = run(c, "srt.sweep", SWEEP)
        assert status["status"] == "done"
        assert c.get(location + "/result").status_code == 200
        time.sleep(1.3)
        assert c.get(location).status_code == 404
        assert c.get(location + "/result").status_code == 404
        assert c.app.state.jobs.kv.used_bytes == 0 or c.app.state.jobs.kv.purge() is None
        assert c.app.state.jobs.kv.used_bytes == 0  # nothing of the job is left in memory


# ------------------------------------------------------------------------------------ refusals at submission


def _errors(r) -> list[tuple[str, str, str]]:
    return sorted((e["field"], e["message"], e["type"]) for e in r.json()["errors"])


@pytest.mark.parametrize(
    "request_body",
    [
        {"vehicle": "table16-btrain", "curves": [{"id": "A", "radius_m": 2.0}]},  # radius below 5 m
        {"vehicle": "table16-btrain", "curves": [{"id": "A", "radius_m": 200.0, "bogus": 1}]},
        {"vehicle": "table16-btrain", "curves": [{"id": "A", "radius_m": 200.0}, {"id": "A", "radius_m": 300.0}]},
        {"vehicle": "table16-btrain"},  # no curves
        {"vehicle": "table16-btrain", "csv": "id,radius_m\nA,abc\n"},  # a CSV row that cannot be read
        {"vehicle": "table16-btrain", "csv": "id,radius_m\nA,100\nB,3\n"},  # row 3 below the bounds
        {"vehicle": "table16-btrain", "csv": "id,radius_m\nA,100\nA,200\n"},  # a duplicate id in the CSV
        # a plain CSV read into columns, refused later (no e and no e_max): the error names its row
        {"vehicle": "table16-btrain", "csv": "id,radius_m,grade_percent\nA,100,2\nB,200,1\n"},
        {"vehicle": "table16-btrain", "max_superelevation_percent": 8, "csv": "id,radius_m\nA,100\nB,200\n"},
        {"vehicle": "table14-semitrailer", "curves": [{"id": "A", "radius_m": 200.0, "superelevation_percent": 2.0}]},
        {"vehicle": "table16-btrain", "curves": [{"id": "A", "radius_m": 200.0}]},  # no e and no e_max to derive it
    ],
)
def test_a_bad_alignment_request_is_refused_at_submission_as_the_synchronous_endpoint_refuses_it(request_body):
    """The same status and problem type, the same errors with their fields under `request.`: never a failed job."""
    with make_client() as c:
        sync = c.post("/v1/alignments/assess", json=request_body)
        job = submit(c, "alignments.assess", request_body)
        assert c.app.state.jobs.active_count() == 0  # no job was created
    assert sync.status_code == job.status_code == 422
    assert job.json()["type"] == sync.json()["type"]
    assert _errors(job) == sorted((f"request.{f}", m, t) for f, m, t in _errors(sync))


def test_a_bad_sweep_request_is_refused_like_the_synchronous_one():
    body = {**SWEEP, "grid": {"bank_percent": [0, 99]}}
    with make_client() as c:
        sync, job = c.post("/v1/srt/sweep", json=body), submit(c, "srt.sweep", body)
    assert sync.status_code == job.status_code == 422
    assert _errors(job) == sorted((f"request.{f}", m, t) for f, m, t in _errors(sync))


@pytest.mark.parametrize(
    ("body", "field"),
    [
        ({"operation": "alignments.explode", "request": {}}, "operation"),
        ({"request": {}}, "operation"),
        ({"operation": "srt.sweep"}, "request"),
        ({"operation": "srt.sweep", "request": [1]}, "request"),
        ({"operation": "srt.sweep", "request": SWEEP, "priority": 1}, "priority"),
    ],
)
def test_a_bad_job_is_a_422_naming_the_field(body, field):
    with make_client() as c:
        r = c.post("/v1/jobs", json=body)
    assert r.status_code == 422 and r.json()["type"] == "urn:rollover:problem:validation-error"
    assert field in {e["field"] for e in r.json()["errors"]}
    if field == "operation" and "operation" in body:
        assert "alignments.assess" in r.json()["detail"] and "srt.sweep" in r.json()["detail"]


def test_an_unknown_preset_is_the_synchronous_404():
    body = {"vehicle": "no-such-truck", "curves": [{"id": "A", "radius_m": 200.0, "superelevation_percent": 2.0}]}
    with make_client() as c:
        r = submit(c, "alignments.assess", body)
    assert r.status_code == 404 and r.json()["type"] == "urn:rollover:problem:unknown-preset"


# --------------------------------------------------------------------------- stored state that does not verify


@pytest.mark.parametrize("suffix", ["", ":part:0"])
def test_a_stored_value_that_does_not_verify_is_a_failed_job_with_the_reason(suffix):
    """Tampered store (a record or a part state not sealed by this deployment): the job reads as failed with a
    job-state-invalid problem naming the value, never a 500 and never used."""
    with make_client() as c:
        location, _ = run(c, "srt.sweep", SWEEP)
        job_id = location.rsplit("/", 1)[1]
        kv = c.app.state.jobs.kv
        key = PREFIX + job_id + suffix
        kv.set(key, b'{"status": "done"}', 60)
        r = c.get(location)
        assert r.status_code == 200
        body = r.json()
        assert body["status"] == "failed" and body["error"]["type"] == "urn:rollover:problem:job-state-invalid"
        assert key in body["error"]["detail"]
        assert c.get(location + "/result").status_code == 409


def test_a_full_embedded_store_refuses_a_job_with_503():
    """ROLLOVER_JOBS_MAX_BYTES (1 MiB) nearly used up by earlier jobs: a new job does not fit; 503 with
    Retry-After, and nothing of it is stored."""
    with make_client(Settings(jobs_max_bytes=2**20)) as c:
        kv = c.app.state.jobs.kv
        kv.set(PREFIX + "job_earlier:out", b"x" * (2**20 - 1000), 60)
        r = submit(c, "alignments.assess", {"vehicle": "table16-btrain", "curves": random_curves(500, seed=9)})
        assert r.status_code == 503 and r.headers["retry-after"] == "60"
        assert r.json()["type"] == "urn:rollover:problem:jobs-storage-full"
        assert kv.used_bytes == 2**20 - 1000 and kv.active() == []


def test_metrics_count_jobs_and_part_durations():
    with make_client() as c:
        run(c, "srt.sweep", SWEEP)
        text = c.get("/metrics").text
    assert 'rollover_jobs_total{operation="srt.sweep",status="done"}' in text
    assert 'rollover_job_part_seconds_count{operation="srt.sweep"}' in text
    active = [line for line in text.splitlines() if line.startswith("rollover_jobs_active ")]
    assert active and not math.isnan(float(active[0].split()[1]))


# ------------------------------------------------------------------------------------------------- routes


@pytest.mark.parametrize("accept", [None, "text/csv"])
def test_route_result_is_the_synchronous_answer_byte_for_byte(accept):
    """A route as a job: the geometry read at submission, the curves found by the worker, the same bytes and ETag
    as POST /v1/routes/assess (JSON and CSV), for two vehicles."""
    from app.routes.schemas import EXAMPLE_GEOJSON

    req = {
        "vehicles": ["table16-btrain", "table23-semitrailer"],
        "geojson": EXAMPLE_GEOJSON,
        "superelevation_percent": 6.0,
        "rear_llt_limit": 0.6,
    }
    headers = {"accept": accept} if accept else None
    with make_client() as c:
        location, status = run(c, "routes.assess", req)
        assert status["status"] == "done" and status["unit"] == "vertices"
        assert status["done"] == status["total"] == 14  # the example's 14 vertices
        job = c.get(location + "/result", headers=headers)
        sync = c.post("/v1/routes/assess", json=req, headers=headers)
    assert job.status_code == sync.status_code == 200
    assert job.headers["etag"] == sync.headers["etag"] and job.content == sync.content
    if accept is None:
        assert len(job.json()["curves"]) == 2
        assert all(c["radius_lower_m"] <= c["radius_m"] for c in job.json()["curves"])  # both radii in the job's
    else:
        assert {"radius_m", "radius_lower_m", "radius_std_m"} <= set(job.text.splitlines()[0].split(","))


ROUTE_FILES = [
    ("drive.gpx", {}),
    ("drive.gpx", {"parts": "all"}),
    ("osm-ways.geojson", {"use_elevation": False, "grade_percent": 2.0}),
]


@pytest.mark.parametrize(("name", "options"), ROUTE_FILES)
def test_a_route_file_as_a_job_answers_as_the_synchronous_request(name, options):
    """examples/drive.gpx (an empty track, a 4 m turn outside the model's domain, a router's <rte>) and
    examples/osm-ways.geojson (three OSM ways, maxspeed) as ``routes.assess`` jobs: the same bytes as POST
    /v1/routes/assess, the turn a row with ``error``, the reading's skipped parts there."""
    from pathlib import Path

    text = (Path(__file__).resolve().parents[2] / "examples" / name).read_text()
    doc = {"gpx": text} if name.endswith(".gpx") else {"geojson": json.loads(text)}
    req = {"vehicle": "table16-btrain", **doc, "superelevation_percent": 7.5, "posted_speed_kmh": 60, **options}
    with make_client() as c:
        location, status = run(c, "routes.assess", req)
        assert status["status"] == "done"
        job = c.get(location + "/result")
        sync = c.post("/v1/routes/assess", json=req)
    assert job.status_code == sync.status_code == 200 and job.content == sync.content
    out = job.json()
    if name == "drive.gpx":
        assert out["curves"][0]["assessment"]["error"] is not None  # the car park's turn
        assert out["reading"]["skipped"][0]["what"] == "trk[1] 'ACTIVE LOG' trkseg[1]"
    else:
        assert all(k["grade_source"] == "request" and k["assessment"]["grade_percent"] == 2.0 for k in out["curves"])


def test_a_road_without_a_curve_as_a_job_is_done_with_none():
    line = {"type": "LineString", "coordinates": [[10.0, 45.0], [10.001, 45.0], [10.002, 45.0]]}
    req = {"vehicle": "table16-btrain", "superelevation_percent": 6.0, "geojson": line}
    with make_client() as c:
        location, status = run(c, "routes.assess", req)
        assert status["status"] == "done"
        out = c.get(location + "/result").json()
        csv_text = c.get(location + "/result", headers={"accept": "text/csv"}).text
    assert out["curves"] == [] and out["vehicles"][0]["summary"]["curves"] == 0
    assert len(csv_text.strip().splitlines()) == 1


def test_a_route_past_the_synchronous_rows_is_told_to_send_a_job_and_runs_as_one(monkeypatch):
    """The synchronous route stops at MAX_ROWS rows (curves x vehicles; lowered here to 3 for the example's 2 curves
    of 2 vehicles): the 422 names the field, the rows and where larger work goes, and the same request as a
    ``routes.assess`` job (whose limit is MAX_JOB_ROWS) is done with both vehicles' rows."""
    import app.routes.service as routes
    from app.routes.schemas import EXAMPLE_GEOJSON

    monkeypatch.setattr(routes, "MAX_ROWS", 3)
    vehicles = ["table16-btrain", "table23-semitrailer"]
    req = {"vehicles": vehicles, "geojson": EXAMPLE_GEOJSON, "superelevation_percent": 6.0}
    with make_client() as c:
        r = c.post("/v1/routes/assess", json=req)
        assert r.status_code == 422, r.text
        (error,) = r.json()["errors"]
        assert error["field"] == "vehicles", error
        assert "2 curves x 2 vehicles = 4 rows; at most 3 rows" in error["message"]
        assert 'POST /v1/jobs with {"operation": "routes.assess"' in error["message"]
        assert f"{routes.MAX_JOB_ROWS:,} rows" in error["message"]
        location, status = run(c, "routes.assess", req)
        assert status["status"] == "done"
        curves = c.get(location + "/result").json()["curves"]
        assert len(curves) == 2 and all(len(k["vehicles"]) == 2 for k in curves)


def test_a_route_past_the_synchronous_vertices_is_told_to_send_a_job_and_runs_as_one(monkeypatch):
    """The synchronous route reads at most MAX_SYNC_VERTICES vertices (lowered here to 10 for the example's 14):
    the 422 names the document, the limit and where larger work goes; the same request as a job (which reads up to
    MAX_VERTICES) is done with the example's two curves."""
    import app.routes.service as routes
    from app.formats.route_io import MAX_VERTICES
    from app.routes.schemas import EXAMPLE_GEOJSON

    monkeypatch.setattr(routes, "MAX_SYNC_VERTICES", 10)
    req = {"vehicle": "table16-btrain", "geojson": EXAMPLE_GEOJSON, "superelevation_percent": 6.0}
    with make_client() as c:
        r = c.post("/v1/routes/assess", json=req)
        assert r.status_code == 422, r.text
        (error,) = r.json()["errors"]
        assert error["field"].startswith("geojson"), error
        assert "more than 10 vertices" in error["message"]
        assert 'POST /v1/jobs with {"operation": "routes.assess"' in error["message"]
        assert f"{MAX_VERTICES:,} vertices" in error["message"]
        location, status = run(c, "routes.assess", req)
        assert status["status"] == "done" and status["total"] == 14
        assert len(c.get(location + "/result").json()["curves"]) == 2


def test_a_route_that_cannot_be_read_is_refused_at_submission():
    bad = {"type": "LineString", "coordinates": [[10.0, 45.0], [10.001, 45.0], [45.0, 100.0]]}  # latitude 100
    with make_client() as c:
        r = submit(c, "routes.assess", {"vehicle": "table16-btrain", "geojson": bad, "superelevation_percent": 6})
    assert r.status_code == 422, r.text
    assert r.json()["errors"][0]["field"] == "request.geojson.coordinates.2" and "latitude" in r.json()["detail"]


def test_a_route_whose_curves_have_no_superelevation_is_refused_at_submission_as_synchronously():
    """No superelevation anywhere (request, feature properties): the synchronous request refuses the first found
    curve; the job is refused at submission with the same message, not failed later by its worker. A route whose
    features carry their own superelevation is taken."""
    from app.routes.schemas import EXAMPLE_GEOJSON

    bare = {"vehicle": "table16-btrain", "geojson": EXAMPLE_GEOJSON}
    with make_client() as c:
        sync = c.post("/v1/routes/assess", json=bare)
        job = submit(c, "routes.assess", bare)
        assert sync.status_code == job.status_code == 422, (sync.text, job.text)
        (s,), (j,) = sync.json()["errors"], job.json()["errors"]
        assert s["field"] == "superelevation_percent" and j["field"] == "request.superelevation_percent"
        assert j["message"] == s["message"] and "has no superelevation" in s["message"]
        own = orjson.loads(orjson.dumps(EXAMPLE_GEOJSON))
        for feature in own["features"]:
            feature["properties"]["superelevation_percent"] = 6.0
        assert submit(c, "routes.assess", {**bare, "geojson": own}).status_code == 202


# ------------------------------------------------------------------------- results rendered from columns

KINDS = [
    {"radius_m": 120.0, "superelevation_percent": 8.0, "grade_percent": -4.0, "posted_speed_kmh": 70.0},
    {"radius_m": 350.0, "posted_speed_kmh": 90.0},  # superelevation derived from the distribution (e_max given)
    {"radius_m": 600.0, "superelevation_percent": 8.0, "grade_percent": -4.0},  # no posted speed
    # adverse crossfall past the rear LLT limit at rest: refused (no SRT, an error)
    {"radius_m": 200.0, "superelevation_percent": -20.0, "posted_speed_kmh": 50.0},
    {"radius_m": 25.0, "superelevation_percent": 2.0, "grade_percent": 3.0, "posted_speed_kmh": 80.0},  # < R_min
]


@pytest.mark.parametrize("accept", [None, "text/csv"])
def test_rows_of_every_kind_rendered_from_columns_are_the_synchronous_answer(accept, monkeypatch):
    """Rows of every kind (given and derived superelevation, with and without a posted speed, refused with an error,
    below the standard's minimum radius; ids with a quote, a comma and a formula prefix), three targets, two
    vehicles, in parts of 120 rows solved in chunks of 30 rows (so a part joins chunks with and without refused
    rows): the job's JSON and CSV, rendered on GET from the parts' columns, are the synchronous answer's bytes."""
    monkeypatch.setattr(op_alignments, "CHUNK_ROWS", 30)
    rng = np.random.default_rng(8)
    ids = ['C,"q"', "=HYPERLINK(1)", "-4", "plain"]
    curves = [{"id": f"{ids[i % 4]}{i}", **KINDS[k]} for i, k in enumerate(rng.integers(0, 5, 900))]
    curves[100:160] = [{"id": f"r{i}", **KINDS[3]} for i in range(60)]  # a run of refused rows: whole chunks
    req = {
        "vehicles": ["table16-btrain", "table23-semitrailer"],
        "rear_llt_limit": 0.2,
        "max_superelevation_percent": 8.0,
        "targets": {"a": 0.3, "b": 0.45, "c": 0.3},
        "curves": curves,
    }
    status, job, sync = job_and_sync(req, accept, 120, 15)
    assert status["done"] == status["total"] == 1800
    assert job.headers["etag"] == sync.headers["etag"]
    assert job.content == sync.content
    if accept is None:
        rows = orjson.loads(job.content)["vehicles"][0]["rows"]
        assert any(r["error"] for r in rows) and any(r["superelevation_source"] == "derived" for r in rows)
        assert any(r["meets_standard_min_radius"] is False for r in rows)


def _corrupt(c, location: str, body: bytes, part: int = 0, *, sealed: bool = True) -> None:
    """Replace a part's stored columns of vehicle 0 by ``body``, sealed as this deployment seals (so only the
    columns' own checks can refuse it), or with a seal whose MAC is wrong (``sealed=False``)."""
    store = c.app.state.jobs.store
    view = store.view(location.rsplit("/", 1)[1])
    key = store.fragment_keys(view, "columns")[part][0]
    value = store._seal(key, RAW_FRAGMENT_TYPE, body)
    if not sealed:
        value = value[:9] + bytes(32) + value[41:]  # ROLLOVER1, then a MAC of zeros
    store.kv.set(key, value, 60)


def _good(c, location: str, part: int) -> bytes:
    store = c.app.state.jobs.store
    view = store.view(location.rsplit("/", 1)[1])
    return b"".join(store.read_fragment(view.id, store.fragment_keys(view, "columns")[part][0], compressed=False))


@pytest.mark.parametrize(
    "damage",
    [
        lambda b: b[: len(b) // 2],  # truncated
        lambda b: b"XCOLS" + b[5:],  # another magic
        lambda b: b[:5] + b"\x09\x00" + b[7:],  # another version
        lambda b: b + b"\x00" * 8,  # trailing bytes
        lambda b: b"",
    ],
    ids=["truncated", "magic", "version", "trailing", "empty"],
)
def test_a_part_whose_columns_do_not_read_is_a_failed_job_never_a_500(damage):
    """The first part's stored columns sealed but not reading back (truncated, another layout or version): the
    result is 409 (the job failed with job-state-invalid naming the reason), before any byte of the answer."""
    req = {"vehicle": "table16-btrain", "curves": random_curves(300, seed=12)}
    with make_client(Settings(jobs_part_size=100)) as c:
        location, status = run(c, "alignments.assess", req)
        assert status["status"] == "done"
        _corrupt(c, location, damage(_good(c, location, 0)))
        for accept in ("application/json", "text/csv"):
            r = c.get(location + "/result", headers={"accept": accept})
            assert r.status_code == 409 and r.json()["job_status"] == "failed"
        body = c.get(location).json()
        assert body["status"] == "failed" and body["error"]["type"] == "urn:rollover:problem:job-state-invalid"
        assert "ColumnsError" in body["error"]["detail"]


@pytest.mark.parametrize(
    "damage",
    [
        lambda b: b"XCOLS" + b[5:],  # another magic
        lambda b: b[:5] + b"\x09\x00" + b[7:],  # another version
        lambda b: b[:11] + b[11:].replace(b'"radius_m"', b'"radius_x"', 1),  # another layout
        lambda b: b[:8],  # no whole header
        lambda b: b"",
    ],
    ids=["magic", "version", "layout", "no-header", "empty"],
)
def test_a_later_part_of_another_layout_is_refused_before_the_answer(damage):
    """Parts after the first are looked at by their first bytes before the answer starts (not read whole: that
    read them all twice): one of another magic, version or layout, or without a whole header, makes the result 409
    and the job failed, before any byte of the answer."""
    req = {"vehicle": "table16-btrain", "curves": random_curves(300, seed=12)}
    with make_client(Settings(jobs_part_size=100)) as c:
        location, status = run(c, "alignments.assess", req)
        assert status["status"] == "done" and status["parts"]["total"] == 3
        _corrupt(c, location, damage(_good(c, location, 2)), part=2)
        r = c.get(location + "/result", headers={"accept": "text/csv"})
        assert r.status_code == 409 and r.json()["job_status"] == "failed"
        body = c.get(location).json()
        assert body["status"] == "failed" and body["error"]["type"] == "urn:rollover:problem:job-state-invalid"
        assert "ColumnsError" in body["error"]["detail"]


@pytest.mark.parametrize(
    ("damage", "sealed", "reason"),
    [
        (lambda b: b[: len(b) // 2], True, "ColumnsError"),  # truncated
        (lambda b: b + b"\x00" * 8, True, "ColumnsError"),  # trailing bytes
        (lambda b: b, False, "not sealed by this deployment"),  # the MAC does not verify
    ],
    ids=["truncated", "trailing", "mac"],
)
def test_a_later_part_that_fails_as_it_is_streamed_ends_the_answer_and_fails_the_job(damage, sealed, reason):
    """A later part whose layout looks right but whose body does not verify (altered since it was written) is found
    when the stream reaches it, and is never used: the answer stops before its rows (never complete, so a client
    cannot take it for the whole), the job is failed with the reason, and the result is 409 from then on."""
    req = {"vehicle": "table16-btrain", "curves": random_curves(300, seed=12)}
    with make_client(Settings(jobs_part_size=100)) as c:
        location, status = run(c, "alignments.assess", req)
        assert status["parts"]["total"] == 3
        whole = c.get(location + "/result", headers={"accept": "text/csv"}).content
        _corrupt(c, location, damage(_good(c, location, 2)), part=2, sealed=sealed)
        r = c.get(location + "/result", headers={"accept": "text/csv"})
        assert r.status_code == 200  # the answer had started
        lines = r.content.count(b"\r\n")
        assert len(r.content) < len(whole) and lines <= 1 + 200  # the header and at most the first two parts
        assert whole.startswith(r.content)
        body = c.get(location).json()
        assert body["status"] == "failed" and body["error"]["type"] == "urn:rollover:problem:job-state-invalid"
        assert reason in body["error"]["detail"]
        assert c.get(location + "/result").status_code == 409


@pytest.mark.parametrize(("part", "streamed"), [(0, False), (2, True)], ids=["checked-first", "streamed"])
def test_a_tampered_part_is_logged_as_a_handled_integrity_failure_with_the_job_and_part(part, streamed):
    """A part whose MAC does not verify (altered in the store; issue 40 item 6): refused, and logged once as
    ``job_part_integrity_failure`` naming the job, the part and its key, at warning, without a traceback; never as
    ``unhandled_exception`` (before: the streamed case propagated out of the response, logged with a traceback).
    The first part is checked whole before the answer (409); a later one is found as it is streamed."""
    req = {"vehicle": "table16-btrain", "curves": random_curves(300, seed=12)}
    with make_client(Settings(jobs_part_size=100)) as c:
        location, status = run(c, "alignments.assess", req)
        assert status["parts"]["total"] == 3
        job_id = location.rsplit("/", 1)[1]
        _corrupt(c, location, _good(c, location, part), part=part, sealed=False)
        with capture_logs() as logs:
            r = c.get(location + "/result", headers={"accept": "text/csv"})
        assert r.status_code == (200 if streamed else 409)
    events = [e["event"] for e in logs]
    assert "unhandled_exception" not in events, events
    failures = [e for e in logs if e["event"] == "job_part_integrity_failure"]
    assert len(failures) == 1, logs
    f = failures[0]
    assert f["log_level"] == "warning" and f["job"] == job_id and f["part"] == part
    assert f["key"].startswith(f"{PREFIX}{job_id}:out:{part}:") and "not sealed by this deployment" in f["reason"]
    assert not any("exc_info" in e or "exception" in e for e in logs)


def test_a_part_with_codes_outside_their_tables_is_refused():
    """Columns that read but hold a code that would index outside its table (governed_by 7): refused the same way."""
    req = {"vehicle": "table16-btrain", "curves": random_curves(50, seed=13)}
    with make_client() as c:
        location, _ = run(c, "alignments.assess", req)
        store = c.app.state.jobs.store
        view = store.view(location.rsplit("/", 1)[1])
        key = store.fragment_keys(view, "columns")[0][0]
        good = b"".join(store.read_fragment(view.id, key, compressed=False))
        cols, meta = unpack_columns(good, RESULT_SCHEMA)
        cols = {k: v.copy() for k, v in cols.items()}
        cols["governed_by"][3] = 7
        bad = pack_columns(cols, RESULT_SCHEMA, meta)
        with pytest.raises(ColumnsError):
            unpack_result(bad)
        _corrupt(c, location, bad)
        r = c.get(location + "/result")
        assert r.status_code == 409 and r.json()["job_status"] == "failed"


def test_the_distinct_pairs_are_solved_once_per_job_and_the_parts_only_gather(monkeypatch):
    """1,000 curves on 7 superelevation/grade pairs, two vehicles, 10 parts: the batch solver runs once per vehicle
    (at submission, on the 7 pairs), never in a part; the answer is still the synchronous one."""
    calls = []
    solve = op_alignments.solve_bank_grade_pairs

    def counting(case, pairs, **kw):
        calls.append(len(pairs))
        return solve(case, pairs, **kw)

    monkeypatch.setattr(op_alignments, "solve_bank_grade_pairs", counting)
    req = {"vehicles": ["table16-btrain", "table23-semitrailer"], "curves": random_curves(1000, seed=14, pairs=7)}
    with make_client(Settings(jobs_part_size=200)) as c:
        location, status = run(c, "alignments.assess", req)
        assert status["status"] == "done" and status["parts"]["total"] == 10
        assert calls == [7, 7]
        assert c.get(location + "/result").content == c.post("/v1/alignments/assess", json=req).content


@pytest.mark.parametrize("accept", [None, "text/csv"])
def test_a_landxml_job_keeps_the_stations_in_its_columns(accept):
    """Curves from a LandXML document carry their stations (staStart): 400 curves in parts of 100, the job's JSON and
    CSV (the stations read back from the parts' columns) are the synchronous answer's bytes."""
    curves = random_curves(400, seed=15)
    items = "".join(
        f'<Curve rot="cw" radius="{c["radius_m"]}" length="50" staStart="{100.5 * k}" name="{c["id"]}"/>'
        for k, c in enumerate(curves)
    )
    document = (
        '<?xml version="1.0"?><LandXML xmlns="http://www.landxml.org/schema/LandXML-1.2" version="1.2">'
        f'<Alignments><Alignment name="A1"><CoordGeom>{items}</CoordGeom></Alignment></Alignments></LandXML>'
    )
    req = {"vehicle": "table16-btrain", "landxml": {"document": document, "superelevation_percent": 4.0}}
    _, job, sync = job_and_sync(req, accept, 100, 4)
    assert job.content == sync.content
    if accept is None:
        assert orjson.loads(job.content)["vehicles"][0]["rows"][399]["station_m"] == 100.5 * 399


# ------------------------------------------------------------------- synchronous limits point to jobs


def test_a_request_past_a_synchronous_limit_is_told_to_send_a_job_and_that_job_is_taken():
    """Past the synchronous limits (10,000 curves, 10,000 rows, 10,000 sweep cases) the 422 says where larger work
    goes (POST /v1/jobs, the operation, the job's limit), and the same request sent that way is taken (202)."""
    with make_client() as c:
        rows = {"vehicles": ["table16-btrain", "table23-semitrailer"], "curves": random_curves(5_001, seed=5)}
        text = "id,radius_m,superelevation_percent\n" + "".join(f"C{i},300,4\n" for i in range(10_001))
        grid = {"bank_percent": [k / 10 for k in range(101)], "slope_percent": [k / 10 for k in range(100)]}
        cases = [
            ("/v1/alignments/assess", rows, "alignments.assess", "10002 rows; at most 10000 per request"),
            ("/v1/alignments/assess", {"vehicle": "table16-btrain", "csv": text}, "alignments.assess", "more than"),
            ("/v1/srt/sweep", {"vehicle": "table16-btrain", "grid": grid}, "srt.sweep", "10100 cases"),
        ]
        for path, body, operation, why in cases:
            r = c.post(path, json=body)
            assert r.status_code == 422, r.text
            detail = r.json()["detail"]
            assert why in detail and "POST /v1/jobs" in detail and f'"operation": "{operation}"' in detail, detail
            assert "1,000,000" in detail
            assert submit(c, operation, body).status_code == 202
        many = [{"id": f"K{i}", "radius_m": 300.0, "superelevation_percent": 4.0} for i in range(10_001)]
        r = c.post("/v1/alignments/assess", json={"vehicle": "table16-btrain", "curves": many})
        assert r.status_code == 422 and "POST /v1/jobs" in r.json()["errors"][0]["message"]


def test_a_tampered_part_input_is_refused_by_the_worker_and_logged_with_the_job_and_part():
    """A part's stored input whose MAC does not verify when a worker claims it (issue 40 item 6): the part never
    runs, the job fails with job-state-invalid naming the part, and ``job_entry_rejected`` is logged at warning
    with the job and the part, without a traceback."""
    from app.jobs.kv import MemoryKV
    from app.jobs.runner import run_part
    from app.jobs.store import JobStore

    store = JobStore(MemoryKV(2**20), b"s" * 32, lease_s=60.0, max_attempts=3)
    record = store.create(operation="srt.sweep", owner=None, unit="cases", shared={}, parts=[(1, b"in0"), (1, b"in1")],
                          formats=["json"], etag={"json": "x"}, ttl_s=60)  # fmt: skip
    key = store.key(record.id, ":in:1")
    sealed = store.kv.get(key)
    store.kv.set(key, sealed[:9] + bytes(32) + sealed[41:], 60)  # ROLLOVER1, then a MAC of zeros
    with capture_logs() as logs:
        run_part(store, record.id, 1, 1, timeout_s=10.0)
    rejected = [e for e in logs if e["event"] == "job_entry_rejected"]
    assert len(rejected) == 1 and rejected[0]["job"] == record.id and rejected[0]["part"] == 1, logs
    assert rejected[0]["log_level"] == "warning" and "not sealed by this deployment" in rejected[0]["reason"]
    assert not any("exc_info" in e or e["event"] in ("job_part_error", "unhandled_exception") for e in logs)
    view = store.view(record.id)
    assert view.status == "failed" and view.stop.error["type"] == "urn:rollover:problem:job-state-invalid"
    assert view.stop.error["detail"].startswith("part 1: ")

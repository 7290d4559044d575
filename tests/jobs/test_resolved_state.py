"""A job's stored resolved request (app/compute/resolved.py) that does not read back as its type: the result is
refused (job-state-invalid naming the field) and a part does not run on it."""

from __future__ import annotations

import orjson
import pytest

from app.jobs import op_routes, op_sweep
from app.jobs.store import RECORD_TYPE
from app.settings import Settings

from .conftest import make_client, random_curves, wait_for


def _run(client, operation: str, request: dict) -> str:
    r = client.post("/v1/jobs", json={"operation": operation, "request": request})
    assert r.status_code == 202, r.text
    location = r.headers["location"]
    assert wait_for(client, location)["status"] == "done"
    return location


def test_an_alignment_job_whose_stored_request_has_another_shape_is_a_failed_job():
    """The record rewritten, sealed as this deployment seals it (so only the request's own check can refuse it),
    with the resolved request's presets as a string: 409 for the result, a job-state-invalid job naming it."""
    req = {"vehicles": ["table16-btrain", "table23-semitrailer"], "curves": random_curves(40, seed=3)}
    with make_client(Settings(jobs_part_size=40)) as c:
        location = _run(c, "alignments.assess", req)
        store = c.app.state.jobs.store
        view = store.view(location.rsplit("/", 1)[1])
        shared = {**view.record.shared, "resolved": {**view.record.shared["resolved"], "presets": "table16-btrain"}}
        record = view.record.model_copy(update={"shared": shared})
        key = store.key(view.id)
        store.kv.set(key, store._seal(key, RECORD_TYPE, record.model_dump_json().encode()), 60)
        for accept in ("application/json", "text/csv"):
            r = c.get(location + "/result", headers={"accept": accept})
            assert r.status_code == 409 and r.json()["job_status"] == "failed"
        body = c.get(location).json()
        assert body["status"] == "failed" and body["error"]["type"] == "urn:rollover:problem:job-state-invalid"
        assert "not a ResolvedAlignment" in body["error"]["detail"] and "presets" in body["error"]["detail"]


class _Context:
    def write(self, fmt: str, section: int, data: bytes) -> None:
        raise AssertionError("nothing is computed from a request that does not read")

    def progress(self, done_units: int) -> None:
        raise AssertionError("nothing is computed from a request that does not read")


def test_a_part_does_not_run_on_a_stored_request_of_another_shape():
    case = {"model": "3d"}
    with pytest.raises(ValueError, match="not a ResolvedSweep: case"):
        op_sweep.run_part(
            {"resolved": {"case": case, "grid": [0.0]}, "fixed_axes": 0},
            orjson.dumps({"first_block": 0, "blocks": 1}),
            _Context(),
        )
    with pytest.raises(ValueError, match="not a ResolvedRoute"):
        op_routes.run_part({"request": {}, "resolved": {"route": {}}, "vertices": 3}, b"{}", _Context())

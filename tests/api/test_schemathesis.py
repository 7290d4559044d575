"""Property-based fuzzing of the whole spec, in process against the ASGI app (schemathesis).

Checks on every generated request, positive and negative: no 5xx, the status code, content type, headers and body
conform to the spec, invalid input is rejected with a 4xx, and no schema-valid request is refused for its shape
(the checks and their configuration are in ``fuzzing.py``, shared with the catalog's suite).

The inverse limits (about ten SRT solves per limit, up to 25 table rows) and the batch operations (up to
10,000 cases) cost far more per call than the rest: they get fewer examples each.
"""

from __future__ import annotations

import pytest
import schemathesis
from fastapi.testclient import TestClient
from hypothesis import settings

from app.main import create_app
from app.settings import Settings

from .fuzzing import CHECKS, FUZZ, config

# schemathesis over the whole spec: minutes, not seconds (the full suite runs it)
pytestmark = pytest.mark.slow
# an IFC file (ISO 10303-21) is text: schemathesis has no serializer of its own for the media type
schemathesis.serializer.alias("application/x-step", "text/plain")

app = create_app(Settings(cache_backend="memory"))
_lifespan = TestClient(app).__enter__()  # the app's lifespan (its cache) runs for the whole module
schema = schemathesis.openapi.from_asgi("/openapi.json", app, config=config())

LIMITS = ["/v1/srt/limits", "/v1/vehicles/payload-table"]
BATCHES = [
    "/v1/srt/sweep",
    "/v1/alignments/assess",
    "/v1/alignments/assess/csv",
    "/v1/alignments/assess/landxml",
    "/v1/alignments/assess/ifc",
    "/v1/routes/assess",
    "/v1/routes/assess/gpx",
    "/v1/routes/assess/geojson",
]
JOBS = ["/v1/jobs", "/v1/jobs/{job_id}", "/v1/jobs/{job_id}/result"]


# The catalog (tag `catalog`) is fuzzed by test_catalog_schemathesis.py on an app with keys and a temporary database.
# Here no key is configured, so every catalog operation rightly answers 403 (disabled), which schemathesis's
# missing-Authorization check would take for a failure (it expects 401).
@schema.exclude(path=LIMITS + BATCHES + JOBS).exclude(tag="catalog").parametrize()
@settings(max_examples=25, **FUZZ)
def test_no_server_errors_and_responses_conform(case):
    case.call_and_validate(**CHECKS)


@schema.include(path=BATCHES).parametrize()
@settings(max_examples=10, **FUZZ)
def test_batches_no_server_errors_and_responses_conform(case):
    case.call_and_validate(**CHECKS)


@schema.include(path=LIMITS).parametrize()
@settings(max_examples=5, **FUZZ)
def test_limits_no_server_errors_and_responses_conform(case):
    case.call_and_validate(**CHECKS)


# Jobs: a submitted job runs in the app's worker thread (the in-process backend); a generated id is unknown (404)
@schema.include(path=JOBS).parametrize()
@settings(max_examples=5, **FUZZ)
def test_jobs_no_server_errors_and_responses_conform(case):
    case.call_and_validate(**CHECKS)
    jobs = app.state.jobs  # a generated job may be a million cases: cancel it, the next example need not wait
    for job_id in jobs.kv.active():
        jobs.store.cancel(jobs.store.view(job_id))

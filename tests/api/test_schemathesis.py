"""Property-based fuzzing of the whole spec, in process against the ASGI app (schemathesis).

Checks on every generated request, positive and negative: no 5xx, the status code, content type, headers and body
conform to the spec, invalid input is rejected with a 4xx, and **no schema-valid request is refused for its
shape** (:func:`schema_valid_requests_are_not_refused_for_their_shape`): every rule about the request's shape is
in the spec, so a generated client knows it. A schema-valid request may still be physically impossible (a track
that differs from the axle width, a CG above Rill's bound, a preset id that does not exist): the engine answers it
with its own problem types (404 unknown-preset, 422 invalid-vehicle / invalid-load / ...), which that check
allows; schemathesis' own ``positive_data_acceptance`` would count those too, so it is replaced by this one.

The inverse limits (about ten SRT solves per limit, up to 25 table rows) and the batch operations (up to
20,000 cases) cost far more per call than the rest: they get fewer examples each.
"""

from __future__ import annotations

import schemathesis
from fastapi.testclient import TestClient
from hypothesis import HealthCheck, settings
from schemathesis.checks import positive_data_acceptance

from app.main import create_app
from app.settings import Settings

SHAPE_PROBLEMS = ("urn:rollover:problem:validation-error", "urn:rollover:problem:malformed-request")
#: the shape rules JSON Schema cannot state (a comparison between two fields, a count after reading a document):
#: (path, field) -> the words of the operation's description that state the rule
UNSTATABLE = {
    ("/v1/plots/min-radius", "speed_max_kmh"): "`speed_max_kmh` must be above `speed_min_kmh`",
    ("/v1/alignments/assess", "vehicles"): "100,000 rows (curves x vehicles)",
    ("/v1/jobs", "request.vehicles"): "1,000,000 rows (curves x vehicles)",
    ("/v1/jobs", "request.grid"): "1,000,000 cases (the product of the axes' lengths)",
}


@schemathesis.check
def schema_valid_requests_are_not_refused_for_their_shape(ctx, response, case):
    """A request generated as valid against the spec must not get a validation-error (or malformed-request)
    problem: that would be a rule the server applies and the spec does not state."""
    meta = case.meta
    if meta is None or not meta.generation.mode.is_positive or response.status_code not in (400, 422):
        return None
    problem = response.json() if "json" in response.headers.get("content-type", [""])[0] else {}
    if problem.get("type") not in SHAPE_PROBLEMS:
        return None
    fields = {e["field"] for e in problem.get("errors") or []}
    stated = [UNSTATABLE.get((case.path, f)) for f in fields]
    if fields and all(stated):
        text = case.operation.definition.raw.get("description", "")
        assert all(words in text for words in stated), (case.path, stated)
        return None
    raise AssertionError(f"a schema-valid request was refused for its shape: {problem}")


CHECKS = {
    "excluded_checks": [positive_data_acceptance],
    "additional_checks": [schema_valid_requests_are_not_refused_for_their_shape],
}

app = create_app(Settings(cache_backend="memory"))
_lifespan = TestClient(app).__enter__()  # the app's lifespan (its cache) runs for the whole module
schema = schemathesis.openapi.from_asgi("/openapi.json", app)

LIMITS = ["/v1/srt/limits"]
BATCHES = ["/v1/srt/sweep", "/v1/alignments/assess", "/v1/alignments/assess/csv", "/v1/alignments/assess/landxml"]
JOBS = ["/v1/jobs", "/v1/jobs/{job_id}", "/v1/jobs/{job_id}/result"]
FUZZ = {"deadline": None, "suppress_health_check": list(HealthCheck), "derandomize": True}


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

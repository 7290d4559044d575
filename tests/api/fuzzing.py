"""What the schemathesis suites share: the hypothesis settings, the checks and their configuration.

**No schema-valid request is refused for its shape** (:func:`schema_valid_requests_are_not_refused_for_their_shape`):
every rule about the request's shape is in the spec, so a generated client knows it. A schema-valid request may
still be physically impossible (a track that differs from the axle width, a CG above Rill's bound, a preset id that
does not exist): the engine answers it with its own problem types (404 unknown-preset, 422 invalid-vehicle /
invalid-load / ...), which that check allows; schemathesis' own ``positive_data_acceptance`` would count those too,
so it is replaced by this one.

**428 refuses a missing ``If-Match``.** The spec requires the header on both PUTs; the server answers its absence
with 428 (RFC 6585), which schemathesis' ``missing_required_header`` is told to take.

**413 is a rejection.** A negative case (schema-violating) may be refused before it is read because its body is
over the operation's declared limit (413 problem ``body-too-large``): schemathesis' ``negative_data_rejection``
lists the 4xx it takes for a rejection and 413 is not among them by default, so it is added here.
"""

from __future__ import annotations

from typing import Any

from hypothesis import HealthCheck
from schemathesis.checks import positive_data_acceptance
from schemathesis.config import SchemathesisConfig
from schemathesis.config._checks import MissingRequiredHeaderConfig, NegativeDataRejectionConfig

SHAPE_PROBLEMS = ("urn:rollover:problem:validation-error", "urn:rollover:problem:malformed-request")
_TABLE21 = "`side_friction_bound` only with `design_standard` `thesis-table21`"
_CURSOR = "pass `next_cursor` of the previous page as it is"
#: the shape rules JSON Schema cannot state (a comparison between two fields, a count after reading a document, an
#: opaque token): (path, field) -> the words of the operation's description that state the rule
UNSTATABLE = {
    ("/v1/plots/min-radius", "speed_max_kmh"): "`speed_max_kmh` must be above `speed_min_kmh`",
    ("/v1/alignments/assess", "vehicles"): "10,000 rows (curves x vehicles)",
    # a product of the axes' lengths
    ("/v1/srt/sweep", "grid"): "at most 10,000 cases",
    ("/v1/jobs", "request.vehicles"): "1,000,000 rows (curves x vehicles)",
    ("/v1/jobs", "request.grid"): "1,000,000 cases (the product of the axes' lengths)",
    # query parameters cannot state a rule between two of them
    ("/v1/alignments/assess/csv", "side_friction_bound"): _TABLE21,
    ("/v1/alignments/assess/landxml", "side_friction_bound"): _TABLE21,
    ("/v1/alignments/assess/ifc", "side_friction_bound"): _TABLE21,
    ("/v1/routes/assess/gpx", "side_friction_bound"): _TABLE21,
    ("/v1/routes/assess/geojson", "side_friction_bound"): _TABLE21,
    # a cursor is what the previous page said, nothing a pattern can describe
    ("/v1/vehicles/saved", "cursor"): _CURSOR,
    ("/v1/fleets", "cursor"): _CURSOR,
}

FUZZ = {"deadline": None, "suppress_health_check": list(HealthCheck), "derandomize": True}


def config() -> SchemathesisConfig:
    """Schemathesis' configuration with 413 among the statuses that reject negative data, and 428 among those that
    refuse a request without a required header (the spec requires ``If-Match`` on both PUTs; RFC 6585 section 3:
    428 Precondition Required is the answer to a change that names no version)."""
    statuses = [*NegativeDataRejectionConfig._DEFAULT_EXPECTED_STATUSES, "413"]
    missing = [*MissingRequiredHeaderConfig._DEFAULT_EXPECTED_STATUSES, "428"]
    return SchemathesisConfig.from_dict(
        {
            "checks": {
                "negative_data_rejection": {"expected-statuses": statuses},
                "missing_required_header": {"expected-statuses": missing},
            }
        }
    )


def schema_valid_requests_are_not_refused_for_their_shape(ctx: Any, response: Any, case: Any) -> None:
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
        text = " ".join(case.operation.definition.raw.get("description", "").split())
        assert all(words in text for words in stated), (case.path, stated)
        return None
    raise AssertionError(f"a schema-valid request was refused for its shape: {problem}")


CHECKS = {
    "excluded_checks": [positive_data_acceptance],
    "additional_checks": [schema_valid_requests_are_not_refused_for_their_shape],
}

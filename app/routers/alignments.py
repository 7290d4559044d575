"""POST /v1/alignments/assess (JSON) and its raw-file forms /assess/csv and /assess/landxml."""

from __future__ import annotations

from typing import Annotated

from fastapi import APIRouter, Query, Request, Response

from ..bodylimit import body_limit
from ..deps import CacheDep, SettingsDep
from ..schemas.alignments import (
    ALIGNMENT_CSV_EXAMPLE,
    ALIGNMENT_JSON_LIMIT,
    ALIGNMENT_LANDXML_EXAMPLE,
    CSV_UPLOAD_LIMIT,
    LANDXML_UPLOAD_LIMIT,
    AlignmentRequest,
    AlignmentResult,
)
from ..service_alignments import compute_alignment
from ..tables import wants_csv
from ..uploads import CsvUploadQuery, LandXmlUploadQuery, csv_upload, landxml_upload, upload_body
from .common import computed_response, table_responses

router = APIRouter(prefix="/v1/alignments", tags=["alignments"])

ASSESSMENT = """For each horizontal curve and each vehicle: the SRT on the curve's bank and grade, the rollover
speed sqrt(127 SRT R) (Eq. 9.1), the side-friction speed sqrt(127 R (0.01 e + f)) with f from Table 21, the safe
speed (the smaller) and which mechanism governs, and the margin against the posted speed, flagged when negative.
Curves sharing superelevation and grade share one SRT solve. JSON, or CSV with `Accept: text/csv` (one row per
vehicle and curve)."""


@router.post(
    "/assess",
    name="assess",
    response_model=AlignmentResult,
    responses=table_responses(400, 404, 422, 500),
    openapi_extra=body_limit(ALIGNMENT_JSON_LIMIT),
    description=ASSESSMENT
    + """

The curves are a JSON list (`curves`), CSV text (`csv`) or a LandXML 1.2 document (`landxml`); the same files can
also be sent as they are to `/v1/alignments/assess/csv` and `/v1/alignments/assess/landxml`.""",
)
async def assess(body: AlignmentRequest, request: Request, cache: CacheDep, settings: SettingsDep) -> Response:
    csv = wants_csv(request.headers.get("accept"))
    return computed_response(await compute_alignment(cache, body, settings, csv=csv), vary_accept=True)


@router.post(
    "/assess/csv",
    name="assess_csv",
    response_model=AlignmentResult,
    responses=table_responses(400, 404, 422, 500),
    openapi_extra=upload_body("text/csv", CSV_UPLOAD_LIMIT, ALIGNMENT_CSV_EXAMPLE),
    description=ASSESSMENT
    + """

The body is the CSV file itself (UTF-8, a header row naming `id`, `radius_m`, `superelevation_percent` and
optionally `grade_percent`, `posted_speed_kmh`), the options are query parameters (`vehicle` repeated for several
presets). The same request as `POST /v1/alignments/assess` with `csv`: same answer, same cache entry.""",
)
async def assess_csv(
    request: Request, query: Annotated[CsvUploadQuery, Query()], cache: CacheDep, settings: SettingsDep
) -> Response:
    body = await csv_upload(request, query)
    csv = wants_csv(request.headers.get("accept"))
    result = await compute_alignment(cache, body, settings, csv=csv, source_field="body")
    return computed_response(result, vary_accept=True)


@router.post(
    "/assess/landxml",
    name="assess_landxml",
    response_model=AlignmentResult,
    responses=table_responses(400, 404, 422, 500),
    openapi_extra=upload_body("application/xml", LANDXML_UPLOAD_LIMIT, ALIGNMENT_LANDXML_EXAMPLE),
    description=ASSESSMENT
    + """

The body is the LandXML 1.2 document itself (every `CoordGeom/Curve` of every `Alignment`), the options and the
superelevation / grade / posted-speed defaults for every curve are query parameters (per-curve values need the
JSON form's `curve_overrides`). The same request as `POST /v1/alignments/assess` with `landxml`.""",
)
async def assess_landxml(
    request: Request, query: Annotated[LandXmlUploadQuery, Query()], cache: CacheDep, settings: SettingsDep
) -> Response:
    body = await landxml_upload(request, query)
    csv = wants_csv(request.headers.get("accept"))
    result = await compute_alignment(cache, body, settings, csv=csv, source_field="body")
    return computed_response(result, vary_accept=True)

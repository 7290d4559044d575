"""POST /v1/alignments/assess (JSON) and its raw-file forms /assess/csv, /assess/landxml and /assess/ifc."""

from __future__ import annotations

from typing import Annotated

from fastapi import APIRouter, Query, Request, Response
from starlette.concurrency import run_in_threadpool

from app.alignments.schemas import (
    ALIGNMENT_CSV_EXAMPLE,
    ALIGNMENT_IFC_EXAMPLE,
    ALIGNMENT_JSON_LIMIT,
    ALIGNMENT_LANDXML_EXAMPLE,
    CSV_UPLOAD_LIMIT,
    IFC_UPLOAD_LIMIT,
    LANDXML_UPLOAD_LIMIT,
    AlignmentRequest,
    AlignmentResult,
)
from app.alignments.service import compute_alignment, parse_json_request, resolve_assessment_request
from app.alignments.uploads import (
    CsvUploadQuery,
    IfcUploadQuery,
    LandXmlUploadQuery,
    csv_upload,
    ifc_upload,
    landxml_upload,
)
from app.compute.cache import ResultCache
from app.deps import CacheDep, SettingsDep
from app.http.bodies import json_body, upload_body
from app.http.bodylimit import body_limit
from app.http.fastpath import replayable
from app.http.negotiation import TABLE_FORMS, wants_csv
from app.http.problems import VEHICLE_REF_CODES
from app.http.responses import table_answer, table_responses
from app.settings import Settings

router = APIRouter(prefix="/v1/alignments", tags=["alignments"])


async def _uploaded_answer(
    request: Request, body: AlignmentRequest, field: str, cache: ResultCache, settings: Settings
) -> Response:
    """The answer to an uploaded file's request (CSV, LandXML or IFC read into the JSON request ``body``; ``field``
    names where its curves came from, for an error in the file), as JSON or CSV by the request's ``Accept``."""
    csv = wants_csv(request.headers.get("accept"))
    resolved = await resolve_assessment_request(request, body, settings)
    return table_answer(await compute_alignment(cache, resolved, None, settings, csv=csv, source_field=field))


ASSESSMENT = """For each horizontal curve and each vehicle: the SRT on the curve's bank and grade, the rollover
speed sqrt(127 SRT R) (Eq. 9.1), the side-friction speed sqrt(127 R (0.01 e + f_max)) with the design standard's
f_max (`design_standard`, AASHTO 2018 by default), the safe speed (the smaller) and which mechanism governs, the
margin against the posted speed (flagged when negative), and whether the radius meets the standard's minimum for the
posted speed. A curve without a superelevation takes the standard's design value for its posted speed and the
request's `max_superelevation_percent`. Curves sharing superelevation and grade share one SRT solve, and every
distinct pair is solved in one batch. JSON, or CSV with `Accept: text/csv` (one row per vehicle and curve). At most
10,000 rows (curves x vehicles) per request: larger work goes to a job (`POST /v1/jobs`, `alignments.assess`, up to
1,000,000 rows), whose result is the same bytes."""


@router.post(
    "/assess",
    name="assess",
    response_model=AlignmentResult,
    responses=table_responses(400, 404, 422, 500, *VEHICLE_REF_CODES),
    openapi_extra={**body_limit(ALIGNMENT_JSON_LIMIT), **json_body(AlignmentRequest)},
    description=ASSESSMENT
    + """

The curves are a JSON list (`curves`), CSV text (`csv`), a LandXML 1.2 document (`landxml`) or an IFC 4.3 file
(`ifc`); the same files can also be sent as they are to `/v1/alignments/assess/csv`, `/v1/alignments/assess/landxml`
and `/v1/alignments/assess/ifc`.""",
)
@replayable("alignments", offers=TABLE_FORMS)
async def assess(request: Request, cache: CacheDep, settings: SettingsDep) -> Response:
    # 100,000 curves are 15 MB of JSON: read and validated in a worker thread, the curves as columns
    body, curves = await run_in_threadpool(parse_json_request, await request.body())
    csv = wants_csv(request.headers.get("accept"))
    return table_answer(
        await compute_alignment(
            cache, await resolve_assessment_request(request, body, settings), curves, settings, csv=csv
        )
    )


@router.post(
    "/assess/csv",
    name="assess_csv",
    response_model=AlignmentResult,
    responses=table_responses(400, 404, 422, 500, *VEHICLE_REF_CODES),
    openapi_extra=upload_body("text/csv", CSV_UPLOAD_LIMIT, ALIGNMENT_CSV_EXAMPLE, "CSV file"),
    description=ASSESSMENT
    + """

The body is the CSV file itself (`--data-binary @curves.csv`), or the part `file` of a `multipart/form-data` body
(`-F file=@curves.csv`): UTF-8, a header row naming `id`, `radius_m`, `superelevation_percent` and optionally
`grade_percent`, `posted_speed_kmh`. The dialect is detected from the header and the first rows: `,`, `;` or a tab
between the fields, a decimal comma with `;` or a tab (as a spreadsheet in a decimal-comma locale saves it), a
UTF-8 byte-order mark, CRLF line ends; the answer names it (`csv_dialect`), and a number written in another dialect
than the file's is refused with its row and column. The options are query parameters (`vehicle` repeated for
several presets). The same request as `POST /v1/alignments/assess` with `csv`: same answer, same cache entry. A rule the
query's schema cannot state: `side_friction_bound` only with `design_standard` `thesis-table21` (or alone).""",
)
@replayable("alignments", offers=TABLE_FORMS)
async def assess_csv(
    request: Request, query: Annotated[CsvUploadQuery, Query()], cache: CacheDep, settings: SettingsDep
) -> Response:
    body, field = await csv_upload(request, query, CSV_UPLOAD_LIMIT)
    return await _uploaded_answer(request, body, field, cache, settings)


@router.post(
    "/assess/landxml",
    name="assess_landxml",
    response_model=AlignmentResult,
    responses=table_responses(400, 404, 422, 500, *VEHICLE_REF_CODES),
    openapi_extra=upload_body("application/xml", LANDXML_UPLOAD_LIMIT, ALIGNMENT_LANDXML_EXAMPLE, "LandXML document"),
    description=ASSESSMENT
    + """

The body is the LandXML 1.2 document itself (every `CoordGeom/Curve` of every `Alignment`), or the part `file` of
a `multipart/form-data` body (`-F file=@alignment.xml`); the options and the
superelevation / grade / posted-speed defaults for every curve are query parameters (per-curve values need the
JSON form's `curve_overrides`). The same request as `POST /v1/alignments/assess` with `landxml`. A rule the query's
schema cannot state: `side_friction_bound` only with `design_standard` `thesis-table21` (or alone).""",
)
@replayable("alignments", offers=TABLE_FORMS)
async def assess_landxml(
    request: Request, query: Annotated[LandXmlUploadQuery, Query()], cache: CacheDep, settings: SettingsDep
) -> Response:
    body, field = await landxml_upload(request, query, LANDXML_UPLOAD_LIMIT)
    return await _uploaded_answer(request, body, field, cache, settings)


@router.post(
    "/assess/ifc",
    name="assess_ifc",
    response_model=AlignmentResult,
    responses=table_responses(400, 404, 422, 500, *VEHICLE_REF_CODES),
    openapi_extra=upload_body("application/x-step", IFC_UPLOAD_LIMIT, ALIGNMENT_IFC_EXAMPLE, "IFC 4.3 file"),
    description=ASSESSMENT
    + """

The body is the IFC 4.3 file itself (ISO 10303-21 text, schema `IFC4X3_ADD2`: every top-level `IfcAlignment`'s
horizontal segments, its vertical layouts and cant, its `STATION` referents), with any content type
(`application/x-step`, `application/octet-stream`, `text/plain`), or the part `file` of a `multipart/form-data` body
(`-F file=@road.ifc`); the options and the superelevation / grade / posted-speed defaults for every curve are query
parameters (per-curve values need the JSON form's `curve_overrides`). A file of another schema (IFC2X3, IFC4, an
IFC4X3 release candidate, IFC4X3_ADD1) is refused naming it. The same request as `POST /v1/alignments/assess` with
`ifc`, and the same answer as the alignment's LandXML export gives. A rule the query's schema cannot state:
`side_friction_bound` only with `design_standard` `thesis-table21` (or alone).""",
)
@replayable("alignments", offers=TABLE_FORMS)
async def assess_ifc(
    request: Request, query: Annotated[IfcUploadQuery, Query()], cache: CacheDep, settings: SettingsDep
) -> Response:
    body, field = await ifc_upload(request, query, IFC_UPLOAD_LIMIT)
    return await _uploaded_answer(request, body, field, cache, settings)

"""Raw route uploads: POST /v1/routes/assess/gpx and /v1/routes/assess/geojson.

A GPS logger or a GIS exports a file; the request is the file itself as the body (``application/gpx+xml``,
``application/geo+json``) or as the part ``file`` of a ``multipart/form-data`` body, the options in the query, as
for the alignment uploads::

    curl --data-binary @examples/road.gpx -H 'Content-Type: application/gpx+xml' \\
      'http://127.0.0.1:8000/v1/routes/assess/gpx?vehicle=table16-btrain&superelevation_percent=6'
    curl -F file=@examples/road.geojson \\
      'http://127.0.0.1:8000/v1/routes/assess/geojson?vehicle=table16-btrain&superelevation_percent=6'

The query is validated by FastAPI against :data:`RouteUploadQuery` (fields and bounds taken from the JSON request's
own, :class:`~app.routes.schemas.RouteRequest` and its ``detection``, so the forms cannot drift); the file is
decoded (GeoJSON parsed as JSON) and the equivalent JSON request (``{"vehicle": ..., "gpx": "<the file>"}``, or
``"geojson": {...}``) goes through the same service and cache entry as ``POST /v1/routes/assess``: the same answer,
byte for byte. Errors in the document name ``body`` (``file`` for the multipart part) and the track or feature.
"""

from __future__ import annotations

from typing import Annotated, Any

from fastapi import Request
from fastapi.exceptions import RequestValidationError
from pydantic import ConfigDict, Field, ValidationError, create_model
from starlette.concurrency import run_in_threadpool

from app.alignments import uploads as alignment_uploads
from app.alignments.schemas import MAX_VEHICLES
from app.formats.uploads import decode_json_object, decode_xml, read_upload
from app.http.problems import InvalidRoute
from app.http.schemas import describe
from app.routes.schemas import Detection, RouteRequest
from app.srt.schemas import LoadIn

#: the alignment uploads' options, and a route's own superelevation and posted speed for every curve
OPTIONS = (
    *alignment_uploads.OPTIONS,
    "superelevation_percent",
    "posted_speed_kmh",
    "grade_percent",
    "parts",
    "use_elevation",
)
LOAD = alignment_uploads.LOAD
DETECTION = ("noise_m", "max_radius_m", "min_deflection_deg")


def _field(model: type, name: str) -> tuple[Any, Any]:
    info = model.model_fields[name]
    return info.annotation, info


_PRESETS = Field(
    min_length=1,
    max_length=MAX_VEHICLES,
    description=describe(
        f"Preset id(s) to assess, repeated for several (1-{MAX_VEHICLES}: `?vehicle=table16-btrain&"
        "vehicle=table23-semitrailer`); a full record or a fleet needs the JSON form (POST /v1/routes/assess).",
        unit="-",
        symbol="Tables 14-16, 22, 23",
    ),
)

RouteUploadQuery = create_model(
    "RouteUploadQuery",
    __config__=ConfigDict(extra="forbid", allow_inf_nan=False),
    vehicle=(list[Annotated[str, Field(min_length=1, max_length=100)]], _PRESETS),
    **{n: _field(RouteRequest, n) for n in OPTIONS},
    **{n: _field(LoadIn, n) for n in LOAD},
    **{n: _field(Detection, n) for n in DETECTION},
)


def upload_request(query, field: str, **document: Any) -> RouteRequest:
    """The JSON request equivalent to a route upload: the query's options and presets, and the document."""
    presets = list(query.vehicle)
    data: dict[str, Any] = {n: getattr(query, n) for n in OPTIONS if getattr(query, n) is not None}
    data["load"] = {n: getattr(query, n) for n in LOAD}
    data["detection"] = {n: getattr(query, n) for n in DETECTION if getattr(query, n) is not None}
    data.update({"vehicle": presets[0]} if len(presets) == 1 else {"vehicles": presets})
    data.update(document)
    try:
        return RouteRequest.model_validate(data)
    except ValidationError as exc:  # the query was checked with the same bounds: only the document is left
        where = ("body",) if field == "body" else ("body", field)
        raise RequestValidationError(
            [
                {**e, "loc": where} if e["loc"][0] in ("gpx", "geojson") else {**e, "loc": ("query", *e["loc"])}
                for e in exc.errors(include_url=False)
            ]
        ) from None


def _empty(field: str, what: str) -> InvalidRoute:
    return InvalidRoute(f"the {field} is empty: send the {what} file", source=field, location=None, column=None)


async def gpx_upload(request: Request, query, limit: int) -> tuple[RouteRequest, str]:
    """The JSON request equivalent to a GPX upload, and the field that holds the file (``body`` or ``file``)."""
    upload = await read_upload(request, limit)

    def build() -> RouteRequest:
        text = decode_xml(upload.data, upload.field, "GPX", InvalidRoute)
        if not text.strip():
            raise _empty(upload.field, "GPX")
        return upload_request(query, upload.field, gpx=text)

    return await run_in_threadpool(build), upload.field  # decoding tens of MB: not on the event loop


async def geojson_upload(request: Request, query, limit: int) -> tuple[RouteRequest, str]:
    """The JSON request equivalent to a GeoJSON upload, and the field that holds the file (``body`` or ``file``)."""
    upload = await read_upload(request, limit)

    def build() -> RouteRequest:
        if not upload.data.strip():
            raise _empty(upload.field, "GeoJSON")
        doc = decode_json_object(upload.data, upload.field, "GeoJSON", InvalidRoute)
        return upload_request(query, upload.field, geojson=doc)

    return await run_in_threadpool(build), upload.field  # parsing tens of MB: not on the event loop

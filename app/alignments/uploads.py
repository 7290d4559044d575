"""Raw CSV, LandXML and IFC uploads: POST /v1/alignments/assess/csv, /assess/landxml and /assess/ifc.

A road-design package exports a file; the natural request is the file itself as the body, or as the part ``file``
of a ``multipart/form-data`` body (a browser form, ``curl -F``), the options in the query::

    curl --data-binary @examples/curves-comma.csv -H 'Content-Type: text/csv' \\
      'http://127.0.0.1:8000/v1/alignments/assess/csv?vehicle=table16-btrain&rear_llt_limit=0.6'
    curl -F file=@examples/curves-semicolon.csv \\
      'http://127.0.0.1:8000/v1/alignments/assess/csv?vehicle=table16-btrain&rear_llt_limit=0.6'

The query is validated by FastAPI against :data:`CsvUploadQuery` / :data:`LandXmlUploadQuery` /
:data:`IfcUploadQuery` (fields and bounds
taken from the JSON request's own, so the two forms cannot drift); the body (bounded by the route's body limit,
:mod:`app.http.bodylimit`) is decoded,
and the equivalent JSON request (``{"vehicle": ..., "csv": "<the file>"}``) goes through the same service and
cache entry as ``POST /v1/alignments/assess``. Errors in the document name ``body`` (``file`` for the multipart
part) and the row or element.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Annotated, Any

from fastapi import Request
from fastapi.exceptions import RequestValidationError
from pydantic import ConfigDict, Field, ValidationError, create_model
from starlette.concurrency import run_in_threadpool

from app.alignments.schemas import (
    MAX_VEHICLES,
    AlignmentRequest,
    IfcIn,
    LandXmlIn,
)
from app.formats.uploads import decode_csv, decode_step, decode_xml, read_upload
from app.http.problems import InvalidAlignment
from app.http.schemas import describe
from app.srt.schemas import LoadIn

OPTIONS = (
    "model",
    "stage",
    "trailer_angle_deg",
    "rear_llt_limit",
    "design_standard",
    "side_friction_bound",
    "max_superelevation_percent",
)
LOAD = ("lateral_offset_m", "longitudinal_offset_m", "vertical_offset_m", "overweight_percent")
LANDXML_DEFAULTS = ("superelevation_percent", "grade_percent", "posted_speed_kmh", "profile")

_PRESETS = Field(
    min_length=1,
    max_length=MAX_VEHICLES,
    description=describe(
        f"Preset id(s) to assess, repeated for several (1-{MAX_VEHICLES}: `?vehicle=table16-btrain&"
        "vehicle=table23-semitrailer`); a full record needs the JSON form (POST /v1/alignments/assess).",
        unit="-",
        symbol="Tables 14-16, 22, 23",
    ),
)


def _field(model: type, name: str) -> tuple[Any, Any]:
    info = model.model_fields[name]
    return info.annotation, info


_QUERY_CONFIG = ConfigDict(extra="forbid", allow_inf_nan=False)
CsvUploadQuery = create_model(
    "CsvUploadQuery",
    __config__=_QUERY_CONFIG,
    vehicle=(list[Annotated[str, Field(min_length=1, max_length=100)]], _PRESETS),
    **{n: _field(AlignmentRequest, n) for n in OPTIONS},
    **{n: _field(LoadIn, n) for n in LOAD},
)
LandXmlUploadQuery = create_model(
    "LandXmlUploadQuery",
    __config__=_QUERY_CONFIG,
    vehicle=(list[Annotated[str, Field(min_length=1, max_length=100)]], _PRESETS),
    **{n: _field(AlignmentRequest, n) for n in OPTIONS},
    **{n: _field(LoadIn, n) for n in LOAD},
    **{n: _field(LandXmlIn, n) for n in LANDXML_DEFAULTS},
)
IfcUploadQuery = create_model(
    "IfcUploadQuery",
    __config__=_QUERY_CONFIG,
    vehicle=(list[Annotated[str, Field(min_length=1, max_length=100)]], _PRESETS),
    **{n: _field(AlignmentRequest, n) for n in OPTIONS},
    **{n: _field(LoadIn, n) for n in LOAD},
    **{n: _field(IfcIn, n) for n in LANDXML_DEFAULTS},
)


def upload_request(query, field: str = "body", **document: Any) -> AlignmentRequest:
    """The JSON request equivalent to an upload: the query's options and presets, and the document."""
    presets = list(query.vehicle)
    data: dict[str, Any] = {n: getattr(query, n) for n in OPTIONS if getattr(query, n) is not None}
    data["load"] = {n: getattr(query, n) for n in LOAD}
    data.update({"vehicle": presets[0]} if len(presets) == 1 else {"vehicles": presets})
    data.update(document)
    try:
        return AlignmentRequest.model_validate(data)
    except ValidationError as exc:  # the query was checked with the same bounds: only the document is left
        raise RequestValidationError(
            [
                {**e, "loc": ("body",) if field == "body" else ("body", field)}
                if e["loc"][0] in ("csv", "landxml", "ifc")
                else {**e, "loc": ("query", *e["loc"])}
                for e in exc.errors()
            ]
        ) from None


async def csv_upload(request: Request, query, limit: int) -> tuple[AlignmentRequest, str]:
    """The JSON request equivalent to a CSV upload, and the field that holds the file (``body`` or ``file``)."""
    upload = await read_upload(request, limit)

    def build() -> AlignmentRequest:
        text = decode_csv(upload.data, upload.field)
        if not text.strip().lstrip("\ufeff"):
            raise InvalidAlignment(
                f"the {upload.field} is empty: send the CSV file", source=upload.field, location=None, column=None
            )
        return upload_request(query, upload.field, csv=text)

    return await run_in_threadpool(build), upload.field  # decoding tens of MB: not on the event loop


async def road_file_upload(
    request: Request,
    query,
    limit: int,
    kind: str = "landxml",
    label: str = "LandXML",
    decode: Callable[[bytes, str], str] = decode_xml,
) -> tuple[AlignmentRequest, str]:
    """The JSON request equivalent to a road file's upload (the request's field ``kind``: a key of
    :data:`app.formats.road_file.ROAD_READERS`; ``label`` names the format in a message; ``decode``: the body's bytes
    to text, refusing what is not the format's, with the field), and the field that holds the file (``body`` or
    ``file``). The query's defaults (:data:`LANDXML_DEFAULTS`) go with the document."""
    upload = await read_upload(request, limit)

    def build() -> AlignmentRequest:
        text = decode(upload.data, upload.field)
        if not text.strip():
            raise InvalidAlignment(
                f"the {upload.field} is empty: send the {label} file", source=upload.field, location=None, column=None
            )
        defaults = {n: getattr(query, n) for n in LANDXML_DEFAULTS}
        return upload_request(query, upload.field, **{kind: {"document": text, **defaults}})

    # decoding a 64 MB document takes the event loop 0.1-0.2 s: in a worker thread (a MiB at a time, so the loop
    # gets the interpreter between two MiB)
    return await run_in_threadpool(build), upload.field


async def landxml_upload(request: Request, query, limit: int) -> tuple[AlignmentRequest, str]:
    """The JSON request equivalent to a LandXML upload, and the field that holds the file (``body`` or ``file``)."""
    return await road_file_upload(request, query, limit, "landxml", "LandXML", decode_xml)


async def ifc_upload(request: Request, query, limit: int) -> tuple[AlignmentRequest, str]:
    """The JSON request equivalent to an IFC 4.3 upload, and the field that holds the file (``body`` or ``file``)."""
    return await road_file_upload(request, query, limit, "ifc", "IFC", decode_step)

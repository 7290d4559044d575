"""Uploaded files: the request body itself (``curl --data-binary @curves.csv``) or the part named ``file`` of a
``multipart/form-data`` body (``curl -F file=@curves.csv``), bounded by the route's body limit
(:mod:`app.http.bodylimit`: the whole request, either way), and decoded to text.

:func:`read_upload` returns the file's bytes and the request field that names it in errors: ``body`` for a raw
body, ``file`` for the multipart part. A multipart body without a ``file`` part, with several, or with other parts
(the options go in the query, as for a raw body) is a 422 naming the part. Text that cannot be decoded
(:func:`decode_csv`, :func:`decode_xml`, :func:`decode_json_object`; :func:`decode_step` takes any bytes) is an
:class:`~app.http.problems.InvalidAlignment` (or the route's :class:`~app.http.problems.InvalidRoute`) naming the
field.
"""

from __future__ import annotations

import codecs
import re
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

import orjson
from fastapi import Request
from fastapi.exceptions import RequestValidationError
from starlette.datastructures import UploadFile

from app.formats.jsonpieces import assembled
from app.http.problems import InvalidAlignment

MULTIPART = "multipart/form-data"
#: the multipart part that holds the file (``curl -F file=@curves.csv``)
FILE_PART = "file"


@dataclass(frozen=True)
class Upload:
    """An uploaded file's bytes and the request field that holds it (``body`` or ``file``)."""

    data: bytes
    field: str
    filename: str | None = None


def is_multipart(content_type: str | None) -> bool:
    return (content_type or "").split(";", 1)[0].strip().lower() == MULTIPART


def _part_error(part: str, message: str, kind: str = "value_error") -> RequestValidationError:
    return RequestValidationError([{"type": kind, "loc": ("body", part), "msg": message, "input": None}])


async def read_upload(request: Request, limit: int) -> Upload:
    """The uploaded file: the ``file`` part of a multipart body, else the body itself (at most ``limit`` bytes: the
    route's body limit, which the middleware has already enforced on the whole request)."""
    if not is_multipart(request.headers.get("content-type")):
        return Upload(await request.body(), "body")
    # a part without a filename (curl -F 'file=<curves.csv') is a plain field: allowed up to the body limit too
    form = await request.form(max_files=2, max_fields=16, max_part_size=limit)
    try:
        others = sorted({k for k in form if k != FILE_PART})
        if others:
            raise _part_error(
                others[0],
                f"unexpected form part(s) {', '.join(repr(k) for k in others)}: send only the file, in the part "
                f"'{FILE_PART}'; the options are query parameters (?vehicle=...), as with a raw body",
            )
        parts = form.getlist(FILE_PART)
        if not parts:
            message = f"the multipart body has no part named '{FILE_PART}' (curl -F file=@curves.csv)"
            raise _part_error(FILE_PART, message, "missing")
        if len(parts) > 1:
            raise _part_error(FILE_PART, f"{len(parts)} parts named '{FILE_PART}': send one file per request")
        (part,) = parts
        if isinstance(part, UploadFile):
            return Upload(await part.read(), FILE_PART, part.filename)
        return Upload(part.encode("utf-8"), FILE_PART)
    finally:
        await form.close()


def decode_csv(data: bytes, field: str = "body") -> str:
    """CSV bytes as text (UTF-8; a byte-order mark is kept: the CSV reader notes and drops it)."""
    if data.startswith((codecs.BOM_UTF16_LE, codecs.BOM_UTF16_BE)):
        raise InvalidAlignment(
            "the CSV is UTF-16 text (a spreadsheet's 'Unicode text'): save it as 'CSV UTF-8'",
            source=field,
            location=None,
            column=None,
        )
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise InvalidAlignment(
            f"the CSV is not UTF-8 text (byte {exc.start}, 0x{data[exc.start]:02X}): a legacy 8-bit export? Save "
            "it as 'CSV UTF-8'",
            source=field,
            location=None,
            column=None,
        ) from None


#: bytes decoded per call: one call over a 64 MiB upload holds the interpreter's lock (and the event loop, where
#: uploads are decoded) for tens of milliseconds
DECODE_CHUNK = 2**20


def _decoded(data: bytes, encoding: str) -> str:
    """``data`` decoded :data:`DECODE_CHUNK` bytes at a time (an incremental decoder: a character split between two
    chunks is decoded whole); raises :class:`UnicodeDecodeError` as ``bytes.decode`` does."""
    decoder = codecs.getincrementaldecoder(encoding)()
    view = memoryview(data)

    def parts() -> Iterator[str]:
        for k in range(0, len(view), DECODE_CHUNK):
            yield decoder.decode(view[k : k + DECODE_CHUNK])
        yield decoder.decode(b"", final=True)

    return assembled(parts())  # appended as decoded, not joined in one call (see assembled)


def decode_xml(data: bytes, field: str = "body", root: str = "LandXML", error: type = InvalidAlignment) -> str:
    """XML bytes as text: UTF-8 (with or without BOM), or the encoding its XML declaration names; else ``error``
    (an :class:`~app.http.problems.InvalidAlignment` or its route form) naming ``field`` and the ``root`` element."""
    try:
        return _decoded(data, "utf-8-sig")
    except UnicodeDecodeError:  # where, for the message: a position to look at, as the CSV's says (found again on the
        try:  # whole bytes, since the incremental decoder counts from its chunk; only a refused upload pays for it)
            data.decode("utf-8-sig")
            bad = "a byte that no chunk decodes"
        except UnicodeDecodeError as exc:
            bad = f"byte {exc.start}, 0x{data[exc.start]:02X}"
    declared = re.match(rb"""\s*<\?xml[^>]*encoding\s*=\s*["']([A-Za-z0-9._-]+)["']""", data)
    if declared:
        try:
            return _decoded(data, codecs.lookup(declared.group(1).decode()).name)
        except (LookupError, UnicodeDecodeError):
            pass
    raise error(
        f"the document is neither UTF-8 (not at {bad}) nor in the encoding its XML declaration names",
        source=field,
        location=root,
        column=None,
    )


def decode_step(data: bytes, field: str = "body") -> str:
    """ISO 10303-21 (STEP, an IFC file) bytes as text: UTF-8 (a byte-order mark dropped), else Latin-1. The format is
    7-bit text with other characters escaped (``\\X2\\...``); some writers put Latin-1 in strings, which only names
    carry, so nothing is refused here (the reader refuses what is not ISO 10303-21; ``field``, the signature shared
    with :func:`decode_csv` and :func:`decode_xml`, names the upload there)."""
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError:
        return data.decode("latin-1")


_JSON_TYPES = {list: "array", str: "string", int: "number", float: "number", bool: "boolean", type(None): "null"}


def decode_json_object(data: bytes, field: str = "body", what: str = "GeoJSON", error: type = InvalidAlignment) -> Any:
    """A JSON object from bytes (UTF-8, a byte-order mark tolerated); else ``error`` naming ``field``."""
    try:
        doc = orjson.loads(data.removeprefix(codecs.BOM_UTF8))  # a BOM is not JSON (RFC 8259 section 8.1)
    except orjson.JSONDecodeError as exc:
        raise error(f"not JSON: {exc}", source=field, location=None, column=None) from None
    if not isinstance(doc, dict):
        kind = _JSON_TYPES.get(type(doc), "value")
        raise error(f"a {what} object is expected, got a JSON {kind}", source=field, location=None, column=None)
    return doc

"""Raw uploads: a file sent as the request body itself (bounded by the route's body limit, :mod:`app.http.bodylimit`),
decoded to text. A body that cannot be decoded is an :class:`~app.http.problems.InvalidAlignment` naming ``body``."""

from __future__ import annotations

import codecs
import re

from app.http.problems import InvalidAlignment


def decode_csv(data: bytes) -> str:
    try:
        return data.decode("utf-8-sig")  # a BOM (spreadsheet exports) is not part of the first column's name
    except UnicodeDecodeError as exc:
        raise InvalidAlignment(
            f"the CSV is not UTF-8 text (byte {exc.start})", source="body", location=None, column=None
        ) from None


def decode_xml(data: bytes) -> str:
    """XML bytes as text: UTF-8 (with or without BOM), or the encoding its XML declaration names."""
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError:
        pass
    declared = re.match(rb"""\s*<\?xml[^>]*encoding\s*=\s*["']([A-Za-z0-9._-]+)["']""", data)
    if declared:
        try:
            return data.decode(codecs.lookup(declared.group(1).decode()).name)
        except (LookupError, UnicodeDecodeError):
            pass
    raise InvalidAlignment(
        "the document is neither UTF-8 nor in the encoding its XML declaration names",
        source="body",
        location="LandXML",
        column=None,
    )

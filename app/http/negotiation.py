"""Content negotiation: which form of an answer ``Accept`` asks for (JSON, CSV, GeoJSON), and the media types.

The batch endpoints (alignment assessment, sweep, tables) answer JSON by default and CSV when ``Accept`` prefers
``text/csv``; a route answers GeoJSON too when ``Accept`` prefers ``application/geo+json``. The raw-body fast path
(:mod:`app.http.fastpath`) negotiates with the same function, so both paths agree on the form.
"""

from __future__ import annotations

import functools

CSV_MEDIA_TYPE = "text/csv"
JSON_MEDIA_TYPE = "application/json"
GEOJSON_MEDIA_TYPE = "application/geo+json"
#: the media types of a JSON and a CSV answer
JSON_TYPE, CSV_TYPE = "application/json", "text/csv; charset=utf-8"


def _parse_accept(accept: str) -> list[tuple[str, float]]:
    out = []
    for part in accept.split(","):
        media, *params = (p.strip() for p in part.split(";"))
        if not media:
            continue
        q = 1.0
        for p in params:
            name, _, value = p.partition("=")
            if name.strip().lower() == "q":
                try:
                    q = float(value)
                except ValueError:
                    q = 0.0
        out.append((media.lower(), q))
    return out


def _quality(ranges: list[tuple[str, float]], media: str) -> tuple[float, int]:
    """(q, specificity) of the most specific range matching ``media``; (0, 0) when none does."""
    kind = media.split("/")[0]
    best = (0.0, 0)
    for m, q in ranges:
        spec = 3 if m == media else 2 if m == f"{kind}/*" else 1 if m == "*/*" else 0
        if spec > best[1]:
            best = (q, spec)
    return best


def wants_csv(accept: str | None) -> bool:
    """Whether ``Accept`` prefers ``text/csv`` to ``application/json`` (JSON on a tie or without the header)."""
    return negotiate(accept) == "csv"


#: the forms of an answer: a table's (JSON, CSV) and a route's (JSON, CSV, GeoJSON)
TABLE_FORMS = ("json", "csv")
WITH_GEOJSON = ("json", "csv", "geojson")


@functools.lru_cache(maxsize=256)  # clients send the same few Accept headers: each is read once per process
def negotiate(accept: str | None, offers: tuple[str, ...] = TABLE_FORMS) -> str:
    """The form ``Accept`` prefers among ``offers``: GeoJSON when offered and preferred to both JSON and CSV, else CSV
    when preferred to JSON, else JSON (on a tie, without the header, or when nothing offered is acceptable)."""
    if not accept:
        return "json"
    ranges = _parse_accept(accept)
    q_json, s_json = _quality(ranges, JSON_MEDIA_TYPE)
    q_csv, s_csv = _quality(ranges, CSV_MEDIA_TYPE)
    if "geojson" in offers:
        q_geo, s_geo = _quality(ranges, GEOJSON_MEDIA_TYPE)
        if q_geo > 0 and all(q_geo > q or (q_geo == q and s_geo > s) for q, s in ((q_json, s_json), (q_csv, s_csv))):
            return "geojson"
    if q_csv > 0 and (q_csv > q_json or (q_csv == q_json and s_csv > s_json)):
        return "csv"
    return "json"

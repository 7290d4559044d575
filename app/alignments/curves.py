"""Curves as columns: the JSON request's ``curves`` list read into arrays, fast enough for 100,000 curves.

Validating 100,000 ``CurveIn`` models with pydantic takes over a second and holds the GIL; the same rules checked
here on arrays take a tenth of that, in plain Python and numpy that let other threads (and the event loop) run.
The schema stays the one published (:class:`app.alignments.schemas.CurveIn`): every curve the fast check cannot
clear is validated by pydantic itself, which gives the exact error the JSON form always gave (its type, location
and message), so the two cannot disagree on an error; ``tests/api/test_curve_columns.py`` checks that they agree
on acceptance too.
"""

from __future__ import annotations

import math
from functools import lru_cache
from operator import itemgetter, methodcaller
from typing import Annotated, Any

import numpy as np
from fastapi.exceptions import RequestValidationError
from pydantic import Field, TypeAdapter, ValidationError

from app.alignments.schemas import CurveIn, as_a_job
from app.formats.alignment_io import CURVE_ID_MAX_CHARS, CURVE_ID_REFUSED, MAX_CURVES, CurveTable
from engine import BOUNDS

_REQUIRED = frozenset(("id", "radius_m"))  # the superelevation may be left out: it is then derived
_FIELDS = frozenset(("id", "radius_m", "superelevation_percent", "grade_percent", "posted_speed_kmh"))
_CURVE = TypeAdapter(CurveIn)


@lru_cache
def _list(max_curves: int) -> TypeAdapter:
    return TypeAdapter(Annotated[list[Any], Field(min_length=1, max_length=max_curves)])


_NUMBER = (int, float)


def _is_number(x: Any) -> bool:
    return type(x) in _NUMBER  # bool is not a number here, as in the strict schema


def _inside(values: np.ndarray, name: str) -> np.ndarray:
    b = BOUNDS[name]
    low = values > b.minimum if b.exclusive_minimum else values >= b.minimum
    return np.isfinite(values) & low & (values <= b.maximum)


def _refuse(index: int, item: Any, prefix: tuple = ("body", "curves")) -> None:
    """Raise pydantic's own errors for one curve (located at its index), if it has any."""
    try:
        _CURVE.validate_python(item, strict=True)
    except ValidationError as exc:
        raise RequestValidationError(
            [{**e, "loc": (*prefix, index, *e["loc"])} for e in exc.errors(include_url=False)]
        ) from None


_TYPES = {"id": {str}, "radius_m": {int, float}, "grade_percent": {int, float}}
_OPTIONAL_TYPES = {int, float, type(None)}


def _columns_at_once(items: list[Any]) -> CurveTable | None:
    """The curves as columns when every one of them is plainly valid, checked column by column (``map`` and set
    operations in C, no Python per curve: about half the time of the loop below); None when any curve may not be
    (the loop then finds and reports it). Accepts exactly what the loop accepts, with the same columns."""
    if set(map(type, items)) != {dict}:
        return None
    keysets = set(map(frozenset, items))
    if not all(_REQUIRED <= k <= _FIELDS for k in keysets):
        return None
    everywhere = frozenset.intersection(*keysets)

    def column(key: str, default: Any = None) -> list[Any]:  # itemgetter where every curve has the key: faster
        return list(map(itemgetter(key) if key in everywhere else methodcaller("get", key, default), items))

    ids, radius, grade = column("id"), column("radius_m"), column("grade_percent", 0.0)
    e, posted = column("superelevation_percent"), column("posted_speed_kmh")
    columns = {"id": ids, "radius_m": radius, "grade_percent": grade}
    if not all(set(map(type, columns[k])) <= t for k, t in _TYPES.items()):
        return None
    if not (set(map(type, e)) <= _OPTIONAL_TYPES and set(map(type, posted)) <= _OPTIONAL_TYPES):
        return None
    try:
        r, g, ev, v = (np.array(c, dtype=float) for c in (radius, grade, e, posted))  # None -> nan
    except OverflowError:  # an integer past the float range: the loop's error
        return None
    return plainly_valid(ids, r, ev, g, v)


def plainly_valid(
    ids: list[str], radius: np.ndarray, e: np.ndarray, grade: np.ndarray, posted: np.ndarray
) -> CurveTable | None:
    """The curves as a table when their ids and values pass the rules :func:`curves_from_json` checks (an id of 1 to
    100 characters, no control characters, no duplicate; every value within its bounds, nan for an absent optional
    one); None otherwise. Shared by :mod:`app.alignments.json_curves`, which reads the same list from the body's
    text."""
    lengths = set(map(len, ids))
    if (
        not lengths
        or min(lengths) < 1
        or max(lengths) > CURVE_ID_MAX_CHARS
        or CURVE_ID_REFUSED.search(" ".join(ids))
        or not all(map(str.strip, ids))
        or len(set(ids)) < len(ids)
    ):
        return None
    ok = _inside(radius, "radius_m") & _inside(grade, "slope_percent")
    ok &= (np.isnan(e) | _inside(e, "bank_percent")) & (np.isnan(posted) | _inside(posted, "speed_kmh"))
    if not ok.all():
        return None
    return CurveTable(ids, radius, e, grade, posted, np.full(len(ids), math.nan))


def curves_from_json(items: Any, max_curves: int = MAX_CURVES) -> CurveTable:
    """The validated ``curves`` of a JSON request as columns (at most ``max_curves``: a job's limit is larger than a
    request's); a 422 naming the curve and field otherwise."""
    if not isinstance(items, list) or not 1 <= len(items) <= max_curves:
        try:  # pydantic's own error: not a list, or too short or too long
            _list(max_curves).validate_python(items, strict=True)
        except ValidationError as exc:
            errors = [{**e, "loc": ("body", "curves", *e["loc"])} for e in exc.errors(include_url=False)]
            if max_curves == MAX_CURVES:  # the synchronous request's limit: say where larger work goes
                errors = [{**e, "msg": as_a_job(e["msg"])} if e["type"] == "too_long" else e for e in errors]
            raise RequestValidationError(errors) from None
    fast = _columns_at_once(items)
    if fast is not None:
        return fast
    n = len(items)
    ids: list[str] = [""] * n
    radius, e, grade, posted = (np.full(n, math.nan) for _ in range(4))
    grade[:] = 0.0
    suspect = np.zeros(n, dtype=bool)
    for i, c in enumerate(items):
        if type(c) is not dict or not (_REQUIRED <= c.keys() <= _FIELDS):
            suspect[i] = True
            continue
        cid, r = c["id"], c["radius_m"]
        ev, g, v = c.get("superelevation_percent"), c.get("grade_percent", 0.0), c.get("posted_speed_kmh")
        if (
            type(cid) is not str
            or not 1 <= len(cid) <= CURVE_ID_MAX_CHARS
            or CURVE_ID_REFUSED.search(cid)
            or not cid.strip()
            or not _is_number(r)
            or not _is_number(g)
            or not (ev is None or _is_number(ev))
            or not (v is None or _is_number(v))
        ):
            suspect[i] = True
            continue
        ids[i] = cid
        radius[i] = r
        grade[i] = g
        if ev is not None:
            e[i] = ev
        if v is not None:
            posted[i] = v
    suspect |= ~_inside(radius, "radius_m") | ~_inside(grade, "slope_percent")
    suspect |= ~(np.isnan(e) | _inside(e, "bank_percent")) | ~(np.isnan(posted) | _inside(posted, "speed_kmh"))
    for i in np.flatnonzero(suspect):
        _refuse(int(i), items[int(i)])  # pydantic's own error for the first curve that has one
    seen: dict[str, int] = {}
    for i, cid in enumerate(ids):
        if cid in seen:
            raise RequestValidationError(
                [
                    {
                        "type": "request_shape",
                        "loc": ("body", "curves", i, "id"),
                        "msg": f"duplicate curve id {cid!r} (also curves.{seen[cid]}.id)",
                        "input": cid,
                    }
                ]
            )
        seen[cid] = i
    return CurveTable(ids, radius, e, grade, posted, np.full(n, math.nan))

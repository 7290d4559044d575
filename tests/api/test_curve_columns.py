"""app.alignments.curves.curves_from_json: the JSON curves read into columns agree with the published schema (CurveIn,
strict) on what they accept, and its two ways of reading them (column by column, curve by curve) agree on everything."""

from __future__ import annotations

import math

import numpy as np
import pytest
from fastapi.exceptions import RequestValidationError
from hypothesis import given, settings
from hypothesis import strategies as st
from pydantic import TypeAdapter, ValidationError

from app.alignments import curves as curves_module
from app.alignments.curves import curves_from_json
from app.alignments.schemas import CurveIn
from app.formats.alignment_io import CURVE_ID_MAX_CHARS

_SCHEMA = TypeAdapter(list[CurveIn])


def _number(low: float, high: float):
    """Numbers in the bound, on it, just past it and far past it; ints and floats; and what is not a number."""
    edge = st.sampled_from([low, high, low - 1e-9, high + 1e-9, 0, -0.0, 1e300, -(2**63), 2**64 - 1])
    inside = st.floats(low, high) | st.integers(math.ceil(low), math.floor(high))
    return inside | edge | st.sampled_from([True, False, "5", None, [1.0]])


_ID = st.one_of(
    st.text(alphabet=st.characters(exclude_categories=("Cs",)), min_size=0, max_size=4),  # controls, empty
    st.sampled_from(["C1", "C2", "x" * CURVE_ID_MAX_CHARS, "x" * (CURVE_ID_MAX_CHARS + 1), "a\x85b", 7, None]),
)
_CURVE = st.fixed_dictionaries(
    {"id": _ID, "radius_m": _number(5.0, 1e5)},
    optional={
        "superelevation_percent": _number(-20.0, 20.0),
        "grade_percent": _number(-20.0, 20.0),
        "posted_speed_kmh": _number(0.0, 200.0),
        "bank": st.just(1.0),  # not a field
    },
)
_ITEMS = st.lists(_CURVE | st.sampled_from([None, [], "C1"]), min_size=1, max_size=5) | st.lists(
    st.fixed_dictionaries(
        {"id": st.sampled_from(["A", "B", "C", "x" * CURVE_ID_MAX_CHARS, "x" * (CURVE_ID_MAX_CHARS + 1), "", "a\x85"])},
        optional={
            "radius_m": st.floats(5, 1e5) | st.sampled_from([True, 4.9, 5]),
            "posted_speed_kmh": st.floats(1, 200) | st.none() | st.sampled_from([0, False]),
            "superelevation_percent": st.floats(-20, 20) | st.sampled_from([True, 20.5, None]),
            "grade_percent": st.floats(-20, 20) | st.sampled_from([True, -21, None]),
        },
    ),
    min_size=1,
    max_size=4,
)  # the second: mostly valid curves, one flaw at a time, for the column-by-column reading


def _read(items, *, by_columns: bool):
    if not by_columns:
        saved, curves_module._columns_at_once = curves_module._columns_at_once, lambda items: None
    try:
        return curves_from_json(items), None
    except RequestValidationError as exc:
        return None, exc.errors()
    finally:
        if not by_columns:
            curves_module._columns_at_once = saved


def _same_table(a, b) -> None:
    assert a.ids == b.ids
    for name in ("radius_m", "superelevation_percent", "grade_percent", "posted_speed_kmh", "station_m"):
        x, y = getattr(a, name), getattr(b, name)
        assert x.tobytes() == y.tobytes() or np.array_equal(x, y, equal_nan=True), name


@settings(max_examples=600, deadline=None)
@given(_ITEMS)
def test_columns_and_loop_and_schema_agree(items):
    try:
        _SCHEMA.validate_python(items, strict=True)
        ids = [c["id"] for c in items]
        schema_accepts = len(set(ids)) == len(ids)  # unique ids: the service's rule beyond the schema
    except ValidationError:
        schema_accepts = False
    fast, fast_errors = _read(items, by_columns=True)
    slow, slow_errors = _read(items, by_columns=False)
    assert (fast is not None) == (slow is not None) == schema_accepts
    if fast is not None:
        _same_table(fast, slow)
        assert fast.ids == [c["id"] for c in items]
        assert list(fast.radius_m) == [float(c["radius_m"]) for c in items]
        assert list(fast.grade_percent) == [float(c.get("grade_percent", 0.0)) for c in items]
    else:
        assert fast_errors == slow_errors


def test_a_refused_curve_is_named_the_same_way_by_either_reading():
    items = [{"id": "A", "radius_m": 100.0}, {"id": "B", "radius_m": 2.0}]
    fast, errors = _read(items, by_columns=True)
    assert fast is None and errors[0]["loc"] == ("body", "curves", 1, "radius_m")
    with pytest.raises(RequestValidationError):
        curves_from_json(items)

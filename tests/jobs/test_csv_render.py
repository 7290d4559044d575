"""app.formats.tables.csv_lines_of_columns (each column written at once, lines put together by slice assignment: what
a job's result and the synchronous CSV answers are rendered with) against the cell-by-cell reference, on columns of
every kind: floats of every magnitude (exponent forms, below 1e-4, -0.0, nan, infinities), ints, booleans, nulls,
texts with quotes, commas and formula prefixes, repeated texts, and target columns."""

from __future__ import annotations

import math

import numpy as np
import pytest

from app.formats.tables import Text, csv_lines_cellwise, csv_lines_of_columns, target_columns_of


def _floats(rng, n: int) -> list[float | None]:
    exp = rng.integers(-30, 30, n)
    values = (rng.uniform(-10, 10, n) * 10.0**exp).tolist()
    values[::7] = np.round(rng.uniform(-200, 200, len(values[::7])), 1).tolist()
    return values


@pytest.mark.parametrize("seed", range(6))
def test_columns_written_at_once_are_the_cells_written_one_by_one(seed):
    rng = np.random.default_rng(seed)
    n = 300
    special = [0.0, -0.0, 1e-4, 9.99e-5, 1e16, 1e15, 5e-324, 1.7976931348623157e308, 123.0, 0.1 + 0.2]
    plain = np.round(rng.uniform(-100, 100, n), 3).tolist()
    with_none = [None if i % 5 == 0 else v for i, v in enumerate(plain)]
    wide = _floats(rng, n)
    wide[: len(special)] = special
    odd = list(plain)
    odd[3], odd[9] = math.nan, -math.inf
    ids = [["=1+1", 'a"b', "c,d", "-4", "plain", "@x", " s"][i % 7] + str(i) for i in range(n)]
    columns = [
        [int(x) for x in rng.integers(-5, 5, n)],
        [Text("table16-btrain")] * n,
        [None] * n,
        [Text(f"C{i}") for i in range(n)],
        ids,
        plain,
        with_none,
        wide,
        odd,
        [bool(x) for x in rng.integers(0, 2, n)],
        [None if i % 3 == 0 else bool(i % 2) for i in range(n)],
        [["rollover", "side-friction", None][i % 3] for i in range(n)],
        [1 if i % 2 else 2.5 for i in range(n)],  # ints and floats mixed
    ]
    for k in range(len(columns)):
        assert csv_lines_of_columns([columns[k]]) == csv_lines_cellwise([columns[k]]), k
    assert csv_lines_of_columns(columns) == csv_lines_cellwise(columns)
    assert csv_lines_of_columns([plain[:1]]) == csv_lines_cellwise([plain[:1]]) and csv_lines_of_columns([[]]) == b""


def test_target_columns_gathered_per_distinct_list_are_those_of_each_row():
    a = [{"name": "x", "meets": True, "margin_g": 0.1}, {"name": "y", "meets": False, "margin_g": -0.2}]
    b = [{"name": "x", "meets": False, "margin_g": -0.05}]
    rows = [a, b, [], a, b, b, []]
    out = target_columns_of(rows)
    assert out["meets_x"] == [True, False, None, True, False, False, None]
    assert out["margin_y_g"] == [-0.2, None, None, -0.2, None, None, None]
    assert sorted(out) == ["margin_x_g", "margin_y_g", "meets_x", "meets_y"]

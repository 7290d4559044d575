"""app.jobs.csv_columns: a job's plain CSV read into columns is read_csv's table, and anything else is left to
read_csv (None), which reports the first bad row and field."""

from __future__ import annotations

import numpy as np
import pytest

from app.formats.alignment_io import read_csv
from app.jobs.csv_columns import RowNames, read_csv_columns

HEADER = "id,radius_m,superelevation_percent,grade_percent,posted_speed_kmh"


def same(a, b) -> None:
    assert a.ids == b.ids
    for name in ("radius_m", "superelevation_percent", "grade_percent", "posted_speed_kmh", "station_m"):
        x, y = getattr(a, name), getattr(b, name)
        assert x.dtype == y.dtype == np.float64 and x.tobytes() == y.tobytes(), name  # bit for bit (-0.0, nan)
    assert list(a.where) == list(b.where)
    assert a.dialect == b.dialect  # the answer names the dialect: the fast path's must be read_csv's


@pytest.mark.parametrize(
    "text",
    [
        HEADER + "\nA,100,6,-2,80\nB,250.5,,0,\nC,1e3,-0,3.25,110\n",
        HEADER + "\r\nA,100,6,-2,80\r\nB,250.5,,,\r\n",  # CRLF, empty optional fields (grade 0)
        "Radius_M , ID\n 100 ,A\n200, B \n\n\n",  # any order, case and spaces; trailing blank lines
        "id,radius_m\nA,40\nB,1_500\n,,\n".replace(",,\n", ""),  # only the required columns; float() syntax
        "id,radius_m,posted_speed_kmh\n=cmd,100,50\n-4,200,60",  # no final newline; ids read as text
    ],
)
def test_a_plain_csv_is_read_csvs_table(text):
    fast = read_csv_columns(text, max_curves=10)
    assert fast is not None
    same(fast, read_csv(text, max_curves=10))


@pytest.mark.parametrize(
    "text",
    [
        HEADER + '\n"A",100,6,-2,80\n',  # quotes
        "\ufeff" + HEADER + "\nA,100,6,-2,80\n",  # a BOM
        "id;radius_m\nA;100\n",  # another separator
        HEADER + "\nA,100,6,-2,80\n\nB,100,6,-2,80\n",  # a blank row between curves
        HEADER + "\nA,100,6,-2\n",  # a field short
        "id,radius_m,superelevation_percent\nC1,100,2,B\n200,4\n",  # a field too many, then one short: k * n in all
        HEADER + "\nA,100,x,-2,80\n",  # not a number
        HEADER + "\nA,100,nan,-2,80\n",  # not finite
        HEADER + "\nA,,6,-2,80\n",  # the radius missing
        HEADER + "\nA,3,6,-2,80\n",  # below the bounds
        HEADER + "\nA,100,6,-2,80\nA,200,6,-2,80\n",  # a duplicate id
        HEADER + "\n ,100,6,-2,80\n",  # an empty id
        HEADER + "\n" + "x" * 101 + ",100,6,-2,80\n",  # an id too long
        HEADER + "\nA\tB,100,6,-2,80\n",  # a control character
        "id,radius_m,speed\nA,100,5\n",  # an unknown column
        HEADER + "\n" + "".join(f"C{i},100,6,-2,80\n" for i in range(11)),  # more than max_curves
        HEADER + "\n",  # no curves
    ],
)
def test_anything_else_is_left_to_read_csv(text):
    assert read_csv_columns(text, max_curves=10) is None


def test_row_names_are_made_when_asked_for():
    rows = RowNames(0, 5)
    assert list(rows) == [f"row {i}" for i in range(2, 7)] and rows[-1] == "row 6"
    assert list(rows[1:3]) == ["row 3", "row 4"] and len(rows[3:]) == 2 and len(rows[4:2]) == 0
    with pytest.raises(IndexError):
        rows[5]

"""CSV text written column by column (app.formats.tables): every cell by the one-cell rule, whatever the column's
types."""

from __future__ import annotations

import csv
import io

import pytest

from app.formats.tables import Text, _cell, _field, csv_lines, csv_lines_of_columns

COLUMNS = {
    "floats": [1.5, None, -4.0, float("nan"), 1e-05, 1e16],
    "bools": [True, False, None, True, False, True],
    "ints": [0, -3, None, 7, 12345678901234567890, 2],
    "texts": ["C1", '=HYPERLINK("x","y")', "-2+3", None, 'say "hi"', "@SUM(A1)"],
    "labels": [Text("table16-btrain")] * 5 + [None],
    "mixed": [1, 2.5, True, "x", None, Text("+y")],  # the generic path
    "empty": [None] * 6,
}


def test_a_small_table_is_written_as_spreadsheets_read_it():
    text = csv_lines_of_columns(list(COLUMNS.values())).decode()
    assert text.splitlines()[0] == '1.5,true,0,"C1","table16-btrain",1,'
    assert text.splitlines()[1] == ',false,-3,"\'=HYPERLINK(""x"",""y"")","table16-btrain",2.5,'
    assert text.endswith("\r\n") and text.count("\r\n") == 6
    rows = list(csv.reader(io.StringIO(text)))
    assert [r[3] for r in rows] == ["C1", '\'=HYPERLINK("x","y")', "'-2+3", "", 'say "hi"', "'@SUM(A1)"]
    assert [r[0] for r in rows] == ["1.5", "", "-4.0", "nan", "1e-05", "1e+16"]


@pytest.mark.parametrize("name", list(COLUMNS))
def test_each_column_kind_writes_every_cell_by_the_one_cell_rule(name):
    values = COLUMNS[name]
    lines = csv_lines_of_columns([values]).decode().split("\r\n")[:-1]
    assert lines == [_field(_cell(v)) for v in values]


def test_rows_and_columns_give_the_same_text():
    names = list(COLUMNS)
    rows = [dict(zip(names, values, strict=True)) for values in zip(*COLUMNS.values(), strict=True)]
    rows[2].pop("texts")  # a column a row does not have is left empty
    expected = csv_lines_of_columns([[row.get(n) for row in rows] for n in names])
    assert csv_lines(names, rows) == csv_lines(names, iter(rows)) == expected
    assert csv_lines(names, []) == csv_lines_of_columns([]) == b""

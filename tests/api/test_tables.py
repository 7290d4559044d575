"""CSV text written column by column (app.formats.tables): every cell by the one-cell rule, whatever the column's
types."""

from __future__ import annotations

import csv
import io

import orjson
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from app.formats.json_rows import RawJson, json_objects, json_template
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


# ------------------------------------------------------------------------ JSON written column by column

_SCALAR = st.one_of(
    st.none(),
    st.booleans(),
    st.integers(min_value=-(2**63), max_value=2**64 - 1),
    st.floats(allow_nan=True, allow_infinity=True),  # nan and infinities: orjson writes null
)
#: texts full of what JSON and the writer's cutting care about: commas, quotes, braces, escapes, the control
#: characters the writer cuts at (orjson escapes them), and any other character but a lone surrogate (orjson refuses
#: those, in a row dict as in a column)
_TEXT = st.text(
    alphabet=st.one_of(st.sampled_from(list(',"{}[]:\\\x00\x01\n é')), st.characters(exclude_categories=("Cs",))),
    max_size=8,
)
_VALUE = st.one_of(
    _SCALAR,
    _TEXT,
    st.lists(st.dictionaries(_TEXT, st.one_of(_SCALAR, _TEXT), max_size=3), max_size=3),
)


@st.composite
def _tables(draw):
    rows = draw(st.integers(min_value=0, max_value=12))
    names = draw(st.lists(_TEXT, min_size=1, max_size=5, unique=True))
    kind = st.sampled_from(["scalar", "any", "raw"])
    columns = {}
    for name in names:
        k = draw(kind)
        values = draw(st.lists(_SCALAR if k == "scalar" else _VALUE, min_size=rows, max_size=rows))
        columns[name] = RawJson(map(orjson.dumps, values)) if k == "raw" else values
    return columns


def _as_dicts(columns) -> list[dict]:
    plain = {k: [orjson.loads(v) for v in vs] if isinstance(vs, RawJson) else vs for k, vs in columns.items()}
    return [dict(zip(plain, row, strict=True)) for row in zip(*plain.values(), strict=True)]


@settings(max_examples=300, deadline=None)
@given(_tables())
def test_json_written_by_columns_is_orjsons_json_of_the_rows(columns):
    """json_objects (and json_template, its one object per row): byte for byte orjson's JSON of the row dicts, for
    columns of numbers (one orjson call, split), of anything (one call a value) and already written (RawJson)."""
    rows = _as_dicts(columns)
    assert json_objects(columns) == orjson.dumps(rows)[1:-1]
    keys = [orjson.dumps(name) + b":" for name in columns]
    fragments = [b"{" + keys[0], *(b"," + k for k in keys[1:]), b"}"]
    each = json_template(fragments, list(columns.values()), b"\x00").split(b"\x00")[1:]
    assert each == ([orjson.dumps(r) for r in rows] if rows else [])


def test_a_json_template_puts_each_rows_values_between_the_fragments():
    text = json_template([b"<", b"|", b">"], [[1, None], ["a,b", float("nan")]], b"\n")
    assert text == b'\n<1|"a,b">\n<null|null>'
    with pytest.raises(ValueError, match="fragments"):
        json_template([b"<", b">"], [[1], [2]])
    with pytest.raises(ValueError, match="column 1 has 1 values, not 2"):
        json_template([b"<", b"|", b">"], [[1, 2], [3]])

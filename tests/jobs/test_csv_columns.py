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


def _spellings(rng: np.random.Generator, x: float) -> list[str]:
    """Ways a spreadsheet or a script writes ``x``: repr, fixed decimals (0-17), a sign, leading zeros, no digit
    before or after the point, an exponent, an underscore, spaces (the last four are float's syntax beyond the
    plain decimals the fast path reads)."""
    d = int(rng.integers(0, 18))
    fixed = f"{x:.{d}f}"
    out = [repr(x), fixed, fixed if fixed.startswith("-") else "+" + fixed, f"{x:.6e}", f" {fixed} "]
    body = fixed.lstrip("-")
    sign = "-" if fixed.startswith("-") else ""
    out.append(sign + "00" + body)
    if body.startswith("0."):
        out.append(sign + body[1:])  # .5
    if "." not in body:
        out.append(sign + body + ".")  # 5.
    if len(body) > 2 and body[:2].isdigit():
        out.append(sign + body[0] + "_" + body[1:])  # 1_500
    return out


def test_every_number_is_floats_own_reading_bit_for_bit():
    """Random values in each column's bounds, each spelled every way, read by the fast path (plain decimals as
    significand / 10^f) and by read_csv (``float`` of each field): the same doubles, -0.0 included."""
    rng = np.random.default_rng(20261204)
    lows, highs = (15.0, -12.0, -12.0, 5.0), (5000.0, 12.0, 12.0, 130.0)
    for trial in range(20):
        rows = []
        for i in range(300):
            values = [rng.uniform(lo, hi) for lo, hi in zip(lows, highs, strict=True)]
            if rng.random() < 0.2:
                values = [float(np.round(v, int(rng.integers(0, 4)))) for v in values]
            if rng.random() < 0.05:
                values[1] = -0.0
            cells = [str(rng.choice(_spellings(rng, v))) for v in values]
            rows.append(f"C{trial}-{i}," + ",".join(cells))
        text = HEADER + "\n" + "\n".join(rows) + "\n"
        fast = read_csv_columns(text, max_curves=1000)
        assert fast is not None
        same(fast, read_csv(text, max_curves=1000))
    # the longest plain decimals: 15 significant digits and up to 22 after the point, then 16 (float's own reading)
    for digits in ("123456789012345", "1234567890123456", "12345678901234567"):
        for point in range(1, len(digits)):
            text = f"id,radius_m,grade_percent\nA,100,{digits[:point]}.{digits[point:]}e-{len(digits) - 1}\n"
            text2 = f"id,radius_m,grade_percent\nA,100,0.{'0' * (22 - len(digits))}{digits}\n"
            for t in (text, text2):
                fast = read_csv_columns(t, max_curves=10)
                assert fast is not None
                same(fast, read_csv(t, max_curves=10))


@pytest.mark.parametrize("spell", [lambda x: f" {x}", lambda x: f"{x:.3e}", lambda x: f"{x}"])
def test_a_column_of_another_form_is_read_as_read_csv_reads_it(spell):
    """Spaces after the commas or exponents in every row (the column read by float over its strings at once), or
    plain decimals throughout: the same table either way; a column with one bad field among many is still refused."""
    rng = np.random.default_rng(7)
    rows = [f"C{i}," + ",".join(spell(float(np.round(rng.uniform(60, 900), 2))) for _ in range(1)) for i in range(500)]
    text = "id,radius_m\n" + "\n".join(rows) + "\n"
    fast = read_csv_columns(text, max_curves=1000)
    assert fast is not None
    same(fast, read_csv(text, max_curves=1000))
    assert read_csv_columns(text.replace(rows[250] + "\n", rows[250] + "x\n"), max_curves=1000) is None

"""Decimal numbers read from text as bytes, a character position at a time over a whole column of fields: the
numeric fast path of the columnar readers of curves (:mod:`app.jobs.csv_columns` for CSV text,
:mod:`app.alignments.json_curves` for a JSON list).

A field of the plain decimal form ``[+-]digits[.digits]`` with at most 15 significant digits is its integer
significand M, read exactly, divided by 10^f (f its digits after the point, at most 22): both are exact doubles, so
IEEE division rounds the quotient correctly, and that is the double ``float`` (and ``orjson``) returns for the text,
bit for bit (Clinger 1990, "How to read floating point numbers accurately", PLDI '90, the fast path; Python's
``float`` rounds correctly, Gay's dtoa). The fields of any other form are marked, for the caller to read its own way.
"""

from __future__ import annotations

import numpy as np

_MINUS, _PLUS, _POINT, _ZERO = (ord(c) for c in "-+.0")
#: significant digits of the fast path: 10^15 < 2^53, so the significand is an exact double
_MAX_DIGITS = 15
_POWERS = 10.0 ** np.arange(23)  # 10^0 .. 10^22: exact doubles
_INTEGER_POWERS = 10 ** np.arange(19, dtype=np.int64)


def decimals(
    buf: np.ndarray, starts: np.ndarray, ends: np.ndarray, *, json: bool = False
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The fast path (the module's doc) over the fields ``buf[starts[i]:ends[i]]``, a character position at a time over
    all of them: ``(values, plain, integral)``, where ``plain`` marks the fields of the form ``[+-]digits[.digits]``
    (also ``digits.`` and ``.digits``) with at most 15 significant digits, whose ``values`` are ``float``'s bit for bit
    (Clinger's fast path), and ``integral`` those without a point. The other fields' values are meaningless: the caller
    reads them its own way (CSV with ``float``, JSON with ``orjson``). ``json``: only JSON's numbers are plain
    (``-?(0|[1-9]digits)(.digits)?``: no ``+``, no leading zero, a digit on both sides of the point), for
    :mod:`app.alignments.json_curves`."""
    n = starts.size
    lens = ends - starts
    width = min(int(lens.max(initial=0)), _MAX_DIGITS + 2)  # the sign and the point besides the digits
    last = max(buf.size - 1, 0)
    significand = np.zeros(n, dtype=np.int64)
    digits = np.zeros(n, dtype=np.int8)
    before = np.zeros(n, dtype=np.int8)  # the digits before the point (of a field with a point)
    points = np.zeros(n, dtype=np.int8)
    first = buf[np.minimum(starts, last)]
    negative = first == _MINUS
    signed = negative | (first == _PLUS)
    clamp = n > 0 and int(starts.max()) + width > buf.size  # a field near the end: keep the look-ups inside
    at = starts.copy()
    for j in range(width):  # in place, no temporary of the significands: a column is millions of fields
        c = buf[np.minimum(at, last)] if clamp else buf[at]
        inside = lens > j
        d = c - np.uint8(_ZERO)  # a byte below '0' wraps to above 9
        digit = d < 10
        digit &= inside
        np.multiply(significand, 10, out=significand, where=digit)
        np.add(significand, d, out=significand, where=digit)
        digits += digit
        point = c == _POINT
        point &= inside
        points += point
        np.copyto(before, digits, where=point)
        at += 1
    plain = (
        (lens <= width) & (points <= 1) & (digits >= 1) & (digits <= _MAX_DIGITS) & (digits + points + signed == lens)
    )
    if json:
        plain &= negative | ~signed
        plain &= (points == 0) | ((before > 0) & (digits > before))
        integer = np.where(points > 0, before, digits)  # no leading zero: the first digit is one when there are two
        plain &= (integer <= 1) | (significand >= _INTEGER_POWERS[np.maximum(digits - 1, 0)])
    fraction = np.where(points > 0, digits - before, 0)  # digits after the point: <= width <= 17
    values = significand / _POWERS[fraction]
    np.negative(values, out=values, where=negative)  # -0 is -0.0, as float("-0")
    return values, plain, points == 0

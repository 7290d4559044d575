"""Texts kept as one UTF-8 blob (app.formats.texts: a job part's curve ids): read back checked, and written into
the answers as slices of the blob exactly as the list of strings is written (app.alignments.rows: CSV fields and
JSON strings), for ids of every kind: plain, several bytes a character, a quote, a backslash, a formula prefix."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from app.alignments.rows import _csv_ids, _json_ids
from app.formats.segments import Slices, write_rows
from app.formats.texts import Texts, TextsError

# the curve id's alphabet (app.formats.alignment_io.CURVE_ID_PATTERN: no control characters), weighted to the odd
_ID = st.text(
    alphabet=st.one_of(st.sampled_from("\"\\=+-@ ,;'aZ09äé曲🚛"), st.characters(blacklist_categories=("Cc", "Cs"))),
    min_size=1,
    max_size=8,
)


@settings(max_examples=200, deadline=None)
@given(st.lists(_ID, max_size=12), st.integers(0, 12), st.integers(0, 12))
def test_texts_read_back_and_slice_as_the_list(ids, a, b):
    texts = Texts.of(ids)
    assert list(texts) == ids and len(texts) == len(ids) and texts == ids
    assert list(texts[a:b]) == ids[a:b] and [texts[i] for i in range(len(ids))] == ids
    blob, ends = texts[a:b].stored()  # a slice stored on its own: its ranges from zero
    again = Texts.read(blob.tobytes(), ends, len(ids[a:b]))
    assert list(again) == ids[a:b] and Texts.of(texts[a:b]).blob == "".join(ids[a:b]).encode()


@settings(max_examples=200, deadline=None)
@given(st.lists(_ID, min_size=1, max_size=12))
def test_ids_from_the_blob_are_written_as_the_list_is(ids):
    """CSV fields and JSON strings of the ids: the same bytes from a Texts as from the list; slices of the blob
    where no id needs an escape (or, in CSV, a formula prefix neutralised)."""
    n = len(ids)
    texts = Texts.of(ids)
    for write in (_csv_ids, _json_ids):
        from_list, from_blob = write(ids), write(texts)
        as_tuple = from_list if isinstance(from_list, tuple) else (from_list,)
        blob_tuple = from_blob if isinstance(from_blob, tuple) else (from_blob,)
        assert write_rows([*blob_tuple, b"\n"], n) == write_rows([*as_tuple, b"\n"], n)
        plain = not any(c in '"\\' for i in ids for c in i) and not any(i[0] in "=+-@" for i in ids)
        if plain:
            assert any(isinstance(s, Slices) for s in blob_tuple), write.__name__


def test_a_stored_column_that_is_not_texts_is_refused():
    blob, ends = Texts.of(["ab", "ä", "c"]).stored()
    assert list(Texts.read(blob.tobytes(), ends, 3)) == ["ab", "ä", "c"]
    with pytest.raises(TextsError, match="3 ends for 2 texts"):
        Texts.read(blob.tobytes(), ends, 2)
    with pytest.raises(TextsError, match="do not run through the blob"):
        Texts.read(blob.tobytes() + b"x", ends, 3)
    with pytest.raises(TextsError, match="do not run through the blob"):
        Texts.read(blob.tobytes(), np.array([3, 2, 5]), 3)
    with pytest.raises(TextsError, match="inside a character"):
        Texts.read(blob.tobytes(), np.array([2, 3, 5]), 3)  # "ä" is two bytes: 2..4
    with pytest.raises(TextsError, match="not UTF-8"):
        Texts.read(b"ab\xff", np.array([2, 3]), 2)
    with pytest.raises(TextsError, match="bytes without a text"):
        Texts.read(b"ab", np.array([], dtype=np.int64), 0)

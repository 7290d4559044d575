"""scripts/docblock.py: the generated blocks of the docs, replaced between their markers and nowhere else."""

from __future__ import annotations

import re

import pytest

from scripts.docblock import markers, replace_block, split_block, write_block
from tests.api.conftest import ROOT

START, END = markers("x")


def test_a_block_is_replaced_between_its_markers_and_the_rest_kept():
    text = f"before\n{START}\nold\nlines\n{END}\nafter {START} is not read twice"
    out = replace_block(text, START, END, "new")
    assert out == f"before\n{START}\nnew\n{END}\nafter {START} is not read twice"
    assert split_block(out, START, END) == ("before\n", "\nnew\n", f"\nafter {START} is not read twice")


@pytest.mark.parametrize("text", ["no markers", f"{START} only the start", f"{END} the end before {START}"])
def test_a_doc_without_its_block_is_a_value_error_naming_the_markers(text):
    with pytest.raises(ValueError, match=re.escape(f"no {START} ... {END} block")):
        replace_block(text, START, END, "new")


def test_write_block_rewrites_the_file_in_place(tmp_path):
    doc = tmp_path / "doc.md"
    doc.write_text(f"# T\n{START}\n{END}\n", encoding="utf-8")
    write_block(doc, START, END, "| a |")
    assert doc.read_text(encoding="utf-8") == f"# T\n{START}\n| a |\n{END}\n"


@pytest.mark.parametrize(
    ("doc", "name"),
    [
        ("docs/routes.md", "bench_routes"),
        ("docs/routes.md", "bench_routes_accuracy"),
        ("docs/routes.md", "route_accuracy_correlated"),
        ("docs/performance.md", "bench_service"),
    ],
)
def test_every_generated_block_the_benches_write_is_in_its_doc(doc, name):
    _, block, _ = split_block((ROOT / doc).read_text(encoding="utf-8"), *markers(name))
    assert block.strip(), f"{doc}: the {name} block is empty (run its bench with --write)"

"""A generated block of a doc, between its two marker comments (``<!-- name:start -->`` ... ``<!-- name:end -->``):
read and replaced by the scripts and benches that write figures and examples into the docs, so a doc quotes only
what a script of the repository printed."""

from __future__ import annotations

import os
import platform
from pathlib import Path


def machine() -> str:
    """The CPU model, its cores and the load average when the run started (the machine may be shared): what a bench
    writes beside the figures it puts in a doc."""
    model = platform.processor() or platform.machine()
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    return f"{model}, {os.cpu_count()} cores, load {load:.1f}"


def markers(name: str) -> tuple[str, str]:
    """The start and end markers of the block ``name``."""
    return f"<!-- {name}:start -->", f"<!-- {name}:end -->"


def split_block(text: str, start: str, end: str) -> tuple[str, str, str]:
    """(what comes before ``start``, the block between the markers, what comes after ``end``); the markers themselves
    in none of them. A :class:`ValueError` naming them when the text lacks either (a doc whose block was removed)."""
    head, found, rest = text.partition(start)
    block, found_end, tail = rest.partition(end)
    if not found or not found_end:
        raise ValueError(f"no {start} ... {end} block")
    return head, block, tail


def replace_block(text: str, start: str, end: str, block: str) -> str:
    """``text`` with the block between the markers replaced by ``block`` (on lines of its own)."""
    head, _, tail = split_block(text, start, end)
    return f"{head}{start}\n{block}\n{end}{tail}"


def write_block(path: Path, start: str, end: str, block: str) -> None:
    """:func:`replace_block` of the file at ``path``, in place."""
    path.write_text(replace_block(path.read_text(encoding="utf-8"), start, end, block), encoding="utf-8")

"""Comparing two answers (dicts, lists, numbers) that may differ only by rounding."""

from __future__ import annotations

from typing import Any

import pytest


def assert_same_to_rounding(a: Any, b: Any, rel: float = 1e-12, path: str = "answer") -> None:
    """The same structure, keys in the same order and the same types; floats equal to ``rel`` (relative, or
    absolute near zero), everything else exactly. For answers of two code paths that compute the same numbers (the
    array and the one-case solves may differ in a last bit on some CPUs)."""
    assert type(a) is type(b), path
    if isinstance(a, dict):
        assert list(a) == list(b), path
        for k in a:
            assert_same_to_rounding(a[k], b[k], rel, f"{path}.{k}")
    elif isinstance(a, list):
        assert len(a) == len(b), path
        for k, (x, y) in enumerate(zip(a, b, strict=True)):
            assert_same_to_rounding(x, y, rel, f"{path}[{k}]")
    elif isinstance(a, float):
        assert a == pytest.approx(b, rel=rel, abs=rel), path
    else:
        assert a == b, path

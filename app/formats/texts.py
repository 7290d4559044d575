"""A column of texts held as one UTF-8 blob and each text's byte range: what a job's part stores its curve ids as.

A million ids as a list are a million Python strings: about 0.1 s to parse from JSON and check, for each read of a
part, and as much again to write them into the answer. As :class:`Texts` they are read with no Python object per
id (two numpy views of the stored bytes, checked in a few vectorised passes) and written into the answer as slices
of the blob (:class:`app.formats.segments.Slices`). A :class:`Texts` is a ``Sequence[str]`` (a text is decoded when
it is asked for), so code that wants strings still gets them.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from typing import overload

import numpy as np


class TextsError(ValueError):
    """A blob and ranges that are not a column of UTF-8 texts (truncated, overlapping, cut inside a character)."""


class Texts(Sequence[str]):
    """Texts ``blob[starts[i]:ends[i]]`` (UTF-8)."""

    __slots__ = ("blob", "ends", "starts")

    def __init__(self, blob: bytes, starts: np.ndarray, ends: np.ndarray) -> None:
        self.blob, self.starts, self.ends = blob, starts, ends

    @classmethod
    def of(cls, texts: Sequence[str]) -> Texts:
        """``texts`` as one blob (a :class:`Texts` as it is, its ranges made to start at zero)."""
        if isinstance(texts, Texts):
            lengths = texts.ends - texts.starts
            if len(texts) and texts.ends[-1] - texts.starts[0] == lengths.sum():  # contiguous: one slice
                a, b = int(texts.starts[0]), int(texts.ends[-1])
                ends = np.cumsum(lengths)
                return cls(bytes(texts.blob[a:b]), ends - lengths, ends)
            texts = list(texts)
        joined = "".join(texts)
        blob = joined.encode()
        if len(blob) == len(joined):  # ASCII: a character a byte
            lengths = np.fromiter(map(len, texts), dtype=np.int64, count=len(texts))
        else:
            lengths = np.fromiter((len(t.encode()) for t in texts), dtype=np.int64, count=len(texts))
        ends = np.cumsum(lengths)
        return cls(blob, ends - lengths, ends)

    @classmethod
    def read(cls, blob: bytes | memoryview, ends: np.ndarray, n: int) -> Texts:
        """The column stored as ``blob`` and each text's end (the texts one after the other), checked: ``n`` ends,
        non-decreasing, the last at the blob's end, the blob UTF-8 and every end on a character's boundary (raises
        :class:`TextsError`)."""
        blob = bytes(blob)
        if ends.shape != (n,):
            raise TextsError(f"{ends.size} ends for {n} texts")
        ends = ends.astype(np.int64, copy=False)
        if n and (ends[0] < 0 or ends[-1] != len(blob) or np.any(ends[1:] < ends[:-1])):
            raise TextsError("the texts' ends do not run through the blob in order")
        if not n and blob:
            raise TextsError("bytes without a text")
        try:
            blob.decode()
        except UnicodeDecodeError as exc:
            raise TextsError(f"the texts are not UTF-8: {exc.reason} at byte {exc.start}") from None
        inner = ends[ends < len(blob)]
        if inner.size and np.any((np.frombuffer(blob, np.uint8)[inner] & 0xC0) == 0x80):
            raise TextsError("a text ends inside a character")
        starts = np.empty_like(ends)
        starts[:1] = 0
        starts[1:] = ends[:-1]
        return cls(blob, starts, ends)

    def stored(self) -> tuple[np.ndarray, np.ndarray]:
        """(blob as uint8, ends): the column as :meth:`read` takes it back."""
        t = Texts.of(self)
        return np.frombuffer(t.blob, dtype=np.uint8), t.ends

    def __len__(self) -> int:
        return len(self.starts)

    @overload
    def __getitem__(self, i: int) -> str: ...
    @overload
    def __getitem__(self, i: slice) -> Texts: ...
    def __getitem__(self, i: int | slice) -> str | Texts:
        if isinstance(i, slice):
            return Texts(self.blob, self.starts[i], self.ends[i])
        return self.blob[self.starts[i] : self.ends[i]].decode()

    def __iter__(self) -> Iterator[str]:
        blob = self.blob
        for a, b in zip(self.starts.tolist(), self.ends.tolist(), strict=True):
            yield blob[a:b].decode()

    def __eq__(self, other: object) -> bool:
        if isinstance(other, Sequence) and not isinstance(other, str | bytes):
            return len(self) == len(other) and all(a == b for a, b in zip(self, other, strict=True))
        return NotImplemented

    __hash__ = None  # type: ignore[assignment]  (mutable views: not hashable, as a list)

    def __repr__(self) -> str:
        shown = ", ".join(map(repr, self[:3]))
        return f"Texts([{shown}{', ...' if len(self) > 3 else ''}] ({len(self)}))"

    def span(self) -> np.ndarray:
        """The blob's bytes from the first text's start to the last one's end, as uint8 (every byte of the texts,
        and of nothing else where they follow one another, as a column's slice does)."""
        if not len(self):
            return np.zeros(0, dtype=np.uint8)
        return np.frombuffer(self.blob, np.uint8)[int(self.starts.min()) : int(self.ends.max())]

    def first_bytes(self) -> np.ndarray:
        """Each non-empty text's first byte."""
        nonempty = self.starts < self.ends
        return np.frombuffer(self.blob, np.uint8)[self.starts[nonempty]]

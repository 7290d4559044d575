"""app.jobs.router.prefetched: a job result's pieces rendered one ahead of the sending, in order, errors after the
pieces before them, nothing rendered past a client that went away."""

from __future__ import annotations

import asyncio
import threading

import pytest

from app.jobs.router import prefetched


def _collect(chunks, take: int | None = None) -> list[bytes]:
    async def run() -> list[bytes]:
        out, stream = [], prefetched(chunks)
        async for piece in stream:
            out.append(piece)
            if take is not None and len(out) == take:
                await stream.aclose()  # what the server does when the client goes away
                break
        return out

    return asyncio.run(run())


def test_the_pieces_come_in_order_and_all_of_them():
    pieces = [bytes([k]) * (k + 1) for k in range(50)]
    assert _collect(iter(pieces)) == pieces
    assert _collect(iter([])) == []


def test_the_next_piece_renders_while_the_current_one_is_sent():
    """When piece k reaches the sender, piece k+1 has been asked for already (rendering and sending overlap)."""
    asked: list[int] = []

    def render():
        for k in range(5):
            asked.append(k)
            yield str(k).encode()

    async def run() -> list[tuple[bytes, int]]:
        seen = []
        async for piece in prefetched(render()):
            k = int(piece)
            for _ in range(5000):  # a slow socket: the next piece is asked for while this one is still held
                if len(asked) >= min(k + 2, 5):
                    break
                await asyncio.sleep(0.001)
            await asyncio.sleep(0.01)  # and no further piece after it
            seen.append((piece, len(asked)))
        return seen

    seen = asyncio.run(run())
    assert [p for p, _ in seen] == [b"0", b"1", b"2", b"3", b"4"]
    assert [n for _, n in seen[:-1]] == [2, 3, 4, 5]  # one ahead, never more


def test_an_error_in_the_rendering_comes_after_the_pieces_before_it():
    def render():
        yield b"a"
        yield b"b"
        raise ValueError("a stored fragment does not verify")

    got: list[bytes] = []

    async def run() -> None:
        async for piece in prefetched(render()):
            got.append(piece)

    with pytest.raises(ValueError, match="does not verify"):
        asyncio.run(run())
    assert got == [b"a", b"b"]


def test_a_client_that_goes_away_stops_the_rendering_after_the_piece_in_progress():
    rendered: list[int] = []
    release = threading.Event()

    def render():
        for k in range(100):
            if k == 2:
                release.wait(5)  # the piece in progress when the client leaves
            rendered.append(k)
            yield b"x"

    def leave_later() -> None:
        release.set()

    threading.Timer(0.1, leave_later).start()
    assert _collect(render(), take=2) == [b"x", b"x"]
    assert rendered == [0, 1, 2]  # the third finished (it was running), nothing after it

"""Concurrent uncached SRT requests solved together (app.compute.coalescer): the same answers as alone, refusals per
request."""

from __future__ import annotations

import asyncio

import httpx

import app.compute.coalescer as coalesce
from app.main import create_app
from app.settings import Settings
from engine.case import Case, Road
from engine.errors import InvalidInput
from engine.models.threshold import MIN_ARRAY_CASES, rollover_threshold
from engine.vehicle.presets import PRESETS
from tests.compare import assert_same_to_rounding

from .conftest import make_client

BTRAIN = PRESETS["table16-btrain"]


def _bodies() -> list[dict]:
    bodies = [{"vehicle": "table16-btrain", "road": {"bank_percent": -5 + 0.37 * k}} for k in range(40)]
    bodies += [{"vehicle": "table15-semitrailer", "road": {"bank_percent": 0.5 * k}} for k in range(3)]
    bodies.append(  # tips at rest: a 422 for this request only
        {"vehicle": "table16-btrain", "road": {"bank_percent": -14.0}, "load": {"lateral_offset_m": 0.5}}
    )
    bodies.append({"vehicle": "table16-btrain", "model": "2d", "road": {"bank_percent": 2.0}})
    return bodies


async def _all_at_once(bodies: list[dict]) -> list[httpx.Response]:
    app = create_app(Settings(cache_backend="memory"))
    async with app.router.lifespan_context(app):
        transport = httpx.ASGITransport(app=app)
        async with httpx.AsyncClient(transport=transport, base_url="http://test") as c:
            return await asyncio.gather(*(c.post("/v1/srt", json=b) for b in bodies))


def test_concurrent_misses_are_solved_together_and_answer_as_alone(monkeypatch):
    sizes = []
    real = coalesce.rollover_thresholds
    monkeypatch.setattr(coalesce, "rollover_thresholds", lambda cases: sizes.append(len(cases)) or real(cases))
    bodies = _bodies()
    together = asyncio.run(_all_at_once(bodies))
    # handed over together, each once, and with them the level-road cases their targets are judged on, each once
    # however many requests need it: the B-train's in 3d and in 2d (the semitrailer's level case is a request's own)
    assert max(sizes) >= MIN_ARRAY_CASES and sum(sizes) == len(bodies) + 2
    with make_client() as c:  # each request alone, on a fresh app
        for body, got in zip(bodies, together, strict=True):
            alone = c.post("/v1/srt", json=body)
            assert got.status_code == alone.status_code, body
            assert got.status_code != 200 or got.headers["x-cache"] == "miss"
            if alone.status_code == 200:
                assert_same_to_rounding(got.json(), alone.json())
                assert got.headers["etag"] == alone.headers["etag"]
            else:  # the refusal of this request only, with its field
                assert got.status_code == 422 and got.json() == alone.json()
    assert sum(r.status_code == 200 for r in together) == len(bodies) - 1


def _run(coroutine):
    return asyncio.run(asyncio.wait_for(coroutine, timeout=60))


def test_a_waiter_that_left_is_not_solved_and_the_others_are_answered(monkeypatch):
    sizes = []
    real = coalesce.rollover_thresholds
    monkeypatch.setattr(coalesce, "rollover_thresholds", lambda cases: sizes.append(len(cases)) or real(cases))
    cases = [Case(BTRAIN, road=Road(bank_percent=float(b))) for b in (1, 2, 3)]

    async def main():
        co = coalesce.SolveCoalescer()
        tasks = [asyncio.create_task(co.threshold(c)) for c in cases]
        await asyncio.sleep(0)  # all three wait on the coalescer
        tasks[1].cancel()
        done = await asyncio.gather(*tasks, return_exceptions=True)
        return done

    first, second, third = _run(main())
    assert isinstance(second, asyncio.CancelledError) and sizes == [2]
    assert first == rollover_threshold(cases[0]) and third == rollover_threshold(cases[2])


def test_an_engine_defect_fails_every_waiter_and_none_waits_forever(monkeypatch):
    def broken(cases):
        raise RuntimeError("a defect")

    monkeypatch.setattr(coalesce, "rollover_thresholds", broken)

    async def main():
        co = coalesce.SolveCoalescer()
        return await asyncio.gather(*(co.threshold(Case(BTRAIN)) for _ in range(3)), return_exceptions=True)

    assert [type(r) for r in _run(main())] == [RuntimeError] * 3


def test_a_defect_in_one_case_fails_only_its_request(monkeypatch):
    import engine.models.threshold

    real = engine.models.threshold.rollover_threshold

    def broken_at_3(case, **kwargs):
        if case.road.bank_percent == 3.0:
            raise RuntimeError("a defect in one case")
        return real(case, **kwargs)

    monkeypatch.setattr(engine.models.threshold, "rollover_threshold", broken_at_3)
    cases = [Case(PRESETS["table14-semitrailer"], model="2d", road=Road(bank_percent=float(b))) for b in range(6)]

    async def main():
        co = coalesce.SolveCoalescer()
        return await asyncio.gather(*(co.threshold(c) for c in cases), return_exceptions=True)

    results = _run(main())
    assert [type(r) for r in results].count(RuntimeError) == 1 and isinstance(results[3], RuntimeError)
    assert [r.srt for k, r in enumerate(results) if k != 3] == [real(c).srt for k, c in enumerate(cases) if k != 3]


def test_a_refused_case_raises_its_own_error_and_a_flush_takes_at_most_max_flush(monkeypatch):
    sizes = []
    real = coalesce.rollover_thresholds
    monkeypatch.setattr(coalesce, "rollover_thresholds", lambda cases: sizes.append(len(cases)) or real(cases))
    n = 2 * coalesce.MAX_FLUSH + 5
    cases = [Case(BTRAIN, road=Road(bank_percent=-4 + 10 * k / n)) for k in range(n)]
    cases[7] = Case(BTRAIN, road=Road(bank_percent=-14.0), load=cases[7].load.__class__(lateral_offset_m=0.5))

    async def main():
        co = coalesce.SolveCoalescer()
        return await asyncio.gather(*(co.threshold(c) for c in cases), return_exceptions=True)

    results = _run(main())
    assert sizes == [coalesce.MAX_FLUSH, coalesce.MAX_FLUSH, 5]
    assert isinstance(results[7], InvalidInput) and results[7].field == "road.bank_percent"
    # the batch is solved on numpy arrays, the reference one case at a time (a last bit may differ on some CPUs)
    assert_same_to_rounding(
        [r.srt for k, r in enumerate(results) if k != 7],
        [rollover_threshold(c).srt for k, c in enumerate(cases) if k != 7],
    )


def test_the_batch_sizes_are_a_metric():
    with make_client() as c:
        assert (
            c.post("/v1/srt", json={"vehicle": "table16-btrain", "road": {"bank_percent": 1.2345}}).status_code == 200
        )
        text = c.get("/metrics").text
    count = [line for line in text.splitlines() if line.startswith("rollover_solve_batch_cases_count ")]
    assert len(count) == 1 and float(count[0].split()[1]) >= 1

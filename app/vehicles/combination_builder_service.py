"""The combination builder for the service: ``POST /v1/combinations/build`` and ``{"combination_spec": ...}``.

:func:`app.vehicle_forms.build.build_combination_spec` is the one place that builds a combination spec for the
service (the build endpoint, a ``{"combination_spec": ...}`` vehicle in any computation, a saved one).
"""

from __future__ import annotations

from starlette.concurrency import run_in_threadpool

from app.compute.cache import ResultCache
from app.compute.resolved import ResolvedBuild
from app.compute.results import Computed, cached
from app.vehicle_forms.build import build_combination_spec
from app.vehicle_forms.combination_builder_schemas import BuildCombinationRequest, BuildCombinationResult
from engine.builder import BuiltCombination


def build_combination_result(built: BuiltCombination) -> BuildCombinationResult:
    out = built.to_dict()
    out["derivation"] = {k: {n: v for n, v in d.items() if n != "field"} for k, d in out["derivation"].items()}
    return BuildCombinationResult.model_validate(out)


async def compute_combination_build(cache: ResultCache, req: BuildCombinationRequest) -> Computed:
    spec = req.engine_spec()
    resolved = ResolvedBuild(spec=spec)  # every input, defaults filled; the library is the engine's

    async def produce() -> bytes:
        built = await run_in_threadpool(build_combination_spec, spec)
        return build_combination_result(built).model_dump_json().encode()

    return await cached(cache, "combination-build", resolved, produce)

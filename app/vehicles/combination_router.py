"""GET /v1/combinations and GET /v1/combinations/{id}: the combination presets, each value with its source;
POST /v1/combinations/build: a combination from what can be measured of each unit."""

from __future__ import annotations

from typing import Annotated

from fastapi import APIRouter, Path, Response

from app.deps import CacheDep
from app.http.fastpath import replayable
from app.http.problems import Problem, error_responses
from app.http.responses import computed_responses, json_response
from app.vehicle_forms.combination_builder_schemas import BuildCombinationRequest, BuildCombinationResult
from app.vehicle_forms.combination_schemas import CombinationPreset, CombinationPresetSummary
from app.vehicles.combination_builder_service import compute_combination_build
from engine.models import supported_models
from engine.vehicle import COMBINATION_INFO, COMBINATION_SOURCES, COMBINATIONS, get_combination, roll_coupled_units

router = APIRouter(prefix="/v1/combinations", tags=["combinations"])


def _summary(cid: str) -> dict:
    c, info = get_combination(cid), COMBINATION_INFO[cid]
    return {
        "id": cid,
        "title": info.title,
        "summary": info.summary,
        "units": [u.kind for u in c.units],
        "roll_coupled_units": [[c.units[i].id for i in rcu] for rcu in roll_coupled_units(c)],
        "models": supported_models(c),
    }


@router.get("", response_model=list[CombinationPresetSummary], responses=error_responses(500))
def list_combinations() -> list[CombinationPresetSummary]:
    """The combination presets: the thesis's trailers behind sourced towing units, and two doubles."""
    return [CombinationPresetSummary(**_summary(cid)) for cid in COMBINATIONS]


@router.get(
    "/{id}",
    response_model=CombinationPreset,
    responses={
        **error_responses(422, 500),
        404: {"model": Problem, "description": "Unknown combination preset (the problem lists the known ids)."},
    },
)  # fmt: skip
def get_combination_preset(
    id: Annotated[str, Path(description="Combination preset id, e.g. `btrain-table16`.", examples=["btrain-table16"])],
) -> CombinationPreset:
    """One combination preset in full (usable as `{"combination": ...}` after editing), with the source of each
    value: the thesis's tables, the TruckSim example database, derived values, or "assumed" and why."""
    c = get_combination(id)  # UnknownPreset -> 404 listing the known ids
    return CombinationPreset(**_summary(id), combination=c.to_dict()["combination"], sources=COMBINATION_SOURCES[id])


@router.post(
    "/build",
    name="build_combination",
    response_model=BuildCombinationResult,
    responses=computed_responses(400, 404, 422, 500),
)
@replayable("combination-build")
async def build_combination(body: BuildCombinationRequest, cache: CacheDep) -> Response:
    """The whole-combination record a measurable spec describes: each unit (tractor, rigid truck, semitrailer,
    B-train lead trailer, converter dolly, full trailer) with its axle groups (tyre size, suspension type from the
    roll component library, or explicit values), tare and payloads (CG heights, or deck and load heights), and the
    couplings (fifth wheel by its library id, B-coupling, pintle or an A-dolly's ball). Answers the record, where
    every component value comes from, each unit's mass, sprung mass and CG, and the static axle loads. The same spec
    is accepted as `"vehicle": {"combination_spec": {...}}` by every computation. A spec that cannot be is a 422
    naming the spec field as typed, with the likely unit slip (docs/vehicles.md)."""
    return json_response(await compute_combination_build(cache, body))

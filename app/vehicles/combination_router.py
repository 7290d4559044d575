"""GET /v1/combinations and GET /v1/combinations/{id}: the combination presets, each value with its source."""

from __future__ import annotations

from typing import Annotated

from fastapi import APIRouter, Path

from app.http.problems import Problem, error_responses
from app.vehicles.combination_schemas import CombinationPreset, CombinationPresetSummary
from engine.models import supported_models
from engine.vehicle import COMBINATION_INFO, COMBINATION_SOURCES, COMBINATIONS, get_combination
from engine.vehicle.combination import roll_coupled_units

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

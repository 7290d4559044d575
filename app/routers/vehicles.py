"""GET /v1/vehicles and GET /v1/vehicles/{id}: the thesis presets as full vehicle records."""

from __future__ import annotations

from typing import Annotated

from fastapi import APIRouter, Path

from engine.models import supported_models
from engine.vehicles import PRESET_INFO, PRESETS, get_preset

from ..problems import error_responses
from ..schemas.vehicles import VehiclePreset

router = APIRouter(prefix="/v1/vehicles", tags=["vehicles"])


def _preset(preset_id: str) -> VehiclePreset:
    info, vehicle = PRESET_INFO[preset_id], get_preset(preset_id)
    return VehiclePreset(
        id=preset_id, title=info.title, source=info.source, models=supported_models(vehicle), **vehicle.to_dict()
    )


@router.get("", response_model=list[VehiclePreset], responses=error_responses(500))
def list_vehicles() -> list[VehiclePreset]:
    """The thesis presets (Tables 14, 15, 16, 22, 23), each as its full vehicle record."""
    return [_preset(p) for p in PRESETS]


@router.get("/{id}", response_model=VehiclePreset, responses=error_responses(404, 422, 500))
def get_vehicle(
    id: Annotated[str, Path(description="Preset id, e.g. `table16-btrain`.", examples=["table16-btrain"])],
) -> VehiclePreset:
    """One preset as its full vehicle record (fields the table does not give are null)."""
    get_preset(id)  # UnknownPreset -> 404 problem listing the known ids
    return _preset(id)

"""GET /v1/vehicles and GET /v1/vehicles/{id}: the thesis presets as full vehicle records, and (with the owner's
bearer key) a saved vehicle by its ``veh_...`` id. Saving, changing, listing saved vehicles: ``app.catalog.router``.
"""

from __future__ import annotations

from typing import Annotated

from fastapi import APIRouter, Path, Request, Response

from app.catalog import service as catalog
from app.catalog.auth import BearerDep, authenticate
from app.catalog.router import problem_responses
from app.catalog.schemas import SavedVehicle
from app.deps import SettingsDep
from app.http.problems import Problem, error_responses
from app.vehicle_forms.schemas import VehiclePreset
from engine.models import supported_models
from engine.vehicle import PRESET_INFO, PRESETS, get_preset

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


@router.get(
    "/{id}",
    response_model=VehiclePreset | SavedVehicle,
    responses={
        200: {
            "headers": {
                "ETag": {"description": 'For a saved vehicle: its version (`"3"`).', "schema": {"type": "string"}}
            }
        },
        **error_responses(422, 500),
        404: {
            "model": Problem,
            "description": "Unknown vehicle preset (the problem lists the known ids), or no saved vehicle with this "
            "id for this key (missing, deleted or another key's).",
        },
        **problem_responses(401, 403, 409, 503),
    },
    openapi_extra={"security": [{}]},  # the bearer key is optional: presets are public
)
async def get_vehicle(
    id: Annotated[
        str,
        Path(
            description="Preset id, e.g. `table16-btrain` (public), or a saved vehicle's id `veh_...` (needs the "
            "key that saved it: `Authorization: Bearer <key>`; another key gets 404).",
            examples=["table16-btrain"],
        ),
    ],
    request: Request,
    credentials: BearerDep,
    settings: SettingsDep,
) -> VehiclePreset | Response:
    """One preset as its full vehicle record (fields the table does not give are null), or one of the caller's
    saved vehicles with its `ETag`."""
    if not id.startswith(catalog.SAVED_VEHICLE_PREFIX):
        get_preset(id)  # UnknownPreset -> 404 problem listing the known ids
        return _preset(id)
    catalog.check_saved_vehicle_id(id)
    owner = authenticate(credentials, settings)
    saved = await catalog.read_vehicle(await catalog.catalog_db(request), owner, id)
    return Response(
        saved.model_dump_json().encode(), media_type="application/json", headers={"ETag": catalog.etag(saved.version)}
    )

"""POST /v1/srt: static rollover threshold."""

from __future__ import annotations

from fastapi import APIRouter, Response

from ..deps import CacheDep, SettingsDep
from ..schemas.srt import SrtRequest, SrtResult
from ..service import compute_srt, resolve_srt, resolve_targets
from .common import computed_responses, json_response

router = APIRouter(prefix="/v1", tags=["srt"])


@router.post("/srt", name="compute_srt", response_model=SrtResult, responses=computed_responses(400, 404, 422, 500))
async def srt(body: SrtRequest, cache: CacheDep, settings: SettingsDep) -> Response:
    """Static rollover threshold (g) of a vehicle on a road with a load case, the roll angle, the stage values,
    the state at the limit and, with `include_curves`, the curves against ay/g; whether the SRT meets each
    target (`targets`, default 0.35 g general and 0.40 g dangerous goods) and its tilt-table angle atan(SRT)."""
    resolved = resolve_srt(
        body,
        targets=resolve_targets(body.targets, settings),
        include_curves=body.include_curves,
        curve_points=body.curve_points,
    )
    return json_response(await compute_srt(cache, resolved))

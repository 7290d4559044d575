"""POST /v1/alignments/assess: safe speeds on the horizontal curves of a road alignment."""

from __future__ import annotations

from fastapi import APIRouter, Request, Response

from ..deps import CacheDep, SettingsDep
from ..schemas.alignments import AlignmentRequest, AlignmentResult
from ..service_alignments import compute_alignment
from ..tables import wants_csv
from .common import computed_response, table_responses

router = APIRouter(prefix="/v1/alignments", tags=["alignments"])


@router.post("/assess", name="assess", response_model=AlignmentResult, responses=table_responses(400, 404, 422, 500))
async def assess(body: AlignmentRequest, request: Request, cache: CacheDep, settings: SettingsDep) -> Response:
    """For each horizontal curve and each vehicle: the SRT on the curve's bank and grade, the rollover speed
    sqrt(127 SRT R) (Eq. 9.1), the side-friction speed sqrt(127 R (0.01 e + f)) with f from Table 21, the safe
    speed (the smaller) and which mechanism governs, and the margin against the posted speed, flagged when
    negative. Curves sharing superelevation and grade share one SRT solve. JSON, or CSV with `Accept: text/csv`
    (one row per vehicle and curve)."""
    csv = wants_csv(request.headers.get("accept"))
    return computed_response(await compute_alignment(cache, body, settings, csv=csv), vary_accept=True)

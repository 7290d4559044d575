"""GET /v1/models: the available models with their equation numbers and references."""

from __future__ import annotations

from fastapi import APIRouter

from app.http.problems import error_responses
from app.schemas.meta import ModelInfoOut
from engine.models import MODELS

router = APIRouter(prefix="/v1/models", tags=["models"])


@router.get("", response_model=list[ModelInfoOut], responses=error_responses(500))
def list_models() -> list[ModelInfoOut]:
    """Every model id accepted by `model`, with the thesis equations, the reference and the inputs it uses."""
    return [
        ModelInfoOut(
            id=m.id,
            name=m.name,
            equation=m.equation,
            reference=m.reference,
            takes=list(m.takes),
            summary=m.summary,
            curves=m.curves,
            default=m.id == "3d",
        )
        for m in MODELS.values()
    ]

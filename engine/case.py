"""One calculation case: the vehicle and the six inputs that determine its SRT.

Every public computation of the engine (:func:`engine.rollover_threshold`, the sweeps, the inverse limits, the
curve assessment) takes a :class:`Case`, and the HTTP layer derives its cache key from :meth:`Case.to_dict`, so
the inputs are written down once and the key can never miss one of them.

References
----------
Thesis Secs. 4.7 (load case), 6.2 (road), 9.1-9.2 (stages, lateral-load-transfer limit).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Any

from .domain import check
from .errors import InvalidInput
from .loads import LoadCase, Road
from .vehicles import Vehicle

#: the two stages of Ch. 9: the full system, and tires and suspension only
STAGES = ("full", "tires-suspension")


@dataclass(frozen=True)
class Case:
    """The vehicle, the model and the road/load case of one SRT.

    Parameters
    ----------
    vehicle : the vehicle record (:class:`engine.vehicles.Vehicle`)
    model : model id of :data:`engine.models.MODELS` (``"3d"`` by default) [-]
    stage : 3D only: ``"full"`` (tires, suspension, fifth wheel, chassis) or ``"tires-suspension"`` (the first
        stage of Ch. 9) [-]
    road : bank and slope (:class:`engine.loads.Road`) [%]
    trailer_angle_deg : psi, the angle between the last two units of the combination (3D only) [deg]
    load : CG offsets d1, d2, d3 and the overweight (:class:`engine.loads.LoadCase`) [m, %]
    rear_llt_limit : rear lateral load transfer at which the load ramp stops; 1 = rear inner tire lift-off
        (Eq. 2.5; Table 17 uses 0.6) [-]
    """

    vehicle: Vehicle
    model: str = "3d"
    stage: str = "full"
    road: Road = field(default_factory=Road)
    trailer_angle_deg: float = 0.0
    load: LoadCase = field(default_factory=LoadCase)
    rear_llt_limit: float = 1.0

    def replace(self, **changes: Any) -> Case:
        """A copy with some inputs changed (``case.replace(road=Road(bank_percent=6))``)."""
        return replace(self, **changes)

    def to_dict(self) -> dict[str, Any]:
        """Every input as plain JSON types (the canonical form the HTTP layer hashes into its cache key)."""
        return {
            "vehicle": self.vehicle.to_dict(),
            "model": self.model,
            "stage": self.stage,
            "road": {"bank_percent": self.road.bank_percent, "slope_percent": self.road.slope_percent},
            "trailer_angle_deg": self.trailer_angle_deg,
            "load": {
                "lateral_offset_m": self.load.lateral_offset_m,
                "longitudinal_offset_m": self.load.longitudinal_offset_m,
                "vertical_offset_m": self.load.vertical_offset_m,
                "overweight_percent": self.load.overweight_percent,
            },
            "rear_llt_limit": self.rear_llt_limit,
        }

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> Case:
        """The inverse of :meth:`to_dict` (the vehicle as a record dict)."""
        return cls(
            vehicle=Vehicle.from_dict(data["vehicle"]),
            model=data.get("model", "3d"),
            stage=data.get("stage", "full"),
            road=Road(**data.get("road", {})),
            trailer_angle_deg=data.get("trailer_angle_deg", 0.0),
            load=LoadCase(**data.get("load", {})),
            rear_llt_limit=data.get("rear_llt_limit", 1.0),
        )

    @property
    def weight_kn(self) -> float:
        """The weight in this case, W (1 + overweight/100) [kN]."""
        return self.load.weight_kn(self.vehicle.weight_kn)

    @property
    def kingpin_to_cg_m(self) -> float | None:
        """a - d2: the CG's distance behind the kingpin (front axle of a truck) in this case [m]."""
        a = self.vehicle.front_axle_to_cg_m
        return None if a is None else a - self.load.longitudinal_offset_m


def check_stage_and_limit(case: Case) -> None:
    """Refuse a stage the model does not have and a rear LLT limit outside (0, 1]."""
    if case.stage not in STAGES:
        raise InvalidInput(
            f"stage must be one of {', '.join(STAGES)}, got {case.stage!r}", field="stage", value=case.stage
        )
    if case.stage != "full" and case.model != "3d":
        raise InvalidInput("stage applies to the 3d model only", field="stage", value=case.stage)
    check("rear_llt_limit", case.rear_llt_limit)

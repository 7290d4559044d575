"""One calculation case: the vehicle and the six inputs that determine its SRT.

Every public computation of the engine (:func:`engine.rollover_threshold`, the sweeps, the inverse limits, the
curve assessment) takes a :class:`Case`, and the HTTP layer derives its cache key from :meth:`Case.to_dict`, so
the inputs are written down once and the key can never miss one of them.

References
----------
Thesis Secs. 4.7 (load case), 6.2 (road), 9.1-9.2 (stages, lateral-load-transfer limit).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Any

from engine.domain import check
from engine.errors import InvalidInput, InvalidLoad
from engine.vehicle.combination import Combination
from engine.vehicle.record import Vehicle

#: the CG may lie behind the rear group by up to a quarter wheelbase (Table 16 moves the B-train's load
#: 1.5 m rearward, 0.24 m behind its tridem); beyond that the kingpin uplift dominates the model
MAX_CG_BEHIND_REAR_GROUP = 1.25


@dataclass(frozen=True)
class Road:
    """Road geometry at the curve.

    bank_percent : superelevation e = 100 tan(bank angle), positive toward the inside of the curve [%]
    slope_percent : longitudinal grade, positive uphill in the direction of travel [%]
    """

    bank_percent: float = 0.0
    slope_percent: float = 0.0

    @property
    def bank_rad(self) -> float:
        return math.atan(self.bank_percent / 100.0)

    @property
    def slope_rad(self) -> float:
        return math.atan(self.slope_percent / 100.0)


@dataclass(frozen=True)
class LoadCase:
    """Load condition of Sec. 4.7 / Fig. 46.

    lateral_offset_m : d1, positive toward the outside of the turn (toward the outer tires) [m]
    longitudinal_offset_m : d2, positive toward the front (CG at x = -a + d2, Table 8) [m]
    vertical_offset_m : d3, positive up [m]
    overweight_percent : extra weight over the nominal W, same CG [%]
    """

    lateral_offset_m: float = 0.0
    longitudinal_offset_m: float = 0.0
    vertical_offset_m: float = 0.0
    overweight_percent: float = 0.0

    def weight_kn(self, nominal_kn: float) -> float:
        return nominal_kn * (1.0 + self.overweight_percent / 100.0)


def check_road(road: Road, trailer_angle_deg: float = 0.0) -> None:
    """Refuse road inputs outside the model's domain (:data:`engine.domain.BOUNDS`) naming the field."""
    check("bank_percent", road.bank_percent, "road.bank_percent")
    check("slope_percent", road.slope_percent, "road.slope_percent")
    check("trailer_angle_deg", trailer_angle_deg)


def check_load(
    load: LoadCase,
    *,
    half_track_m: float,
    cg_height_above_chassis_m: float,
    wheelbase_m: float | None,
    front_axle_to_cg_m: float | None,
) -> None:
    """Refuse a load case outside the bounds, that puts the CG outside the vehicle, or that removes the load."""
    d1, d2, d3 = load.lateral_offset_m, load.longitudinal_offset_m, load.vertical_offset_m
    for name in ("lateral_offset_m", "longitudinal_offset_m", "vertical_offset_m", "overweight_percent"):
        check(name, getattr(load, name), f"load.{name}")
    if abs(d1) >= half_track_m:
        raise InvalidLoad(
            f"load.lateral_offset_m = {d1} m puts the CG outside the track (half track {half_track_m} m)",
            field="load.lateral_offset_m",
            value=d1,
        )
    if cg_height_above_chassis_m + d3 <= 0:
        raise InvalidLoad(
            f"load.vertical_offset_m = {d3} m puts the CG below the chassis (l12 = {cg_height_above_chassis_m} m)",
            field="load.vertical_offset_m",
            value=d3,
        )
    if wheelbase_m is not None and front_axle_to_cg_m is not None:
        a_eff = front_axle_to_cg_m - d2
        if not 0.0 < a_eff <= MAX_CG_BEHIND_REAR_GROUP * wheelbase_m:
            raise InvalidLoad(
                f"load.longitudinal_offset_m = {d2} m puts the CG at a - d2 = {a_eff:.3f} m behind the kingpin; "
                f"it must be in (0, {MAX_CG_BEHIND_REAR_GROUP:g} L = {MAX_CG_BEHIND_REAR_GROUP * wheelbase_m:.3f}] m",
                field="load.longitudinal_offset_m",
                value=d2,
            )


def check_case(vehicle, road: Road, trailer_angle_deg: float, load: LoadCase) -> None:
    """Check a road and load case against a vehicle record (its half track, l12, wheelbase, a)."""
    check_road(road, trailer_angle_deg)
    check_load(
        load,
        half_track_m=vehicle.rear_track_m / 2.0,
        cg_height_above_chassis_m=vehicle.cg_height_above_chassis_m,
        wheelbase_m=vehicle.wheelbase_m,
        front_axle_to_cg_m=vehicle.front_axle_to_cg_m,
    )


def kingpin_uplift_note(a_eff_m: float, wheelbase_m: float | None) -> str | None:
    """A note when the CG lies behind the rear group: Eq. 4.27 then lifts the kingpin (negative front load)."""
    if wheelbase_m is None or a_eff_m <= wheelbase_m:
        return None
    return (
        f"the CG is {a_eff_m - wheelbase_m:.2f} m behind the rear axle group: Eq. 4.27 gives a negative "
        "load on the kingpin; the model's front unit is massless, so its tire loads come out negative where "
        "the lead unit's own weight would keep them positive"
    )


#: the two stages of Ch. 9: the full system, and tires and suspension only
STAGES = ("full", "tires-suspension")


@dataclass(frozen=True)
class Case:
    """The vehicle, the model and the road/load case of one SRT.

    Parameters
    ----------
    vehicle : the vehicle record (:class:`engine.vehicle.Vehicle`) or a combination
        (:class:`engine.vehicle.Combination`)
    model : model id of :data:`engine.models.MODELS`; default ``"3d"`` for a record, ``"combination"`` (the
        whole-combination model) for a combination [-]
    stage : 3D only: ``"full"`` (tires, suspension, fifth wheel, chassis) or ``"tires-suspension"`` (the first
        stage of Ch. 9) [-]
    road : bank and slope (:class:`engine.case.Road`) [%]
    trailer_angle_deg : psi, the angle between the last two units of the combination (3D only) [deg]
    load : CG offsets d1, d2, d3 and the overweight (:class:`engine.case.LoadCase`) [m, %]
    rear_llt_limit : rear lateral load transfer at which the load ramp stops; 1 = rear inner tire lift-off
        (Eq. 2.5; Table 17 uses 0.6) [-]
    """

    vehicle: Vehicle | Combination
    model: str | None = None
    stage: str = "full"
    road: Road = field(default_factory=Road)
    trailer_angle_deg: float = 0.0
    load: LoadCase = field(default_factory=LoadCase)
    rear_llt_limit: float = 1.0

    def __post_init__(self) -> None:
        if self.model is None:
            object.__setattr__(self, "model", "combination" if isinstance(self.vehicle, Combination) else "3d")

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
        v = data["vehicle"]
        vehicle = Combination.from_dict(v["combination"]) if "combination" in v else Vehicle.from_dict(v)
        return cls(
            vehicle=vehicle,
            model=data.get("model"),
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

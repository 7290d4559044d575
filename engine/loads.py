"""Actions on the centre of gravity: weight and lateral inertia on a banked, sloped road (Sec. 4.7).

Frame (Table 8): x forward along the trailer, y lateral toward the *inside* of the turn (the outer
tires are at y = 0), z normal to the road surface, up. The external actions at the CG are the thesis's
primary variables Px, Py, Pz (Eq. 6.13); their unit wrench directions are (1, 0, 0), (0, -1, 0) and
(0, 0, -1) (Table 11), so positive Py pushes the CG toward the outer tires and positive Pz presses it
onto the road.

Slope sign: the thesis writes Px = W sin(phi) with Px along +x, i.e. its phi is positive *downhill*
(Eq. 4.27 then unloads the rear). This module takes road-practice grades, positive *uphill*, and uses
``Px = -W sin(phi_uphill)``: on an uphill the weight pulls the trailer backwards and Eq. 4.27 loads the
rear group.

References
----------
Thesis Eqs. 2.5, 4.24-4.27; Bonneson (2000) for the force decomposition.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .domain import check
from .errors import InvalidLoad

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

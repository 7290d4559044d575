"""The domain of every scalar input the engine accepts, in one place.

Each :class:`Bound` is checked by the engine (:func:`check`) and published by the HTTP layer's schemas (which build
their fields from the same table), so the spec, the service and the library refuse exactly the same values. The
vehicle record's fields have their own table, :data:`engine.vehicle.FIELD_DOCS`, with the same structure.

Sources of the bounds: the thesis's small-slope road geometry and the design practice of its Table 21 for
superelevation and grade (at most 20 %); the widest and tallest legal heavy vehicles (2.60 m, 4.40 m: CONTRAN
Res. 210/2006) for the CG offsets; the speed range of road design for speeds; the turning circle every heavy
vehicle must be able to drive (EU Directive 97/27/EC: outer radius 12.5 m, inner 5.3 m) for the smallest radius.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from engine.errors import InvalidInput, InvalidLoad, InvalidRoad


@dataclass(frozen=True)
class Bound:
    """The admissible range of one input: ``minimum`` (``exclusive_minimum``: strictly above) to ``maximum``."""

    minimum: float
    maximum: float
    unit: str
    why: str
    exclusive_minimum: bool = False
    error: type[InvalidInput] = InvalidInput

    def contains(self, value: float) -> bool:
        if not (isinstance(value, int | float) and not isinstance(value, bool) and math.isfinite(value)):
            return False
        low = value > self.minimum if self.exclusive_minimum else value >= self.minimum
        return low and value <= self.maximum

    def text(self) -> str:
        bracket = "(" if self.exclusive_minimum else "["
        return f"{bracket}{self.minimum:g}, {self.maximum:g}] {self.unit}".rstrip()

    def pydantic(self) -> dict[str, float]:
        """The bound as pydantic ``Field`` keywords (``gt``/``ge`` and ``le``)."""
        low = {"gt": self.minimum} if self.exclusive_minimum else {"ge": self.minimum}
        return {**low, "le": self.maximum}


#: the steepest superelevation and grade [%]: beyond them the small-slope road geometry of the thesis and the
#: design practice of Table 21 no longer apply
MAX_BANK_PERCENT = 20.0
MAX_SLOPE_PERCENT = 20.0
MAX_TRAILER_ANGLE_DEG = 60.0
MAX_OVERWEIGHT_PERCENT = 50.0
MAX_SPEED_KMH = 200.0

BOUNDS: dict[str, Bound] = {
    "bank_percent": Bound(-MAX_BANK_PERCENT, MAX_BANK_PERCENT, "%", "small-slope road geometry", error=InvalidRoad),
    "design_superelevation_percent": Bound(
        -4.0,
        MAX_BANK_PERCENT,
        "%",
        "a design superelevation: no curve is designed with an adverse crossfall beyond twice the normal crown (-2 %),"
        " and down to -4 % 0.01 e + f stays positive for every tabulated side friction (f >= 0.08)",
        error=InvalidRoad,
    ),
    "max_superelevation_percent": Bound(
        0.0, 12.0, "%", "the maximum superelevations the design standards tabulate (4-12 %)", True, InvalidRoad
    ),
    "slope_percent": Bound(-MAX_SLOPE_PERCENT, MAX_SLOPE_PERCENT, "%", "small-slope road geometry", error=InvalidRoad),
    "trailer_angle_deg": Bound(
        -MAX_TRAILER_ANGLE_DEG, MAX_TRAILER_ANGLE_DEG, "deg", "a combination turning on a road curve", error=InvalidRoad
    ),
    "lateral_offset_m": Bound(-1.3, 1.3, "m", "within half the widest legal vehicle (2.60 m)", error=InvalidLoad),
    "longitudinal_offset_m": Bound(-20.0, 20.0, "m", "within the longest wheelbase accepted", error=InvalidLoad),
    "vertical_offset_m": Bound(-4.4, 4.4, "m", "within the tallest legal vehicle (4.40 m)", error=InvalidLoad),
    "overweight_percent": Bound(
        -100.0, MAX_OVERWEIGHT_PERCENT, "%", "a load that exists, at most half as heavy again", True, InvalidLoad
    ),
    "rear_llt_limit": Bound(0.0, 1.0, "", "1 = rear inner tire lift-off", True, InvalidLoad),
    "speed_kmh": Bound(0.0, MAX_SPEED_KMH, "km/h", "road design speeds", True, InvalidRoad),
    "radius_m": Bound(5.0, 1e5, "m", "at least the 5.3 m inner turning radius of a heavy vehicle", error=InvalidRoad),
    "srt_g": Bound(0.01, 2.0, "g", "a vehicle below 0.01 g tips at rest; 2 g is beyond any road vehicle"),
    "target_srt_g": Bound(0.0, 2.0, "g", "a lateral acceleration a road vehicle can reach", True, InvalidInput),
    "side_friction": Bound(
        0.01,
        1.0,
        "",
        "a side-friction factor; below 0.01 (the srt_g floor) a curve's radius is unbounded",
        False,
        InvalidRoad,
    ),
}

#: curves against ay/g: the thesis's figures use 41 points from rest to the limit; at most this many
DEFAULT_CURVE_POINTS = 41
MAX_CURVE_POINTS = 401


def check(name: str, value: float, field: str | None = None) -> None:
    """Refuse ``value`` outside the bound ``name`` of :data:`BOUNDS`, with the bound's error class naming
    ``field`` (default: ``name``) and the admissible range."""
    b = BOUNDS[name]
    if not b.contains(value):
        raise b.error(f"{field or name} = {value!r} is outside {b.text()} ({b.why})", field=field or name, value=value)

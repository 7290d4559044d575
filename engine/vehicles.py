"""The vehicle parameter record and the thesis presets (Tables 14, 15, 16, 22 and 23).

Units are SI with forces in kN (so stiffnesses are kN/m, moments kN m). Every field is documented in
:data:`FIELD_DOCS` with its unit and thesis symbol; the HTTP layer reuses those texts.

How per-axle and per-tire stiffnesses combine into the model's equivalent stiffnesses
-------------------------------------------------------------------------------------
The mechanisms of Chapters 5 and 6 have *one equivalent axle per axle group* with one tire column and
one leaf spring *per side* (Figs. 41-43). Each of those elements stands for everything on that side of
the group, acting in parallel, so its stiffness is a per-side sum:

* suspension, per side:  ``kLs_side = n_axles * suspension_stiffness_kn_per_m``.
  The record's ``suspension_stiffness_kn_per_m`` (kLs "per axle" in Tables 16, 22, 23) is the rate of the
  leaf spring on *one side* of one axle. Table 14's equivalent 5400 kN/m is the 2D model's single spring
  per side: 3 axles x 1800 kN/m.
* tires, per side:  ``kT_side = n_axles * (tires_per_axle / 2) * tire_stiffness_kn_per_m``.
  Half of an axle's tires are on each side (duals: 2 per side). Table 14's 5040 kN/m = 3 axles x 2 tires
  x 840 kN/m.
* fifth wheel, per side: ``kf_side = fifth_wheel_stiffness_kn_per_m``. The fifth-wheel mechanism
  (Fig. 37, Eq. 4.14) has one spring on each side of the plate, written with the same per-leg stiffness
  symbol as the suspension; we read Table 16's kf = 7500 kN/m the same way as the suspension's per-axle
  rate, i.e. as the rate of each of the two legs. (The fifth wheel only shapes the front unit's roll; with
  the front/rear lateral-load-transfer closure of Ch. 9 its influence on the SRT is below 0.1 %.)
* roll stiffness of a group (Eq. 2.11): ``k_theta = kLs_side * b**2 / 2`` (two springs at +-b/2).

Track and axle width
--------------------
The tire system keeps both tires perpendicular to the axle (Sec. 4.1.1, Fig. 28), so at rest the track
(contact spacing, t1/t3) equals the axle width (column spacing, t2/t4); under load Eq. 4.3 widens the
track slightly. A record whose track differs from its axle width by more than 1 mm cannot be represented
by this mechanism and is refused.

References
----------
Moreno, G. G. (thesis), Tables 14-16, 22, 23; Eqs. 2.11, 4.1, 4.7, 4.14.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, fields, replace
from typing import Any

from .errors import InvalidVehicle, MissingParameter, UnknownPreset

# --------------------------------------------------------------------------------------------- record


@dataclass(frozen=True)
class FieldDoc:
    unit: str
    symbol: str
    description: str


FIELD_DOCS: dict[str, FieldDoc] = {
    "weight_kn": FieldDoc("kN", "W", "Weight of the (last) trailer or truck, nominal (without overweight)."),
    "front_track_m": FieldDoc("m", "t1", "Track width of the front axle group (tire contact spacing)."),
    "rear_track_m": FieldDoc("m", "t3", "Track width of the rear axle group (tire contact spacing)."),
    "front_axle_width_m": FieldDoc("m", "t2", "Axle width of the front group (tire column spacing); equals t1."),
    "rear_axle_width_m": FieldDoc("m", "t4", "Axle width of the rear group (tire column spacing); equals t3."),
    "front_axles": FieldDoc("count", "-", "Number of axles in the front group (under the fifth wheel)."),
    "rear_axles": FieldDoc("count", "-", "Number of axles in the rear group of the trailer."),
    "front_tires_per_axle": FieldDoc("count", "-", "Tires per front axle (2 single, 4 dual)."),
    "rear_tires_per_axle": FieldDoc("count", "-", "Tires per rear axle (2 single, 4 dual)."),
    "suspension_stiffness_kn_per_m": FieldDoc(
        "kN/m", "kLs", "Leaf-spring rate per axle and side; the model sums it over the group's axles."
    ),
    "tire_stiffness_kn_per_m": FieldDoc(
        "kN/m", "kT", "Vertical (radial) stiffness of one tire; the model sums the tires of a side."
    ),
    "fifth_wheel_stiffness_kn_per_m": FieldDoc(
        "kN/m", "kf", "Rate of each of the two fifth-wheel springs; null for a rigid truck without fifth wheel."
    ),
    "suspension_height_m": FieldDoc("m", "ls", "Initial (static, nominal load) suspension height."),
    "rolling_radius_m": FieldDoc("m", "lr", "Initial dynamic (loaded) rolling radius of the tires."),
    "fifth_wheel_height_m": FieldDoc("m", "lf", "Initial height of the fifth wheel above the front bolster."),
    "spring_separation_m": FieldDoc("m", "b", "Lateral separation between the leaf springs."),
    "fifth_wheel_width_m": FieldDoc("m", "b1", "Width of the fifth wheel (separation of its two springs)."),
    "cg_height_above_chassis_m": FieldDoc("m", "l12", "Height of the centre of gravity above the chassis."),
    "fifth_wheel_to_front_axle_m": FieldDoc(
        "m", "l13", "Longitudinal distance from the fifth wheel (kingpin) back to the front axle group."
    ),
    "wheelbase_m": FieldDoc("m", "L", "Wheelbase: kingpin (or front axle of a truck) to the rear axle group."),
    "front_axle_to_cg_m": FieldDoc("m", "a", "Distance from the kingpin (front axle) back to the CG."),
    "front_llt_ratio": FieldDoc(
        "-",
        "LLTf/LLTr",
        "Front lateral load transfer as a ratio of the rear one (0.7 per Kamnik et al. 2003 for trailers).",
    ),
    "chassis_torsional_stiffness_knm2_per_rad": FieldDoc(
        "kN m^2/rad",
        "G Jr",
        "Torsional rigidity of the chassis section between the rear axle group and the CG (Eq. 4.20); "
        "null = torsionally rigid there (the chassis compliance then acts only through front_llt_ratio).",
    ),
}


@dataclass(frozen=True)
class Vehicle:
    """One vehicle (the last unit of a combination, or a rigid truck). See :data:`FIELD_DOCS`."""

    weight_kn: float
    rear_track_m: float
    rear_axle_width_m: float
    rear_axles: int
    rear_tires_per_axle: int
    suspension_stiffness_kn_per_m: float
    tire_stiffness_kn_per_m: float
    suspension_height_m: float
    rolling_radius_m: float
    spring_separation_m: float
    cg_height_above_chassis_m: float
    front_track_m: float | None = None
    front_axle_width_m: float | None = None
    front_axles: int | None = None
    front_tires_per_axle: int | None = None
    fifth_wheel_stiffness_kn_per_m: float | None = None
    fifth_wheel_height_m: float | None = None
    fifth_wheel_width_m: float | None = None
    fifth_wheel_to_front_axle_m: float | None = None
    wheelbase_m: float | None = None
    front_axle_to_cg_m: float | None = None
    front_llt_ratio: float | None = None
    chassis_torsional_stiffness_knm2_per_rad: float | None = None

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> Vehicle:
        names = {f.name for f in fields(cls)}
        unknown = sorted(set(data) - names)
        if unknown:
            raise InvalidVehicle(f"unknown vehicle field(s): {', '.join(unknown)}", field=unknown[0])
        return cls(**data)

    def replace(self, **changes: Any) -> Vehicle:
        return replace(self, **changes)

    # ----------------------------------------------------------------------- derived quantities
    @property
    def is_3d_capable(self) -> bool:
        return all(getattr(self, n) is not None for n in THREE_D_FIELDS)

    @property
    def has_fifth_wheel(self) -> bool:
        return self.fifth_wheel_stiffness_kn_per_m is not None


#: fields the 3D model needs beyond the rear group (the fifth-wheel ones only when kf is given)
THREE_D_FIELDS = (
    "front_track_m",
    "front_axle_width_m",
    "front_axles",
    "front_tires_per_axle",
    "wheelbase_m",
    "front_axle_to_cg_m",
    "front_llt_ratio",
)
FIFTH_WHEEL_FIELDS = ("fifth_wheel_height_m", "fifth_wheel_width_m")


@dataclass(frozen=True)
class GroupStiffness:
    """Equivalent per-side stiffnesses of one axle group (see the module docstring)."""

    suspension_side_kn_per_m: float
    tire_side_kn_per_m: float

    def roll_stiffness(self, spring_separation_m: float) -> float:
        """Suspension roll stiffness k_theta = kLs b^2 / 2 [kN m/rad] (Eq. 2.11)."""
        return self.suspension_side_kn_per_m * spring_separation_m**2 / 2.0

    def tire_roll_stiffness(self, track_m: float) -> float:
        """Roll stiffness of the tires, kT t^2 / 2 [kN m/rad] (two sides at +-t/2)."""
        return self.tire_side_kn_per_m * track_m**2 / 2.0


def group_stiffness(vehicle: Vehicle, group: str) -> GroupStiffness:
    """Per-side equivalent stiffnesses of the ``'front'`` or ``'rear'`` axle group [kN/m]."""
    axles = vehicle.rear_axles if group == "rear" else vehicle.front_axles
    tires = vehicle.rear_tires_per_axle if group == "rear" else vehicle.front_tires_per_axle
    if axles is None or tires is None:
        raise MissingParameter(f"the {group} axle group is not described", field=f"{group}_axles")
    return GroupStiffness(
        suspension_side_kn_per_m=axles * vehicle.suspension_stiffness_kn_per_m,
        tire_side_kn_per_m=axles * (tires / 2.0) * vehicle.tire_stiffness_kn_per_m,
    )


def cg_height_m(vehicle: Vehicle, vertical_offset_m: float = 0.0) -> float:
    """Static CG height above the road h = lr + ls + l12 (+ d3) [m] (rigid-model h of Eq. 2.6)."""
    return (
        vehicle.rolling_radius_m + vehicle.suspension_height_m + vehicle.cg_height_above_chassis_m + vertical_offset_m
    )


def static_axle_loads(vehicle: Vehicle, longitudinal_offset_m: float = 0.0, weight_kn: float | None = None):
    """Static (flat road) loads on the front and rear groups [kN]: Eq. 4.27 with Px = 0.

    A record without wheelbase (a 2D vehicle such as Table 14) carries everything on its rear group.
    ``longitudinal_offset_m`` is d2, positive toward the front (CG at x = -a + d2).
    """
    w = vehicle.weight_kn if weight_kn is None else weight_kn
    if vehicle.wheelbase_m is None or vehicle.front_axle_to_cg_m is None:
        return 0.0, w
    a_eff = vehicle.front_axle_to_cg_m - longitudinal_offset_m
    rear = w * a_eff / vehicle.wheelbase_m
    return w - rear, rear


# ------------------------------------------------------------------------------------ validation


def _positive(v: Vehicle, name: str, *, allow_none: bool = False) -> None:
    value = getattr(v, name)
    if value is None:
        if allow_none:
            return
        raise MissingParameter(f"{name} is required", field=name)
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise InvalidVehicle(f"{name} must be a finite number, got {value!r}", field=name, value=value)
    if value <= 0:
        raise InvalidVehicle(f"{name} must be positive, got {value}", field=name, value=value)


def _count(v: Vehicle, name: str, *, even: bool = False, allow_none: bool = False) -> None:
    value = getattr(v, name)
    if value is None and allow_none:
        return
    if isinstance(value, bool) or not isinstance(value, int) or value < 1:
        raise InvalidVehicle(f"{name} must be a positive whole number, got {value!r}", field=name, value=value)
    if even and value % 2:
        raise InvalidVehicle(
            f"{name} must be even (the same number of tires on each side), got {value}", field=name, value=value
        )


TRACK_TOLERANCE_M = 1e-3


def validate_group(v: Vehicle, group: str) -> None:
    """Check one axle group's fields (track, axle width, counts) for the mechanism of Sec. 4.1-4.2."""
    track, width = f"{group}_track_m", f"{group}_axle_width_m"
    _positive(v, track)
    _positive(v, width)
    _count(v, f"{group}_axles")
    _count(v, f"{group}_tires_per_axle", even=True)
    t, t_axle = getattr(v, track), getattr(v, width)
    if abs(t - t_axle) > TRACK_TOLERANCE_M:
        raise InvalidVehicle(
            f"{track} ({t} m) must equal {width} ({t_axle} m): the tire system keeps the tires "
            "perpendicular to the axle (Sec. 4.1.1), so at rest the track is the axle width",
            field=track,
            value=t,
        )
    if not v.spring_separation_m < t_axle:
        raise InvalidVehicle(
            f"spring_separation_m ({v.spring_separation_m} m) must be smaller than {width} ({t_axle} m)",
            field="spring_separation_m",
            value=v.spring_separation_m,
        )


def validate_vehicle(v: Vehicle, *, model: str = "3d") -> None:
    """Refuse a physically impossible record, or one missing what ``model`` needs, before solving.

    Raises :class:`InvalidVehicle` (or :class:`MissingParameter`) naming the field.
    """
    for name in (
        "weight_kn",
        "suspension_stiffness_kn_per_m",
        "tire_stiffness_kn_per_m",
        "suspension_height_m",
        "rolling_radius_m",
        "spring_separation_m",
        "cg_height_above_chassis_m",
    ):
        _positive(v, name)
    validate_group(v, "rear")
    _positive(v, "chassis_torsional_stiffness_knm2_per_rad", allow_none=True)
    needs_3d = model == "3d"
    if needs_3d or model in ("gillespie", "navin"):
        missing = [n for n in THREE_D_FIELDS if getattr(v, n) is None]
        if model == "gillespie":
            missing = [n for n in missing if n in ("front_axles", "front_tires_per_axle")]
        if model == "navin":
            missing = [n for n in missing if n in ("wheelbase_m", "front_axle_to_cg_m")]
        if missing:
            raise MissingParameter(
                f"the {model} model needs {', '.join(missing)}, which this vehicle leaves null", field=missing[0]
            )
    if v.front_axles is not None or needs_3d:
        if needs_3d:
            validate_group(v, "front")
        else:
            _count(v, "front_axles")
            _count(v, "front_tires_per_axle", even=True)
    if v.wheelbase_m is not None or v.front_axle_to_cg_m is not None:
        _positive(v, "wheelbase_m")
        _positive(v, "front_axle_to_cg_m")
        if not v.front_axle_to_cg_m < v.wheelbase_m:
            raise InvalidVehicle(
                f"front_axle_to_cg_m ({v.front_axle_to_cg_m} m) must lie between the kingpin and the rear "
                f"group, i.e. below wheelbase_m ({v.wheelbase_m} m)",
                field="front_axle_to_cg_m",
                value=v.front_axle_to_cg_m,
            )
    if v.front_llt_ratio is not None:
        r = v.front_llt_ratio
        if not (isinstance(r, int | float) and math.isfinite(r) and 0.0 < r <= 1.0):
            raise InvalidVehicle(
                f"front_llt_ratio must be in (0, 1] (the rear inner tire is the one that lifts), got {r!r}",
                field="front_llt_ratio",
                value=r,
            )
    if v.has_fifth_wheel:
        _positive(v, "fifth_wheel_stiffness_kn_per_m")
        if needs_3d:
            for name in FIFTH_WHEEL_FIELDS:
                _positive(v, name)
            if not v.fifth_wheel_width_m < v.front_axle_width_m:
                raise InvalidVehicle(
                    f"fifth_wheel_width_m ({v.fifth_wheel_width_m} m) must be smaller than front_axle_width_m",
                    field="fifth_wheel_width_m",
                    value=v.fifth_wheel_width_m,
                )
    if v.fifth_wheel_to_front_axle_m is not None:
        x = v.fifth_wheel_to_front_axle_m
        if not math.isfinite(x) or (v.wheelbase_m is not None and abs(x) >= v.wheelbase_m):
            raise InvalidVehicle(
                "fifth_wheel_to_front_axle_m must be finite and shorter than the wheelbase",
                field="fifth_wheel_to_front_axle_m",
                value=x,
            )
    # Rill's condition k_theta > m g l12 per group with its static share (Eq. 2.17): below it the body
    # falls over at rest.
    front_load, rear_load = static_axle_loads(v)
    for group, load in (("rear", rear_load), ("front", front_load)):
        if group == "front" and (not needs_3d or load <= 0):
            continue
        k_theta = group_stiffness(v, group).roll_stiffness(v.spring_separation_m)
        if k_theta <= load * v.cg_height_above_chassis_m:
            raise InvalidVehicle(
                f"the {group} suspension roll stiffness kLs b^2/2 = {k_theta:.1f} kN m/rad does not exceed "
                f"W l12 = {load * v.cg_height_above_chassis_m:.1f} kN m: the body would fall over at rest "
                "(Eq. 2.17); raise suspension_stiffness_kn_per_m or spring_separation_m, or lower the CG",
                field="suspension_stiffness_kn_per_m",
                value=v.suspension_stiffness_kn_per_m,
            )


# --------------------------------------------------------------------------------------- presets


@dataclass(frozen=True)
class PresetInfo:
    title: str
    source: str
    models: tuple[str, ...]


_TRI_AXLE_REAR = dict(
    rear_axles=3,
    rear_tires_per_axle=4,
    suspension_stiffness_kn_per_m=1800.0,
    tire_stiffness_kn_per_m=840.0,
    suspension_height_m=0.205,
    rolling_radius_m=0.499,
    spring_separation_m=0.95,
)

# the 1.86 m tracks and the lead unit's tandem under a fifth wheel, shared by Tables 16 and 23
_TANDEM_FRONT_WITH_FIFTH_WHEEL = dict(
    front_track_m=1.86,
    rear_track_m=1.86,
    front_axle_width_m=1.86,
    rear_axle_width_m=1.86,
    front_axles=2,
    front_tires_per_axle=4,
    fifth_wheel_stiffness_kn_per_m=7500.0,
    fifth_wheel_height_m=0.1,
    fifth_wheel_width_m=0.6,
)

PRESETS: dict[str, Vehicle] = {
    # Ch. 7, Table 14: the 2D model of a semi-trailer's tridem group. Its "equivalent" 5400 and 5040 kN/m
    # are 3 axles x 1800 kN/m and 3 axles x 2 tires per side x 840 kN/m.
    "table14-semitrailer": Vehicle(
        weight_kn=250.0,
        rear_track_m=1.86,
        rear_axle_width_m=1.86,
        cg_height_above_chassis_m=1.346,
        **_TRI_AXLE_REAR,
    ),
    # Ch. 8, Table 15: the TruckSim semi-trailer (LLTf = 0.57 LLTr at the limit, as the check states).
    "table15-semitrailer": Vehicle(
        weight_kn=364.147,
        front_track_m=1.815,
        rear_track_m=1.815,
        front_axle_width_m=1.815,
        rear_axle_width_m=1.815,
        front_axles=1,
        rear_axles=3,
        front_tires_per_axle=4,
        rear_tires_per_axle=4,
        suspension_stiffness_kn_per_m=2500.0,
        tire_stiffness_kn_per_m=980.0,
        fifth_wheel_stiffness_kn_per_m=7500.0,
        suspension_height_m=0.205,
        rolling_radius_m=0.51,
        fifth_wheel_height_m=0.1,
        spring_separation_m=0.95,
        fifth_wheel_width_m=0.6,
        cg_height_above_chassis_m=1.285,
        fifth_wheel_to_front_axle_m=0.9,
        wheelbase_m=8.7,
        front_axle_to_cg_m=5.0,
        front_llt_ratio=0.57,
    ),
    # Ch. 9, Table 16: the rear trailer of a B-train.
    "table16-btrain": Vehicle(
        weight_kn=355.22,
        cg_height_above_chassis_m=1.356,
        fifth_wheel_to_front_axle_m=0.15,
        wheelbase_m=4.26,
        front_axle_to_cg_m=3.0,
        front_llt_ratio=0.7,
        **_TRI_AXLE_REAR,
        **_TANDEM_FRONT_WITH_FIFTH_WHEEL,
    ),
    # Appendix B, Table 22: a rigid truck, one steer axle (single tires) and a tandem (LLTf = 0.9 LLTr).
    "table22-truck": Vehicle(
        weight_kn=255.0,
        front_track_m=1.86,
        rear_track_m=1.86,
        front_axle_width_m=1.86,
        rear_axle_width_m=1.86,
        front_axles=1,
        rear_axles=2,
        front_tires_per_axle=2,
        rear_tires_per_axle=4,
        suspension_stiffness_kn_per_m=1800.0,
        tire_stiffness_kn_per_m=840.0,
        suspension_height_m=0.205,
        rolling_radius_m=0.499,
        spring_separation_m=0.95,
        cg_height_above_chassis_m=1.41,
        fifth_wheel_to_front_axle_m=0.0,
        wheelbase_m=7.62,
        front_axle_to_cg_m=5.63,
        front_llt_ratio=0.9,
    ),
    # Appendix C, Table 23: the semi-trailer of a tractor-semitrailer (LLTf = 0.7 LLTr).
    "table23-semitrailer": Vehicle(
        weight_kn=392.13,
        cg_height_above_chassis_m=1.21,
        fifth_wheel_to_front_axle_m=0.2,
        wheelbase_m=8.7,
        front_axle_to_cg_m=5.55,
        front_llt_ratio=0.7,
        **_TRI_AXLE_REAR,
        **_TANDEM_FRONT_WITH_FIFTH_WHEEL,
    ),
}

_ALL = ("3d", "2d", "rigid", "rigid-bank", "winkler", "rill", "chang", "gillespie", "navin")
_TWO_D = ("2d", "rigid", "rigid-bank", "winkler", "rill", "chang")

PRESET_INFO: dict[str, PresetInfo] = {
    "table14-semitrailer": PresetInfo(
        "Semi-trailer tridem group, 2D (Ch. 7)", "Thesis Table 14 (Adams comparison)", _TWO_D
    ),
    "table15-semitrailer": PresetInfo(
        "Semi-trailer, 1 + 3 axles (Ch. 8)", "Thesis Table 15 (TruckSim comparison)", _ALL
    ),
    "table16-btrain": PresetInfo("B-train rear trailer, 2 + 3 axles (Ch. 9)", "Thesis Table 16", _ALL),
    "table22-truck": PresetInfo("Rigid truck, 1 + 2 axles (App. B)", "Thesis Table 22", _ALL),
    "table23-semitrailer": PresetInfo("Semi-trailer, 2 + 3 axles (App. C)", "Thesis Table 23", _ALL),
}


def get_preset(preset_id: str) -> Vehicle:
    """The preset vehicle with this id; :class:`UnknownPreset` lists the known ids otherwise."""
    try:
        return PRESETS[preset_id]
    except KeyError:
        raise UnknownPreset(preset_id, sorted(PRESETS)) from None

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
from dataclasses import dataclass, fields, replace
from typing import Any

from engine.errors import InvalidVehicle, MissingParameter

# --------------------------------------------------------------------------------------------- record

#: the widest heavy vehicle any of the cited regulations allows [m]: Brazil (CONTRAN Res. 210/2006) and the EU
#: (Directive 96/53/EC, conditioned bodies) 2.60 m, the US 102 in = 2.59 m (23 CFR 658.15). A track (tire-contact
#: spacing; the centres of dual pairs) is narrower than the vehicle, so it is bounded by this width.
MAX_VEHICLE_WIDTH_M = 2.60
#: the tallest heavy vehicle the cited regulations allow [m]: 4.40 m in Brazil (CONTRAN Res. 210/2006; the EU's
#: Directive 96/53/EC allows 4.00 m). The CG of a vehicle lies below its top, so its height above the road is
#: bounded by this height.
MAX_VEHICLE_HEIGHT_M = 4.40
#: a spring of the mechanism (tires, leaf springs, fifth wheel) may not deflect by this fraction of its initial
#: length or more under its side's static load: at the rollover limit the outer side carries about twice its
#: static load, so its spring would be compressed to nothing and the mechanism of Secs. 4.1-4.3 would fold
MAX_STATIC_DEFLECTION_RATIO = 1.0
#: the largest chassis twist accepted between the rear group and the CG under the rear group's whole roll moment
#: (its load on one tire line, W_rear t/2) [rad]: 0.5 rad is 29 deg, a folded chassis, far beyond any real frame
MAX_CHASSIS_TWIST_RAD = 0.5


@dataclass(frozen=True)
class FieldDoc:
    """One field of the vehicle record: its unit, thesis symbol, meaning and admissible range.

    ``minimum``/``maximum`` bound the value (``exclusive_minimum``: strictly above it); ``bounds`` says where the
    range comes from. Counts are integers (``integer``); ``even`` counts have the same number on each side. The
    HTTP schemas are generated from this table, so the published spec states the same bounds the engine checks.
    """

    unit: str
    symbol: str
    description: str
    minimum: float
    maximum: float
    bounds: str
    exclusive_minimum: bool = True
    integer: bool = False
    even: bool = False
    required: bool = False


_TYRE_RADIUS = (
    "the loaded radius of heavy-vehicle tyres lies between about 0.37 m (17.5-inch rims) and 0.55 m "
    "(445/65R22.5); 0.25-0.80 m brackets them (assumed bracket, see docs/model.md)"
)
#: the stiffest spring accepted [kN/m]: effectively rigid (the rigid limit of the models is tested at this value)
MAX_STIFFNESS_KN_PER_M = 1e12
_STIFFNESS = (
    "positive, up to 1e12 (rigid); too soft a spring is refused by the static-deflection check "
    "(MAX_STATIC_DEFLECTION_RATIO) naming the field"
)
_TRACK = f"at most the widest legal vehicle, {MAX_VEHICLE_WIDTH_M} m (CONTRAN Res. 210/2006; EU Dir. 96/53/EC)"
_LENGTH = "assumed: above the longest legal semi-trailer (EU 13.6 m, Dir. 96/53/EC) with room for special vehicles"

FIELD_DOCS: dict[str, FieldDoc] = {
    "weight_kn": FieldDoc(
        "kN",
        "W",
        "Weight of the (last) trailer or truck, nominal (without overweight).",
        0.0,
        1000.0,
        "positive, at most 1000 kN (102 t; assumed: above the heaviest unit of a 91 t Brazilian combination)",
        required=True,
    ),
    "front_track_m": FieldDoc(
        "m", "t1", "Track width of the front axle group (tire contact spacing).", 1.0, MAX_VEHICLE_WIDTH_M, _TRACK
    ),
    "rear_track_m": FieldDoc(
        "m",
        "t3",
        "Track width of the rear axle group (tire contact spacing).",
        1.0,
        MAX_VEHICLE_WIDTH_M,
        _TRACK,
        required=True,
    ),
    "front_axle_width_m": FieldDoc(
        "m",
        "t2",
        "Axle width of the front group (tire column spacing); equals t1.",
        1.0,
        MAX_VEHICLE_WIDTH_M,
        _TRACK,
    ),
    "rear_axle_width_m": FieldDoc(
        "m",
        "t4",
        "Axle width of the rear group (tire column spacing); equals t3.",
        1.0,
        MAX_VEHICLE_WIDTH_M,
        _TRACK,
        required=True,
    ),
    "front_axles": FieldDoc(
        "count",
        "-",
        "Number of axles in the front group (under the fifth wheel).",
        1,
        8,
        "1-8 axles in a group",
        exclusive_minimum=False,
        integer=True,
    ),
    "rear_axles": FieldDoc(
        "count",
        "-",
        "Number of axles in the rear group of the trailer.",
        1,
        8,
        "1-8 axles in a group",
        exclusive_minimum=False,
        integer=True,
        required=True,
    ),
    "front_tires_per_axle": FieldDoc(
        "count",
        "-",
        "Tires per front axle (2 single, 4 dual).",
        2,
        8,
        "2-8, even: the same number on each side",
        exclusive_minimum=False,
        integer=True,
        even=True,
    ),
    "rear_tires_per_axle": FieldDoc(
        "count",
        "-",
        "Tires per rear axle (2 single, 4 dual).",
        2,
        8,
        "2-8, even: the same number on each side",
        exclusive_minimum=False,
        integer=True,
        even=True,
        required=True,
    ),
    "suspension_stiffness_kn_per_m": FieldDoc(
        "kN/m",
        "kLs",
        "Leaf-spring rate per axle and side; the model sums it over the group's axles.",
        0.0,
        MAX_STIFFNESS_KN_PER_M,
        _STIFFNESS,
        required=True,
    ),
    "tire_stiffness_kn_per_m": FieldDoc(
        "kN/m",
        "kT",
        "Vertical (radial) stiffness of one tire; the model sums the tires of a side.",
        0.0,
        MAX_STIFFNESS_KN_PER_M,
        _STIFFNESS,
        required=True,
    ),
    "fifth_wheel_stiffness_kn_per_m": FieldDoc(
        "kN/m",
        "kf",
        "Rate of each of the two fifth-wheel springs; null for a rigid truck without fifth wheel.",
        0.0,
        MAX_STIFFNESS_KN_PER_M,
        _STIFFNESS,
    ),
    "suspension_height_m": FieldDoc(
        "m",
        "ls",
        "Initial (static, nominal load) suspension height.",
        0.02,
        1.0,
        "0.02-1.0 m (assumed bracket: leaf and air suspensions ride 0.1-0.45 m above the axle)",
        required=True,
    ),
    "rolling_radius_m": FieldDoc(
        "m",
        "lr",
        "Initial dynamic (loaded) rolling radius of the tires.",
        0.25,
        0.80,
        _TYRE_RADIUS,
        exclusive_minimum=False,
        required=True,
    ),
    "fifth_wheel_height_m": FieldDoc(
        "m",
        "lf",
        "Initial height of the fifth wheel above the front bolster.",
        0.0,
        1.0,
        "positive, at most 1 m (assumed: the thesis uses 0.1 m)",
    ),
    "spring_separation_m": FieldDoc(
        "m",
        "b",
        "Lateral separation between the leaf springs.",
        0.3,
        MAX_VEHICLE_WIDTH_M,
        "0.3 m (assumed) up to the axle width (the springs sit on the axle)",
        required=True,
    ),
    "fifth_wheel_width_m": FieldDoc(
        "m",
        "b1",
        "Width of the fifth wheel (separation of its two springs).",
        0.0,
        MAX_VEHICLE_WIDTH_M,
        "positive, below the front axle width",
    ),
    "cg_height_above_chassis_m": FieldDoc(
        "m",
        "l12",
        "Height of the centre of gravity above the chassis.",
        0.0,
        MAX_VEHICLE_HEIGHT_M,
        f"positive; the CG height above the road, lr + ls + l12, at most the tallest legal vehicle, "
        f"{MAX_VEHICLE_HEIGHT_M} m (CONTRAN Res. 210/2006)",
        required=True,
    ),
    "fifth_wheel_to_front_axle_m": FieldDoc(
        "m",
        "l13",
        "Longitudinal distance from the fifth wheel (kingpin) back to the front axle group.",
        -20.0,
        20.0,
        "shorter than the wheelbase (either side of the kingpin)",
        exclusive_minimum=False,
    ),
    "wheelbase_m": FieldDoc(
        "m",
        "L",
        "Wheelbase: kingpin (or front axle of a truck) to the rear axle group.",
        1.0,
        20.0,
        _LENGTH,
    ),
    "front_axle_to_cg_m": FieldDoc(
        "m", "a", "Distance from the kingpin (front axle) back to the CG.", 0.0, 20.0, "between 0 and the wheelbase"
    ),
    "front_llt_ratio": FieldDoc(
        "-",
        "LLTf/LLTr",
        "Front lateral load transfer as a ratio of the rear one (0.7 per Kamnik et al. 2003 for trailers).",
        0.0,
        1.0,
        "in (0, 1]: the rear inner tire is the one that lifts",
    ),
    "chassis_torsional_stiffness_knm2_per_rad": FieldDoc(
        "kN m^2/rad",
        "G Jr",
        "Torsional rigidity of the chassis section between the rear axle group and the CG (Eq. 4.20); "
        "null = torsionally rigid there (the chassis compliance then acts only through front_llt_ratio).",
        0.0,
        1e9,
        "positive",
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
        # every field is a number, a string or None: no deep copy needed (dataclasses.asdict deep-copies each
        # value, and this is called once or twice per request on the service's uncached path)
        return {name: getattr(self, name) for name in _VEHICLE_FIELDS}

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> Vehicle:
        names = {f.name for f in fields(cls)}
        unknown = sorted(set(data) - names)
        if unknown:
            raise InvalidVehicle(f"unknown vehicle field(s): {', '.join(unknown)}", field=unknown[0])
        return cls(**data)

    def replace(self, **changes: Any) -> Vehicle:
        return replace(self, **changes)

    @property
    def has_fifth_wheel(self) -> bool:
        return self.fifth_wheel_stiffness_kn_per_m is not None


_VEHICLE_FIELDS = tuple(f.name for f in fields(Vehicle))

#: the fifth wheel's geometry, needed by a model with a front mechanism group when kf is given
FIFTH_WHEEL_FIELDS = ("fifth_wheel_height_m", "fifth_wheel_width_m")


@dataclass(frozen=True)
class GroupStiffness:
    """Equivalent per-side stiffnesses of one axle group (see the module docstring)."""

    suspension_side_kn_per_m: float
    tire_side_kn_per_m: float

    def roll_stiffness(self, spring_separation_m: float) -> float:
        """Suspension roll stiffness k_theta = kLs b^2 / 2 [kN m/rad] (Eq. 2.11)."""
        return self.suspension_side_kn_per_m * spring_separation_m**2 / 2.0


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

TRACK_TOLERANCE_M = 1e-3


def _check_field(v: Vehicle, name: str) -> None:
    """A non-null field is a finite number (an integer for counts) inside its :data:`FIELD_DOCS` range."""
    value, doc = getattr(v, name), FIELD_DOCS[name]
    if doc.integer:
        if isinstance(value, bool) or not isinstance(value, int):
            raise InvalidVehicle(f"{name} must be a whole number, got {value!r}", field=name, value=value)
    elif isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise InvalidVehicle(f"{name} must be a finite number, got {value!r}", field=name, value=value)
    low_ok = value > doc.minimum if doc.exclusive_minimum else value >= doc.minimum
    if not (low_ok and value <= doc.maximum):
        bracket = "(" if doc.exclusive_minimum else "["
        raise InvalidVehicle(
            f"{name} = {value} {doc.unit} is outside {bracket}{doc.minimum:g}, {doc.maximum:g}]: {doc.bounds}",
            field=name,
            value=value,
        )
    if doc.even and value % 2:
        raise InvalidVehicle(
            f"{name} must be even (the same number of tires on each side), got {value}", field=name, value=value
        )


def validate_group(v: Vehicle, group: str) -> None:
    """Check one axle group's geometry for the mechanism of Secs. 4.1-4.2 (track = axle width, springs inside)."""
    track, width = f"{group}_track_m", f"{group}_axle_width_m"
    for name in (track, width, f"{group}_axles", f"{group}_tires_per_axle"):
        if getattr(v, name) is None:
            raise MissingParameter(f"{name} is required to describe the {group} axle group", field=name)
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


def _check_longitudinal(v: Vehicle) -> None:
    if v.wheelbase_m is None and v.front_axle_to_cg_m is None:
        return
    for name in ("wheelbase_m", "front_axle_to_cg_m"):
        if getattr(v, name) is None:
            raise MissingParameter(f"{name} is required with the other of wheelbase_m, front_axle_to_cg_m", field=name)
    if not v.front_axle_to_cg_m < v.wheelbase_m:
        raise InvalidVehicle(
            f"front_axle_to_cg_m ({v.front_axle_to_cg_m} m) must lie between the kingpin and the rear "
            f"group, i.e. below wheelbase_m ({v.wheelbase_m} m)",
            field="front_axle_to_cg_m",
            value=v.front_axle_to_cg_m,
        )
    x = v.fifth_wheel_to_front_axle_m
    if x is not None and abs(x) >= v.wheelbase_m:
        raise InvalidVehicle(
            f"fifth_wheel_to_front_axle_m ({x} m) must be shorter than the wheelbase ({v.wheelbase_m} m)",
            field="fifth_wheel_to_front_axle_m",
            value=x,
        )


def _check_cg_height(v: Vehicle) -> None:
    h = cg_height_m(v)
    if h > MAX_VEHICLE_HEIGHT_M:
        raise InvalidVehicle(
            f"the CG height above the road lr + ls + l12 = {h:.3f} m exceeds {MAX_VEHICLE_HEIGHT_M} m, the tallest "
            "legal heavy vehicle (CONTRAN Res. 210/2006): the CG lies below the top of the vehicle",
            field="cg_height_above_chassis_m",
            value=v.cg_height_above_chassis_m,
        )


def _check_deflection(v: Vehicle, name: str, what: str, side_load_kn: float, side_k_kn_per_m: float, length_m: float):
    """A spring compressed by more than :data:`MAX_STATIC_DEFLECTION_RATIO` of its length by its side's static
    load: at the limit the outer side carries about twice it, and the mechanism leaves its valid geometry."""
    deflection = side_load_kn / side_k_kn_per_m
    if deflection >= MAX_STATIC_DEFLECTION_RATIO * length_m:
        raise InvalidVehicle(
            f"{name} is too low: the {what} would deflect by {deflection:.3g} m under its side's static load of "
            f"{side_load_kn:.1f} kN, at least its {length_m} m length: at the rollover limit the outer side carries "
            "about twice that load and the spring would be compressed to nothing; raise the stiffness",
            field=name,
            value=getattr(v, name),
        )


def _check_group_springs(v: Vehicle, group: str, load_kn: float) -> None:
    """The static-deflection check of the tires and springs of one group, and Rill's condition (Eq. 2.17)."""
    k = group_stiffness(v, group)
    side = 0.5 * load_kn
    _check_deflection(v, "tire_stiffness_kn_per_m", f"{group} tires", side, k.tire_side_kn_per_m, v.rolling_radius_m)
    _check_deflection(
        v, "suspension_stiffness_kn_per_m", f"{group} springs", side, k.suspension_side_kn_per_m, v.suspension_height_m
    )
    # Rill's condition k_theta > m g l12 with the group's static share: below it the body falls over at rest
    k_theta = k.roll_stiffness(v.spring_separation_m)
    if k_theta <= load_kn * v.cg_height_above_chassis_m:
        raise InvalidVehicle(
            f"the {group} suspension roll stiffness kLs b^2/2 = {k_theta:.1f} kN m/rad does not exceed "
            f"W l12 = {load_kn * v.cg_height_above_chassis_m:.1f} kN m: the body would fall over at rest "
            "(Eq. 2.17); raise suspension_stiffness_kn_per_m or spring_separation_m, or lower the CG",
            field="suspension_stiffness_kn_per_m",
            value=v.suspension_stiffness_kn_per_m,
        )


def _check_chassis_twist(v: Vehicle, rear_load_kn: float) -> None:
    """The chassis twist of Eq. 4.20 under the rear group's whole roll moment stays below a fold."""
    g_jr = v.chassis_torsional_stiffness_knm2_per_rad
    if g_jr is None:
        return
    twist = rear_load_kn * v.rear_track_m / 2.0 * (v.wheelbase_m - v.front_axle_to_cg_m) / g_jr  # Eq. 4.20
    if twist >= MAX_CHASSIS_TWIST_RAD:
        raise InvalidVehicle(
            f"chassis_torsional_stiffness_knm2_per_rad is too low: the chassis would twist by {twist:.3g} rad "
            f"(Eq. 4.20) under the rear group's roll moment, at least {MAX_CHASSIS_TWIST_RAD} rad; raise it, or "
            "leave it null for a torsionally rigid chassis",
            field="chassis_torsional_stiffness_knm2_per_rad",
            value=g_jr,
        )


def validate_vehicle(v: Vehicle, *, requires: tuple[str, ...] = (), front_group: bool = False) -> None:
    """Refuse a record that no heavy vehicle can be, or that misses what a model needs, before solving.

    Parameters
    ----------
    v : the record
    requires : fields the model needs beyond the rear group's (e.g. the wheelbase) [-]
    front_group : whether the model represents the front axle group as a mechanism (the 3D model): then its
        geometry, its springs and (with a fifth wheel) the fifth wheel's geometry are checked too [-]

    Every non-null field must be inside its :data:`FIELD_DOCS` range (the bounds and their sources are in
    ``docs/model.md``); the CG below the tallest legal vehicle; no spring compressed by half its length under its
    side's static load; each modelled group above Rill's roll-stiffness condition (Eq. 2.17).

    Raises
    ------
    MissingParameter : a required field is null.
    InvalidVehicle : a field is out of range or the record is inconsistent; ``field`` names it.
    """
    for name, doc in FIELD_DOCS.items():
        if getattr(v, name) is None:
            if doc.required:
                raise MissingParameter(f"{name} is required", field=name)
            continue
        _check_field(v, name)
    missing = [n for n in requires if getattr(v, n) is None]
    if missing:
        raise MissingParameter(
            f"the model needs {', '.join(missing)}, which this vehicle leaves null", field=missing[0]
        )
    validate_group(v, "rear")
    _check_longitudinal(v)
    _check_cg_height(v)
    front_load, rear_load = static_axle_loads(v)
    _check_group_springs(v, "rear", rear_load)
    if not front_group:
        return
    validate_group(v, "front")
    if front_load > 0:
        _check_group_springs(v, "front", front_load)
    _check_chassis_twist(v, rear_load)
    if v.has_fifth_wheel:
        for name in FIFTH_WHEEL_FIELDS:
            if getattr(v, name) is None:
                raise MissingParameter(
                    f"{name} is required with a fifth wheel (fifth_wheel_stiffness_kn_per_m)", field=name
                )
        if not v.fifth_wheel_width_m < v.front_axle_width_m:
            raise InvalidVehicle(
                f"fifth_wheel_width_m ({v.fifth_wheel_width_m} m) must be smaller than front_axle_width_m",
                field="fifth_wheel_width_m",
                value=v.fifth_wheel_width_m,
            )
        if front_load > 0:
            _check_deflection(
                v,
                "fifth_wheel_stiffness_kn_per_m",
                "fifth-wheel springs",
                0.5 * front_load,
                v.fifth_wheel_stiffness_kn_per_m,
                v.fifth_wheel_height_m,
            )

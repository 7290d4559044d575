"""A combination vehicle as a chain of units: axle groups, sprung masses and couplings, and its static loads.

A :class:`Combination` is what the whole-combination roll model (:mod:`engine.models.combination`) needs to know
of a tractor and its semitrailer, a B-double, an A-double or a truck and its trailer:

* each **unit** (:class:`Unit`): its kind, its sprung mass and the sprung CG (height above the road, position
  behind the unit's reference point), and its axle groups;
* each **axle group** (:class:`AxleGroup`): axles, tyres per axle, track (for duals: between the centres of the
  pairs), the vertical rate of one tyre, the suspension's roll stiffness per axle, its roll-centre height and roll
  lash, the unsprung mass per axle and its height, the group centre's position on the unit;
* each **coupling** (:class:`Coupling`) between consecutive units: a fifth wheel (on a tractor or a converter
  dolly), a B-coupling (the fifth wheel on a B-train lead trailer), or a pintle / drawbar (A-dolly, full trailer),
  with its position on the towing unit and its height, and for the fifth wheels its roll stiffness and lash.

Reference points (positions are metres *behind* them): a tractor's or rigid truck's front axle group centre; a
semitrailer's or B-train lead trailer's kingpin; a dolly's or full trailer's drawbar eye. A towed unit's coupling
is therefore at its own position 0.

Static loads (Eq. 4.27 generalised to the chain)
------------------------------------------------
Each unit rests on exactly two vertical supports: its two axle groups (tractor, rigid truck, full trailer), or its
coupling and its one group (semitrailer, B-train lead trailer, and a dolly, whose drawbar is rigid in pitch). A
full trailer's drawbar is hinged at both ends and carries no vertical load. From the last unit forward, the normal
loads follow from each unit's force and pitch-moment balance about the road below its reference point, with the
weight's normal component at each CG and, on a grade, its longitudinal component at each CG height; the towed
units' tyres roll freely (the thesis's reading of Eq. 4.27), so the longitudinal force of everything behind a
coupling passes through it at its height, and the first unit's driven group reacts the total at the road. Loads
are split into a part proportional to the normal weight factor (:attr:`StaticLoads.normal_kn`, per unit factor) and
a part proportional to the grade's sin (:attr:`StaticLoads.grade_kn`), because the roll model needs them apart.

Roll coupling
-------------
Fifth wheels and B-couplings transmit a roll moment: the units they join roll together. A pintle or drawbar does
not: it cuts the chain into *roll-coupled units* (:func:`roll_coupled_units`), each with its own SRT.

References
----------
.. [1] Moreno, G. G., *Static rollover threshold of long combination vehicles* (thesis), Eq. 4.27 and Sec. 4.7.
.. [2] Winkler, C. B. and Ervin, R. D. (1999), *Rollover of heavy commercial vehicles*, UMTRI-99-19; Ervin, R. D.
   (1986), The dependence of truck roll stability on size and weight variables, Int. J. Vehicle Design 7(5-6):
   the static roll model of a chain of roll-coupled units, per-axle suspensions with roll centres and lash.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import MISSING, dataclass, field, fields, replace
from typing import Any

from engine.errors import InvalidVehicle
from engine.vehicle.plausibility import RANGES, check_plausible
from engine.vehicle.record import Vehicle

#: gravitational acceleration used for W = m g [m/s^2], as the builder's (:data:`engine.builder.G_M_PER_S2`)
G_M_PER_S2 = 9.81

#: unit kinds, what reference point their positions are measured from, and how many axle groups they have
UNIT_KINDS: dict[str, tuple[str, int]] = {
    "tractor": ("the centre of its front (steer) axle group", 2),
    "rigid-truck": ("the centre of its front (steer) axle group", 2),
    "semitrailer": ("its kingpin", 1),
    "btrain-lead": ("its kingpin", 1),
    "dolly": ("its drawbar eye", 1),
    "full-trailer": ("its drawbar eye", 2),
}
#: units that carry the payload: the load case (offsets, overweight) applies to them (not to tractors and dollies)
LOAD_CARRYING_KINDS = ("rigid-truck", "semitrailer", "btrain-lead", "full-trailer")
#: which unit kinds a coupling may join: (towing kinds, towed kinds)
COUPLING_KINDS: dict[str, tuple[tuple[str, ...], tuple[str, ...]]] = {
    "fifth-wheel": (("tractor", "dolly"), ("semitrailer", "btrain-lead")),
    "b-coupling": (("btrain-lead",), ("semitrailer", "btrain-lead")),
    "pintle": (("rigid-truck", "semitrailer", "btrain-lead", "full-trailer"), ("dolly", "full-trailer")),
}
ROLL_COUPLINGS = ("fifth-wheel", "b-coupling")
LEADING_KINDS = ("tractor", "rigid-truck")


@dataclass(frozen=True)
class AxleGroup:
    """One axle group of a unit (the load-sharing axles under one suspension), with per-axle values.

    id : a name unique within its unit (``"steer"``, ``"drive"``, ``"trailer"``) [-]
    axles : number of axles [-]
    tyres_per_axle : 2 (single tyres) or 4 (duals), up to 8 [-]
    track_m : T, lateral spacing of the tyre contacts; for duals, of the centres of the pairs [m]
    position_m : the group centre behind the unit's reference point (:data:`UNIT_KINDS`) [m]
    tyre_stiffness_kn_per_m : kT, vertical (radial) rate of one tyre [kN/m]
    roll_stiffness_knm_per_rad : suspension roll stiffness of one axle (springs and anti-roll) [kN m/rad]
    roll_centre_height_m : height above the road of the suspension's roll centre [m]
    unsprung_mass_kg : mass of one axle with its wheels, tyres and brakes [kg]
    unsprung_cg_height_m : height of the unsprung CG above the road (about the loaded radius) [m]
    lash_deg : the suspension's roll free play, each way from centre, before it takes a moment [deg]
    spring_spacing_m : lateral spacing of the springs (recorded; the roll stiffness is what the model uses) [m]
    steer : a steer group (the LLT limit and the PBS definition of the SRT leave it out) [-]
    """

    id: str
    axles: int
    tyres_per_axle: int
    track_m: float
    position_m: float
    tyre_stiffness_kn_per_m: float
    roll_stiffness_knm_per_rad: float
    roll_centre_height_m: float
    unsprung_mass_kg: float
    unsprung_cg_height_m: float
    lash_deg: float = 0.0
    spring_spacing_m: float | None = None
    steer: bool = False

    @property
    def tyre_side_stiffness_kn_per_m(self) -> float:
        """Vertical rate of all the group's tyres on one side: axles x tyres per axle / 2 x kT [kN/m]."""
        return self.axles * self.tyres_per_axle / 2.0 * self.tyre_stiffness_kn_per_m

    @property
    def tyre_roll_stiffness_knm_per_rad(self) -> float:
        """Roll stiffness of the group's tyres, k_side T^2 / 2 (two tyre lines at +-T/2, Eq. 2.11) [kN m/rad]."""
        return self.tyre_side_stiffness_kn_per_m * self.track_m**2 / 2.0

    @property
    def suspension_roll_stiffness_knm_per_rad(self) -> float:
        """Roll stiffness of the group's suspension, axles x per-axle stiffness [kN m/rad]."""
        return self.axles * self.roll_stiffness_knm_per_rad

    @property
    def unsprung_weight_kn(self) -> float:
        return self.axles * self.unsprung_mass_kg * G_M_PER_S2 / 1000.0


@dataclass(frozen=True)
class Unit:
    """One unit of the combination.

    id : a name unique within the combination (``"tractor"``, ``"trailer"``, ``"lead"``) [-]
    kind : one of :data:`UNIT_KINDS` [-]
    sprung_mass_kg : the sprung mass, everything but the axles: body, tare, payload [kg]
    cg_height_m : the sprung mass's CG height above the road [m]
    cg_position_m : the sprung CG behind the unit's reference point [m]
    groups : the axle groups, front to rear [-]
    title : a name for people [-]
    """

    id: str
    kind: str
    sprung_mass_kg: float
    cg_height_m: float
    cg_position_m: float
    groups: tuple[AxleGroup, ...]
    title: str | None = None

    @property
    def sprung_weight_kn(self) -> float:
        return self.sprung_mass_kg * G_M_PER_S2 / 1000.0

    @property
    def carries_load(self) -> bool:
        return self.kind in LOAD_CARRYING_KINDS


@dataclass(frozen=True)
class Coupling:
    """The coupling between unit i (towing) and unit i + 1 (towed).

    kind : ``fifth-wheel``, ``b-coupling`` or ``pintle`` (:data:`COUPLING_KINDS`) [-]
    position_m : on the towing unit, behind its reference point [m]
    height_m : height above the road of the fifth-wheel plate or the pintle [m]
    roll_stiffness_knm_per_rad : a fifth wheel's roll stiffness; None for a pintle (no roll moment) [kN m/rad]
    lash_deg : a fifth wheel's roll free play each way before it takes a moment [deg]
    """

    kind: str
    position_m: float
    height_m: float
    roll_stiffness_knm_per_rad: float | None = None
    lash_deg: float = 0.0

    @property
    def transmits_roll(self) -> bool:
        return self.kind in ROLL_COUPLINGS


@dataclass(frozen=True)
class Combination:
    """A combination vehicle: its units front to rear and the couplings between them.

    units : the units, towing unit first [-]
    couplings : ``len(units) - 1`` couplings; ``couplings[i]`` joins ``units[i]`` and ``units[i + 1]`` [-]
    title : a name for people [-]
    last_unit_record : the last unit as the thesis's vehicle record (:class:`engine.vehicle.Vehicle`), for the 3D
        model of the last unit; its ``front_llt_ratio`` is replaced by the combination's [-]
    front_llt_ratio : LLTf/LLTr for the 3D model of the last unit, given explicitly instead of computed by the
        whole-combination model [-]
    """

    units: tuple[Unit, ...]
    couplings: tuple[Coupling, ...] = ()
    title: str | None = None
    last_unit_record: Vehicle | None = None
    front_llt_ratio: float | None = None

    def to_dict(self) -> dict[str, Any]:
        """Every field as plain JSON types, wrapped as ``{"combination": {...}}`` (the canonical vehicle form)."""
        return {"combination": _plain(self)}

    @classmethod
    def from_dict(cls, data: Mapping[str, Any], *, path: str = "combination") -> Combination:
        """Build from plain dicts and lists (the ``combination`` object); unknown keys are refused naming them."""
        return _read(cls, data, path)

    def replace(self, **changes: Any) -> Combination:
        return replace(self, **changes)

    @property
    def last_unit(self) -> Unit:
        return self.units[-1]


def _plain(obj: Any) -> Any:
    if isinstance(obj, Vehicle):
        return obj.to_dict()
    if hasattr(obj, "__dataclass_fields__"):
        return {f.name: _plain(getattr(obj, f.name)) for f in fields(obj)}
    if isinstance(obj, tuple | list):
        return [_plain(v) for v in obj]
    return obj


def _read(cls: type, data: object, path: str):
    if not isinstance(data, Mapping):
        raise InvalidVehicle(f"{path} must be an object", field=path, value=data)
    names = {f.name: f for f in fields(cls)}
    unknown = sorted(set(data) - set(names))
    if unknown:
        raise InvalidVehicle(f"{path}.{unknown[0]} is not a field of {cls.__name__}", field=f"{path}.{unknown[0]}")
    kwargs = {}
    for name, f in names.items():
        if name not in data:
            if f.default is MISSING and f.default_factory is MISSING:
                raise InvalidVehicle(f"{path}.{name} is required", field=f"{path}.{name}")
            continue
        value = data[name]
        sub = f"{path}.{name}"
        if cls is Combination and name == "units":
            kwargs[name] = tuple(_read(Unit, u, f"{sub}[{i}]") for i, u in enumerate(_list(value, sub)))
        elif cls is Combination and name == "couplings":
            kwargs[name] = tuple(_read(Coupling, c, f"{sub}[{i}]") for i, c in enumerate(_list(value, sub)))
        elif cls is Unit and name == "groups":
            kwargs[name] = tuple(_read(AxleGroup, g, f"{sub}[{i}]") for i, g in enumerate(_list(value, sub)))
        elif cls is Combination and name == "last_unit_record":
            kwargs[name] = None if value is None else _vehicle(value, sub)
        else:
            kwargs[name] = value
    return cls(**kwargs)


def _list(value: object, path: str) -> list:
    if not isinstance(value, list | tuple):
        raise InvalidVehicle(f"{path} must be a list", field=path, value=value)
    return list(value)


def _vehicle(value: object, path: str) -> Vehicle:
    if isinstance(value, Vehicle):
        return value
    if not isinstance(value, Mapping):
        raise InvalidVehicle(f"{path} must be a vehicle record object", field=path, value=value)
    try:
        return Vehicle.from_dict(dict(value))
    except (TypeError, InvalidVehicle) as exc:
        raise InvalidVehicle(f"{path}: {exc}", field=path) from exc


# ------------------------------------------------------------------------------------------ validation


def _what(unit: Unit) -> str:
    return f"the {unit.kind} {unit.id!r}"


def _int(value: object, field: str, low: int, high: int, what: str) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or not low <= value <= high:
        message = f"{field} must be a whole number from {low} to {high} for {what}, got {value!r}"
        raise InvalidVehicle(message, field=field, value=value)
    return value


def validate_combination(c: Combination) -> None:
    """Refuse a combination that no real vehicle can be, naming the unit and the field.

    Checks: the chain (a tractor or rigid truck first; each coupling of a kind that joins those two units; a
    dolly and a tractor each tow something); per unit, its number of groups; every measurable value inside the
    plausible ranges of :mod:`engine.vehicle.plausibility` (with the likely unit slip); a roll centre below the
    sprung CG; a fifth wheel not behind the group it sits on; every static load positive, within the plausible
    load per axle, and each group carrying more than its own axles.

    Raises
    ------
    InvalidVehicle : ``field`` is the path as typed, ``combination.units[1].groups[0].track_m``.
    """
    if not isinstance(c, Combination):
        raise InvalidVehicle("the combination must be a Combination", field="combination")
    if not c.units:
        raise InvalidVehicle("a combination has at least one unit", field="combination.units")
    if len(c.units) > 8:
        raise InvalidVehicle("a combination has at most 8 units", field="combination.units")
    if len(c.couplings) != len(c.units) - 1:
        raise InvalidVehicle(
            f"{len(c.units)} units need {len(c.units) - 1} couplings (one between each two), got {len(c.couplings)}",
            field="combination.couplings",
        )
    ids = [u.id for u in c.units]
    for i, u in enumerate(c.units):
        _check_unit(u, f"combination.units[{i}]", first=i == 0)
        if ids.count(u.id) > 1:
            raise InvalidVehicle(f"unit id {u.id!r} is used twice", field=f"combination.units[{i}].id", value=u.id)
    for i, cp in enumerate(c.couplings):
        _check_coupling(cp, c.units[i], c.units[i + 1], f"combination.couplings[{i}]")
    for i, u in enumerate(c.units):
        towing = i < len(c.couplings)
        if u.kind in ("tractor", "dolly") and not towing:
            raise InvalidVehicle(
                f"{_what(u)} tows nothing: a {u.kind} carries a semitrailer on its fifth wheel (a dolly carrying "
                "nothing is no vehicle of its own)",
                field=f"combination.units[{i}].kind",
                value=u.kind,
            )
    if c.front_llt_ratio is not None:
        r = c.front_llt_ratio
        if isinstance(r, bool) or not isinstance(r, int | float) or not 0.0 < r <= 1.0:
            raise InvalidVehicle(
                f"combination.front_llt_ratio must be in (0, 1], got {r!r}",
                field="combination.front_llt_ratio",
                value=r,
            )
    loads = static_loads(c)
    for i, u in enumerate(c.units):
        for j, g in enumerate(u.groups):
            n = loads.normal_kn[(i, j)]
            path = f"combination.units[{i}].groups[{j}]"
            per_axle_kg = n / g.axles * 1000.0 / G_M_PER_S2
            if per_axle_kg <= g.unsprung_mass_kg:
                raise InvalidVehicle(
                    f"{path} ({g.id!r} of {_what(u)}) carries {per_axle_kg:.0f} kg per axle at rest, not more than "
                    f"its own axle ({g.unsprung_mass_kg:g} kg): the CG or the couplings put the load elsewhere "
                    "(a CG outside its supports, or a fifth wheel behind the group it sits on)",
                    field=f"combination.units[{i}].cg_position_m",
                    value=u.cg_position_m,
                )
            r = RANGES["axle_load_kg"]
            if per_axle_kg > r.maximum:
                blame = f"combination.units[{i}].sprung_mass_kg"
                check_plausible("axle_load_kg", per_axle_kg, blame, f"an axle of {path} ({g.id!r} of {_what(u)})")
    for i, cp in enumerate(c.couplings):
        if loads.coupling_kn[i] < 0 and cp.kind != "pintle":
            raise InvalidVehicle(
                f"the kingpin of {_what(c.units[i + 1])} would lift off its fifth wheel at rest: its CG lies behind "
                "its axle group",
                field=f"combination.units[{i + 1}].cg_position_m",
                value=c.units[i + 1].cg_position_m,
            )


def _check_unit(u: Unit, path: str, *, first: bool) -> None:
    if not isinstance(u.id, str) or not 0 < len(u.id) <= 40:
        raise InvalidVehicle(f"{path}.id must be a name of 1-40 characters", field=f"{path}.id", value=u.id)
    if u.kind not in UNIT_KINDS:
        raise InvalidVehicle(
            f"{path}.kind must be one of {', '.join(UNIT_KINDS)}, got {u.kind!r}", field=f"{path}.kind", value=u.kind
        )
    if first and u.kind not in LEADING_KINDS:
        raise InvalidVehicle(
            f"the first unit must be a tractor or a rigid truck (it stands on its own two axle groups), got {u.kind!r}",
            field=f"{path}.kind",
            value=u.kind,
        )
    if not first and u.kind in LEADING_KINDS:
        raise InvalidVehicle(
            f"a {u.kind} leads the combination; only the first unit can be one", field=f"{path}.kind", value=u.kind
        )
    ref, n_groups = UNIT_KINDS[u.kind]
    what = _what(u)
    if len(u.groups) != n_groups:
        raise InvalidVehicle(
            f"{what} has {n_groups} axle group(s) (one load-sharing group under each support), got {len(u.groups)}",
            field=f"{path}.groups",
        )
    check_plausible("unit_mass_kg", u.sprung_mass_kg, f"{path}.sprung_mass_kg", f"the sprung mass of {what}")
    check_plausible("height_m", u.cg_height_m, f"{path}.cg_height_m", f"the sprung CG of {what}")
    check_plausible("position_m", u.cg_position_m, f"{path}.cg_position_m", f"the sprung CG of {what} (behind {ref})")
    gids = [g.id for g in u.groups]
    for j, g in enumerate(u.groups):
        gp = f"{path}.groups[{j}]"
        gw = f"group {g.id!r} of {what}"
        if not isinstance(g.id, str) or not 0 < len(g.id) <= 40 or gids.count(g.id) > 1:
            raise InvalidVehicle(f"{gp}.id must be a name of 1-40 characters unique in its unit", field=f"{gp}.id")
        _int(g.axles, f"{gp}.axles", 1, 8, gw)
        _int(g.tyres_per_axle, f"{gp}.tyres_per_axle", 2, 8, gw)
        if g.tyres_per_axle % 2:
            raise InvalidVehicle(
                f"{gp}.tyres_per_axle must be even (as many tyres on each side)", field=f"{gp}.tyres_per_axle"
            )
        check_plausible("track_m", g.track_m, f"{gp}.track_m", gw)
        check_plausible("position_m", g.position_m, f"{gp}.position_m", f"{gw} (behind {ref})")
        check_plausible("tyre_stiffness_kn_per_m", g.tyre_stiffness_kn_per_m, f"{gp}.tyre_stiffness_kn_per_m", gw)
        check_plausible(
            "suspension_roll_stiffness_knm_per_rad",
            g.roll_stiffness_knm_per_rad,
            f"{gp}.roll_stiffness_knm_per_rad",
            gw,
        )
        check_plausible("height_m", g.roll_centre_height_m, f"{gp}.roll_centre_height_m", gw)
        check_plausible("unsprung_mass_kg", g.unsprung_mass_kg, f"{gp}.unsprung_mass_kg", gw)
        check_plausible("height_m", g.unsprung_cg_height_m, f"{gp}.unsprung_cg_height_m", gw)
        check_plausible("lash_deg", g.lash_deg, f"{gp}.lash_deg", f"the suspension of {gw}")
        if g.spring_spacing_m is not None:
            check_plausible("spring_spacing_m", g.spring_spacing_m, f"{gp}.spring_spacing_m", gw)
            if not g.spring_spacing_m < g.track_m:
                raise InvalidVehicle(
                    f"{gp}.spring_spacing_m ({g.spring_spacing_m} m) must be smaller than the track ({g.track_m} m)",
                    field=f"{gp}.spring_spacing_m",
                    value=g.spring_spacing_m,
                )
        if not isinstance(g.steer, bool):
            raise InvalidVehicle(f"{gp}.steer must be true or false", field=f"{gp}.steer", value=g.steer)
        if g.steer and not (u.kind in LEADING_KINDS and j == 0):
            raise InvalidVehicle(
                f"{gp}: only the front group of a tractor or rigid truck steers", field=f"{gp}.steer", value=g.steer
            )
        if not g.roll_centre_height_m < u.cg_height_m:
            raise InvalidVehicle(
                f"{gp}.roll_centre_height_m ({g.roll_centre_height_m} m) must lie below the sprung CG of {what} "
                f"({u.cg_height_m} m): the sprung mass rolls about its roll centres",
                field=f"{gp}.roll_centre_height_m",
                value=g.roll_centre_height_m,
            )
    if n_groups == 2 and not u.groups[0].position_m < u.groups[1].position_m:
        raise InvalidVehicle(
            f"the groups of {what} are listed front to rear: {path}.groups[1].position_m must exceed groups[0]'s",
            field=f"{path}.groups[1].position_m",
            value=u.groups[1].position_m,
        )
    if n_groups == 1 and not u.groups[0].position_m > 0:
        raise InvalidVehicle(
            f"the group of {what} lies behind {ref}: {path}.groups[0].position_m must be positive",
            field=f"{path}.groups[0].position_m",
            value=u.groups[0].position_m,
        )


def _check_coupling(cp: Coupling, towing: Unit, towed: Unit, path: str) -> None:
    if cp.kind not in COUPLING_KINDS:
        raise InvalidVehicle(
            f"{path}.kind must be one of {', '.join(COUPLING_KINDS)}, got {cp.kind!r}",
            field=f"{path}.kind",
            value=cp.kind,
        )
    towers, towees = COUPLING_KINDS[cp.kind]
    if towing.kind not in towers or towed.kind not in towees:
        raise InvalidVehicle(
            f"a {cp.kind} joins a towing {' or '.join(towers)} to a towed {' or '.join(towees)}; here it joins "
            f"{_what(towing)} to {_what(towed)}",
            field=f"{path}.kind",
            value=cp.kind,
        )
    what = f"the {cp.kind} behind {_what(towing)}"
    check_plausible("position_m", cp.position_m, f"{path}.position_m", what)
    check_plausible("height_m", cp.height_m, f"{path}.height_m", what)
    check_plausible("lash_deg", cp.lash_deg, f"{path}.lash_deg", what)
    rear = towing.groups[-1]
    if cp.transmits_roll:
        if cp.roll_stiffness_knm_per_rad is None:
            raise InvalidVehicle(
                f"{path}.roll_stiffness_knm_per_rad is required for a {cp.kind}",
                field=f"{path}.roll_stiffness_knm_per_rad",
            )
        check_plausible(
            "coupling_roll_stiffness_knm_per_rad", cp.roll_stiffness_knm_per_rad, f"{path}.roll_stiffness_knm_per_rad",
            what,
        )  # fmt: skip
        if cp.position_m > rear.position_m and towing.kind in ("tractor", "dolly"):  # a B-coupling may overhang
            raise InvalidVehicle(
                f"{path}.position_m ({cp.position_m} m) puts {what} behind the group it sits on ({rear.id!r} at "
                f"{rear.position_m} m): the load behind it would lift the front of {_what(towing)}",
                field=f"{path}.position_m",
                value=cp.position_m,
            )
        if towing.kind == "tractor" and cp.position_m <= towing.groups[0].position_m:
            raise InvalidVehicle(
                f"{path}.position_m ({cp.position_m} m) puts {what} ahead of its steer axle",
                field=f"{path}.position_m",
                value=cp.position_m,
            )
    else:
        if cp.roll_stiffness_knm_per_rad not in (None, 0, 0.0):
            raise InvalidVehicle(
                f"{path}: a pintle transmits no roll moment; leave roll_stiffness_knm_per_rad null",
                field=f"{path}.roll_stiffness_knm_per_rad",
                value=cp.roll_stiffness_knm_per_rad,
            )
        if cp.lash_deg:
            raise InvalidVehicle(f"{path}: a pintle has no roll lash", field=f"{path}.lash_deg", value=cp.lash_deg)
        if cp.position_m < rear.position_m:
            raise InvalidVehicle(
                f"{path}.position_m ({cp.position_m} m) puts the pintle ahead of the rear group of {_what(towing)}",
                field=f"{path}.position_m",
                value=cp.position_m,
            )


# --------------------------------------------------------------------------------------- static loads


@dataclass(frozen=True)
class UnitLoad:
    """The load case applied to one load-carrying unit: CG offsets and overweight (as :class:`engine.LoadCase`)."""

    lateral_offset_m: float = 0.0
    longitudinal_offset_m: float = 0.0
    vertical_offset_m: float = 0.0
    overweight_percent: float = 0.0


@dataclass(frozen=True)
class LoadedUnit:
    """A unit with the load case applied: sprung weight [kN], CG height and position [m], lateral offset d1 [m]."""

    weight_kn: float
    cg_height_m: float
    cg_position_m: float
    lateral_offset_m: float


def loaded_units(c: Combination, load: UnitLoad | None = None) -> list[LoadedUnit]:
    """Each unit's sprung weight and CG with the load case: overweight scales the sprung weight of the load-carrying
    units (the 3D model scales the trailer's weight, Sec. 9.4); d2 (+ forward) moves their CG forward, d3 up, d1
    (+ toward the outside of the turn) sideways. Tractors and dollies keep theirs."""
    load = load or UnitLoad()
    out = []
    for u in c.units:
        if u.carries_load:
            out.append(
                LoadedUnit(
                    u.sprung_weight_kn * (1.0 + load.overweight_percent / 100.0),
                    u.cg_height_m + load.vertical_offset_m,
                    u.cg_position_m - load.longitudinal_offset_m,
                    load.lateral_offset_m,
                )
            )
        else:
            out.append(LoadedUnit(u.sprung_weight_kn, u.cg_height_m, u.cg_position_m, 0.0))
    return out


@dataclass(frozen=True)
class StaticLoads:
    """Normal loads of the groups and couplings: ``normal factor * normal_kn + sin(grade) * grade_kn``.

    normal_kn : ``(unit, group) ->`` the ground normal load per unit normal weight factor (level road) [kN]
    grade_kn : ``(unit, group) ->`` the change per unit sin(grade), positive uphill (load moves rearward) [kN]
    coupling_kn / coupling_grade_kn : the same for the vertical load each coupling passes to the towing unit [kN]
    """

    normal_kn: dict[tuple[int, int], float] = field(default_factory=dict)
    grade_kn: dict[tuple[int, int], float] = field(default_factory=dict)
    coupling_kn: dict[int, float] = field(default_factory=dict)
    coupling_grade_kn: dict[int, float] = field(default_factory=dict)


def static_loads(c: Combination, units: list[LoadedUnit] | None = None) -> StaticLoads:
    """The groups' and couplings' normal loads (see the module docstring), from the last unit forward."""
    units = units if units is not None else loaded_units(c)
    out = StaticLoads()
    for normal, grade, target_n, target_c in ((1.0, 0.0, out.normal_kn, out.coupling_kn),
                                              (0.0, 1.0, out.grade_kn, out.coupling_grade_kn)):  # fmt: skip
        behind_down, behind_long = 0.0, 0.0  # what the towed unit puts on the coupling ahead of it
        for i in range(len(c.units) - 1, -1, -1):
            u, lu = c.units[i], units[i]
            down = [(lu.weight_kn * normal, lu.cg_position_m)]  # (force, x)
            rearward = [(lu.weight_kn * grade, lu.cg_height_m)]  # (force, z)
            for g in u.groups:
                down.append((g.unsprung_weight_kn * normal, g.position_m))
                rearward.append((g.unsprung_weight_kn * grade, g.unsprung_cg_height_m))
            if i < len(c.couplings):  # the towed unit's load on this unit's coupling
                cp = c.couplings[i]
                down.append((behind_down, cp.position_m))
                rearward.append((behind_long, cp.height_m))
            total_down = sum(f for f, _ in down)
            total_long = sum(f for f, _ in rearward)
            moment = sum(f * x for f, x in down) + sum(f * z for f, z in rearward)  # about the road below x = 0
            towed_by = c.couplings[i - 1] if i > 0 else None
            if towed_by is not None:  # free-rolling tyres: the coupling ahead pulls the unit's whole load forward
                moment -= total_long * towed_by.height_m
            if len(u.groups) == 2:  # two groups; a full trailer's hinged drawbar carries nothing vertical
                (x1, x2) = (u.groups[0].position_m, u.groups[1].position_m)
                n2 = (moment - x1 * total_down) / (x2 - x1)
                target_n[(i, 0)], target_n[(i, 1)] = total_down - n2, n2
                front = 0.0
            else:  # the coupling ahead (at x = 0) and the one group
                n = moment / u.groups[0].position_m
                target_n[(i, 0)] = n
                front = total_down - n
            if towed_by is not None:
                target_c[i - 1] = front
            behind_down, behind_long = front, total_long
    return out


def roll_coupled_units(c: Combination) -> list[tuple[int, ...]]:
    """The units that roll together: the chain cut at every coupling that transmits no roll moment (a pintle)."""
    out, current = [], [0]
    for i, cp in enumerate(c.couplings):
        if cp.transmits_roll:
            current.append(i + 1)
        else:
            out.append(tuple(current))
            current = [i + 1]
    out.append(tuple(current))
    return out


def kingpin_group(c: Combination, towed_index: int) -> tuple[int, int]:
    """(unit, group) of the towing unit's group under the coupling ahead of unit ``towed_index``: the group that the
    towed unit's front rests on (the 'front group' of the thesis's 3D model of a trailer)."""
    i = towed_index - 1
    cp = c.couplings[i]
    groups = c.units[i].groups
    j = min(range(len(groups)), key=lambda k: abs(groups[k].position_m - cp.position_m))
    return i, j


def unit_weight_kn(u: Unit) -> float:
    """The unit's whole weight, sprung and unsprung [kN]."""
    return u.sprung_weight_kn + sum(g.unsprung_weight_kn for g in u.groups)


def check_combination_load(c: Combination, load: UnitLoad) -> None:
    """Refuse a load case that puts a load-carrying unit's CG outside its track, below its roll centres, or where a
    support would carry no load; and the load fields outside :data:`engine.domain.BOUNDS`."""
    from engine.domain import check
    from engine.errors import InvalidLoad

    for name in ("lateral_offset_m", "longitudinal_offset_m", "vertical_offset_m", "overweight_percent"):
        check(name, getattr(load, name), f"load.{name}")
    carriers = [u for u in c.units if u.carries_load]
    if not carriers and any(getattr(load, n) for n in ("lateral_offset_m", "longitudinal_offset_m",
                                                       "vertical_offset_m", "overweight_percent")):  # fmt: skip
        raise InvalidLoad(
            "the load case applies to the load-carrying units, and this combination has none", field="load"
        )
    for u in carriers:
        half = min(g.track_m for g in u.groups) / 2.0
        if abs(load.lateral_offset_m) >= half:
            raise InvalidLoad(
                f"load.lateral_offset_m = {load.lateral_offset_m} m puts the CG of {_what(u)} outside its track "
                f"(half track {half} m)",
                field="load.lateral_offset_m",
                value=load.lateral_offset_m,
            )
        h = u.cg_height_m + load.vertical_offset_m
        top = max(g.roll_centre_height_m for g in u.groups)
        if not h > top:
            raise InvalidLoad(
                f"load.vertical_offset_m = {load.vertical_offset_m} m puts the sprung CG of {_what(u)} at {h:.3f} m, "
                f"not above its roll centre ({top} m)",
                field="load.vertical_offset_m",
                value=load.vertical_offset_m,
            )
    lu = loaded_units(c, load)
    st = static_loads(c, lu)
    for i, u in enumerate(c.units):
        for j, g in enumerate(u.groups):
            if st.normal_kn[(i, j)] <= g.unsprung_weight_kn:
                field = "load.longitudinal_offset_m" if load.longitudinal_offset_m else "load.overweight_percent"
                raise InvalidLoad(
                    f"with this load case group {g.id!r} of {_what(u)} carries no more than its own axles: the CG "
                    "lies outside its supports",
                    field=field,
                    value=getattr(load, field.split(".")[1]),
                )
    for i, cp in enumerate(c.couplings):
        if cp.kind != "pintle" and st.coupling_kn[i] <= 0:
            raise InvalidLoad(
                f"with this load case the kingpin of {_what(c.units[i + 1])} lifts off its fifth wheel",
                field="load.longitudinal_offset_m",
                value=load.longitudinal_offset_m,
            )

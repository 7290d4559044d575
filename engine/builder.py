"""Vehicle builder: a specification in measurable terms -> the engine's vehicle record, with its derivation.

Certifiers and operators know a vehicle by its unit type, axle groups, tyres, suspension type, masses and deck and
load heights (the inputs of the TERNZ / NZTA SRT calculator), not by the thesis's 23 record fields. A
:class:`VehicleSpec` holds those measurable inputs; :func:`build_vehicle` turns it into the
:class:`engine.vehicles.Vehicle` record and says, for every record field, how its value was obtained
(``given``, ``computed``, ``library`` or ``default``), by what formula, and from which source.

Mapping (details and limits in ``docs/vehicles.md``)
------------------------------------------------------
* W = (tare + payloads) g, g = 9.81 m/s^2 (:data:`G_M_PER_S2`).
* Composite CG: h = sum(m_i z_i) / sum(m_i) above the ground, x = sum(m_i x_i) / sum(m_i) behind the kingpin
  (the front axle group of a rigid truck).
* l12 = h - (lr + ls): the record measures the CG from the chassis reference lr + ls
  (:func:`engine.vehicles.cg_height_m`); a = x; L = the rear group centre's distance; l13 = the front group
  centre's distance (0 for a truck).
* A payload's CG: uniform density between deck and load top: mid-height (TERNZ "uniform density"); "mixed
  freight", 70 % of the mass in the bottom half of the load space: 0.4 of the load height above the deck (TERNZ);
  a sloping deck (heights varying linearly along the load): the centroid of the side-view trapezoid, integrated
  exactly; a liquid in a circular or elliptical tank: the centroid of the liquid segment (closed form).
* The record's single kLs, kT, lr, ls and b are the **rear** group's (the unit's own group, whose inner tyre
  lift-off is the limit); the front group contributes its axles, tyres per axle and track. Where the front group's
  components differ, the derivation says so: the record cannot represent the difference.

References
----------
.. [1] Moreno, G. G., *Static rollover threshold of long combination vehicles* (doctoral thesis), Tables 15, 16,
   22, 23; Eqs. 2.11, 4.27; Sec. 4.1.1; Ch. 9 (Kamnik et al., 2003: LLTf = 0.7 LLTr).
.. [2] TERNZ / NZ Transport Agency, *SRT Calculator* help ("Load Categories", ternz.co.nz/SRT_Calculator/
   mainhelp.html; the same text on Main Roads WA's mrwebapps.mainroads.wa.gov.au/srtcalculator/mainhelp.html).
.. [3] Centroid of a circular segment, ybar = 4 R sin^3(theta/2) / (3 (theta - sin theta)) from the centre: the
   sector (area R^2 theta/2, centroid 4 R sin(theta/2) / (3 theta) from the centre; Wolfram MathWorld, "Circular
   Sector", after Gearhart and Schulz, 1990) minus its triangle (area R^2 sin(theta)/2, centroid 2/3 R cos(theta/2)).
"""

from __future__ import annotations

import math
import types
import typing
from collections.abc import Mapping, Sequence
from dataclasses import MISSING, asdict, dataclass, field, fields, is_dataclass, replace

from scipy.optimize import brentq

from .bracket import bracketed_limit
from .case import Case
from .components import (
    Sourced,
    get_suspension,
    get_tyre,
    parse_tyre_size,
    rated_load_from_load_index_kg,
    spring_rate_from_roll_stiffness,
)
from .errors import InvalidInput, InvalidVehicle, RolloverError
from .loads import LoadCase, Road
from .models import get_model
from .threshold import rollover_threshold
from .vehicles import FIELD_DOCS, Vehicle

#: gravitational acceleration used for W = m g [m/s^2]. With it two of the thesis's weights are masses rounded to
#: 10 kg (Table 15: 364.147 kN = 37 120 kg g; Table 16: 355.22 kN = 36 210 kg g, within 0.02 kg); with 9.80665
#: neither is (37 132.66 and 36 222.36 kg).
G_M_PER_S2 = 9.81

UNIT_TYPES = ("semitrailer", "btrain-rear", "rigid-truck")
TRAILER_TYPES = ("semitrailer", "btrain-rear")

#: height of a payload's CG above the deck as a fraction of the load thickness, per load category [2]
LOAD_DISTRIBUTIONS = {
    "uniform": 0.5,  # TERNZ "uniform density": CG midway between load bed and load height
    "mixed-freight": 0.4,  # TERNZ "mixed freight": 70 % of the mass in the bottom half: 0.7/4 + 0.3 * 3/4
}
TANK_SHAPES = ("circular", "elliptical")
METHODS = ("given", "computed", "library", "default")

_THESIS = "Moreno (thesis)"

# --------------------------------------------------------------------------------------------- the spec


@dataclass(frozen=True)
class TyreSpec:
    """Tyres of an axle group: a library ``id`` and/or explicit data (explicit values win).

    id : a tyre of the component library (:data:`engine.components.TYRES`), by its id
    size : size designation (``"295/80R22.5"``, ``"11R22.5"``): its section width and rim bound the geometry
    loaded_radius_m : lr, static loaded (dynamic rolling) radius [m]
    stiffness_kn_per_m : kT, vertical (radial) stiffness of one tyre [kN/m]
    section_width_m : section width of one tyre [m] (else read from ``size``)
    rated_load_kg : the load one tyre may carry in this fitment (single or dual) [kg]
    load_index : or the sidewall load indices, ``"152/148"`` (single/dual) or ``"160"`` (single only): the rated
        load of this fitment from the ISO load-index table (:func:`engine.components.rated_load_from_load_index_kg`)
    """

    id: str | None = None
    size: str | None = None
    loaded_radius_m: float | None = None
    stiffness_kn_per_m: float | None = None
    section_width_m: float | None = None
    rated_load_kg: float | None = None
    load_index: str | None = None


@dataclass(frozen=True)
class SuspensionSpec:
    """Suspension of an axle group: a library ``type`` and/or explicit data (explicit values win).

    type : a suspension of the component library (:data:`engine.components.SUSPENSIONS`), by its id
    stiffness_kn_per_m : kLs, vertical rate of the spring on one side of one axle [kN/m]
    roll_stiffness_knm_per_rad : roll stiffness of one axle [kN m/rad]; mapped to kLs = 2 k_theta / b^2 (Eq. 2.11)
    height_m : ls, static suspension height at the rated load [m]
    spring_separation_m : b, lateral spacing of the two springs [m]
    """

    type: str | None = None
    stiffness_kn_per_m: float | None = None
    roll_stiffness_knm_per_rad: float | None = None
    height_m: float | None = None
    spring_separation_m: float | None = None


@dataclass(frozen=True)
class AxleGroupSpec:
    """One axle group. The model has one equivalent axle per group at the group centre.

    axles : number of axles [-]
    tyres_per_axle : 2 (single tyres) or 4 (duals) [-]
    track_m : lateral spacing of the tyre contacts; for duals, of the centres of the dual pairs [m]
    centre_from_kingpin_m : group centre behind the kingpin (truck: behind the front group centre) [m]
    axle_spacing_m : spread between adjacent axles [m] (recorded; the one-equivalent-axle model does not use it)
    tyre : the group's tyres (the front group's default to the rear group's)
    suspension : the group's suspension (the front group's default to the rear group's)
    rated_load_kg : the largest load the group may carry [kg]; the built vehicle's static load is checked against it
    """

    axles: int
    tyres_per_axle: int
    track_m: float
    centre_from_kingpin_m: float | None = None
    axle_spacing_m: float | None = None
    tyre: TyreSpec | None = None
    suspension: SuspensionSpec | None = None
    rated_load_kg: float | None = None


@dataclass(frozen=True)
class TareSpec:
    """The unit's unladen mass with its CG.

    mass_kg : tare mass of the unit (a semi-trailer: the whole trailer, kingpin load included) [kg]
    cg_height_m : tare CG height above the ground [m]; default (assumed): the lowest deck height
    cg_from_kingpin_m : tare CG behind the kingpin (truck: behind the front group centre) [m]
    rear_group_load_kg : alternatively, the tare load on the rear group (weighbridge): x = L m_rear / m [kg]
    """

    mass_kg: float
    cg_height_m: float | None = None
    cg_from_kingpin_m: float | None = None
    rear_group_load_kg: float | None = None


@dataclass(frozen=True)
class TankSpec:
    """A liquid payload in a tank of circular or elliptical cross-section (constant along its length).

    height_m : inside height of the tank (the diameter of a circular one) [m]
    bottom_height_m : height of the inside bottom above the ground [m]
    shape : ``circular`` or ``elliptical`` [-]
    fill_height_m : liquid depth (or give fill_fraction) [m]
    fill_fraction : liquid volume / tank volume (or give fill_height_m) [-]
    """

    height_m: float
    bottom_height_m: float
    shape: str = "circular"
    fill_height_m: float | None = None
    fill_fraction: float | None = None


@dataclass(frozen=True)
class PayloadSpec:
    """One payload: its mass, how high it sits (one of three ways) and where along the unit.

    mass_kg : payload mass [kg]
    deck_height_m : deck (load bed) above the ground, at the load's front [m]
    load_height_m : top of the load above the ground, at the load's front [m]
    deck_height_rear_m : deck height at the load's rear, for a sloping deck [m]
    load_height_rear_m : load top at the load's rear, for a sloping deck (default: parallel to the deck) [m]
    distribution : ``uniform`` (CG at mid-height) or ``mixed-freight`` (0.4 of the height) [-]
    cg_height_m : the payload CG height above the ground, instead of deck and load heights [m]
    tank : a liquid in a tank (its CG from the tank's geometry), instead of deck and load heights
    front_from_kingpin_m : front end of the load behind the kingpin (default: the load centred on the deck) [m]
    length_m : length of the load (default: the deck's length) [m]
    cg_from_kingpin_m : the payload CG's distance behind the kingpin, instead of the load's extent [m]
    """

    mass_kg: float
    deck_height_m: float | None = None
    load_height_m: float | None = None
    deck_height_rear_m: float | None = None
    load_height_rear_m: float | None = None
    distribution: str = "uniform"
    cg_height_m: float | None = None
    tank: TankSpec | None = None
    front_from_kingpin_m: float | None = None
    length_m: float | None = None
    cg_from_kingpin_m: float | None = None


@dataclass(frozen=True)
class DeckSpec:
    """The load space.

    front_from_kingpin_m : front end of the load space behind the kingpin (truck: the front group centre) [m]
    length_m : length of the load space [m]
    """

    front_from_kingpin_m: float
    length_m: float


@dataclass(frozen=True)
class FrontUnitSpec:
    """Front-unit and chassis data; every value defaults as documented in :func:`build_vehicle`.

    fifth_wheel_stiffness_kn_per_m : kf, rate of each fifth-wheel spring [kN/m]
    fifth_wheel_height_m : lf, initial height of the fifth wheel above the front bolster [m]
    fifth_wheel_width_m : b1, width of the fifth wheel (separation of its two springs) [m]
    front_llt_ratio : LLTf / LLTr at the limit [-]
    chassis_torsional_stiffness_knm2_per_rad : G Jr, torsional stiffness of the chassis; absent: rigid [kN m^2/rad]
    """

    fifth_wheel_stiffness_kn_per_m: float | None = None
    fifth_wheel_height_m: float | None = None
    fifth_wheel_width_m: float | None = None
    front_llt_ratio: float | None = None
    chassis_torsional_stiffness_knm2_per_rad: float | None = None


@dataclass(frozen=True)
class VehicleSpec:
    """A vehicle in measurable terms (see the module docstring). Overweight and CG offsets are load cases.

    unit_type : ``semitrailer`` (front group = the tractor's drive group under the fifth wheel), ``btrain-rear``
        (the last trailer of a B-train: front group = the lead trailer's group under the fifth wheel) or
        ``rigid-truck`` (front group = the steer axle(s), no fifth wheel)
    rear : the rear axle group (the last unit's own)
    front : the front axle group (under the fifth wheel; a rigid truck's steer group)
    tare : the unladen mass
    payloads : 0 or more payloads (two decks: two payloads)
    deck : the load space (for payload positions)
    front_unit : fifth-wheel and chassis data
    title : a name for the vehicle (shown in results) [-]
    """

    unit_type: str
    rear: AxleGroupSpec
    front: AxleGroupSpec
    tare: TareSpec
    payloads: tuple[PayloadSpec, ...] = ()
    deck: DeckSpec | None = None
    front_unit: FrontUnitSpec = field(default_factory=FrontUnitSpec)
    title: str | None = None

    @classmethod
    def from_dict(cls, data: Mapping[str, typing.Any]) -> VehicleSpec:
        """Build from plain dicts and lists; unknown keys are refused, naming them (``spec.rear.tyre.foo``)."""
        return _from_dict(cls, data, "spec")

    def to_dict(self) -> dict[str, typing.Any]:
        return asdict(self)


def _from_dict(cls: type, data: object, path: str):
    if not isinstance(data, Mapping):
        raise InvalidVehicle(f"{path} must be an object, got {type(data).__name__}", field=path, value=data)
    names = [f.name for f in fields(cls)]
    unknown = sorted(set(data) - set(names))
    if unknown:
        raise InvalidVehicle(
            f"unknown field(s) in {path}: {', '.join(unknown)}; known: {', '.join(names)}",
            field=f"{path}.{unknown[0]}",
            value=unknown,
        )
    hints = typing.get_type_hints(cls)
    kwargs = {}
    for f in fields(cls):
        if f.name in data:
            kwargs[f.name] = _convert(hints[f.name], data[f.name], f"{path}.{f.name}")
        elif f.default is MISSING and f.default_factory is MISSING:
            raise InvalidVehicle(f"{path}.{f.name} is required", field=f"{path}.{f.name}")
    return cls(**kwargs)


def _convert(tp: typing.Any, value: object, path: str):
    if value is None:
        return None
    origin, args = typing.get_origin(tp), typing.get_args(tp)
    if origin in (typing.Union, types.UnionType):
        tp = next(a for a in args if a is not type(None))
        origin, args = typing.get_origin(tp), typing.get_args(tp)
    if is_dataclass(tp):
        return _from_dict(tp, value, path)
    if origin is tuple:
        if not isinstance(value, list | tuple):
            raise InvalidVehicle(f"{path} must be a list", field=path, value=value)
        return tuple(_convert(args[0], item, f"{path}[{i}]") for i, item in enumerate(value))
    return value


# -------------------------------------------------------------------------------------------- the result


@dataclass(frozen=True)
class FieldDerivation:
    """How one record field was obtained.

    method : ``given`` (an input as is), ``computed`` (a formula of inputs), ``library`` (a component library
        value) or ``default`` (a documented default)
    explanation : the formula or reason, one line; source : the document, the input path, or ``assumed: why``
    spec_path : the spec input the value comes from (errors on the record field point there)
    """

    field: str
    value: float | int | None
    unit: str
    method: str
    explanation: str
    source: str
    spec_path: str | None = None


@dataclass(frozen=True)
class MassItem:
    """One mass of the composite: tare or a payload, with its CG and how the CG was obtained."""

    name: str
    mass_kg: float
    cg_height_m: float
    cg_from_kingpin_m: float
    explanation: str


@dataclass(frozen=True)
class BuiltVehicle:
    """The record, the derivation of every field, the masses behind the CG and notes on what is not represented."""

    vehicle: Vehicle
    derivation: dict[str, FieldDerivation]
    masses: tuple[MassItem, ...]
    gross_mass_kg: float
    cg_height_m: float  # composite CG above the ground [m]
    cg_from_kingpin_m: float  # composite CG behind the kingpin / front group [m]
    group_loads_kg: dict[str, float]  # static loads, lever rule (Eq. 4.27 at rest): "front" (kingpin), "rear"
    notes: tuple[str, ...] = ()

    def to_dict(self) -> dict[str, typing.Any]:
        out = asdict(self)
        out["vehicle"] = self.vehicle.to_dict()
        return out


# ------------------------------------------------------------------------------------------ input checks


def _number(value: object, path: str, *, minimum: float = 0.0, strict: bool = True, reason: str = "") -> float:
    """A finite number above ``minimum`` (or at it when not ``strict``); InvalidVehicle naming ``path``."""
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise InvalidVehicle(f"{path} must be a finite number, got {value!r}", field=path, value=value)
    if value < minimum or (strict and value == minimum):
        bound = f"above {minimum:g}" if strict else f"at least {minimum:g}"
        raise InvalidVehicle(f"{path} must be {bound}, got {value:g}{reason}", field=path, value=value)
    return float(value)


def _count(value: object, path: str, allowed: Sequence[int] | None = None) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or value < 1:
        raise InvalidVehicle(f"{path} must be a positive whole number, got {value!r}", field=path, value=value)
    if allowed is not None and value not in allowed:
        raise InvalidVehicle(
            f"{path} must be one of {', '.join(map(str, allowed))} (2 = single tyres, 4 = duals: the model has one "
            f"tyre column per side, Sec. 4.1), got {value}",
            field=path,
            value=value,
        )
    return value


def _one_of(value: object, path: str, allowed: Sequence[str]) -> str:
    if value not in allowed:
        raise InvalidVehicle(f"{path} must be one of {', '.join(allowed)}, got {value!r}", field=path, value=value)
    return typing.cast(str, value)


# -------------------------------------------------------------------------------------- components


@dataclass(frozen=True)
class _Value:
    value: float
    method: str
    explanation: str
    source: str
    path: str


@dataclass(frozen=True)
class _Group:
    """A resolved axle group: counts, track and the component values with their provenance."""

    path: str
    axles: int
    tyres_per_axle: int
    track_m: float
    lr: _Value | None
    kt: _Value | None
    kls: _Value | None
    ls: _Value | None
    b: _Value | None
    section_width_m: float | None
    tyre_rated_load_kg: float | None
    rated_load_kg: float | None


def _pick(explicit: object, library: Sourced | None, path: str, lib_path: str, name: str) -> _Value | None:
    if explicit is not None:
        return _Value(_number(explicit, path), "given", f"{name} as given", path, path)
    if library is not None:
        return _Value(library.value, "library", f"{name} from the component library", library.source, lib_path)
    return None


def _resolve_tyre(
    spec: TyreSpec, path: str, tyres_per_axle: int
) -> tuple[_Value | None, _Value | None, float | None, float | None]:
    entry = get_tyre(spec.id, field=f"{path}.id") if spec.id is not None else None
    lib_path = f"{path}.id"
    lr = _pick(spec.loaded_radius_m, entry and entry.loaded_radius_m, f"{path}.loaded_radius_m", lib_path, "lr")
    kt = _pick(
        spec.stiffness_kn_per_m, entry and entry.stiffness_kn_per_m, f"{path}.stiffness_kn_per_m", lib_path, "kT"
    )
    size = parse_tyre_size(spec.size, field=f"{path}.size") if spec.size is not None else None
    if size is None and entry is not None and entry.size is not None:
        size = parse_tyre_size(entry.size, field=lib_path)
    width = _number(spec.section_width_m, f"{path}.section_width_m") if spec.section_width_m is not None else None
    if width is None and size is not None:
        width = size.section_width_m
    if lr is not None and size is not None:
        _check_loaded_radius(lr.value, size, lr.path)
    rated = spec.rated_load_kg
    if spec.load_index is not None:
        if rated is not None:
            raise InvalidVehicle(
                f"give either {path}.rated_load_kg or {path}.load_index, not both",
                field=f"{path}.load_index",
                value=spec.load_index,
            )
        rated = rated_load_from_load_index_kg(spec.load_index, tyres_per_axle, field=f"{path}.load_index")
    if rated is None and entry is not None and entry.rated_load_kg is not None:
        rated = entry.rated_load_kg.value
    rated = _number(rated, f"{path}.rated_load_kg") if rated is not None else None
    return lr, kt, width, rated


def _check_loaded_radius(lr: float, size, path: str) -> None:
    if lr <= size.rim_radius_m:
        raise InvalidVehicle(
            f"{path} = {lr:g} m is not above the rim radius of a {size.designation} tyre ({size.rim_radius_m:.4f} m)",
            field=path,
            value=lr,
        )
    free = size.nominal_free_radius_m
    if free is not None and lr >= free:
        raise InvalidVehicle(
            f"{path} = {lr:g} m is not below the nominal unloaded radius of a {size.designation} tyre "
            f"({free:.4f} m = rim/2 + width x aspect ratio): a loaded tyre is deflected",
            field=path,
            value=lr,
        )


def _resolve_suspension(spec: SuspensionSpec, path: str) -> tuple[_Value | None, _Value | None, _Value | None]:
    entry = get_suspension(spec.type, field=f"{path}.type") if spec.type is not None else None
    lib_path = f"{path}.type"
    ls = _pick(spec.height_m, entry and entry.height_m, f"{path}.height_m", lib_path, "ls")
    b = _pick(
        spec.spring_separation_m, entry and entry.spring_separation_m, f"{path}.spring_separation_m", lib_path, "b"
    )
    if spec.roll_stiffness_knm_per_rad is not None:
        roll_path = f"{path}.roll_stiffness_knm_per_rad"
        if spec.stiffness_kn_per_m is not None:
            raise InvalidVehicle(
                f"give either {path}.stiffness_kn_per_m or {roll_path}, not both (Eq. 2.11 ties them through b)",
                field=roll_path,
                value=spec.roll_stiffness_knm_per_rad,
            )
        k_theta = _number(spec.roll_stiffness_knm_per_rad, roll_path)
        if b is None:
            raise InvalidVehicle(f"{roll_path} needs the spring separation b", field=f"{path}.spring_separation_m")
        kls = _Value(
            spring_rate_from_roll_stiffness(k_theta, b.value),
            "computed",
            f"kLs = 2 k_theta / b^2 = 2 x {k_theta:g} / {b.value:g}^2 (Eq. 2.11)",
            f"{roll_path}; Eq. 2.11",
            roll_path,
        )
    else:
        kls = _pick(
            spec.stiffness_kn_per_m, entry and entry.stiffness_kn_per_m, f"{path}.stiffness_kn_per_m", lib_path, "kLs"
        )
    return kls, ls, b


def _resolve_group(spec: AxleGroupSpec, path: str) -> _Group:
    if not isinstance(spec, AxleGroupSpec):
        raise InvalidVehicle(f"{path} must be an axle group", field=path, value=spec)
    lr = kt = kls = ls = b = None
    width = tyre_rated = None
    tyres_per_axle = _count(spec.tyres_per_axle, f"{path}.tyres_per_axle", (2, 4))
    if spec.tyre is not None:
        lr, kt, width, tyre_rated = _resolve_tyre(spec.tyre, f"{path}.tyre", tyres_per_axle)
    if spec.suspension is not None:
        kls, ls, b = _resolve_suspension(spec.suspension, f"{path}.suspension")
    if spec.axle_spacing_m is not None:
        _number(spec.axle_spacing_m, f"{path}.axle_spacing_m")
    rated = _number(spec.rated_load_kg, f"{path}.rated_load_kg") if spec.rated_load_kg is not None else None
    return _Group(
        path=path,
        axles=_count(spec.axles, f"{path}.axles"),
        tyres_per_axle=tyres_per_axle,
        track_m=_number(spec.track_m, f"{path}.track_m"),
        lr=lr,
        kt=kt,
        kls=kls,
        ls=ls,
        b=b,
        section_width_m=width,
        tyre_rated_load_kg=tyre_rated,
        rated_load_kg=rated,
    )


_COMPONENTS = (  # record field, _Group attribute, the input to name, what else would do
    ("rolling_radius_m", "lr", "tyre.loaded_radius_m", "or tyre.id"),
    ("tire_stiffness_kn_per_m", "kt", "tyre.stiffness_kn_per_m", "or tyre.id"),
    ("suspension_stiffness_kn_per_m", "kls", "suspension.stiffness_kn_per_m", "roll_stiffness_knm_per_rad or type"),
    ("suspension_height_m", "ls", "suspension.height_m", "or suspension.type"),
    ("spring_separation_m", "b", "suspension.spring_separation_m", "or suspension.type"),
)


def _component_fields(rear: _Group, front: _Group) -> tuple[dict[str, FieldDerivation], list[str]]:
    """The record's shared component fields, from the rear group; notes where the front group differs."""
    out: dict[str, FieldDerivation] = {}
    notes = []
    for name, attr, what, alternative in _COMPONENTS:
        v: _Value | None = getattr(rear, attr)
        if v is None:
            raise InvalidVehicle(
                f"{name} ({FIELD_DOCS[name].symbol}) is unknown: give {rear.path}.{what}, {alternative}",
                field=f"{rear.path}.{what}",
            )
        out[name] = FieldDerivation(name, v.value, FIELD_DOCS[name].unit, v.method, v.explanation, v.source, v.path)
        f: _Value | None = getattr(front, attr)
        if f is not None and not math.isclose(f.value, v.value, rel_tol=1e-9):
            notes.append(
                f"{name}: the front group's {f.value:g} {FIELD_DOCS[name].unit} ({f.path}) differs from the rear "
                f"group's {v.value:g}; the record has one value for both groups and keeps the rear group's (the "
                "unit's own group, whose inner tyre lift-off is the limit)"
            )
    return out, notes


def _check_width(group: _Group, b: float) -> None:
    """Springs inboard of the inner tyres: b < track - (tyres per side) x section width (duals touching)."""
    if group.section_width_m is None:
        return
    per_side = group.tyres_per_axle // 2
    inner = group.track_m - per_side * group.section_width_m
    if not b < inner:
        raise InvalidVehicle(
            f"{group.path}.track_m = {group.track_m:g} m leaves {inner:.3f} m between the inner tyres "
            f"({per_side} tyre(s) of {group.section_width_m:.3f} m per side), not more than the spring separation "
            f"b = {b:g} m: the springs must sit inboard of the tyres",
            field=f"{group.path}.track_m",
            value=group.track_m,
        )


# ------------------------------------------------------------------------------------------ payload CGs


def _segment_centroid_height(depth_m: float, radius_m: float) -> float:
    """Centroid height above the bottom of a circle's segment of depth ``depth_m`` [m].

    Central angle theta = 2 acos((R - d)/R); centroid 4 R sin^3(theta/2) / (3 (theta - sin theta)) below the
    centre [3].
    """
    theta = 2.0 * math.acos(max(-1.0, min(1.0, (radius_m - depth_m) / radius_m)))
    below_centre = 4.0 * radius_m * math.sin(theta / 2.0) ** 3 / (3.0 * (theta - math.sin(theta)))  # [3]
    return radius_m - below_centre


def _segment_area_fraction(depth_m: float, radius_m: float) -> float:
    """Area of a circle's segment of depth ``depth_m`` over the circle's area, (theta - sin theta) / 2 pi [-]."""
    theta = 2.0 * math.acos(max(-1.0, min(1.0, (radius_m - depth_m) / radius_m)))
    return (theta - math.sin(theta)) / (2.0 * math.pi)


def tank_liquid_cg_height_m(
    height_m: float, bottom_height_m: float, *, fill_height_m: float | None = None, fill_fraction: float | None = None
) -> float:
    """CG height above the ground of a liquid in a circular or elliptical tank [m].

    An ellipse is a circle of radius height/2 stretched horizontally; the stretch keeps heights and area ratios,
    so the liquid segment's centroid height is the circle's whatever the tank's width.

    Parameters
    ----------
    height_m : inside height of the tank (diameter of a circular one) [m]
    bottom_height_m : inside bottom of the tank above the ground [m]
    fill_height_m : liquid depth [m] (give this or ``fill_fraction``)
    fill_fraction : liquid volume over tank volume [-]

    References
    ----------
    Centroid of a circular segment, 4 R sin^3(theta/2) / (3 (theta - sin theta)) below the centre (sector minus
    triangle, see the module's reference [3]).
    """
    r = height_m / 2.0
    if fill_height_m is None:
        if fill_fraction >= 1.0:
            return bottom_height_m + r
        fill_height_m = brentq(lambda d: _segment_area_fraction(d, r) - fill_fraction, 0.0, height_m, xtol=1e-12)
    return bottom_height_m + _segment_centroid_height(fill_height_m, r)


def _simpson(f0: float, fm: float, f1: float, length: float) -> float:
    """Simpson's rule on one interval: exact for the polynomials of degree <= 3 integrated here."""
    return length * (f0 + 4.0 * fm + f1) / 6.0


def sloped_load_centroid(
    length_m: float,
    deck_front_m: float,
    deck_rear_m: float,
    top_front_m: float,
    top_rear_m: float,
    cg_fraction: float = 0.5,
) -> tuple[float, float]:
    """Centroid (distance behind the load's front end, height above the ground) of a load on a sloping deck [m].

    Deck d(s) and load top t(s) vary linearly over the load's length; the thickness h = t - d carries the mass,
    whose CG in each section is at d + f h (f = 0.5 uniform, 0.4 mixed freight). Hence
    s_bar = int s h ds / int h ds and z_bar = int (d + f h) h ds / int h ds; the integrands are quadratic, so
    Simpson's rule is exact.

    Parameters
    ----------
    length_m : length of the load [m]
    deck_front_m, deck_rear_m : deck height above the ground at the load's front and rear [m]
    top_front_m, top_rear_m : top of the load above the ground at its front and rear [m]
    cg_fraction : section CG height above the deck as a fraction of the thickness [-]
    """
    deck_mid, top_mid = (deck_front_m + deck_rear_m) / 2.0, (top_front_m + top_rear_m) / 2.0
    h0, hm, h1 = top_front_m - deck_front_m, top_mid - deck_mid, top_rear_m - deck_rear_m
    area = _simpson(h0, hm, h1, length_m)
    s_bar = _simpson(0.0, length_m / 2.0 * hm, length_m * h1, length_m) / area
    z_bar = (
        _simpson(
            (deck_front_m + cg_fraction * h0) * h0,
            (deck_mid + cg_fraction * hm) * hm,
            (deck_rear_m + cg_fraction * h1) * h1,
            length_m,
        )
        / area
    )
    return s_bar, z_bar


def _payload_extent(p: PayloadSpec, deck: DeckSpec | None, path: str) -> tuple[float, float, str]:
    """Front end and length of a payload [m], with how they were obtained."""
    if p.length_m is not None:
        length = _number(p.length_m, f"{path}.length_m")
    elif deck is not None:
        length = deck.length_m
    else:
        raise InvalidVehicle(
            f"{path} has no longitudinal position: give {path}.cg_from_kingpin_m, or front_from_kingpin_m and "
            "length_m, or the vehicle's deck",
            field=f"{path}.cg_from_kingpin_m",
        )
    if p.front_from_kingpin_m is not None:
        front = _number(p.front_from_kingpin_m, f"{path}.front_from_kingpin_m", minimum=-math.inf)
        how = "as given"
    elif deck is not None:
        front = deck.front_from_kingpin_m + (deck.length_m - length) / 2.0
        how = "centred on the deck"
    else:
        raise InvalidVehicle(
            f"{path}.front_from_kingpin_m is needed (no deck to centre the load on)",
            field=f"{path}.front_from_kingpin_m",
        )
    if deck is not None and (
        front < deck.front_from_kingpin_m - 1e-9 or front + length > deck.front_from_kingpin_m + deck.length_m + 1e-9
    ):
        raise InvalidVehicle(
            f"{path} spans {front:g}-{front + length:g} m behind the kingpin, outside the deck "
            f"({deck.front_from_kingpin_m:g}-{deck.front_from_kingpin_m + deck.length_m:g} m)",
            field=f"{path}.front_from_kingpin_m" if p.front_from_kingpin_m is not None else f"{path}.length_m",
            value=front,
        )
    return front, length, how


def _deck_load_heights(p: PayloadSpec, path: str) -> tuple[float, float, float, float]:
    deck0 = _number(p.deck_height_m, f"{path}.deck_height_m")
    top0 = _number(
        p.load_height_m,
        f"{path}.load_height_m",
        minimum=deck0,
        reason=f" (the top of the load must be above the deck, {deck0:g} m)",
    )
    deck1 = deck0 if p.deck_height_rear_m is None else _number(p.deck_height_rear_m, f"{path}.deck_height_rear_m")
    if p.load_height_rear_m is None:
        top1 = deck1 + (top0 - deck0)  # load top parallel to the deck
    else:
        top1 = _number(
            p.load_height_rear_m,
            f"{path}.load_height_rear_m",
            minimum=deck1,
            strict=False,
            reason=f" (the top of the load may not be below the deck, {deck1:g} m)",
        )
    return deck0, deck1, top0, top1


def _payload_item(p: PayloadSpec, deck: DeckSpec | None, path: str) -> MassItem:
    if not isinstance(p, PayloadSpec):
        raise InvalidVehicle(f"{path} must be a payload", field=path, value=p)
    mass = _number(p.mass_kg, f"{path}.mass_kg", strict=False)
    modes = [
        n
        for n, v in (("deck_height_m", p.deck_height_m), ("cg_height_m", p.cg_height_m), ("tank", p.tank))
        if v is not None
    ]
    if len(modes) != 1:
        raise InvalidVehicle(
            f"{path} needs exactly one of deck_height_m (with load_height_m), cg_height_m or tank; got "
            f"{', '.join(modes) or 'none'}",
            field=f"{path}.{modes[1] if len(modes) > 1 else 'deck_height_m'}",
        )
    if p.cg_from_kingpin_m is not None:
        if p.front_from_kingpin_m is not None or p.length_m is not None:
            raise InvalidVehicle(
                f"give {path}.cg_from_kingpin_m or the load's extent (front_from_kingpin_m, length_m), not both",
                field=f"{path}.cg_from_kingpin_m",
            )
        x_cg, x_how = _number(p.cg_from_kingpin_m, f"{path}.cg_from_kingpin_m", minimum=-math.inf), "as given"
        front = length = None
    else:
        front, length, x_how = _payload_extent(p, deck, path)
        x_cg = front + length / 2.0
    stray = [n for n in ("load_height_m", "deck_height_rear_m", "load_height_rear_m") if getattr(p, n) is not None]
    if modes[0] != "deck_height_m" and stray:
        raise InvalidVehicle(
            f"{path}.{stray[0]} applies to a deck load only (with deck_height_m), not with {modes[0]}",
            field=f"{path}.{stray[0]}",
        )
    if modes[0] == "cg_height_m":
        z, z_how = _number(p.cg_height_m, f"{path}.cg_height_m"), "CG height as given"
    elif modes[0] == "tank":
        z, z_how = _tank_cg(p.tank, f"{path}.tank")
    else:
        z, z_how, x_cg = _deck_cg(p, path, front, length, x_cg)
    return MassItem(path.removeprefix("spec."), mass, z, x_cg, f"{z_how}; longitudinal: {x_how}")


def _deck_cg(p: PayloadSpec, path: str, front: float | None, length: float | None, x_cg: float):
    f = LOAD_DISTRIBUTIONS[_one_of(p.distribution, f"{path}.distribution", tuple(LOAD_DISTRIBUTIONS))]
    deck0, deck1, top0, top1 = _deck_load_heights(p, path)
    if deck0 == deck1 and top0 == top1:
        return deck0 + f * (top0 - deck0), f"{p.distribution}: z = deck + {f:g} (load - deck)", x_cg
    if length is None:
        raise InvalidVehicle(
            f"a sloping deck needs the load's length: give {path}.length_m (or the deck) instead of cg_from_kingpin_m",
            field=f"{path}.length_m",
        )
    s_bar, z = sloped_load_centroid(length, deck0, deck1, top0, top1, f)
    return z, f"{p.distribution} on a sloping deck: centroid of the side-view trapezoid", front + s_bar


def _tank_cg(t: TankSpec, path: str) -> tuple[float, str]:
    if not isinstance(t, TankSpec):
        raise InvalidVehicle(f"{path} must be a tank", field=path, value=t)
    shape = _one_of(t.shape, f"{path}.shape", TANK_SHAPES)
    height = _number(t.height_m, f"{path}.height_m")
    bottom = _number(t.bottom_height_m, f"{path}.bottom_height_m")
    if (t.fill_height_m is None) == (t.fill_fraction is None):
        raise InvalidVehicle(
            f"give exactly one of {path}.fill_height_m or fill_fraction", field=f"{path}.fill_height_m"
        )
    if t.fill_height_m is not None:
        depth = _number(t.fill_height_m, f"{path}.fill_height_m")
        if depth > height:
            raise InvalidVehicle(
                f"{path}.fill_height_m = {depth:g} m exceeds the tank's height {height:g} m",
                field=f"{path}.fill_height_m",
                value=depth,
            )
        z = tank_liquid_cg_height_m(height, bottom, fill_height_m=depth)
        fill = f"depth {depth:g} m"
    else:
        frac = _number(t.fill_fraction, f"{path}.fill_fraction")
        if frac > 1:
            raise InvalidVehicle(
                f"{path}.fill_fraction must be in (0, 1], got {frac:g}", field=f"{path}.fill_fraction", value=frac
            )
        z = tank_liquid_cg_height_m(height, bottom, fill_fraction=frac)
        fill = f"{100 * frac:g} % full by volume"
    return z, f"liquid in a {shape} tank ({fill}): centroid of the liquid segment (circular-segment closed form)"


def _tare_item(t: TareSpec, deck_heights: Sequence[float], wheelbase: float) -> tuple[MassItem, str | None]:
    if not isinstance(t, TareSpec):
        raise InvalidVehicle("spec.tare must be a tare mass", field="spec.tare", value=t)
    mass = _number(t.mass_kg, "spec.tare.mass_kg")
    note = None
    if t.cg_height_m is not None:
        z, z_how = _number(t.cg_height_m, "spec.tare.cg_height_m"), "CG height as given"
    else:
        if not deck_heights:
            raise InvalidVehicle(
                "spec.tare.cg_height_m is needed (no deck height to default it to)", field="spec.tare.cg_height_m"
            )
        z = min(deck_heights)
        z_how = "default (assumed): at the lowest deck height"
        note = (
            f"tare CG height assumed at the lowest deck height ({z:g} m): no published body-type default was found; "
            "conservative for a flat-deck or skeletal trailer whose chassis and axles lie below the deck, not for a "
            "body or tank built above it; give spec.tare.cg_height_m"
        )
    if (t.cg_from_kingpin_m is None) == (t.rear_group_load_kg is None):
        raise InvalidVehicle(
            "give exactly one of spec.tare.cg_from_kingpin_m or spec.tare.rear_group_load_kg",
            field="spec.tare.cg_from_kingpin_m",
        )
    if t.cg_from_kingpin_m is not None:
        x, x_how = _number(t.cg_from_kingpin_m, "spec.tare.cg_from_kingpin_m", minimum=-math.inf), "as given"
    else:
        rear = _number(t.rear_group_load_kg, "spec.tare.rear_group_load_kg")
        x = wheelbase * rear / mass  # lever rule about the kingpin (Eq. 4.27 at rest)
        x_how = f"lever rule x = L m_rear / m = {wheelbase:g} x {rear:g} / {mass:g} (Eq. 4.27 at rest)"
    return MassItem("tare", mass, z, x, f"{z_how}; longitudinal: {x_how}"), note


# --------------------------------------------------------------------------------------------- the build


def _front_defaults(unit_type: str) -> dict[str, tuple[float | None, str]]:
    """Documented defaults of the front-unit fields, per unit type: value and source."""
    t15_16 = f"{_THESIS}, Tables 15 and 16 (the thesis's value for every fifth wheel; no measurement cited)"
    if unit_type == "rigid-truck":
        none = (None, "not applicable: a rigid truck has no fifth wheel")
        return {
            "fifth_wheel_stiffness_kn_per_m": none,
            "fifth_wheel_height_m": none,
            "fifth_wheel_width_m": none,
            "fifth_wheel_to_front_axle_m": (0.0, "a rigid truck's reference is its front group itself (Table 22)"),
            "front_llt_ratio": (0.9, f"{_THESIS}, App. B: LLTf is about 90 % of LLTr for the truck of Table 22"),
        }
    l13 = (0.2, f"{_THESIS}, Table 23 (tractor-semitrailer)")
    if unit_type == "btrain-rear":
        l13 = (0.15, f"{_THESIS}, Table 16 (B-train)")
    return {
        "fifth_wheel_stiffness_kn_per_m": (7500.0, t15_16),
        "fifth_wheel_height_m": (0.1, t15_16),
        "fifth_wheel_width_m": (0.6, t15_16),
        "fifth_wheel_to_front_axle_m": l13,
        "front_llt_ratio": (0.7, f"{_THESIS}, Ch. 9 and Tables 16, 23, after Kamnik et al. (2003): LLTf = 0.7 LLTr"),
    }


def _front_unit_fields(spec: VehicleSpec) -> dict[str, FieldDerivation]:
    fu = spec.front_unit if spec.front_unit is not None else FrontUnitSpec()
    defaults = _front_defaults(spec.unit_type)
    out = {}
    for name in ("fifth_wheel_stiffness_kn_per_m", "fifth_wheel_height_m", "fifth_wheel_width_m", "front_llt_ratio"):
        given, path = getattr(fu, name), f"spec.front_unit.{name}"
        unit = FIELD_DOCS[name].unit
        if given is None:
            value, source = defaults[name]
            out[name] = FieldDerivation(
                name, value, unit, "default", f"{FIELD_DOCS[name].symbol} default", source, path
            )
        elif spec.unit_type == "rigid-truck" and name.startswith("fifth_wheel"):
            raise InvalidVehicle(f"{path}: a rigid truck has no fifth wheel", field=path, value=given)
        else:
            out[name] = FieldDerivation(
                name, _number(given, path), unit, "given", f"{FIELD_DOCS[name].symbol} as given", path, path
            )
    name, path = "chassis_torsional_stiffness_knm2_per_rad", "spec.front_unit.chassis_torsional_stiffness_knm2_per_rad"
    if fu.chassis_torsional_stiffness_knm2_per_rad is None:
        out[name] = FieldDerivation(
            name,
            None,
            FIELD_DOCS[name].unit,
            "default",
            "torsionally rigid between the rear group and the CG",
            f"{_THESIS}: no value given; the presets leave it null (docs/model.md, Sec. 6)",
            path,
        )
    else:
        value = _number(fu.chassis_torsional_stiffness_knm2_per_rad, path)
        out[name] = FieldDerivation(name, value, FIELD_DOCS[name].unit, "given", "G Jr as given", path, path)
    return out


def _geometry_fields(spec: VehicleSpec, rear: _Group, front: _Group) -> dict[str, FieldDerivation]:
    out = {}
    for side, g in (("rear", rear), ("front", front)):
        out[f"{side}_track_m"] = FieldDerivation(
            f"{side}_track_m", g.track_m, "m", "given", "track as given", f"{g.path}.track_m", f"{g.path}.track_m"
        )
        out[f"{side}_axle_width_m"] = FieldDerivation(
            f"{side}_axle_width_m",
            g.track_m,
            "m",
            "computed",
            "axle width = track: the tyres stay perpendicular to the axle",
            f"{_THESIS}, Sec. 4.1.1",
            f"{g.path}.track_m",
        )
        out[f"{side}_axles"] = FieldDerivation(
            f"{side}_axles", g.axles, "count", "given", "axles as given", f"{g.path}.axles", f"{g.path}.axles"
        )
        name = f"{side}_tires_per_axle"
        out[name] = FieldDerivation(
            name,
            g.tyres_per_axle,
            "count",
            "given",
            "tyres per axle as given",
            f"{g.path}.tyres_per_axle",
            f"{g.path}.tyres_per_axle",
        )
    path = "spec.rear.centre_from_kingpin_m"
    if spec.rear.centre_from_kingpin_m is None:
        raise InvalidVehicle(f"{path} (the wheelbase L) is required", field=path)
    wheelbase = _number(spec.rear.centre_from_kingpin_m, path)
    out["wheelbase_m"] = FieldDerivation(
        "wheelbase_m",
        wheelbase,
        "m",
        "given",
        "L = rear group centre behind the kingpin (truck: front group)",
        path,
        path,
    )
    path, name = "spec.front.centre_from_kingpin_m", "fifth_wheel_to_front_axle_m"
    value, source = _front_defaults(spec.unit_type)[name]
    given = spec.front.centre_from_kingpin_m
    if spec.unit_type == "rigid-truck":
        if given not in (None, 0, 0.0):
            raise InvalidVehicle(
                f"{path} must be 0 or absent for a rigid truck: its front group is the reference",
                field=path,
                value=given,
            )
        out[name] = FieldDerivation(name, 0.0, "m", "default", "l13 = 0", source, path)
    elif given is None:
        out[name] = FieldDerivation(name, value, "m", "default", "l13 default", source, path)
    else:
        l13 = _number(given, path, minimum=-math.inf)
        out[name] = FieldDerivation(name, l13, "m", "given", "l13 = front group centre behind the kingpin", path, path)
    return out


def _composite(items: Sequence[MassItem]) -> tuple[float, float, float]:
    mass = sum(i.mass_kg for i in items)
    z = sum(i.mass_kg * i.cg_height_m for i in items) / mass
    x = sum(i.mass_kg * i.cg_from_kingpin_m for i in items) / mass
    return mass, z, x


def _mass_fields(
    items: Sequence[MassItem], comp: dict[str, FieldDerivation], wheelbase: float
) -> dict[str, FieldDerivation]:
    mass, z, x = _composite(items)
    lr, ls = comp["rolling_radius_m"].value, comp["suspension_height_m"].value
    terms = " + ".join(f"{i.mass_kg:g}" for i in items)
    chassis = lr + ls
    l12 = z - chassis
    worst = max(items, key=lambda i: i.mass_kg) if items else None
    if not l12 > 0:
        raise InvalidVehicle(
            f"the composite CG ({z:.3f} m above the ground) is not above the chassis reference lr + ls = "
            f"{chassis:.3f} m, so l12 = h - (lr + ls) = {l12:.3f} m; the model's CG sits on the sprung body",
            field="spec.tare.cg_height_m" if worst is None or worst.name == "tare" else f"spec.{worst.name}",
            value=z,
        )
    if not 0 < x < wheelbase:
        offender = max(items, key=lambda i: abs(i.cg_from_kingpin_m - wheelbase / 2))
        path = "spec.tare.cg_from_kingpin_m" if offender.name == "tare" else f"spec.{offender.name}"
        raise InvalidVehicle(
            f"the composite CG lies {x:.3f} m behind the kingpin, outside (0, L = {wheelbase:g} m): the model needs "
            "the CG between the kingpin (front group) and the rear group centre (Eq. 4.27 with both loads positive)",
            field=path,
            value=x,
        )
    return {
        "weight_kn": FieldDerivation(
            "weight_kn",
            mass * G_M_PER_S2 / 1000.0,
            "kN",
            "computed",
            f"W = ({terms}) kg x {G_M_PER_S2} m/s^2",
            f"masses of spec.tare and spec.payloads; g = {G_M_PER_S2}",
            "spec.tare.mass_kg",
        ),
        "cg_height_above_chassis_m": FieldDerivation(
            "cg_height_above_chassis_m",
            l12,
            "m",
            "computed",
            f"l12 = h - (lr + ls) = {z:.4f} - ({lr:g} + {ls:g}), h = sum(m z)/sum(m)",
            "engine.vehicles.cg_height_m: h = lr + ls + l12",
            "spec.tare.cg_height_m",
        ),
        "front_axle_to_cg_m": FieldDerivation(
            "front_axle_to_cg_m",
            x,
            "m",
            "computed",
            f"a = sum(m x)/sum(m) = {x:.4f}",
            "CG positions of spec.tare and spec.payloads",
            "spec.tare.cg_from_kingpin_m",
        ),
    }


def _check_ratings(
    front: _Group, rear: _Group, group_loads: dict[str, float], payloads: Sequence[PayloadSpec], unit_type: str
) -> None:
    blame = "spec.payloads[0].mass_kg" if payloads else "spec.tare.mass_kg"
    for g, key in ((rear, "rear"), (front, "front")):
        load = group_loads[key]
        what = "the kingpin load alone" if key == "front" and unit_type in TRAILER_TYPES else f"the {key} group's load"
        if g.rated_load_kg is not None and load > g.rated_load_kg:
            raise InvalidVehicle(
                f"{what} at rest, {load:.0f} kg (lever rule, Eq. 4.27), exceeds {g.path}.rated_load_kg = "
                f"{g.rated_load_kg:g} kg: the payload is above the group's rating",
                field=blame,
                value=load,
            )
        if g.tyre_rated_load_kg is not None:
            per_tyre = load / (g.axles * g.tyres_per_axle)
            if per_tyre > g.tyre_rated_load_kg:
                raise InvalidVehicle(
                    f"each {key} tyre carries {per_tyre:.0f} kg at rest (from {what}), above "
                    f"the tyre rating of {g.tyre_rated_load_kg:g} kg ({g.path}.tyre)",
                    field=blame,
                    value=per_tyre,
                )


def build_vehicle(spec: VehicleSpec) -> BuiltVehicle:
    """The engine's vehicle record for a measurable spec, with the derivation of every field.

    Parameters
    ----------
    spec : the vehicle in measurable terms (:class:`VehicleSpec`)

    Returns
    -------
    BuiltVehicle with ``vehicle`` (validated by :func:`engine.vehicles.validate_vehicle` for the 3D model),
    ``derivation`` (every record field), ``masses``, the composite CG and the static group loads [kg].

    Raises
    ------
    InvalidVehicle : an input is missing, impossible or inconsistent; ``field`` is its dotted spec path
        (``spec.payloads[1].load_height_m``), errors on a derived record field point at the input behind it.
    """
    if not isinstance(spec, VehicleSpec):
        raise InvalidVehicle("spec must be a VehicleSpec", field="spec", value=spec)
    _one_of(spec.unit_type, "spec.unit_type", UNIT_TYPES)
    rear, front = _resolve_group(spec.rear, "spec.rear"), _resolve_group(spec.front, "spec.front")
    comp, notes = _component_fields(rear, front)
    for g in (rear, front):
        _check_width(g, comp["spring_separation_m"].value)
    derivation = {**comp, **_geometry_fields(spec, rear, front), **_front_unit_fields(spec)}
    wheelbase = derivation["wheelbase_m"].value
    deck = spec.deck
    if deck is not None:
        deck = DeckSpec(
            _number(deck.front_from_kingpin_m, "spec.deck.front_from_kingpin_m", minimum=-math.inf),
            _number(deck.length_m, "spec.deck.length_m"),
        )
    payloads = tuple(spec.payloads or ())
    loads = tuple(_payload_item(p, deck, f"spec.payloads[{i}]") for i, p in enumerate(payloads))
    deck_heights = [p.deck_height_m for p in payloads if p.deck_height_m is not None]  # validated by _payload_item
    tare, note = _tare_item(spec.tare, deck_heights, wheelbase)
    notes += [note] if note else []
    items = (tare, *loads)
    derivation.update(_mass_fields(items, comp, wheelbase))
    mass, z, x = _composite(items)
    group_loads = {"front": mass * (wheelbase - x) / wheelbase, "rear": mass * x / wheelbase}  # Eq. 4.27 at rest
    _check_ratings(front, rear, group_loads, payloads, spec.unit_type)
    if spec.rear.axle_spacing_m is not None or spec.front.axle_spacing_m is not None:
        notes.append("axle spacing is recorded but not used: the model has one equivalent axle per group (Figs. 41-43)")
    vehicle = Vehicle(**{name: d.value for name, d in derivation.items()})
    _validate_record(vehicle, derivation)
    return BuiltVehicle(vehicle, derivation, items, mass, z, x, group_loads, tuple(notes))


def _validate_record(vehicle: Vehicle, derivation: dict[str, FieldDerivation]) -> None:
    """engine.vehicles.validate_vehicle on the record; its errors re-pointed at the spec input behind the field."""
    try:
        get_model("3d").validate(vehicle)
    except InvalidVehicle as exc:
        d = derivation.get(exc.field or "")
        path = d.spec_path if d is not None and d.spec_path else f"record.{exc.field}"
        raise InvalidVehicle(f"{exc} (record field {exc.field}, from {path})", field=path, value=exc.value) from exc


# ------------------------------------------------------------------------------------ payload table


def _srt_g(vehicle: Vehicle, road: Road, load: LoadCase) -> float:
    """The module's one engine call: the 3D model's SRT [g]."""
    return rollover_threshold(Case(vehicle, "3d", road=road, load=load)).srt


@dataclass(frozen=True)
class PayloadLimit:
    """The largest acceptable value of one input for a row of the table.

    value : the limit [kg or m]; None when never met. status : ``found``, ``always-met`` or ``never-met``.
    srt_at_limit_g : the SRT at ``value`` [g]; range : the searched range [kg or m]; evaluations : SRT solves
    """

    value: float | None
    status: str
    srt_at_limit_g: float | None
    range: tuple[float, float]
    evaluations: int


@dataclass(frozen=True)
class PayloadRow:
    """One row: a load height with the largest payload mass, or a payload mass with the largest load height."""

    load_height_m: float | None
    payload_mass_kg: float | None
    limit: PayloadLimit


@dataclass(frozen=True)
class PayloadTable:
    """TERNZ's table of acceptable payload mass / load height pairs, solved with the 3D model."""

    target_srt_g: float
    payload_index: int
    srt_at_spec_g: float  # at the spec's own mass and load height
    by_load_height: tuple[PayloadRow, ...]  # largest mass for each load height
    by_payload_mass: tuple[PayloadRow, ...]  # largest load height for each mass


def _with_payload(spec: VehicleSpec, index: int, mass_kg: float, load_height_m: float) -> VehicleSpec:
    p = spec.payloads[index]
    rear = None if p.load_height_rear_m is None else p.load_height_rear_m + (load_height_m - p.load_height_m)
    payloads = list(spec.payloads)
    payloads[index] = replace(p, mass_kg=mass_kg, load_height_m=load_height_m, load_height_rear_m=rear)
    return replace(spec, payloads=tuple(payloads))


def payload_table(
    spec: VehicleSpec,
    target_srt_g: float,
    *,
    load_heights_m: Sequence[float] | None = None,
    payload_masses_kg: Sequence[float] | None = None,
    payload_index: int = 0,
    road: Road = Road(),
    load: LoadCase = LoadCase(),
    mass_tolerance_kg: float = 1.0,
    height_tolerance_m: float = 1e-4,
    rows: int = 5,
) -> PayloadTable:
    """Largest payload mass for each load height and largest load height for each payload mass meeting a target.

    The SRT falls as the payload's load height rises (its CG rises) and, for a payload whose CG lies above the
    rest of the vehicle's, as its mass grows; each limit is a root of SRT - target found by Brent's method on a
    bracket over the physical range (mass 0 to the spec's mass; load height from 1 mm above the deck to the
    spec's load height), stepping off ends the model cannot solve (:func:`engine.bracket.bracketed_limit`). A value
    the spec itself refuses (a payload above a rated group load, a body that would fall over at rest) counts as
    unsolvable: the limit is then the last acceptable value, with status ``always-met``.

    Parameters
    ----------
    spec : the vehicle; payload ``payload_index`` must be a deck load (deck and load heights)
    target_srt_g : the SRT to meet [g]
    load_heights_m : load heights of the first table [m] (default ``rows`` heights up to the spec's)
    payload_masses_kg : payload masses of the second table [kg] (default ``rows`` masses up to the spec's)
    payload_index : which payload varies [-]
    road, load : road and load case of the SRT (default flat road, nominal load)
    mass_tolerance_kg, height_tolerance_m : tolerances of the limits [kg], [m]
    rows : rows of each default table [-]

    Raises
    ------
    InvalidInput : a bad target, row or payload; InvalidVehicle : the spec itself cannot be built.
    """
    if not (isinstance(target_srt_g, int | float) and math.isfinite(target_srt_g) and 0 < target_srt_g < 2):
        raise InvalidInput("target_srt_g must be in (0, 2) g", field="target_srt_g", value=target_srt_g)
    if not (isinstance(payload_index, int) and 0 <= payload_index < len(spec.payloads)):
        raise InvalidInput(
            f"payload_index must select one of the spec's {len(spec.payloads)} payloads",
            field="payload_index",
            value=payload_index,
        )
    p = spec.payloads[payload_index]
    if p.deck_height_m is None or p.load_height_m is None:
        raise InvalidInput(
            "the payload table varies a deck load's mass and load height: the payload needs deck_height_m and "
            "load_height_m (not cg_height_m or a tank)",
            field=f"spec.payloads[{payload_index}].load_height_m",
        )
    srt_spec = _srt_g(build_vehicle(spec).vehicle, road, load)  # errors of the spec itself pass through
    deck, full_height, full_mass = float(p.deck_height_m), float(p.load_height_m), float(p.mass_kg)
    if not full_mass > 0:
        raise InvalidInput(
            "the payload's mass must be positive for a table", field=f"spec.payloads[{payload_index}].mass_kg"
        )
    heights = _rows(load_heights_m, "load_heights_m", deck, full_height, rows)
    masses = _rows(payload_masses_kg, "payload_masses_kg", 0.0, full_mass, rows)

    def margin(mass_kg: float, height_m: float) -> float | None:
        try:
            return (
                _srt_g(build_vehicle(_with_payload(spec, payload_index, mass_kg, height_m)).vehicle, road, load)
                - target_srt_g
            )
        except RolloverError:  # this value collapses the body or leaves the model's range: unsolvable
            return None

    low_height = deck + 1e-3
    by_height = tuple(
        PayloadRow(
            h,
            None,
            _limit(lambda m, h=h: margin(m, h), 0.0, full_mass, mass_tolerance_kg, target_srt_g, "payload_mass_kg"),
        )
        for h in heights
    )
    by_mass = tuple(
        PayloadRow(
            None,
            m,
            _limit(
                lambda h, m=m: margin(m, h), low_height, full_height, height_tolerance_m, target_srt_g, "load_height_m"
            ),
        )
        for m in masses
    )
    return PayloadTable(float(target_srt_g), payload_index, srt_spec, by_height, by_mass)


def _rows(values: Sequence[float] | None, name: str, low: float, high: float, n: int) -> tuple[float, ...]:
    if values is None:
        return tuple(low + (high - low) * (k + 1) / n for k in range(n))
    out = []
    for i, v in enumerate(values):
        if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v) or v <= low:
            raise InvalidInput(f"{name}[{i}] must be a number above {low:g}, got {v!r}", field=f"{name}[{i}]", value=v)
        out.append(float(v))
    return tuple(out)


def _limit(margin, good: float, bad: float, xtol: float, target: float, name: str) -> PayloadLimit:
    r = bracketed_limit(margin, good, bad, xtol=xtol, field=name)
    srt = None if r.margin is None else target + r.margin
    return PayloadLimit(r.value, r.status, srt, (good, bad), r.evaluations)

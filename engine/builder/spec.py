"""The builder's inputs (:class:`VehicleSpec` and its parts) and its result records."""

from __future__ import annotations

import math
import types
import typing
from collections.abc import Mapping, Sequence
from dataclasses import MISSING, asdict, dataclass, field, fields, is_dataclass

from engine.errors import InvalidVehicle
from engine.vehicle.record import Vehicle

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

THESIS = "Moreno (thesis)"

# --------------------------------------------------------------------------------------------- the spec


@dataclass(frozen=True)
class TyreSpec:
    """Tyres of an axle group: a library ``id`` and/or explicit data (explicit values win).

    id : a tyre of the component library (:data:`engine.vehicle.components.TYRES`), by its id
    size : size designation (``"295/80R22.5"``, ``"11R22.5"``): its section width and rim bound the geometry
    loaded_radius_m : lr, static loaded (dynamic rolling) radius [m]
    stiffness_kn_per_m : kT, vertical (radial) stiffness of one tyre [kN/m]
    section_width_m : section width of one tyre [m] (else read from ``size``)
    rated_load_kg : the load one tyre may carry in this fitment (single or dual) [kg]
    load_index : or the sidewall load indices, ``"152/148"`` (single/dual) or ``"160"`` (single only): the rated
        load of this fitment from the ISO load-index table (:func:`engine.vehicle.rated_load_from_load_index_kg`)
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

    type : a suspension of the component library (:data:`engine.vehicle.components.SUSPENSIONS`), by its id
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


def check_number(value: object, path: str, *, minimum: float = 0.0, strict: bool = True, reason: str = "") -> float:
    """A finite number above ``minimum`` (or at it when not ``strict``); InvalidVehicle naming ``path``."""
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise InvalidVehicle(f"{path} must be a finite number, got {value!r}", field=path, value=value)
    if value < minimum or (strict and value == minimum):
        bound = f"above {minimum:g}" if strict else f"at least {minimum:g}"
        raise InvalidVehicle(f"{path} must be {bound}, got {value:g}{reason}", field=path, value=value)
    return float(value)


def check_count(value: object, path: str, allowed: Sequence[int] | None = None) -> int:
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


def check_choice(value: object, path: str, allowed: Sequence[str]) -> str:
    if value not in allowed:
        raise InvalidVehicle(f"{path} must be one of {', '.join(allowed)}, got {value!r}", field=path, value=value)
    return typing.cast(str, value)

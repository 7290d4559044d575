"""The combination builder's input (:func:`engine.builder.combination.build_combination`): a combination
described by its units' parts (tare, payloads, axle groups with catalogue tyres and suspensions, couplings), as the
API's ``combination_spec`` takes it. Apart from the build so that the modules the build calls (the last unit's record,
:mod:`engine.builder.last_unit`) can name these types without importing the build.
"""

from __future__ import annotations

import typing
from collections.abc import Mapping
from dataclasses import asdict, dataclass

from engine.builder.spec import DeckSpec, PayloadSpec, TareSpec, _from_dict
from engine.vehicle.dynamic_data import GroupData, UnitData

#: the root of the spec's field paths in errors
ROOT = "combination_spec"


@dataclass(frozen=True)
class RollTyreSpec:
    """The tyres of an axle group, for the roll model: a size and/or explicit data (explicit values win).

    size : size designation (``"295/80R22.5"``, ``"11R22.5"``): the library tyre of that size or size class [-]
    stiffness_kn_per_m : kT, vertical (radial) rate of one tyre [kN/m]
    loaded_radius_m : lr, static loaded radius (the axle centre's height) [m]
    """

    size: str | None = None
    stiffness_kn_per_m: float | None = None
    loaded_radius_m: float | None = None


@dataclass(frozen=True)
class RollSuspensionSpec:
    """The suspension of an axle group in roll, per axle: a library type and/or explicit data (explicit values win).

    type : a suspension of the roll component library (``GET /v1/components``, ``trucksim-...``) by its id [-]
    roll_stiffness_knm_per_rad : k_theta, roll stiffness of one axle (springs and anti-roll) [kN m/rad]
    roll_centre_height_m : height of the suspension's roll centre above the road [m]
    spring_spacing_m : b, lateral spacing of the springs [m]
    lash_deg : roll free play each way from centre before the suspension takes a moment [deg]
    unsprung_mass_kg : mass of one axle with its wheels, tyres and brakes [kg]
    unsprung_cg_height_m : height of the axle's CG above the road (default: the tyre's loaded radius) [m]
    """

    type: str | None = None
    roll_stiffness_knm_per_rad: float | None = None
    roll_centre_height_m: float | None = None
    spring_spacing_m: float | None = None
    lash_deg: float | None = None
    unsprung_mass_kg: float | None = None
    unsprung_cg_height_m: float | None = None


@dataclass(frozen=True)
class UnitGroupSpec:
    """One axle group of a unit (load-sharing axles under one suspension).

    axles : number of axles [-]
    tyres_per_axle : 2 (single tyres) or 4 (duals) [-]
    track_m : lateral spacing of the tyre contacts; for duals, of the centres of the dual pairs [m]
    position_m : the group centre behind the unit's reference point (tractor, rigid truck: the front group centre, so
        0 for the front group; semitrailer, lead trailer: the kingpin; dolly, full trailer: the drawbar eye) [m]
    tyre : the group's tyres
    suspension : the group's suspension
    axle_spacing_m : spread between adjacent axles (the roll model has one equivalent axle per group; the yaw-roll
        model places the axles at this spacing, estimated when left out) [m]
    id : a name unique within its unit (default: steer, drive; front, rear; the unit's id) [-]
    dynamics : for the yaw-roll model only (each field optional, estimated when left out): the group's cornering
        coefficient or tyre type; its axle spacing is ``axle_spacing_m`` above
    """

    axles: int
    tyres_per_axle: int
    track_m: float
    position_m: float
    tyre: RollTyreSpec
    suspension: RollSuspensionSpec
    axle_spacing_m: float | None = None
    id: str | None = None
    dynamics: GroupData | None = None


@dataclass(frozen=True)
class CouplingSpec:
    """The coupling between a unit (towing) and the next one (towed).

    kind : ``fifth-wheel`` (on a tractor or a dolly), ``b-coupling`` (the fifth wheel of a B-train lead trailer),
        ``pintle`` (a drawbar's eye on a pintle hook) or ``ball`` (an A-dolly's ball coupling): the last two pass no
        roll moment [-]
    position_m : on the towing unit, behind its reference point [m]
    height_m : height above the road of the fifth-wheel plate, the pintle or the ball [m]
    fifth_wheel : a fifth wheel of the roll component library by its id (fifth wheel, B-coupling) [-]
    roll_stiffness_knm_per_rad : a fifth wheel's roll stiffness, instead of or over the library's [kN m/rad]
    lash_deg : a fifth wheel's roll free play each way, instead of or over the library's [deg]
    """

    kind: str
    position_m: float
    height_m: float
    fifth_wheel: str | None = None
    roll_stiffness_knm_per_rad: float | None = None
    lash_deg: float | None = None


@dataclass(frozen=True)
class UnitSpec:
    """One unit in measurable terms.

    kind : ``tractor``, ``rigid-truck``, ``semitrailer``, ``btrain-lead``, ``dolly`` or ``full-trailer`` [-]
    axle_groups : its axle groups, front to rear (two for a tractor, rigid truck or full trailer, else one)
    tare : its unladen mass with the axles (as weighed) and the tare CG, positions behind its reference point
    payloads : 0 or more payloads, positions behind its reference point
    deck : its load space (for payload positions), behind its reference point
    id : a name unique within the combination (default: its kind, numbered when repeated) [-]
    title : a name for people [-]
    dynamics : for the yaw-roll model only (each field optional, estimated when left out): inertias, extents, width
    """

    kind: str
    axle_groups: tuple[UnitGroupSpec, ...]
    tare: TareSpec
    payloads: tuple[PayloadSpec, ...] = ()
    deck: DeckSpec | None = None
    id: str | None = None
    title: str | None = None
    dynamics: UnitData | None = None


@dataclass(frozen=True)
class CombinationSpec:
    """A combination in measurable terms: units front to rear and one coupling between each two.

    units : the units, towing unit first
    couplings : ``couplings[i]`` joins ``units[i]`` and ``units[i + 1]``
    title : a name for the combination [-]
    front_llt_ratio : LLTf/LLTr for the 3D model of the last unit, given instead of computed [-]
    """

    units: tuple[UnitSpec, ...]
    couplings: tuple[CouplingSpec, ...] = ()
    title: str | None = None
    front_llt_ratio: float | None = None

    @classmethod
    def from_dict(cls, data: Mapping[str, typing.Any]) -> CombinationSpec:
        """Build from plain dicts and lists; unknown keys are refused naming them
        (``combination_spec.units[1].tare.foo``)."""
        return _from_dict(cls, data, ROOT)

    def to_dict(self) -> dict[str, typing.Any]:
        return asdict(self)


# -------------------------------------------------------------------------------------------- the result

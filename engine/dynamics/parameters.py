"""What the yaw-roll model needs beyond the combination description, and how it is estimated where not given.

The static description (:class:`~engine.vehicle.combination.Combination`) has masses, CG heights and positions,
axle groups and couplings. The motion also needs, per unit, a yaw and a roll inertia and the body's extent (for the
low-speed corners), and per axle group a cornering coefficient and the axle spacing. Each may be given
(:class:`DynamicsData`); otherwise it is estimated here, and every value carries where it came from
(:class:`Parameter`: ``source`` is the given value's, or ``"estimated: <formula>; <source>"``).

Estimates
---------
* cornering stiffness of an axle ``C = n_tyres x C_tyre(N)`` with ``N`` each tyre's static load and ``C_tyre`` the
  cornering stiffness of the group's tyre type (``tyre_type``, :data:`~engine.dynamics.tyres.TYRE_TYPES`, each with
  its table, its source and the rule that reads it; :mod:`engine.dynamics.tyres`). Left out, the type is the presets'
  tyre class, TruckSim's 3000 kg tyre (9.8 /rad at 7.4 kN a tyre falling to 7.4 /rad at 58.9 kN), since the
  description does not name its tyres; the other types are two tyres measured in the SAE Cooperative Research
  program (a 295/75R22.5 steer and drive tyre), TruckSim's 2000 and 3500 kg tyres, and OpenPBS's constant 5.5 /rad
  for every axle (``openpbs-constant``, also :data:`CORNERING_COEFFICIENT_PER_RAD`). A cornering coefficient may be
  given instead (``C = Cc N``, constant): accepted range 2-12 /rad (assumed: outside it no truck tyre's linear
  coefficient lies); a coefficient and a tyre type for one group are refused;
* axle spacing within a group: 1.27 m (the spacing of the tandems and tridems of the TruckSim example database
  the presets use: LX_AXLE 5000 / 6270 / 7540 mm, 5230 / 6500 mm);
* body extent (ahead of / behind the unit's reference point): a uniform load-carrying body centred on its sprung
  CG, its front at ``x_front`` (assumed 1.0 m ahead of a kingpin or of a full trailer's turntable; a tractor's or
  rigid truck's front 1.4 m ahead of the steer axle; a dolly's body from its eye to 0.5 m behind its last axle), so
  ``rear = 2 x_cg - x_front`` for a load carrier; a tractor's rear 1.0 m behind its last axle; every rear at least
  0.3 m behind a rear coupling;
* width: 2.5 m (assumed: the common general width limit of heavy vehicles);
* yaw and roll inertias of the sprung mass: a preset's where its sources give them (:data:`PRESET_SPRUNG_INERTIAS`:
  TruckSim's sprung masses and payloads); otherwise, about its CG, a uniform box ``m (L^2 + w^2) / 12`` (Gillespie
  1992, the moments of inertia of a rectangular body); the axles' own yaw inertia is that of their masses as points;
* roll inertia of the sprung mass about its CG: a uniform box ``m (w^2 + H^2) / 12`` with ``H = 2 (h_cg - h_rc)``
  (the box from its highest roll centre up, centred on the CG);
* suspension roll damping per axle ``c = tau K_s`` with ``tau = 0.02 s`` (assumed: no readable source; it sets a
  sprung-mass roll damping ratio of roughly 0.1-0.3 on the presets and does not enter any steady answer).

References
----------
.. [1] The tyre tables and their sources: :mod:`engine.dynamics.tyres` (TruckSim 2022.1 example dataset,
   github.com/Steve-Krug/Axicle, 04-Trucksim/Tires/Fy/; OpenPBS, ``OpenPBS/Parameters/Base/VehicleModel.mo``).
.. [2] Gillespie, T. D. (1992), *Fundamentals of Vehicle Dynamics*, SAE, ch. 6.
"""

from __future__ import annotations

from dataclasses import dataclass

from engine.dynamics.tyres import DEFAULT_TYRE_TYPE, TYRE_TYPES
from engine.errors import InvalidVehicle
from engine.vehicle.combination import G_M_PER_S2, Combination, static_loads
from engine.vehicle.dynamic_data import DynamicsData, GroupData, UnitData

#: the presets' tyre class (TruckSim's 3000 kg radial), the default tyre type
TYRE_SOURCE = (
    "TruckSim 2022.1 example dataset 'Fy: 3000 kg Load Rating' (github.com/Steve-Krug/Axicle, "
    "04-Trucksim/Tires/Fy/TireFy_b8272e0f...par, FY_TIRE_CARPET at 1 deg), the tyre of the '510 mm Radius (Trailer)' "
    "3000 kg dataset the presets use; interpolated at each tyre's static load"
)
#: a constant coefficient for comparison: OpenPBS gives every axle 5.5 /rad
CORNERING_COEFFICIENT_PER_RAD = 5.5
CORNERING_SOURCE = "OpenPBS, OpenPBS/Parameters/Base/VehicleModel.mo: Cc = 5.5, 'Cornering coefficient per axle'"
CORNERING_RANGE_PER_RAD = (2.0, 12.0)
AXLE_SPACING_M = 1.27
AXLE_SPACING_SOURCE = "TruckSim 2022.1 example database tandems and tridems: LX_AXLE 5000/6270/7540 and 5230/6500 mm"
WIDTH_M = 2.5
ROLL_DAMPING_TAU_S = 0.02


_TS = "TruckSim 2022.1 example dataset, github.com/Steve-Krug/Axicle, 04-Trucksim/"


def _combined(m1: float, h1: float, i1: tuple[float, float], m2: float, h2: float, i2: tuple[float, float]):
    """(Ixx, Izz) of two bodies with their CGs on one vertical line, about the common CG [kg m^2]."""
    hc = (m1 * h1 + m2 * h2) / (m1 + m2)
    ixx = i1[0] + i2[0] + m1 * (h1 - hc) ** 2 + m2 * (h2 - hc) ** 2
    return ixx, i1[1] + i2[1]


_PUP = _combined(2116.0, 1.935, (5592.5, 40672.8), 9000.0, 2.3, (6000.0, 21750.0))
_PUP_SOURCE = (
    f"derived: {_TS}Vehicles/Trl_Sprung_Mass/TrlSprM_0d042329...par ('1A Van Trailer, 28-ft': IXX_SU 5592.5, "
    "IZZ_SU 40672.8 at H_CG_SU 1935) and Payloads/Box/Box_aaf9bc17...par ('Double Trailers (9000 kg)': IXX_PL 6000, "
    "IZZ_PL 21750 at Z_CG_PL 2300), both at LX 3500 mm, about their common CG"
)
_FULL = _combined(3000.0, 2.0, (5964.3, 27000.0), 4500.0, 2.3, (3000.0, 10875.0))
_FULL_SOURCE = (
    f"derived: {_TS}Vehicles/Trl_Sprung_Mass/TrlSprM_db68818b...par ('1A Trailer (Typical 28ft)': IXX_SU 5964.3, "
    "IZZ_SU 27000 at H_CG_SU 2000) and Payloads/Box/Box_9009210f...par ('Trailer (4500 kg)': IXX_PL 3000, IZZ_PL "
    "10875 at Z_CG_PL 2300), both at LX 3500 mm, about their common CG"
)
_CAB_OVER = (2283.9, 34802.6, f"{_TS}Vehicles/Sprung_Mass/SprMass_5f3ae270...par ('2A Cab-Over'): IXX_SU 2283.9, "
             "IZZ_SU 34802.6 (the sprung mass the preset takes)")  # fmt: skip
#: one preset's units: unit id -> (Ixx, Izz, source)
UnitInertias = dict[str, tuple[float, float, str]]

#: the sprung masses' roll and yaw inertias about their own CGs where the presets' sources give them: preset id ->
#: unit id -> (Ixx, Izz, source); the thesis's trailers (Tables 15, 16) and the truck's van body give none
PRESET_SPRUNG_INERTIAS: dict[str, UnitInertias] = {
    "tractor-semitrailer-table15": {"tractor": _CAB_OVER},
    "btrain-table16": {
        "tractor": (
            6879.0,
            19665.0,
            f"{_TS}Vehicles/Sprung_Mass/SprMass_93a3d6a8...par ('3A Sleeper Cab'): IXX_SU 6879, IZZ_SU 19665",
        )
    },
    "adouble": {
        "tractor": _CAB_OVER,
        "trailer1": (*_PUP, _PUP_SOURCE),
        "dolly": (
            215.0,
            290.0,
            f"{_TS}Vehicles/Trl_Sprung_Mass/TrlSprM_1399a1df...par ('1A Dolly w/ Rigid "
            "Towbar'): IXX_SU 215, IZZ_SU 290",
        ),
        "trailer2": (*_PUP, _PUP_SOURCE),
    },
    "truck-trailer": {"trailer": (*_FULL, _FULL_SOURCE)},
}


def preset_inertias(c: Combination) -> dict[str, tuple[float, float, str]]:
    """The sourced sprung inertias of every unit of ``c`` that is, field for field, a preset's unit that has them."""
    from engine.vehicle.combination_presets import COMBINATIONS

    out = {}
    for u in c.units:
        for pid, pc in COMBINATIONS.items():
            data = PRESET_SPRUNG_INERTIAS.get(pid, {})
            if any(pu.id in data and pu == u for pu in pc.units):
                out[u.id] = data[u.id]
    return out


@dataclass(frozen=True)
class Parameter:
    """A value with where it comes from: ``given``, a preset's source, or ``estimated: formula; source``."""

    value: float
    unit: str
    source: str


#: every optional per-unit field: (description, unit, lowest, highest) -- the one definition the schemas follow
UNIT_DATA_DOCS: dict[str, tuple[str, str, float, float]] = {
    "yaw_inertia_kgm2": ("Yaw inertia of the whole unit (sprung and axles) about its own CG; at least the point-mass "
                         "bound of its own masses", "kg m^2", 1.0, 5e6),
    "roll_inertia_kgm2": ("Roll inertia of the sprung mass about its CG", "kg m^2", 1.0, 1e6),
    "front_overhang_m": ("How far the unit's front lies ahead of its reference point (a full trailer's: of its "
                         "turntable)", "m", 0.0, 5.0),
    "rear_extent_m": ("How far the unit's rear lies behind its reference point; must reach its axles and its rear "
                      "coupling", "m", 0.5, 25.0),
    "width_m": ("Overall width of the unit", "m", 1.5, 3.5),
}  # fmt: skip
#: every optional per-group field: (description, unit, lowest, highest) of a number, or (description, unit,
#: choices) of a choice
GROUP_DATA_DOCS: dict[str, tuple] = {
    "cornering_coefficient_per_rad": ("Cornering stiffness of each axle per unit of its vertical load; not with "
                                      "tyre_type", "1/rad", *CORNERING_RANGE_PER_RAD),
    "axle_spacing_m": ("Spacing of the group's axles", "m", 0.9, 3.0),
    "tyre_type": ("The group's tyre type, whose sourced table of cornering stiffness against load gives each axle's "
                  f"(default {DEFAULT_TYRE_TYPE}, the presets' tyre); not with cornering_coefficient_per_rad",
                  "-", tuple(TYRE_TYPES)),
}  # fmt: skip


@dataclass(frozen=True)
class UnitParameters:
    """The resolved data of one unit (all SI): see the module docstring for the estimates."""

    yaw_inertia_kgm2: Parameter
    roll_inertia_kgm2: Parameter
    front_overhang_m: Parameter
    rear_extent_m: Parameter
    width_m: Parameter


@dataclass(frozen=True)
class GroupParameters:
    cornering_coefficient_per_rad: Parameter
    axle_spacing_m: Parameter
    axle_positions_m: tuple[float, ...]
    axle_load_kn: float
    cornering_stiffness_kn_per_rad: tuple[float, ...]
    #: the tyre type used and where it came from (None: a coefficient was given)
    tyre_type: str | None = None
    tyre_type_source: str = ""


@dataclass(frozen=True)
class ResolvedParameters:
    units: tuple[UnitParameters, ...]
    groups: dict[tuple[int, int], GroupParameters]
    roll_damping_tau_s: Parameter


def _front_estimate(kind: str) -> tuple[float, str]:
    if kind in ("tractor", "rigid-truck"):
        return 1.4, "assumed: the front 1.4 m ahead of the steer axle (cab-over front overhang)"
    if kind == "dolly":
        return 0.0, "assumed: a dolly's front is its drawbar eye"
    if kind == "full-trailer":
        return 1.0, "assumed: the body's front 1.0 m ahead of its turntable"
    return 1.0, "assumed: the body's front 1.0 m ahead of its kingpin"


def _check_range(value: float, low: float, high: float, path: str, what: str) -> None:
    if not isinstance(value, int | float) or isinstance(value, bool) or not low <= value <= high:
        raise InvalidVehicle(f"{path} must be from {low:g} to {high:g} for {what}, got {value!r}", field=path,
                             value=value)  # fmt: skip


def resolve(c: Combination, data: DynamicsData | None = None) -> ResolvedParameters:
    """Every unit's and group's dynamic data, given or estimated, with sources; refuse impossible given values.

    Raises
    ------
    InvalidVehicle : a negative overhang, an extent that leaves a coupling or an axle outside its unit, a yaw
        inertia below the point-mass bound of the unit's own axles, a cornering coefficient outside 2-12 /rad;
        ``field`` is ``dynamics.units[<unit id>].<name>`` or ``dynamics.groups[<unit id>/<group id>].<name>``.
    """
    data = data or DynamicsData()

    def given(key: str) -> str:
        """A given value's source: where it was typed, when known (``key``: ``units[<id>].<field>``)."""
        return f"given in {data.given_at[key]}" if key in data.given_at else "given"

    known_units = {u.id for u in c.units}
    for uid in data.units:
        if uid not in known_units:
            raise InvalidVehicle(f"dynamics.units: no unit {uid!r} (units: {', '.join(sorted(known_units))})",
                                 field=f"dynamics.units[{uid}]", value=uid)  # fmt: skip
    known_groups = {(u.id, g.id) for u in c.units for g in u.groups}
    for key in data.groups:
        if key not in known_groups:
            raise InvalidVehicle(f"dynamics.groups: no group {key[1]!r} on unit {key[0]!r}",
                                 field=f"dynamics.groups[{key[0]}/{key[1]}]", value=key[1])  # fmt: skip
    st = static_loads(c)
    inertias = preset_inertias(c)
    groups: dict[tuple[int, int], GroupParameters] = {}
    for i, u in enumerate(c.units):
        for j, g in enumerate(u.groups):
            gd = data.groups.get((u.id, g.id), GroupData())
            gkey = f"groups[{u.id}/{g.id}]"
            path = f"dynamics.{gkey}"
            if gd.tyre_type is not None and gd.tyre_type not in TYRE_TYPES:
                raise InvalidVehicle(f"{path}.tyre_type must be one of {', '.join(TYRE_TYPES)}, got "
                                     f"{gd.tyre_type!r}", field=f"{path}.tyre_type", value=gd.tyre_type)  # fmt: skip
            if gd.tyre_type is not None and gd.cornering_coefficient_per_rad is not None:
                raise InvalidVehicle(f"{path}.tyre_type and {path}.cornering_coefficient_per_rad: give one, not "
                                     "both (the coefficient replaces the tyre's table)", field=f"{path}.tyre_type",
                                     value=gd.tyre_type)  # fmt: skip
            tyre_id, tyre_why = None, "not used: the cornering coefficient was given"
            if gd.cornering_coefficient_per_rad is not None:
                _check_range(
                    gd.cornering_coefficient_per_rad,
                    *CORNERING_RANGE_PER_RAD,
                    f"{path}.cornering_coefficient_per_rad",
                    "a truck tyre's linear cornering coefficient",
                )
                cc = Parameter(
                    gd.cornering_coefficient_per_rad, "1/rad", given(f"{gkey}.cornering_coefficient_per_rad")
                )
            else:
                tyre_id = gd.tyre_type or DEFAULT_TYRE_TYPE
                tyre = TYRE_TYPES[tyre_id]
                tyre_why = (
                    given(f"{gkey}.tyre_type")
                    if gd.tyre_type
                    else "default: the presets' tyre class (the description names none)"
                )
                per_tyre = st.normal_kn[(i, j)] * 1000.0 / g.axles / g.tyres_per_axle
                # the default keeps its source text of before tyre types, so that default answers do not change
                src = TYRE_SOURCE if tyre_id == DEFAULT_TYRE_TYPE else f"{tyre.name}: {tyre.source}"
                cc = Parameter(tyre.stiffness_n_per_rad(per_tyre) / per_tyre, "1/rad",
                               f"estimated: {src} ({per_tyre / 1000.0:.1f} kN a tyre)")  # fmt: skip
            if gd.axle_spacing_m is not None:
                _check_range(gd.axle_spacing_m, 0.9, 3.0, f"{path}.axle_spacing_m", "axles of one group")
                sp = Parameter(gd.axle_spacing_m, "m", given(f"{gkey}.axle_spacing_m"))
            else:
                sp = Parameter(AXLE_SPACING_M, "m", f"estimated: {AXLE_SPACING_SOURCE}")
            n = g.axles
            xs = tuple(g.position_m + (k - (n - 1) / 2.0) * sp.value for k in range(n))
            load = st.normal_kn[(i, j)] / n
            groups[(i, j)] = GroupParameters(cc, sp, xs, load, tuple(cc.value * load for _ in xs), tyre_id, tyre_why)
    units = []
    for i, u in enumerate(c.units):
        ud = data.units.get(u.id, UnitData())
        ukey = f"units[{u.id}]"
        path = f"dynamics.{ukey}"
        xs_all = [x for j in range(len(u.groups)) for x in groups[(i, j)].axle_positions_m]
        if ud.front_overhang_m is not None:
            _check_range(ud.front_overhang_m, 0.0, 5.0, f"{path}.front_overhang_m", f"unit {u.id!r} (ahead of its "
                         "reference point)")  # fmt: skip
            front = Parameter(ud.front_overhang_m, "m", given(f"{ukey}.front_overhang_m"))
        else:
            f, why = _front_estimate(u.kind)
            front = Parameter(f, "m", f"estimated: {why}")
        # the body's front, behind the reference point (a full trailer's overhang is measured from its turntable)
        front_x = -front.value + (u.groups[0].position_m if u.kind == "full-trailer" else 0.0)
        if ud.rear_extent_m is not None:
            rear = Parameter(ud.rear_extent_m, "m", given(f"{ukey}.rear_extent_m"))
        else:
            hitch = c.couplings[i].position_m + 0.3 if i < len(c.couplings) else 0.0
            if u.kind == "tractor":
                r, why = max(max(xs_all) + 1.0, hitch), "1.0 m behind the last axle"
            elif u.kind == "dolly":
                r, why = max(max(xs_all) + 0.5, hitch), "0.5 m behind the last axle"
            else:
                r = max(2.0 * u.cg_position_m - front_x, max(xs_all) + 0.5, hitch)
                why = (
                    "uniform body centred on the sprung CG, rear = 2 x_cg + front, 0.5 m behind the last axle at least"
                )
            rear = Parameter(r, "m", f"estimated: {why} and 0.3 m behind a rear coupling (assumed)")
        # a coupling or an axle must lie on the unit
        reach = max([*xs_all, c.couplings[i].position_m if i < len(c.couplings) else 0.0])
        if not rear.value >= reach:
            raise InvalidVehicle(
                f"{path}.rear_extent_m = {rear.value:g} m leaves an axle or the rear coupling ({reach:g} m behind "
                f"the reference point) outside unit {u.id!r}",
                field=f"{path}.rear_extent_m",
                value=rear.value,
            )
        if ud.width_m is not None:
            _check_range(ud.width_m, 1.5, 3.5, f"{path}.width_m", f"unit {u.id!r}")
            width = Parameter(ud.width_m, "m", given(f"{ukey}.width_m"))
        else:
            width = Parameter(WIDTH_M, "m", "estimated: assumed 2.5 m, the common general width limit")
        length = rear.value - front_x
        m = u.sprung_mass_kg
        axle_mass = [(g.unsprung_mass_kg, x) for j, g in enumerate(u.groups) for x in groups[(i, j)].axle_positions_m]
        sourced = inertias.get(u.id)
        if ud.yaw_inertia_kgm2 is None and sourced is not None:
            iz = Parameter(sourced[1], "kg m^2", f"{sourced[2]} (the sprung mass about its CG)")
        elif ud.yaw_inertia_kgm2 is not None:
            total = m + sum(ma for ma, _ in axle_mass)
            x_cg = (m * u.cg_position_m + sum(ma * x for ma, x in axle_mass)) / total
            bound = sum(ma * (x - x_cg) ** 2 for ma, x in axle_mass) + m * (u.cg_position_m - x_cg) ** 2
            if not ud.yaw_inertia_kgm2 > bound:
                raise InvalidVehicle(
                    f"{path}.yaw_inertia_kgm2 = {ud.yaw_inertia_kgm2:g} kg m^2 is below the point-mass bound of "
                    f"the own masses of unit {u.id!r} about its CG ({bound:.0f} kg m^2)",
                    field=f"{path}.yaw_inertia_kgm2", value=ud.yaw_inertia_kgm2)  # fmt: skip
            iz = Parameter(ud.yaw_inertia_kgm2 - bound, "kg m^2", given(f"{ukey}.yaw_inertia_kgm2") + " (the unit's, "
                           "about its CG; the axles' point masses taken out)")  # fmt: skip
        else:
            iz = Parameter(m * (length**2 + width.value**2) / 12.0, "kg m^2",
                           f"estimated: sprung mass as a uniform box m (L^2 + w^2)/12, L = {length:.2f} m, w = "
                           f"{width.value:g} m (Gillespie 1992)")  # fmt: skip
        hr = max(g.roll_centre_height_m for g in u.groups)
        if ud.roll_inertia_kgm2 is None and sourced is not None:
            ix = Parameter(sourced[0], "kg m^2", sourced[2])
        elif ud.roll_inertia_kgm2 is not None:
            _check_range(ud.roll_inertia_kgm2, 1.0, 1e6, f"{path}.roll_inertia_kgm2", f"unit {u.id!r}")
            ix = Parameter(ud.roll_inertia_kgm2, "kg m^2", given(f"{ukey}.roll_inertia_kgm2"))
        else:
            height = 2.0 * (u.cg_height_m - hr)
            formula = f"a uniform box m (w^2 + H^2)/12 with H = 2 (h_cg - h_rc) = {height:.2f} m"
            ix = Parameter(m * (width.value**2 + height**2) / 12.0, "kg m^2", f"estimated: {formula}")
        units.append(UnitParameters(iz, ix, front, rear, width))
    tau = Parameter(ROLL_DAMPING_TAU_S, "s", "assumed: suspension roll damping c = 0.02 s x roll stiffness (no "
                    "readable source)")  # fmt: skip
    return ResolvedParameters(tuple(units), groups, tau)


def tyre_cornering_stiffness_n_per_rad(load_n: float, tyre_type: str = DEFAULT_TYRE_TYPE) -> float:
    """Cornering stiffness of one tyre of a type (default: the presets' class) at a vertical load [N/rad]
    (:meth:`engine.dynamics.tyres.TyreType.stiffness_n_per_rad`)."""
    return TYRE_TYPES[tyre_type].stiffness_n_per_rad(load_n)


def unit_total_mass_kg(c: Combination, i: int) -> float:
    u = c.units[i]
    return u.sprung_mass_kg + sum(g.axles * g.unsprung_mass_kg for g in u.groups)


def as_dict(c: Combination, p: ResolvedParameters) -> dict:
    """The parameters used, plain JSON types: units and groups with value, unit and source (for the answers)."""
    units = []
    for u, up in zip(c.units, p.units, strict=True):
        units.append({"unit": u.id, **{k: vars(getattr(up, k)) for k in
                                       ("yaw_inertia_kgm2", "roll_inertia_kgm2", "front_overhang_m", "rear_extent_m",
                                        "width_m")}})  # fmt: skip
    groups = []
    for (i, j), gp in p.groups.items():
        groups.append({
            "unit": c.units[i].id, "group": c.units[i].groups[j].id,
            "cornering_coefficient_per_rad": vars(gp.cornering_coefficient_per_rad),
            "axle_spacing_m": vars(gp.axle_spacing_m),
            "tyre_type": {"value": gp.tyre_type, "source": gp.tyre_type_source if gp.tyre_type is None else
                          f"{gp.tyre_type_source}: {TYRE_TYPES[gp.tyre_type].name}"},
            "axle_positions_m": list(gp.axle_positions_m),
            "cornering_stiffness_kn_per_rad": list(gp.cornering_stiffness_kn_per_rad),
        })  # fmt: skip
    return {"units": units, "groups": groups, "roll_damping_tau_s": vars(p.roll_damping_tau_s),
            "gravity_m_per_s2": G_M_PER_S2}  # fmt: skip

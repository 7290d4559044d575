"""Combination presets: the thesis's trailers behind sourced towing units, and two doubles from sourced components.

Each preset is a :class:`~engine.vehicle.combination.Combination` and, for every value, where it comes from
(:data:`COMBINATION_SOURCES`, ``field path -> source``): the thesis's tables, the TruckSim example database
(:mod:`engine.vehicle.roll_components`), a value derived from them (said so, with how), or "assumed" and why.

Derived from a thesis record (:func:`unit_from_record`): the roll stiffness of an axle from its leaf springs,
``kLs b^2 / 2`` (Eq. 2.11); the roll centre at the spring tops, ``lr + ls``, where the thesis's sprung body rests on
its suspension (joints 7 and 10 of Fig. 26); the unsprung mass of a trailer axle from TruckSim (445 kg, its trailer
axle) at the record's loaded radius; the sprung mass and CG are the record's weight and CG less the axles.

References
----------
.. [1] Moreno (thesis), Tables 15 and 16, Ch. 8 (the TruckSim semitrailer), Ch. 9 (the B-train of Ervin and Guy,
   1986), Eq. 2.11.
.. [2] TruckSim 2022.1 example database, github.com/Steve-Krug/Axicle, 04-Trucksim/ (see roll_components).
"""

from __future__ import annotations

from dataclasses import dataclass

from engine.errors import UnknownPreset
from engine.vehicle.combination import G_M_PER_S2, AxleGroup, Combination, Coupling, Unit
from engine.vehicle.presets import PRESETS
from engine.vehicle.record import Vehicle
from engine.vehicle.roll_components import (
    FIFTH_WHEELS,
    SUSPENSIONS_IN_ROLL,
    TYRES_BY_SIZE,
    RollSuspension,
    RollTyre,
)

_THESIS = "Moreno (thesis)"
_TS = "TruckSim 2022.1 example dataset"
_REPO = "github.com/Steve-Krug/Axicle, 04-Trucksim/"
TRAILER_AXLE = SUSPENSIONS_IN_ROLL["trucksim-trailer-leaf-18t"]  # its unsprung mass: TruckSim's trailer axle


@dataclass(frozen=True)
class CombinationInfo:
    title: str
    summary: str


class _Sources(dict):
    def set(self, path: str, value, source: str):
        self[path] = source
        return value


def _group_from_library(
    src: _Sources,
    path: str,
    gid: str,
    axles: int,
    tyres_per_axle: int,
    track_m: float,
    track_source: str,
    position_m: float,
    position_source: str,
    susp: RollSuspension,
    tyre: RollTyre,
    *,
    steer: bool = False,
) -> AxleGroup:
    src.set(f"{path}.axles", axles, position_source)
    src.set(f"{path}.tyres_per_axle", tyres_per_axle, position_source)
    return AxleGroup(
        gid,
        axles,
        tyres_per_axle,
        src.set(f"{path}.track_m", track_m, track_source),
        src.set(f"{path}.position_m", position_m, position_source),
        src.set(f"{path}.tyre_stiffness_kn_per_m", tyre.stiffness_kn_per_m.value, tyre.stiffness_kn_per_m.source),
        src.set(
            f"{path}.roll_stiffness_knm_per_rad",
            susp.roll_stiffness_knm_per_rad.value,
            susp.roll_stiffness_knm_per_rad.source,
        ),
        src.set(f"{path}.roll_centre_height_m", susp.roll_centre_height_m.value, susp.roll_centre_height_m.source),
        src.set(f"{path}.unsprung_mass_kg", susp.unsprung_mass_kg.value, susp.unsprung_mass_kg.source),
        src.set(f"{path}.unsprung_cg_height_m", susp.unsprung_cg_height_m.value, susp.unsprung_cg_height_m.source),
        lash_deg=src.set(f"{path}.lash_deg", susp.lash_deg.value, susp.lash_deg.source),
        spring_spacing_m=src.set(f"{path}.spring_spacing_m", susp.spring_spacing_m.value, susp.spring_spacing_m.source),
        steer=steer,
    )


def unit_from_record(v: Vehicle, uid: str, kind: str, table: str, src: _Sources, path: str) -> Unit:
    """The last unit of a thesis record as a roll-model unit (see the module docstring)."""
    t = f"{_THESIS}, {table}"
    lr, ls, b = v.rolling_radius_m, v.suspension_height_m, v.spring_separation_m
    m_axle = TRAILER_AXLE.unsprung_mass_kg.value
    n = v.rear_axles
    total_kg = v.weight_kn * 1000.0 / G_M_PER_S2
    h_total = lr + ls + v.cg_height_above_chassis_m
    sprung = total_kg - n * m_axle
    h_sprung = (total_kg * h_total - n * m_axle * lr) / sprung
    x_sprung = (total_kg * v.front_axle_to_cg_m - n * m_axle * v.wheelbase_m) / sprung
    gp = f"{path}.groups[0]"
    group = AxleGroup(
        uid,
        src.set(f"{gp}.axles", n, f"{t}: rear axles"),
        src.set(f"{gp}.tyres_per_axle", v.rear_tires_per_axle, f"{t}: tires per axle"),
        src.set(f"{gp}.track_m", v.rear_track_m, f"{t}: track t3"),
        src.set(f"{gp}.position_m", v.wheelbase_m, f"{t}: wheelbase L (kingpin to the rear group)"),
        src.set(f"{gp}.tyre_stiffness_kn_per_m", v.tire_stiffness_kn_per_m, f"{t}: kT"),
        src.set(
            f"{gp}.roll_stiffness_knm_per_rad",
            v.suspension_stiffness_kn_per_m * b * b / 2.0,
            f"derived: kLs b^2/2 (Eq. 2.11) with {t}'s kLs = {v.suspension_stiffness_kn_per_m:g} kN/m, b = {b:g} m",
        ),
        src.set(f"{gp}.roll_centre_height_m", lr + ls, f"derived: lr + ls ({t}), the spring tops the body rests on"),
        src.set(f"{gp}.unsprung_mass_kg", m_axle, TRAILER_AXLE.unsprung_mass_kg.source),
        src.set(f"{gp}.unsprung_cg_height_m", lr, f"{t}: loaded radius lr (the axle centre)"),
        lash_deg=src.set(f"{gp}.lash_deg", 0.0, f"{t}: the thesis's suspension has no lash"),
        spring_spacing_m=src.set(f"{gp}.spring_spacing_m", b, f"{t}: b"),
    )
    return Unit(
        uid,
        kind,
        src.set(
            f"{path}.sprung_mass_kg",
            sprung,
            f"derived: {t}'s W = {v.weight_kn:g} kN / g less {n} axles of {m_axle:g} kg",
        ),
        src.set(f"{path}.cg_height_m", h_sprung, f"derived: {t}'s CG lr + ls + l12 = {h_total:.3f} m less the axles"),
        src.set(f"{path}.cg_position_m", x_sprung, f"derived: {t}'s a = {v.front_axle_to_cg_m:g} m less the axles"),
        (group,),
        title=f"{table} trailer",
    )


def _tractor_4x2(src: _Sources, drive_track: float, drive_track_source: str) -> Unit:
    steer = SUSPENSIONS_IN_ROLL["trucksim-steer-leaf-5.5t"]
    drive = SUSPENSIONS_IN_ROLL["trucksim-drive-leaf-8.5t"]
    tyre = TYRES_BY_SIZE["trucksim-3000kg"]
    lead = f"{_TS} '2A Day Cab' (4x2 tractor), {_REPO}Vehicles/Lead_2a/Lead2a_29ff09fb...par"
    tyre_note = (
        " (its tyre group '3000 kg Steer, 3000 kg Drive (510 mm)' is not in the copy: the 3000 kg tyre of the same "
        "database stands in)"
    )
    tyre = RollTyre(
        tyre.id,
        tyre.title,
        tyre.sizes,
        type(tyre.stiffness_kn_per_m)(
            tyre.stiffness_kn_per_m.value, "kN/m", tyre.stiffness_kn_per_m.source + tyre_note
        ),
        tyre.free_radius_m,
        tyre.rated_load_kg,
    )
    p = "combination.units[0]"
    groups = (
        _group_from_library(
            src,
            f"{p}.groups[0]",
            "steer",
            1,
            2,
            2.03,
            f"{_TS} '5.5t Steer, Single Wheel - Kinematics': L_TRACK 2030",
            0.0,
            f"{lead}: the steer axle is the reference",
            steer,
            tyre,
            steer=True,
        ),
        _group_from_library(
            src,
            f"{p}.groups[1]",
            "drive",
            1,
            4,
            drive_track,
            drive_track_source,
            3.5,
            f"{lead}: LX_AXLE_2 3500",
            drive,
            tyre,
        ),
    )
    sprung = f"{_TS} '2A Cab-Over' sprung mass, {_REPO}Vehicles/Sprung_Mass/SprMass_5f3ae270...par"
    sub = " (the 2A Day Cab's own sprung mass 'SprMass_455496a4' is not in the copy: the database's other two-axle tractor sprung mass stands in)"  # noqa: E501
    return Unit(
        "tractor",
        "tractor",
        src.set(f"{p}.sprung_mass_kg", 4455.0, f"{sprung}: M_SU 4455{sub}"),
        src.set(f"{p}.cg_height_m", 1.175, f"{sprung}: H_CG_SU 1175{sub}"),
        src.set(f"{p}.cg_position_m", 1.11, f"{sprung}: LX_CG_SU 1110{sub}"),
        groups,
        title="Two-axle (4x2) tractor, TruckSim '2A Day Cab'",
    )


def _tractor_6x4(src: _Sources) -> Unit:
    steer = SUSPENSIONS_IN_ROLL["trucksim-steer-leaf-5.5t"]
    drive = SUSPENSIONS_IN_ROLL["trucksim-tandem-leaf-15.5t"]
    tyre = TYRES_BY_SIZE["trucksim-3000kg"]
    lead = f"{_TS} '3A Sleeper (18 Spd)' (6x4 tractor), {_REPO}Vehicles/Lead_3a/Lead3a_9e25d126...par"
    p = "combination.units[0]"
    sub_steer = (
        "; the tractor links '5.5t Leaf: +150 mm, -60 mm Travel', not in the copy: '5.5t Leaf: +150 mm, -150 mm "
        "Travel' stands in"
    )
    steer_s = RollSuspension(
        steer.id,
        steer.title,
        steer.kind,
        type(steer.roll_stiffness_knm_per_rad)(
            steer.roll_stiffness_knm_per_rad.value, "kN m/rad", steer.roll_stiffness_knm_per_rad.source + sub_steer
        ),
        steer.roll_centre_height_m,
        steer.lash_deg,
        steer.spring_spacing_m,
        steer.unsprung_mass_kg,
        steer.unsprung_cg_height_m,
        steer.rated_axle_load_kg,
    )
    groups = (
        _group_from_library(
            src,
            f"{p}.groups[0]",
            "steer",
            1,
            2,
            2.03,
            f"{_TS} '5.5t Steer, Single Wheel - Kinematics': L_TRACK 2030",
            0.0,
            f"{lead}: the steer axle is the reference",
            steer_s,
            tyre,
            steer=True,
        ),
        _group_from_library(
            src,
            f"{p}.groups[1]",
            "drive",
            2,
            4,
            1.863,
            f"{_TS} '15.5t Drive, Dual Wheels - Kinematics': L_TRACK 1863",
            5.635,
            f"{lead}: LX_AXLE 5000 and 6270 mm, the tandem's centre",
            drive,
            tyre,
        ),
    )
    sprung = f"{_TS} '3A Sleeper Cab' sprung mass, {_REPO}Vehicles/Sprung_Mass/SprMass_93a3d6a8...par"
    return Unit(
        "tractor",
        "tractor",
        src.set(f"{p}.sprung_mass_kg", 6310.0, f"{sprung}: M_SU 6310"),
        src.set(f"{p}.cg_height_m", 1.02, f"{sprung}: H_CG_SU 1020"),
        src.set(f"{p}.cg_position_m", 1.385, f"{sprung}: LX_CG_SU 1385"),
        groups,
        title="Three-axle (6x4) tractor, TruckSim '3A Sleeper (18 Spd)'",
    )


def _fifth_wheel(
    src: _Sources, path: str, position: float, position_source: str, height: float, height_source: str
) -> Coupling:
    fw = FIFTH_WHEELS["trucksim-fifth-wheel"]
    return Coupling(
        src.set(f"{path}.kind", "fifth-wheel", position_source),
        src.set(f"{path}.position_m", position, position_source),
        src.set(f"{path}.height_m", height, height_source),
        src.set(
            f"{path}.roll_stiffness_knm_per_rad",
            fw.roll_stiffness_knm_per_rad.value,
            fw.roll_stiffness_knm_per_rad.source,
        ),
        src.set(f"{path}.lash_deg", fw.lash_deg.value, fw.lash_deg.source),
    )


def _tractor_semitrailer_table15() -> tuple[Combination, _Sources]:
    src = _Sources()
    t15 = PRESETS["table15-semitrailer"]
    tractor = _tractor_4x2(
        src,
        1.815,
        f"{_THESIS}, Table 15: t1 = 1.815 m (the tractor's drive axle is the front group of the trailer model)",
    )
    trailer = unit_from_record(t15, "trailer", "semitrailer", "Table 15", src, "combination.units[1]")
    fw = _fifth_wheel(
        src,
        "combination.couplings[0]",
        3.5 - 0.9,
        f"{_THESIS}, Table 15: l13 = 0.9 m, the fifth wheel "
        "ahead of the drive axle (TruckSim's '2A Day Cab' puts it 0.6 m ahead)",
        1.07,
        f"{_TS} '2A Day Cab': H_H 1070",
    )
    record = t15.replace(front_llt_ratio=None)
    src["last_unit_record"] = f"{_THESIS}, Table 15 (front_llt_ratio left to the whole-combination model)"
    return Combination((tractor, trailer), (fw,), "Table 15 semitrailer behind a 4x2 tractor (Ch. 8)", record), src


def _btrain_table16() -> tuple[Combination, _Sources]:
    src = _Sources()
    t16 = PRESETS["table16-btrain"]
    tractor = _tractor_6x4(src)
    lead_path = "combination.units[1]"
    t = f"{_THESIS}, Table 16"
    lr, ls = t16.rolling_radius_m, t16.suspension_height_m
    b = t16.spring_separation_m
    lead_l = 6.27
    gp = f"{lead_path}.groups[0]"
    lead_group = AxleGroup(
        "lead",
        src.set(f"{gp}.axles", t16.front_axles, f"{t}: front axles (the lead trailer's group under the B-coupling)"),
        src.set(f"{gp}.tyres_per_axle", t16.front_tires_per_axle, f"{t}: tires per axle"),
        src.set(f"{gp}.track_m", t16.front_track_m, f"{t}: t1"),
        src.set(
            f"{gp}.position_m",
            lead_l,
            f"assumed: the kingpin-to-group distance of {_TS} '18t Flatbed B-Train, "
            "Tridem' (lead trailer, LX_AXLE 5000/6270/7540 mm: centre 6270); the thesis gives none",
        ),
        src.set(f"{gp}.tyre_stiffness_kn_per_m", t16.tire_stiffness_kn_per_m, f"{t}: kT"),
        src.set(
            f"{gp}.roll_stiffness_knm_per_rad",
            t16.suspension_stiffness_kn_per_m * b * b / 2.0,
            f"derived: kLs b^2/2 (Eq. 2.11), {t}'s kLs 1800 kN/m and b 0.95 m",
        ),
        src.set(f"{gp}.roll_centre_height_m", lr + ls, f"derived: lr + ls ({t})"),
        src.set(f"{gp}.unsprung_mass_kg", TRAILER_AXLE.unsprung_mass_kg.value, TRAILER_AXLE.unsprung_mass_kg.source),
        src.set(f"{gp}.unsprung_cg_height_m", lr, f"{t}: lr"),
        lash_deg=src.set(f"{gp}.lash_deg", 0.0, f"{t}: no lash"),
        spring_spacing_m=src.set(f"{gp}.spring_spacing_m", b, f"{t}: b"),
    )
    lead = Unit(
        "lead",
        "btrain-lead",
        src.set(
            f"{lead_path}.sprung_mass_kg",
            20000.0 - 2 * TRAILER_AXLE.unsprung_mass_kg.value,
            "assumed: 20,000 kg laden (its two axles then carry about 9 t each, near the rear trailer's 8.5 t); "
            "the thesis describes the rear trailer only",
        ),
        src.set(f"{lead_path}.cg_height_m", 2.0, "assumed: about the rear trailer's CG height (2.06 m, Table 16)"),
        src.set(f"{lead_path}.cg_position_m", 2.5, "assumed: 2.5 m behind its kingpin"),
        (lead_group,),
        title="B-train lead trailer (assumed body on Table 16's front group)",
    )
    rear = unit_from_record(t16, "rear", "semitrailer", "Table 16", src, "combination.units[2]")
    fw = _fifth_wheel(
        src,
        "combination.couplings[0]",
        5.635,
        f"{_TS} '3A Sleeper (18 Spd)': LX_H 5635",
        1.09,
        f"{_TS} '3A Sleeper (18 Spd)': H_H 1090",
    )
    cp = "combination.couplings[1]"
    b1 = t16.fifth_wheel_width_m
    bcoupling = Coupling(
        src.set(f"{cp}.kind", "b-coupling", f"{t}: the rear trailer's fifth wheel on the lead trailer"),
        src.set(
            f"{cp}.position_m",
            lead_l - t16.fifth_wheel_to_front_axle_m,
            f"{t}: l13 = 0.15 m, the fifth wheel ahead of the lead trailer's group",
        ),
        src.set(
            f"{cp}.height_m",
            lr + ls + t16.fifth_wheel_height_m,
            f"derived: lr + ls + lf ({t}: 0.499 + 0.205 + 0.1 m), the fifth-wheel plate of the thesis's mechanism",
        ),
        src.set(
            f"{cp}.roll_stiffness_knm_per_rad",
            t16.fifth_wheel_stiffness_kn_per_m * b1 * b1 / 2.0,
            f"derived: kf b1^2/2 (Eq. 2.11 for the fifth wheel's two springs), {t}'s kf 7500 kN/m, b1 0.6 m",
        ),
        src.set(f"{cp}.lash_deg", 0.0, f"{t}: the thesis's fifth wheel has no lash"),
    )
    src["last_unit_record"] = f"{t} (front_llt_ratio left to the whole-combination model)"
    return (
        Combination(
            (tractor, lead, rear),
            (fw, bcoupling),
            "B-double: 6x4 tractor, lead trailer, Table 16 rear trailer",
            t16.replace(front_llt_ratio=None),
        ),
        src,
    )


def _pup(src: _Sources, path: str, uid: str) -> Unit:
    """TruckSim's 28-ft van semitrailer with its 'Double Trailers (9000 kg)' payload, on one 15.5 t axle."""
    body = f"{_TS} '1A Van Trailer, 28-ft' sprung mass, {_REPO}Vehicles/Trl_Sprung_Mass/TrlSprM_0d042329...par"
    load = f"{_TS} payload 'Double Trailers (9000 kg)', {_REPO}Payloads/Box/Box_aaf9bc17...par"
    mass = 2116.0 + 9000.0
    h = (2116.0 * 1.935 + 9000.0 * 2.3) / mass
    x = (2116.0 * 3.5 + 9000.0 * 3.5) / mass
    susp = SUSPENSIONS_IN_ROLL["trucksim-tandem-leaf-15.5t"]
    tyre = TYRES_BY_SIZE["trucksim-3000kg"]
    group = _group_from_library(
        src,
        f"{path}.groups[0]",
        uid,
        1,
        4,
        1.863,
        f"{_TS} '15.5t Trailer, Dual Wheels - Kinematics': L_TRACK 1863",
        7.0,
        "assumed: the axle 7.0 m behind the kingpin, about "
        "1.5 m from the rear of a 28-ft (8.53 m) trailer (the assembly giving it was not "
        "read)",
        susp,
        tyre,
    )
    return Unit(
        uid,
        "semitrailer",
        src.set(f"{path}.sprung_mass_kg", mass, f"{body}: M_SU 2116; plus {load}: M_PL 9000"),
        src.set(f"{path}.cg_height_m", h, "derived: the body (H_CG_SU 1935) and payload (Z_CG_PL 2300) combined"),
        src.set(f"{path}.cg_position_m", x, "derived: LX_CG_SU 3500 and LX_CG_PL 3500"),
        (group,),
        title="28-ft van semitrailer with 9000 kg (TruckSim)",
    )


def _adouble() -> tuple[Combination, _Sources]:
    src = _Sources()
    tractor = _tractor_4x2(src, 1.863, f"{_TS} '8.5t Drive, Dual Wheels': L_TRACK 1863")
    first = _pup(src, "combination.units[1]", "trailer1")
    dp = "combination.units[2]"
    dolly_s = SUSPENSIONS_IN_ROLL["trucksim-dolly-leaf-22.5kip"]
    dolly_body = f"{_TS} '1A Dolly w/ Rigid Towbar', {_REPO}Vehicles/Dolly_1a/Dly1a_b71e331b...par"
    dolly = Unit(
        "dolly",
        "dolly",
        src.set(f"{dp}.sprung_mass_kg", 1315.0, f"{dolly_body} (sprung mass TrlSprM_1399a1df): M_SU 1315"),
        src.set(f"{dp}.cg_height_m", 1.0, f"{dolly_body}: H_CG_SU 1000"),
        src.set(f"{dp}.cg_position_m", 1.827, f"{dolly_body}: LX_CG_SU 1827"),
        (
            _group_from_library(
                src,
                f"{dp}.groups[0]",
                "dolly",
                1,
                4,
                1.863,
                f"{_TS} '15.5t Trailer, Dual Wheels': "
                "L_TRACK 1863 (the dolly's own kinematics file is not in the copy)",
                1.98,
                f"{dolly_body}: LX_AXLE 1980",
                dolly_s,
                TYRES_BY_SIZE["trucksim-3000kg"],
            ),
        ),
        title="Converter dolly (A-dolly), TruckSim '1A Dolly w/ Rigid Towbar'",
    )
    second = _pup(src, "combination.units[3]", "trailer2")
    fw = _fifth_wheel(
        src, "combination.couplings[0]", 2.9, f"{_TS} '2A Day Cab': LX_H 2900", 1.07, f"{_TS} '2A Day Cab': H_H 1070"
    )
    pin = "combination.couplings[1]"
    pintle = Coupling(
        src.set(f"{pin}.kind", "pintle", "the A-dolly's drawbar eye on the first trailer's pintle hook"),
        src.set(
            f"{pin}.position_m",
            8.5,
            "assumed: at the rear of the 28-ft trailer, 1.5 m behind its axle (TruckSim's "
            "'53-ft Van Trailer w/ Pintle' has its pintle 1.57 m behind its last axle)",
        ),
        src.set(f"{pin}.height_m", 0.82, f"{_TS} '53-ft Van Trailer w/ Pintle': H_H 820"),
        lash_deg=src.set(f"{pin}.lash_deg", 0.0, "a pintle passes no roll moment: it has no roll lash"),
    )
    dfw = _fifth_wheel(
        src,
        "combination.couplings[2]",
        1.98,
        f"{dolly_body}: the dolly's fifth wheel LX_H 1980",
        1.065,
        f"{dolly_body}: H_H 1065",
    )
    return (
        Combination(
            (tractor, first, dolly, second),
            (fw, pintle, dfw),
            "A-double: 4x2 tractor, 28-ft semitrailer, A-dolly, 28-ft semitrailer (TruckSim components)",
        ),
        src,
    )


def _truck_trailer() -> tuple[Combination, _Sources]:
    src = _Sources()
    lead = f"{_TS} '3A Conv Van (S_SS)' (rigid truck, air tandem), {_REPO}Vehicles/Lead_3a/Lead3a_5833e3c8...par"
    p = "combination.units[0]"
    tyre = TYRES_BY_SIZE["trucksim-3000kg"]
    body = f"{_TS} 'Conventional Van' sprung mass"
    van_mass, van_h, van_x = 4455.0, 1.175, 1.25
    load_mass, load_h, load_x = 8000.0, 2.3, 4.0
    mass = van_mass + load_mass
    truck = Unit(
        "truck",
        "rigid-truck",
        src.set(
            f"{p}.sprung_mass_kg", mass, f"{body}: M_SU 4455 (no payload in the file), plus assumed 8000 kg of payload"
        ),
        src.set(
            f"{p}.cg_height_m",
            (van_mass * van_h + load_mass * load_h) / mass,
            f"derived: {body} H_CG_SU 1175 and "
            "the assumed payload at 2.3 m (TruckSim's trailer boxes: H_BOX_BOTTOM 1300 + half of 2000)",
        ),
        src.set(
            f"{p}.cg_position_m",
            (van_mass * van_x + load_mass * load_x) / mass,
            f"derived: {body} LX_CG_SU 1250 and the assumed payload 4.0 m behind the front axle",
        ),
        (
            _group_from_library(
                src,
                f"{p}.groups[0]",
                "steer",
                1,
                2,
                2.03,
                f"{_TS} '5.5t Steer, Single Wheel - Kinematics': L_TRACK 2030",
                0.0,
                f"{lead}: the reference",
                SUSPENSIONS_IN_ROLL["trucksim-steer-leaf-5.5t"],
                tyre,
                steer=True,
            ),
            _group_from_library(
                src,
                f"{p}.groups[1]",
                "drive",
                2,
                4,
                1.863,
                f"{_TS} '10t Drive, Dual Wheels': L_TRACK 1863",
                5.865,
                f"{lead}: LX_AXLE 5230 and 6500 mm, the tandem's centre",
                SUSPENSIONS_IN_ROLL["trucksim-air-high-roll-10t"],
                tyre,
            ),
        ),
        title="Rigid truck with an air tandem, TruckSim '3A Conv Van'",
    )
    fp = "combination.units[1]"
    trailer_body = (
        f"{_TS} '1A Trailer (Typical 28ft)' sprung mass, {_REPO}Vehicles/Trl_Sprung_Mass/TrlSprM_db68818b...par"
    )
    trailer_load = f"{_TS} payload 'Trailer (4500 kg)', {_REPO}Payloads/Box/Box_9009210f...par"
    t_mass = 3000.0 + 4500.0
    full = Unit(
        "trailer",
        "full-trailer",
        src.set(f"{fp}.sprung_mass_kg", t_mass, f"{trailer_body}: M_SU 3000; plus {trailer_load}: M_PL 4500"),
        src.set(f"{fp}.cg_height_m", (3000.0 * 2.0 + 4500.0 * 2.3) / t_mass, "derived: H_CG_SU 2000 and Z_CG_PL 2300"),
        src.set(
            f"{fp}.cg_position_m",
            2.0 + 3.5,
            "derived: body and payload 3.5 m behind the front of the body "
            "(LX_CG_SU, LX_CG_PL 3500), which is assumed to start over the turntable 2.0 m behind the drawbar eye",
        ),
        (
            _group_from_library(
                src,
                f"{fp}.groups[0]",
                "front",
                1,
                4,
                1.863,
                f"{_TS} '15.5t Trailer, Dual Wheels': L_TRACK 1863",
                1.98,
                f"{_TS} '1A Dolly w/ Rigid Towbar': LX_AXLE 1980 (the turntable axle placed as the dolly's)",
                SUSPENSIONS_IN_ROLL["trucksim-dolly-leaf-22.5kip"],
                tyre,
            ),
            _group_from_library(
                src,
                f"{fp}.groups[1]",
                "rear",
                1,
                4,
                1.863,
                f"{_TS} '15.5t Trailer, Dual Wheels': L_TRACK 1863",
                8.7,
                "assumed: 6.7 m behind the turntable (the 28-ft trailer's L_FRAME 6700)",
                SUSPENSIONS_IN_ROLL["trucksim-tandem-leaf-15.5t"],
                tyre,
            ),
        ),
        title="Full (drawbar) trailer on a turntable: TruckSim 28-ft body with 4500 kg",
    )
    pin = "combination.couplings[0]"
    pintle = Coupling(
        src.set(f"{pin}.kind", "pintle", "the full trailer's drawbar on the truck's pintle hook"),
        src.set(f"{pin}.position_m", 7.4, "assumed: 1.5 m behind the truck's tandem centre"),
        src.set(f"{pin}.height_m", 0.82, f"{_TS} '53-ft Van Trailer w/ Pintle': H_H 820"),
        lash_deg=src.set(f"{pin}.lash_deg", 0.0, "a pintle passes no roll moment: it has no roll lash"),
    )
    return Combination((truck, full), (pintle,), "Rigid truck and full (drawbar) trailer (TruckSim components)"), src


_BUILT = {
    "tractor-semitrailer-table15": _tractor_semitrailer_table15(),
    "btrain-table16": _btrain_table16(),
    "adouble": _adouble(),
    "truck-trailer": _truck_trailer(),
}

#: the combination presets by id
COMBINATIONS: dict[str, Combination] = {k: v[0] for k, v in _BUILT.items()}
#: where each value of a preset comes from: preset id -> {field path -> source}
COMBINATION_SOURCES: dict[str, dict[str, str]] = {k: dict(v[1]) for k, v in _BUILT.items()}
COMBINATION_INFO: dict[str, CombinationInfo] = {
    "tractor-semitrailer-table15": CombinationInfo(
        "Tractor-semitrailer: Table 15's semitrailer behind a 4x2 tractor (Ch. 8)",
        "The TruckSim semitrailer of the thesis's Ch. 8 behind TruckSim's two-axle tractor.",
    ),
    "btrain-table16": CombinationInfo(
        "B-double: 6x4 tractor, lead trailer, Table 16's rear trailer (Ch. 9)",
        "The thesis's B-train rear trailer behind an assumed lead trailer on its front group and TruckSim's 6x4 "
        "tractor; the three units roll together.",
    ),
    "adouble": CombinationInfo(
        "A-double: tractor, semitrailer, A-dolly, semitrailer",
        "Two 28-ft semitrailers joined by a converter dolly on a pintle: two roll-coupled units, each with its SRT.",
    ),
    "truck-trailer": CombinationInfo(
        "Rigid truck and full trailer",
        "A rigid truck with an air tandem towing a drawbar full trailer: two roll-coupled units.",
    ),
}
del _BUILT


def get_combination(combination_id: str) -> Combination:
    """The combination preset with this id; :class:`UnknownPreset` lists the known ids otherwise."""
    try:
        return COMBINATIONS[combination_id]
    except (KeyError, TypeError):
        raise UnknownPreset(combination_id, sorted(COMBINATIONS)) from None

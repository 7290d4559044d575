"""Component library of the whole-combination roll model: suspensions in roll, tyres by size, fifth wheels, units.

Every value is a :class:`~engine.vehicle.components.Sourced` number (value, unit, source). The one complete, readable
set of heavy-vehicle component data found is the **TruckSim example database** (Mechanical Simulation Corp.,
TruckSim 2022.1 / 2023.0), as committed to the public repository github.com/Steve-Krug/Axicle, folder
``04-Trucksim/`` (commits a7fa703ae736 and d36b1db6074, whose common files are identical but for the version
header). Its datasets are the vendor's generic examples, not measurements of a named vehicle, except where their own
notes name a measurement (the SAE Cooperative Research tyres, measured by UMTRI). A value computed from dataset values
says so ("derived") and how; where a dataset could not be read, the substitute is named.

Suspension roll stiffness per axle
----------------------------------
TruckSim's solid axle has two springs at the lateral spacing ``L_SPRINGS`` with the rate per side
``FS_COMP_COEFFICIENT``, and an auxiliary roll moment (anti-roll) in N m/deg; the roll stiffness of one axle is
``k s^2 / 2`` (Eq. 2.11) plus the auxiliary one (derived; 1 N m/deg = 57.2958 N m/rad). For the air suspensions the
spring rate depends on the load: TruckSim's air spring ("Air Spring, 2000 N Friction") gives at static load F a force
of 0.6 F / F / 1.4 F at -100 / 0 / +100 mm, i.e. ``k = 0.004 F per mm`` (derived from its table), evaluated here at
the axle's rated load (its GAWR split over two springs).

Three leaf suspensions carry the **UMTRI Factbook**'s (Fancher et al. 1986, UMTRI-86-12) springs, as TruckSim's
datasets "5.5t Leaf, Steer: Compliance", "8t Leaf, Trailer: Compliance" and "6.8t Leaf" and their springs cite it in
their notes (page numbers of the 202-page scan: tractor front springs p. 189, single-axle trailer and dolly springs
p. 192, trailer tandem springs p. 193; spring spreads and auxiliary roll stiffnesses pp. 196-200). The Factbook itself
could be read only to its title page; its values here are those the datasets took from it. The trailer springs are
tables of force against compression from the free spring, a loading and an unloading branch; their rate at the
axle's rated load is the slope of the mid-line between the branches there (:func:`leaf_table_rate`, derived), the
gap between the branches being the spring's Coulomb friction, which a static roll model does not carry.

Roll-centre height
------------------
TruckSim's notes define it from the lateral movement of the axle per degree of roll: "5 degrees of roll corresponds
to 4.6193 mm of lateral movement. Hence, 4.6193/(sin 5) = 53 mm (Roll center is 53 mm below Axle)" (dataset "0.9
mm/deg", ``Suspensions/Lateral_Roll/LatRoll_47be6450``). The steer axles use that dataset: 53 mm below the axle,
whose centre is 510 mm high. The heavy drive and trailer axles link the dataset "-3.4 mm/deg", whose file is not in
the copy: by the same definition its title gives 3.4 / sin(1 deg) = 195 mm above the axle (derived, a linear table
assumed), 530 mm + 195 mm = 0.725 m above the road -- within 2 cm of the thesis's mechanism, whose sprung body rests
on the spring tops at lr + ls = 0.704 m (Tables 16, 22, 23).

Lash
----
TruckSim models no suspension lash (its leaf springs carry Coulomb friction instead), and no readable source gives
one: the library's suspensions have no lash (0), and a user can enter a measured one. The fifth wheel's 1 deg each
way is from TruckSim's notes of its default fifth wheel.

References
----------
.. [1] TruckSim 2022.1 / 2023.0 example database (Mechanical Simulation Corp.), github.com/Steve-Krug/Axicle,
   ``04-Trucksim/`` (file paths in each source).
.. [2] Moreno (thesis), Eq. 2.11; Tables 15, 16, 22, 23.
.. [3] SAE Cooperative Research Program on truck tyres (1990s), measured by UMTRI, as the TruckSim datasets
   "Steer Tire, Symmetric", "Drive Tire, Asymmetric" and "Widebase, Symmetric" state.
.. [4] Fancher, Ervin, Winkler and Gillespie, A Factbook of the Mechanical Properties of the Components for
   Single-Unit and Articulated Heavy Trucks, UMTRI-86-12 (1986), as cited page by page in the notes of the TruckSim
   datasets [1] (the report's own tables were not readable here).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

from engine.errors import InvalidVehicle
from engine.vehicle.components import Sourced, parse_tyre_size

G = 9.81
_TS = "TruckSim 2022.1 example dataset"
_REPO = "github.com/Steve-Krug/Axicle, 04-Trucksim/"
_NM_PER_DEG = 180.0 / math.pi / 1000.0  # N m/deg -> kN m/rad


def _ts(title: str, path: str, what: str) -> str:
    return f"{_TS} '{title}' (Mechanical Simulation Corp.), {_REPO}{path}: {what}"


def _roll(k_n_per_mm: float, spacing_mm: float, aux_n_m_per_deg: float) -> float:
    """Roll stiffness of one axle: k s^2 / 2 (Eq. 2.11) plus the auxiliary roll moment [kN m/rad]."""
    return k_n_per_mm * (spacing_mm / 1000.0) ** 2 / 2.0 + aux_n_m_per_deg * _NM_PER_DEG


@dataclass(frozen=True)
class RollSuspension:
    """A suspension as the roll model sees it, per axle: roll stiffness, roll centre, lash, spring spacing, the
    axle's unsprung mass and its height, and the rated axle load it was described at."""

    id: str
    title: str
    kind: str
    roll_stiffness_knm_per_rad: Sourced
    roll_centre_height_m: Sourced
    lash_deg: Sourced
    spring_spacing_m: Sourced
    unsprung_mass_kg: Sourced
    unsprung_cg_height_m: Sourced
    rated_axle_load_kg: Sourced


_NO_LASH = Sourced(0.0, "deg", f"{_TS}s model no suspension lash (leaf springs carry Coulomb friction instead) and no "
                   "readable source gives one: none assumed; enter a measured lash where known")  # fmt: skip
_RC_STEER = Sourced(
    0.457,
    "m",
    _ts("0.9 mm/deg", "Suspensions/Lateral_Roll/LatRoll_47be6450...par",
        "its notes: 'Roll center is 53 mm below Axle'; with the steer axle centre H_WC 510 mm: 0.510 - 0.053"),
)  # fmt: skip
_RC_HEAVY = Sourced(
    0.725,
    "m",
    _ts("-3.4 mm/deg", "Suspensions/Lateral_Roll/LatRoll_32c683f9...par (not in the copy; linked by every heavy drive "
        "and trailer axle)", "derived from its title by TruckSim's own definition (lateral movement / sin(roll)): "
        "195 mm above the axle centre H_WC 530 mm"),
)  # fmt: skip
_STEER_KIN = "Suspensions/Kin_Solid/KinSA_64c30f3c...par"
_DRIVE_KIN = "Suspensions/Kin_Solid/KinSA_762a39b9...par"
_TRAILER_KIN = "Suspensions/Kin_Solid/KinSA_fdc0b85f...par"


# The UMTRI Factbook's leaf springs as TruckSim tabulates them (force [N] at compression [mm] from the free, unloaded
# position; a loading and an unloading branch, their gap the spring's Coulomb friction), the points from 0 to 76.2 mm
# of the datasets' FS_COMP_TABLE and FS_EXT_TABLE (the rebound points below 0 carry no load).
_FACTBOOK_TANDEM_SPRING = (  # 'Tandem Axle Trailer, 8t / 17.6 kip' (Suspensions/Springs/Spring_b1276e96...par)
    (0.0, 12.7, 25.4, 38.1, 50.8, 63.5, 76.2),
    (0.0, 15012.0, 32523.776, 52539.776, 75060.0, 100080.0, 250200.0),
    (0.0, 7503.776, 25020.0, 45036.0, 67551.776, 92571.776, 200160.0),
)
_FACTBOOK_SINGLE_SPRING = (  # 'Single Axle Trailer, 6.8t / 15 kip' (Suspensions/Springs/Spring_10789ed3...par)
    (0.0, 12.7, 25.4, 38.1, 50.8, 63.5, 76.2),
    (0.0, 16680.0, 36140.0, 58268.8, 83400.0, 111200.0, 275776.0),
    (0.0, 8340.0, 27800.0, 50040.0, 75060.0, 102860.0, 222400.0),
)
_IN_LB = 4.4482216152605 * 0.0254  # 1 in-lb = 0.112985 N m


def leaf_table_rate(table: tuple[tuple[float, ...], ...], spring_load_n: float) -> float:
    """The rate [N/mm] of a tabulated leaf spring at a static load: the slope, at that load, of the mid-line between
    its loading and unloading branches (the friction band taken out), piecewise linear as TruckSim interpolates it."""
    x, comp, ext = table
    mid = [(c + e) / 2.0 for c, e in zip(comp, ext, strict=True)]
    for i in range(len(x) - 1):
        if mid[i] <= spring_load_n <= mid[i + 1]:
            return (mid[i + 1] - mid[i]) / (x[i + 1] - x[i])
    raise ValueError(f"{spring_load_n} N is beyond the table")


def _leaf_table_roll(table, gawr_kg: float, spacing_mm: float, aux_n_m_per_deg: float) -> float:
    return _roll(leaf_table_rate(table, gawr_kg * G / 2.0), spacing_mm, aux_n_m_per_deg)


def _air_roll(gawr_kg: float, aux: float) -> float:
    spring_load_n = gawr_kg * G / 2.0
    return _roll(0.004 * spring_load_n, 1000.0, aux)


#: the unsprung mass and CG height of the library's trailer axle, for the Factbook leaf suspensions, whose datasets
#: name no kinematics of their own
_BORROWED_TRAILER_AXLE = (
    Sourced(
        445.0,
        "kg",
        _ts(
            "15.5t Trailer, Dual Wheels - Kinematics",
            _TRAILER_KIN,
            "M_US 445 (the library's trailer axle: the dataset names no kinematics)",
        ),
    ),
    Sourced(0.53, "m", _ts("15.5t Trailer, Dual Wheels - Kinematics", _TRAILER_KIN, "H_WC 530")),
)

SUSPENSIONS_IN_ROLL: dict[str, RollSuspension] = {
    s.id: s
    for s in (
        RollSuspension(
            "trucksim-steer-leaf-5.5t",
            "Steel leaf steer axle, 5.5 t (TruckSim '5.5t Leaf')",
            "steel leaf, steer",
            Sourced(
                _roll(250, 890, 8500),
                "kN m/rad",
                _ts(
                    "5.5t Leaf: +150 mm, -150 mm Travel",
                    "Suspensions/Compliance_SA/CmpSA_de50d1ae...par",
                    "FS_COMP_COEFFICIENT 250 N/mm per side, L_SPRINGS 890 mm, auxiliary roll 'Linear: 8500 N-m/deg' "
                    "(the linked file is not in the copy: its title); derived 250 x 0.89^2/2 + 8500 N m/deg",
                ),
            ),
            _RC_STEER,
            _NO_LASH,
            Sourced(
                0.89,
                "m",
                _ts(
                    "5.5t Leaf: +150 mm, -150 mm Travel",
                    "Suspensions/Compliance_SA/CmpSA_de50d1ae...par",
                    "L_SPRINGS 890",
                ),
            ),
            Sourced(362.0, "kg", _ts("5.5t Steer, Single Wheel - Kinematics", _STEER_KIN, "M_US 362")),
            Sourced(0.51, "m", _ts("5.5t Steer, Single Wheel - Kinematics", _STEER_KIN, "H_CG_AXLE 510")),
            Sourced(5500.0, "kg", _ts("5.5t Steer, Single Wheel - Kinematics", _STEER_KIN, "'Typical 5.5 tonne GAWR'")),
        ),
        RollSuspension(
            "trucksim-drive-leaf-8.5t",
            "Steel leaf drive axle, 8.5 t, of a two-axle tractor (TruckSim '8.5t Leaf')",
            "steel leaf, drive",
            Sourced(
                _roll(700, 1000, 1500),
                "kN m/rad",
                _ts(
                    "8.5t Leaf: +100 mm, -60 mm Travel",
                    "Suspensions/Compliance_SA/CmpSA_f30bb345...par",
                    "700 N/mm per side, L_SPRINGS 1000 mm, aux 'Linear: 1500 N-m/deg'; derived 700 x 1^2/2 + 1500",
                ),
            ),
            _RC_HEAVY,
            _NO_LASH,
            Sourced(
                1.0,
                "m",
                _ts(
                    "8.5t Leaf: +100 mm, -60 mm Travel",
                    "Suspensions/Compliance_SA/CmpSA_f30bb345...par",
                    "L_SPRINGS 1000",
                ),
            ),
            Sourced(
                679.0, "kg", _ts("8.5t Drive, Dual Wheels", "Suspensions/Kin_Solid/KinSA_372fbdd1...par", "M_US 679")
            ),
            Sourced(
                0.53, "m", _ts("8.5t Drive, Dual Wheels", "Suspensions/Kin_Solid/KinSA_372fbdd1...par", "H_WC 530")
            ),
            Sourced(
                8500.0,
                "kg",
                _ts(
                    "8.5t Leaf",
                    "Suspensions/Compliance_SA/CmpSA_f30bb345...par",
                    "'Typical 8.5 tonne (18,500 lb) GAWR drive axle'",
                ),
            ),
        ),
        RollSuspension(
            "trucksim-tandem-leaf-15.5t",
            "Steel leaf tandem axle, 15.5 t per tandem (TruckSim '15.5t Leaf': tractor tandem drives, trailers)",
            "steel leaf, tandem (drive or trailer)",
            Sourced(
                _roll(700, 1000, 3000),
                "kN m/rad",
                _ts(
                    "15.5t Leaf: +100 mm, -60 mm Travel",
                    "Suspensions/Compliance_SA/CmpSA_29ff82d8...par",
                    "700 N/mm per side, L_SPRINGS 1000 mm, aux 'Linear: 3000 N-m/deg'; derived 700 x 1^2/2 + 3000",
                ),
            ),
            _RC_HEAVY,
            _NO_LASH,
            Sourced(1.0, "m", _ts("15.5t Leaf", "Suspensions/Compliance_SA/CmpSA_29ff82d8...par", "L_SPRINGS 1000")),
            Sourced(603.0, "kg", _ts("15.5t Drive, Dual Wheels - Kinematics", _DRIVE_KIN, "M_US 603")),
            Sourced(0.53, "m", _ts("15.5t Drive, Dual Wheels - Kinematics", _DRIVE_KIN, "H_WC 530")),
            Sourced(
                7750.0,
                "kg",
                _ts("15.5t Leaf", "Suspensions/Compliance_SA/CmpSA_29ff82d8...par", "15.5 t per tandem, half per axle"),
            ),
        ),
        RollSuspension(
            "trucksim-trailer-leaf-18t",
            "Heavy multi-leaf trailer axle, 18 t per tridem (TruckSim '18t Leaf': van, B-train and dump trailers)",
            "steel multi-leaf, trailer tridem",
            Sourced(
                _roll(2500, 1000, 3000),
                "kN m/rad",
                _ts(
                    "18t Leaf: +100 mm, -60 mm Travel",
                    "Suspensions/Compliance_SA/CmpSA_b2468e94...par",
                    "2500 N/mm per side, L_SPRINGS 1000 mm, aux 'Linear: 3000 N-m/deg'; derived 2500 x 1^2/2 + 3000",
                ),
            ),
            _RC_HEAVY,
            _NO_LASH,
            Sourced(1.0, "m", _ts("18t Leaf", "Suspensions/Compliance_SA/CmpSA_b2468e94...par", "L_SPRINGS 1000")),
            Sourced(445.0, "kg", _ts("15.5t Trailer, Dual Wheels - Kinematics", _TRAILER_KIN, "M_US 445")),
            Sourced(0.53, "m", _ts("15.5t Trailer, Dual Wheels - Kinematics", _TRAILER_KIN, "H_WC 530")),
            Sourced(
                6000.0,
                "kg",
                _ts("18t Leaf", "Suspensions/Compliance_SA/CmpSA_b2468e94...par", "18 t per tridem, a third per axle"),
            ),
        ),
        RollSuspension(
            "trucksim-dolly-leaf-22.5kip",
            "Steel leaf converter-dolly axle, 22,500 lb (TruckSim '22.5 kip Leaf, Dolly')",
            "steel leaf, dolly",
            Sourced(
                _roll(660, 1000, 5700),
                "kN m/rad",
                _ts(
                    "22.5 kip Leaf, Dolly: +100 mm, -60 mm",
                    "Suspensions/Compliance_SA/CmpSA_3c5326f4...par",
                    "660 N/mm per side, L_SPRINGS 1000 mm, aux 'Linear: 5700 N-m/deg'; derived 660 x 1^2/2 + 5700",
                ),
            ),
            _RC_HEAVY,
            _NO_LASH,
            Sourced(
                1.0,
                "m",
                _ts("22.5 kip Leaf, Dolly", "Suspensions/Compliance_SA/CmpSA_3c5326f4...par", "L_SPRINGS 1000"),
            ),
            Sourced(
                445.0,
                "kg",
                _ts(
                    "15.5t Trailer, Dual Wheels - Kinematics",
                    _TRAILER_KIN,
                    "M_US 445 (the dolly's own kinematics file is not in the copy: a trailer axle "
                    "of the same duals stands in)",
                ),
            ),
            Sourced(0.53, "m", _ts("15.5t Trailer, Dual Wheels - Kinematics", _TRAILER_KIN, "H_WC 530")),
            Sourced(
                10206.0,
                "kg",
                _ts(
                    "22.5 kip Leaf, Dolly",
                    "Suspensions/Compliance_SA/CmpSA_3c5326f4...par",
                    "'22,500 lb (22.5 kip) GAWR dolly axle'",
                ),
            ),
        ),
        RollSuspension(
            "trucksim-air-high-roll-8.5t",
            "Air suspension with high roll stiffness, 8.5 t axle (TruckSim '8.5t Air', auxiliary roll 8500 N m/deg)",
            "air, high roll stiffness",
            Sourced(
                _air_roll(8500, 8500),
                "kN m/rad",
                _ts(
                    "8.5t Air",
                    "Suspensions/Compliance_SA/CmpSA_ff5425ec...par",
                    "air springs 1000 mm apart ('Air Spring, 2000 N Friction': k = 0.004 F per mm, derived from its "
                    "table, at the 8.5 t GAWR: F = 41.7 kN per spring) and aux 'Linear: 8500 N-m/deg' (title)",
                ),
            ),
            _RC_HEAVY,
            _NO_LASH,
            Sourced(1.0, "m", _ts("8.5t Air", "Suspensions/Compliance_SA/CmpSA_ff5425ec...par", "L_SPRINGS 1000")),
            Sourced(
                679.0, "kg", _ts("8.5t Drive, Dual Wheels", "Suspensions/Kin_Solid/KinSA_372fbdd1...par", "M_US 679")
            ),
            Sourced(
                0.53, "m", _ts("8.5t Drive, Dual Wheels", "Suspensions/Kin_Solid/KinSA_372fbdd1...par", "H_WC 530")
            ),
            Sourced(
                8500.0,
                "kg",
                _ts(
                    "8.5t Air",
                    "Suspensions/Compliance_SA/CmpSA_ff5425ec...par",
                    "'appropriate for 8.5 tonne (18,500 lb) GAWR axle'",
                ),
            ),
        ),
        RollSuspension(
            "trucksim-air-high-roll-10t",
            "Air suspension with high roll stiffness, 10 t axle (TruckSim '10t Air', auxiliary roll 8500 N m/deg)",
            "air, high roll stiffness",
            Sourced(
                _air_roll(10000, 8500),
                "kN m/rad",
                _ts(
                    "10t Air: +60 mm, -60 mm Travel",
                    "Suspensions/Compliance_SA/CmpSA_fb97cc4b...par",
                    "air springs 1000 mm apart (k = 0.004 F per mm at the 10 t GAWR: F = 49.1 kN per spring) and aux "
                    "'Linear: 8500 N-m/deg' (title)",
                ),
            ),
            _RC_HEAVY,
            _NO_LASH,
            Sourced(1.0, "m", _ts("10t Air", "Suspensions/Compliance_SA/CmpSA_fb97cc4b...par", "L_SPRINGS 1000")),
            Sourced(769.0, "kg", _ts("10t Drive, Dual Wheels", "Suspensions/Kin_Solid/...par", "M_US 769")),
            Sourced(0.53, "m", _ts("10t Drive, Dual Wheels", "Suspensions/Kin_Solid/...par", "H_WC 530")),
            Sourced(10000.0, "kg", _ts("10t Air", "Suspensions/Compliance_SA/CmpSA_fb97cc4b...par", "10 t GAWR")),
        ),
        RollSuspension(
            "trucksim-air-low-roll-6t",
            "Air suspension with low roll stiffness, 6 t axle (TruckSim '6t Air', auxiliary roll 3000 N m/deg)",
            "air, low roll stiffness",
            Sourced(
                _air_roll(6000, 3000),
                "kN m/rad",
                _ts(
                    "6t Air",
                    "Suspensions/Compliance_SA/CmpSA_d15f1e92...par",
                    "air springs 1000 mm apart (k = 0.004 F per mm at the 6 t GAWR: F = 29.4 kN per spring) and aux "
                    "'Linear: 3000 N-m/deg'",
                ),
            ),
            _RC_HEAVY,
            _NO_LASH,
            Sourced(1.0, "m", _ts("6t Air", "Suspensions/Compliance_SA/CmpSA_d15f1e92...par", "L_SPRINGS 1000")),
            Sourced(
                445.0,
                "kg",
                _ts(
                    "15.5t Trailer, Dual Wheels - Kinematics",
                    _TRAILER_KIN,
                    "M_US 445 (a trailer axle stands in: the 6t axle's kinematics give none)",
                ),
            ),
            Sourced(0.53, "m", _ts("15.5t Trailer, Dual Wheels - Kinematics", _TRAILER_KIN, "H_WC 530")),
            Sourced(6000.0, "kg", _ts("6t Air", "Suspensions/Compliance_SA/CmpSA_d15f1e92...par", "6 t GAWR")),
        ),
        RollSuspension(
            "factbook-steer-leaf-5.5t",
            "Steel leaf steer axle, 5.5 t, with the UMTRI Factbook's tractor front springs "
            "(TruckSim '5.5t Leaf, Steer: Compliance')",
            "steel leaf, steer",
            Sourced(
                _roll(580, 813, 1500 * _IN_LB),
                "kN m/rad",
                _ts(
                    "5.5t Leaf, Steer: Compliance",
                    "Suspensions/Compliance_SA/CmpSA_290679cc...par (commit a7fa703ae736)",
                    "FS_COMP_COEFFICIENT 580 N/mm per side (Coulomb friction 1334 N), L_SPRINGS 813 mm; its notes "
                    "cite the UMTRI Factbook (UMTRI-86-12) p. 189 'Springs used on tractor front suspensions' and "
                    "p. 200 'Spring Spread = 32 in, Auxiliary Roll Stiffness = 1500 in-lb/deg' (the dataset links "
                    "'Linear: 170 N-m/deg'); derived 580 x 0.813^2/2 + 1500 in-lb/deg (169.5 N m/deg)",
                ),
            ),
            _RC_STEER,
            _NO_LASH,
            Sourced(
                0.813,
                "m",
                _ts(
                    "5.5t Leaf, Steer: Compliance",
                    "Suspensions/Compliance_SA/CmpSA_290679cc...par",
                    "L_SPRINGS 813 (the Factbook's spring spread, 32 in, p. 200, as its notes cite)",
                ),
            ),
            Sourced(
                362.0,
                "kg",
                _ts("5.5t Steer, Single Wheel - Kinematics", _STEER_KIN, "M_US 362 (the library's steer axle)"),
            ),
            Sourced(0.51, "m", _ts("5.5t Steer, Single Wheel - Kinematics", _STEER_KIN, "H_CG_AXLE 510")),
            Sourced(
                5500.0,
                "kg",
                _ts(
                    "5.5t Leaf, Steer: Compliance",
                    "Suspensions/Compliance_SA/CmpSA_290679cc...par",
                    "5.5 t (its title)",
                ),
            ),
        ),
        RollSuspension(
            "factbook-trailer-tandem-leaf-8t",
            "Steel multi-leaf trailer tandem, 8 t per axle, with the UMTRI Factbook's trailer tandem springs "
            "(TruckSim '8t Leaf, Trailer: Compliance')",
            "steel multi-leaf, trailer tandem",
            Sourced(
                _leaf_table_roll(_FACTBOOK_TANDEM_SPRING, 8000, 965, 1000 * _IN_LB),
                "kN m/rad",
                _ts(
                    "8t Leaf, Trailer: Compliance",
                    "Suspensions/Compliance_SA/CmpSA_6f4c3dbc...par (commit a7fa703ae736), its spring 'Tandem Axle "
                    "Trailer, 8t / 17.6 kip' Suspensions/Springs/Spring_b1276e96...par (commit d36b1db6074)",
                    "its notes cite the UMTRI Factbook (UMTRI-86-12) p. 193 'Springs used on trailer tandem axle "
                    "rear suspension' (the spring's table) and p. 199 'Spring spread = 38 in, Auxiliary Roll "
                    "Stiffness = 1000 in-lb/deg' (the dataset links 'Linear: 150 N-m/deg'); L_SPRINGS 965 mm; "
                    "derived: the rate at the 8 t GAWR (39.2 kN per spring) is the slope of the mid-line of the "
                    "table's loading and unloading branches, (52539.8 + 45036 - 32523.8 - 25020) / 2 / 12.7 = "
                    "1576.1 N/mm, then 1576.1 x 0.965^2/2 + 1000 in-lb/deg (113.0 N m/deg)",
                ),
            ),
            _RC_HEAVY,
            _NO_LASH,
            Sourced(
                0.965,
                "m",
                _ts(
                    "8t Leaf, Trailer: Compliance",
                    "Suspensions/Compliance_SA/CmpSA_6f4c3dbc...par",
                    "L_SPRINGS 965 (the Factbook's 38 in, p. 199, as its notes cite)",
                ),
            ),
            *_BORROWED_TRAILER_AXLE,
            Sourced(
                8000.0,
                "kg",
                _ts(
                    "8t Leaf, Trailer: Compliance",
                    "Suspensions/Compliance_SA/CmpSA_6f4c3dbc...par",
                    "8 t per axle (its title; the spring's '8t / 17.6 kip')",
                ),
            ),
        ),
        RollSuspension(
            "factbook-trailer-single-leaf-6.8t",
            "Steel multi-leaf single trailer or dolly axle, 6.8 t, with the UMTRI Factbook's single-axle trailer "
            "springs (TruckSim '6.8t Leaf')",
            "steel multi-leaf, single trailer or dolly axle",
            Sourced(
                _leaf_table_roll(_FACTBOOK_SINGLE_SPRING, 6800, 965, 1500),
                "kN m/rad",
                _ts(
                    "6.8t Leaf: +100 mm, -60 mm Travel",
                    "Suspensions/Compliance_SA/CmpSA_0df2c525...par (commit d36b1db6074), its spring 'Single Axle "
                    "Trailer, 6.8t / 15 kip' Suspensions/Springs/Spring_10789ed3...par (commit a7fa703ae736)",
                    "its notes cite the UMTRI Factbook (UMTRI-86-12) p. 192 'Springs used on single axle trailer "
                    "and dolly suspensions' and p. 196 'Spring Spread = 38 in'; L_SPRINGS 965 mm; aux 'Linear: 1500 "
                    "N-m/deg' (title of the linked file); derived: the rate at the 6.8 t GAWR (33.4 kN per spring) is "
                    "the slope of the mid-line of the table's branches, (58268.8 + 50040 - 36140 - 27800) / 2 / 12.7 "
                    "= 1746.8 N/mm, then 1746.8 x 0.965^2/2 + 1500 N m/deg",
                ),
            ),
            _RC_HEAVY,
            _NO_LASH,
            Sourced(
                0.965,
                "m",
                _ts(
                    "6.8t Leaf",
                    "Suspensions/Compliance_SA/CmpSA_0df2c525...par",
                    "L_SPRINGS 965 (the Factbook's 38 in, p. 196, as its notes cite)",
                ),
            ),
            *_BORROWED_TRAILER_AXLE,
            Sourced(
                6800.0,
                "kg",
                _ts(
                    "6.8t Leaf",
                    "Suspensions/Compliance_SA/CmpSA_0df2c525...par",
                    "6.8 t (its title; the spring's '6.8t / 15 kip')",
                ),
            ),
        ),
    )
}

#: looked for and not found, so not in the library: what was searched
NOT_FOUND_IN_ROLL: dict[str, str] = {
    "walking-beam, trunnion / bogie and four-spring tandems": (
        "no TruckSim dataset of these types is in either copy of the database found (github.com/Steve-Krug/Axicle "
        "04-Trucksim/, all 23 solid-axle compliance datasets read, and its springs, auxiliary roll moments and "
        "kinematics; github.com/LiAngHNU/CYBRIX utils/resources/custom_TruckSim_dataset_2020.1/, two suspension "
        "files, copies of Axicle's); the UMTRI Factbook (UMTRI-86-12), Winkler, Bogard and Karamihas (SAE 922426) "
        "and Fu and Cebon (2002, 61 measured suspensions in eight categories; its Scribd copies show the first "
        "page) tabulate them, but only their title pages or abstracts could be read; the per-axle roll values of "
        "github.com/TomLousberg/LHVTool2016a (Files/custom_model/Tractor_initialize.m) carry no source, and Project "
        "Chrono's military MTV walking beam (data/vehicle/mtv/) names only the M1078 operator's manual for its data, "
        "its spring curve no source of its own; the library's Factbook trailer tandem is a leaf tandem whose "
        "dataset does not say whether it is four-spring"
    ),
    "suspension lash (any type)": (
        "TruckSim models none; the UMTRI reports that give it (Ervin 1986, UMTRI-86-35, UMTRI-99-19; Ervin's IJVD "
        "7(5-6) abstract names 'spring lash properties at the various axle positions' without values) and the "
        "TERNZ tilt-table report (2001) could be read only to their first pages"
    ),
    "TERNZ / NZTA generic air (low and high roll stiffness) and generic steel values": (
        "the calculator's help pages (ternz.co.nz/SRT_Calculator/mainhelp.html, "
        "mrwebapps.mainroads.wa.gov.au/srtcalculator/mainhelp.html) name the types 'Generic Air - low roll "
        "stiffness', 'Generic Air - high roll stiffness', 'Generic Steel' and 'User Defined' but its values are "
        "inside the calculator; its user guides (Main Roads WA, Tasmania DIER 2006) and Main Roads WA / ARRB's "
        "re-implementation (ravrat.au/srt, ravrat.au/srt-help, 'based on the TERNZ Static Rollover Threshold "
        "Calculator v3.01wa') could be read only to their introductions; the library's two air suspensions are "
        "TruckSim's, of low and high auxiliary roll stiffness"
    ),
    "manufacturer roll stiffness (Hendrickson, Reyco, SAF-Holland, BPW)": (
        "the brochures found (Hendrickson L761 'Understanding Trailer Air Suspensions', L578, T15001; BPW and SAF "
        "catalogues and design manuals) name roll stability but state no roll stiffness in what could be read; the "
        "trailer-axle catalogues that give numbers (SAF 'Design Handbook SAF MODUL' 11a/2003; Vector Gigant's "
        "'Permissible Centres of Gravity Height for Air Suspensions', p. 51, at '0,4g transverse acceleration' and "
        "'about 3º inclination of body') tabulate permitted CG heights, not a roll stiffness, and name no roll "
        "centre in what could be read"
    ),
}


# ------------------------------------------------------------------------------------------------ tyres


@dataclass(frozen=True)
class RollTyre:
    """A tyre for the roll model: vertical rate, free radius and the static loaded radius at its rated load."""

    id: str
    title: str
    sizes: tuple[str, ...]
    stiffness_kn_per_m: Sourced
    free_radius_m: Sourced
    rated_load_kg: Sourced

    @property
    def loaded_radius_m(self) -> float:
        """Static loaded radius at the rated load, r = R0 - Fz/Cz [m] (the linear vertical model of the data)."""
        return self.free_radius_m.value - self.rated_load_kg.value * G / 1000.0 / self.stiffness_kn_per_m.value


def _tyre(tid, title, sizes, cz, r0, rated, dataset, path, what):
    src = _ts(dataset, path, what)
    return RollTyre(
        tid,
        title,
        sizes,
        Sourced(cz, "kN/m", f"{src}: FZ_TIRE_COEFFICIENT {cz:g} N/mm"),
        Sourced(r0, "m", f"{src}: R0 {r0 * 1000:g} mm"),
        Sourced(rated, "kg", f"{src}: {what}"),
    )


TYRES_BY_SIZE: dict[str, RollTyre] = {
    t.id: t
    for t in (
        _tyre("sae-steer-295-75r22.5", "295/75R22.5 | 275/80R22.5 steer tyre, measured (SAE / UMTRI)",
              ("295/75R22.5", "275/80R22.5"), 985.0, 0.519, 2800.0, "Steer Tire, Symmetric",
              "Tires/Tire/Tire_a8a17c13...par",
              "SAE Cooperative Research program, measured by UMTRI; 'The Steer Tire is of the size "
              "295/75|275/80R22.5'; category 'SAE Steer Tire 2800 kg'"),
        _tyre("sae-widebase-425-65r22.5", "425/65R22.5 wide-base single, measured (SAE / UMTRI)", ("425/65R22.5",),
              1988.0, 0.562, 4750.0, "Widebase, Symmetric", "Tires/Tire/Tire_a3f0e562...par",
              "SAE Cooperative Research program, measured by UMTRI; 'The Widebase Tire is of the size 425/65R22.5'; "
              "category 'SAE Widebase, 4750 kg'"),
        _tyre("trucksim-3000kg", "Radial truck tyre of 3000 kg rating (305/75R22.5, 11.00R22, 12R24.5 class)",
              ("305/75R22.5", "11.00R22", "12R24.5", "11R22.5", "11R24.5", "12R22.5", "315/80R22.5", "295/80R22.5"),
              980.0, 0.520, 3000.0, "510 mm Radius (Trailer)", "Tires/Tire/Tire_cc56c1f1...par",
              "'typical for a radial tire with a nominal load rating of 3000 kg, such as a 305/75R22.5, 11.00R22 or a "
              "12R24.5'; 11R22.5, 11R24.5, 12R22.5, 315/80R22.5 and 295/80R22.5 are placed in this class "
              "by their load range and size (assumed: the dataset names only the first three; 295/80R22.5's "
              "nominal free radius, 0.2858 + 0.295 x 0.80 = 0.522 m, is the class's 0.520 m)"),
        _tyre("trucksim-3500kg", "Radial truck tyre of 3500 kg rating (385/65R22.5, 15R19.5, 12.00R24 class)",
              ("385/65R22.5", "15R19.5", "12.00R24"), 1350.0, 0.538, 3500.0, "528 mm Radius (Drive)",
              "Tires/Tire/Tire_2be17cb3...par", "'typical for a radial tire with a nominal load rating of 3500 kg, "
              "such as a 385/65R22.5, 15R19.5 or a 12.00R24'"),
        _tyre("trucksim-2000kg", "Radial truck tyre of 2000 kg rating (295/60R22.5, 265/70R19.5, 305/70R19.5, 10R22.5)",
              ("295/60R22.5", "265/70R19.5", "305/70R19.5", "10R22.5"), 750.0, 0.435, 2000.0, "425 mm Radius (Steer)",
              "Tires/Tire/Tire_4dea65ca...par", "'typical for a radial tire with a nominal load rating of 2000 kg, "
              "such as a 295/60R22.5 (463 mm), 265/70R19.5 (433), 305/70R19.5 (462), 10R22.5 (510)'"),
    )
}  # fmt: skip

_SIZE = re.compile(r"\s+")


def roll_tyre_for_size(designation: str, *, field: str = "tyre.size") -> RollTyre:
    """The library tyre of a size designation (``"295/80R22.5"``, ``"11R22.5"``): a measured tyre of that size, else
    the TruckSim load-rating class that names it; :class:`InvalidVehicle` listing the known sizes otherwise."""
    parse_tyre_size(designation, field=field)  # a well-formed designation first
    key = _SIZE.sub("", designation).upper()
    for t in TYRES_BY_SIZE.values():
        if key in (s.upper() for s in t.sizes):
            return t
    known = sorted({s for t in TYRES_BY_SIZE.values() for s in t.sizes})
    raise InvalidVehicle(
        f"{field}: no sourced data for the size {designation!r}; sizes with data: {', '.join(known)} (or give "
        "stiffness_kn_per_m and loaded_radius_m explicitly)",
        field=field,
        value=designation,
    )


# ------------------------------------------------------------------------------------------ fifth wheels


@dataclass(frozen=True)
class FifthWheel:
    id: str
    title: str
    roll_stiffness_knm_per_rad: Sourced
    lash_deg: Sourced


FIFTH_WHEELS: dict[str, FifthWheel] = {
    f.id: f
    for f in (
        FifthWheel(
            "trucksim-fifth-wheel",
            "Fifth wheel, 100 kN m/deg with 1 deg of lash each way (TruckSim default)",
            Sourced(100_000 * _NM_PER_DEG, "kN m/rad", _ts("Hitch: Roll Moment - 100 kN-m/deg (1 deg lash)",
                    "Hitches/Mx/HchMx_f7f9a25f...par", "its notes: 'a linear stiffness of the hitch of 100,000 "
                    "N-m/deg'")),
            Sourced(1.0, "deg", _ts("Hitch: Roll Moment - 100 kN-m/deg (1 deg lash)", "Hitches/Mx/HchMx_f7f9a25f...par",
                    "its notes: linear to +-0.5 deg, a constant +-50 kN m ('the trailer lifts off of the hitch "
                    "turntable') to +-1.5 deg, then 100 kN m/deg again: beyond 1.5 deg the moment is 100 kN m/deg x "
                    "(roll - 1 deg), a dead zone of 1 deg each way (the table itself was edited out of the copy)")),
        ),
        FifthWheel(
            "trucksim-turntable",
            "Turntable without lash, 500 kN m/deg (TruckSim)",
            Sourced(500_000 * _NM_PER_DEG, "kN m/rad", _ts("Hitch: Roll Moment - 500 kN-m/deg (0 deg lash)",
                    "Hitches/Mx/HchMx_96f8431a...par", "MX_HITCH_COEFFICIENT 500000")),
            Sourced(0.0, "deg", _ts("Hitch: Roll Moment - 500 kN-m/deg (0 deg lash)", "Hitches/Mx/HchMx_96f8431a...par",
                                    "0 deg lash")),
        ),
    )
}  # fmt: skip


def get_roll_suspension(sid: str, *, field: str = "suspension.type") -> RollSuspension:
    try:
        return SUSPENSIONS_IN_ROLL[sid]
    except (KeyError, TypeError):
        raise InvalidVehicle(
            f"unknown suspension type {sid!r}; known: {', '.join(SUSPENSIONS_IN_ROLL)} (or give "
            "roll_stiffness_knm_per_rad and roll_centre_height_m explicitly)",
            field=field,
            value=sid,
        ) from None


def get_fifth_wheel(fid: str, *, field: str = "coupling.type") -> FifthWheel:
    try:
        return FIFTH_WHEELS[fid]
    except (KeyError, TypeError):
        raise InvalidVehicle(
            f"unknown fifth wheel {fid!r}; known: {', '.join(FIFTH_WHEELS)} (or give roll_stiffness_knm_per_rad "
            "and lash_deg explicitly)",
            field=field,
            value=fid,
        ) from None

"""Tyre and suspension library: the component values the vehicle builder can look up, each with its source.

Every value is a :class:`Sourced` number: the value, its unit and where it comes from (document, edition or
year, table or page). A value without a published source says ``"assumed: <why>"``; nothing here is
invented. What the library holds is what could be traced to a readable source; what was looked for and not
found is listed in :data:`NOT_FOUND` (and in ``docs/vehicles.md``) rather than filled with a guess.

Tyre size designations
----------------------
A truck tyre's designation carries its nominal section width and rim diameter: ``11R22.5`` (width in inches,
radial, rim in inches), ``295/80R22.5`` (width in mm, aspect ratio in %, radial, rim in inches), ``9.00R20``
[1]_. :func:`parse_tyre_size` reads those numbers; they bound the tyre geometrically (the loaded radius lies
above the rim radius and, for a metric size, below the nominal unloaded radius; the dual pair is at least two
section widths wide). The designation does **not** give the loaded radius or the vertical stiffness: those
are measured properties of a particular tyre [2]_, and only the entries of :data:`TYRES` carry them.

Loaded radius from a tyre property file
---------------------------------------
A Magic-Formula tyre property file (``.tir``) gives the free radius R0, the linear radial stiffness Cz and the
nominal wheel load Fz0 of a measured tyre; its vertical force is Fz = Cz (R0 - r) [4]_, so the static loaded
radius at Fz0 is r = R0 - Fz0 / Cz (:func:`static_loaded_radius_m`). That is the axle height above the road, the
quantity the thesis calls "the dynamic rolling radius or loaded radius lr" and takes from Michelin's data book
[3]_. The file's effective rolling radius (BREFF, DREFF, FREFF) is a kinematic radius, not a height; it is not
used.

Rated load by load index
------------------------
A truck tyre's sidewall carries its load indices, ``152/148`` (single fitment / dual fitment) or ``160`` (single
only). :data:`LOAD_INDEX_KG` is the ISO 4000-1 / ETRTO load-index table over the truck and bus range LI 140-168
[5]_; :func:`rated_load_from_load_index_kg` gives the load one tyre may carry in its fitment (2 tyres per axle:
the single index; 4: the dual index). The index of a given size is not fixed (one size is sold with several), so
the library keeps no rated load per size: the builder takes the marking read from the tyre.

Suspension roll stiffness
-------------------------
The model's leaf spring is one spring per side with the rate kLs per axle and side; two springs at +-b/2 give
the roll stiffness per axle k_theta = kLs b^2 / 2 (Eq. 2.11). A published roll stiffness per axle maps back
with :func:`spring_rate_from_roll_stiffness`.

References
----------
.. [1] Michelin North America, *Truck Tire Service Manual*, "Determining Michelin tire size", p. 10
   (read.dmtmag.com/i/34501/10): sizes are designated by the nominal section width in inches or millimetres
   and the rim diameter (11R22.5, 275/80R22.5); aspect ratio = section height / section width.
.. [2] Tyres4U, "Tyre Tip 5 - Dimensions & Loads" (tyres4u.com.au): loads and nominal dimensions are
   standardised (T&RAA, TRA, ETRTO) but the static loaded radius and spring rate are particular to each
   manufacturer's tyre.
.. [3] Moreno, G. G., *Static rollover threshold of long combination vehicles* (doctoral thesis), Tables 15,
   16, 22, 23 and Sec. 9 (citing Harwood et al., 2003, *NCHRP Report 505: Review of Truck Characteristics
   as Factors in Roadway Design*, for kLs and kT, and MICHELIN, 2013, for the loaded radius).
.. [4] Goodyear, MF-Tyre 5.0 property file ``335_65R22_5_G275MSA_95psi.tir`` (Calspan test, 10 June 2010), as
   distributed with Project Chrono (github.com/projectchrono/chrono, ``data/vehicle/feda/tires/``); Chrono's
   ``FEDA_Pac02Tire::GetNormalStiffnessForce`` evaluates the same file's vertical force as depth x Cz.
.. [5] ISO 4000-1 / ETRTO load-index table, as reproduced by Pirelli, "Tyre load index & chart" (pirelli.com,
   LI 75-150) and in Project Chrono's ``ChTMeasyTire::GetTireMaxLoad`` (LI 0-279); cells cross-checked in
   ``tests/engine/test_components.py``.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from engine.errors import InvalidVehicle

INCH_M = 0.0254  # exact, by definition of the inch

THESIS = "Moreno, G. G., Static rollover threshold of long combination vehicles (doctoral thesis)"
_T16 = f"{THESIS}, Table 16 (B-train trailer)"
_T15 = f"{THESIS}, Table 15 (TruckSim semi-trailer, Ch. 8)"


@dataclass(frozen=True)
class Sourced:
    """A library value with its unit and source (or ``"assumed: why"``)."""

    value: float
    unit: str
    source: str


def static_loaded_radius_m(unloaded_radius_m: float, load_kn: float, stiffness_kn_per_m: float) -> float:
    """Static loaded radius of a tyre with a linear radial stiffness, r = R0 - Fz / Cz [m].

    Parameters
    ----------
    unloaded_radius_m : R0, free radius of the inflated, unloaded tyre [m]
    load_kn : Fz, vertical load on the tyre [kN]
    stiffness_kn_per_m : Cz, radial (vertical) stiffness of the tyre [kN/m]

    References
    ----------
    The vertical force of an MF-Tyre property file, Fz = Cz (R0 - r) (Chrono ``FEDA_Pac02Tire``: depth x Cz).
    """
    return unloaded_radius_m - load_kn / stiffness_kn_per_m  # Fz = Cz (R0 - r) solved for r


# ------------------------------------------------------------------------------------------- tyres


@dataclass(frozen=True)
class TyreEntry:
    """A tyre the library describes: loaded radius and vertical stiffness per tyre, each with its source.

    ``size`` is the size designation when the source names it (None when it does not).
    """

    id: str
    title: str
    size: str | None
    loaded_radius_m: Sourced
    stiffness_kn_per_m: Sourced
    rated_load_kg: Sourced | None = None


_GOODYEAR = (
    "Goodyear MF-Tyre 5.0 property file 335_65R22_5_G275MSA_95psi.tir (Goodyear 335/65R22.5 G275 MSA, "
    "construction '0L5001', INFLATION_PRESSURE 6.5 bar, TEST_DEVICE 'CALSPAN', DATESTAMP '10-JUN-2010', "
    "GENERATED_BY A305512), as distributed with Project Chrono (github.com/projectchrono/chrono, "
    "data/vehicle/feda/tires/; the same numbers in src/chrono_models/vehicle/feda/FEDA_Pac02Tire.cpp, "
    "SetParametersLevel4)"
)
#: the file's [DIMENSION] UNLOADED_RADIUS [m], [VERTICAL] VERTICAL_STIFFNESS [kN/m] and FNOMIN [kN]
_GOODYEAR_R0_M, _GOODYEAR_CZ_KN_PER_M, _GOODYEAR_FZ0_KN = 0.4990, 848.55, 29.912

TYRES: dict[str, TyreEntry] = {
    entry.id: entry
    for entry in (
        TyreEntry(
            id="thesis-michelin-xza",
            title="Michelin XZA radial truck tyre as used by the thesis (Tables 16, 22, 23)",
            size=None,  # the thesis names the tyre (Michelin XZA) but not its size
            loaded_radius_m=Sourced(
                0.499,
                "m",
                f"{_T16}: 'initial dynamic rolling radius lr (MICHELIN, 2013) 0.499 m' for Michelin XZA radial "
                "tyres (Ch. 9). The thesis's reference list is not in the available text; Michelin's Truck Tire "
                "Data Book of April 2013 (16th ed.) lists the XZA on p. 41. The thesis does not say which size",
            ),
            stiffness_kn_per_m=Sourced(
                840.0,
                "kN/m",
                f"{_T16}: 'vertical stiffness per tire kT (HARWOOD et al., 2003) 840 kN/m' (Harwood et al., "
                "2003, NCHRP Report 505)",
            ),
        ),
        TyreEntry(
            id="thesis-trucksim-semitrailer",
            title="Tyre of the TruckSim semi-trailer of the thesis's Ch. 8 (Table 15)",
            size=None,
            loaded_radius_m=Sourced(0.51, "m", f"{_T15}: 'initial dynamic rolling radius lr 0.51 m'"),
            stiffness_kn_per_m=Sourced(980.0, "kN/m", f"{_T15}: 'vertical stiffness per tire kT 980 kN/m'"),
        ),
        TyreEntry(
            id="goodyear-g275msa-335-65r22.5-6.5bar",
            title="Goodyear G275 MSA 335/65R22.5 at 6.5 bar (95 psi), measured at Calspan (Goodyear MF-Tyre file)",
            size="335/65R22.5",  # the file's WIDTH 0.3350 m, ASPECT_RATIO 0.6500, RIM_RADIUS 0.2858 m
            loaded_radius_m=Sourced(
                static_loaded_radius_m(_GOODYEAR_R0_M, _GOODYEAR_FZ0_KN, _GOODYEAR_CZ_KN_PER_M),
                "m",
                f"{_GOODYEAR}: static loaded radius at the file's nominal wheel load, converted: r = UNLOADED_RADIUS - "
                "FNOMIN / VERTICAL_STIFFNESS = 0.4990 m - 29 912 N / 848 550 N/m = 0.4637 m (the file's linear "
                "vertical model). This is the axle height, the quantity the thesis takes as lr; the file's effective "
                "rolling radius (BREFF, DREFF) is a kinematic radius and is not used. At another load the "
                "radius differs by the load change / Cz",
            ),
            stiffness_kn_per_m=Sourced(
                _GOODYEAR_CZ_KN_PER_M,
                "kN/m",
                f"{_GOODYEAR}: [VERTICAL] VERTICAL_STIFFNESS = 8.4855e+005 N/m, the radial stiffness of one "
                "tyre at 6.5 bar (FEDA_Pac02Tire.cpp's 40, 60 and 70 psi levels of the same tyre: 406.5, 565.2 and "
                "644.5 kN/m)",
            ),
        ),
    )
}


@dataclass(frozen=True)
class TyreSize:
    """Numbers read from a size designation (nominal, unloaded)."""

    designation: str
    section_width_m: float
    rim_diameter_m: float
    aspect_ratio: float | None  # section height / section width; None when the designation omits it

    @property
    def rim_radius_m(self) -> float:
        """Radius of the rim seat [m]: the loaded radius must exceed it."""
        return self.rim_diameter_m / 2.0

    @property
    def nominal_free_radius_m(self) -> float | None:
        """Nominal unloaded radius rim/2 + width x aspect ratio [m]; None without an aspect ratio."""
        if self.aspect_ratio is None:
            return None
        return self.rim_diameter_m / 2.0 + self.section_width_m * self.aspect_ratio


_METRIC = re.compile(r"^\s*(\d{3})\s*/\s*(\d{2})\s*R\s*(\d{2}(?:\.5)?)\s*$", re.IGNORECASE)
_INCH = re.compile(r"^\s*(\d{1,2}(?:\.\d{1,2})?)\s*R\s*(\d{2}(?:\.5)?)\s*$", re.IGNORECASE)


def parse_tyre_size(designation: str, *, field: str = "size") -> TyreSize:
    """Nominal section width, rim diameter and aspect ratio of a radial truck-tyre size designation.

    Parameters
    ----------
    designation : ``"295/80R22.5"`` (width [mm] / aspect ratio [%] R rim [in]) or ``"11R22.5"``,
        ``"9.00R20"`` (width [in] R rim [in]) [-]
    field : the dotted input path named in the error [-]

    Returns
    -------
    TyreSize with the section width [m], rim diameter [m] and aspect ratio [-] (None for inch sizes).

    Raises
    ------
    InvalidVehicle : the designation is in neither form.

    References
    ----------
    Michelin, *Truck Tire Service Manual*, p. 10 (the designation convention).
    """
    text = designation if isinstance(designation, str) else ""
    m = _METRIC.match(text)
    if m:
        width_mm, aspect, rim_in = (float(g) for g in m.groups())
        return TyreSize(text.strip(), width_mm / 1000.0, rim_in * INCH_M, aspect / 100.0)
    m = _INCH.match(text)
    if m:
        width_in, rim_in = (float(g) for g in m.groups())
        return TyreSize(text.strip(), width_in * INCH_M, rim_in * INCH_M, None)
    raise InvalidVehicle(
        f"{field} {designation!r} is not a radial truck-tyre size: expected e.g. '295/80R22.5' "
        "(width mm / aspect % R rim in) or '11R22.5', '9.00R20' (width in R rim in)",
        field=field,
        value=designation,
    )


# ------------------------------------------------------------------------------------- load index

#: load one tyre may carry, by ISO 4000-1 / ETRTO load index, over the truck and bus range LI 140-168 [kg].
#: Transcribed from Project Chrono's ChTMeasyTire::GetTireMaxLoad table; cross-checked cell by cell where a second
#: source could be read: Pirelli's chart (LI 140-150), a McCormick tractor manual (142, 165, 168), Heuver
#: (150, 154, 164) and a commercial-tyre guide (148, 150, 152) -- see tests/engine/test_components.py. Below 140 the
#: two main sources disagree (LI 135: Chrono 2180 kg, Pirelli 2190 kg), so the table starts at 140.
# fmt: off
LOAD_INDEX_KG: dict[int, float] = {
    140: 2500.0, 141: 2575.0, 142: 2650.0, 143: 2725.0, 144: 2800.0, 145: 2900.0, 146: 3000.0, 147: 3075.0,
    148: 3150.0, 149: 3250.0, 150: 3350.0, 151: 3450.0, 152: 3550.0, 153: 3650.0, 154: 3750.0, 155: 3875.0,
    156: 4000.0, 157: 4125.0, 158: 4250.0, 159: 4375.0, 160: 4500.0, 161: 4625.0, 162: 4750.0, 163: 4875.0,
    164: 5000.0, 165: 5150.0, 166: 5300.0, 167: 5450.0, 168: 5600.0,
}
# fmt: on

_LOAD_INDEX = re.compile(r"^\s*(\d{2,3})\s*(?:/\s*(\d{2,3}))?\s*$")


def parse_load_index(marking: str | int, *, field: str = "load_index") -> tuple[int, int | None]:
    """Single- and dual-fitment load indices of a sidewall marking: ``"152/148"`` -> (152, 148), ``"160"`` ->
    (160, None).

    Parameters
    ----------
    marking : the load indices as moulded on the sidewall, single/dual or single only [-]
    field : the dotted input path named in the error [-]

    Raises
    ------
    InvalidVehicle : not of that form, an index outside :data:`LOAD_INDEX_KG`, or a dual index above the single one.
    """
    text = str(marking) if isinstance(marking, int | str) and not isinstance(marking, bool) else ""
    m = _LOAD_INDEX.match(text)
    if not m:
        raise InvalidVehicle(
            f"{field} {marking!r} is not a load-index marking: expected e.g. '152/148' (single/dual) or '160'",
            field=field,
            value=marking,
        )
    single, dual = int(m.group(1)), (int(m.group(2)) if m.group(2) else None)
    for index in (single, dual):
        if index is not None and index not in LOAD_INDEX_KG:
            raise InvalidVehicle(
                f"{field}: load index {index} is outside the table's truck range "
                f"{min(LOAD_INDEX_KG)}-{max(LOAD_INDEX_KG)}; give rated_load_kg instead",
                field=field,
                value=marking,
            )
    if dual is not None and dual > single:
        raise InvalidVehicle(
            f"{field} {marking!r}: the dual-fitment index {dual} is above the single-fitment index {single}; "
            "a tyre carries less in a dual pair, so the marking reads single/dual, e.g. '152/148'",
            field=field,
            value=marking,
        )
    return single, dual


def rated_load_from_load_index_kg(marking: str | int, tyres_per_axle: int, *, field: str = "load_index") -> float:
    """Load one tyre may carry in its fitment, from its load-index marking and the ISO table [kg].

    Parameters
    ----------
    marking : ``"152/148"`` (single/dual) or ``"160"`` (single fitment only) [-]
    tyres_per_axle : 2 (single tyres: the first index) or 4 (dual pairs: the second index) [-]
    field : the dotted input path named in the error [-]

    Raises
    ------
    InvalidVehicle : a bad marking (:func:`parse_load_index`), or dual fitment of a tyre marked for single only.

    References
    ----------
    ISO 4000-1 / ETRTO load-index table (:data:`LOAD_INDEX_KG`).
    """
    single, dual = parse_load_index(marking, field=field)
    if tyres_per_axle == 2:
        return LOAD_INDEX_KG[single]
    if dual is None:
        raise InvalidVehicle(
            f"{field} {marking!r} carries no dual-fitment index, but the group has {tyres_per_axle} tyres per axle "
            "(dual pairs); give the single/dual marking (e.g. '152/148') or rated_load_kg",
            field=field,
            value=marking,
        )
    return LOAD_INDEX_KG[dual]


# -------------------------------------------------------------------------------------- suspensions


@dataclass(frozen=True)
class SuspensionEntry:
    """A suspension the library describes, in the model's terms (per axle and side), with sources.

    stiffness_kn_per_m : kLs, vertical rate of the spring on one side of one axle [kN/m]
    height_m : ls, static suspension height at the rated load [m]
    spring_separation_m : b, lateral spacing of the two springs [m]
    """

    id: str
    title: str
    kind: str
    stiffness_kn_per_m: Sourced
    height_m: Sourced
    spring_separation_m: Sourced

    @property
    def roll_stiffness_knm_per_rad(self) -> float:
        """Roll stiffness per axle k_theta = kLs b^2 / 2 [kN m/rad] (Eq. 2.11)."""
        return roll_stiffness_from_spring_rate(self.stiffness_kn_per_m.value, self.spring_separation_m.value)


_T16_LS = Sourced(0.205, "m", f"{_T16}: 'initial suspension height ls 0.205 m'")
_T16_B = Sourced(0.95, "m", f"{_T16}: 'lateral separation between the springs b 0.95 m'")
_HARWOOD_RANGE = (
    f"{THESIS}, Ch. 9: 'Harwood et al. (2003) reported that the range of values for the stiffness of the "
    "suspension per axle is kLs = (1500-2400) kN/m'"
)
_RANGE_GEOMETRY = "; the range gives no height or spring spacing: Table 16's are used with it"

SUSPENSIONS: dict[str, SuspensionEntry] = {
    entry.id: entry
    for entry in (
        SuspensionEntry(
            id="thesis-steel-leaf",
            title="Steel leaf-spring tandem/tridem of the thesis (Tables 16, 22, 23)",
            kind="steel leaf spring",
            stiffness_kn_per_m=Sourced(
                1800.0,
                "kN/m",
                f"{_T16}: 'stiffness of the suspension per axle kLs (HARWOOD et al., 2003) 1800 kN/m'",
            ),
            height_m=_T16_LS,
            spring_separation_m=_T16_B,
        ),
        SuspensionEntry(
            id="thesis-trucksim-semitrailer",
            title="Suspension of the TruckSim semi-trailer of the thesis's Ch. 8 (Table 15)",
            kind="steel leaf spring",
            stiffness_kn_per_m=Sourced(2500.0, "kN/m", f"{_T15}: 'stiffness of the suspension per axle kLs 2500'"),
            height_m=Sourced(0.205, "m", f"{_T15}: 'initial suspension height ls 0.205 m'"),
            spring_separation_m=Sourced(0.95, "m", f"{_T15}: 'lateral separation between the springs b 0.95 m'"),
        ),
        SuspensionEntry(
            id="harwood-2003-soft",
            title="Softest per-axle suspension rate of the range Harwood et al. (2003) report",
            kind="truck suspension, range end (type not stated)",
            stiffness_kn_per_m=Sourced(1500.0, "kN/m", _HARWOOD_RANGE + " (lower end)"),
            height_m=Sourced(0.205, "m", _T16_LS.source + _RANGE_GEOMETRY),
            spring_separation_m=Sourced(0.95, "m", _T16_B.source + _RANGE_GEOMETRY),
        ),
        SuspensionEntry(
            id="harwood-2003-stiff",
            title="Stiffest per-axle suspension rate of the range Harwood et al. (2003) report",
            kind="truck suspension, range end (type not stated)",
            stiffness_kn_per_m=Sourced(2400.0, "kN/m", _HARWOOD_RANGE + " (upper end)"),
            height_m=Sourced(0.205, "m", _T16_LS.source + _RANGE_GEOMETRY),
            spring_separation_m=Sourced(0.95, "m", _T16_B.source + _RANGE_GEOMETRY),
        ),
    )
}

#: what was looked for and could not be read from a source (so it is not in the library): id -> why
NOT_FOUND: dict[str, str] = {
    (
        "loaded radius and vertical stiffness of 11R22.5, 295/80R22.5, 275/70R22.5, 385/65R22.5, 315/80R22.5, "
        "425/65R22.5, 445/65R22.5, 9.00R20, 10.00R20, 11.00R20, 12R22.5"
    ): (
        "the static loaded radius per size and load range is tabulated in the manufacturers' data books -- "
        "Michelin Truck Tire Data Book (9th ed.; 10th, Jan 2008; 12th, Jan 2010; 13th and 14th, Jan and Sep "
        "2011; 16th, Apr 2013), Michelin Truck and Bus Tyre Technical Databook (East Asia and Oceania, 2016), "
        "Firestone/Bridgestone Truck Tire Data Books (2009-2024), BFGoodrich, Continental and Semperit technical "
        "data books -- whose transcriptions on public document sites could be read only as far as their covers "
        "and contents; the size tables are further in. Vertical stiffness per size is in the UMTRI Factbook "
        "(Fancher, Ervin, Winkler, Gillespie, 1986, UMTRI-86-12, tyre section) and in Ervin et al. (1976, "
        "UM-HSRI-76-11-1, truck tyre data): title pages only. Not filled in with a guess"
    ),
    "315/80R22.5 'typical truck tire' (Pacejka book / Adams example property file)": (
        "two public copies of the same example file disagree on the vertical stiffness (784 944 N/m in "
        "pac2002_315_80R22_5.tir; 1 000 000 N/m in Project Chrono's CityBus_Pac02Tire.tir, which is marked "
        "'please check'), and the file calls itself an example for a typical tyre, not a named measured one; not "
        "used"
    ),
    "rated load per tyre size (ETRTO / TRA standard load index of each size)": (
        "one size is sold with several load indices (e.g. 295/80R22.5 152/148 and 154/149) and the ETRTO / TRA "
        "standards manuals could not be read; the library keeps the ISO load-index table (LOAD_INDEX_KG, LI "
        "140-168) and the builder takes the marking read from the tyre (tyre.load_index)"
    ),
    "load indices below 140": (
        "the two readable tables disagree at LI 135 (Chrono 2180 kg, Pirelli 2190 kg); the truck range 140-168 "
        "is cross-checked, the rest is left out"
    ),
    "generic air suspension, high and low roll stiffness; generic steel (TERNZ)": (
        "the TERNZ / NZTA SRT calculator and its Main Roads WA (v3.01wa) and RAVRAT web successors offer these "
        "types, but their values are inside the calculators; the help pages (ternz.co.nz, "
        "mrwebapps.mainroads.wa.gov.au), the MRWA user guide and the LTSA index page name the types without "
        "numbers"
    ),
    "parabolic / taper leaf, multi-leaf, walking beam, four-spring / trunnion, air (measured)": (
        "measured per-type vertical rates, roll stiffnesses and roll-centre heights are tabulated in the UMTRI "
        "Factbook (1986, suspension section), in Winkler, Bogard and Karamihas (1992), 'Roll-stability "
        "performance of heavy-vehicle suspensions', SAE 922426 (94 suspensions), and in Fu and Cebon (2002), "
        "'Analysis of a truck suspension database', Heavy Vehicle Systems 9(4) 281-297 (61 suspensions in 8 "
        "categories); of these only the title pages and abstracts could be read. Winkler and Ervin (1999, "
        "UMTRI-99-19), Sampson's thesis (Cambridge, 2000), the FHWA 2015 CTSW study's Appendix D and NCHRP "
        "Report 505's chapter 5 (NAP) were likewise readable only as far as their opening pages. Project "
        "Chrono's Kraz 64431 trailer leaf spring (710.6 kN/m per side) is an uncited 'work-a-like' and is not "
        "used"
    ),
    ("tare CG height by body type"): ("the UMTRI Factbook's mass-distribution section has it; not readable here"),
}


def roll_stiffness_from_spring_rate(stiffness_kn_per_m: float, spring_separation_m: float) -> float:
    """Roll stiffness per axle of two springs at +-b/2, k_theta = kLs b^2 / 2 [kN m/rad] (Eq. 2.11).

    Parameters
    ----------
    stiffness_kn_per_m : kLs, rate of the spring on one side of the axle [kN/m]
    spring_separation_m : b, lateral spacing of the two springs [m]
    """
    return stiffness_kn_per_m * spring_separation_m**2 / 2.0  # Eq. 2.11


def spring_rate_from_roll_stiffness(roll_stiffness_knm_per_rad: float, spring_separation_m: float) -> float:
    """The per-side spring rate kLs = 2 k_theta / b^2 that gives a roll stiffness per axle [kN/m] (Eq. 2.11).

    Parameters
    ----------
    roll_stiffness_knm_per_rad : k_theta, suspension roll stiffness of one axle [kN m/rad]
    spring_separation_m : b, lateral spacing of the two springs [m]
    """
    return 2.0 * roll_stiffness_knm_per_rad / spring_separation_m**2  # Eq. 2.11 solved for kLs


def get_tyre(tyre_id: str, *, field: str = "tyre.id") -> TyreEntry:
    """The library tyre ``tyre_id``; :class:`InvalidVehicle` naming ``field`` and the known ids otherwise."""
    try:
        return TYRES[tyre_id]
    except (KeyError, TypeError):
        raise InvalidVehicle(
            f"unknown tyre {tyre_id!r}; known tyres: {', '.join(sorted(TYRES))} (or give loaded_radius_m and "
            "stiffness_kn_per_m explicitly)",
            field=field,
            value=tyre_id,
        ) from None


def get_suspension(suspension_id: str, *, field: str = "suspension.type") -> SuspensionEntry:
    """The library suspension ``suspension_id``; :class:`InvalidVehicle` listing the known ids otherwise."""
    try:
        return SUSPENSIONS[suspension_id]
    except (KeyError, TypeError):
        raise InvalidVehicle(
            f"unknown suspension type {suspension_id!r}; known types: {', '.join(sorted(SUSPENSIONS))} (or give "
            "stiffness_kn_per_m or roll_stiffness_knm_per_rad, height_m and spring_separation_m explicitly)",
            field=field,
            value=suspension_id,
        ) from None


def library_sources() -> list[tuple[str, str, Sourced]]:
    """Every library value as (entry id, parameter, value with source), for listing and auditing."""
    out: list[tuple[str, str, Sourced]] = []
    for t in TYRES.values():
        for name in ("loaded_radius_m", "stiffness_kn_per_m", "rated_load_kg"):
            value = getattr(t, name)
            if value is not None:
                out.append((t.id, name, value))
    for s in SUSPENSIONS.values():
        for name in ("stiffness_kn_per_m", "height_m", "spring_separation_m"):
            out.append((s.id, name, getattr(s, name)))
    return out

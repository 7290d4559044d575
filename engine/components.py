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
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from .errors import InvalidVehicle

INCH_M = 0.0254  # exact, by definition of the inch

_THESIS = "Moreno, G. G., Static rollover threshold of long combination vehicles (doctoral thesis)"
_T16 = f"{_THESIS}, Table 16 (B-train trailer)"
_T15 = f"{_THESIS}, Table 15 (TruckSim semi-trailer, Ch. 8)"


@dataclass(frozen=True)
class Sourced:
    """A library value with its unit and source (or ``"assumed: why"``)."""

    value: float
    unit: str
    source: str


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
    f"{_THESIS}, Ch. 9: 'Harwood et al. (2003) reported that the range of values for the stiffness of the "
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
    "tyre sizes 11R22.5, 295/80R22.5, 275/70R22.5, 385/65R22.5, 425/65R22.5, 445/65R22.5, 9.00R20, 10.00R20, "
    "11.00R20, 12R22.5": "loaded radius and vertical stiffness per size are in the manufacturers' data books "
    "(Michelin Truck Tire Data Book 2013, Firestone/Bridgestone data books, Hankook technical manual) and in "
    "the UMTRI Factbook (Fancher et al., 1986, UMTRI-86-12, tyre section); only their title pages and "
    "contents could be read, not the tables",
    "generic air suspension, high and low roll stiffness; generic steel (TERNZ)": "the TERNZ / NZTA SRT "
    "calculator and its Main Roads WA / ARRB successor offer these types, but their values are inside the "
    "calculator; the help pages and user guides that could be read name the types without numbers",
    "parabolic / taper leaf, walking beam, four-spring, air (measured)": "measured per-type rates and roll "
    "stiffnesses are tabulated in the UMTRI Factbook (1986, suspension section) and in Fu & Cebon (2002), "
    "'Analysis of a truck suspension database', Heavy Vehicle Systems 9(4) 281-297 (61 suspensions in 8 "
    "categories); neither table could be read",
    "tare CG height by body type": "the UMTRI Factbook's mass-distribution section has it; not readable here",
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

"""Advisory speeds on horizontal curves: each method's speed, the speed shown on the plaque, the sign treatment and
the truck rollover warning (W1-13).

What was read and where is in docs/advisory.md; every criterion below names its source and whether it was verified in
a primary text. Nothing here imports the rest of the engine except :mod:`engine.errors` and
:mod:`engine.road.profile` (the truck's speed profile, for :func:`advise_alignment`).

Methods
-------
- ``design-method``: FHWA-SA-11-22 (2011) and TxDOT's *Procedures for Establishing Speed Zones* compute the advisory
  speed (TxDOT: "the average speed of free-flowing trucks") from the curve speed model of Bonneson, Pratt, Miles and
  Carlson (TxDOT 0-5439-P1, 2009). The model's equation could not be read here, so the method is reported as
  *unverified* and gives no speed (:data:`DESIGN_METHOD_NOTE`); no coefficient is typed from memory.
- ``txdot-direct``: TxDOT's Direct Method from a measured average speed of free-flowing passenger cars at mid-curve:
  times 0.97 for the average truck speed, plus 1.0 mph, rounded down to a multiple of 5 mph (TxDOT, *Procedures for
  Establishing Speed Zones*, "Direct Method", Step 2).
- legacy (each labelled ``legacy``): ball-bank criteria converted to side friction with a stated body-roll allowance
  (:func:`ball_bank_side_friction`), and TxDOT's older "calculated speed" (f = 0.15 / 0.18 / 0.31 by speed), which
  TxDOT says is not to be the sole basis of the posted speed.

The displayed speed is rounded with TxDOT's rule (+1 mph, down to 5 mph) in US units; in metric units it is rounded
down to a multiple of 10 km/h (assumed: no metric rule was read; down is the direction of TxDOT's rule).

References
----------
FHWA-SA-11-22, *Procedures for Setting Advisory Speeds on Curves*, June 2011. TxDOT, *Procedures for Establishing
Speed Zones*, Ch. 5 Sec. 2 "Curves and Turns" (Methods, Direct Method, Design Method, Calculated Speed). MUTCD 2003
Sec. 2C.46 (16 degrees, via TRB RNS project 15577); MUTCD 2009 Sec. 2C.08 Support (16/14/12 degrees, via FHWA's
summary of the 2009 revisions); Public Roads, "Analysis of advisory speed setting criteria" (14/12/10 degrees).
MUTCD 11th ed. (2023) Table 2C-4 (as transcribed; unverified).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache, partial

import numpy as np

from engine.errors import InvalidRoad
from engine.road import profile as prof

KMH_PER_MPH = 1.609344  # exact (international mile)
KMH2_PER_M_G = 127.0  # V^2 / (127 R) is the lateral acceleration in g for V in km/h, R in m (thesis Eq. 9.1)

#: the sign's increment by unit system: 5 mph (MUTCD: a multiple of 5 mph) or 10 km/h (the metric option)
SIGN_INCREMENTS = {"us": 5.0, "metric": 10.0}
UNITS = tuple(SIGN_INCREMENTS)

#: the speeds a posted or tangent speed may take [km/h] (the service's accepted range)
SPEED_RANGE_KMH = (10.0, 130.0)

#: TxDOT Direct Method, Step 2: average passenger-car speed x 0.97 = average truck speed
TXDOT_TRUCK_FACTOR = 0.97
#: TxDOT Direct Method, Step 2: add 1.0 mph, then round down to the nearest 5 mph
TXDOT_ROUNDING_ADD_MPH = 1.0

#: assumed passenger-car body roll per g of lateral acceleration [deg/g] (the ball-bank reads the lateral
#: acceleration plus the body's roll; no source for a value was read, so this one is stated and can be changed)
BODY_ROLL_DEG_PER_G = 5.0

#: the service's margin below the rollover speed for the W1-13 rule [km/h] (assumed: one metric plaque increment;
#: no manual's W1-13 criterion was found)
ROLLOVER_MARGIN_KMH = 10.0

#: TxDOT 0-5439 / FHWA-SA-11-22: GPS Method needs a deflection of 6 deg or more; "a curve with a smaller deflection
#: angle will rarely justify curve warning signs or an advisory speed plaque" (TxDOT, GPS Method)
MIN_DEFLECTION_DEG = 6.0

DESIGN_METHOD_NOTE = (
    "unverified: the Design Method's curve speed model (Bonneson, Pratt, Miles and Carlson, TxDOT 0-5439-P1, "
    "2009; FHWA-SA-11-22, 2011) could not be read in its primary text here, so no speed is computed from it"
)


@dataclass(frozen=True)
class SpeedBands:
    """A criterion that changes with speed: ``values[i]`` applies from ``edges_mph[i]`` (inclusive) up to
    ``edges_mph[i + 1]`` (exclusive); the last band is open."""

    id: str
    quantity: str  # "ball_bank_deg" or "side_friction"
    edges_mph: tuple[float, ...]
    values: tuple[float, ...]
    source: str
    verified: bool
    legacy: bool = True


#: 2003 MUTCD Sec. 2C.46: 16 degrees at every speed
BALL_BANK_2003 = SpeedBands(
    "ball-bank-16deg-2003",
    "ball_bank_deg",
    (0.0,),
    (16.0,),
    "MUTCD 2003 Sec. 2C.46 (16 deg ball-bank), as stated by TRB RNS project 15577; not read in the manual",
    False,
)
#: 2009 MUTCD Sec. 2C.08 Support: 16 deg at 20 mph or less, 14 deg at 25-30 mph, 12 deg at 35 mph and higher; the
#: gaps (20-25, 30-35 mph) are closed at 25 and 35 mph (this service's reading)
BALL_BANK_2009 = SpeedBands(
    "ball-bank-2009",
    "ball_bank_deg",
    (0.0, 25.0, 35.0),
    (16.0, 14.0, 12.0),
    "MUTCD 2009 Sec. 2C.08 Support (16/14/12 deg by speed), as summarised in FHWA's presentation of the 2009 "
    "revisions to Chapter 2C; not read in the manual",
    False,
)
#: the traditional criteria: 14 deg below 20 mph, 12 deg at 20-35 mph, 10 deg at 35 mph or more
BALL_BANK_TRADITIONAL = SpeedBands(
    "ball-bank-10-12-14deg",
    "ball_bank_deg",
    (0.0, 20.0, 35.0),
    (14.0, 12.0, 10.0),
    "Public Roads (FHWA), 'Analysis of advisory speed setting criteria': 14 deg below 20 mph, 12 deg at 20-35 mph, "
    "10 deg at 35 mph or more",
    True,
)
#: TxDOT's older calculated speed: f = 0.31 at 20 mph or less, 0.18 between 20 and 35 mph, 0.15 at 35 mph or more
TXDOT_CALCULATED = SpeedBands(
    "txdot-calculated-speed",
    "side_friction",
    (0.0, 20.0, 35.0),
    (0.31, 0.18, 0.15),
    "TxDOT, Procedures for Establishing Speed Zones, 'Calculated Speed' (f 0.31 / 0.18 / 0.15 by speed); TxDOT: "
    "'not to be used as the sole basis for selecting the posted speed'. The formula is an image not read here; its "
    "variables (V mph, R ft, e ft/ft, f) are those of the point-mass formula applied, V^2 = 15 R (e + f)",
    True,
)
LEGACY_CRITERIA = (BALL_BANK_2003, BALL_BANK_2009, BALL_BANK_TRADITIONAL, TXDOT_CALCULATED)

# -------------------------------------------------------------------------------------------------- treatment

#: MUTCD 11th ed. (2023) Table 2C-4, devices by the difference between the posted and the advisory speed [mph], as
#: transcribed (unverified against the manual): (lowest difference, devices)
TREATMENT_BANDS_MPH = (
    (5.0, ("advisory speed plaque (W13-1)", "pavement markings or an advance horizontal alignment warning sign")),
    (10.0, ("advisory speed plaque (W13-1)", "advance horizontal alignment warning sign")),
    (15.0, ("advisory speed plaque (W13-1)", "advance horizontal alignment warning sign", "delineators")),
    (20.0, ("advisory speed plaque (W13-1)", "advance horizontal alignment warning sign", "chevron alignment signs")),
)
TREATMENTS = ((), *(devices for _, devices in TREATMENT_BANDS_MPH))  # code 0: none
TREATMENT_SOURCE = (
    "MUTCD 11th ed. (2023) Table 2C-4 (devices by the posted-advisory difference), as transcribed: unverified "
    "against the manual; the need by road type and traffic volume is not applied (no such input). The plaque from "
    "a 5 mph difference: TxDOT, Procedures for Establishing Speed Zones ('a safe operating speed of 5 miles per "
    "hour or more below the posted maximum speed limit should be signed with advisory speed')"
)
W1_13_RULE = (
    "this service's rule, not a manual's: a truck rollover warning (W1-13) is recommended where the vehicle's "
    "rollover speed (thesis Eq. 9.1 with its SRT on this bank and grade) less a margin of {margin:g} km/h falls "
    "below the advisory speed shown"
)


# ------------------------------------------------------------------------------------------------- conversions


def kmh_to_mph(v):
    return np.asarray(v, dtype=float) / KMH_PER_MPH


def mph_to_kmh(v):
    return np.asarray(v, dtype=float) * KMH_PER_MPH


def check_units(units: str, field: str = "units") -> None:
    if units not in SIGN_INCREMENTS:
        raise InvalidRoad(f"units must be one of {', '.join(UNITS)}, not {units!r}", field=field, value=units)


def check_increment(units: str, increment: float, field: str = "increment") -> None:
    """Refuse an increment that is not the sign's: 5 (mph) with ``us``, 10 (km/h) with ``metric``."""
    check_units(units)
    if not math.isclose(float(increment), SIGN_INCREMENTS[units]):
        raise InvalidRoad(
            f"{increment:g} is not a sign increment in {units} units: advisory speeds are shown in multiples of "
            f"{SIGN_INCREMENTS[units]:g} {'mph' if units == 'us' else 'km/h'}",
            field=field,
            value=increment,
        )


def check_speed_range(value: float, field: str) -> None:
    lo, hi = SPEED_RANGE_KMH
    if not (math.isfinite(value) and lo <= value <= hi):
        raise InvalidRoad(f"{field} must lie in {lo:g}-{hi:g} km/h", field=field, value=value)


# ------------------------------------------------------------------------------------------------ the displayed speed


def displayed_speed_kmh(speed_kmh, units: str = "us"):
    """The speed shown on the plaque [km/h]: a multiple of 5 mph or of 10 km/h.

    US: add 1.0 mph and round down to the nearest 5 mph (TxDOT, Direct Method, Step 2: "rounding curve speeds that
    end in 4 or 9 up to the next higher 5 mph increment"). Metric: round down to 10 km/h (assumed). A speed below one
    increment shows one increment (a plaque cannot show 0). nan stays nan.
    """
    check_units(units)
    v = np.asarray(speed_kmh, dtype=float)
    step = SIGN_INCREMENTS[units]
    with np.errstate(invalid="ignore"):
        if units == "us":
            shown = np.floor((v / KMH_PER_MPH + TXDOT_ROUNDING_ADD_MPH) / step + 1e-9) * step * KMH_PER_MPH
            floor_kmh = step * KMH_PER_MPH
        else:
            shown = np.floor(v / step + 1e-9) * step
            floor_kmh = step
        return np.where(np.isnan(v), np.nan, np.maximum(shown, floor_kmh))


def displayed_in_units(speed_kmh, units: str = "us"):
    """A displayed speed [km/h] in the units of the plaque (mph for ``us``, km/h for ``metric``), rounded to the
    increment (removes the conversion's float noise)."""
    v = np.asarray(speed_kmh, dtype=float)
    return np.round(v / KMH_PER_MPH, 6) if units == "us" else np.round(v, 6)


# ---------------------------------------------------------------------------------------------- side-friction speeds


def point_mass_speed_kmh(radius_m, superelevation_percent, side_friction):
    """V = sqrt(127 R (0.01 e + f)) [km/h]: the point-mass curve formula solved for speed (thesis Eq. 9.2 inverted;
    AASHTO Green Book Eq. 3-8). Where 0.01 e + f <= 0 the curve holds no speed: 0."""
    r = np.asarray(radius_m, dtype=float)
    demand = 0.01 * np.asarray(superelevation_percent, dtype=float) + np.asarray(side_friction, dtype=float)
    return np.sqrt(np.maximum(KMH2_PER_M_G * r * demand, 0.0))


@lru_cache(maxsize=64)
def ball_bank_side_friction(ball_bank_deg: float, body_roll_deg_per_g: float = BODY_ROLL_DEG_PER_G) -> float:
    """The side friction (lateral acceleration above what the superelevation balances) [g] that a ball-bank
    indicator reads as ``ball_bank_deg``: atan(f) + body_roll * f = ball-bank angle, solved for f by bisection.

    The ball sits in the vehicle, so it reads the unbalanced lateral acceleration plus the body's roll toward the
    outside; the roll allowance is :data:`BODY_ROLL_DEG_PER_G` unless given (assumed).
    """
    if not (0.0 < ball_bank_deg < 45.0) or body_roll_deg_per_g < 0:
        raise InvalidRoad("ball-bank angle must lie in (0, 45) deg, body roll >= 0", field="ball_bank_deg")
    lo, hi = 0.0, 1.0
    for _ in range(80):  # the left side rises with f: one root
        mid = 0.5 * (lo + hi)
        if math.degrees(math.atan(mid)) + body_roll_deg_per_g * mid < ball_bank_deg:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def band_values_side_friction(bands: SpeedBands, body_roll_deg_per_g: float = BODY_ROLL_DEG_PER_G) -> np.ndarray:
    """The side friction of each band [-]: the ball-bank angles converted, or the table's f as it is."""
    if bands.quantity == "side_friction":
        return np.asarray(bands.values, dtype=float)
    return np.array([ball_bank_side_friction(a, body_roll_deg_per_g) for a in bands.values])


def criterion_speed_kmh(
    bands: SpeedBands, radius_m, superelevation_percent, body_roll_deg_per_g: float = BODY_ROLL_DEG_PER_G
):
    """The highest speed at which the curve meets a speed-dependent criterion [km/h], elementwise.

    The demand rises with speed and the criterion's side friction falls with it, so the speeds that meet it are an
    interval from 0: in the band whose own point-mass speed lies inside it, that speed; where a band's speed lies
    below the band's lowest edge, that edge (the band before met the criterion up to it).
    """
    r = np.atleast_1d(np.asarray(radius_m, dtype=float))
    e = np.broadcast_to(np.asarray(superelevation_percent, dtype=float), r.shape)
    f = band_values_side_friction(bands, body_roll_deg_per_g)
    edges = mph_to_kmh(np.array((*bands.edges_mph, np.inf)))
    if r.ndim == 1 and len(r) > _CHUNK:  # in chunks, into one array: the temporaries stay small
        out = np.empty(len(r))
        for lo in range(0, len(r), _CHUNK):
            k = slice(lo, lo + _CHUNK)
            out[k] = _criterion_speed_kmh(f, edges, r[k], e[k])
        return out
    return _criterion_speed_kmh(f, edges, r, e)


#: curves per chunk of the criteria's arithmetic (whole-road temporaries are fresh pages at 100,000 curves, which cost
#: more to touch than the arithmetic on them; a chunk's stay in the allocator's free memory)
_CHUNK = 8192


def _criterion_speed_kmh(f, edges, r, e):
    """:func:`criterion_speed_kmh` of the bands' side frictions ``f`` and speed edges [km/h] (the last inf)."""
    # the first band (in rising speed) whose own speed lies below its upper edge sets the speed: max(v, its lower
    # edge); bands taken from the last so the first one's overwrites (selects, not masked assignments: these cost
    # ten times an arithmetic pass on random masks)
    out = np.full(r.shape, np.nan)
    r127, e01 = KMH2_PER_M_G * r, 0.01 * e  # point_mass_speed_kmh's terms, the same for every band
    for i in reversed(range(len(f))):
        v = np.sqrt(np.maximum(r127 * (e01 + f[i]), 0.0))  # point_mass_speed_kmh(r, e, f[i])
        out = np.where(v < edges[i + 1], np.maximum(v, edges[i]), out)
    return out


def direct_method_speed_kmh(average_car_speed_kmh):
    """TxDOT Direct Method: the average free-flowing truck speed, 0.97 x the average passenger-car speed measured
    at mid-curve [km/h] (TxDOT, Direct Method, Step 2). The displayed speed then follows
    :func:`displayed_speed_kmh` (+1 mph, down to 5 mph)."""
    return TXDOT_TRUCK_FACTOR * np.asarray(average_car_speed_kmh, dtype=float)


# ----------------------------------------------------------------------------------------------------- treatment


def treatment_code(posted_speed_kmh, advisory_shown_kmh) -> np.ndarray:
    """Index into :data:`TREATMENTS` from the posted-advisory difference in mph (MUTCD 11e Table 2C-4 as
    transcribed): 0 below 5 mph (no advisory speed), then one code per band. nan (no posted speed) gives -1."""
    diff = kmh_to_mph(np.asarray(posted_speed_kmh, dtype=float) - np.asarray(advisory_shown_kmh, dtype=float))
    code = np.zeros(np.shape(diff), dtype=np.int8)
    for lowest, _ in TREATMENT_BANDS_MPH:  # the bands' lower ends rise: the code is the number of them reached
        code += diff >= lowest - 1e-9
    code[np.isnan(diff)] = -1
    return code


def rollover_warning(rollover_speed_kmh, advisory_shown_kmh, margin_kmh: float = ROLLOVER_MARGIN_KMH) -> np.ndarray:
    """W1-13 recommended (this service's rule): rollover speed - margin < advisory speed shown. False where the
    rollover speed is unknown (nan)."""
    if not (math.isfinite(margin_kmh) and margin_kmh >= 0):
        raise InvalidRoad("the rollover margin must be >= 0 km/h", field="rollover_margin_kmh", value=margin_kmh)
    vr = np.asarray(rollover_speed_kmh, dtype=float)
    with np.errstate(invalid="ignore"):
        return np.isfinite(vr) & (vr - margin_kmh < np.asarray(advisory_shown_kmh, dtype=float))


# ------------------------------------------------------------------------------------------------ curves as arrays

#: codes of :attr:`AdvisoryColumns.governed_by` (the curve assessment's are :data:`engine.road.curves.GOVERNED_BY`)
ADVICE_GOVERNED_BY = ("txdot-direct", BALL_BANK_2009.id)


@dataclass(frozen=True)
class AdvisoryColumns:
    """The advisory speed of every curve, as arrays (one entry per curve; nan = not known).

    ``methods`` maps a method id to its speed [km/h] before rounding; ``advisory_speed_kmh`` is the shown speed
    (a multiple of the increment); ``governed_by`` indexes :data:`ADVICE_GOVERNED_BY`; ``treatment`` indexes
    :data:`TREATMENTS` (-1: no posted speed); ``truck_rollover_warning`` is the W1-13 rule per curve (any vehicle).
    """

    units: str
    advisory_speed_kmh: np.ndarray
    governed_by: np.ndarray
    methods: dict[str, np.ndarray]
    treatment: np.ndarray
    truck_rollover_warning: np.ndarray
    small_deflection: np.ndarray  # deflection below 6 deg (TxDOT: rarely justifies a plaque)
    rollover_margin_kmh: float

    def __len__(self) -> int:
        return len(self.advisory_speed_kmh)


def advise_curves(
    radius_m,
    superelevation_percent,
    posted_speed_kmh,
    rollover_speed_kmh=None,
    *,
    deflection_deg=None,
    measured_car_speed_kmh=None,
    units: str = "us",
    rollover_margin_kmh: float = ROLLOVER_MARGIN_KMH,
    body_roll_deg_per_g: float = BODY_ROLL_DEG_PER_G,
) -> AdvisoryColumns:
    """Advisory speed, treatment and W1-13 rule of every curve (arrays; the alignment answers call this).

    The advisory speed is TxDOT's Direct Method where a measured average car speed is given, else the newest
    ball-bank criterion read (MUTCD 2009, 16/14/12 deg, legacy) because the primary Design Method could not be
    verified (:data:`DESIGN_METHOD_NOTE`); every other method's speed is in ``methods``.

    Parameters
    ----------
    radius_m : the radius of the curve's sharpest component [m]
    superelevation_percent : its superelevation [%]
    posted_speed_kmh : the posted speed, nan = none [km/h]
    rollover_speed_kmh : the lowest rollover speed of the vehicles on the curve (Eq. 9.1), nan = unknown [km/h]
    deflection_deg : the total deflection angle, nan = not given [deg]
    measured_car_speed_kmh : the average free-flowing passenger-car speed at mid-curve, nan = not measured [km/h]
    units : ``us`` (5 mph) or ``metric`` (10 km/h)
    rollover_margin_kmh : the W1-13 rule's margin [km/h]
    body_roll_deg_per_g : the ball-bank conversion's body-roll allowance [deg/g]
    """
    shown, governed_by, methods, small_deflection = _advisory_speeds(
        radius_m, superelevation_percent, deflection_deg, measured_car_speed_kmh, units, body_roll_deg_per_g
    )

    def column(x):
        return np.full(shown.shape, np.nan) if x is None else np.broadcast_to(np.asarray(x, dtype=float), shown.shape)

    return AdvisoryColumns(
        units=units,
        advisory_speed_kmh=shown,
        governed_by=governed_by,
        methods=methods,
        treatment=treatment_code(column(posted_speed_kmh), shown),
        truck_rollover_warning=rollover_warning(column(rollover_speed_kmh), shown, rollover_margin_kmh),
        small_deflection=small_deflection,
        rollover_margin_kmh=rollover_margin_kmh,
    )


def _advisory_speeds(radius_m, superelevation_percent, deflection_deg, measured_car_speed_kmh, units,
                     body_roll_deg_per_g, all_methods: bool = True):  # fmt: skip
    """:func:`advise_curves`'s shown speed, ``governed_by``, methods and small-deflection flag; ``all_methods``
    False: of the legacy criteria only the one the shown speed comes from (the others' speeds are not wanted)."""
    check_units(units)
    r = np.atleast_1d(np.asarray(radius_m, dtype=float))
    n = r.shape

    def column(x):
        return np.full(n, np.nan) if x is None else np.broadcast_to(np.asarray(x, dtype=float), n)

    e = column(superelevation_percent)
    criteria = LEGACY_CRITERIA if all_methods else (BALL_BANK_2009,)
    methods = {b.id: criterion_speed_kmh(b, r, e, body_roll_deg_per_g) for b in criteria}
    if measured_car_speed_kmh is None:  # (an alignment's rows): every speed is the criterion's, no select
        methods["txdot-direct"] = np.broadcast_to(np.nan, n)  # (read-only: no whole-road array of nan made)
        raw, governed_by = methods[BALL_BANK_2009.id], np.ones(n, dtype=np.int8)
    else:
        direct = direct_method_speed_kmh(column(measured_car_speed_kmh))
        methods["txdot-direct"] = direct
        use_direct = np.isfinite(direct)
        raw = np.where(use_direct, direct, methods[BALL_BANK_2009.id])
        governed_by = np.where(use_direct, 0, 1).astype(np.int8)
    shown = displayed_speed_kmh(raw, units)
    deflection = column(deflection_deg)
    small_deflection = np.isfinite(deflection) & (deflection < MIN_DEFLECTION_DEG)
    return shown, governed_by, methods, small_deflection


def method_source(method_id: str) -> tuple[str, bool, bool]:
    """(source, legacy, verified) of a method id of :func:`advise_curves`."""
    for b in LEGACY_CRITERIA:
        if b.id == method_id:
            return b.source, b.legacy, b.verified
    if method_id == "txdot-direct":
        return (
            "TxDOT, Procedures for Establishing Speed Zones, Direct Method, Step 2: average free-flowing passenger-car "
            "speed at mid-curve x 0.97 = average truck speed; +1.0 mph, rounded down to 5 mph",
            False,
            True,
        )
    if method_id == "design-method":
        return DESIGN_METHOD_NOTE, False, False
    raise KeyError(method_id)


# ------------------------------------------------------------------------------------------------------ alignments

#: TxDOT (Design Method, Step 1; Direct Method, Step 1): "When two or more curves are separated by a tangent of 600 ft
#: or less, one sign should apply for all curves" [m]
SHARED_SIGN_TANGENT_M = 600.0 * 0.3048


@dataclass(frozen=True)
class AlignmentAdvice:
    """What an alignment's assessed curves carry (one vehicle): the advisory columns (with the shared sign of curves
    close together applied), the sign group of each curve (the index of its group's first curve; -1 where its
    stations are unknown), and the truck's speed profile (:class:`engine.road.profile.SpeedProfile`) with its
    per-curve figures (``approach_speed_kmh``, ``required_deceleration_mps2``, ...)."""

    advisory: AdvisoryColumns
    sign_group: np.ndarray
    profile: prof.SpeedProfile

    def treatment_devices(self, i: int) -> list[str]:
        code = int(self.advisory.treatment[i])
        return list(TREATMENTS[code]) if code >= 0 else []


def sign_groups(start_station_m, length_m, part=None) -> np.ndarray:
    """Index of the first curve of each curve's sign group: a curve whose tangent from the previous curve is at most
    600 ft shares that curve's sign (TxDOT). -1 where a curve's stations are unknown or out of order (no group).
    ``part``: each curve's part where the road has unconnected parts (stations along each part): no group spans two
    parts."""
    s = np.atleast_1d(np.asarray(start_station_m, dtype=float))
    length = np.broadcast_to(np.asarray(length_m, dtype=float), s.shape)
    n = len(s)
    groups = np.arange(n)
    ok = np.isfinite(s) & np.isfinite(length) & (length > 0)
    if n > 1:
        tangent = s[1:] - (s[:-1] + length[:-1])
        joined = ok[1:] & ok[:-1] & (tangent >= 0) & (tangent <= SHARED_SIGN_TANGENT_M + 1e-9)
        if part is not None:
            p = np.asarray(part)
            joined &= p[1:] == p[:-1]
        starts = np.ones(n, dtype=bool)
        starts[1:] = ~joined
        groups = np.maximum.accumulate(np.arange(n) * starts)  # (a product, not a select on a random mask)
    return np.where(ok, groups, -1)


def advise_alignment(
    columns,
    start_station_m,
    length_m,
    *,
    deflection_deg=None,
    measured_car_speed_kmh=None,
    desired_speed_kmh: float | None = None,
    units: str = "us",
    rollover_margin_kmh: float = ROLLOVER_MARGIN_KMH,
    body_roll_deg_per_g: float = BODY_ROLL_DEG_PER_G,
    deceleration_mps2: float | None = None,
    reaction_time_s: float | None = None,
    alignment_start_m: float | None = None,
    alignment_end_m: float | None = None,
    part=None,
    all_methods: bool = True,
    all_figures: bool = True,
) -> AlignmentAdvice:
    """Advisory speed, treatment, W1-13 rule and the truck's speed profile for the curves of one alignment and one
    vehicle: the function the alignment and route answers call per vehicle.

    Parameters
    ----------
    columns : :class:`engine.road.curves.AlignmentColumns` of the vehicle (its radius, superelevation, grade,
        posted, rollover and safe speeds are used)
    start_station_m, length_m : each curve's start station and length, in travel order [m] (nan: unknown; such
        curves get a reason and the alignment no profile)
    deflection_deg, measured_car_speed_kmh : per curve, optional (see :func:`advise_curves`)
    desired_speed_kmh : the tangent speed where a curve has no posted speed [km/h]; the posted speed otherwise
    units, rollover_margin_kmh, body_roll_deg_per_g : see :func:`advise_curves`
    deceleration_mps2, reaction_time_s, alignment_start_m, alignment_end_m : see
        :func:`engine.road.profile.speed_profile` (None: its defaults)
    part : each curve's part where the road is made of unconnected parts, their stations each along its own part
        (a route's tracks): one profile per part (:func:`engine.road.profile.speed_profiles_by_part`) and no shared
        sign across parts; None: one road
    all_methods : False: ``advisory.methods`` holds only the speeds the shown one comes from (the 2009 ball-bank
        criterion's and the Direct Method's), not every legacy criterion's (an answer that lists none of them)
    all_figures : False: the profile's per-curve figures are only the approach speed and the required deceleration
        (:func:`engine.road.profile.speed_profile`'s ``all_figures``)

    Returns
    -------
    AlignmentAdvice
        A group of curves that shares a sign shows its lowest advisory speed (this service's reading of TxDOT's rule:
        the one sign has to be right for the sharpest curve); the treatment and W1-13 rule follow the shown speed.
    """
    shown, governed_by, methods, small_deflection = _advisory_speeds(
        columns.radius_m,
        columns.superelevation_percent,
        deflection_deg,
        measured_car_speed_kmh,
        units,
        body_roll_deg_per_g,
        all_methods,
    )
    groups = sign_groups(start_station_m, length_m, part)
    grouped = groups >= 0
    if grouped.all() and len(groups):
        # every curve placed: the groups are runs of consecutive curves, each run's lowest by one reduction
        first = np.flatnonzero(groups == np.arange(len(groups)))  # (a group's label is its first curve)
        lowest = np.empty(len(shown))
        lowest[first] = np.minimum.reduceat(shown, first)
        shown = lowest[groups]
    elif np.any(grouped):
        shown = shown.copy()
        lowest = np.full(len(shown), np.inf)
        np.minimum.at(lowest, groups[grouped], shown[grouped])
        shown[grouped] = lowest[groups[grouped]]
    posted = np.asarray(columns.posted_speed_kmh, dtype=float)
    advisory = AdvisoryColumns(
        units=units,
        advisory_speed_kmh=shown,
        governed_by=governed_by,
        methods=methods,
        treatment=treatment_code(posted, shown),
        truck_rollover_warning=rollover_warning(columns.rollover_speed_kmh, shown, rollover_margin_kmh),
        small_deflection=small_deflection,
        rollover_margin_kmh=rollover_margin_kmh,
    )
    desired = posted if desired_speed_kmh is None else np.where(np.isfinite(posted), posted, desired_speed_kmh)
    options = {}
    if deceleration_mps2 is not None:
        options["deceleration_mps2"] = deceleration_mps2
    if reaction_time_s is not None:
        options["reaction_time_s"] = reaction_time_s
    missing = ~np.isfinite(desired)
    if np.any(missing):  # no speed to travel the tangents at: say so per curve, invent none
        n = len(desired)
        first = int(np.flatnonzero(missing)[0])
        reasons = [
            "no posted speed and no desired_speed_kmh: the tangent speed is unknown"
            if missing[i]
            else f"no profile: curves[{first}] has no tangent speed"
            for i in range(n)
        ]
        profile = prof.SpeedProfile.none(
            reasons,
            options.get("deceleration_mps2", prof.DECELERATION_MPS2),
            options.get("reaction_time_s", prof.REACTION_TIME_S),
            "no profile: a curve has no tangent speed",
        )
    else:
        profile = (prof.speed_profile if part is None else partial(prof.speed_profiles_by_part, part))(
            start_station_m,
            length_m,
            desired,
            columns.safe_speed_kmh,
            shown,
            columns.grade_percent,
            alignment_start_m=alignment_start_m,
            alignment_end_m=alignment_end_m,
            all_figures=all_figures,
            **options,
        )
    return AlignmentAdvice(advisory=advisory, sign_group=groups, profile=profile)

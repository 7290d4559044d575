"""Plausibility of measurable inputs: the range a heavy vehicle's masses, heights, lengths and stiffnesses can take,
and the unit slip that most likely explains a value outside it.

A value outside its range is refused (:class:`~engine.errors.InvalidVehicle`) naming the field as the user typed it
and, where multiplying or dividing by 1000 (or 100) would put it inside the range, the slip that explains it: "31.5
kg is not a semitrailer's mass; in tonnes?". The ranges are deliberately wide (a value inside one can still be
wrong); each says where it comes from, or that it is assumed and why.

References
----------
.. [1] Council Directive 96/53/EC (as amended by (EU) 2015/719), Annex I: maximum authorised axle loads (single
   non-driving axle 10 t, driving axle 11.5 t), heights (4.00 m) and widths (2.55 m, 2.60 m conditioned bodies).
.. [2] CONTRAN Resolucao 210/2006 (Brazil): maximum height 4.40 m, width 2.60 m.
.. [3] 23 CFR 658.17 (USA): 20,000 lb (9.07 t) on a single axle.
.. [5] Directive 2007/46/EC, Annex II (vehicle categories): goods vehicles N2/N3 and trailers O3/O4 are those over
   3.5 t maximum mass; Directive 96/53/EC [1], Annex I 3.4-3.5: tandem/tridem axle spacings from under 1.0 m to
   1.8 m and over; ETRTO/ISO 4209 truck tyre sizes (17.5" to 22.5" rims, sections up to 445 mm).
.. [4] TruckSim 2022.1 example datasets (Mechanical Simulation Corp.), as committed in the public repository
   github.com/Steve-Krug/Axicle, folder 04-Trucksim (see :mod:`engine.vehicle.components`): unsprung masses of
   362-679 kg per axle, tyre vertical rates of 750-980 N/mm, suspension roll stiffnesses of 436-657 kN m/rad per
   axle, fifth-wheel roll stiffness 100 kN m/deg (5730 kN m/rad) with 1 deg of lash.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from engine.errors import InvalidVehicle


@dataclass(frozen=True)
class Range:
    """Where a measurable quantity of a heavy vehicle lies: [minimum, maximum] in ``unit``, and why."""

    minimum: float
    maximum: float
    unit: str
    why: str
    #: the unit slips worth suggesting: (factor that brings the value into range, what the user likely typed in)
    slips: tuple[tuple[float, str], ...] = ()
    #: a slip whose reading is plausible too, for the values where both are (factor, the unit it was typed in): such
    #: a value is answered, with a warning that names both readings (:func:`ambiguous_reading`)
    either_way: tuple[float, str] | None = None

    def contains(self, value: float) -> bool:
        return self.minimum <= value <= self.maximum


_MASS_SLIPS = ((1000.0, "tonnes"), (1 / 9.81 * 1000.0, "kN"))
_LENGTH_SLIPS = ((1e-3, "millimetres"), (1e-2, "centimetres"))
_RATE_SLIPS = ((1e-3, "N/m"), (1e3, "kN/mm"))
#: standard gravity: a weight in kN from a mass in tonnes (x 9.80665) or kg (x 0.00980665)
G = 9.80665
_WEIGHT_SLIPS = ((G, "tonnes"), (1e-3, "N"), (G / 1000.0, "kg"))

RANGES: dict[str, Range] = {
    "unit_mass_kg": Range(
        300.0,
        80_000.0,
        "kg",
        "assumed: a converter dolly's sprung mass is about 1,300 kg [4]; 80 t is above any unit of the heaviest "
        "combinations the cited rules allow",
        _MASS_SLIPS,
    ),
    "axle_load_kg": Range(
        300.0,
        20_000.0,
        "kg per axle",
        "assumed: above the lightest axle's own mass (362 kg, [4]) and below 1.7 times the largest regulated "
        "single-axle load, 11.5 t (EU Dir. 96/53/EC [1]; 10 t in Brazil, 9.07 t in the USA [3])",
        _MASS_SLIPS,
    ),
    "unsprung_mass_kg": Range(
        50.0,
        2_000.0,
        "kg per axle",
        "assumed bracket around the sourced 362-679 kg per axle (TruckSim examples [4])",
        _MASS_SLIPS,
    ),
    "height_m": Range(
        0.05,
        4.40,
        "m",
        "at most the tallest legal heavy vehicle, 4.40 m (CONTRAN Res. 210/2006 [2]; the EU allows 4.00 m [1])",
        _LENGTH_SLIPS,
    ),
    "track_m": Range(
        1.0,
        2.60,
        "m",
        "at most the widest legal vehicle, 2.60 m (CONTRAN Res. 210/2006 [2], EU Dir. 96/53/EC [1]); a track "
        "under 1 m is no heavy vehicle's",
        _LENGTH_SLIPS,
    ),
    "spring_spacing_m": Range(
        0.3,
        2.60,
        "m",
        "from 0.3 m (assumed) up to the widest legal vehicle, 2.60 m ([1], [2]: the springs sit inside the track)",
        _LENGTH_SLIPS,
    ),
    "position_m": Range(
        -5.0,
        30.0,
        "m",
        "assumed: a point of a unit lies within 30 m behind its reference (the longest legal semitrailer is 13.6 m "
        "to 14.6 m) and at most 5 m ahead of it",
        _LENGTH_SLIPS,
    ),
    "tyre_stiffness_kn_per_m": Range(
        200.0,
        5_000.0,
        "kN/m per tyre",
        "assumed bracket, about a quarter to five times the sourced 750-980 kN/m (TruckSim examples [4]; the "
        "thesis's 840 and 980 kN/m)",
        ((1e-3, "N/m"),),
    ),
    "suspension_roll_stiffness_knm_per_rad": Range(
        20.0,
        20_000.0,
        "kN m/rad per axle",
        "assumed bracket around the sourced 436-657 kN m/rad (TruckSim examples [4]) and the thesis's leaf springs "
        "(kLs b^2/2 = 812-1128 kN m/rad)",
        ((1e-3, "N m/rad"),),
    ),
    "coupling_roll_stiffness_knm_per_rad": Range(
        100.0,
        200_000.0,
        "kN m/rad",
        "assumed bracket around the sourced fifth wheels: 5730 kN m/rad (100 kN m/deg) and 28,650 kN m/rad "
        "(500 kN m/deg) (TruckSim examples [4])",
        ((1e-3, "N m/rad"),),
    ),
    "payload_mass_kg": Range(
        100.0,
        60_000.0,
        "kg",
        "assumed: one loaded pallet is 100 kg or more (a lighter payload moves the SRT by less than the model's "
        "accuracy, and '24' typed as the mass of a freight payload is far likelier 24 t); at most the heaviest unit "
        "of the cited rules' combinations less its tare",
        _MASS_SLIPS,
    ),
    "group_load_kg": Range(
        300.0,
        40_000.0,
        "kg per group",
        "assumed: above the lightest axle's own mass (362 kg, [4]) and below 1.7 times the heaviest regulated group "
        "load, a tridem's 24 t (EU Dir. 96/53/EC [1])",
        _MASS_SLIPS,
    ),
    "length_m": Range(
        0.1,
        30.0,
        "m",
        "assumed: a deck or load is at most 30 m long (the longest legal semitrailer is 13.6 m to 14.6 m [1])",
        _LENGTH_SLIPS,
    ),
    "axle_spacing_m": Range(
        0.5,
        3.1,
        "m",
        "the regulated tandem/tridem spacing classes run from under 1.0 m to 1.8 m and over (EU Dir. 96/53/EC [1], "
        "[5]); 0.5 m and 3.1 m (a US spread tandem's 10 ft) are assumed ends",
        _LENGTH_SLIPS,
    ),
    "tyre_radius_m": Range(
        0.25,
        0.8,
        "m",
        "assumed around truck tyres on 17.5-24.5 in rims (loaded radii about 0.35-0.55 m, [5]); 0.8 m is the "
        "record's own bound for the rolling radius",
        _LENGTH_SLIPS,
    ),
    "tyre_width_m": Range(
        0.1,
        0.6,
        "m",
        "assumed around truck tyre sections (215 mm to a 445 mm super single, ETRTO [5])",
        _LENGTH_SLIPS,
    ),
    "tyre_load_kg": Range(
        200.0,
        8_000.0,
        "kg per tyre",
        "assumed: truck tyres are rated about 1,000-4,500 kg (load indices 116-160, ETRTO [5])",
        _MASS_SLIPS,
    ),
    "spring_rate_kn_per_m": Range(
        100.0,
        20_000.0,
        "kN/m",
        "assumed bracket around the thesis's leaf springs (1800 and 2500 kN/m per axle and side, Tables 14-16)",
        _RATE_SLIPS,
    ),
    "fifth_wheel_rate_kn_per_m": Range(
        100.0,
        200_000.0,
        "kN/m",
        "assumed bracket around the thesis's 7500 kN/m (Table 15) and the sourced fifth wheels' 5730-28,650 kN m/rad "
        "as two springs 0.8 m apart, 2 k / b1^2 = 18,000-90,000 kN/m (TruckSim examples [4])",
        _RATE_SLIPS,
    ),
    "weight_kn": Range(
        3.5 * G,
        1000.0,
        "kN",
        "a heavy vehicle or trailer is over 3.5 t (categories N2/N3, O3/O4 [5]): 34.3 kN; at most the record's own "
        "bound, 1000 kN",
        _WEIGHT_SLIPS,
        # 34.3-102 kN is a light trailer's weight (3.5-10.4 t) and the same number in tonnes is a heavy unit's
        # (336-1000 kN): both plausible, so neither can be refused
        either_way=(G, "tonnes"),
    ),
    "lash_deg": Range(
        0.0,
        2.0,
        "deg each way",
        "assumed: twice the only sourced lash, 1 deg each way of TruckSim's default fifth wheel [4]; no source "
        "for suspension lash could be read (docs/combinations.md)",
    ),
}


def check_plausible(quantity: str, value: object, field: str, what: str) -> float:
    """``value`` as a float if it is a finite number inside :data:`RANGES` ``[quantity]``, else
    :class:`InvalidVehicle` naming ``field`` and the likely unit slip.

    Parameters
    ----------
    quantity : key of :data:`RANGES` [-]
    value : the value as given [the range's unit]
    field : the field's path as the user typed it (``combination.units[1].sprung_mass_kg``) [-]
    what : the thing it belongs to, for the message (``"the semitrailer 'trailer'"``) [-]
    """
    r = RANGES[quantity]
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise InvalidVehicle(f"{field} must be a finite number in {r.unit}, got {value!r}", field=field, value=value)
    v = float(value)
    if r.contains(v):
        return v
    expected = f"expected {r.minimum:g} to {r.maximum:g} {r.unit} ({r.why})"
    slip = unit_slip(v, r.minimum, r.maximum, r.slips) if v > 0 else None  # a slip never makes a value negative
    if slip is not None:
        typed, meant = slip
        raise InvalidVehicle(
            f"{field} = {v:g} {r.unit} for {what}: in {typed}? ({v:g} {typed} would be {meant:g} "
            f"{r.unit.split(' ')[0]}); not plausible: {expected}",
            field=field,
            value=value,
        )
    raise InvalidVehicle(f"{field} = {v:g} {r.unit} is not plausible for {what}: {expected}", field=field, value=value)


@dataclass(frozen=True)
class InputWarning:
    """A value answered as given that reads plausibly in another unit too: the field as typed, the value, and both
    readings in the range's unit."""

    field: str
    value: float
    unit: str
    other_unit: str
    other_reading: float
    message: str


def ambiguous_reading(quantity: str, value: object, field: str, what: str) -> InputWarning | None:
    """An :class:`InputWarning` when ``value`` lies where :data:`RANGES` ``[quantity]`` is plausible read either way
    (its ``either_way`` slip also lands inside the range); None otherwise (or when the value is not a plausible
    number at all: :func:`check_plausible` refuses those).

    Parameters
    ----------
    quantity : key of :data:`RANGES` [-]
    value : the value as given [the range's unit]
    field : the field's path as the user typed it (``vehicle.weight_kn``) [-]
    what : the thing it belongs to, for the message [-]
    """
    r = RANGES[quantity]
    if r.either_way is None or isinstance(value, bool) or not isinstance(value, int | float):
        return None
    v = float(value)
    factor, typed = r.either_way
    if not (math.isfinite(v) and r.contains(v) and r.contains(v * factor)):
        return None
    unit = r.unit.split(" ")[0]
    other = v * factor
    message = (
        f"{field} = {v:g} {unit} is plausible for {what} read either way: {v:g} {unit} as given (the answer's "
        f"reading), or {v:g} {typed} typed as {unit}, which would be {other:.4g} {unit}; if you meant {typed}, send "
        f"{other:.4g}"
    )
    return InputWarning(field, v, unit, typed, other, message)


def record_warnings(vehicle, where: str = "") -> list[InputWarning]:
    """The :class:`InputWarning` of every field of a vehicle record (typed by a user) that reads plausibly in
    another unit too (:data:`RECORD_RANGES`), named ``where`` + the record field (``vehicle.weight_kn``)."""
    out = []
    for name, quantity in RECORD_RANGES.items():
        w = ambiguous_reading(quantity, getattr(vehicle, name, None), f"{where}{name}", "the vehicle record")
        if w is not None:
            out.append(w)
    return out


def unit_slip(
    value: float, minimum: float, maximum: float, slips: tuple[tuple[float, str], ...]
) -> tuple[str, float] | None:
    """The first unit slip of ``slips`` that brings ``value`` into [minimum, maximum]: (the unit the user likely typed
    in, the value it would be) [-, the range's unit]; None when none does."""
    for factor, typed in slips:
        if minimum <= value * factor <= maximum:
            return typed, value * factor
    return None


#: the slips worth suggesting for a record field outside its schema bounds, by the field's unit
RECORD_SLIPS: dict[str, tuple[tuple[float, str], ...]] = {"m": _LENGTH_SLIPS, "kN": _WEIGHT_SLIPS, "kN/m": _RATE_SLIPS}

#: vehicle record fields (:data:`engine.vehicle.record.FIELD_DOCS`) -> their plausibility range (a record's own
#: bounds are the model's domain; these are what a heavy vehicle measures: the record's stiffness bound is 1e12 kN/m,
#: which the engine's own tests use for a near-rigid vehicle, so records typed over HTTP are checked here)
RECORD_RANGES = {
    "weight_kn": "weight_kn",
    "tire_stiffness_kn_per_m": "tyre_stiffness_kn_per_m",
    "suspension_stiffness_kn_per_m": "spring_rate_kn_per_m",
    "fifth_wheel_stiffness_kn_per_m": "fifth_wheel_rate_kn_per_m",
}


def check_record_plausible(vehicle, where: str = "") -> None:
    """Refuse a vehicle record (typed by a user) whose weight or stiffnesses lie outside :data:`RANGES`, naming the
    field (``where`` + the record field) and the likely unit slip: a 31.5 kN semitrailer is 31.5 t typed in kN, a
    tyre of 840,000 kN/m is 840 kN/m typed in N/m. Lengths need no check here: the record's own bounds (at most 4.4 m
    high, 2.6 m wide, ...) already refuse millimetres, and the HTTP layer adds the slip to that message."""
    title = "the vehicle record"
    for name, quantity in RECORD_RANGES.items():
        value = getattr(vehicle, name, None)
        if value is not None:
            check_plausible(quantity, value, f"{where}{name}", title)

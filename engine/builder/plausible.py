"""Plausibility of a builder spec's measurable inputs, checked field by field before anything is derived.

Every number a user types into a :class:`~engine.builder.spec.VehicleSpec` is checked against its range in
:data:`engine.vehicle.plausibility.RANGES` (each range gives its source, or says it is assumed and why) under the
spec path the user typed (``spec.tare.mass_kg``, ``spec.payloads[0].load_height_m``), with the likely unit slip:
``spec.tare.mass_kg = 7.5 kg for the tare of a semitrailer: in tonnes?``. Checked first, so a height typed in
millimetres is blamed on itself, not on the derived CG height of another input that was right.

Only given values are checked: a field left out takes its documented default. Values the builder's own checks
refuse with a more specific reason (zero or negative values, non-numbers) are left to them: a unit slip makes a
positive value too large or too small, never negative. Positions are the exception: a deck or a load may begin
ahead of the kingpin, so a negative position is judged by its range too (the published schema's bound).
"""

from __future__ import annotations

import math

from engine.builder.spec import AxleGroupSpec, VehicleSpec
from engine.vehicle.plausibility import check_plausible

#: what a unit type's tare is called in a message
_UNIT_NAMES = {
    "semitrailer": "a semitrailer",
    "btrain-rear": "a B-train's rear trailer",
    "rigid-truck": "a rigid truck",
}


def _number(value: object) -> bool:
    return isinstance(value, int | float) and not isinstance(value, bool) and math.isfinite(value)


def _check(quantity: str, value: object, path: str, what: str, *, positive: bool = True) -> None:
    """``value`` against its range when given as a number (and, for a ``positive`` quantity, above zero)."""
    if _number(value) and (value > 0 or not positive):
        check_plausible(quantity, value, path, what)


def _check_group(g: object, path: str, name: str) -> None:
    if not isinstance(g, AxleGroupSpec):
        return
    _check("track_m", g.track_m, f"{path}.track_m", f"the track of the {name}")
    _check("position_m", g.centre_from_kingpin_m, f"{path}.centre_from_kingpin_m", f"the {name}", positive=False)
    _check("axle_spacing_m", g.axle_spacing_m, f"{path}.axle_spacing_m", f"the axle spacing of the {name}")
    _check("group_load_kg", g.rated_load_kg, f"{path}.rated_load_kg", f"the rated load of the {name}")
    t = g.tyre
    if t is not None:
        tp, tw = f"{path}.tyre", f"a tyre of the {name}"
        _check("tyre_radius_m", getattr(t, "loaded_radius_m", None), f"{tp}.loaded_radius_m", tw)
        _check("tyre_stiffness_kn_per_m", getattr(t, "stiffness_kn_per_m", None), f"{tp}.stiffness_kn_per_m", tw)
        _check("tyre_width_m", getattr(t, "section_width_m", None), f"{tp}.section_width_m", tw)
        _check("tyre_load_kg", getattr(t, "rated_load_kg", None), f"{tp}.rated_load_kg", tw)
    s = g.suspension
    if s is not None:
        sp, sw = f"{path}.suspension", f"the suspension of the {name}"
        _check("spring_rate_kn_per_m", getattr(s, "stiffness_kn_per_m", None), f"{sp}.stiffness_kn_per_m", sw)
        roll = getattr(s, "roll_stiffness_knm_per_rad", None)
        _check("suspension_roll_stiffness_knm_per_rad", roll, f"{sp}.roll_stiffness_knm_per_rad", sw)
        _check("height_m", getattr(s, "height_m", None), f"{sp}.height_m", sw)
        _check("spring_spacing_m", getattr(s, "spring_separation_m", None), f"{sp}.spring_separation_m", sw)


def check_spec_plausible(spec: VehicleSpec) -> None:
    """Refuse a spec with a measurable input outside its plausible range (:mod:`engine.vehicle.plausibility`),
    naming the spec path as typed and the likely unit slip.

    Raises
    ------
    InvalidVehicle : ``field`` is the offending input's spec path (``spec.payloads[0].mass_kg``).
    """
    unit = _UNIT_NAMES.get(spec.unit_type, "the unit") if isinstance(spec.unit_type, str) else "the unit"
    _check_group(spec.rear, "spec.rear", "rear axle group")
    _check_group(spec.front, "spec.front", "front axle group")
    t = spec.tare
    if t is not None and hasattr(t, "mass_kg"):
        _check("unit_mass_kg", t.mass_kg, "spec.tare.mass_kg", f"the tare of {unit}")
        _check("height_m", t.cg_height_m, "spec.tare.cg_height_m", f"the tare CG height of {unit}")
        _check(
            "position_m", t.cg_from_kingpin_m, "spec.tare.cg_from_kingpin_m", f"the tare CG of {unit}", positive=False
        )
        _check("group_load_kg", t.rear_group_load_kg, "spec.tare.rear_group_load_kg", f"the tare rear load of {unit}")
    d = spec.deck
    if d is not None and hasattr(d, "length_m"):
        _check("position_m", d.front_from_kingpin_m, "spec.deck.front_from_kingpin_m", "the deck", positive=False)
        _check("length_m", d.length_m, "spec.deck.length_m", "the deck")
    check_payloads_plausible(spec.payloads, "spec")
    f = spec.front_unit
    if f is not None:
        rate = getattr(f, "fifth_wheel_stiffness_kn_per_m", None)
        _check("fifth_wheel_rate_kn_per_m", rate, "spec.front_unit.fifth_wheel_stiffness_kn_per_m", "the fifth wheel")
        height = getattr(f, "fifth_wheel_height_m", None)
        _check("height_m", height, "spec.front_unit.fifth_wheel_height_m", "the fifth wheel")
        width = getattr(f, "fifth_wheel_width_m", None)
        _check("spring_spacing_m", width, "spec.front_unit.fifth_wheel_width_m", "the fifth wheel")


def check_payloads_plausible(payloads: object, where: str) -> None:
    """Refuse a payload (:class:`~engine.builder.spec.PayloadSpec`) with a measurable input outside its
    plausible range, named under ``where`` (``spec``, ``combination_spec.units[1]``): the single-unit spec's and every
    unit of a combination spec's, one rule (a 22 kg payload is 22 t typed in kg, in either).

    Raises
    ------
    InvalidVehicle : ``field`` is the offending input's path (``spec.payloads[0].mass_kg``).
    """
    if not isinstance(payloads, list | tuple):
        return
    for i, p in enumerate(payloads):
        if not hasattr(p, "mass_kg"):
            continue
        path, what = f"{where}.payloads[{i}]", f"payload {i}"
        _check("payload_mass_kg", p.mass_kg, f"{path}.mass_kg", f"a payload ({what})")
        for name in ("deck_height_m", "load_height_m", "deck_height_rear_m", "load_height_rear_m", "cg_height_m"):
            _check("height_m", getattr(p, name), f"{path}.{name}", f"a height of {what}")
        _check("position_m", p.front_from_kingpin_m, f"{path}.front_from_kingpin_m", what, positive=False)
        _check("position_m", p.cg_from_kingpin_m, f"{path}.cg_from_kingpin_m", what, positive=False)
        _check("length_m", p.length_m, f"{path}.length_m", f"the length of {what}")
        tank = p.tank
        if tank is not None:
            tp = f"{path}.tank"
            for name in ("height_m", "bottom_height_m", "fill_height_m"):
                _check("height_m", getattr(tank, name, None), f"{tp}.{name}", f"the tank of {what}")


#: (builder dataclass, field) -> the key of :data:`engine.vehicle.plausibility.RANGES` the builders judge it by: what
#: :func:`check_spec_plausible`, :func:`check_payloads_plausible` and the combination builder check, as data, for
#: the published schema's bounds (``app.vehicle_forms.builder_schemas``: a value outside is refused, so the bounds are
#: true).
#: Left out where the server takes a value outside the range: a tank's fill height of 0 (empty), a pintle's roll
#: stiffness of 0 (none)
SPEC_RANGES: dict[tuple[str, str], str] = {
    ("AxleGroupSpec", "track_m"): "track_m",
    ("AxleGroupSpec", "centre_from_kingpin_m"): "position_m",
    ("AxleGroupSpec", "axle_spacing_m"): "axle_spacing_m",
    ("AxleGroupSpec", "rated_load_kg"): "group_load_kg",
    ("TyreSpec", "loaded_radius_m"): "tyre_radius_m",
    ("TyreSpec", "stiffness_kn_per_m"): "tyre_stiffness_kn_per_m",
    ("TyreSpec", "section_width_m"): "tyre_width_m",
    ("TyreSpec", "rated_load_kg"): "tyre_load_kg",
    ("SuspensionSpec", "stiffness_kn_per_m"): "spring_rate_kn_per_m",
    ("SuspensionSpec", "roll_stiffness_knm_per_rad"): "suspension_roll_stiffness_knm_per_rad",
    ("SuspensionSpec", "height_m"): "height_m",
    ("SuspensionSpec", "spring_separation_m"): "spring_spacing_m",
    ("TareSpec", "mass_kg"): "unit_mass_kg",
    ("TareSpec", "cg_height_m"): "height_m",
    ("TareSpec", "cg_from_kingpin_m"): "position_m",
    ("TareSpec", "rear_group_load_kg"): "group_load_kg",
    ("DeckSpec", "front_from_kingpin_m"): "position_m",
    ("DeckSpec", "length_m"): "length_m",
    ("PayloadSpec", "mass_kg"): "payload_mass_kg",
    ("PayloadSpec", "deck_height_m"): "height_m",
    ("PayloadSpec", "load_height_m"): "height_m",
    ("PayloadSpec", "deck_height_rear_m"): "height_m",
    ("PayloadSpec", "load_height_rear_m"): "height_m",
    ("PayloadSpec", "cg_height_m"): "height_m",
    ("PayloadSpec", "front_from_kingpin_m"): "position_m",
    ("PayloadSpec", "cg_from_kingpin_m"): "position_m",
    ("PayloadSpec", "length_m"): "length_m",
    ("TankSpec", "height_m"): "height_m",
    ("TankSpec", "bottom_height_m"): "height_m",
    ("FrontUnitSpec", "fifth_wheel_stiffness_kn_per_m"): "fifth_wheel_rate_kn_per_m",
    ("FrontUnitSpec", "fifth_wheel_height_m"): "height_m",
    ("FrontUnitSpec", "fifth_wheel_width_m"): "spring_spacing_m",
    # the combination spec (engine.builder.combination)
    ("RollTyreSpec", "stiffness_kn_per_m"): "tyre_stiffness_kn_per_m",
    ("RollTyreSpec", "loaded_radius_m"): "tyre_radius_m",
    ("RollSuspensionSpec", "roll_stiffness_knm_per_rad"): "suspension_roll_stiffness_knm_per_rad",
    ("RollSuspensionSpec", "roll_centre_height_m"): "height_m",
    ("RollSuspensionSpec", "spring_spacing_m"): "spring_spacing_m",
    ("RollSuspensionSpec", "lash_deg"): "lash_deg",
    ("RollSuspensionSpec", "unsprung_mass_kg"): "unsprung_mass_kg",
    ("RollSuspensionSpec", "unsprung_cg_height_m"): "height_m",
    ("UnitGroupSpec", "track_m"): "track_m",
    ("UnitGroupSpec", "position_m"): "position_m",
    ("UnitGroupSpec", "axle_spacing_m"): "axle_spacing_m",
    ("CouplingSpec", "position_m"): "position_m",
    ("CouplingSpec", "height_m"): "height_m",
    ("CouplingSpec", "lash_deg"): "lash_deg",
}

#: spec fields whose 0 is taken (and means none) although the rest of the range starts above it: a payload of 0 kg
#: is no payload (what the payload table's first row builds); any other mass under the range is refused
SPEC_ZERO_ALLOWED = frozenset({("PayloadSpec", "mass_kg")})

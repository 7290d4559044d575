"""The build: a spec -> the record, every field with how it was obtained."""

from __future__ import annotations

import math
from collections.abc import Sequence

from engine.builder.groups import ResolvedGroup, check_width, component_fields, resolve_group
from engine.builder.payloads import payload_item, tare_item
from engine.builder.plausible import check_spec_plausible
from engine.builder.spec import (
    G_M_PER_S2,
    THESIS,
    TRAILER_TYPES,
    UNIT_TYPES,
    BuiltVehicle,
    DeckSpec,
    FieldDerivation,
    FrontUnitSpec,
    MassItem,
    PayloadSpec,
    VehicleSpec,
    check_choice,
    check_number,
)
from engine.errors import InvalidVehicle
from engine.models.registry import get_model
from engine.vehicle.record import FIELD_DOCS, Vehicle

# --------------------------------------------------------------------------------------------- the build


def _front_defaults(unit_type: str) -> dict[str, tuple[float | None, str]]:
    """Documented defaults of the front-unit fields, per unit type: value and source."""
    t15_16 = f"{THESIS}, Tables 15 and 16 (the thesis's value for every fifth wheel; no measurement cited)"
    if unit_type == "rigid-truck":
        none = (None, "not applicable: a rigid truck has no fifth wheel")
        return {
            "fifth_wheel_stiffness_kn_per_m": none,
            "fifth_wheel_height_m": none,
            "fifth_wheel_width_m": none,
            "fifth_wheel_to_front_axle_m": (0.0, "a rigid truck's reference is its front group itself (Table 22)"),
            "front_llt_ratio": (0.9, f"{THESIS}, App. B: LLTf is about 90 % of LLTr for the truck of Table 22"),
        }
    l13 = (0.2, f"{THESIS}, Table 23 (tractor-semitrailer)")
    if unit_type == "btrain-rear":
        l13 = (0.15, f"{THESIS}, Table 16 (B-train)")
    return {
        "fifth_wheel_stiffness_kn_per_m": (7500.0, t15_16),
        "fifth_wheel_height_m": (0.1, t15_16),
        "fifth_wheel_width_m": (0.6, t15_16),
        "fifth_wheel_to_front_axle_m": l13,
        "front_llt_ratio": (0.7, f"{THESIS}, Ch. 9 and Tables 16, 23, after Kamnik et al. (2003): LLTf = 0.7 LLTr"),
    }


def _front_unit_fields(spec: VehicleSpec) -> dict[str, FieldDerivation]:
    fu = spec.front_unit if spec.front_unit is not None else FrontUnitSpec()
    defaults = _front_defaults(spec.unit_type)
    out = {}
    for name in ("fifth_wheel_stiffness_kn_per_m", "fifth_wheel_height_m", "fifth_wheel_width_m", "front_llt_ratio"):
        given, path = getattr(fu, name), f"spec.front_unit.{name}"
        unit = FIELD_DOCS[name].unit
        if given is None:
            value, source = defaults[name]
            out[name] = FieldDerivation(
                name, value, unit, "default", f"{FIELD_DOCS[name].symbol} default", source, path
            )
        elif spec.unit_type == "rigid-truck" and name.startswith("fifth_wheel"):
            raise InvalidVehicle(f"{path}: a rigid truck has no fifth wheel", field=path, value=given)
        else:
            out[name] = FieldDerivation(
                name, check_number(given, path), unit, "given", f"{FIELD_DOCS[name].symbol} as given", path, path
            )
    name, path = "chassis_torsional_stiffness_knm2_per_rad", "spec.front_unit.chassis_torsional_stiffness_knm2_per_rad"
    if fu.chassis_torsional_stiffness_knm2_per_rad is None:
        out[name] = FieldDerivation(
            name,
            None,
            FIELD_DOCS[name].unit,
            "default",
            "torsionally rigid between the rear group and the CG",
            f"{THESIS}: no value given; the presets leave it null (docs/model.md, Sec. 6)",
            path,
        )
    else:
        value = check_number(fu.chassis_torsional_stiffness_knm2_per_rad, path)
        out[name] = FieldDerivation(name, value, FIELD_DOCS[name].unit, "given", "G Jr as given", path, path)
    return out


def _geometry_fields(spec: VehicleSpec, rear: ResolvedGroup, front: ResolvedGroup) -> dict[str, FieldDerivation]:
    out = {}
    for side, g in (("rear", rear), ("front", front)):
        out[f"{side}_track_m"] = FieldDerivation(
            f"{side}_track_m", g.track_m, "m", "given", "track as given", f"{g.path}.track_m", f"{g.path}.track_m"
        )
        out[f"{side}_axle_width_m"] = FieldDerivation(
            f"{side}_axle_width_m",
            g.track_m,
            "m",
            "computed",
            "axle width = track: the tyres stay perpendicular to the axle",
            f"{THESIS}, Sec. 4.1.1",
            f"{g.path}.track_m",
        )
        out[f"{side}_axles"] = FieldDerivation(
            f"{side}_axles", g.axles, "count", "given", "axles as given", f"{g.path}.axles", f"{g.path}.axles"
        )
        name = f"{side}_tires_per_axle"
        out[name] = FieldDerivation(
            name,
            g.tyres_per_axle,
            "count",
            "given",
            "tyres per axle as given",
            f"{g.path}.tyres_per_axle",
            f"{g.path}.tyres_per_axle",
        )
    path = "spec.rear.centre_from_kingpin_m"
    if spec.rear.centre_from_kingpin_m is None:
        raise InvalidVehicle(f"{path} (the wheelbase L) is required", field=path)
    wheelbase = check_number(spec.rear.centre_from_kingpin_m, path)
    out["wheelbase_m"] = FieldDerivation(
        "wheelbase_m",
        wheelbase,
        "m",
        "given",
        "L = rear group centre behind the kingpin (truck: front group)",
        path,
        path,
    )
    path, name = "spec.front.centre_from_kingpin_m", "fifth_wheel_to_front_axle_m"
    value, source = _front_defaults(spec.unit_type)[name]
    given = spec.front.centre_from_kingpin_m
    if spec.unit_type == "rigid-truck":
        if given not in (None, 0, 0.0):
            raise InvalidVehicle(
                f"{path} must be 0 or absent for a rigid truck: its front group is the reference",
                field=path,
                value=given,
            )
        out[name] = FieldDerivation(name, 0.0, "m", "default", "l13 = 0", source, path)
    elif given is None:
        out[name] = FieldDerivation(name, value, "m", "default", "l13 default", source, path)
    else:
        l13 = check_number(given, path, minimum=-math.inf)
        out[name] = FieldDerivation(name, l13, "m", "given", "l13 = front group centre behind the kingpin", path, path)
    return out


def _composite(items: Sequence[MassItem]) -> tuple[float, float, float]:
    mass = sum(i.mass_kg for i in items)
    z = sum(i.mass_kg * i.cg_height_m for i in items) / mass
    x = sum(i.mass_kg * i.cg_from_kingpin_m for i in items) / mass
    return mass, z, x


def _mass_fields(
    items: Sequence[MassItem], comp: dict[str, FieldDerivation], wheelbase: float
) -> dict[str, FieldDerivation]:
    mass, z, x = _composite(items)
    lr, ls = comp["rolling_radius_m"].value, comp["suspension_height_m"].value
    terms = " + ".join(f"{i.mass_kg:g}" for i in items)
    chassis = lr + ls
    l12 = z - chassis
    worst = max(items, key=lambda i: i.mass_kg) if items else None
    if not l12 > 0:
        raise InvalidVehicle(
            f"the composite CG ({z:.3f} m above the ground) is not above the chassis reference lr + ls = "
            f"{chassis:.3f} m, so l12 = h - (lr + ls) = {l12:.3f} m; the model's CG sits on the sprung body",
            field="spec.tare.cg_height_m" if worst is None or worst.name == "tare" else f"spec.{worst.name}",
            value=z,
        )
    if not 0 < x < wheelbase:
        offender = max(items, key=lambda i: abs(i.cg_from_kingpin_m - wheelbase / 2))
        path = "spec.tare.cg_from_kingpin_m" if offender.name == "tare" else f"spec.{offender.name}"
        raise InvalidVehicle(
            f"the composite CG lies {x:.3f} m behind the kingpin, outside (0, L = {wheelbase:g} m): the model needs "
            "the CG between the kingpin (front group) and the rear group centre (Eq. 4.27 with both loads positive)",
            field=path,
            value=x,
        )
    return {
        "weight_kn": FieldDerivation(
            "weight_kn",
            mass * G_M_PER_S2 / 1000.0,
            "kN",
            "computed",
            f"W = ({terms}) kg x {G_M_PER_S2} m/s^2",
            f"masses of spec.tare and spec.payloads; g = {G_M_PER_S2}",
            "spec.tare.mass_kg",
        ),
        "cg_height_above_chassis_m": FieldDerivation(
            "cg_height_above_chassis_m",
            l12,
            "m",
            "computed",
            f"l12 = h - (lr + ls) = {z:.4f} - ({lr:g} + {ls:g}), h = sum(m z)/sum(m)",
            "engine.vehicle.record.cg_height_m: h = lr + ls + l12",
            "spec.tare.cg_height_m",
        ),
        "front_axle_to_cg_m": FieldDerivation(
            "front_axle_to_cg_m",
            x,
            "m",
            "computed",
            f"a = sum(m x)/sum(m) = {x:.4f}",
            "CG positions of spec.tare and spec.payloads",
            "spec.tare.cg_from_kingpin_m",
        ),
    }


def _check_ratings(
    front: ResolvedGroup,
    rear: ResolvedGroup,
    group_loads: dict[str, float],
    payloads: Sequence[PayloadSpec],
    unit_type: str,
) -> None:
    blame = "spec.payloads[0].mass_kg" if payloads else "spec.tare.mass_kg"
    for g, key in ((rear, "rear"), (front, "front")):
        load = group_loads[key]
        what = "the kingpin load alone" if key == "front" and unit_type in TRAILER_TYPES else f"the {key} group's load"
        if g.rated_load_kg is not None and load > g.rated_load_kg:
            raise InvalidVehicle(
                f"{what} at rest, {load:.0f} kg (lever rule, Eq. 4.27), exceeds {g.path}.rated_load_kg = "
                f"{g.rated_load_kg:g} kg: the payload is above the group's rating",
                field=blame,
                value=load,
            )
        if g.tyre_rated_load_kg is not None:
            per_tyre = load / (g.axles * g.tyres_per_axle)
            if per_tyre > g.tyre_rated_load_kg:
                raise InvalidVehicle(
                    f"each {key} tyre carries {per_tyre:.0f} kg at rest (from {what}), above "
                    f"the tyre rating of {g.tyre_rated_load_kg:g} kg ({g.path}.tyre)",
                    field=blame,
                    value=per_tyre,
                )


def build_vehicle(spec: VehicleSpec) -> BuiltVehicle:
    """The engine's vehicle record for a measurable spec, with the derivation of every field.

    Parameters
    ----------
    spec : the vehicle in measurable terms (:class:`VehicleSpec`)

    Returns
    -------
    BuiltVehicle with ``vehicle`` (validated by :func:`engine.vehicle.validate_vehicle` for the 3D model),
    ``derivation`` (every record field), ``masses``, the composite CG and the static group loads [kg].

    Raises
    ------
    InvalidVehicle : an input is missing, impossible or inconsistent; ``field`` is its dotted spec path
        (``spec.payloads[1].load_height_m``), errors on a derived record field point at the input behind it.
    """
    if not isinstance(spec, VehicleSpec):
        raise InvalidVehicle("spec must be a VehicleSpec", field="spec", value=spec)
    check_choice(spec.unit_type, "spec.unit_type", UNIT_TYPES)
    check_spec_plausible(spec)  # every typed number in its plausible range first, blamed on itself (unit slips)
    rear, front = resolve_group(spec.rear, "spec.rear"), resolve_group(spec.front, "spec.front")
    comp, notes = component_fields(rear, front)
    for g in (rear, front):
        check_width(g, comp["spring_separation_m"].value)
    derivation = {**comp, **_geometry_fields(spec, rear, front), **_front_unit_fields(spec)}
    wheelbase = derivation["wheelbase_m"].value
    deck = spec.deck
    if deck is not None:
        deck = DeckSpec(
            check_number(deck.front_from_kingpin_m, "spec.deck.front_from_kingpin_m", minimum=-math.inf),
            check_number(deck.length_m, "spec.deck.length_m"),
        )
    payloads = tuple(spec.payloads or ())
    loads = tuple(payload_item(p, deck, f"spec.payloads[{i}]") for i, p in enumerate(payloads))
    deck_heights = [p.deck_height_m for p in payloads if p.deck_height_m is not None]  # validated by payload_item
    tare, note = tare_item(spec.tare, deck_heights, wheelbase)
    notes += [note] if note else []
    items = (tare, *loads)
    derivation.update(_mass_fields(items, comp, wheelbase))
    mass, z, x = _composite(items)
    group_loads = {"front": mass * (wheelbase - x) / wheelbase, "rear": mass * x / wheelbase}  # Eq. 4.27 at rest
    _check_ratings(front, rear, group_loads, payloads, spec.unit_type)
    if spec.rear.axle_spacing_m is not None or spec.front.axle_spacing_m is not None:
        notes.append("axle spacing is recorded but not used: the model has one equivalent axle per group (Figs. 41-43)")
    vehicle = Vehicle(**{name: d.value for name, d in derivation.items()})
    _validate_record(vehicle, derivation)
    return BuiltVehicle(vehicle, derivation, items, mass, z, x, group_loads, tuple(notes))


def _validate_record(vehicle: Vehicle, derivation: dict[str, FieldDerivation]) -> None:
    """engine.vehicle.validate_vehicle on the record; its errors re-pointed at the spec input behind the field."""
    try:
        get_model("3d").validate(vehicle)
    except InvalidVehicle as exc:
        d = derivation.get(exc.field or "")
        path = d.spec_path if d is not None and d.spec_path else f"record.{exc.field}"
        raise InvalidVehicle(f"{exc} (record field {exc.field}, from {path})", field=path, value=exc.value) from exc

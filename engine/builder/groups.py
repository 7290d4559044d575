"""Axle groups of a spec: their tyres and suspensions resolved from the component library or given data."""

from __future__ import annotations

import math
from dataclasses import dataclass

from engine.builder.spec import (
    AxleGroupSpec,
    FieldDerivation,
    SuspensionSpec,
    TyreSpec,
    check_count,
    check_number,
)
from engine.errors import InvalidVehicle
from engine.vehicle.components import (
    Sourced,
    get_suspension,
    get_tyre,
    parse_tyre_size,
    rated_load_from_load_index_kg,
    spring_rate_from_roll_stiffness,
)
from engine.vehicle.record import FIELD_DOCS

# -------------------------------------------------------------------------------------- components


@dataclass(frozen=True)
class _Value:
    value: float
    method: str
    explanation: str
    source: str
    path: str


@dataclass(frozen=True)
class ResolvedGroup:
    """A resolved axle group: counts, track and the component values with their provenance."""

    path: str
    axles: int
    tyres_per_axle: int
    track_m: float
    lr: _Value | None
    kt: _Value | None
    kls: _Value | None
    ls: _Value | None
    b: _Value | None
    section_width_m: float | None
    tyre_rated_load_kg: float | None
    rated_load_kg: float | None


def _pick(explicit: object, library: Sourced | None, path: str, lib_path: str, name: str) -> _Value | None:
    if explicit is not None:
        return _Value(check_number(explicit, path), "given", f"{name} as given", path, path)
    if library is not None:
        return _Value(library.value, "library", f"{name} from the component library", library.source, lib_path)
    return None


def _resolve_tyre(
    spec: TyreSpec, path: str, tyres_per_axle: int
) -> tuple[_Value | None, _Value | None, float | None, float | None]:
    entry = get_tyre(spec.id, field=f"{path}.id") if spec.id is not None else None
    lib_path = f"{path}.id"
    lr = _pick(spec.loaded_radius_m, entry and entry.loaded_radius_m, f"{path}.loaded_radius_m", lib_path, "lr")
    kt = _pick(
        spec.stiffness_kn_per_m, entry and entry.stiffness_kn_per_m, f"{path}.stiffness_kn_per_m", lib_path, "kT"
    )
    size = parse_tyre_size(spec.size, field=f"{path}.size") if spec.size is not None else None
    if size is None and entry is not None and entry.size is not None:
        size = parse_tyre_size(entry.size, field=lib_path)
    width = check_number(spec.section_width_m, f"{path}.section_width_m") if spec.section_width_m is not None else None
    if width is None and size is not None:
        width = size.section_width_m
    if lr is not None and size is not None:
        _check_loaded_radius(lr.value, size, lr.path)
    rated = spec.rated_load_kg
    if spec.load_index is not None:
        if rated is not None:
            raise InvalidVehicle(
                f"give either {path}.rated_load_kg or {path}.load_index, not both",
                field=f"{path}.load_index",
                value=spec.load_index,
            )
        rated = rated_load_from_load_index_kg(spec.load_index, tyres_per_axle, field=f"{path}.load_index")
    if rated is None and entry is not None and entry.rated_load_kg is not None:
        rated = entry.rated_load_kg.value
    rated = check_number(rated, f"{path}.rated_load_kg") if rated is not None else None
    return lr, kt, width, rated


def _check_loaded_radius(lr: float, size, path: str) -> None:
    if lr <= size.rim_radius_m:
        raise InvalidVehicle(
            f"{path} = {lr:g} m is not above the rim radius of a {size.designation} tyre ({size.rim_radius_m:.4f} m)",
            field=path,
            value=lr,
        )
    free = size.nominal_free_radius_m
    if free is not None and lr >= free:
        raise InvalidVehicle(
            f"{path} = {lr:g} m is not below the nominal unloaded radius of a {size.designation} tyre "
            f"({free:.4f} m = rim/2 + width x aspect ratio): a loaded tyre is deflected",
            field=path,
            value=lr,
        )


def _resolve_suspension(spec: SuspensionSpec, path: str) -> tuple[_Value | None, _Value | None, _Value | None]:
    entry = get_suspension(spec.type, field=f"{path}.type") if spec.type is not None else None
    lib_path = f"{path}.type"
    ls = _pick(spec.height_m, entry and entry.height_m, f"{path}.height_m", lib_path, "ls")
    b = _pick(
        spec.spring_separation_m, entry and entry.spring_separation_m, f"{path}.spring_separation_m", lib_path, "b"
    )
    if spec.roll_stiffness_knm_per_rad is not None:
        roll_path = f"{path}.roll_stiffness_knm_per_rad"
        if spec.stiffness_kn_per_m is not None:
            raise InvalidVehicle(
                f"give either {path}.stiffness_kn_per_m or {roll_path}, not both (Eq. 2.11 ties them through b)",
                field=roll_path,
                value=spec.roll_stiffness_knm_per_rad,
            )
        k_theta = check_number(spec.roll_stiffness_knm_per_rad, roll_path)
        if b is None:
            raise InvalidVehicle(f"{roll_path} needs the spring separation b", field=f"{path}.spring_separation_m")
        kls = _Value(
            spring_rate_from_roll_stiffness(k_theta, b.value),
            "computed",
            f"kLs = 2 k_theta / b^2 = 2 x {k_theta:g} / {b.value:g}^2 (Eq. 2.11)",
            f"{roll_path}; Eq. 2.11",
            roll_path,
        )
    else:
        kls = _pick(
            spec.stiffness_kn_per_m, entry and entry.stiffness_kn_per_m, f"{path}.stiffness_kn_per_m", lib_path, "kLs"
        )
    return kls, ls, b


def resolve_group(spec: AxleGroupSpec, path: str) -> ResolvedGroup:
    if not isinstance(spec, AxleGroupSpec):
        raise InvalidVehicle(f"{path} must be an axle group", field=path, value=spec)
    lr = kt = kls = ls = b = None
    width = tyre_rated = None
    tyres_per_axle = check_count(spec.tyres_per_axle, f"{path}.tyres_per_axle", (2, 4))
    if spec.tyre is not None:
        lr, kt, width, tyre_rated = _resolve_tyre(spec.tyre, f"{path}.tyre", tyres_per_axle)
    if spec.suspension is not None:
        kls, ls, b = _resolve_suspension(spec.suspension, f"{path}.suspension")
    if spec.axle_spacing_m is not None:
        check_number(spec.axle_spacing_m, f"{path}.axle_spacing_m")
    rated = check_number(spec.rated_load_kg, f"{path}.rated_load_kg") if spec.rated_load_kg is not None else None
    return ResolvedGroup(
        path=path,
        axles=check_count(spec.axles, f"{path}.axles"),
        tyres_per_axle=tyres_per_axle,
        track_m=check_number(spec.track_m, f"{path}.track_m"),
        lr=lr,
        kt=kt,
        kls=kls,
        ls=ls,
        b=b,
        section_width_m=width,
        tyre_rated_load_kg=tyre_rated,
        rated_load_kg=rated,
    )


_COMPONENTS = (  # record field, ResolvedGroup attribute, the input to name, what else would do
    ("rolling_radius_m", "lr", "tyre.loaded_radius_m", "or tyre.id"),
    ("tire_stiffness_kn_per_m", "kt", "tyre.stiffness_kn_per_m", "or tyre.id"),
    ("suspension_stiffness_kn_per_m", "kls", "suspension.stiffness_kn_per_m", "roll_stiffness_knm_per_rad or type"),
    ("suspension_height_m", "ls", "suspension.height_m", "or suspension.type"),
    ("spring_separation_m", "b", "suspension.spring_separation_m", "or suspension.type"),
)


def component_fields(rear: ResolvedGroup, front: ResolvedGroup) -> tuple[dict[str, FieldDerivation], list[str]]:
    """The record's shared component fields, from the rear group; notes where the front group differs."""
    out: dict[str, FieldDerivation] = {}
    notes = []
    for name, attr, what, alternative in _COMPONENTS:
        v: _Value | None = getattr(rear, attr)
        if v is None:
            raise InvalidVehicle(
                f"{name} ({FIELD_DOCS[name].symbol}) is unknown: give {rear.path}.{what}, {alternative}",
                field=f"{rear.path}.{what}",
            )
        out[name] = FieldDerivation(name, v.value, FIELD_DOCS[name].unit, v.method, v.explanation, v.source, v.path)
        f: _Value | None = getattr(front, attr)
        if f is not None and not math.isclose(f.value, v.value, rel_tol=1e-9):
            notes.append(
                f"{name}: the front group's {f.value:g} {FIELD_DOCS[name].unit} ({f.path}) differs from the rear "
                f"group's {v.value:g}; the record has one value for both groups and keeps the rear group's (the "
                "unit's own group, whose inner tyre lift-off is the limit)"
            )
    return out, notes


def check_width(group: ResolvedGroup, b: float) -> None:
    """Springs inboard of the inner tyres: b < track - (tyres per side) x section width (duals touching)."""
    if group.section_width_m is None:
        return
    per_side = group.tyres_per_axle // 2
    inner = group.track_m - per_side * group.section_width_m
    if not b < inner:
        raise InvalidVehicle(
            f"{group.path}.track_m = {group.track_m:g} m leaves {inner:.3f} m between the inner tyres "
            f"({per_side} tyre(s) of {group.section_width_m:.3f} m per side), not more than the spring separation "
            f"b = {b:g} m: the springs must sit inboard of the tyres",
            field=f"{group.path}.track_m",
            value=group.track_m,
        )

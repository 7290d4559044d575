"""Vehicles: the parameter record, the thesis presets, the component library and the builder.

- :mod:`~engine.vehicle.record`: :class:`Vehicle` (every field in :data:`FIELD_DOCS` with unit, symbol, bounds)
  and its validation;
- :mod:`~engine.vehicle.presets`: the vehicles of Tables 14, 15, 16, 22 and 23;
- :mod:`~engine.vehicle.components`: tyres and suspensions, each value with its source;
- :mod:`~engine.vehicle.builder` (imported on its own: it builds on the models): a vehicle from what can be
  measured -> the record and its derivation.
"""

from .components import (
    INCH_M,
    LOAD_INDEX_KG,
    NOT_FOUND,
    SUSPENSIONS,
    TYRES,
    Sourced,
    SuspensionEntry,
    TyreEntry,
    TyreSize,
    get_suspension,
    get_tyre,
    library_sources,
    parse_load_index,
    parse_tyre_size,
    rated_load_from_load_index_kg,
    roll_stiffness_from_spring_rate,
    spring_rate_from_roll_stiffness,
    static_loaded_radius_m,
)
from .presets import (
    PRESET_INFO,
    PRESETS,
    PresetInfo,
    get_preset,
)
from .record import (
    FIELD_DOCS,
    FIFTH_WHEEL_FIELDS,
    MAX_CHASSIS_TWIST_RAD,
    MAX_STATIC_DEFLECTION_RATIO,
    MAX_STIFFNESS_KN_PER_M,
    MAX_VEHICLE_HEIGHT_M,
    MAX_VEHICLE_WIDTH_M,
    TRACK_TOLERANCE_M,
    FieldDoc,
    GroupStiffness,
    Vehicle,
    cg_height_m,
    group_stiffness,
    static_axle_loads,
    validate_group,
    validate_vehicle,
)

__all__ = [
    "FIELD_DOCS",
    "FIFTH_WHEEL_FIELDS",
    "INCH_M",
    "LOAD_INDEX_KG",
    "MAX_CHASSIS_TWIST_RAD",
    "MAX_STATIC_DEFLECTION_RATIO",
    "MAX_STIFFNESS_KN_PER_M",
    "MAX_VEHICLE_HEIGHT_M",
    "MAX_VEHICLE_WIDTH_M",
    "NOT_FOUND",
    "PRESETS",
    "PRESET_INFO",
    "SUSPENSIONS",
    "TRACK_TOLERANCE_M",
    "TYRES",
    "FieldDoc",
    "GroupStiffness",
    "PresetInfo",
    "Sourced",
    "SuspensionEntry",
    "TyreEntry",
    "TyreSize",
    "Vehicle",
    "cg_height_m",
    "get_preset",
    "get_suspension",
    "get_tyre",
    "group_stiffness",
    "library_sources",
    "parse_load_index",
    "parse_tyre_size",
    "rated_load_from_load_index_kg",
    "roll_stiffness_from_spring_rate",
    "spring_rate_from_roll_stiffness",
    "static_axle_loads",
    "static_loaded_radius_m",
    "validate_group",
    "validate_vehicle",
]

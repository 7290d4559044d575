"""rollover engine: the static rollover threshold (SRT) of heavy vehicles and the road design that follows from it.

A pure numerical library (numpy, scipy; no I/O, no logging, no global state). Describe a case, solve it::

    from engine import Case, LoadCase, Road, get_preset, rollover_threshold

    case = Case(get_preset("table16-btrain"), road=Road(bank_percent=6), load=LoadCase(lateral_offset_m=0.1))
    result = rollover_threshold(case)
    result.srt, result.roll_angle_deg, result.stage_values["srt_ts"]

Units are SI with forces in kN, except road practice: speeds in km/h, superelevation and grade in %, the SRT in g.

The science is the thesis this project implements:

    Moreno, G. G., *Static rollover threshold of long combination vehicles* (doctoral thesis; a three-dimensional
    mechanism model of the last trailer of a long combination vehicle, solved statically by the Davies method;
    published in part as Moreno, Nicolazzi, Vieira and Martins, IFToMM 2015 and Road Safety on Five Continents
    2016). Equation, table and figure numbers in this package's docstrings ("Eq. 6.18", "Table 16") are the
    thesis's.

Storeys (each package imports only the ones below it; ``pyproject.toml`` ``[tool.importlinter]`` holds the
contract, ``docs/architecture.md`` the picture). Each package has a face, its ``__init__``, whose docstring lists what
it exports; the rest of a package is its own:

- :mod:`engine.route`: geodesy, the noise model, circle and line fits, curve detection of surveyed routes;
- :mod:`engine.road`: Eqs. 9.1-9.3, the design standards, superelevation, SRT targets, inverse limits, curve and
  alignment assessment, advisory speeds, road-file geometry; :mod:`engine.dynamics`: the combination in motion, a
  linear yaw-roll model, its manoeuvres and measures, the low-speed turn and the PBS screening (indicative, not a
  certification); :mod:`engine.builder`: a vehicle from what can be measured
  (:func:`~engine.builder.build_vehicle`), a whole combination from what can be measured of each unit
  (:func:`~engine.builder.build_combination`);
- :mod:`engine.models`: the model registry, spring laws, axle groups, the 2D and 3D models, the closed forms, load
  stepping, the whole-combination model and the SRT entry points;
- :mod:`engine.case` (:class:`Case`, :class:`Road`, :class:`LoadCase`) and :mod:`engine.results`;
- :mod:`engine.vehicle`: the vehicle record, the presets, the component library, combinations;
  :mod:`engine.mechanics`: screw theory and the generic Davies statics (knows nothing of vehicles);
- :mod:`engine.domain` (the bounds of every scalar input), :mod:`engine.bracket`, and at the bottom
  :mod:`engine.errors`.

Exports (``__all__``: the library's documented API, by concept):

The case

- ``Case``: one vehicle on one road under one load case, what every solve takes;
- ``Road``: the road's bank and grade; ``LoadCase``: the load's lateral offset and the stage; ``STAGES``: the stages
  of a case (the vehicle's combination stages of Table 16);
- ``Vehicle``: the thesis's parameter record; ``FIELD_DOCS``: each field's unit, symbol, bounds and meaning;
  ``validate_vehicle``: a record's checks, the error naming the field;
- ``PRESETS``, ``PRESET_INFO``, ``get_preset``: the thesis's vehicles (Tables 14, 15, 16, 22, 23), their titles,
  one by id;
- ``Combination``, ``Unit``, ``AxleGroup``, ``Coupling``: a whole combination as its units, axle groups and couplings;
  ``validate_combination``: its checks; ``COMBINATIONS``, ``COMBINATION_INFO``, ``get_combination``: the combination
  presets, their titles, one by id (``Case(get_combination("btrain-table16"))`` solves it with the whole-combination
  model);
- ``BOUNDS``: the accepted range of every scalar input; ``DEFAULT_CURVE_POINTS``, ``MAX_CURVE_POINTS``: the points of a
  result's curves by default and at most.

The SRT

- ``rollover_threshold``: one case; ``rollover_thresholds``: many, each with its full result; ``evaluate_cases``: many
  cases of one vehicle, SRT and roll only; ``sweep``, ``SWEEP_AXES``, ``SweepResult``: grids (Tables 17 and 19);
- ``MODELS``, ``Model``, ``get_model``, ``supported_models``: the model registry, one model, the models a record
  supports.

The results

- ``RolloverResult``: an SRT with its roll angle, stage values, tyre loads and curves; ``Curves``: the load-stepping
  curves; ``TireLoads``: the tyre loads at the limit.

Road design

- ``DEFAULT_TARGETS``, ``TargetCheck``, ``check_targets``: SRT targets; ``tilt_table_angle_deg``: the tilt-table angle
  of an SRT;
- ``LIMIT_PARAMETERS``, ``Limit``, ``LimitTableRow``, ``parameter_limit``, ``limit_table``: inverse limits (the
  largest payload, CG height, ... that still meets a target);
- ``Curve``, ``CurveAssessment``, ``AlignmentAssessment``, ``assess_curves``: the safe speed on every curve;
- ``max_curve_speed_kmh``, ``rollover_min_radius_m``, ``aashto_min_radius_m``: Eqs. 9.1-9.3; ``min_radius``,
  ``MinRadius``: both minimum radii and the governing one; ``side_friction_factor``, ``side_friction_speed_kmh``: the
  design standards' side friction.

The errors (each names the offending field)

- ``RolloverError``: the base of them all; ``InvalidInput``, ``InvalidVehicle``, ``InvalidRoad``, ``InvalidLoad``,
  ``MissingParameter``, ``UnknownPreset``: bad input; ``ConvergenceError``, ``MechanismSingular``: a solve that
  cannot finish.

The version

- ``ENGINE_VERSION``: bumped whenever a change can alter a number the engine returns (part of every cache key).
"""

#: bumped whenever a change can alter a number the engine returns (it is part of every cache key)
ENGINE_VERSION = "1.8.0"
__version__ = ENGINE_VERSION

from engine.case import STAGES, Case, LoadCase, Road  # noqa: E402
from engine.domain import BOUNDS, DEFAULT_CURVE_POINTS, MAX_CURVE_POINTS  # noqa: E402
from engine.errors import (  # noqa: E402
    ConvergenceError,
    InvalidInput,
    InvalidLoad,
    InvalidRoad,
    InvalidVehicle,
    MechanismSingular,
    MissingParameter,
    RolloverError,
    UnknownPreset,
)
from engine.models import (  # noqa: E402
    MODELS,
    SWEEP_AXES,
    Model,
    SweepResult,
    evaluate_cases,
    get_model,
    rollover_threshold,
    rollover_thresholds,
    supported_models,
    sweep,
)
from engine.results import Curves, RolloverResult, TireLoads  # noqa: E402
from engine.road import (  # noqa: E402
    DEFAULT_TARGETS,
    LIMIT_PARAMETERS,
    AlignmentAssessment,
    Curve,
    CurveAssessment,
    Limit,
    LimitTableRow,
    MinRadius,
    TargetCheck,
    aashto_min_radius_m,
    assess_curves,
    check_targets,
    limit_table,
    max_curve_speed_kmh,
    min_radius,
    parameter_limit,
    rollover_min_radius_m,
    side_friction_factor,
    side_friction_speed_kmh,
    tilt_table_angle_deg,
)
from engine.vehicle import (  # noqa: E402
    COMBINATION_INFO,
    COMBINATIONS,
    FIELD_DOCS,
    PRESET_INFO,
    PRESETS,
    AxleGroup,
    Combination,
    Coupling,
    Unit,
    Vehicle,
    get_combination,
    get_preset,
    validate_combination,
    validate_vehicle,
)

__all__ = [
    "BOUNDS",
    "COMBINATIONS",
    "COMBINATION_INFO",
    "DEFAULT_CURVE_POINTS",
    "DEFAULT_TARGETS",
    "ENGINE_VERSION",
    "FIELD_DOCS",
    "LIMIT_PARAMETERS",
    "MAX_CURVE_POINTS",
    "MODELS",
    "PRESETS",
    "PRESET_INFO",
    "STAGES",
    "SWEEP_AXES",
    "AlignmentAssessment",
    "AxleGroup",
    "Case",
    "Combination",
    "ConvergenceError",
    "Coupling",
    "Curve",
    "CurveAssessment",
    "Curves",
    "InvalidInput",
    "InvalidLoad",
    "InvalidRoad",
    "InvalidVehicle",
    "Limit",
    "LimitTableRow",
    "LoadCase",
    "MechanismSingular",
    "MinRadius",
    "MissingParameter",
    "Model",
    "Road",
    "RolloverError",
    "RolloverResult",
    "SweepResult",
    "TargetCheck",
    "TireLoads",
    "Unit",
    "UnknownPreset",
    "Vehicle",
    "aashto_min_radius_m",
    "assess_curves",
    "check_targets",
    "evaluate_cases",
    "get_combination",
    "get_model",
    "get_preset",
    "limit_table",
    "max_curve_speed_kmh",
    "min_radius",
    "parameter_limit",
    "rollover_min_radius_m",
    "rollover_threshold",
    "rollover_thresholds",
    "side_friction_factor",
    "side_friction_speed_kmh",
    "supported_models",
    "sweep",
    "tilt_table_angle_deg",
    "validate_combination",
    "validate_vehicle",
]

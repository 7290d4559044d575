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

Layout (each subpackage has its own ``__all__``; the names below are re-exported here):

- :mod:`engine.mechanics`: screw theory and the generic Davies statics (knows nothing of vehicles);
- :mod:`engine.models`: the model registry, spring laws, axle groups, the 2D and 3D models, the closed forms, load
  stepping and the SRT entry points;
- :mod:`engine.vehicle`: the vehicle record, the presets, the component library; :mod:`engine.builder`
  (a vehicle from what can be measured, :func:`~engine.builder.build_vehicle`; a whole combination from
  what can be measured of each unit, :func:`~engine.builder.build_combination`);
- :mod:`engine.road`: Eqs. 9.1-9.3, the design standards, superelevation, SRT targets, inverse limits, curve and
  alignment assessment;
- :mod:`engine.route`: geodesy, the noise model, circle and line fits, curve detection of surveyed routes;
- :mod:`engine.dynamics`: the combination in motion, a linear yaw-roll model, its manoeuvres and measures, the
  low-speed turn and the PBS screening (indicative, not a certification);
- :mod:`engine.case` (:class:`Case`, :class:`Road`, :class:`LoadCase`), :mod:`engine.results`,
  :mod:`engine.errors`, :mod:`engine.domain` (the bounds of every scalar input) and :mod:`engine.bracket`.

Public surface (everything in ``__all__``):

- the case: :class:`Vehicle` (the record, :data:`FIELD_DOCS`), :data:`PRESETS` / :func:`get_preset`, :class:`Road`,
  :class:`LoadCase`, :class:`Case`; a :class:`Combination` of :class:`Unit` s, :class:`AxleGroup` s and
  :class:`Coupling` s, :data:`COMBINATIONS` / :func:`get_combination` (``Case(get_combination("btrain-table16"))``
  solves it with the whole-combination model);
- the SRT: :func:`rollover_threshold` (one case), :func:`rollover_thresholds` (many, each with its full result),
  :func:`evaluate_cases`, :func:`sweep` (grids, Tables 17 and 19),
  the model registry :data:`MODELS`;
- the road-design tools: targets and the tilt-table angle, inverse limits (:func:`parameter_limit`,
  :func:`limit_table`), curve assessment (:func:`assess_curves`), and the road formulas of Ch. 9
  (:func:`max_curve_speed_kmh`, :func:`min_radius`, ...);
- the results (:class:`RolloverResult`, :class:`Curves`, ...) and the errors (:class:`RolloverError` and its
  subclasses, each naming the offending ``field``).
"""

#: bumped whenever a change can alter a number the engine returns (it is part of every cache key)
ENGINE_VERSION = "1.7.0"
__version__ = ENGINE_VERSION

from engine.case import STAGES, Case, LoadCase, Road  # noqa: E402
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
from engine.models.registry import MODELS, Model, get_model, supported_models  # noqa: E402
from engine.models.threshold import (  # noqa: E402
    SWEEP_AXES,
    SweepResult,
    evaluate_cases,
    rollover_threshold,
    rollover_thresholds,
    sweep,
)
from engine.results import Curves, RolloverResult, TireLoads  # noqa: E402
from engine.road.curves import AlignmentAssessment, Curve, CurveAssessment, assess_curves  # noqa: E402
from engine.road.formulas import aashto_min_radius_m, max_curve_speed_kmh, rollover_min_radius_m  # noqa: E402
from engine.road.limits import LIMIT_PARAMETERS, Limit, LimitTableRow, limit_table, parameter_limit  # noqa: E402
from engine.road.min_radius import MinRadius, min_radius  # noqa: E402
from engine.road.standards import side_friction_factor, side_friction_speed_kmh  # noqa: E402
from engine.road.targets import DEFAULT_TARGETS, TargetCheck, check_targets, tilt_table_angle_deg  # noqa: E402
from engine.vehicle.combination import (  # noqa: E402
    AxleGroup,
    Combination,
    Coupling,
    Unit,
    validate_combination,
)
from engine.vehicle.combination_presets import COMBINATION_INFO, COMBINATIONS, get_combination  # noqa: E402
from engine.vehicle.presets import PRESET_INFO, PRESETS, get_preset  # noqa: E402
from engine.vehicle.record import FIELD_DOCS, Vehicle, validate_vehicle  # noqa: E402

__all__ = [
    "COMBINATIONS",
    "COMBINATION_INFO",
    "DEFAULT_TARGETS",
    "ENGINE_VERSION",
    "FIELD_DOCS",
    "LIMIT_PARAMETERS",
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

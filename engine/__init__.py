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

Public surface (everything in ``__all__``):

- the case: :class:`Vehicle` (the record, :data:`FIELD_DOCS`), :data:`PRESETS` / :func:`get_preset`, :class:`Road`,
  :class:`LoadCase`, :class:`Case`;
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
ENGINE_VERSION = "1.2.0"
__version__ = ENGINE_VERSION

from .assessment import (  # noqa: E402
    DEFAULT_TARGETS,
    LIMIT_PARAMETERS,
    AlignmentAssessment,
    Curve,
    CurveAssessment,
    Limit,
    LimitTableRow,
    TargetCheck,
    assess_curves,
    check_targets,
    limit_table,
    parameter_limit,
    tilt_table_angle_deg,
)
from .case import STAGES, Case  # noqa: E402
from .errors import (  # noqa: E402
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
from .loads import LoadCase, Road  # noqa: E402
from .models import MODELS, Model, get_model, supported_models  # noqa: E402
from .results import Curves, RolloverResult, TireLoads  # noqa: E402
from .road import (  # noqa: E402
    MinRadius,
    aashto_min_radius_m,
    max_curve_speed_kmh,
    min_radius,
    rollover_min_radius_m,
    side_friction_factor,
    side_friction_speed_kmh,
)
from .threshold import (  # noqa: E402
    SWEEP_AXES,
    SweepResult,
    evaluate_cases,
    rollover_threshold,
    rollover_thresholds,
    sweep,
)
from .vehicles import FIELD_DOCS, PRESET_INFO, PRESETS, Vehicle, get_preset, validate_vehicle  # noqa: E402

__all__ = [
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
    "Case",
    "ConvergenceError",
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
    "UnknownPreset",
    "Vehicle",
    "aashto_min_radius_m",
    "assess_curves",
    "check_targets",
    "evaluate_cases",
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
    "validate_vehicle",
]

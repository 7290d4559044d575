"""Road design on the SRT: the formulas of Ch. 9, the design standards and the assessment of curves.

- :mod:`~engine.road.formulas`: Eqs. 9.1-9.3 and Table 21 (imports nothing of the rest of the engine);
- :mod:`~engine.road.standards`: AASHTO 2018, DNIT 1999, the thesis's Table 21: f_max and side-friction speeds;
- :mod:`~engine.road.min_radius`: the minimum radius, Eq. 9.2 against Eq. 9.3, and the standards' minimum radii;
- :mod:`~engine.road.superelevation`: the standards' superelevation distributions;
- :mod:`~engine.road.targets`: SRT targets and the tilt-table angle;
- :mod:`~engine.road.limits`: inverse limits (the largest payload, CG height, ... that still meets a target);
- :mod:`~engine.road.curves`: the safe speed on every curve of an alignment;
- :mod:`~engine.road.advisory`: advisory speeds, the sign treatment and the truck rollover warning (W1-13);
- :mod:`~engine.road.profile`: a truck's speed profile along the curves (braking into, accelerating out of them).
"""

from .curves import (
    GOVERNED_BY,
    AlignmentAssessment,
    AlignmentColumns,
    Curve,
    CurveAssessment,
    assess_alignment,
    assess_curves,
    bank_grade_pairs,
    check_columns,
    check_curve,
    solve_bank_grade_pairs,
    superelevation_used,
)
from .formulas import (
    FRICTION_BOUNDS,
    KMH2_PER_M_G,
    MIN_LATERAL_DEMAND,
    TABLE21_F_HIGH,
    TABLE21_F_LOW,
    TABLE21_SPEEDS_KMH,
    aashto_min_radius_m,
    check_speed,
    max_curve_speed_kmh,
    rollover_min_radius_m,
    side_friction_min_radius_m,
)
from .limits import (
    LIMIT_PARAMETERS,
    Limit,
    LimitTableRow,
    limit_table,
    parameter_limit,
    parameter_range,
    with_parameter,
)
from .min_radius import (
    MinRadius,
    MinRadiusCheck,
    MinRadiusResult,
    meets_min_radius,
    min_radius,
    min_radius_array,
    min_radius_m,
)
from .standards import (
    AASHTO_METHOD,
    DEFAULT_DESIGN_STANDARD,
    DNIT_METHOD,
    E_MAX_LIMIT_PERCENT,
    STANDARDS,
    DesignStandard,
    SideFrictionSpeed,
    check_design_speeds,
    check_e_max,
    check_radii,
    get_standard,
    resolve_standard,
    side_friction_factor,
    side_friction_speed,
    side_friction_speed_kmh,
)
from .superelevation import (
    SuperelevationResult,
    SuperelevationTable,
    distribution_min_radius_m,
    superelevation_percent,
    superelevation_table,
)
from .targets import (
    DEFAULT_TARGETS,
    TargetCheck,
    check_targets,
    tilt_table_angle_deg,
)

__all__ = [
    "AASHTO_METHOD",
    "DEFAULT_DESIGN_STANDARD",
    "DEFAULT_TARGETS",
    "DNIT_METHOD",
    "E_MAX_LIMIT_PERCENT",
    "FRICTION_BOUNDS",
    "GOVERNED_BY",
    "KMH2_PER_M_G",
    "LIMIT_PARAMETERS",
    "MIN_LATERAL_DEMAND",
    "STANDARDS",
    "TABLE21_F_HIGH",
    "TABLE21_F_LOW",
    "TABLE21_SPEEDS_KMH",
    "AlignmentAssessment",
    "AlignmentColumns",
    "Curve",
    "CurveAssessment",
    "DesignStandard",
    "Limit",
    "LimitTableRow",
    "MinRadius",
    "MinRadiusCheck",
    "MinRadiusResult",
    "SideFrictionSpeed",
    "SuperelevationResult",
    "SuperelevationTable",
    "TargetCheck",
    "aashto_min_radius_m",
    "assess_alignment",
    "assess_curves",
    "bank_grade_pairs",
    "check_columns",
    "check_curve",
    "check_design_speeds",
    "check_e_max",
    "check_radii",
    "check_speed",
    "check_targets",
    "distribution_min_radius_m",
    "get_standard",
    "limit_table",
    "max_curve_speed_kmh",
    "meets_min_radius",
    "min_radius",
    "min_radius_array",
    "min_radius_m",
    "parameter_limit",
    "parameter_range",
    "resolve_standard",
    "rollover_min_radius_m",
    "side_friction_factor",
    "side_friction_min_radius_m",
    "side_friction_speed",
    "side_friction_speed_kmh",
    "solve_bank_grade_pairs",
    "superelevation_percent",
    "superelevation_table",
    "superelevation_used",
    "tilt_table_angle_deg",
    "with_parameter",
]

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

Exports (the face's ``__all__``, by concept; every other name is the package's own, importable by its
module path for the package and its tests):

From :mod:`~engine.road.advisory`, advisory speeds on horizontal curves: each method's speed, the speed shown on the
plaque, the sign treatment and the truck rollover warning (W1-13):

- ``ADVICE_GOVERNED_BY``: the codes of an advisory speed's governed_by: the method that set it
- ``advise_alignment``: Advisory speed, treatment, W1-13 rule and the truck's speed profile for the curves of one
  alignment and one vehicle: the function the alignment and route answers call per vehicle
- ``advise_curves``: Advisory speed, treatment and W1-13 rule of every curve (arrays; the alignment answers call this)
- ``BALL_BANK_2009``: the 2009 MUTCD ball-bank criterion (Sec. 2C.08), the legacy advisory method
- ``BODY_ROLL_DEG_PER_G``: assumed passenger-car body roll per g of lateral acceleration [deg/g] (the ball-bank reads
  the lateral acceleration plus the body's roll; no source for a value was read, so this one is stated and ...
- ``check_increment``: Refuse an increment that is not the sign's: 5 (mph) with ``us``, 10 (km/h) with ``metric``
- ``DESIGN_METHOD_NOTE``: why the Design Method gives no speed (its model unread: unverified)
- ``displayed_in_units``: A displayed speed [km/h] in the units of the plaque (mph for ``us``, km/h for ``metric``),
  rounded to the increment (removes the conversion's float noise)
- ``kmh_to_mph``: a speed in km/h as mph
- ``method_source``: (source, legacy, verified) of a method id of ``advise_curves``
- ``MIN_DEFLECTION_DEG``: the smallest deflection that justifies curve signs or an advisory speed [deg] (TxDOT 0-5439,
  FHWA-SA-11-22)
- ``ROLLOVER_MARGIN_KMH``: the service's margin below the rollover speed for the W1-13 rule [km/h] (assumed: one metric
  plaque increment; no manual's W1-13 criterion was found)
- ``rollover_warning``: W1-13 recommended (this service's rule): rollover speed - margin < advisory speed shown
- ``SIGN_INCREMENTS``: the sign's increment by unit system: 5 mph (MUTCD: a multiple of 5 mph) or 10 km/h (the metric
  option)
- ``SPEED_RANGE_KMH``: the speeds a posted or tangent speed may take [km/h] (the service's accepted range)
- ``TREATMENT_SOURCE``: the source of the sign treatments, and what of it is unverified
- ``TREATMENTS``: the devices of each sign treatment, by code (0: none)
- ``W1_13_RULE``: the truck rollover warning (W1-13) rule, this service's, with its margin

From :mod:`~engine.road.curves`, curve and alignment assessment: the safe speed on every horizontal curve (Eq. 9.1
against side friction):

- ``AlignmentAssessment``: every curve of an alignment assessed, and the SRT solves it took
- ``AlignmentColumns``: The assessment of every curve of an alignment for one vehicle, as arrays (one entry per curve)
- ``assess_alignment``: Safe speed on every curve of an alignment, on arrays (one entry per curve)
- ``assess_curves``: ``assess_alignment`` for a list of ``Curve`` (one ``CurveAssessment`` each)
- ``bank_grade_pairs``: The distinct (superelevation, grade) pairs of some curves, shape (n, 2), and each curve's index
  into them: one SRT solve per pair (the SRT does not depend on the radius)
- ``check_columns``: The bounds of ``check_curve`` on arrays (nan: a superelevation or posted speed not given)
- ``Curve``: One horizontal curve. grade_percent is signed along the direction of travel (+ uphill); a superelevation of
  None is derived from the design standard's distribution (see ``assess_alignment``)
- ``CurveAssessment``: one curve's SRT, safe speed and what governs it
- ``GOVERNED_BY``: the codes of a curve assessment's governed_by: none, rollover, side friction
- ``solve_bank_grade_pairs``: The SRT of ``case`` on each (superelevation, grade) pair (rows of ``pairs``) in one batch,
  and why a pair has none (``evaluate_arrays``); a pair's SRT does not depend on the others in the batch
- ``superelevation_used``: The superelevation each curve is assessed on by ``assess_alignment``: its own, or (nan) the
  design standard's at its posted speed and ``max_superelevation_percent``, without solving any SRT

From :mod:`~engine.road.formulas`, road-design formulas of Ch. 9: maximum curve speed and minimum curve radius:

- ``aashto_min_radius_m``: deprecated name of ``side_friction_min_radius_m`` (Eq. 9.2 is not only AASHTO's); kept for
  one version
- ``FRICTION_BOUNDS``: the Table 21 side-friction bounds a formula may use: low, mid, high
- ``max_curve_speed_kmh``: Maximum speed on a curve before rollover, V = sqrt(127 SRT R) [km/h] (Eq. 9.1)
- ``rollover_min_radius_m``: Minimum radius against rollover R = V^2 / (127 SRT) [m] (Eq. 9.3), SRT on that bank and
  slope
- ``side_friction_min_radius_m``: Minimum radius by the simplified curve formula R = V^2 / (127 (0.01 e + f)) [m] (Eq.
  9.2)

From :mod:`~engine.road.geometry`, an alignment's geometry as road-design files describe it, in SI units: the horizontal
elements (lines, circular arcs, spirals), stations, the vertical profile and the superelevation:

- ``AlignmentGeometry``: One alignment as read from a file, in SI units (see the module's conventions)
- ``bend_columns``: The alignment's rows, in order of distance (see ``Bend``), as arrays
- ``covers_many``: ``covers`` for many ranges
- ``CrossSlope``: The cross slopes at one distance (LandXML design ``CrossSect``
- ``distance_at``: The distance along [m] of each written station [m] (the inverse of ``station_at``): a station is
  taken in the last station range (between two equations) that contains it, so a station written ...
- ``element_columns``: The alignment's elements as columns (``ElementColumns``), whichever form it holds them in
- ``element_distances``: The distance along the alignment [m] at the start of each element and at the end of the last
  (``n + 1`` values): the cumulative sum of the element lengths, from 0 at the alignment's start
- ``ElementColumns``: An alignment's horizontal elements held as columns, one entry per element: a sequence of
  ``HorizontalElement`` (each made when it is asked for) that the numerics read as arrays (``element_columns``)
- ``grades_over``: ``grade_ranges`` over ``[start_m, end_m]`` and ``grades_at`` at ``at_m`` (the same numbers) from one
  reading of the profile's segments (a long profile has tens of thousands)
- ``HorizontalElement``: One element of the horizontal alignment (LandXML ``Line``/``Curve``/``Spiral``
- ``Profile``: A vertical profile (LandXML ``ProfAlign``
- ``RangeColumns``: Superelevation ranges held as columns, one entry per range: a sequence of ``SuperelevationRange``
  (each made when it is asked for) that ``superelevations`` reads as arrays
- ``RoadFile``: What a reader made of one road-design file: its alignments in SI units and the facts the answer's
  ``reading`` summary reports (``format`` such as ``"LandXML 1.2"`` or ``"IFC4X3_ADD2"``
- ``station_at``: The station as the file writes it [m] at each distance along [m]: the alignment's start station plus
  the distance, restarted at each station equation's ahead station past its distance (an equation ...
- ``SegmentColumns``: A profile's segments held as columns, one entry per segment: a sequence of ``VerticalSegment``
  (each made when it is asked for) that the grades read as arrays
- ``SlopeColumns``: Cross slopes held as columns, one entry per section: a sequence of ``CrossSlope`` (each made when
  it is asked for) that ``superelevations`` reads as arrays
- ``StationEquation``: A station equation (LandXML ``StaEquation``): at ``distance_m`` along the alignment the written
  station jumps from ``station_back_m`` to ``station_ahead_m``
- ``SuperelevationRange``: The full superelevation of a curve between two distances (LandXML ``Superelevation``)
- ``superelevations``: Each row's superelevation [%] from the file and where it came from (0: a ``SuperelevationRange``,
  1: the cross slopes; nan: none, and the value nan)
- ``VerticalSegment``: One piece of the vertical profile over ``[start_distance_m, start_distance_m + length_m]``
  (horizontal length): a constant grade, a parabola (the grade changes linearly from ``start_grade`` to ...

From :mod:`~engine.road.limits`, inverse limits: the largest (smallest) value of one parameter at which the SRT still
meets a target:

- ``Limit``: one parameter's inverse limit at a target
- ``LIMIT_PARAMETERS``: the parameters an inverse limit can be found for, each with its direction
- ``limit_table``: The limit of ``parameter`` for each overweight (TERNZ's table of acceptable mass / load-height pairs)
- ``LimitTableRow``: one overweight step of a limit table
- ``parameter_limit``: The limit of one parameter at which the SRT of ``case`` equals ``target_srt_g`` (Brent's method,
  bracketed)
- ``with_parameter``: The case with one ``LIMIT_PARAMETERS`` entry set to ``value`` (a vehicle field or a load input)

From :mod:`~engine.road.min_radius`, minimum curve radius:

- ``min_radius``: Both minimum radii (Eqs. 9.2 and 9.3) and the governing (larger) one
- ``min_radius_m``: The standard's minimum radius for a design speed and maximum superelevation
- ``MinRadius``: Both minimum radii of a design speed and superelevation, and which governs

From :mod:`~engine.road.profile`, the speed profile of a truck along a sequence of curves: desired speed on the
tangents, braking into each curve at a stated rate, accelerating out of it within the truck's power on the grade, ...:

- ``check_deceleration``: Refuse a deceleration a loaded truck cannot brake at (> NCHRP 774's 15 ft/s^2) or <= 0
- ``DECELERATION_MPS2``: the deceleration into a curve, MUTCD 11e Table 2C-3 basis (as transcribed; unverified) [m/s^2]
- ``MAX_TRUCK_DECELERATION_MPS2``: NCHRP Report 774 (2014), Summary: emergency braking, -15 ft/s^2, the most a truck was
  taken to brake in a curve
- ``REACTION_TIME_S``: the perception-reaction time before braking for a curve [s]

From :mod:`~engine.road.standards`, named road-design standards: side friction, minimum radius and superelevation
distribution:

- ``check_design_speeds``: The design speeds as an array [km/h]
- ``DEFAULT_DESIGN_STANDARD``: the design standard used when none is named
- ``DesignStandard``: A named design standard: its side-friction table, published minimum radii and distribution rule
- ``get_standard``: The design standard with this id, at a Table 21 ``bound`` for ``thesis-table21``
- ``side_friction_factor``: Maximum side-friction factor f_max of a standard at a design speed [-]
- ``side_friction_speed``: Speed at which a curve uses up the design side friction
- ``side_friction_speed_kmh``: The speed of ``side_friction_speed`` alone [km/h]: a float for scalar input, else an
  array
- ``STANDARDS``: the known standards by id (``thesis-table21`` at its default ``low`` bound)

From :mod:`~engine.road.superelevation`, superelevation distribution of a design standard:

- ``superelevation_percent``: Design superelevation of a curve by the standard's distribution method
- ``superelevation_table``: Vectorised ``superelevation_percent`` over an array of radii [m] (all at least R_min)

From :mod:`~engine.road.targets`, road-design and compliance tools built on the SRT (the thesis's Ch. 9.6 and 11
proposals):

- ``check_targets``: Whether ``srt_g`` meets each target (SRT >= target) and the margin SRT - target [g]
- ``DEFAULT_TARGETS``: the SRT targets checked by default [g]
- ``TargetCheck``: an SRT against one target
- ``tilt_table_angle_deg``: Tilt-table angle equivalent to an SRT: a rigid vehicle tips at tan(angle) = SRT [deg]
"""

from .advisory import (
    ADVICE_GOVERNED_BY,
    BALL_BANK_2009,
    BODY_ROLL_DEG_PER_G,
    DESIGN_METHOD_NOTE,
    MIN_DEFLECTION_DEG,
    ROLLOVER_MARGIN_KMH,
    SIGN_INCREMENTS,
    SPEED_RANGE_KMH,
    TREATMENT_SOURCE,
    TREATMENTS,
    W1_13_RULE,
    advise_alignment,
    advise_curves,
    check_increment,
    displayed_in_units,
    kmh_to_mph,
    method_source,
    rollover_warning,
)
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
    solve_bank_grade_pairs,
    superelevation_used,
)
from .formulas import (
    FRICTION_BOUNDS,
    aashto_min_radius_m,
    max_curve_speed_kmh,
    rollover_min_radius_m,
    side_friction_min_radius_m,
)
from .geometry import (
    AlignmentGeometry,
    CrossSlope,
    ElementColumns,
    HorizontalElement,
    Profile,
    RangeColumns,
    RoadFile,
    SegmentColumns,
    SlopeColumns,
    StationEquation,
    SuperelevationRange,
    VerticalSegment,
    bend_columns,
    covers_many,
    distance_at,
    element_columns,
    element_distances,
    grades_over,
    station_at,
    superelevations,
)
from .limits import (
    LIMIT_PARAMETERS,
    Limit,
    LimitTableRow,
    limit_table,
    parameter_limit,
    with_parameter,
)
from .min_radius import (
    MinRadius,
    min_radius,
    min_radius_m,
)
from .profile import (
    DECELERATION_MPS2,
    MAX_TRUCK_DECELERATION_MPS2,
    REACTION_TIME_S,
    check_deceleration,
)
from .standards import (
    DEFAULT_DESIGN_STANDARD,
    STANDARDS,
    DesignStandard,
    check_design_speeds,
    get_standard,
    side_friction_factor,
    side_friction_speed,
    side_friction_speed_kmh,
)
from .superelevation import (
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
    "ADVICE_GOVERNED_BY",
    "BALL_BANK_2009",
    "BODY_ROLL_DEG_PER_G",
    "DECELERATION_MPS2",
    "DEFAULT_DESIGN_STANDARD",
    "DEFAULT_TARGETS",
    "DESIGN_METHOD_NOTE",
    "FRICTION_BOUNDS",
    "GOVERNED_BY",
    "LIMIT_PARAMETERS",
    "MAX_TRUCK_DECELERATION_MPS2",
    "MIN_DEFLECTION_DEG",
    "REACTION_TIME_S",
    "ROLLOVER_MARGIN_KMH",
    "SIGN_INCREMENTS",
    "SPEED_RANGE_KMH",
    "STANDARDS",
    "TREATMENTS",
    "TREATMENT_SOURCE",
    "W1_13_RULE",
    "AlignmentAssessment",
    "AlignmentColumns",
    "AlignmentGeometry",
    "CrossSlope",
    "Curve",
    "CurveAssessment",
    "DesignStandard",
    "ElementColumns",
    "HorizontalElement",
    "Limit",
    "LimitTableRow",
    "MinRadius",
    "Profile",
    "RangeColumns",
    "RoadFile",
    "SegmentColumns",
    "SlopeColumns",
    "StationEquation",
    "SuperelevationRange",
    "TargetCheck",
    "VerticalSegment",
    "aashto_min_radius_m",
    "advise_alignment",
    "advise_curves",
    "assess_alignment",
    "assess_curves",
    "bank_grade_pairs",
    "bend_columns",
    "check_columns",
    "check_deceleration",
    "check_design_speeds",
    "check_increment",
    "check_targets",
    "covers_many",
    "displayed_in_units",
    "distance_at",
    "element_columns",
    "element_distances",
    "get_standard",
    "grades_over",
    "kmh_to_mph",
    "limit_table",
    "max_curve_speed_kmh",
    "method_source",
    "min_radius",
    "min_radius_m",
    "parameter_limit",
    "rollover_min_radius_m",
    "rollover_warning",
    "side_friction_factor",
    "side_friction_min_radius_m",
    "side_friction_speed",
    "side_friction_speed_kmh",
    "solve_bank_grade_pairs",
    "station_at",
    "superelevation_percent",
    "superelevation_table",
    "superelevation_used",
    "superelevations",
    "tilt_table_angle_deg",
    "with_parameter",
]

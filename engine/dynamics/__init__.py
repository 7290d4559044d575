"""The combination in motion: a linear yaw-roll model and the manoeuvres and measures of indicative screening.

Concepts, one module each:

- :mod:`engine.dynamics.parameters`: what the motion needs beyond the static description (inertias, extents,
  cornering coefficients, axle spacing), given or estimated, each with its source or formula;
- :mod:`engine.dynamics.model`: the equations of motion of the whole combination, assembled as a constrained
  multibody system (lateral and yaw of every yaw body, an articulation at every yawing coupling, roll of every
  sprung mass with the static combination model's stiffnesses), built once per vehicle;
- :mod:`engine.dynamics.reference`: the tractor-semitrailer's equations derived by hand (Newton-Euler with the
  hitch force eliminated), the independent check of the assembly;
- :mod:`engine.dynamics.response`: state space at a speed, exact discretisation (matrix exponential), frequency
  response, eigenvalues and mode shapes, steady state;
- :mod:`engine.dynamics.manoeuvres`: single lane change (rearward amplification, high-speed transient
  offtracking, load transfer ratio), frequency response of rearward amplification, pulse steer (yaw damping),
  stability against speed, steady turn;
- :mod:`engine.dynamics.lowspeed`: the low-speed 90 degree turn (swept path, tail swing, frontal swing);
- :mod:`engine.dynamics.pbs`: the Performance-Based Standards this model can judge, with the limits' sources.

A linear passive model: no tyre saturation, no lift-off, no stability control. Its answers are an indicative
screening, not a certification.

Exports (the face's ``__all__``, by concept; every other name is the package's own, importable by its
module path for the package and its tests):

From :mod:`~engine.dynamics.lowspeed`, the low-speed 90 degree turn: kinematic (no slip) paths of every unit, swept
path, tail swing, frontal swing:

- ``low_speed_turn``: The 90 degree turn (module docstring)
- ``OUTER_RADIUS_M``: the outer radius of the low-speed 90 degree turn [m]

From :mod:`~engine.dynamics.manoeuvres`, manoeuvres and measures: lane change, frequency response, pulse steer,
stability against speed, steady turn:

- ``lane_change``: The single lane change (module docstring)
- ``pulse_steer``: Yaw damping after a steer pulse (a half sine of ``pulse_s``; its shape unverified against the rules)
- ``rearward_amplification_spectrum``: RA(f) = |a_rear| / |a_steer| per frequency [-]
- ``stability``: The sway critical speed and the divergence speed (module docstring)
- ``steady_turn``: The steady turn with the steer axle's path on ``radius_m`` at ``speed_kmh`` (module docstring; from
  0.5 km/h, a crawl)
- ``Unstable``: The vehicle is unstable at this speed
- ``worst_frequency``: (frequency [Hz], RA) of the largest RA in ``band``: a 60-point logarithmic scan refined by a
  bounded search

From :mod:`~engine.dynamics.model`, the linear yaw-roll model of a combination: a constrained multibody assembly, built
once per vehicle:

- ``build``: Assemble the equations of ``c`` (validated) with its given or estimated dynamic data (see the module)
- ``YawRollModel``: The assembled, condensed equations (SI: kg, N, m, rad) and the maps to every output

From :mod:`~engine.dynamics.parameters`, what the yaw-roll model needs beyond the combination description, and how it is
estimated where not given:

- ``as_dict``: The parameters used, plain JSON types: units and groups with value, unit and source (for the answers)
- ``DynamicsData``: What the caller gives beyond the description
- ``GROUP_DATA_DOCS``: every optional per-group field
- ``GroupData``: Optional per-group data: cornering coefficient [1/rad] and axle spacing [m] (None: estimated)
- ``resolve``: Every unit's and group's dynamic data, given or estimated, with sources; refuse impossible given values
- ``UNIT_DATA_DOCS``: every optional per-unit field
- ``UnitData``: Optional per-unit data (None: estimated)

From :mod:`~engine.dynamics.pbs`, Performance-Based Standards: the standards this model can judge, with the limits'
sources, as indicative screening:

- ``LANE_CHANGE_AMPLITUDE_G``: the lane change's lateral acceleration amplitude by default [g]
- ``LANE_CHANGE_SPEED_KMH``: the lane change's speed by default [km/h]
- ``PULSE_STEER_SPEED_KMH``: the pulse steer's speed by default [km/h]
- ``screen``: Every standard this model judges (module docstring), with limits per level and their sources
- ``SCREENING_NOTE``: what a screening is (indicative, not a certification), carried by every answer
"""

from .lowspeed import (
    OUTER_RADIUS_M,
    low_speed_turn,
)
from .manoeuvres import (
    Unstable,
    lane_change,
    pulse_steer,
    rearward_amplification_spectrum,
    stability,
    steady_turn,
    worst_frequency,
)
from .model import (
    YawRollModel,
    build,
)
from .parameters import (
    GROUP_DATA_DOCS,
    UNIT_DATA_DOCS,
    DynamicsData,
    GroupData,
    UnitData,
    as_dict,
    resolve,
)
from .pbs import (
    LANE_CHANGE_AMPLITUDE_G,
    LANE_CHANGE_SPEED_KMH,
    PULSE_STEER_SPEED_KMH,
    SCREENING_NOTE,
    screen,
)

__all__ = [
    "GROUP_DATA_DOCS",
    "LANE_CHANGE_AMPLITUDE_G",
    "LANE_CHANGE_SPEED_KMH",
    "OUTER_RADIUS_M",
    "PULSE_STEER_SPEED_KMH",
    "SCREENING_NOTE",
    "UNIT_DATA_DOCS",
    "DynamicsData",
    "GroupData",
    "UnitData",
    "Unstable",
    "YawRollModel",
    "as_dict",
    "build",
    "lane_change",
    "low_speed_turn",
    "pulse_steer",
    "rearward_amplification_spectrum",
    "resolve",
    "screen",
    "stability",
    "steady_turn",
    "worst_frequency",
]

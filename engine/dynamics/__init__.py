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
"""

from engine.dynamics.model import YawRollModel, build
from engine.dynamics.parameters import DynamicsData, GroupData, UnitData, resolve

__all__ = ["DynamicsData", "GroupData", "UnitData", "YawRollModel", "build", "resolve"]

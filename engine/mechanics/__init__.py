"""Screw theory and the generic Davies method: the statics of any mechanism, knowing nothing of vehicles.

- :mod:`~engine.mechanics.screw`: successive screw displacements and unit wrenches (Appendix A.1, Eq. 3.4);
- :mod:`~engine.mechanics.mechanism`: links, joints with their constraints, external actions;
- :mod:`~engine.mechanics.davies`: the cut-set statics of Sec. 3.2 solved by SVD, with closures and the null-space
  check that tells a determined variable from a free one.
"""

from .davies import (
    PLANAR_YZ,
    SPATIAL,
    Closure,
    CutSet,
    StaticsSolution,
    cutset_matrix,
    expanded_cutset,
    incidence_matrix,
    solve_statics,
    unit_action_matrix,
)
from .mechanism import (
    Constraint,
    Edge,
    Mechanism,
    custom_joint,
    external,
    joint,
)
from .screw import (
    rot_x,
    screw_matrix,
    successive,
    unit_couple,
    unit_force,
)

__all__ = [
    "PLANAR_YZ",
    "SPATIAL",
    "Closure",
    "Constraint",
    "CutSet",
    "Edge",
    "Mechanism",
    "StaticsSolution",
    "custom_joint",
    "cutset_matrix",
    "expanded_cutset",
    "external",
    "incidence_matrix",
    "joint",
    "rot_x",
    "screw_matrix",
    "solve_statics",
    "successive",
    "unit_action_matrix",
    "unit_couple",
    "unit_force",
]

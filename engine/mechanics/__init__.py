"""Screw theory and the generic Davies method: the statics of any mechanism, knowing nothing of vehicles.

- :mod:`~engine.mechanics.screw`: successive screw displacements and unit wrenches (Appendix A.1, Eq. 3.4);
- :mod:`~engine.mechanics.mechanism`: links, joints with their constraints, external actions;
- :mod:`~engine.mechanics.davies`: the cut-set statics of Sec. 3.2 solved by SVD, with closures and the null-space
  check that tells a determined variable from a free one.

Exports (the face's ``__all__``, by concept; every other name is the package's own, importable by its
module path for the package and its tests):

From :mod:`~engine.mechanics.davies`, generic Davies-method statics (Sec. 3.2, Appendix A); knows nothing about
vehicles:

- ``Closure``: An extra linear equation on the magnitudes
- ``PLANAR_YZ``: rows kept for a planar mechanism in the y-z plane (lambda = 3): [Mx, Fy, Fz] (Sec. 5.1.2)
- ``solve_statics``: Solve the cut-set equations for the secondary magnitudes given the primary ones (Eq. 6.12)

From :mod:`~engine.mechanics.mechanism`, mechanism description for the Davies method: links, joints with their
constraints, external actions:

- ``custom_joint``: Add a joint with an explicit list of (magnitude name, unit wrench) constraints
- ``external``: Add an external action on ``link`` (an edge from the ground) with magnitude ``name``
- ``joint``: Add a joint of ``kind`` between links ``a`` (tail side) and ``b`` at ``point``
- ``Mechanism``: Links (vertices, ``links[0]`` is the ground/road) and edges (joints, then external actions)

From :mod:`~engine.mechanics.screw`, screw theory: successive screw displacements and unit wrenches (Appendix A.1, Eq.
3.4):

- ``rot_x``: 3x3 rotation about x (a screw with s = (1, 0, 0), the axis of every revolute of Tables 3 and 8)
- ``screw_matrix``: 4x4 homogeneous matrix of a screw displacement (Eqs
- ``unit_couple``: Normalized wrench of a pure moment (couple) about ``direction`` (Eq
- ``unit_force``: Normalized wrench of a force of unit magnitude along ``direction`` through ``point`` (Eq
"""

from .davies import (
    PLANAR_YZ,
    Closure,
    solve_statics,
)
from .mechanism import (
    Mechanism,
    custom_joint,
    external,
    joint,
)
from .screw import (
    rot_x,
    screw_matrix,
    unit_couple,
    unit_force,
)

__all__ = [
    "PLANAR_YZ",
    "Closure",
    "Mechanism",
    "custom_joint",
    "external",
    "joint",
    "rot_x",
    "screw_matrix",
    "solve_statics",
    "unit_couple",
    "unit_force",
]

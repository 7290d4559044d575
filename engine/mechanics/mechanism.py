"""Mechanism description for the Davies method: links, joints with their constraints, external actions.

A joint couples two links and *constrains* some relative motions; each constraint is a unit wrench the
joint can transmit (Eq. 3.4, Tables 6 and 11). A passive actuator (spring along a prismatic axis, torsion
spring about a revolute axis) transmits one more wrench whose magnitude the compliance law relates to the
joint variable (Table 2). External actions (the CG loads Px, Py, Pz) are edges from the ground to the
loaded link, like joints, but their magnitudes are the *primary* variables.

Every constraint is a named magnitude (``"Fz17"``, ``"FT18"``, ``"Tx21"``...); its value is the wrench the
*tail* link of the edge exerts on the *head* link, where the tail is the lower-numbered link (the thesis
orients every edge from the minor to the major vertex, Sec. 3.2 step 2).

Joint kinds (local frame ``e1, e2, e3``; for the trailer groups e1 is the group's longitudinal axis and
e2/e3 span its transverse plane):

========================  =======================================  ====================================
kind                      constraints                              thesis
========================  =======================================  ====================================
``revolute(axis e1)``     F e1, F e2, F e3, M e2, M e3             R (Table 11: Fx Fy Fz My Mz)
``revolute + torsion``    the same + actuator M e1                 R with spring (Tx5, Tx11, Tx21)
``prismatic(axis e3)``    F e1, F e2, M e1, M e2, M e3             P (Fx Fp Mx My Mz)
``prismatic + spring``    the same + actuator F e3                 FT, FLS, FFW
``spherical slider``      F e1, M e2, F e3                         Sd tire contact (Fx My Fz)
``planar`` variants       the in-plane subset (Mx, Fy, Fz)         Table 6 (2D)
========================  =======================================  ====================================
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from engine.mechanics.screw import unit_couple, unit_force


@dataclass(frozen=True)
class Constraint:
    """One transmitted magnitude: a name and its unit wrench (6-vector, moment first)."""

    name: str
    wrench: np.ndarray
    actuator: bool = False  # a passive actuator (spring) rather than a rigid constraint


@dataclass
class Edge:
    """A joint or an external action between two links (tail = lower index)."""

    name: str
    tail: int
    head: int
    constraints: list[Constraint] = field(default_factory=list)
    external: bool = False


@dataclass
class Mechanism:
    """Links (vertices, ``links[0]`` is the ground/road) and edges (joints, then external actions)."""

    links: list[str]
    edges: list[Edge] = field(default_factory=list)

    def link(self, name: str) -> int:
        return self.links.index(name)

    def add(self, edge: Edge) -> Edge:
        if edge.tail == edge.head:
            raise ValueError(f"edge {edge.name} joins link {edge.tail} to itself")
        if edge.tail > edge.head:  # orient from the minor to the major vertex
            edge.tail, edge.head = edge.head, edge.tail
            edge.constraints = [Constraint(c.name, -c.wrench, c.actuator) for c in edge.constraints]
        self.edges.append(edge)
        return edge

    @property
    def variable_names(self) -> list[str]:
        return [c.name for e in self.edges for c in e.constraints]

    @property
    def mobility_counts(self) -> tuple[int, int, int]:
        """(n links, j joints, f external actions)."""
        j = sum(1 for e in self.edges if not e.external)
        return len(self.links), j, len(self.edges) - j


def _between(mech: Mechanism, a: str | int, b: str | int) -> tuple[int, int]:
    ia = a if isinstance(a, int) else mech.link(a)
    ib = b if isinstance(b, int) else mech.link(b)
    return ia, ib


def joint(mech: Mechanism, name: str, a, b, point, frame, kind: str, *, actuator: str | None = None) -> Edge:
    """Add a joint of ``kind`` between links ``a`` (tail side) and ``b`` at ``point``.

    ``frame`` is a 3x3 matrix whose columns are the joint's local axes e1, e2, e3. The constraint wrench
    directions are written in that frame; a wrench is the action of link ``a`` on link ``b``.
    ``actuator`` names the passive actuator's magnitude (spring force or torsion moment), if any.
    Constraint names are ``<component><name>`` with components as in Table 11.
    """
    e1, e2, e3 = (np.asarray(frame, dtype=float)[:, i] for i in range(3))
    p = np.asarray(point, dtype=float)
    F = lambda d: unit_force(d, p)  # noqa: E731
    M = unit_couple
    if kind == "revolute":  # rotation about e1 free
        cons = [("Fx", F(e1)), ("Fy", F(e2)), ("Fz", F(e3)), ("My", M(e2)), ("Mz", M(e3))]
        act = ("Tx", M(e1))
    elif kind == "prismatic":  # translation along e3 free
        cons = [("Fx", F(e1)), ("Fp", F(e2)), ("Mx", M(e1)), ("My", M(e2)), ("Mz", M(e3))]
        act = ("", F(e3))
    elif kind == "spherical-slider":  # tire contact that may slide along e2 (Sec. 4.1.1, Table 11)
        cons = [("Fx", F(e1)), ("My", M(e2)), ("Fz", F(e3))]
        act = None
    elif kind == "planar-revolute":  # Table 6
        cons = [("Fy", F(e2)), ("Fz", F(e3))]
        act = ("Tx", M(e1))
    elif kind == "planar-prismatic":  # Table 6, axis e3
        cons = [("Fp", F(e2)), ("Mx", M(e1))]
        act = ("", F(e3))
    elif kind == "planar-slider":  # Table 6, joint 3: slides along e2
        cons = [("Mx", M(e1)), ("Fz", F(e3))]
        act = None
    else:
        raise ValueError(f"unknown joint kind {kind!r}")
    constraints = [Constraint(f"{c}{name}", w) for c, w in cons]
    if actuator is not None:
        if act is None:
            raise ValueError(f"a {kind} joint has no actuator axis")
        constraints.append(Constraint(actuator, act[1], actuator=True))
    ia, ib = _between(mech, a, b)
    return mech.add(Edge(name, ia, ib, constraints))


def custom_joint(mech: Mechanism, name: str, a, b, constraints: list[tuple[str, np.ndarray]]) -> Edge:
    """Add a joint with an explicit list of (magnitude name, unit wrench) constraints."""
    ia, ib = _between(mech, a, b)
    return mech.add(Edge(name, ia, ib, [Constraint(n, np.asarray(w, dtype=float)) for n, w in constraints]))


def external(mech: Mechanism, name: str, link, wrench) -> Edge:
    """Add an external action on ``link`` (an edge from the ground) with magnitude ``name``.

    ``wrench`` is the unit wrench the action applies *to the link* (Table 11: Px (1,0,0), Py (0,-1,0),
    Pz (0,0,-1) at the CG).
    """
    _, il = _between(mech, 0, link)
    return mech.add(Edge(name, 0, il, [Constraint(name, np.asarray(wrench, dtype=float))], external=True))

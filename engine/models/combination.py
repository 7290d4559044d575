"""The whole-combination static roll model: every unit, every axle group, every coupling, solved step by step.

In the tradition of the UMTRI static roll models (Ervin 1986; Winkler and Fancher 1992; Winkler and Ervin 1999),
each roll-coupled unit of a :class:`~engine.vehicle.combination.Combination` (units joined by fifth wheels or
B-couplings) is a set of rigid bodies in the roll plane:

* a **sprung mass** per unit, rolling by phi_u relative to the road;
* an **axle** per axle group, rolling by phi_g relative to the road by the deflection of its tyres.

Laws (small angles, all per group): the tyres give the roll moment ``M_t = k_side T^2/2 phi_g`` until the inner
line's load ``N/2 - M_t/T`` reaches zero (lift-off), then ``M_t = N T/2``; the suspension passes
``M_s = K_s dz(phi_u - phi_g, lash)`` (``dz`` a dead zone of half-width ``lash``) about its roll centre at height
``h_r``, through which it also passes the sprung mass's lateral force; a fifth wheel passes
``M_c = K_c dz(phi_towed - phi_towing, lash)`` at its height; a pintle passes forces but no moment.

Equilibrium, per axle g of unit u (moments about the road below the group's centre, + outward)::

    M_t,g = M_s,g + l(ay) (S0_g h_r,g + W_a,g h_a,g) + phi_g (S_g h_r,g + n0 W_a,g h_a,g)

and per sprung mass u (moments about the road below the unit; its lateral position drops out when its supports'
normal loads satisfy the unit's own pitch balance, as they do by construction)::

    l W_u h_u + n(ay) W_u d1_u + phi_u n0 W_u h_u + sum_towing (l V0_c h_c + phi_u V_c h_c + M_c)
        = sum_groups (l S0_g h_r,g + phi_u S_g h_r,g + M_s,g) + sum_towed_by (l V0_c h_c + phi_u V_c h_c + M_c)

with the normal-weight and lateral factors of the road ``n(ay) = cos(b) cos(s) + ay sin(b)`` and
``l(ay) = ay cos(b) - sin(b) cos(s)`` (bank b, grade s; the 3D model's Eqs. 4.24-4.26), the normal loads per unit
normal factor ``N0``, ``S0 = N0 - W_a``, ``V0`` (:func:`engine.vehicle.combination.static_loads`), and, in the
second-order (P-Delta) terms ``phi (...)``, the normal loads ``S``, ``V`` at the normal factor ``n0`` of the limit.
Summed over a roll-coupled unit the equations are its moment balance about the road (tested).

**The stepped solution.** Every law is piecewise linear, so between two events (a group lifting off, a lash being
taken up) the equilibrium path is a straight line in (phi, ay). From the unloaded state the path is followed event by
event: the direction is the null vector of the current regime's equations; the next event is the first inequality
that reaches its bound; the new regime's direction is oriented into its own interior. The **SRT of a roll-coupled
unit** is the largest ay on the path (past it every equilibrium needs less: the vehicle rolls over), or the ay at
which a group other than a steer group reaches the requested LLT limit. A load offset d1 is applied first, at
zero lateral force (ay = tan(b) cos(s)). :mod:`engine.models.combination_reference` solves the same equations as a
general nonlinear equilibrium with scipy; the two agree on random vehicles (``tests/engine/test_combination.py``).

**Bank.** On a bank the normal loads grow with ay, and the P-Delta terms with them: the path is solved with those
terms at one normal factor, brought to the limit's own by a fixed point (:func:`solve_unit`), so the limit is the
exact equilibrium there.

References
----------
.. [1] Ervin, R. D. (1986), The dependence of truck roll stability on size and weight variables, Int. J. Vehicle
   Design 7(5-6); Winkler, C. B. and Fancher, P. S. (1992), ESV; Winkler, C. B. and Ervin, R. D. (1999),
   *Rollover of heavy commercial vehicles*, UMTRI-99-19: the static roll model of roll-coupled units.
.. [2] Moreno (thesis), Eqs. 2.5 (LLT), 2.11 (roll stiffness of two springs), 4.24-4.27 (actions on a banked,
   sloped road; the load split).
.. [3] Allgower, E. L. and Georg, K. (1990), *Numerical Continuation Methods*, Springer, Ch. 12: following the
   solution path of a piecewise-linear system (null vector of each linear piece, orientation across pieces).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field, replace

import numpy as np

from engine.errors import ConvergenceError, InvalidLoad
from engine.models import roll_tree
from engine.results import (
    CombinationDetail,
    CouplingState,
    GroupState,
    LiftEvent,
    RollCoupledUnitResult,
)
from engine.vehicle.combination import (
    Combination,
    UnitLoad,
    kingpin_group,
    loaded_units,
    roll_coupled_units,
    static_loads,
)

#: lift-off states of a group's tyres and dead-zone states of a suspension or coupling
LINEAR, LIFTED, LIFTED_OUT = 0, 1, -1
BAND, PLUS, MINUS = 0, 1, -1
#: a constraint this close to its bound [kN m or rad, scaled] counts as reached
TOL = 1e-12


@dataclass(frozen=True)
class RoadFactors:
    """The road's factors on the weight: normal ``n(ay) = n0 + n1 ay``, lateral ``l(ay) = l0 + l1 ay`` [-], and
    ``grade = sin(grade)`` (positive uphill) [-]."""

    n0: float
    n1: float
    l0: float
    l1: float
    grade: float

    @classmethod
    def of(cls, bank_percent: float, slope_percent: float) -> RoadFactors:
        b, s = math.atan(bank_percent / 100.0), math.atan(slope_percent / 100.0)
        cb, sb, cs, ss = math.cos(b), math.sin(b), math.cos(s), math.sin(s)
        return cls(n0=cb * cs, n1=sb, l0=-sb * cs, l1=cb, grade=ss)

    @property
    def neutral_ay(self) -> float:
        """The ay at which the road plane feels no lateral force: l(ay) = 0 [g]."""
        return -self.l0 / self.l1


@dataclass
class Tyres:
    """The tyres of one group as a roll element on DOF ``dof`` (the axle)."""

    dof: int
    unit: int
    group: int
    k: float  # roll stiffness k_side T^2/2 [kN m/rad]
    cap_normal: float  # N0 T/2: the lift-off moment per unit normal factor [kN m]
    cap_grade: float  # L T/2 per unit sin(grade) [kN m]
    track: float
    normal_kn: float  # N0
    grade_kn: float  # L
    steer: bool


@dataclass
class DeadZone:
    """A suspension or fifth wheel: moment K dz(q_i - q_j, lash) acting +M on DOF i and -M on DOF j."""

    i: int
    j: int
    k: float
    lash: float  # half-width [rad]
    kind: str  # "suspension" or "coupling"
    ref: tuple[int, int]  # (unit, group) or (coupling index, -1)


@dataclass
class System:
    """One roll-coupled unit's equations: ``R(q, ay) = sum(elements) - P q - l(ay) lat - n(ay) off = 0``."""

    units: tuple[int, ...]
    n: int
    body: dict[int, int]  # unit index -> DOF
    axle: dict[tuple[int, int], int]  # (unit, group) -> DOF
    P: np.ndarray  # P-Delta (destabilising) stiffness [kN m/rad]
    lat: np.ndarray  # lateral-load pattern [kN m per unit lateral factor]
    off: np.ndarray  # load-offset moments W d1 [kN m per unit normal factor]
    weights: np.ndarray  # sprung weights on the body DOFs (the outward-roll measure) [kN]
    tyres: list[Tyres]
    zones: list[DeadZone]
    couplings: list[tuple[int, float, float]]  # (coupling index, V0, V grade) of every coupling inside or at the edge
    road: RoadFactors = field(default=None)  # type: ignore[assignment]
    P_normal: np.ndarray = field(default=None)  # type: ignore[assignment]  # P per unit normal factor
    P_grade: np.ndarray = field(default=None)  # type: ignore[assignment]  # P per unit sin(grade)
    #: P's diagonal (P is diagonal) as floats, for the solves on the tree (:func:`_pivots`)
    P_diag: tuple = field(default=None)  # type: ignore[assignment]
    #: the element arrays and the per-regime pieces (:func:`_elements`): they do not depend on the normal factor, so
    #: the copies :meth:`at_normal` makes share them across the fixed point's iterations
    cache: dict = field(default_factory=dict, compare=False, repr=False)

    def at_normal(self, normal: float) -> System:
        """The same equations with the P-Delta terms at the normal factor ``normal``."""
        P = normal * self.P_normal + self.road.grade * self.P_grade
        return replace(self, P=P, P_diag=tuple(np.diagonal(P).tolist()))

    def cap(self, t: Tyres, ay: float) -> float:
        """The group's lift-off moment N(ay) T/2 [kN m]."""
        r = self.road
        return (r.n0 + r.n1 * ay) * t.cap_normal + r.grade * t.cap_grade


def build_systems(c: Combination, bank_percent: float, slope_percent: float, load: UnitLoad) -> list[System]:
    """The equations of each roll-coupled unit of ``c`` on that road with that load case."""
    road = RoadFactors.of(bank_percent, slope_percent)
    lu = loaded_units(c, load)
    st = static_loads(c, lu)
    out = []
    for members in roll_coupled_units(c):
        body = {u: k for k, u in enumerate(members)}
        axle = {}
        for u in members:
            for j in range(len(c.units[u].groups)):
                axle[(u, j)] = len(body) + len(axle)
        n = len(body) + len(axle)
        Pn, Pg = np.zeros((n, n)), np.zeros((n, n))  # P-Delta per unit normal factor, per unit sin(grade)
        lat, off, weights = np.zeros(n), np.zeros(n), np.zeros(n)
        tyres, zones, coupl = [], [], []
        for u in members:
            unit, lw = c.units[u], lu[u]
            b = body[u]
            weights[b] = lw.weight_kn
            lat[b] += lw.weight_kn * lw.cg_height_m
            Pn[b, b] += lw.weight_kn * lw.cg_height_m
            off[b] += lw.weight_kn * lw.lateral_offset_m
            for j, g in enumerate(unit.groups):
                a = axle[(u, j)]
                wa = g.unsprung_weight_kn
                n0g, lg = st.normal_kn[(u, j)], st.grade_kn[(u, j)]
                s0 = n0g - wa  # through the suspension, per unit normal factor
                lat[a] += s0 * g.roll_centre_height_m + wa * g.unsprung_cg_height_m
                Pn[a, a] += s0 * g.roll_centre_height_m + wa * g.unsprung_cg_height_m
                Pg[a, a] += lg * g.roll_centre_height_m
                lat[b] -= s0 * g.roll_centre_height_m
                Pn[b, b] -= s0 * g.roll_centre_height_m
                Pg[b, b] -= lg * g.roll_centre_height_m
                tyres.append(
                    Tyres(
                        a, u, j, g.tyre_roll_stiffness_knm_per_rad, n0g * g.track_m / 2.0, lg * g.track_m / 2.0,
                        g.track_m, n0g, lg, g.steer,
                    )
                )  # fmt: skip
                zones.append(
                    DeadZone(b, a, g.suspension_roll_stiffness_knm_per_rad, math.radians(g.lash_deg), "suspension",
                             (u, j))
                )  # fmt: skip
        for i, cp in enumerate(c.couplings):
            towing, towed = i, i + 1
            v0, vg = st.coupling_kn[i], st.coupling_grade_kn[i]
            touched = False
            if towing in body:  # the towed unit's front presses on this unit at the coupling
                lat[body[towing]] += v0 * cp.height_m
                Pn[body[towing], body[towing]] += v0 * cp.height_m
                Pg[body[towing], body[towing]] += vg * cp.height_m
                touched = True
            if towed in body:  # and this unit rests on it
                lat[body[towed]] -= v0 * cp.height_m
                Pn[body[towed], body[towed]] -= v0 * cp.height_m
                Pg[body[towed], body[towed]] -= vg * cp.height_m
                touched = True
            if touched:
                coupl.append((i, v0, vg))
            if cp.transmits_roll and towing in body and towed in body:
                zones.append(
                    DeadZone(body[towed], body[towing], cp.roll_stiffness_knm_per_rad, math.radians(cp.lash_deg),
                             "coupling", (i, -1))
                )  # fmt: skip
        P = road.n0 * Pn + road.grade * Pg  # at rest; solve_unit moves it to the limit's normal factor
        out.append(System(members, n, body, axle, P, lat, off, weights, tyres, zones, coupl, road, Pn, Pg,
                          tuple(np.diagonal(P).tolist())))  # fmt: skip
    return out


# ------------------------------------------------------------------------------------------- the path


@dataclass
class Regime:
    tyre: list[int]
    zone: list[int]


class _Elements:
    """The system's tyres and dead zones as arrays, and what each regime makes of them (cached per regime: the path
    meets the same regimes in every iteration of the fixed point). Profiling showed the per-element Python loops
    that built the equations and the constraints row by row taking most of a solve."""

    def __init__(self, s: System):
        self.n = s.n
        self.tdof = np.array([t.dof for t in s.tyres], dtype=int)
        self.tk = np.array([t.k for t in s.tyres], dtype=float)
        self.capn = np.array([t.cap_normal for t in s.tyres], dtype=float)
        self.capg = np.array([t.cap_grade for t in s.tyres], dtype=float)
        self.steer = np.array([t.steer for t in s.tyres], dtype=bool)
        self.zi = np.array([z.i for z in s.zones], dtype=int)
        self.zj = np.array([z.j for z in s.zones], dtype=int)
        self.zk = np.array([z.k for z in s.zones], dtype=float)
        self.lash = np.array([z.lash for z in s.zones], dtype=float)
        self.capn_dof, self.capg_dof = np.zeros(s.n), np.zeros(s.n)  # the same on the DOFs
        self.capn_dof[self.tdof], self.capg_dof[self.tdof] = self.capn, self.capg
        # a regime's pieces, tables and ends depend on the elements alone, not on the road: shared by every system
        # with the same elements (the next solve of the same vehicle, on any road, builds none of them again: a
        # tenth of a banked solve's time)
        key = tuple(x.tobytes() for x in (self.tdof, self.tk, self.steer, self.zi, self.zj, self.zk, self.lash))
        self.pieces, self.tables, self.ends, self.trees = _shared_regimes(self.n, key)
        self.tree = _tree(self.n, self.zi.tobytes(), self.zj.tobytes())
        self.rows: dict = {}  # road-dependent: an _Elements belongs to one System and its at_normal copies
        self.loads: dict = {}
        self.steps: dict = {}

    def piece(self, tyre: tuple, zone: tuple):
        """(K, S, kz) of a regime: its stiffness matrix, the sign of each lifted group's moment on its DOF (0 where
        linear), and the constant moments of the taken-up lashes."""
        key = (tyre, zone)
        out = self.pieces.get(key)
        if out is None:
            self._build(tyre, zone)
            out = self.pieces[key]
        return out

    def tree_piece(self, tyre: tuple, zone: tuple) -> tuple[tuple[float, ...], tuple[float, ...]]:
        """A regime's K as :mod:`~engine.models.roll_tree` takes it: its diagonal and its entries on the tree's
        edges, as floats (both modes subtract each row's P-Delta diagonal from the same floats)."""
        key = (tyre, zone)
        out = self.trees.get(key)
        if out is None:
            self._build(tyre, zone)
            out = self.trees[key]
        return out

    def _build(self, tyre: tuple, zone: tuple) -> None:
        """A regime's :meth:`piece` and :meth:`tree_piece`, summed in floats (element by element into a numpy
        matrix took a third of a vehicle's first solve, profiled) in the order the elements come: the same sums."""
        n = self.n
        diag, S, kz = [0.0] * n, [0.0] * n, [0.0] * n
        edges: dict[tuple[int, int], float] = {}
        tdof, tk = self.tdof.tolist(), self.tk.tolist()
        for t, state in enumerate(tyre):
            if state == LINEAR:
                diag[tdof[t]] += tk[t]
            else:
                S[tdof[t]] = float(state)
        zi, zj, zk, lashes = self.zi.tolist(), self.zj.tolist(), self.zk.tolist(), self.lash.tolist()
        for z, state in enumerate(zone):
            lash = lashes[z]
            if state == BAND and lash > 0:
                continue
            i, j, k = zi[z], zj[z], zk[z]
            diag[i] += k
            diag[j] += k
            edges[i, j] = edges.get((i, j), 0.0) - k
            if lash > 0:
                off = -k * lash * state  # PLUS: K (d - lash); MINUS: K (d + lash)
                kz[i] += off
                kz[j] -= off
        K = np.diag(diag)
        for (i, j), k in edges.items():
            K[i, j] = K[j, i] = k
        t = self.tree
        on_tree = tuple(edges.get((v, p), edges.get((p, v), 0.0)) for v, p in zip(t.order, t.parent, strict=True))
        # the tree piece first: a reader that finds the piece finds its tree piece too (solver threads share both)
        self.trees.setdefault((tyre, zone), (tuple(diag), on_tree))
        self.pieces.setdefault((tyre, zone), _frozen(K, np.array(S), np.array(kz)))

    def table(self, tyre: tuple, zone: tuple, phase: int, limit: bool):
        """The inequalities bounding a regime, ``c1 x[i1] + c2 x[i2] + b >= 0`` (x = (q, p)), in a fixed order (a
        tie goes to the first), as index arrays over the tyres and zones: tyre rows ``(tyre index, sign of k, factor
        of the lift-off moment: +-1, or 0 for the LLT limit)``, zone rows ``(zone index, sign of d, sign of lash)``,
        and what crossing each means, ``ends``: rows of (kind 0 tyre / 1 zone / 2 stop, index, new state)."""
        key = (tyre, zone, phase, limit)
        out = self.tables.get(key)
        if out is None:
            trows, zrows, ends = [], [], []
            for idx, state in enumerate(tyre):
                if state == LINEAR:
                    trows.append((idx, -1.0, 1.0)), ends.append((0, idx, LIFTED))  # cap - K q >= 0
                    trows.append((idx, 1.0, 1.0)), ends.append((0, idx, LIFTED_OUT))  # K q + cap >= 0
                    if phase == 2 and limit and not self.steer[idx]:
                        trows.append((idx, -1.0, 0.0)), ends.append((2, idx, 0))  # L cap - K q >= 0
                elif state == LIFTED:
                    trows.append((idx, 1.0, -1.0)), ends.append((0, idx, LINEAR))  # K q - cap >= 0
                else:
                    trows.append((idx, -1.0, -1.0)), ends.append((0, idx, LINEAR))  # -K q - cap >= 0
            for idx, state in enumerate(zone):
                if self.lash[idx] <= 0:
                    continue
                if state == BAND:
                    zrows.append((idx, -1.0, 1.0)), ends.append((1, idx, PLUS))  # lash - d >= 0
                    zrows.append((idx, 1.0, 1.0)), ends.append((1, idx, MINUS))  # d + lash >= 0
                elif state == PLUS:
                    zrows.append((idx, 1.0, -1.0)), ends.append((1, idx, BAND))  # d - lash >= 0
                else:
                    zrows.append((idx, -1.0, -1.0)), ends.append((1, idx, BAND))  # -d - lash >= 0
            if phase == 1:
                ends.append((2, -1, 0))  # 1 - t >= 0
            n, tdof, zi_, zj_ = self.n, self.tdof.tolist(), self.zi.tolist(), self.zj.tolist()
            ti, zi = [x[0] for x in trows], [x[0] for x in zrows]
            i1 = np.array([tdof[t] for t in ti] + [zi_[z] for z in zi] + [n] * (phase == 1), dtype=int)
            i2 = np.array([n] * len(ti) + [zj_[z] for z in zi] + [n] * (phase == 1), dtype=int)
            tr = np.array(trows, dtype=float).reshape(-1, 3)
            zr = np.array(zrows, dtype=float).reshape(-1, 3)
            ti, zi = np.array(ti, dtype=int), np.array(zi, dtype=int)
            out = self.tables[key] = _frozen(ti, tr[:, 1], tr[:, 2], zi, zr[:, 1], zr[:, 2], i1, i2, np.array(ends))
        return out

    def row_of(self, tyre: tuple, zone: tuple, phase: int, limit: bool) -> dict:
        """(kind, index, new state) -> the first row of the regime's :meth:`table` with that end."""
        key = (tyre, zone, phase, limit)
        out = self.ends.get(key)
        if out is None:
            # built whole before it is stored: the table is shared by the solves of this vehicle on other threads
            # (the solver threads), which must never see it half filled
            built: dict = {}
            for k, e in enumerate(self.table(tyre, zone, phase, limit)[-1].tolist()):
                built.setdefault(tuple(e), k)
            out = self.ends.setdefault(key, built)
        return out


@functools.lru_cache(maxsize=256)
def _tree(n: int, zi: bytes, zj: bytes) -> roll_tree.Tree:
    """The elimination order of a system's DOFs, joined by its suspensions and roll-stiff couplings (a tree)."""
    return roll_tree.tree_of(n, list(zip(np.frombuffer(zi, dtype=int).tolist(), np.frombuffer(zj, dtype=int).tolist(),
                                         strict=True)))  # fmt: skip


@functools.lru_cache(maxsize=256)
def _shared_regimes(n: int, elements: tuple) -> tuple[dict, dict, dict, dict]:
    """The (pieces, tables, ends, trees) caches of the systems with these elements (:class:`_Elements`): a memo of
    values that depend on the elements alone, read-only once stored and stored only whole, so that solves on several
    threads may share it (at worst two threads build the same entry, and one of the equal values is kept)."""
    return {}, {}, {}, {}


def _frozen(*arrays: np.ndarray) -> tuple:
    for x in arrays:  # shared by every solve of the vehicle: read-only, so no caller can change another's
        x.flags.writeable = False
    return arrays


def _elements(s: System) -> _Elements:
    e = s.cache.get("elements")
    if e is None:
        e = s.cache["elements"] = _Elements(s)
    return e


def _assemble(s: System, rg: Regime, phase: int):
    """The loads of the current piece's equations ``J q + jp p + k = 0`` (p: ay in phase 2, the offset scale t in
    phase 1), (jp, k), cached per regime (they depend on the road, not on the P-Delta terms that the fixed point
    changes: a solve assembled the same regimes' loads some 25 times, a tenth of its time). J = K - P is
    :func:`_pivots`' (on the tree) or :func:`_stiffness`' (dense)."""
    e = _elements(s)
    tyre, zone = tuple(rg.tyre), tuple(rg.zone)
    _K, S, kz = e.piece(tyre, zone)
    key = (tyre, zone, phase)
    loads = e.loads.get(key)
    if loads is None:
        r = s.road
        capn, capg = e.capn_dof, e.capg_dof
        if phase == 2:
            jp = -(r.l1 * s.lat + r.n1 * s.off) + S * (r.n1 * capn)
            k = -(r.l0 * s.lat + r.n0 * s.off) + S * (r.n0 * capn + r.grade * capg) + kz
        else:  # at ay0: no lateral force; the offsets scaled by t
            ay0 = r.neutral_ay
            jp = -(r.n0 + r.n1 * ay0) * s.off
            k = S * ((r.n0 + r.n1 * ay0) * capn + r.grade * capg) + kz
        loads = e.loads[key] = (jp, k)
    return loads


def _stiffness(s: System, tyre: tuple, zone: tuple) -> np.ndarray:
    """A piece's J = K - P as a dense matrix (for the SVD of a singular piece)."""
    return _elements(s).piece(tyre, zone)[0] - s.P


def _pivots(s: System, tyre: tuple, zone: tuple) -> tuple[roll_tree.Tree, roll_tree.Factor]:
    """(tree, factor) of a piece's J = K - P (:mod:`~engine.models.roll_tree`, in floats); raises
    :class:`~engine.models.roll_tree.Singular` at a zero pivot."""
    e = _elements(s)
    kd, ke = e.tree_piece(tyre, zone)
    diag = [a - b for a, b in zip(kd, s.P_diag, strict=True)]
    return e.tree, roll_tree.factor(e.tree, diag, ke)


def _tree_solve(s: System, tyre: tuple, zone: tuple, rhs: np.ndarray) -> np.ndarray:
    """q with J q = rhs for a piece's J = K - P (raises Singular)."""
    t, f = _pivots(s, tyre, zone)
    return np.array(roll_tree.solve(t, f, rhs.tolist()))


def _constraint_rows(s: System, rg: Regime, phase: int, llt_limit: float | None):
    """The inequalities bounding the current piece as ``(c1, c2, b, i1, i2, ends, scale)``: ``c1 x[i1] + c2 x[i2] + b
    >= 0`` with x = (q, p), what crossing each one means (:meth:`_Elements.table`), and each row's scale."""
    e = _elements(s)
    key = (tuple(rg.tyre), tuple(rg.zone), phase, llt_limit)
    out = e.rows.get(key)  # on one road: the fixed point's iterations meet the same regimes
    if out is None:
        out = e.rows[key] = _rows_of(s, e, key)
    return out


def _rows_of(s: System, e: _Elements, key):
    tyre, zone, phase, llt_limit = key
    r = s.road
    ti, sk, sf, zi, sg, sb, i1, i2, ends = e.table(tyre, zone, phase, llt_limit is not None)
    if phase == 2:  # in Python floats: a handful of rows, each its own regime's once (the same IEEE operations)
        c1, c2, b = [], [], []
        for t, k_sign, f in zip(ti.tolist(), sk.tolist(), sf.tolist(), strict=True):
            el = s.tyres[t]
            fac = llt_limit if f == 0.0 else f
            c1.append(k_sign * el.k)
            c2.append(fac * (r.n1 * el.cap_normal))
            b.append(fac * (r.n0 * el.cap_normal + r.grade * el.cap_grade))
        for z, g, sign in zip(zi.tolist(), sg.tolist(), sb.tolist(), strict=True):
            c1.append(g), c2.append(-g), b.append(sign * s.zones[z].lash)
        c1, c2, b = np.array(c1, dtype=float), np.array(c2, dtype=float), np.array(b, dtype=float)
        return c1, c2, b, i1, i2, ends, np.maximum(1.0, np.abs(c1) + np.abs(c2))
    cp, cc = np.zeros(ti.size), np.array([s.cap(s.tyres[t], r.neutral_ay) for t in ti], dtype=float)  # phase 1
    fac = np.where(sf == 0.0, llt_limit if llt_limit is not None else 0.0, sf)
    c1 = np.concatenate([sk * e.tk[ti], sg, [-1.0] * (phase == 1)])
    c2 = np.concatenate([fac * cp, -sg, [0.0] * (phase == 1)])
    b = np.concatenate([fac * cc, sb * e.lash[zi], [1.0] * (phase == 1)])
    return c1, c2, b, i1, i2, ends, np.maximum(1.0, np.abs(c1) + np.abs(c2))


def _step_terms(s: System, rg: Regime, phase: int, llt_limit: float | None):
    """What a step of the path needs of its regime, looked up once per step: ((tyre, zone), jp,
    :func:`_constraint_rows`, :meth:`_Elements.row_of`); the same arrays as those functions give (cached per regime
    and road like them)."""
    e = _elements(s)
    key = (tuple(rg.tyre), tuple(rg.zone), phase, llt_limit)
    out = e.steps.get(key)
    if out is None:
        jp, _k = _assemble(s, rg, phase)
        rows = _constraint_rows(s, rg, phase, llt_limit)
        out = e.steps[key] = (
            (key[0], key[1]),
            jp,
            rows,
            e.row_of(key[0], key[1], phase, llt_limit is not None),
        )
    return out


def _null_direction(s: System, piece: tuple, jp: np.ndarray) -> np.ndarray:
    """The unit null vector of [J | jp] (the direction of the piece's solution line) of the piece (tyre, zone)."""
    try:
        t, f = _pivots(s, *piece)
        out, sq = roll_tree.direction(roll_tree.solve(t, f, [-x for x in jp.tolist()]))
        if sq < 1e24:  # finite and |dq| < 1e12 (nan and inf fail the comparison)
            return np.array(out)
    except roll_tree.Singular:
        pass
    _, _, vt = np.linalg.svd(np.column_stack([_stiffness(s, *piece), jp]))
    return vt[-1]


@dataclass
class _Vertex:
    z: np.ndarray
    regime: Regime
    event: tuple | None


_KINDS = ("tyre", "zone", "stop")


def _trace(s: System, z0: np.ndarray, rg: Regime, phase: int, llt_limit: float | None, watch: int | None,
           orient: float):  # fmt: skip
    """Follow the path from ``z0`` event by event. Returns the vertices (state, regime, event that ended the piece)
    and why it ended: ``"stop"`` (t = 1, or a group at the LLT limit) or ``"end"`` (the last piece, no more events)."""
    n = s.n
    vertices = [_Vertex(z0.copy(), Regime(list(rg.tyre), list(rg.zone)), None)]
    z = z0.copy()
    last = None
    prev_d = None
    max_steps = 8 * (len(s.tyres) + len(s.zones)) + 40
    for _ in range(max_steps):
        piece, jp, (c1, c2, b, i1, i2, ends, scale), back_rows = _step_terms(s, rg, phase, llt_limit)
        d = _null_direction(s, piece, jp)
        rates = c1 * d[i1] + c2 * d[i2]
        # orientation: the first piece by the outward roll of the sprung masses; a later one into its own interior
        if last is None:
            w = float(s.weights @ d[:n])
            if w == 0.0:
                w = d[n]
            if w * orient < 0:
                d, rates = -d, -rates
        else:
            kind, idx, previous = last
            back = back_rows.get((kind, idx, previous))
            rate = float(rates[back]) if back is not None else 0.0
            if abs(rate) > 1e-14:
                if rate < 0:
                    d, rates = -d, -rates
            elif prev_d is not None and float(prev_d @ d) < 0:
                d, rates = -d, -rates
        falling = (rates < -1e-15).nonzero()[0]
        if not len(falling):
            vertices.append(_Vertex(z.copy(), Regime(list(rg.tyre), list(rg.zone)), ("end", d)))
            return vertices, "end"
        # the step to each falling row's bound (its rate is negative: no division by zero, no errstate needed);
        # the first of the nearest, as argmin over all rows with the others at infinity would pick
        value = (c1 * z[i1] + c2 * z[i2] + b)[falling]
        tau = np.where(value > -TOL * scale[falling], np.maximum(value, 0.0) / -rates[falling], 0.0)
        k = int(np.argmin(tau))
        row, best = int(falling[k]), float(tau[k])
        kc, idx, state = ends[row].tolist()
        which = (_KINDS[kc], idx, None if kc == 2 else state)
        z = z + best * d
        prev_d = d
        vertices.append(_Vertex(z.copy(), Regime(list(rg.tyre), list(rg.zone)), which))
        kind = which[0]
        if kind == "stop":
            return vertices, "stop"
        if phase == 2 and kind == "tyre" and state == LIFTED and sum(x == LINEAR for x in rg.tyre) == 1:
            # the last group in contact on both sides lifts: the unit stands on its outer wheels, and past this
            # point every equilibrium needs less ay (the path beyond is no state a vehicle passes through)
            rg.tyre[idx] = state
            vertices.append(_Vertex(z.copy(), Regime(list(rg.tyre), list(rg.zone)), ("all-lifted", idx, state)))
            return vertices, "all-lifted"
        if kind == "tyre":
            previous, rg.tyre[idx] = rg.tyre[idx], state
        else:
            previous, rg.zone[idx] = rg.zone[idx], state
        last = (kc, idx, previous)
    raise ConvergenceError(f"the roll path did not end within {max_steps} events", iterations=max_steps)


# ------------------------------------------------------------------------------------------- results


@dataclass(frozen=True)
class UnitSolution:
    """The path of one roll-coupled unit and its limit."""

    system: System
    vertices: list
    peak: int  # index of the vertex at the limit
    limit: str
    watch: tuple[float, np.ndarray, Regime] | None  # (ay, z, regime) when the watched group reached the limit

    @property
    def srt(self) -> float:
        return float(self.vertices[self.peak].z[self.system.n])


def _state_at(s: System, rg: Regime, ay: float) -> np.ndarray:
    """The equilibrium roll angles of one regime at a given ay (its equations solved for q)."""
    jp, k = _assemble(s, rg, 2)
    return _tree_solve(s, tuple(rg.tyre), tuple(rg.zone), -(jp * ay + k))


def _consistent(s: System, q: np.ndarray, ay: float) -> Regime:
    """The regime the state ``q`` lies in, each element's state read off its own law."""
    tyres = []
    for t in s.tyres:
        m, cap = t.k * q[t.dof], s.cap(t, ay)
        tyres.append(LIFTED if m > cap else LIFTED_OUT if m < -cap else LINEAR)
    zones = []
    for z in s.zones:
        d = q[z.i] - q[z.j]
        zones.append(BAND if z.lash <= 0 or abs(d) <= z.lash else PLUS if d > 0 else MINUS)
    return Regime(tyres, zones)


def _residual(s: System, q: np.ndarray, ay: float) -> np.ndarray:
    """The net restoring moment on every DOF, from the laws themselves (the gradient of :func:`_potential`)."""
    r = s.road
    out = -(s.P @ q) - (r.l0 + r.l1 * ay) * s.lat - (r.n0 + r.n1 * ay) * s.off
    for t in s.tyres:
        cap = s.cap(t, ay)
        out[t.dof] += min(cap, max(-cap, t.k * q[t.dof]))
    for z in s.zones:
        d = q[z.i] - q[z.j]
        m = z.k * (d - z.lash if d > z.lash else d + z.lash if d < -z.lash else 0.0)
        out[z.i] += m
        out[z.j] -= m
    return out


def _potential(s: System, q: np.ndarray, ay: float) -> float:
    """The potential energy of the roll degrees of freedom at a fixed ay [kN m rad]: springs and dead zones, tyres
    up to lift-off and their constant moment beyond, minus the P-Delta work and the loads' work."""
    r = s.road
    v = -0.5 * float(q @ s.P @ q) - float(((r.l0 + r.l1 * ay) * s.lat + (r.n0 + r.n1 * ay) * s.off) @ q)
    for t in s.tyres:
        cap, x = s.cap(t, ay), q[t.dof]
        v += 0.5 * t.k * x * x if abs(t.k * x) <= cap else cap * abs(x) - cap * cap / (2.0 * t.k)
    for z in s.zones:
        d = abs(q[z.i] - q[z.j])
        if d > z.lash:
            v += 0.5 * z.k * (d - z.lash) ** 2
    return v


def _settled(s: System, q: np.ndarray, ay: float, made_in: Regime | None = None) -> tuple[np.ndarray, Regime] | None:
    """``q`` polished to its regime's exact equilibrium, if that lies in the same regime and is stable (``made_in``:
    the regime whose equilibrium ``q`` already is, when known: polishing it again would give the same bits)."""
    rg = _consistent(s, q, ay)
    if made_in is not None and rg.tyre == made_in.tyre and rg.zone == made_in.zone:
        exact = q
    else:
        try:
            exact = _state_at(s, rg, ay)
        except np.linalg.LinAlgError:
            return None
    again = _consistent(s, exact, ay)
    if again.tyre != rg.tyre or again.zone != rg.zone:
        return None
    try:  # stable: J positive definite, which the signs of its pivots tell (Sylvester's law of inertia)
        stable = roll_tree.positive(_pivots(s, tuple(rg.tyre), tuple(rg.zone))[1])
    except roll_tree.Singular:
        return None
    return (exact, rg) if stable else None


def _start(s: System) -> tuple[np.ndarray, Regime]:
    """The state at rest on the road with the load offsets (zero lateral force: ay = tan(b) cos(s)): a stable
    equilibrium, a minimum of the potential energy (every law derives from one, so the residual is its gradient).

    Inside a lash a sprung mass has no stiffness of its own and leans until a lash is taken up. First guess: every
    lash taken up in the sense its element is loaded at rest, or, where nothing loads it, in the sense the first
    lateral acceleration loads it (both from the equations without lash), a coupling left free where that leaves it
    inside its lash. When that guess is not an equilibrium in its own regime, the potential is minimised (BFGS from
    the state without lash, leaning outward) and the minimum polished in its regime."""
    n = s.n
    ay0 = s.road.neutral_ay
    lashless = replace(s, zones=[DeadZone(z.i, z.j, z.k, 0.0, z.kind, z.ref) for z in s.zones],
                       cache=s.cache.setdefault("lashless", {}))  # fmt: skip
    linear = Regime([LINEAR] * len(s.tyres), [BAND] * len(s.zones))
    q0 = _state_at(lashless, linear, ay0)
    if not any(z.lash > 0 for z in s.zones):
        found = _settled(s, q0, ay0, linear)
        if found is None:
            raise InvalidLoad("the vehicle does not stand at rest with this load case", field="load.lateral_offset_m")
        return np.append(found[0], ay0), found[1]
    dq = None  # how the first ay loads each element: solved only for a suspension that nothing loads at rest
    zones = []
    for z in s.zones:
        d = q0[z.i] - q0[z.j]
        if z.lash <= 0:
            zones.append(BAND)
        elif abs(d) > 1e-12:
            zones.append(PLUS if d > 0 else MINUS)
        elif z.kind == "coupling":
            zones.append(BAND)
        else:
            if dq is None:
                jp, _k = _assemble(lashless, linear, 2)
                dq = _tree_solve(lashless, tuple(linear.tyre), tuple(linear.zone), -jp)
            zones.append(PLUS if dq[z.i] - dq[z.j] >= 0 else MINUS)
    guess = Regime([LINEAR] * len(s.tyres), zones)
    for _ in range(len(s.zones) + 2):
        try:
            q = _state_at(s, guess, ay0)
        except np.linalg.LinAlgError:
            break
        found = _settled(s, q, ay0, guess)
        if found is not None:
            return np.append(found[0], ay0), found[1]
        guess = _consistent(s, q, ay0)
    from scipy.optimize import minimize

    lean = np.zeros(n)
    for z in s.zones:  # start leaning outward just past every lash
        lean[z.i] += 1.01 * z.lash
    res = minimize(lambda x: _potential(s, x, ay0), q0 + lean, jac=lambda x: _residual(s, x, ay0), method="BFGS",
                   options={"gtol": 1e-10, "maxiter": 2000})  # fmt: skip
    found = _settled(s, res.x, ay0)
    if found is None:
        raise ConvergenceError("no stable state at rest was found for this load case (the vehicle may fall over)")
    return np.append(found[0], ay0), found[1]


def solve_unit(s: System, llt_limit: float, watch_tyre: int | None) -> UnitSolution:
    """The stepped solution of one roll-coupled unit: from its state at rest with the load offsets (:func:`_start`),
    ay up to the limit (the largest ay on the path, or a non-steer group at ``llt_limit`` < 1).

    On a bank the normal load grows with ay (``n(ay) = n0 + sin(b) ay``) and with it the P-Delta terms: each piece of
    the path is solved with those terms at one normal factor, and that factor is brought to the limit's own (a fixed
    point on the SRT, secant steps), so the state at the limit is the exact equilibrium there. The states before it
    (the earlier lift-offs) carry the limit's factor: on a 10 % bank they are a few thousandths of a g off theirs."""
    sol = _solve_unit_at(s, llt_limit, watch_tyre)
    r = s.road
    if r.n1 == 0.0:
        return sol
    # the first solve is the fixed-point map at ay = 0 (the normal factor at rest): with it the secant starts at once,
    # from the limit that the rest solve's last piece and event give at their own fixed point (Newton on that vertex
    # alone: one more path, not three, when the path at the limit's factor ends in the same piece)
    a0, g0 = 0.0, sol.srt
    a1 = sol.srt
    if sol.peak > 0:
        v = sol.vertices[sol.peak]
        c1, c2, b, i1, i2, ends, _scale = _constraint_rows(s, v.regime, 2, llt_limit if llt_limit < 1.0 else None)
        kind, idx, state = v.event
        code = (_KINDS.index(kind), idx, 0 if state is None else state)
        row = next(k for k, e in enumerate(ends.tolist()) if tuple(e) == code)
        e = _elements(s)
        kd, ke = e.tree_piece(tuple(v.regime.tyre), tuple(v.regime.zone))
        jp, k = _assemble(s, v.regime, 2)
        a1 = _vertex_fixed_point(
            e.tree, kd, ke, jp.tolist(), k.tolist(), float(c1[row]), float(c2[row]), float(b[row]), int(i1[row]),
            int(i2[row]), np.diagonal(s.P_normal).tolist(), np.diagonal(s.P_grade).tolist(), r.n0, r.n1, r.grade,
            sol.srt,
        )  # fmt: skip
    for _ in range(30):
        sol = _solve_unit_at(s.at_normal(r.n0 + r.n1 * a1), llt_limit, watch_tyre)
        g1 = sol.srt - a1
        if abs(g1) <= 1e-13:
            return sol
        if g0 is None or g1 == g0:
            a0, g0, a1 = a1, g1, sol.srt
        else:
            a0, g0, a1 = a1, g1, a1 - g1 * (a1 - a0) / (g1 - g0)
    raise ConvergenceError("the normal factor of the P-Delta terms did not settle at the limit")


def _vertex_fixed_point(t, kd, ke, jp, k, c1, c2, b, i1, i2, pn, pg, n0, n1, grade, a):
    """The point of a piece's line ``(K - P(N)) q + jp ay + k = 0`` where its event's constraint ``c1 x[i1] + c2 x[i2]
    + b = 0`` holds (x = (q, ay): an index n is ay), with the P-Delta terms ``P(N) = N Pn + grade Pg`` at that
    point's own normal factor ``N = n0 + n1 ay``: a few Newton steps on ay from ``a`` (:func:`_vertex_step`).

    One row (floats: the scalar solve, ``i1``, ``i2`` ints) or many (arrays of shape (m,), ``i1``, ``i2`` int arrays:
    :mod:`engine.models.combination_batch`): the same operations on each row, so a row gives the scalar's bits. K is
    given on its tree (:meth:`_Elements.tree_piece`: ``kd`` its diagonal, ``ke`` its edges); ``jp``, ``k`` are columns
    (one entry per DOF), ``pn``, ``pg`` the diagonals of Pn and Pg (both diagonal) as floats. A row stops at its own
    last step, or where its system is singular (it keeps its ay there)."""
    if isinstance(a, float):
        for _ in range(8):
            try:
                step = _vertex_step(t, kd, ke, jp, k, c1, c2, b, i1, i2, pn, pg, n0, n1, grade, a)
            except (roll_tree.Singular, ZeroDivisionError):
                break
            if not math.isfinite(step):
                break
            a -= step
            if abs(step) <= 1e-15:
                break
        return a
    a = np.array(a, dtype=float)
    n0, n1, grade = (np.broadcast_to(np.asarray(x, dtype=float), a.shape) for x in (n0, n1, grade))
    i1, i2 = _rows_by_index(i1), _rows_by_index(i2)
    moving = np.ones(a.shape, dtype=bool)
    for _ in range(8):
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            step, singular = _vertex_step(t, kd, ke, jp, k, c1, c2, b, i1, i2, pn, pg, n0, n1, grade, a)
        moving &= ~singular & np.isfinite(step)
        a = np.where(moving, a - step, a)
        moving &= np.abs(step) > 1e-15
        if not moving.any():
            break
    return a


def _rows_by_index(i: np.ndarray) -> list[tuple[int, np.ndarray | None]]:
    """The rows of each distinct index in ``i`` (None: every row), for :func:`_pick`."""
    if (i == i[0]).all():
        return [(int(i[0]), None)]
    return [(v, np.flatnonzero(i == v)) for v in np.unique(i).tolist()]


def _pick(x: list, i, last):
    """x[i] of a column list extended by x[n] = ``last``: i an int (one row), or for columns of many rows each row's
    own index, as :func:`_rows_by_index` groups them (a gather: no arithmetic)."""
    n = len(x)
    if isinstance(i, int):
        return x[i] if i < n else last
    if i[0][1] is None:
        v = i[0][0]
        return x[v] if v < n else np.full(x[0].shape, last)
    out = np.empty(x[0].shape)
    for v, rows in i:
        out[rows] = x[v][rows] if v < n else last
    return out


def _vertex_step(t, kd, ke, jp, k, c1, c2, b, i1, i2, pn, pg, n0, n1, grade, a):
    """One Newton step of :func:`_vertex_fixed_point` at ay = ``a`` (floats; with arrays also the rows whose J has a
    zero pivot, whose values are meaningless).

    The vertex x = (q, ay) solves the bordered system ``J q + jp ay = -k``, ``c1 x[i1] + c2 x[i2] = -b``: with ``J u =
    -k`` and ``J w = jp``, q = u - ay w, so ay = (c1 u[i1] + c2 u[i2] + b) / (c1 w[i1] + c2 w[i2]) (u[n] = 0, w[n] =
    -1). Its derivative in ``a`` solves the same system with the right-hand side (n1 Pn q, 0) (dJ/da = -n1 Pn); the
    step is Newton's on g(a) = ay(a) - a."""
    n = t.n
    normal = n0 + n1 * a
    f = roll_tree.factor(t, [kd[v] - (normal * pn[v] + grade * pg[v]) for v in range(n)], ke)
    u = roll_tree.solve(t, f, [-x for x in k])
    w = roll_tree.solve(t, f, jp)
    den = c1 * _pick(w, i1, -1.0) + c2 * _pick(w, i2, -1.0)
    ay = (c1 * _pick(u, i1, 0.0) + c2 * _pick(u, i2, 0.0) + b) / den
    dq = roll_tree.solve(t, f, [pn[v] * (u[v] - ay * w[v]) for v in range(n)])
    day = (c1 * _pick(dq, i1, 0.0) + c2 * _pick(dq, i2, 0.0)) / den
    step = (ay - a) / (day * n1 - 1.0)
    if isinstance(a, float):
        return step
    return step, roll_tree.zero_pivot(f)


def _solve_unit_at(s: System, llt_limit: float, watch_tyre: int | None) -> UnitSolution:
    """:func:`solve_unit` with the P-Delta terms at the system's own normal factor."""
    n = s.n
    z, rg = _start(s)
    if any(state != LINEAR for state in rg.tyre):
        raise InvalidLoad(
            "the load offset lifts a group off the road at rest: the vehicle would tip over",
            field="load.lateral_offset_m",
        )
    z[n] = s.road.neutral_ay
    limit = llt_limit if llt_limit < 1.0 else None
    vs, why = _trace(s, z, rg, 2, limit, watch_tyre, orient=1.0)
    ays = [v.z[n] for v in vs]
    if why == "stop":
        peak = int(np.argmax(ays))
        limit_kind = "llt-limit" if peak == len(vs) - 1 else "rollover"
    else:
        if why == "end" and vs[-1].event[1][n] > 1e-12:
            raise ConvergenceError("the roll path never turns: no rollover limit was found")
        peak = int(np.argmax(ays))
        limit_kind = "rollover"
    watch = _watched(s, vs, peak, watch_tyre, llt_limit)
    return UnitSolution(s, vs, peak, limit_kind, watch)


def _describe(s: System, c: Combination, event) -> str:
    kind, idx, state = event
    if kind == "tyre":
        t = s.tyres[idx]
        g, u = c.units[t.unit].groups[t.group], c.units[t.unit]
        if state == LIFTED:
            return f"the inner tyres of group {g.id!r} of {u.id!r} lift off"
        return f"group {g.id!r} of {u.id!r} changes contact"
    if kind == "zone":
        z = s.zones[idx]
        if z.kind == "suspension":
            u, j = z.ref
            return f"the lash of the {c.units[u].groups[j].id!r} suspension of {c.units[u].id!r} is taken up"
        return f"the fifth-wheel lash behind {c.units[z.ref[0]].id!r} is taken up"
    t = s.tyres[idx]
    return f"group {c.units[t.unit].groups[t.group].id!r} of {c.units[t.unit].id!r} reaches the LLT limit"


def _watched(s: System, vs, peak, watch_tyre, llt_limit):
    """(ay, z, regime) where the watched tyres first reach the LLT limit (lift off at 1), at or before the peak."""
    if watch_tyre is None:
        return None
    n = s.n
    t = s.tyres[watch_tyre]
    for k in range(1, peak + 1):
        a, b = vs[k - 1].z, vs[k].z
        rg = vs[k - 1].regime
        if rg.tyre[watch_tyre] != LINEAR:
            return b[n], b, vs[k].regime
        la, lb = _llt_linear(s, t, a), _llt_linear(s, t, b)
        if lb >= llt_limit - 1e-12:
            f = (llt_limit - la) / (lb - la) if lb != la else 1.0
            z = a + f * (b - a)
            return z[n], z, rg
    return None


def _llt_linear(s: System, t: Tyres, z: np.ndarray) -> float:
    return t.k * z[t.dof] / s.cap(t, z[s.n])


def _tyre_moment(s: System, t: Tyres, state: int, z: np.ndarray) -> float:
    if state == LINEAR:
        return t.k * z[t.dof]
    return state * s.cap(t, z[s.n])


def _zone_moment(z_el: DeadZone, state: int, z: np.ndarray) -> float:
    d = z[z_el.i] - z[z_el.j]
    if z_el.lash <= 0:
        return z_el.k * d
    if state == BAND:
        return 0.0
    return z_el.k * (d - z_el.lash * state)


def unit_result(c: Combination, sol: UnitSolution) -> RollCoupledUnitResult:
    """The answer of one roll-coupled unit, in words and numbers."""
    s, vs = sol.system, sol.vertices
    n = s.n
    v = vs[sol.peak]
    z, rg = v.z, _regime_at(vs, sol.peak)
    ay = float(z[n])
    groups = []
    for idx, t in enumerate(s.tyres):
        m = _tyre_moment(s, t, rg.tyre[idx], z)
        cap = s.cap(t, ay)
        normal = 2.0 * cap / t.track
        susp = next(zz for zz in s.zones if zz.kind == "suspension" and zz.ref == (t.unit, t.group))
        sidx = s.zones.index(susp)
        groups.append(
            GroupState(
                unit=c.units[t.unit].id,
                group=c.units[t.unit].groups[t.group].id,
                llt=float(m / cap),
                outer_kn=float(normal / 2.0 + m / t.track),
                inner_kn=float(normal / 2.0 - m / t.track),
                axle_roll_deg=math.degrees(z[t.dof]),
                suspension_moment_knm=float(_zone_moment(susp, rg.zone[sidx], z)),
                lifted=bool(rg.tyre[idx] == LIFTED or m >= cap * (1.0 - 1e-9)),
            )
        )
    couplings = []
    r = s.road
    for i, v0, vg in s.couplings:
        zone = next((k for k, zz in enumerate(s.zones) if zz.kind == "coupling" and zz.ref == (i, -1)), None)
        moment = _zone_moment(s.zones[zone], rg.zone[zone], z) if zone is not None else 0.0
        couplings.append(
            CouplingState(
                towing_unit=c.units[i].id,
                towed_unit=c.units[i + 1].id,
                kind=c.couplings[i].kind,
                roll_moment_knm=float(moment),
                vertical_load_kn=float((r.n0 + r.n1 * ay) * v0 + r.grade * vg),
            )
        )
    lifts = []
    for k in range(1, sol.peak + 1):
        e = vs[k].event
        if e and e[0] == "tyre" and e[2] == LIFTED:
            t = s.tyres[e[1]]
            lifts.append(LiftEvent(c.units[t.unit].id, c.units[t.unit].groups[t.group].id, float(vs[k].z[n])))
    # groups that reach lift-off at the limit together with the event that ends the path (a tie within rounding:
    # the path records one event per step, so the other arrives a step later, past the peak) lifted there too
    listed = {(e.unit, e.group) for e in lifts}
    lifts += [LiftEvent(g.unit, g.group, float(ay)) for g in groups if g.lifted and (g.unit, g.group) not in listed]
    event = vs[sol.peak].event
    if event is not None and event[0] == "all-lifted":
        event = ("tyre", event[1], event[2])
    if sol.limit == "llt-limit":
        ended = _describe(s, c, event)
    elif event is not None and event[0] != "end":
        ended = (
            f"the largest lateral acceleration it holds, reached when {_describe(s, c, event)}; past it every "
            "equilibrium needs less (the vehicle rolls over)"
        )
    else:
        ended = "the largest lateral acceleration it holds"
    return RollCoupledUnitResult(
        units=tuple(c.units[u].id for u in s.units),
        srt=ay,
        limit=sol.limit,
        ended_by=ended,
        roll_angle_deg={c.units[u].id: math.degrees(z[s.body[u]]) for u in s.units},
        groups=tuple(groups),
        couplings=tuple(couplings),
        lift_sequence=tuple(lifts),
    )


def _regime_at(vs, k: int) -> Regime:
    """The regime in force *at* vertex k: the state before its event switched anything (the limit's own state)."""
    return vs[k].regime


def front_llt_ratio(c: Combination, systems: list[System], sols: list[UnitSolution]) -> float | None:
    """LLTf/LLTr of the last unit at its watched state (see :class:`engine.results.CombinationDetail`)."""
    if len(c.units) < 2 or not c.couplings[-1].transmits_roll:
        return None
    s, sol = systems[-1], sols[-1]
    fu, fg = kingpin_group(c, len(c.units) - 1)
    last = len(c.units) - 1
    t_front = next(i for i, t in enumerate(s.tyres) if (t.unit, t.group) == (fu, fg))
    t_rear = next(i for i, t in enumerate(s.tyres) if t.unit == last)
    if sol.watch is not None:
        ay, z, rg = sol.watch
    else:
        z, rg = sol.vertices[sol.peak].z, _regime_at(sol.vertices, sol.peak)
        ay = z[s.n]

    def llt(i):
        t = s.tyres[i]
        return _tyre_moment(s, t, rg.tyre[i], z) / s.cap(t, ay)

    rear = llt(t_rear)
    return float(llt(t_front) / rear) if rear > 0 else None


def solve_combination(
    c: Combination, *, bank_percent: float = 0.0, slope_percent: float = 0.0, load: UnitLoad | None = None,
    llt_limit: float = 1.0,
) -> CombinationDetail:  # fmt: skip
    """Every roll-coupled unit's SRT and state, the governing one, and LLTf/LLTr of the last unit.

    Parameters
    ----------
    c : the combination (validated by :func:`engine.vehicle.combination.validate_combination`)
    bank_percent, slope_percent : the road (+ bank toward the inside of the curve, + grade uphill) [%]
    load : the load case of the load-carrying units (:class:`engine.vehicle.combination.UnitLoad`)
    llt_limit : 1 for the largest ay each unit holds; below 1, the ay at which a non-steer group's LLT reaches it [-]
    """
    load = load or UnitLoad()
    systems = build_systems(c, bank_percent, slope_percent, load)
    last = len(c.units) - 1
    sols = []
    for s in systems:
        watch = None
        if last in s.body and len(c.units) > 1:
            watch = next(i for i, t in enumerate(s.tyres) if t.unit == last)
        sols.append(solve_unit(s, llt_limit, watch))
    results = tuple(unit_result(c, sol) for sol in sols)
    governing = min(range(len(results)), key=lambda k: results[k].srt)
    return CombinationDetail(results, governing, front_llt_ratio(c, systems, sols))


def rigid_srt(c: Combination, *, bank_percent: float = 0.0, slope_percent: float = 0.0,
              load: UnitLoad | None = None) -> list[float]:  # fmt: skip
    """The rigid-vehicle SRT of each roll-coupled unit: every group at lift-off with no roll,
    ``sum_g N_g T_g/2 = l(ay) sum(W h) + n(ay) sum(W d1)`` solved for ay (on a level road ``sum(N T/2 - W d1) /
    sum(W h)``; Eq. 2.6 for one unit) [g]."""
    out = []
    for s in build_systems(c, bank_percent, slope_percent, load or UnitLoad()):
        r = s.road
        cap_n = sum(t.cap_normal for t in s.tyres)
        cap_g = sum(t.cap_grade for t in s.tyres)
        lat, off = float(s.lat.sum()), float(s.off.sum())
        # (n0 + n1 ay) cap_n + grade cap_g = (l0 + l1 ay) lat + (n0 + n1 ay) off
        out.append(
            (r.l0 * lat + r.n0 * off - r.n0 * cap_n - r.grade * cap_g) / (r.n1 * cap_n - r.l1 * lat - r.n1 * off)
        )
    return out

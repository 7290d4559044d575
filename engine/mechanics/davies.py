"""Generic Davies-method statics (Sec. 3.2, Appendix A); knows nothing about vehicles.

Steps, as numbered in Sec. 3.2:

- 1-2: the mechanism's links are the vertices and its joints and external actions the edges of the direct
  coupling graph G_A, each edge oriented from the minor to the major vertex (:mod:`engine.mechanics.mechanism`);
- 3: incidence matrix [I]_{n, j+f} (:func:`incidence_matrix`);
- 4: cut-set matrix [Q]_{k, j+f} by Gauss-Jordan elimination, k = n - 1 cuts; the pivot columns are the
  branches of a spanning tree, the others the chords (:func:`cutset_matrix`);
- 5: expanded cut-set matrix [Q]_{k, c}: every edge's column repeated once per constraint it carries
  (:func:`expanded_cutset`);
- 6-7: unit action matrix [A_n]_{lambda k, c}: each entry of the expanded cut-set matrix multiplied by the
  constraint's unit wrench (Eq. 3.4), i.e. the Kirchhoff-Davies cut-set law "the wrenches crossing
  each cut sum to zero" written for unit magnitudes (:func:`unit_action_matrix`, Eqs. 5.9/6.10);
- 8: split the magnitudes into primary (given) and secondary (unknown) ones and solve
  [A_ns] [Psi_s] = -[A_np] [Psi_p] (Eqs. 5.11/6.12), together with any closure equations the caller
  adds (the thesis closes the 3D trailer with Eqs. 4.27, 4.21, 4.22, Eq. 6.19) (:func:`solve_statics`).

The solve is by singular value decomposition. The rank tells whether the equations determine the
secondary variables; when they do not (the 3D trailer has 132 cut-set equations for 147 unknowns), the
null space says *which* variables are still free: a variable is determined exactly when its row of the
null-space basis vanishes. :class:`StaticsSolution` refuses to report an undetermined quantity, and
:func:`solve_statics` refuses an inconsistent system (residual above tolerance), both with
:class:`~engine.errors.MechanismSingular`.

References
----------
Davies, T. H. (1981, 1983, 1995, 2000); Erthal (2010); Mejia et al. (2013); thesis App. A.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field

import numpy as np

from engine.errors import MechanismSingular
from engine.mechanics.mechanism import Mechanism

#: rows of the 6-vector wrench [Mx, My, Mz, Fx, Fy, Fz] kept for a spatial (lambda = 6) mechanism
SPATIAL = (0, 1, 2, 3, 4, 5)
#: rows kept for a planar mechanism in the y-z plane (lambda = 3): [Mx, Fy, Fz] (Sec. 5.1.2)
PLANAR_YZ = (0, 4, 5)


def incidence_matrix(mech: Mechanism) -> np.ndarray:
    """Incidence matrix [I]_{n, j+f} of the direct coupling graph (Eqs. 5.6, 6.7, A.9).

    ``I[v, e] = +1`` if link v is the tail (minor vertex) of edge e, ``-1`` if it is the head.
    """
    out = np.zeros((len(mech.links), len(mech.edges)), dtype=np.int64)
    for e, edge in enumerate(mech.edges):
        out[edge.tail, e] = 1
        out[edge.head, e] = -1
    return out


@dataclass(frozen=True)
class CutSet:
    """Cut-set matrix Q (k x edges) with its branches (pivot columns) and chords."""

    q: np.ndarray
    branches: tuple[int, ...]
    chords: tuple[int, ...]


def cutset_matrix(incidence: np.ndarray) -> CutSet:
    """Cut-set matrix [Q]_{k, j+f} from the incidence matrix by Gauss-Jordan elimination (Eqs. 5.7, A.10).

    Pivots are taken column by column from the left, so the edges listed first (the joints) become the
    branches of the spanning tree and the later ones (the external actions) chords, as in the thesis.
    An incidence matrix is totally unimodular: every entry stays in {-1, 0, 1} and the arithmetic is exact.
    Raises :class:`MechanismSingular` if the graph is not connected.
    """
    a = incidence.astype(np.int64).copy()
    n, m = a.shape
    row = 0
    pivots: list[int] = []
    for col in range(m):
        if row == n:
            break
        candidates = np.nonzero(a[row:, col])[0]
        if candidates.size == 0:
            continue
        r = row + int(candidates[0])
        a[[row, r]] = a[[r, row]]
        a[row] *= a[row, col]  # pivot is +-1: make it +1
        for other in range(n):
            if other != row and a[other, col] != 0:
                a[other] -= a[other, col] * a[row]
        pivots.append(col)
        row += 1
    if row != n - 1:
        raise MechanismSingular(f"the coupling graph is not connected (rank {row}, expected {n - 1})")
    chords = tuple(c for c in range(m) if c not in pivots)
    return CutSet(a[: n - 1], tuple(pivots), chords)


def expanded_cutset(mech: Mechanism, cutset: CutSet) -> np.ndarray:
    """Expanded cut-set matrix [Q]_{k, c}: each edge column repeated once per constraint (Eqs. 5.8, 6.9)."""
    cols = [cutset.q[:, e] for e, edge in enumerate(mech.edges) for _ in edge.constraints]
    return np.stack(cols, axis=1)


def unit_action_matrix(mech: Mechanism, cutset: CutSet | None = None, space=SPATIAL) -> np.ndarray:
    """Unit action matrix [A_n]_{lambda k, c} (Eqs. 5.9-5.10, 6.10-6.11).

    Row block r holds the cut-set law of cut r: the sum over the constraints c of Q[r, edge(c)] times the
    unit wrench of c, restricted to the ``space`` components (lambda = len(space)).
    """
    if cutset is None:
        cutset = cutset_matrix(incidence_matrix(mech))
    wrenches = np.stack([c.wrench[list(space)] for e in mech.edges for c in e.constraints], axis=1)
    q = expanded_cutset(mech, cutset).astype(float)
    lam = len(space)
    # block row r: q[r, c] * wrenches[:, c]
    return (q[:, None, :] * wrenches[None, :, :]).reshape(q.shape[0] * lam, wrenches.shape[1])


@dataclass(frozen=True)
class Closure:
    """An extra linear equation on the magnitudes: ``sum(coef[name] * Psi[name]) + constant = 0``.

    Coefficients may name secondary or primary variables. This is how the thesis closes the 3D trailer
    (Eq. 6.19: the load split Eq. 4.27 and the chassis torsion split Eqs. 4.21-4.22).
    """

    coefficients: Mapping[str, float]
    constant: float = 0.0
    label: str = ""


@dataclass
class StaticsSolution:
    """Solution of the Davies equations.

    values : least-norm solution for every secondary variable (and the given primaries)
    determined : names whose value the equations fix uniquely (zero row in the null-space basis)
    rank, nullity : of the secondary coefficient matrix with the closures appended
    residual : relative residual of the solve (0 for a consistent system)
    """

    values: dict[str, float]
    determined: frozenset[str]
    rank: int
    nullity: int
    n_equations: int
    n_unknowns: int
    residual: float
    null_space: np.ndarray = field(repr=False)
    secondary: tuple[str, ...] = field(repr=False, default=())

    def __getitem__(self, name: str) -> float:
        if name not in self.values:
            raise KeyError(name)
        if name not in self.determined:
            raise MechanismSingular(
                f"{name} is not determined by the statics: it has a component in the {self.nullity}-dimensional "
                "null space; add a closure equation that fixes it"
            )
        return self.values[name]

    def get(self, names: Iterable[str]) -> dict[str, float]:
        return {n: self[n] for n in names}


def solve_statics(
    mech: Mechanism,
    primary: Mapping[str, float],
    closures: Iterable[Closure] = (),
    *,
    space=SPATIAL,
    require: Iterable[str] = (),
    extra_unknowns: Iterable[str] = (),
    rtol: float = 1e-10,
) -> StaticsSolution:
    """Solve the cut-set equations for the secondary magnitudes given the primary ones (Eq. 6.12).

    Parameters
    ----------
    mech : the mechanism (links, joints, external actions)
    primary : values of the primary variables (e.g. ``{"Px": .., "Py": .., "Pz": ..}``) [kN, kN m]
    closures : extra equations appended below the cut-set equations (Eq. 6.19)
    space : wrench components kept (:data:`SPATIAL` or :data:`PLANAR_YZ`)
    require : names that must come out determined; :class:`MechanismSingular` otherwise
    extra_unknowns : scalar unknowns that appear only in closures (e.g. the lateral acceleration when the
        limit condition is itself a closure and the primaries become unknowns tied to it)
    rtol : relative tolerance for rank, null space and consistency

    Raises
    ------
    MechanismSingular : inconsistent equations, or a required quantity left in the null space.
    """
    names = mech.variable_names + list(extra_unknowns)
    if len(set(names)) != len(names):
        dup = sorted({n for n in names if names.count(n) > 1})
        raise ValueError(f"duplicate magnitude names: {dup}")
    index = {n: i for i, n in enumerate(names)}
    unknown = [n for n in primary if n not in index]
    if unknown:
        raise KeyError(f"primary variables not in the mechanism: {unknown}")
    a = unit_action_matrix(mech, space=space)
    n_extra = len(names) - a.shape[1]
    if n_extra:
        a = np.hstack((a, np.zeros((a.shape[0], n_extra))))
    closures = list(closures)
    if closures:
        rows = np.zeros((len(closures), len(names)))
        consts = np.zeros(len(closures))
        for r, cl in enumerate(closures):
            for n, c in cl.coefficients.items():
                if n not in index:
                    raise KeyError(f"closure {cl.label!r} names unknown variable {n!r}")
                rows[r, index[n]] += c
            consts[r] = cl.constant
        a = np.vstack((a, rows))
    else:
        consts = np.zeros(0)
    const = np.concatenate((np.zeros(a.shape[0] - consts.size), consts))
    p_idx = [index[n] for n in primary]
    s_idx = [i for i in range(len(names)) if i not in set(p_idx)]
    p_val = np.array([float(primary[n]) for n in primary])
    a_s = a[:, s_idx]
    b = -(a[:, p_idx] @ p_val + const)

    u, sv, vt = np.linalg.svd(a_s, full_matrices=True)
    tol = rtol * (sv[0] if sv.size else 1.0) * max(a_s.shape)
    rank = int(np.sum(sv > tol))
    ub = u[:, :rank].T @ b
    x = vt[:rank].T @ (ub / sv[:rank])
    scale = max(np.linalg.norm(b), np.max(np.abs(a[:, p_idx]), initial=0.0) * np.linalg.norm(p_val), 1e-300)
    residual = float(np.linalg.norm(a_s @ x - b) / scale)
    null = vt[rank:].T  # columns span the null space of a_s
    secondary = tuple(names[i] for i in s_idx)
    if residual > 1e3 * rtol:
        raise MechanismSingular(
            f"the statics are inconsistent (relative residual {residual:.2e}): the closures contradict the "
            "cut-set equations or the loads cannot be carried by the mechanism"
        )
    row_norm = np.linalg.norm(null, axis=1) if null.size else np.zeros(len(s_idx))
    determined = frozenset(n for n, rn in zip(secondary, row_norm, strict=True) if rn <= 1e-8)
    values = dict(zip(secondary, x.tolist(), strict=True))
    values.update({n: float(primary[n]) for n in primary})
    determined = determined | frozenset(primary)
    sol = StaticsSolution(
        values=values,
        determined=determined,
        rank=rank,
        nullity=len(s_idx) - rank,
        n_equations=a.shape[0],
        n_unknowns=len(s_idx),
        residual=residual,
        null_space=null,
        secondary=secondary,
    )
    missing = [n for n in require if n not in determined]
    if missing:
        raise MechanismSingular(
            f"not determined by the statics: {', '.join(missing)} (null space of dimension {sol.nullity})"
        )
    return sol

"""The roll equations of one roll-coupled unit solved on their tree: one code for one row and for many.

A roll-coupled unit's degrees of freedom are its sprung masses and its axles (:mod:`engine.models.combination`).
Only its elements join them: a suspension joins a unit's sprung mass to one of its own axles, a roll-stiff coupling
joins two neighbouring sprung masses, and the tyres and the P-Delta terms act on one DOF each. Its stiffness matrix
``J = K - P`` is therefore symmetric, with off-diagonal entries only on the edges of a tree (the axles are leaves,
the sprung masses a path). Eliminated leaves first, such a matrix makes no fill-in (Parter 1961; George and Liu 1981,
Ch. 6): its factor ``J = L D L^T`` costs one division and two products per edge, and a solve two more per edge,
against the O(n^3) of a dense LU with its call overhead per system.

Pivots are not exchanged. The matrix is symmetric, so the signs of the pivots ``D`` are those of its eigenvalues
(Sylvester's law of inertia): every pivot positive is exactly "J positive definite", the stability test of an
equilibrium, and for a positive definite matrix elimination without pivoting is backward stable (Higham, *Accuracy
and Stability of Numerical Algorithms*, 2nd ed., Thm 10.5 for LDL^T with D > 0). On the pieces of a path past its
peak J is indefinite; a zero pivot there is reported (:class:`Singular`), the caller's dense fallback takes it.

**One code, both modes.** Every function takes *columns*: a list with one entry per DOF, each entry a Python float
(the scalar solve of one road) or a numpy array of shape ``(m,)`` (the batch: m roads in lockstep). The operations
are the same IEEE-754 operations in the same order either way (a float64 product, quotient, sum or square root is
correctly rounded whether numpy or CPython forms it), so a row of the batch gives the scalar's bits by construction.
With arrays, a zero pivot gives inf or nan in its rows instead of raising: :func:`zero_pivot` marks those rows,
which the caller leaves out (the scalar raises there, before any value of the row is used).

References
----------
.. [1] Parter, S. (1961), The use of linear graphs in Gauss elimination, SIAM Review 3(2) 119-130.
.. [2] George, A. and Liu, J. W. H. (1981), *Computer Solution of Large Sparse Positive Definite Systems*,
   Prentice-Hall, Ch. 6 (tree partitioning; elimination without fill).
.. [3] Higham, N. J. (2002), *Accuracy and Stability of Numerical Algorithms*, 2nd ed., SIAM, Ch. 10.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


class Singular(np.linalg.LinAlgError):
    """A zero pivot: the piece's equations have no unique solution (what LAPACK's solve raises on an exact zero
    pivot, so the callers that caught that catch this)."""


@dataclass(frozen=True)
class Tree:
    """The elimination order of a tree of ``n`` DOFs: ``order[k]`` is eliminated ``k``-th into ``parent[k]``, leaves
    first; ``root`` is the one DOF left."""

    n: int
    order: tuple[int, ...]
    parent: tuple[int, ...]
    root: int


def tree_of(n: int, edges: list[tuple[int, int]]) -> Tree:
    """The elimination order of the graph of ``n`` DOFs joined by ``edges`` (pairs of DOFs), which must be a tree
    (connected, n - 1 distinct edges): repeatedly the lowest-numbered leaf goes into its one neighbour."""
    links: list[set[int]] = [set() for _ in range(n)]
    for i, j in edges:
        if i == j or j in links[i]:
            raise ValueError(f"the roll DOFs {i} and {j} are joined twice or to themselves: not a tree")
        links[i].add(j)
        links[j].add(i)
    if len(edges) != n - 1:
        raise ValueError(f"{n} roll DOFs joined by {len(edges)} elements: not a tree")
    order, parent = [], []
    left = set(range(n))
    while len(left) > 1:
        leaf = min((v for v in left if len(links[v]) == 1), default=None)
        if leaf is None:
            raise ValueError("the roll DOFs are not joined as a tree")
        (p,) = links[leaf]
        order.append(leaf)
        parent.append(p)
        links[p].discard(leaf)
        left.discard(leaf)
    return Tree(n, tuple(order), tuple(parent), left.pop())


def edge_values(t: Tree, K: np.ndarray) -> tuple[float, ...]:
    """The off-diagonal entries of ``K`` on the tree's edges, in elimination order, as floats (the entries of J = K -
    P there: P is diagonal)."""
    return tuple(float(K[v, p]) for v, p in zip(t.order, t.parent, strict=True))


@dataclass(frozen=True)
class Factor:
    """``J = L D L^T`` on a tree: the pivots ``d`` (columns, one per DOF) and the multipliers ``lower`` (one per edge in
    elimination order, L's entry below the pivot of the DOF eliminated there; None where the edge is absent)."""

    d: list
    lower: list


def factor(t: Tree, diag: list, edge: tuple[float, ...]) -> Factor:
    """``J = L D L^T``, J given by its diagonal (columns) and its edge values. Raises :class:`Singular` at a zero
    pivot when the columns are floats."""
    d = list(diag)
    ls = []
    scalar = isinstance(d[0], float)
    for v, p, e in zip(t.order, t.parent, edge, strict=True):
        if scalar and d[v] == 0.0:
            raise Singular
        if e:  # a suspension inside its lash passes nothing: the edge is absent in this piece
            lv = e / d[v]
            d[p] = d[p] - lv * e
            ls.append(lv)
        else:
            ls.append(None)
    if scalar and d[t.root] == 0.0:
        raise Singular
    return Factor(d, ls)


def zero_pivot(f: Factor) -> np.ndarray:
    """The rows with a zero pivot (for columns of arrays; their other values are meaningless)."""
    d = f.d
    out = d[0] == 0.0
    for x in d[1:]:
        out = out | (x == 0.0)
    return out


def positive(f: Factor):
    """Every pivot positive: J positive definite (a stable equilibrium). A bool for floats, a mask for arrays."""
    d = f.d
    if isinstance(d[0], float):
        return all(x > 0.0 for x in d)
    out = d[0] > 0.0
    for x in d[1:]:
        out = out & (x > 0.0)
    return out


def solve(t: Tree, f: Factor, b: list) -> list:
    """x with ``J x = b`` from the factor :func:`factor` gives (b and x as columns): L y = b, then L^T x = D^-1 y."""
    d, ls = f.d, f.lower
    y = list(b)
    for v, p, lv in zip(t.order, t.parent, ls, strict=True):
        if lv is not None:
            y[p] = y[p] - lv * y[v]
    x = list(y)
    x[t.root] = y[t.root] / d[t.root]
    for k in range(len(t.order) - 1, -1, -1):
        v, lv = t.order[k], ls[k]
        x[v] = y[v] / d[v] if lv is None else y[v] / d[v] - lv * x[t.parent[k]]
    return x


def squares(x: list):
    """The sum of the squares of the columns, added in the order of the DOFs (one order for both modes: numpy's
    pairwise sum over an axis of eight or more adds in another)."""
    s = x[0] * x[0]
    for v in x[1:]:
        s = s + v * v
    return s


def sqrt(x):
    return math.sqrt(x) if isinstance(x, float) else np.sqrt(x)


def direction(dq: list, out: np.ndarray | None = None) -> tuple[list, object]:
    """The unit vector along ``(dq, 1)``, the direction of a piece's solution line in (q, ay) when ``J dq = -jp``, and
    the squared length of dq (the caller's test that dq is finite and not huge). With ``out`` (columns of arrays: an
    (n + 1, m) array) the vector is written into its rows, and ``out`` is the first value returned."""
    sq = squares(dq)
    norm = sqrt(sq + 1.0)
    if out is None:
        return [x / norm for x in dq] + [1.0 / norm], sq
    for v, x in enumerate(dq):
        np.divide(x, norm, out=out[v])
    np.divide(1.0, norm, out=out[len(dq)])
    return out, sq

"""engine.models.roll_tree: the LDL^T of a matrix on a tree against dense LAPACK, and one row against many."""

from __future__ import annotations

import numpy as np
import pytest

from engine.models import roll_tree
from engine.models.combination import build_systems
from engine.vehicle.combination import UnitLoad
from engine.vehicle.combination_presets import COMBINATIONS


def random_tree(rng, n: int) -> list[tuple[int, int]]:
    """n DOFs joined as a random tree (each DOF after the first to one before it), in random labels."""
    perm = rng.permutation(n)
    return [(int(perm[v]), int(perm[rng.integers(0, v)])) for v in range(1, n)]


def dense(n: int, edges, diag, values) -> np.ndarray:
    J = np.diag(np.asarray(diag, dtype=float))
    for (i, j), x in zip(edges, values, strict=True):
        J[i, j] = J[j, i] = x
    return J


@pytest.mark.parametrize("seed", range(20))
def test_solve_is_the_dense_solve_on_random_trees(seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(2, 14))
    edges = random_tree(rng, n)
    t = roll_tree.tree_of(n, edges)
    values = rng.standard_normal(n - 1) * 100.0
    values[rng.random(n - 1) < 0.2] = 0.0  # absent edges (a suspension inside its lash)
    diag = np.abs(rng.standard_normal(n)) * 300.0 + 1.0 + rng.choice([0.0, -250.0], n)  # some indefinite
    J = dense(n, edges, diag, values)
    K = J.copy()
    edge = roll_tree.edge_values(t, K)
    b = rng.standard_normal(n)
    f = roll_tree.factor(t, diag.tolist(), edge)
    x = roll_tree.solve(t, f, b.tolist())
    np.testing.assert_allclose(J @ np.array(x), b, rtol=0, atol=1e-9 * np.abs(J).max() * max(1.0, np.abs(x).max()))
    # Sylvester: the pivots' signs are the eigenvalues' signs
    assert sum(p > 0 for p in f.d) == int(np.sum(np.linalg.eigvalsh(J) > 0))
    assert roll_tree.positive(f) == bool(np.linalg.eigvalsh(J)[0] > 0)


def test_rows_give_the_bits_of_one_row():
    rng = np.random.default_rng(7)
    n, m = 9, 50
    edges = random_tree(rng, n)
    t = roll_tree.tree_of(n, edges)
    edge = tuple((rng.standard_normal(n - 1) * 50.0).tolist())
    diag = rng.uniform(100.0, 400.0, (m, n))
    b = rng.standard_normal((m, n))
    d_many = roll_tree.factor(t, [diag[:, v] for v in range(n)], edge)
    x_many = roll_tree.solve(t, d_many, [b[:, v] for v in range(n)])
    dir_many, sq_many = roll_tree.direction(x_many)
    into, sq_into = roll_tree.direction(x_many, np.empty((n + 1, m)))
    for i in range(m):
        d_one = roll_tree.factor(t, diag[i].tolist(), edge)
        x_one = roll_tree.solve(t, d_one, b[i].tolist())
        dir_one, sq_one = roll_tree.direction(x_one)
        assert [x[i] for x in x_many] == x_one
        assert [x[i] for x in dir_many] == dir_one
        assert into[:, i].tolist() == dir_one
        assert sq_many[i] == sq_one == sq_into[i]
        assert [x[i] for x in d_many.d] == d_one.d
        assert [x if x is None else x[i] for x in d_many.lower] == d_one.lower


def test_a_zero_pivot_raises_for_one_row_and_is_marked_for_many():
    t = roll_tree.tree_of(3, [(0, 2), (1, 2)])
    edge = (1.0, 1.0)
    with pytest.raises(roll_tree.Singular):
        roll_tree.factor(t, [0.0, 1.0, 1.0], edge)
    with pytest.raises(roll_tree.Singular):  # the root's pivot: 1 - 1/1 - 1/1 + 1 = 0
        roll_tree.factor(t, [1.0, 1.0, 2.0], edge)
    with np.errstate(divide="ignore", invalid="ignore"):
        d = roll_tree.factor(t, [np.array([0.0, 1.0, 1.0]), np.array([1.0, 1.0, 1.0]), np.array([1.0, 2.0, 3.0])], edge)
    assert roll_tree.zero_pivot(d).tolist() == [True, True, False]


def test_not_a_tree_is_refused():
    with pytest.raises(ValueError, match="not a tree"):
        roll_tree.tree_of(3, [(0, 1), (1, 2), (2, 0)])
    with pytest.raises(ValueError, match="not a tree"):
        roll_tree.tree_of(4, [(0, 1), (2, 3)])  # two pieces: too few edges
    with pytest.raises(ValueError, match="not a tree"):
        roll_tree.tree_of(4, [(0, 1), (0, 1), (2, 3)])


@pytest.mark.parametrize("cid", list(COMBINATIONS))
def test_every_preset_unit_is_a_tree_eliminated_leaf_by_leaf(cid):
    for s in build_systems(COMBINATIONS[cid], 0.0, 0.0, UnitLoad()):
        edges = [(z.i, z.j) for z in s.zones]
        t = roll_tree.tree_of(s.n, edges)
        gone: set[int] = set()
        for v, p in zip(t.order, t.parent, strict=True):
            # each DOF is a leaf of what is left when it goes: its one neighbour left is its parent (no fill-in)
            neighbours = {j for i, j in edges if i == v} | {i for i, j in edges if j == v}
            assert neighbours - gone == {p}
            gone.add(v)
        assert set(t.order) | {t.root} == set(range(s.n))

"""Many cases of one combination at once: the stepped solution of :mod:`engine.models.combination` on stacked rows.

The alignments, sweeps, routes and jobs ask for the SRT of one vehicle over many bank/grade pairs (and a few load
cases). Solved one by one each case costs a whole path of small numpy calls (about a millisecond); here the paths of
all rows are followed in lockstep while their regimes agree (one vehicle's event sequences over different roads are
mostly the same), a group splitting where its rows meet different events. The arithmetic is the scalar solve's, row
by row (:func:`engine.models.combination._assemble`, :meth:`engine.models.combination._Elements.table`, the same
start, the same secant on the normal factor of a bank), so a row's answer is the scalar one bit for bit (what
``tests/engine/test_combination_batch.py`` asserts). A row whose path leaves what the lockstep handles (a start that
needs the scalar's further guesses or its minimisation, a singular piece, a path that does not turn, a fixed point
that does not settle) is solved alone by :func:`engine.models.combination.solve_combination`: nan if that fails.

The small linear systems of every step (a piece's direction, a state at rest, the stability of an equilibrium, the
Newton steps of a vertex on a bank) are solved on the roll equations' tree (:mod:`engine.models.roll_tree`): one
column operation per edge for all the rows at once, and the same code the scalar solve runs on floats, so the same
bits by construction. (Before, every row's dense system went to LAPACK, one call per row and solve: half a batch's
time, and the floor under the lockstep.)
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from engine.case import Case
from engine.errors import RolloverError
from engine.models import combination as whole
from engine.models import roll_tree
from engine.models.combination import (
    BAND,
    LIFTED,
    LIFTED_OUT,
    LINEAR,
    MINUS,
    PLUS,
    TOL,
    DeadZone,
    System,
)
from engine.vehicle.combination import Combination, UnitLoad, check_combination_load

#: rows solved together: the lockstep's arrays of 8,192 rows stay in the caches where 16,384 (a block of
#: :func:`engine.models.threshold.evaluate_arrays`) do not: a tenth less time per row, measured
BLOCK_ROWS = 8_192


class _Alone(Exception):
    """A row the lockstep leaves to the scalar solve."""


_ROAD = ("n0", "n1", "l0", "l1", "grade")


class _Rows:
    """The road factors of some rows (arrays), each of shape (k,), and with :meth:`of_system` what a system's steps
    take of them."""

    fields = _ROAD

    def __init__(self, bank_percent: np.ndarray, slope_percent: np.ndarray):
        # the scalar's RoadFactors.of row by row: numpy's vectorised sin/cos/atan may differ from libm's in the last
        # bit, and a route's curve must give the bits /v1/srt gives for its bank and grade
        # (its arithmetic inlined: building 100,000 records took a tenth of a batch; libm's once per distinct bank
        # and per distinct grade: many curves share them, 100,000 pairs on a 0.01 % grid hold some 1,200 banks)
        cb, sb = _cos_sin(bank_percent)
        cs, ss = _cos_sin(slope_percent)
        self.n0, self.n1, self.l0, self.l1, self.grade = cb * cs, sb, -sb * cs, cb, ss

    def take(self, idx: np.ndarray) -> _Rows:
        out = object.__new__(_Rows)
        out.fields = self.fields
        for k in self.fields:
            setattr(out, k, getattr(self, k)[idx])
        return out

    def of_system(self, s: System, e: whole._Elements) -> _Rows:
        """These rows with the road's products that the steps of ``s`` (and of its lashless copy: the same loads and
        tyres) take, formed once per block and gathered with the rows: they do not depend on the P-Delta terms the
        fixed point changes, and forming them at every step and start took a tenth of a batch (profiled). The same
        products as the scalar's :func:`~engine.models.combination._assemble` (jp = jp_free + S jp_cap, k = k_free +
        S k_cap + kz), ``_rows_of`` (a group's c2 = fac cap_ay, b = fac cap_0) and ``_consistent`` at rest (the
        groups' lift-off moments cap_rest at ay0), so the same bits."""
        out = self.take(slice(None))
        n0, n1, l0, l1, grade = (_row(getattr(self, k)) for k in _ROAD)
        out.jp_free = -(l1 * s.lat + n1 * s.off)
        out.jp_cap = n1 * e.capn_dof
        out.k_free = -(l0 * s.lat + n0 * s.off)
        out.k_cap = n0 * e.capn_dof + grade * e.capg_dof
        out.cap_ay = n1 * e.capn
        out.cap_0 = n0 * e.capn + grade * e.capg
        out.ay0 = -self.l0 / self.l1  # the scalar's neutral_ay
        out.cap_rest = _row(self.n0 + self.n1 * out.ay0) * e.capn + grade * e.capg
        out.fields = (*_ROAD, "jp_free", "jp_cap", "k_free", "k_cap", "cap_ay", "cap_0", "ay0", "cap_rest")
        return out


def _cos_sin(percent: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """cos and sin of atan(percent / 100) by libm, once per distinct value (distinct bits: -0.0 is not 0.0)."""
    percent = np.ascontiguousarray(percent, dtype=float)
    _bits, first, inverse = np.unique(percent.view(np.int64), return_index=True, return_inverse=True)
    angles = [math.atan(x / 100.0) for x in percent[first].tolist()]
    cos, sin = np.array([math.cos(x) for x in angles]), np.array([math.sin(x) for x in angles])
    return cos[inverse.reshape(-1)], sin[inverse.reshape(-1)]


def _row(x: np.ndarray) -> np.ndarray:
    return x[:, None]


def _loads(e: whole._Elements, r: _Rows, tyre: tuple, zone: tuple):
    """jp, k of a regime for every row (the scalar :func:`~engine.models.combination._assemble`, phase 2; ``r`` of
    the system, :meth:`_Rows.of_system`)."""
    _K, S, kz = e.piece(tyre, zone)
    return r.jp_free + S * r.jp_cap, r.k_free + S * r.k_cap + kz


def _every(mask: np.ndarray) -> np.ndarray:
    """The rows (axis 0) whose entries are all true: one global test first (the usual case: all of them), since a
    reduction along a short last axis takes several times as long (profiled)."""
    return np.ones(mask.shape[0], dtype=bool) if mask.all() else np.all(mask, axis=1)


def _pivots(e: whole._Elements, tyre: tuple, zone: tuple, pd: np.ndarray) -> roll_tree.Factor:
    """The factor of every row's J = K - P of a piece on its tree (``pd``: the rows' P-Delta diagonals, DOF
    by row, (n, k)): the scalar ``_pivots``' operations on columns of rows."""
    kd, ke = e.tree_piece(tyre, zone)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        return roll_tree.factor(e.tree, [kd[v] - pd[v] for v in range(e.n)], ke)


def _solve(e: whole._Elements, tyre: tuple, zone: tuple, pd: np.ndarray, b: np.ndarray) -> np.ndarray:
    """J x = b row by row (b and x: (k, n)) for a piece's J = K - P; raises :class:`_Alone` when a row's J has a zero
    pivot (the scalar raises there)."""
    f = _pivots(e, tyre, zone, pd)
    if roll_tree.zero_pivot(f).any():
        raise _Alone
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        return np.column_stack(roll_tree.solve(e.tree, f, [b[:, v] for v in range(e.n)]))


def _consistent(e: whole._Elements, r: _Rows, q: np.ndarray):
    """The tyre and zone states of each row's q at rest (the scalar ``_consistent`` at ay0), as (k, T) and (k, Z)
    arrays."""
    m = e.tk * q[:, e.tdof]
    cap = r.cap_rest
    tyre = np.where(m > cap, LIFTED, np.where(m < -cap, LIFTED_OUT, LINEAR))
    d = q[:, e.zi] - q[:, e.zj]
    zone = np.where((e.lash <= 0) | (np.abs(d) <= e.lash), BAND, np.where(d > 0, PLUS, MINUS))
    return tyre, zone


def _distinct(states: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The distinct rows of an array of element states (each -1, 0 or 1) and each row's index among them. A row is
    coded as one integer in base 3 (np.unique over rows sorts them as records: most of a start's time, profiled)."""
    if not states.shape[0]:
        return states[:0], np.zeros(0, dtype=int)
    if (states == states[0]).all():  # the usual case: every row in the same regime
        return states[:1], np.zeros(states.shape[0], dtype=int)
    # (an integer matmul: a sum over axis 1 of rows this short took a dozen times as long, measured)
    code = (states + 1).astype(np.int64) @ 3 ** np.arange(states.shape[1], dtype=np.int64)
    _values, first, inverse = np.unique(code, return_index=True, return_inverse=True)
    return states[first], inverse.reshape(-1)


def _stable(e: whole._Elements, tyre: tuple, zone: tuple, pd: np.ndarray) -> np.ndarray:
    """Each row's J = K - P positive definite: the scalar's test (every pivot positive), row by row."""
    f = _pivots(e, tyre, zone, pd)
    return roll_tree.positive(f) & ~roll_tree.zero_pivot(f)


def _state(e: whole._Elements, r: _Rows, pd: np.ndarray, key: np.ndarray, T: int):
    """The equilibrium of every row in one regime (tyre states then zone states in ``key``) at rest (the scalar
    ``_state_at`` at ay0), or None when a row's equations are singular."""
    tyre, zone = tuple(key[:T].tolist()), tuple(key[T:].tolist())
    jp, k = _loads(e, r, tyre, zone)
    try:
        return _solve(e, tyre, zone, pd, -(jp * _row(r.ay0) + k))
    except _Alone:
        return None


def _start(s: System, e: whole._Elements, lashless: System, r: _Rows, pd: np.ndarray):
    """The scalar ``_start`` for rows whose first guess settles: (z0 (k, n+1), the distinct starting regimes (tyre,
    zone tuples), each row's index among them, ok)."""
    n = s.n
    T, Z = len(s.tyres), len(s.zones)
    el = whole._elements(lashless)
    ay0 = r.ay0
    linear_t, band_z = (LINEAR,) * T, (BAND,) * Z
    jp0, k0 = _loads(el, r, linear_t, band_z)
    q0 = _solve(el, linear_t, band_z, pd, -(jp0 * _row(ay0) + k0))
    k_rows = q0.shape[0]
    ok = np.ones(k_rows, dtype=bool)
    if not np.any(e.lash > 0):
        tyre, zone = _consistent(e, r, q0)
        ok &= _every(tyre == LINEAR) & _every(zone == BAND)
        ok &= _stable(e, linear_t, band_z, pd)
        return np.column_stack([q0, ay0]), [(linear_t, band_z)], np.zeros(k_rows, dtype=int), ok
    d = q0[:, e.zi] - q0[:, e.zj]
    coupling = np.array([z.kind == "coupling" for z in s.zones])
    # how the first ay loads each element, for the rows with a suspension that nothing loads at rest (the scalar
    # solves it for those only; on a bank none is)
    dd = np.zeros_like(d)
    need = np.flatnonzero(np.any((e.lash > 0) & ~coupling & (np.abs(d) <= 1e-12), axis=1))
    if need.size:
        dq = _solve(el, linear_t, band_z, pd[:, need], -jp0[need])
        dd[need] = dq[:, e.zi] - dq[:, e.zj]
    guess = np.where(
        e.lash <= 0,
        BAND,
        np.where(
            np.abs(d) > 1e-12, np.where(d > 0, PLUS, MINUS), np.where(coupling, BAND, np.where(dd >= 0, PLUS, MINUS))
        ),
    )
    z0 = np.zeros((k_rows, n + 1))
    z0[:, n] = ay0
    # the scalar's guesses in turn: a row whose guess does not settle takes the regime its state lies in as the next
    state = np.full((k_rows, T + Z), LINEAR)
    state[:, T:] = guess
    final = np.zeros((k_rows, T + Z), dtype=int)
    pending = np.ones(k_rows, dtype=bool)
    for _ in range(Z + 2):
        if not pending.any():
            break
        keys, inv = _distinct(state[pending])
        rows_p = np.flatnonzero(pending)
        for g, key in enumerate(keys):
            idx = rows_p[inv == g]
            every = idx.size == k_rows  # every row, in order (the usual case): no copies of the rows' arrays
            ri, pi = (r, pd) if every else (r.take(idx), pd[:, idx])
            q = _state(e, ri, pi, key, T)
            if q is None:
                pending[idx], ok[idx] = False, False  # the scalar leaves the loop for its minimisation
                continue
            tyre, zone = _consistent(e, ri, q)
            rg = np.column_stack([tyre, zone])
            same = _every(rg == key)
            if same.all():  # every state in its guess's regime: already its exact equilibrium (the scalar's made_in)
                settled = _every(np.isfinite(q))
                exact = q
                if settled.all():  # the usual case: the rows settle in their one regime if they are stable in it
                    settled = _stable(e, tuple(key[:T].tolist()), tuple(key[T:].tolist()), pi)
                    if settled.all():
                        at = slice(None) if every else idx  # every row: plain stores, no scatter
                        z0[at, :n], final[at], pending[at] = q, key, False
                        continue
            else:
                exact = q.copy()
                for key2 in _distinct(rg[~same])[0]:
                    sub = np.flatnonzero(~same & np.all(rg == key2, axis=1))
                    q2 = _state(e, ri.take(sub), pi[:, sub], key2, T)
                    if q2 is None:
                        exact[sub] = np.nan  # the scalar's settle fails there: next guess
                    else:
                        exact[sub] = q2
                t2, z2 = _consistent(e, ri, exact)
                settled = np.all(np.isfinite(exact), axis=1) & np.all(np.column_stack([t2, z2]) == rg, axis=1)
            for key2 in _distinct(rg[settled])[0]:
                sub = np.flatnonzero(settled & np.all(rg == key2, axis=1))
                settled[sub] &= _stable(e, tuple(key2[:T].tolist()), tuple(key2[T:].tolist()), pi[:, sub])
            done = idx[settled]
            z0[done, :n] = exact[settled]
            final[done] = rg[settled]
            pending[done] = False
            state[idx[~settled]] = rg[~settled]
    ok &= ~pending  # no guess settled: the scalar minimises the potential
    ok &= _every(final[:, :T] == LINEAR)  # an offset that lifts a group at rest: the scalar refuses it
    keys, which = _distinct(final)
    regimes = [(tuple(k[:T].tolist()), tuple(k[T:].tolist())) for k in keys]
    return z0, regimes, which, ok


def _trace(s: System, e: whole._Elements, r: _Rows, pd: np.ndarray, limit: np.ndarray | None, z0, regimes, start_of, ok,
           peaks: bool = True):  # fmt: skip
    """The scalar ``_trace`` from each row's start, rows in lockstep while their regimes agree. Returns (the largest
    ay on each row's path, the state there (k, n+1), ok, and with ``peaks`` the piece and event of each row's peak:
    the fixed point's start, which the solves at the limit's normal factor need not keep).

    The constraint rows are held constraint by row, (c, m), and the states DOF by row, (n+1, m): the regime's
    coefficients then broadcast along the rows' long axis and the gathers take whole rows (on (m, c) arrays, c some
    ten, each broadcast or gathered operation took three to four times as long, measured). Every value is the same
    elementwise operation as before, so the same bits; the reductions over the constraints only compare."""
    n = s.n
    best_ay = z0[:, n].copy()
    best_zT = np.ascontiguousarray(z0.T)
    # the piece and event of each row's peak vertex (the scalar's Newton start on a bank): its regime's index in
    # ``pieces`` (-1: the peak is the start), and the event's constraint (c1, c2, b, i1, i2)
    pieces: list = []
    peak_piece = np.full(z0.shape[0], -1)
    peak_row = np.zeros((z0.shape[0], 5))
    ok = ok.copy()
    max_steps = 8 * (len(s.tyres) + len(s.zones)) + 40
    # a group: (rows, its states (n+1, m), its last direction (n+1, m), tyre, zone, last, steps)
    work = []
    for g, key in enumerate(regimes):
        rows = np.flatnonzero(ok & (start_of == g))
        if rows.size:
            work.append((rows, np.ascontiguousarray(z0[rows].T), None, key[0], key[1], None, 0))
    lim = limit is not None
    # the loads DOF by row, (n, k): a column of the tree's solve is then one contiguous row (r of the system: of_system)
    jp_free, jp_cap, cap_ayT, cap_0T = (np.ascontiguousarray(x.T) for x in (r.jp_free, r.jp_cap, r.cap_ay, r.cap_0))
    while work:
        rows, zT, prev_d, tyre, zone, last, steps = work.pop()
        if steps >= max_steps:
            ok[rows] = False
            continue
        whole_set = rows.size == pd.shape[1]  # every row, in order: no copies of the rows' arrays
        if whole_set:
            jf, jc, caT, c0T, pr = jp_free, jp_cap, cap_ayT, cap_0T, pd
        else:
            jf, jc, pr = (np.take(x, rows, axis=1) for x in (jp_free, jp_cap, pd))
            caT, c0T = np.take(cap_ayT, rows, axis=1), np.take(cap_0T, rows, axis=1)
        _K, S, _kz = e.piece(tyre, zone)
        f = _pivots(e, tyre, zone, pr)
        # -jp, jp = jp_free + S jp_cap (the scalar's loads): a column by DOF
        minus_jp = [-(jf[v] + S[v] * jc[v]) for v in range(n)]
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            # the direction, DOF by row (n + 1, m)
            dT, sq = roll_tree.direction(roll_tree.solve(e.tree, f, minus_jp), np.empty((n + 1, jf.shape[1])))
        # the scalar's test: finite and |dq| < 1e12; where it fails, or on a zero pivot, the scalar takes an SVD
        fine = (sq < 1e24) & ~roll_tree.zero_pivot(f)
        if not fine.all():  # left to the scalar
            ok[rows[~fine]] = False
            rows, zT, dT, caT, c0T = rows[fine], zT[:, fine], dT[:, fine], caT[:, fine], c0T[:, fine]
            prev_d = None if prev_d is None else prev_d[:, fine]
            if not rows.size:
                continue
        m = rows.size
        ti, sk, sf, zi, sg, sb, i1, i2, ends = e.table(tyre, zone, 2, lim)
        # the constraint rows c1 x[i1] + c2 x[i2] + b >= 0: c1 is the regime's (the same on every row), c2 and b
        # the row's on its tyre rows (filled in place: concatenating broadcast copies took a tenth of a step)
        nt = ti.size
        c1 = np.concatenate([sk * e.tk[ti], sg])
        c1c = c1[:, None]
        c2T, bT = np.empty((c1.size, m)), np.empty((c1.size, m))
        fac = np.where(sf[:, None] == 0.0, limit[rows][None, :] if lim else 0.0, sf[:, None])
        c2T[:nt] = fac * caT[ti]
        bT[:nt] = fac * c0T[ti]
        c2T[nt:], bT[nt:] = -sg[:, None], (sb * e.lash[zi])[:, None]
        if last is None:
            w = s.weights @ dT[:n]
            w = np.where(w == 0.0, dT[n], w)
            flip = w < 0
        else:
            kc, idx, previous = last
            back = np.flatnonzero((ends[:, 0] == kc) & (ends[:, 1] == idx) & (ends[:, 2] == previous))
            if back.size:  # the rate of the constraint just crossed (the scalar's rates[back]: the same operations)
                j = back[0]
                rate = c1[j] * dT[i1[j]] + c2T[j] * dT[i2[j]]
            else:
                rate = np.zeros(m)
            turned = np.einsum("ij,ij->j", prev_d, dT) < 0
            flip = np.where(np.abs(rate) > 1e-14, rate < 0, turned)
        dT *= np.where(flip, -1.0, 1.0)
        # the scalar's c1 x[i1] + c2 x[i2] (+ b), in place: the same operations in the same order, fewer temporaries
        # (on the oriented direction: -(c1 x + c2 y) is c1 (-x) + c2 (-y) bit for bit)
        rates = c1c * dT[i1]
        rates += c2T * dT[i2]
        falling = rates < -1e-15
        ended = ~falling.any(axis=0)
        if ended.any():  # the last piece: a path that still climbs never turns (the scalar's ConvergenceError)
            ok[rows[ended & (dT[n] > 1e-12)]] = False
        value = c1c * zT[i1]
        value += c2T * zT[i2]
        value += bT
        reached = np.abs(c2T)  # -TOL scale, scale = max(1, |c1| + |c2|), in place
        reached += np.abs(c1c)
        np.maximum(reached, 1.0, out=reached)
        reached *= -TOL
        # the scalar's where(value > -TOL scale, max(value, 0) / -rates, 0), then inf where not falling, in place
        # (x / -r is -(x / r) bit for bit: rounding is symmetric)
        tau = np.maximum(value, 0.0)
        with np.errstate(divide="ignore", invalid="ignore"):
            np.divide(tau, rates, out=tau)
        np.negative(tau, out=tau)
        np.copyto(tau, 0.0, where=~(value > reached))
        np.copyto(tau, np.inf, where=~falling)
        # the scalar's argmin: the first constraint at the least tau (tau holds no nan: a nan value gives 0 above)
        step = tau.min(axis=0)
        which = np.zeros(m, dtype=np.intp)
        for j in range(c1.size - 1, -1, -1):
            which[tau[j] == step] = j
        go = ~ended
        if go.all():
            zT = zT + step * dT
        else:
            zT = zT.copy()
            zT[:, go] = zT[:, go] + step[go] * dT[:, go]
        higher = go & (zT[n] > best_ay[rows])
        if higher.all() and whole_set:  # the usual case before the peak: every row climbs, no scatter
            best_ay[:], best_zT[:] = zT[n], zT
        elif higher.all():
            best_ay[rows], best_zT[:, rows] = zT[n], zT
        else:
            best_ay[rows[higher]] = zT[n, higher]
            best_zT[:, rows[higher]] = zT[:, higher]
        if peaks and higher.any():  # only the rest solve's peaks start the fixed point
            pieces.append((tyre, zone))
            h = np.flatnonzero(higher)
            w = which[h]
            at = slice(None) if whole_set and h.size == m else rows[h]  # every row: plain stores, no scatter
            peak_piece[at] = len(pieces) - 1
            peak_row[at, 0], peak_row[at, 1], peak_row[at, 2] = c1[w], c2T[w, h], bT[w, h]
            peak_row[at, 3], peak_row[at, 4] = i1[w], i2[w]
        events = np.flatnonzero(np.bincount(which[go], minlength=c1.size))
        for row in events:
            kc, idx, state = (int(x) for x in ends[row])
            if kc == 2:
                continue  # a group at the LLT limit: the path stops
            if kc == 0 and state == LIFTED and sum(x == LINEAR for x in tyre) == 1:
                continue  # the last group in contact on both sides lifts
            if kc == 0:
                previous = tyre[idx]
                new_t, new_z = (*tyre[:idx], state, *tyre[idx + 1 :]), zone
            else:
                previous = zone[idx]
                new_t, new_z = tyre, (*zone[:idx], state, *zone[idx + 1 :])
            if events.size == 1 and go.all():  # the usual case: every row meets the same event, no copies
                work.append((rows, zT, dT, new_t, new_z, (kc, idx, previous), steps + 1))
            else:
                sel = go & (which == row)
                work.append((rows[sel], zT[:, sel], dT[:, sel], new_t, new_z, (kc, idx, previous), steps + 1))
    return best_ay, np.ascontiguousarray(best_zT.T), ok, (pieces, peak_piece, peak_row)


def _solve_at(s, e, lashless, r, pd, limit, peaks=True):
    try:
        z0, regimes, which, ok = _start(s, e, lashless, r, pd)
    except _Alone:  # a singular start somewhere in the rows: all of them alone (never seen on a valid vehicle)
        k = pd.shape[1]
        return np.zeros(k), np.zeros((k, s.n + 1)), np.zeros(k, dtype=bool), ([], np.full(k, -1), np.zeros((k, 5)))
    return _trace(s, e, r, pd, limit, z0, regimes, which, ok, peaks)


def _solve_unit(s: System, r: _Rows, limit: np.ndarray | None):
    """The scalar :func:`~engine.models.combination.solve_unit` of every row: (srt, state at the limit, ok)."""
    e = whole._elements(s)
    lashless = replace(s, zones=[DeadZone(z.i, z.j, z.k, 0.0, z.kind, z.ref) for z in s.zones], cache={})
    r = r.of_system(s, e)
    # the P-Delta terms' diagonals (the P at rest of build_systems, on its diagonal: the same products)
    pn, pg = np.diagonal(s.P_normal), np.diagonal(s.P_grade)
    pd0 = r.n0 * pn[:, None] + r.grade * pg[:, None]  # DOF by row, (n, k)
    srt, zs, ok, peaks = _solve_at(s, e, lashless, r, pd0, limit, bool(np.any(r.n1 != 0.0)))
    active = np.flatnonzero(ok & (r.n1 != 0.0))
    a0, g0, a1 = np.zeros(active.size), srt[active].copy(), srt[active].copy()
    pieces, peak_piece, peak_row = peaks
    for g, (tyre, zone) in enumerate(pieces):  # the scalar's Newton start, row by row
        sel = np.flatnonzero(peak_piece[active] == g)
        if not sel.size:
            continue
        rows = active[sel]
        ri = r if rows.size == srt.size else r.take(rows)  # every row (the usual case): no copies
        jp, k = _loads(e, ri, tyre, zone)
        kd, ke = e.tree_piece(tyre, zone)
        pr = peak_row[rows]
        a1[sel] = whole._vertex_fixed_point(
            e.tree, kd, ke, [jp[:, v] for v in range(s.n)], [k[:, v] for v in range(s.n)], pr[:, 0], pr[:, 1],
            pr[:, 2], pr[:, 3].astype(int), pr[:, 4].astype(int), pn.tolist(), pg.tolist(), ri.n0, ri.n1, ri.grade,
            srt[rows],
        )  # fmt: skip
    if active.size and ok.all() and active.size < ok.size:
        # the rows on no bank join the fixed point's first solve, at their own SRT: there the normal factor is n0 +
        # 0 ay = n0, the rest solve's P, so that solve gives their bits back and they settle at once (g1 = 0, the
        # scalar's answer for them); it spares gathering every array of the block for the banked rows (profiled: a
        # few % of a batch). Not in the Newton start above: a singular vertex there stops the steps of its whole call
        every = srt.copy()
        every[active] = a1
        a0, g0, a1, active = np.zeros(ok.size), srt.copy(), every, np.arange(ok.size)
    for _ in range(30):
        if not active.size:
            break
        ra = r if active.size == ok.size else r.take(active)
        normal = ra.n0 + ra.n1 * a1
        pd = normal * pn[:, None] + ra.grade * pg[:, None]
        got, gz, gok, _peaks = _solve_at(s, e, lashless, ra, pd, None if limit is None else limit[active], False)
        ok[active[~gok]] = False
        g1 = got - a1
        done = gok & (np.abs(g1) <= 1e-13)
        srt[active[done]], zs[active[done]] = got[done], gz[done]
        with np.errstate(divide="ignore", invalid="ignore"):
            secant = a1 - g1 * (a1 - a0) / (g1 - g0)
        nxt = np.where(g1 == g0, got, secant)
        keep = gok & ~done
        a0, g0, a1, active = a1[keep], g1[keep], nxt[keep], active[keep]
    ok[active] = False  # the fixed point did not settle
    return srt, zs, ok


def _alone(c: Combination, bank: float, slope: float, load: UnitLoad, llt: float) -> tuple[float, float]:
    """One row by the scalar solve: (the governing SRT, its largest unit roll) or nan where it fails."""
    try:
        detail = whole.solve_combination(c, bank_percent=bank, slope_percent=slope, load=load, llt_limit=llt)
    except (RolloverError, np.linalg.LinAlgError):
        return math.nan, math.nan
    gov = detail.roll_coupled_units[detail.governing]
    return gov.srt, max(gov.roll_angle_deg.values())


def batch(case: Case, col: dict[str, np.ndarray], chassis_closure: str = "chassis-constant"):
    """(SRT [g], roll [deg]) arrays of many cases of one combination (the combination model's ``batch``, as
    :func:`engine.models.stepping.batch_3d`): each row's SRT is that of :func:`engine.models.rollover_threshold` of
    the row's case, its roll that result's ``roll_angle_deg`` (the largest roll of the governing roll-coupled unit's
    sprung masses); nan for a row the scalar solve refuses (``chassis_closure`` does not apply)."""
    c: Combination = case.vehicle  # type: ignore[assignment]
    rows = len(col["bank_percent"])
    srt, roll = np.full(rows, np.nan), np.full(rows, np.nan)
    loads = np.column_stack(
        [col[k] for k in ("lateral_offset_m", "longitudinal_offset_m", "vertical_offset_m", "overweight_percent")]
    )
    bank, slope, llt = (np.asarray(col[k], dtype=float) for k in ("bank_percent", "slope_percent", "rear_llt_limit"))
    alone = np.asarray(col["trailer_angle_deg"]) != 0  # an input the model does not take: the scalar path refuses it
    for i in np.flatnonzero(alone):
        srt[i], roll[i] = math.nan, math.nan
    usual = loads[:1].tolist() if loads.size and np.all(loads == loads[0]) else None  # one load case: no set
    for key in map(tuple, usual) if usual is not None else {tuple(x) for x in loads[~alone].tolist()}:
        load = UnitLoad(*key)
        for below in (False, True):
            idx = np.flatnonzero(~alone & np.all(loads == key, axis=1) & ((llt < 1.0) == below))
            if not idx.size:
                continue
            try:
                check_combination_load(c, load)
                systems = whole.build_systems(c, 0.0, 0.0, load)
            except RolloverError:
                continue
            for lo in range(0, idx.size, BLOCK_ROWS):
                part = idx[lo : lo + BLOCK_ROWS]
                r = _Rows(bank[part], slope[part])
                limit = llt[part] if below else None
                per_unit = [_solve_unit(s, r, limit) for s in systems]
                ays = np.column_stack([p[0] for p in per_unit])
                good = np.all(np.column_stack([p[2] for p in per_unit]), axis=1)
                gov = np.argmin(ays, axis=1)
                for u, (s, (_a, zs, _ok)) in enumerate(zip(systems, per_unit, strict=True)):
                    sel = good & (gov == u)
                    bodies = [s.body[k] for k in s.units]
                    srt[part[sel]] = ays[sel, u]
                    # the scalar's max(math.degrees(x)): x * (180 / pi) in both, and the largest angle has the largest
                    roll[part[sel]] = np.max(zs[sel][:, bodies], axis=1) * (180.0 / math.pi)
                for i in part[~good]:
                    srt[i], roll[i] = _alone(c, bank[i], slope[i], load, llt[i])
    return srt, roll

"""The linear yaw-roll model of a combination: a constrained multibody assembly, built once per vehicle.

Coordinates (small angles about straight travel at speed ``u``, in a ground frame moving with the vehicle; + left):

* every **yaw body** has a lateral position ``y`` of its reference point and a yaw angle ``psi``; a unit is one yaw
  body, a full trailer two (its drawbar with the turntable axle, and its body turning on the turntable over that
  axle): the turntable is a dolly's own yaw;
* every **coupling** (fifth wheel, B-coupling, pintle) and every turntable joins two yaw bodies at a point: a
  holonomic constraint ``y_A - x_a psi_A = y_B - x_b psi_B`` that removes ``y_B`` (:func:`build`: the null-space
  map ``T`` from independent to all coordinates);
* every **sprung mass** rolls by ``phi_u``, every **axle group** by ``phi_g`` (the tyres' deflection), with the
  static combination model's stiffnesses (:mod:`engine.models.combination`), lash left out: tyres
  ``k_side T^2/2`` on ``phi_g``, suspensions ``K_s`` on ``phi_u - phi_g``, fifth wheels ``K_c`` on the relative
  roll of the units they join; gravity's destabilising (P-Delta) terms with the static loads.

Roll kinematics. A point of a sprung mass at height ``z`` moves sideways by ``R_u(z) = sum_s w_s R_s(h_s) +
(z - h_bar) phi_u``: the unit rests on its supports ``s`` (its axle groups at their roll centres, where
``R_g(h) = h phi_g``, and the coupling it rests on at its height, on the towing unit) with the shares ``w_s`` of
their static loads, ``h_bar = sum w_s h_s``; an axle's unsprung mass at ``h_a`` moves ``h_a phi_g``. By virtual
work a lateral force at a sprung CG then loads the roll coordinates exactly as the static model's lateral-load
pattern does, so in a steady turn (every point at the same lateral acceleration ``u r``) the roll angles are the
static model's at that lateral acceleration (tested). In a transient the roll moment is passed to the supports by
their static shares, a simplification of the same kind as the static model's.

Tyres: linear, ``F = C (psi + delta - Ydot / u)`` at every axle's contact (``C = Cc N``, multi-axle groups as
their axles, :mod:`engine.dynamics.parameters`); the steer group's axles take the road-wheel angle ``delta``.

Equations ``M q'' + (C_t / u + C_r) q' + (K_t + K_r) q = B delta`` (``M`` from the kinetic energy of every mass,
``K_r`` symmetric, ``K_t`` and ``C_t`` from the tyres). The groups' roll coordinates carry no inertia of their
own worth keeping (an axle's roll mode lies near 10-30 Hz): they are condensed statically (Guyan), which leaves
every steady state exact.

References
----------
.. [1] Ervin, R. D. and Guy, Y. (1986), *The influence of weights and dimensions on the stability and control of
   heavy-duty trucks in Canada*, UMTRI-86-35 (the UMTRI Yaw/Roll model); Fancher, P. S. and Winkler, C. B.,
   linear multi-unit yaw-roll models; Sampson, D. J. M. and Cebon, D. (2003), Vehicle System Dynamics 40.
.. [2] Guyan, R. J. (1965), Reduction of stiffness and mass matrices, AIAA Journal 3(2): static condensation.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from engine.dynamics.parameters import DynamicsData, ResolvedParameters, resolve
from engine.errors import InvalidRoad
from engine.vehicle.combination import Combination, roll_coupled_units, static_loads


@dataclass(frozen=True)
class Body:
    """A yaw body: ``unit`` index, ``part`` (``"unit"`` or ``"drawbar"`` of a full trailer)."""

    unit: int
    part: str


@dataclass
class YawRollModel:
    """The assembled, condensed equations (SI: kg, N, m, rad) and the maps to every output.

    ``M q'' + (Ct1 / u + Cr) q' + (Kt + Kr) q = B delta``; ``q`` = (y and yaw of the first body, every other body's
    yaw relative to the first, every sprung mass's roll) (``roll=False``: no roll coordinates).
    """

    combination: Combination
    parameters: ResolvedParameters
    bodies: list[Body]
    M: np.ndarray
    Ct1: np.ndarray
    Cr: np.ndarray
    Kt: np.ndarray
    Kr: np.ndarray
    B: np.ndarray
    #: per yaw body, rows mapping q to y and to psi
    y_rows: np.ndarray
    psi_rows: np.ndarray
    #: per unit, the row mapping q to the sprung roll; per group (unit, group), its roll as rows on (q, q', q'')
    phi_unit_rows: np.ndarray
    phi_group_rows: dict[tuple[int, int], tuple[np.ndarray, np.ndarray, np.ndarray]]
    #: per unit the main yaw body's index; per group its yaw body
    main_body: list[int]
    group_body: dict[tuple[int, int], int]
    #: per group: tyre roll stiffness [N m/rad], static load [N], track [m]
    tyre_roll: dict[tuple[int, int], tuple[float, float, float]]
    roll: bool

    @property
    def n(self) -> int:
        return self.M.shape[0]

    def point_row(self, body: int, x: float) -> np.ndarray:
        """The row mapping q to the lateral position of the point ``x`` behind the body's reference [m]."""
        return self.y_rows[body] - x * self.psi_rows[body]

    def state_space(self, speed_mps: float) -> StateSpace:
        """``x' = A x + B delta`` with ``x = (q, q')`` at the forward speed ``speed_mps`` [m/s]."""
        if not speed_mps > 0:
            raise InvalidRoad("the speed must be positive", field="speed_kmh", value=speed_mps * 3.6)
        n = self.n
        Minv = np.linalg.inv(self.M)
        K = self.Kt + self.Kr
        C = self.Ct1 / speed_mps + self.Cr
        A = np.zeros((2 * n, 2 * n))
        A[:n, n:] = np.eye(n)
        A[n:, :n] = -Minv @ K
        A[n:, n:] = -Minv @ C
        Bs = np.zeros(2 * n)
        Bs[n:] = Minv @ self.B
        return StateSpace(self, speed_mps, A, Bs)


@dataclass
class StateSpace:
    """The first-order form at one speed; output rows act on ``(x, delta)``."""

    model: YawRollModel
    speed_mps: float
    A: np.ndarray
    B: np.ndarray

    def position(self, row: np.ndarray) -> tuple[np.ndarray, float]:
        """Output (C, D) of a position-like quantity ``row @ q``."""
        n = self.model.n
        c = np.zeros(2 * n)
        c[:n] = row
        return c, 0.0

    def acceleration(self, row: np.ndarray) -> tuple[np.ndarray, float]:
        """Output (C, D) of ``row @ q''`` (the second half of ``A``'s rows)."""
        n = self.model.n
        return row @ self.A[n:, :], float(row @ self.B[n:])

    def velocity(self, row: np.ndarray) -> tuple[np.ndarray, float]:
        n = self.model.n
        c = np.zeros(2 * n)
        c[n:] = row
        return c, 0.0

    def combined(self, pos: np.ndarray, vel: np.ndarray, acc: np.ndarray) -> tuple[np.ndarray, float]:
        """Output (C, D) of ``pos @ q + vel @ q' + acc @ q''``."""
        c_acc, d = self.acceleration(acc)
        n = self.model.n
        c = c_acc.copy()
        c[:n] += pos
        c[n:] += vel
        return c, d

    def group_roll(self, key: tuple[int, int]) -> tuple[np.ndarray, float]:
        """Output (C, D) of a group's roll [rad]."""
        return self.combined(*self.model.phi_group_rows[key])

    def unit_ltr(self, units: tuple[int, ...]) -> tuple[np.ndarray, float]:
        """Output (C, D) of a roll-coupled unit's load transfer ratio: the sum of its groups' load transfers over
        the sum of their loads, ``sum(2 M_t,g / T_g) / sum(N_g)`` with ``M_t,g = k_t phi_g`` [-]."""
        n = self.model.n
        c, d, den = np.zeros(2 * n), 0.0, 0.0
        for key, (kt, n0, track) in self.model.tyre_roll.items():
            if key[0] in units:
                ck, dk = self.group_roll(key)
                c += kt * ck / (track / 2.0)
                d += kt * dk / (track / 2.0)
                den += n0
        return c / den, d / den


def build(c: Combination, data: DynamicsData | None = None, *, roll: bool = True,
          parameters: ResolvedParameters | None = None) -> YawRollModel:  # fmt: skip
    """Assemble the equations of ``c`` (validated) with its given or estimated dynamic data (see the module)."""
    p = parameters or resolve(c, data)
    st = static_loads(c)
    bodies: list[Body] = []
    main_body, front_body = [], []
    group_body: dict[tuple[int, int], int] = {}
    for i, u in enumerate(c.units):
        if u.kind == "full-trailer":
            bodies.append(Body(i, "drawbar"))
            front_body.append(len(bodies) - 1)
            group_body[(i, 0)] = len(bodies) - 1
        bodies.append(Body(i, "unit"))
        main_body.append(len(bodies) - 1)
        if u.kind != "full-trailer":
            front_body.append(len(bodies) - 1)
        for j in range(len(u.groups)):
            group_body.setdefault((i, j), main_body[i])
    nb, nu = len(bodies), len(c.units)
    gkeys = [(i, j) for i, u in enumerate(c.units) for j in range(len(u.groups))]
    ng = len(gkeys)
    nfull = 2 * nb + nu + ng
    iy = [2 * b for b in range(nb)]
    ipsi = [2 * b + 1 for b in range(nb)]
    iphu = [2 * nb + i for i in range(nu)]
    iphg = {k: 2 * nb + nu + m for m, k in enumerate(gkeys)}

    # the independent coordinates: y of body 0, every psi, every phi; T maps them to all (constraints eliminate y)
    free = [iy[0], *ipsi, *iphu, *iphg.values()] if roll else [iy[0], *ipsi]
    T = np.zeros((nfull, len(free)))
    for k, f in enumerate(free):
        T[f, k] = 1.0
    joints = []  # (body A, x on A, body B, x on B): y_B = y_A - x_a psi_A + x_b psi_B
    for i, u in enumerate(c.units):
        if u.kind == "full-trailer":
            xt = u.groups[0].position_m
            if i > 0:
                joints.append((main_body[i - 1], c.couplings[i - 1].position_m, front_body[i], 0.0))
            joints.append((front_body[i], xt, main_body[i], xt))
        elif i > 0:
            joints.append((main_body[i - 1], c.couplings[i - 1].position_m, main_body[i], 0.0))
    for a, xa, b, xb in joints:
        T[iy[b]] = T[iy[a]] - xa * T[ipsi[a]] + xb * T[ipsi[b]]
    # yaw of every body but the first as the first's plus its own angle relative to it (psi_b = psi_0 + gamma_b):
    # the forces then depend on psi_0 only through psi_0 - y_0'/u (:func:`engine.dynamics.response.reduced`)
    S = np.eye(len(free))
    S[2 : 1 + nb, 1] = 1.0
    T = T @ S

    def e(index: int) -> np.ndarray:
        v = np.zeros(nfull)
        v[index] = 1.0
        return v

    # roll kinematics R_u(z) (rows over all coordinates)
    base, hbar = [], []
    for i, u in enumerate(c.units):
        shares = []  # (load [kN], height [m], row of the support point's roll displacement)
        for j, grp in enumerate(u.groups):
            s0 = st.normal_kn[(i, j)] - grp.unsprung_weight_kn
            shares.append((s0, grp.roll_centre_height_m, grp.roll_centre_height_m * e(iphg[(i, j)])))
        if i > 0 and st.coupling_kn.get(i - 1, 0.0) > 0 and c.units[i].kind != "full-trailer":
            cp = c.couplings[i - 1]
            towing = base[i - 1] + (cp.height_m - hbar[i - 1]) * e(iphu[i - 1])
            shares.append((st.coupling_kn[i - 1], cp.height_m, towing))
        total = sum(s for s, _, _ in shares)
        base.append(sum(s / total * row for s, _, row in shares))
        hbar.append(sum(s / total * h for s, h, _ in shares))

    def sprung_row(i: int, z: float) -> np.ndarray:
        return base[i] + (z - hbar[i]) * e(iphu[i])

    M = np.zeros((nfull, nfull))

    def add_mass(m: float, row: np.ndarray) -> None:
        M[:] += m * np.outer(row, row)

    for i, u in enumerate(c.units):
        b = main_body[i]
        up = p.units[i]
        add_mass(u.sprung_mass_kg, e(iy[b]) - u.cg_position_m * e(ipsi[b]) + sprung_row(i, u.cg_height_m))
        M[ipsi[b], ipsi[b]] += up.yaw_inertia_kgm2.value
        M[iphu[i], iphu[i]] += up.roll_inertia_kgm2.value
        for j, grp in enumerate(u.groups):
            gb = group_body[(i, j)]
            for x in p.groups[(i, j)].axle_positions_m:
                add_mass(grp.unsprung_mass_kg, e(iy[gb]) - x * e(ipsi[gb]) + grp.unsprung_cg_height_m * e(iphg[(i, j)]))
            if gb != b:  # a full trailer's drawbar: its axle's yaw inertia as a bar across the track
                M[ipsi[gb], ipsi[gb]] += grp.axles * grp.unsprung_mass_kg * grp.track_m**2 / 12.0

    # tyres
    Ct1 = np.zeros((nfull, nfull))
    Kt = np.zeros((nfull, nfull))
    Bf = np.zeros(nfull)
    for (i, j), gp in p.groups.items():
        gb = group_body[(i, j)]
        steer = c.units[i].groups[j].steer
        for x, ck in zip(gp.axle_positions_m, gp.cornering_stiffness_kn_per_rad, strict=True):
            cn = ck * 1000.0
            J = e(iy[gb]) - x * e(ipsi[gb])
            Ct1 += cn * np.outer(J, J)
            Kt -= cn * np.outer(J, e(ipsi[gb]))
            if steer:
                Bf += cn * J

    # roll: springs, gravity, damping (kN -> N)
    Kr = np.zeros((nfull, nfull))
    Cr = np.zeros((nfull, nfull))
    tyre_roll = {}

    def spring(k: float, a: int, b_: int | None) -> np.ndarray:
        r = e(a) - (e(b_) if b_ is not None else 0.0)
        return k * np.outer(r, r)

    tau = p.roll_damping_tau_s.value
    for i, u in enumerate(c.units):
        Kr[iphu[i], iphu[i]] -= 1000.0 * u.sprung_weight_kn * u.cg_height_m
        for j, grp in enumerate(u.groups):
            a = iphg[(i, j)]
            n0 = st.normal_kn[(i, j)]
            s0 = n0 - grp.unsprung_weight_kn
            kt = grp.tyre_roll_stiffness_knm_per_rad * 1000.0
            ks = grp.suspension_roll_stiffness_knm_per_rad * 1000.0
            Kr += spring(kt, a, None) + spring(ks, iphu[i], a)
            Cr += spring(tau * ks, iphu[i], a)
            Kr[iphu[i], iphu[i]] += 1000.0 * s0 * grp.roll_centre_height_m
            Kr[a, a] -= 1000.0 * (s0 * grp.roll_centre_height_m + grp.unsprung_weight_kn * grp.unsprung_cg_height_m)
            tyre_roll[(i, j)] = (kt, n0 * 1000.0, grp.track_m)
    for k, cp in enumerate(c.couplings):
        v0 = st.coupling_kn.get(k, 0.0) * 1000.0
        Kr[iphu[k], iphu[k]] -= v0 * cp.height_m
        Kr[iphu[k + 1], iphu[k + 1]] += v0 * cp.height_m
        if cp.transmits_roll:
            kc = cp.roll_stiffness_knm_per_rad * 1000.0
            Kr += spring(kc, iphu[k + 1], iphu[k])
            Cr += spring(tau * kc, iphu[k + 1], iphu[k])

    # reduce to the independent coordinates, then condense the groups' rolls (Guyan)
    def red(X: np.ndarray) -> np.ndarray:
        return T.T @ X @ T

    Mi, Cti, Cri, Kti, Kri, Bi = red(M), red(Ct1), red(Cr), red(Kt), red(Kr), T.T @ Bf
    nind = len(free)
    group_rows = {}
    if roll:
        s_idx = np.arange(nind - ng, nind)
        m_idx = np.arange(0, nind - ng)
        kss = Kri[np.ix_(s_idx, s_idx)]
        X = -np.linalg.solve(kss, Kri[np.ix_(s_idx, m_idx)])
        Gm = np.zeros((nind, len(m_idx)))
        Gm[m_idx, np.arange(len(m_idx))] = 1.0
        Gm[s_idx] = X
        # the groups' rolls recovered with the inertial and damping loads that act on them directly (Guyan's
        # reduction alone is exact for loads on the kept coordinates only): phi_g = X q - K_ss^-1 (M_s q'' + C_s q')
        acc = -np.linalg.solve(kss, Mi[s_idx] @ Gm)
        vel = -np.linalg.solve(kss, Cri[s_idx] @ Gm)
        for m_, k in enumerate(gkeys):
            group_rows[k] = (X[m_], vel[m_], acc[m_])
    else:
        Gm = np.eye(nind)
    TG = T @ Gm

    def cond(X: np.ndarray) -> np.ndarray:
        return Gm.T @ X @ Gm

    return YawRollModel(
        combination=c,
        parameters=p,
        bodies=bodies,
        M=cond(Mi),
        Ct1=cond(Cti),
        Cr=cond(Cri),
        Kt=cond(Kti),
        Kr=cond(Kri),
        B=Gm.T @ Bi,
        y_rows=np.array([TG[iy[b]] for b in range(nb)]),
        psi_rows=np.array([TG[ipsi[b]] for b in range(nb)]),
        phi_unit_rows=np.array([TG[iphu[i]] for i in range(nu)]),
        phi_group_rows=group_rows,
        main_body=main_body,
        group_body=group_body,
        tyre_roll=tyre_roll,
        roll=roll,
    )


def roll_units(model: YawRollModel) -> list[tuple[int, ...]]:
    return roll_coupled_units(model.combination)


def articulation_rows(model: YawRollModel) -> list[tuple[str, np.ndarray]]:
    """Every yawing joint, front to rear: (name, row mapping q to the towing body's yaw less the towed one's)."""
    out = []
    c = model.combination
    for b in range(1, len(model.bodies)):
        body = model.bodies[b]
        u = c.units[body.unit]
        if body.part == "drawbar":
            name = f"{c.units[body.unit - 1].id}/{u.id} drawbar"
            prev = model.main_body[body.unit - 1]
        elif u.kind == "full-trailer":
            name = f"{u.id} turntable"
            prev = b - 1
        else:
            name = f"{c.units[body.unit - 1].id}/{u.id}"
            prev = model.main_body[body.unit - 1]
        out.append((name, model.psi_rows[prev] - model.psi_rows[b]))
    return out

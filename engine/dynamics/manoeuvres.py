"""Manoeuvres and measures: lane change, frequency response, pulse steer, stability against speed, steady turn.

Definitions (PBS texts: the NTC rules could not be read here, so every PBS manoeuvre value is "unverified"):

* **single lane change**: the steer axle's lateral acceleration is one period of a sine, ``A sin(2 pi f t)`` for
  ``0 <= t <= 1/f`` (0.4 Hz by default: confirmed only second-hand, an open PBS implementation citing NTC 2008;
  speed and amplitude are options, their PBS values unverified). The steer follows from the inverse system
  (:func:`engine.dynamics.response.follow`), so the steer axle moves sideways by exactly ``A / (2 pi f^2)``.
  **Rearward amplification** (RA): the peak lateral acceleration of the rearmost unit's CG (``ra_definition``
  ``"cg"``) or of the rearmost axle (``"axle"``) over the steer axle's. **High-speed transient offtracking**
  (HSTO): the rearmost axle's lateral overshoot beyond the steer axle's final path (its largest lateral position
  less ``A / (2 pi f^2)``, as an open PBS implementation measures it: unverified against the rules); beside it the
  largest lateral distance between the rearmost axle's path and the steer axle's at the same station (the steer
  axle's position ``d / u`` earlier, ``d`` the distance between them along the vehicle).
  Per roll-coupled unit the peak **load transfer ratio** (a measure, not a PBS standard); per unit the peak lateral
  acceleration (at the sprung CG, in the yaw plane) and roll; a unit whose peak exceeds its roll-coupled unit's
  static SRT flags lift-off, where the linear model's validity ends.
* **frequency response**: RA(f) = |a_rear(j w)| / |a_steer(j w)| (Fancher and Winkler 1992; ISO 14791's
  frequency-domain approach), its worst frequency refined by a bounded scalar search.
* **pulse steer**: yaw damping of the rearmost articulation from successive same-sign peaks ``A_i, A_i+1``,
  ``delta = ln(A_i / A_i+1)``, ``zeta = delta / sqrt(4 pi^2 + delta^2)`` (the full-cycle logarithmic decrement);
  beside it the least-damped eigenvalue's damping ratio and mode shape.
* **stability**: the lowest speed at which an oscillatory mode (trailer sway) reaches zero damping, and the lowest
  at which a real eigenvalue becomes positive (divergence), by a scan of 2 km/h refined by bisection to
  0.05 km/h, up to :data:`MAX_SPEED_KMH`.
* **steady turn**: the equilibrium of the reduced state at the yaw rate that puts the steer axle on the radius;
  the path radius of every axle group's centre from the rigid motion of each unit about the turn centre.

References
----------
.. [1] Fancher, P. S. and Winkler, C. B. (1992), A methodology for measuring rearward amplification, 3rd Int.
   Symp. on Heavy Vehicle Weights and Dimensions.
.. [2] NHVR, Performance Based Standards, vehicle standards page (definitions of HSTO and yaw damping);
   NTC (2008), Performance Based Standards Scheme - The Standards and Vehicle Assessment Rules (not read).
.. [3] Gillespie, T. D. (1992), *Fundamentals of Vehicle Dynamics*, SAE, ch. 6 (logarithmic decrement).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import scipy.optimize

from engine.dynamics.model import StateSpace, YawRollModel, articulation_rows, roll_units
from engine.dynamics.response import (
    damping_ratio,
    eigen,
    follow,
    frequency_response,
    least_damped_oscillatory,
    reduced,
    simulate,
    steady_state,
)
from engine.errors import ConvergenceError, InvalidRoad, RolloverError
from engine.vehicle.combination import G_M_PER_S2

MAX_SPEED_KMH = 200.0
DT_S = 0.02


class Unstable(RolloverError, ArithmeticError):
    """The vehicle is unstable at this speed: ``limit_kmh`` is the stability limit and ``kind`` its mode."""

    def __init__(self, speed_kmh: float, limit_kmh: float | None, kind: str) -> None:
        super().__init__(f"unstable at {speed_kmh:g} km/h ({kind} from {limit_kmh} km/h)")
        self.speed_kmh = speed_kmh
        self.limit_kmh = limit_kmh
        self.kind = kind


def _speed(speed_kmh: float, low: float = 5.0) -> float:
    if not isinstance(speed_kmh, int | float) or not low <= speed_kmh <= MAX_SPEED_KMH:
        raise InvalidRoad(f"speed_kmh must be from {low:g} to {MAX_SPEED_KMH:g} km/h, got {speed_kmh!r}",
                          field="speed_kmh", value=speed_kmh)  # fmt: skip
    return speed_kmh / 3.6


def body_offsets(model: YawRollModel) -> list[float]:
    """Distance along the straight vehicle from the steer axle to each yaw body's reference point [m]."""
    c = model.combination
    off = [0.0] * len(model.bodies)
    for b in range(1, len(model.bodies)):
        body = model.bodies[b]
        u = c.units[body.unit]
        if body.part == "unit" and u.kind == "full-trailer":
            off[b] = off[b - 1]  # the body shares the drawbar's reference (the eye); the turntable is at x_t on both
        else:
            off[b] = off[model.main_body[body.unit - 1]] + c.couplings[body.unit - 1].position_m
    return off


def rear_points(model: YawRollModel, ra_definition: str) -> tuple[int, float, int, float]:
    """(body, x) of the rearmost unit's CG or rearmost axle for RA, and (body, x) of the rearmost axle."""
    c = model.combination
    last = len(c.units) - 1
    j = len(c.units[last].groups) - 1
    axle = (model.group_body[(last, j)], model.parameters.groups[(last, j)].axle_positions_m[-1])
    if ra_definition == "cg":
        return model.main_body[last], c.units[last].cg_position_m, *axle
    if ra_definition == "axle":
        return (*axle, *axle)
    raise InvalidRoad("ra_definition must be 'cg' (the rearmost unit's CG) or 'axle' (the rearmost axle)",
                      field="ra_definition", value=ra_definition)  # fmt: skip


def check_stable(model: YawRollModel, speed_kmh: float) -> None:
    """Raise :class:`Unstable` when a mode grows at this speed (no number from a diverging simulation)."""
    w, _, _ = eigen(model.state_space(speed_kmh / 3.6))
    if np.max(w.real) > 1e-9:
        st = stability(model)
        if st.sway_critical_speed_kmh is not None and (
            st.divergence_speed_kmh is None or st.sway_critical_speed_kmh <= st.divergence_speed_kmh
        ):
            raise Unstable(speed_kmh, st.sway_critical_speed_kmh, "trailer sway (an oscillatory mode)")
        raise Unstable(speed_kmh, st.divergence_speed_kmh, "divergence (a real mode)")


@dataclass
class LaneChange:
    speed_kmh: float
    frequency_hz: float
    amplitude_g: float
    ra_definition: str
    rearward_amplification: float
    high_speed_transient_offtracking_m: float
    steer_axle_lateral_offset_m: float
    roll_coupled_units: list[dict]
    units: list[dict]
    validity: list[str]
    time_step_s: float
    history: dict = field(default_factory=dict)
    max_path_deviation_m: float = 0.0


def unit_cg_outputs(ss: StateSpace) -> list[tuple[np.ndarray, float]]:
    m = ss.model
    return [ss.acceleration(m.point_row(m.main_body[i], u.cg_position_m)) for i, u in enumerate(m.combination.units)]


def lane_change(model: YawRollModel, speed_kmh: float, *, frequency_hz: float = 0.4, amplitude_g: float = 0.15,
                ra_definition: str = "cg", srt_g: list[float] | None = None, dt: float = DT_S,
                settle_s: float = 6.0, history: bool = False) -> LaneChange:  # fmt: skip
    """The single lane change (module docstring); ``srt_g`` the static SRT of each roll-coupled unit [g]."""
    u = _speed(speed_kmh)
    if not 0.05 <= frequency_hz <= 3.0:
        raise InvalidRoad("frequency_hz must be from 0.05 to 3 Hz", field="frequency_hz", value=frequency_hz)
    if not 0.01 <= amplitude_g <= 0.6:
        raise InvalidRoad("amplitude_g must be from 0.01 to 0.6 g", field="amplitude_g", value=amplitude_g)
    rb, rx, ab, ax = rear_points(model, ra_definition)
    check_stable(model, speed_kmh)
    ss = model.state_space(u)
    c = model.combination
    period = 1.0 / frequency_hz
    t = np.arange(0.0, period + settle_s + dt / 2, dt)
    amp = amplitude_g * G_M_PER_S2
    target = np.where(t <= period, amp * np.sin(2 * np.pi * frequency_hz * t), 0.0)
    steer_acc = ss.acceleration(model.point_row(0, 0.0))
    x, delta, poles = follow(ss, steer_acc, target, dt)
    if np.max(poles.real) > 1e-6:  # the steer needed to hold the steer axle on the path would grow without bound
        raise ConvergenceError(
            f"at {speed_kmh:g} km/h the steer axle cannot follow the prescribed lateral acceleration: the inverse "
            "system is unstable (a non-minimum-phase vehicle)"
        )
    n = model.n
    q = x[:, :n]
    a_units = np.array([x @ cc + dd * delta for cc, dd in unit_cg_outputs(ss)])
    a_rear_c, a_rear_d = ss.acceleration(model.point_row(rb, rx))
    a_rear = x @ a_rear_c + a_rear_d * delta
    ra = float(np.max(np.abs(a_rear)) / amp)
    y_steer = q @ model.point_row(0, 0.0)
    y_rear = q @ model.point_row(ab, ax)
    d = body_offsets(model)[ab] + ax
    y_steer_at = np.interp(t - d / u, t, y_steer, left=0.0)
    offtrack = y_rear - y_steer_at
    final = float(y_steer[-1])
    # HSTO: the rearmost axle's overshoot beyond the steer axle's final path (as the open PBS implementation
    # measures it: the largest lateral position less the lane change's width); the path deviation at equal stations
    # is reported beside it
    hsto = max(0.0, float(np.max(y_rear * math.copysign(1.0, final))) - abs(final))
    deviation = float(np.max(np.abs(offtrack)))
    rolls = np.array([q @ r for r in model.phi_unit_rows]) if model.roll else np.zeros((len(c.units), len(t)))
    rcu = []
    validity = []
    for k, members in enumerate(roll_units(model)):
        entry = {"units": [c.units[i].id for i in members]}
        if model.roll:
            cc, dd = ss.unit_ltr(members)
            entry["peak_load_transfer_ratio"] = float(np.max(np.abs(x @ cc + dd * delta)))
            if entry["peak_load_transfer_ratio"] >= 1.0:
                validity.append(f"roll-coupled unit {entry['units']}: load transfer ratio reaches 1 (a wheel lifts "
                                "off): past the linear model's validity")  # fmt: skip
        if srt_g is not None:
            entry["srt_g"] = srt_g[k]
        rcu.append(entry)
    units = []
    for i, un in enumerate(c.units):
        peak_g = float(np.max(np.abs(a_units[i])) / G_M_PER_S2)
        units.append({"unit": un.id, "peak_lateral_acceleration_g": peak_g,
                      "peak_roll_angle_deg": float(np.degrees(np.max(np.abs(rolls[i]))))})  # fmt: skip
        if srt_g is not None:
            k = next(k for k, mem in enumerate(roll_units(model)) if i in mem)
            if peak_g > srt_g[k]:
                validity.append(f"unit {un.id!r}: peak lateral acceleration {peak_g:.3f} g exceeds its roll-coupled "
                                f"unit's SRT {srt_g[k]:.3f} g: lift-off, past the linear model's validity")  # fmt: skip
    hist = {}
    if history:
        step = max(1, round(0.02 / dt))
        hist = {"time_s": t[::step].tolist(), "steer_deg": np.degrees(delta[::step]).tolist(),
                "lateral_acceleration_g": {un.id: (a_units[i][::step] / G_M_PER_S2).tolist()
                                           for i, un in enumerate(c.units)},
                "rear_offtracking_m": offtrack[::step].tolist()}  # fmt: skip
    return LaneChange(speed_kmh, frequency_hz, amplitude_g, ra_definition, ra, hsto, final, rcu, units, validity, dt,
                      hist, deviation)  # fmt: skip


def rearward_amplification_spectrum(model: YawRollModel, speed_kmh: float, freqs_hz: np.ndarray,
                                    ra_definition: str = "cg") -> np.ndarray:  # fmt: skip
    """RA(f) = |a_rear| / |a_steer| per frequency [-]."""
    ss = model.state_space(_speed(speed_kmh))
    rb, rx, _, _ = rear_points(model, ra_definition)
    h = frequency_response(ss, [ss.acceleration(model.point_row(0, 0.0)), ss.acceleration(model.point_row(rb, rx))],
                           np.asarray(freqs_hz, dtype=float))  # fmt: skip
    return np.abs(h[1]) / np.abs(h[0])


def worst_frequency(model: YawRollModel, speed_kmh: float, ra_definition: str = "cg",
                    band: tuple[float, float] = (0.1, 3.0)) -> tuple[float, float]:  # fmt: skip
    """(frequency [Hz], RA) of the largest RA in ``band``: a 60-point logarithmic scan refined by a bounded search."""
    grid = np.geomspace(*band, 60)
    ra = rearward_amplification_spectrum(model, speed_kmh, grid, ra_definition)
    k = int(np.argmax(ra))
    lo, hi = grid[max(k - 1, 0)], grid[min(k + 1, len(grid) - 1)]
    res = scipy.optimize.minimize_scalar(
        lambda f: -rearward_amplification_spectrum(model, speed_kmh, np.array([f]), ra_definition)[0],
        bounds=(lo, hi), method="bounded", options={"xatol": 1e-4})  # fmt: skip
    return (float(res.x), float(-res.fun)) if -res.fun >= ra[k] else (float(grid[k]), float(ra[k]))


def peaks(y: np.ndarray) -> list[int]:
    """Indices of the strict local extrema of a sampled signal."""
    dy = np.diff(y)
    return [k for k in range(1, len(y) - 1) if dy[k - 1] * dy[k] < 0]


def damping_from_peaks(y: np.ndarray, *, same_sign: bool = True, floor: float = 1e-3) -> float | None:
    """Damping ratio from a decaying oscillation's peaks: the mean log decrement over successive same-sign peaks,
    ``zeta = delta / sqrt(4 pi^2 + delta^2)`` (full cycle). ``same_sign=False`` reproduces the half-cycle mistake
    (every extremum taken into the full-cycle formula), for the test that shows it halves the ratio. Peaks below
    ``floor`` times the largest are left out (numerical noise), and so are the peaks before the largest: the free
    decay starts there (earlier peaks are the forced response to the input itself)."""
    ks = peaks(y)
    big = max((abs(y[k]) for k in ks), default=0.0)
    if ks:
        first = max(range(len(ks)), key=lambda i: abs(y[ks[i]]))
        ks = ks[first:]
    ks = [k for k in ks if abs(y[k]) > floor * big]
    decs = []
    if same_sign:
        for sign in (1, -1):
            s = [y[k] * sign for k in ks if y[k] * sign > 0]
            decs += [math.log(s[i] / s[i + 1]) for i in range(len(s) - 1)]
    else:
        decs = [math.log(abs(y[ks[i]]) / abs(y[ks[i + 1]])) for i in range(len(ks) - 1)]
    if not decs:
        return None
    d = float(np.mean(decs))
    return d / math.sqrt(4 * math.pi**2 + d * d)


@dataclass
class PulseSteer:
    speed_kmh: float
    yaw_damping_ratio: float | None
    articulation: str
    least_damped_mode: dict | None
    eigenvalues: list[complex]
    validity: list[str]


def mode_shape(model: YawRollModel, vec: np.ndarray) -> dict[str, dict[str, float]]:
    """A mode's articulations and unit rolls, normalised to the largest magnitude: {name: magnitude, phase}."""
    n = model.n
    qv = vec[: n - 2]
    parts = {f"articulation {name}": row[2:] @ qv for name, row in articulation_rows(model)}
    if model.roll:
        for i, un in enumerate(model.combination.units):
            parts[f"roll {un.id}"] = model.phi_unit_rows[i][2:] @ qv
    # articulations and rolls are both angles [rad]; normalise on the largest
    big = max(abs(v) for v in parts.values()) or 1.0
    ref = max(parts.values(), key=abs)
    ph0 = np.angle(ref)
    return {k: {"magnitude": float(abs(v) / big), "phase_deg": float(np.degrees(np.angle(v) - ph0) % 360.0)}
            for k, v in parts.items()}  # fmt: skip


def pulse_steer(model: YawRollModel, speed_kmh: float, *, pulse_s: float = 0.2, duration_s: float = 20.0,
                dt: float = 0.01) -> PulseSteer:  # fmt: skip
    """Yaw damping after a steer pulse (a half sine of ``pulse_s``; its shape unverified against the rules)."""
    u = _speed(speed_kmh)
    check_stable(model, speed_kmh)
    ss = model.state_space(u)
    t = np.arange(0.0, duration_s + dt / 2, dt)
    steer = np.where(t <= pulse_s, np.sin(np.pi * t / pulse_s), 0.0) * math.radians(1.0)
    x = simulate(ss.A, ss.B, steer, dt)
    arts = articulation_rows(model)
    validity = []
    if arts:
        name, row = arts[-1]
        sig = x[:, : model.n] @ row
        zeta = damping_from_peaks(sig)
        if zeta is None:
            validity.append("the rearmost articulation does not oscillate after the pulse: no peaks to measure")
    else:
        name, zeta = "none", None
        validity.append("a rigid vehicle has no articulation: yaw damping is not defined")
    w, v, _ = eigen(ss)
    k = least_damped_oscillatory(w)
    mode = None
    if k is not None:
        mode = {"damping_ratio": damping_ratio(w[k]), "frequency_hz": float(abs(w[k].imag) / (2 * math.pi)),
                "shape": mode_shape(model, v[:, k])}  # fmt: skip
    return PulseSteer(speed_kmh, zeta, name, mode, [complex(z) for z in w], validity)


@dataclass
class Stability:
    sway_critical_speed_kmh: float | None
    divergence_speed_kmh: float | None
    max_speed_kmh: float


def _growth(model: YawRollModel, v_kmh: float) -> tuple[float, float]:
    w, _, _ = eigen(model.state_space(v_kmh / 3.6))
    osc = [z.real for z in w if abs(z.imag) > 1e-6]
    real = [z.real for z in w if abs(z.imag) <= 1e-6]
    return max(osc, default=-np.inf), max(real, default=-np.inf)


def stability(model: YawRollModel, *, lo_kmh: float = 5.0, hi_kmh: float = MAX_SPEED_KMH) -> Stability:
    """The sway critical speed and the divergence speed (module docstring); None where stable up to ``hi_kmh``."""
    grid = np.arange(lo_kmh, hi_kmh + 1e-9, 2.0)
    found: list[float | None] = [None, None]
    prev = lo_kmh
    for v in grid:
        g = _growth(model, v)
        for k in (0, 1):
            if found[k] is None and g[k] > 0:
                a, b = prev, v
                while b - a > 0.05:
                    mid = 0.5 * (a + b)
                    if _growth(model, mid)[k] > 0:
                        b = mid
                    else:
                        a = mid
                found[k] = round(b, 2)
        prev = v
        if all(f is not None for f in found):
            break
    return Stability(found[0], found[1], hi_kmh)


@dataclass
class SteadyTurn:
    radius_m: float
    speed_kmh: float
    lateral_acceleration_g: float
    steer_deg: float
    axles: list[dict]
    units: list[dict]
    roll_coupled_units: list[dict]
    validity: list[str]
    couplings: list[dict]


def steady_turn(model: YawRollModel, radius_m: float, speed_kmh: float, srt_g: list[float] | None = None
                ) -> SteadyTurn:  # fmt: skip
    """The steady turn with the steer axle's path on ``radius_m`` at ``speed_kmh`` (module docstring; from 0.5 km/h,
    a crawl)."""
    u = _speed(speed_kmh, 0.5)
    if not isinstance(radius_m, int | float) or not 10.0 <= radius_m <= 10000.0:
        raise InvalidRoad("radius_m must be from 10 to 10000 m", field="radius_m", value=radius_m)
    check_stable(model, speed_kmh)
    ss = model.state_space(u)
    z1, red = steady_state(ss)
    n = model.n
    x1 = red.L @ z1
    v1, r1 = x1[n], x1[n + 1]  # per rad of steer; v = lateral velocity of the steer axle (psi_0 = 0)
    k = v1 / r1
    r = u / math.sqrt(radius_m**2 - k**2) if radius_m > abs(k) else u / radius_m
    delta = r / r1
    x = x1 * delta
    q = x[:n]
    c = model.combination
    # geometry of the instant: each body's heading (its yaw relative to the first) and reference point
    heads = [float(model.psi_rows[b] @ q - model.psi_rows[0] @ q) for b in range(len(model.bodies))]
    refs = [np.zeros(2) for _ in model.bodies]

    def direction(h: float) -> np.ndarray:  # the body's forward axis
        return np.array([math.cos(h), math.sin(h)])

    for b in range(1, len(model.bodies)):
        body = model.bodies[b]
        un = c.units[body.unit]
        if body.part == "unit" and un.kind == "full-trailer":
            xt = un.groups[0].position_m
            refs[b] = refs[b - 1] - xt * direction(heads[b - 1]) + xt * direction(heads[b])
        else:
            a = model.main_body[body.unit - 1]
            refs[b] = refs[a] - c.couplings[body.unit - 1].position_m * direction(heads[a])
    v0 = np.array([u, x[n]])

    def radius_of(p: np.ndarray) -> float:
        vel = v0 + r * np.array([-p[1], p[0]])
        return float(np.hypot(*vel) / r)

    axles = []
    for i, j in model.parameters.groups:
        b = model.group_body[(i, j)]
        xg = c.units[i].groups[j].position_m
        p = refs[b] - xg * direction(heads[b])
        rad = radius_of(p)
        axles.append({"unit": c.units[i].id, "group": c.units[i].groups[j].id, "path_radius_m": rad,
                      "offtracking_m": radius_m - rad})  # fmt: skip
    couplings = []
    for k_, cp in enumerate(c.couplings):
        a = model.main_body[k_]
        p = refs[a] - cp.position_m * direction(heads[a])
        couplings.append({"coupling": k_, "kind": cp.kind, "path_radius_m": radius_of(p)})
    ay = u * r / G_M_PER_S2
    units = []
    for i, un in enumerate(c.units):
        entry = {"unit": un.id, "articulation_deg": None}
        if i > 0:
            b = model.main_body[i]
            entry["articulation_deg"] = math.degrees(heads[model.main_body[i - 1]] - heads[b])
        entry["roll_angle_deg"] = math.degrees(float(model.phi_unit_rows[i] @ q)) if model.roll else 0.0
        units.append(entry)
    rcu, validity = [], []
    for kk, members in enumerate(roll_units(model)):
        e = {"units": [c.units[i].id for i in members]}
        if model.roll:
            cc, dd = ss.unit_ltr(members)
            e["load_transfer_ratio"] = float(abs(x @ cc + dd * delta))
        if srt_g is not None:
            e["srt_g"] = srt_g[kk]
            if ay > srt_g[kk]:
                validity.append(f"roll-coupled unit {e['units']}: {ay:.3f} g exceeds its SRT {srt_g[kk]:.3f} g")
        rcu.append(e)
    for e in units:
        e["load_transfer_ratio"] = (
            next(r_["load_transfer_ratio"] for r_ in rcu if e["unit"] in r_["units"]) if model.roll else None
        )
    return SteadyTurn(radius_m, speed_kmh, ay, math.degrees(delta), axles, units, rcu, validity, couplings)


__all__ = [
    "LaneChange",
    "PulseSteer",
    "Stability",
    "SteadyTurn",
    "Unstable",
    "damping_from_peaks",
    "lane_change",
    "pulse_steer",
    "rearward_amplification_spectrum",
    "reduced",
    "stability",
    "steady_turn",
    "worst_frequency",
]  # fmt: skip

"""Closed-form static rollover models of Chapter 2, and their mapping from the vehicle record.

Each model is a small pure function of its own symbols (Eqs. 2.6-2.30); :func:`classic_threshold` maps
the vehicle record and load case onto those symbols:

==================  =====================================================================================
symbol              from the record
==================  =====================================================================================
t                   rear_track_m (t3); with a lateral CG offset d1 the half track t/2 becomes t/2 - d1
h                   lr + ls + l12 + d3, the static CG height (so t/2h = 0.451 for the B-train)
h0                  lr + ls, the roll-centre height (spring seat) of Rill's and Gillespie's figures
W (2D models)       the rear group's static share, W (1 + overweight) (a - d2)/L; the whole W for a
                    record without wheelbase (Table 14). Rigid, rigid-bank, Winkler, Rill and Chang
                    describe one axle group, as the developed 2D model does (Ch. 7 uses the tridem).
W (3D models)       the whole W (1 + overweight) for Gillespie and Navin, which see both groups
k_theta             kLs_side b^2 / 2 per group (Eq. 2.11, per-side stiffness as in vehicles.py)
kT                  the per-side tire stiffness of the group (Eq. 2.14 deflects one side by W/2)
theta (Chang)       suspension roll at the limit, Eq. 2.17 with theta1 of Eq. 2.15
theta (Navin)       body roll at the limit, Eq. 2.27 (Gillespie's roll about the roll axis)
Delta t (Winkler)   h theta1 + l12 theta2 (tire roll about the outer contact, suspension roll about the
                    roll centre); with this small-angle mapping Winkler's Eq. 2.10 coincides with Rill's
                    Eq. 2.20 -- they are the same mechanics written two ways
lre, L, h5 (Navin)  L - a + d2, wheelbase_m, lr + ls + lf (the kingpin height; lr + ls for a truck)
==================  =====================================================================================

Models that do not contain a road or load effect refuse it instead of ignoring it (the ``takes`` of each
model in :data:`engine.models.registry.MODELS`): only rigid-bank, Chang and Navin take a bank angle; none of them takes
slope, trailer angle or a lateral-load-transfer limit below 1.

References
----------
Gillespie (1992); Winkler et al. (1992); Navin (1992); Chang (2001); Rill (2011); thesis Ch. 2.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from engine.case import Case
from engine.errors import InvalidLoad
from engine.vehicle.record import cg_height_m, group_stiffness, static_axle_loads

# ------------------------------------------------------------------------------- the formulas


def rigid(t, h):
    """Rigid vehicle: SRT = (t/2) / h [g] (Eq. 2.6). t track [m], h CG height [m]."""
    return (t / 2.0) / h


def rigid_bank(t, h, e):
    """Rigid vehicle on a bank: SRT = t/2h + e [g] (Eq. 2.8), e = tan(bank angle) [-]."""
    return (t / 2.0) / h + e


def winkler(t, delta_t, h2):
    """Winkler et al.: SRT = (t/2 - Delta t) / h2 [g] (Eq. 2.10); Delta t lateral CG shift [m]."""
    return (t / 2.0 - delta_t) / h2


def rill(t, h, l12, k_theta, k_t, weight):
    """Rill: SRT = (t/2) / (h + l12/(k*_theta - 1)) - 1/k*_T [g] (Eq. 2.20, with Eq. 2.19).

    k_theta suspension roll stiffness [kN m/rad], k_t tire stiffness of one side [kN/m], weight m g [kN].
    """
    k_t_star = t * k_t / weight  # Eq. 2.19
    k_theta_star = k_theta / (weight * l12)
    return (t / 2.0) / (h + l12 / (k_theta_star - 1.0)) - 1.0 / k_t_star


def rill_roll_angles(ay_g, t, l12, k_theta, k_t, weight):
    """Tire roll theta1 = m g/(t kT) (Eq. 2.15) and suspension roll theta2 (Eq. 2.17) at the limit [rad]."""
    theta1 = weight / (t * k_t)
    a = weight * l12 / (k_theta - weight * l12)
    return theta1, ay_g * a + a * theta1


def chang(t, h, h0, bank_rad, theta):
    """Chang, rigid-suspension on a bank: SRT = t/2h + (1 - h0/h)(phi - theta) [g] (Eq. 2.22)."""
    return (t / 2.0) / h + (1.0 - h0 / h) * (bank_rad - theta)


def gillespie(t, h, h0, weight, k_theta_f, k_theta_r):
    """Gillespie: SRT = (t/2h) / (1 + (1 - h0/h) W(h-h0)/(k_f + k_r - W(h-h0))) [g] (Eq. 2.28)."""
    m = weight * (h - h0)
    return (t / (2.0 * h)) / (1.0 + (1.0 - h0 / h) * (m / (k_theta_f + k_theta_r - m)))


def gillespie_roll(ay_g, h, h0, weight, k_theta_f, k_theta_r):
    """Roll angle about the roll axis, theta = W(h-h0)/(k_f + k_r - W(h-h0)) ay/g [rad] (Eq. 2.27)."""
    m = weight * (h - h0)
    return m / (k_theta_f + k_theta_r - m) * ay_g


def navin(t, h, h0, h5, lre, wheelbase, bank_rad, theta):
    """Navin, roll axis from the fifth wheel to the rear outer tire (Eq. 2.30) [g].

    SRT = [t/2 (1 - lre/L) + h(phi - theta) - h5 lre phi/L + h0 theta] / [t phi/2 (lre/L - 1) + h - h5 lre/L]
    """
    r = lre / wheelbase
    num = (t / 2.0) * (1.0 - r) + h * (bank_rad - theta) - h5 * r * bank_rad + h0 * theta
    den = (t * bank_rad / 2.0) * (r - 1.0) + h - h5 * r
    return num / den


# ------------------------------------------------------------------------------ the mapping


@dataclass(frozen=True)
class ClassicResult:
    model: str
    srt: float  # [g]
    roll_angle_deg: float | None  # [deg], None for the rigid models
    parameters: dict[str, float] = field(default_factory=dict)  # the mapped symbols, for transparency


@dataclass(frozen=True)
class _Symbols:
    """The record and load case mapped onto the symbols of Ch. 2 (see the module docstring)."""

    t: float  # track, with the lateral offset: t - 2 d1 [m]
    h: float  # static CG height lr + ls + l12 + d3 [m]
    h0: float  # roll-centre (spring-seat) height lr + ls [m]
    l12: float  # CG height above the chassis with d3 [m]
    bank: float  # bank angle phi [rad]
    w_total: float  # W (1 + overweight) [kN]
    w_rear: float  # the rear group's static share [kN]
    k_theta_r: float  # rear suspension roll stiffness (Eq. 2.11) [kN m/rad]
    k_t: float  # rear tire stiffness of one side [kN/m]

    def params(self, **more: float) -> dict[str, float]:
        return {"t": self.t, "h": self.h, "h0": self.h0, "l12": self.l12, **more}


def _symbols(case: Case) -> _Symbols:
    v, load = case.vehicle, case.load
    w_total = case.weight_kn
    _, w_rear = static_axle_loads(v, load.longitudinal_offset_m, weight_kn=w_total)
    rear = group_stiffness(v, "rear")
    h = cg_height_m(v, load.vertical_offset_m)
    return _Symbols(
        t=v.rear_track_m - 2.0 * load.lateral_offset_m,  # (t/2 - d1) as a track: the CG is d1 nearer the outer tires
        h=h,
        h0=v.rolling_radius_m + v.suspension_height_m,
        l12=v.cg_height_above_chassis_m + load.vertical_offset_m,
        bank=case.road.bank_rad,
        w_total=w_total,
        w_rear=w_rear,
        k_theta_r=rear.roll_stiffness(v.spring_separation_m),
        k_t=rear.tire_side_kn_per_m,
    )


def _group_roll_stiff_enough(s: _Symbols, case: Case) -> None:
    if s.k_theta_r <= s.w_rear * s.l12:
        raise InvalidLoad(
            "the suspension roll stiffness does not exceed m g l12 for this load (Eq. 2.17)",
            field="load.overweight_percent",
            value=case.load.overweight_percent,
        )


def solve_rigid(case: Case) -> ClassicResult:
    """Eq. 2.6 for the case."""
    s = _symbols(case)
    return ClassicResult("rigid", float(rigid(s.t, s.h)), None, s.params())


def solve_rigid_bank(case: Case) -> ClassicResult:
    """Eq. 2.8 for the case."""
    s = _symbols(case)
    e = math.tan(s.bank)
    return ClassicResult("rigid-bank", float(rigid_bank(s.t, s.h, e)), None, s.params(e=e))


def _rill_or_winkler(case: Case, model: str) -> ClassicResult:
    s = _symbols(case)
    _group_roll_stiff_enough(s, case)
    srt = rill(s.t, s.h, s.l12, s.k_theta_r, s.k_t, s.w_rear)
    th1, th2 = rill_roll_angles(srt, s.t, s.l12, s.k_theta_r, s.k_t, s.w_rear)
    params = s.params(W=s.w_rear, k_theta=s.k_theta_r, kT=s.k_t)
    if model == "winkler":
        delta_t = s.h * th1 + s.l12 * th2
        params.update(delta_t=delta_t, h2=s.h)
        srt = winkler(s.t, delta_t, s.h)
    return ClassicResult(model, float(srt), math.degrees(th1 + th2), params)


def solve_rill(case: Case) -> ClassicResult:
    """Eq. 2.20 for the case."""
    return _rill_or_winkler(case, "rill")


def solve_winkler(case: Case) -> ClassicResult:
    """Eq. 2.10 with Delta t from the tire and suspension roll (coincides with Rill, see the module docstring)."""
    return _rill_or_winkler(case, "winkler")


def solve_chang(case: Case) -> ClassicResult:
    """Eq. 2.22: theta (suspension roll, Eq. 2.17) is linear in ay, so the equation is solved exactly."""
    s = _symbols(case)
    _group_roll_stiff_enough(s, case)
    th1, _ = rill_roll_angles(0.0, s.t, s.l12, s.k_theta_r, s.k_t, s.w_rear)
    a = s.w_rear * s.l12 / (s.k_theta_r - s.w_rear * s.l12)
    c = 1.0 - s.h0 / s.h
    srt = ((s.t / 2.0) / s.h + c * (s.bank - a * th1)) / (1.0 + c * a)
    theta = a * srt + a * th1
    params = s.params(W=s.w_rear, k_theta=s.k_theta_r, kT=s.k_t, phi=s.bank, theta=theta)
    return ClassicResult("chang", float(chang(s.t, s.h, s.h0, s.bank, theta)), math.degrees(theta), params)


def _whole_vehicle(case: Case) -> tuple[_Symbols, float]:
    """The symbols and the front roll stiffness of a 3D closed form, which sees both groups."""
    s = _symbols(case)
    v = case.vehicle
    k_theta_f = group_stiffness(v, "front").roll_stiffness(v.spring_separation_m) if v.front_axles else 0.0
    if k_theta_f + s.k_theta_r <= s.w_total * (s.h - s.h0):
        raise InvalidLoad(
            "the total roll stiffness does not exceed W (h - h0) (Eq. 2.27)",
            field="load.overweight_percent",
            value=case.load.overweight_percent,
        )
    return s, k_theta_f


def solve_gillespie(case: Case) -> ClassicResult:
    """Eq. 2.28 with the roll of Eq. 2.27."""
    s, k_theta_f = _whole_vehicle(case)
    srt = gillespie(s.t, s.h, s.h0, s.w_total, k_theta_f, s.k_theta_r)
    theta = gillespie_roll(srt, s.h, s.h0, s.w_total, k_theta_f, s.k_theta_r)
    params = s.params(W=s.w_total, k_theta_f=k_theta_f, k_theta_r=s.k_theta_r)
    return ClassicResult("gillespie", float(srt), math.degrees(theta), params)


def solve_navin(case: Case) -> ClassicResult:
    """Eq. 2.30: with theta = B SRT (Eq. 2.27) it is linear in the SRT.

    Navin's moment balance (Eq. 2.29) is about a roll axis from the fifth wheel (height h5) to the rear outer tire;
    it describes rollover only while the CG lies above that axis, h - h5 lre/L > 0 at the CG's section. A CG at or
    below it (a very low load under a high kingpin) cannot roll about it: the formula's denominator changes sign
    and gives a negative SRT, so such a case is refused.
    """
    s, k_theta_f = _whole_vehicle(case)
    v = case.vehicle
    lre = v.wheelbase_m - v.front_axle_to_cg_m + case.load.longitudinal_offset_m
    h5 = s.h0 + ((v.fifth_wheel_height_m or 0.0) if v.has_fifth_wheel else 0.0)
    r = lre / v.wheelbase_m
    above_axis = s.h - h5 * r
    if above_axis <= 0:
        raise InvalidLoad(
            f"the CG ({s.h:.3f} m high) lies {-above_axis:.3f} m below Navin's roll axis (fifth wheel at h5 = "
            f"{h5:.3f} m to the rear outer tire, {h5 * r:.3f} m high at the CG): the model (Eq. 2.29) does not "
            "apply; use the 3d model",
            field="cg_height_above_chassis_m",
            value=v.cg_height_above_chassis_m,
        )
    b = gillespie_roll(1.0, s.h, s.h0, s.w_total, k_theta_f, s.k_theta_r)
    n0 = (s.t / 2.0) * (1.0 - r) + s.h * s.bank - h5 * r * s.bank
    d0 = (s.t * s.bank / 2.0) * (r - 1.0) + above_axis
    srt = n0 / (d0 + (s.h - s.h0) * b)
    theta = b * srt
    params = s.params(
        W=s.w_total,
        k_theta_f=k_theta_f,
        k_theta_r=s.k_theta_r,
        lre=lre,
        L=v.wheelbase_m,
        h5=h5,
        phi=s.bank,
        theta=theta,
    )
    srt = navin(s.t, s.h, s.h0, h5, lre, v.wheelbase_m, s.bank, theta)
    return ClassicResult("navin", float(srt), math.degrees(theta), params)

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

Models that do not contain a road or load effect refuse it (:class:`InvalidRoad`) instead of ignoring it:
only rigid-bank, Chang and Navin take a bank angle; none of them takes slope, trailer angle or a
lateral-load-transfer limit below 1.

References
----------
Gillespie (1992); Winkler et al. (1992); Navin (1992); Chang (2001); Rill (2011); thesis Ch. 2.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from .errors import InvalidInput, InvalidLoad, InvalidRoad
from .loads import LoadCase, Road, check_case
from .vehicles import Vehicle, group_stiffness, static_axle_loads, validate_vehicle

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
class ModelInfo:
    id: str
    name: str
    equation: str
    reference: str
    takes: tuple[str, ...]  # road/load inputs the model accounts for
    summary: str


MODELS: dict[str, ModelInfo] = {
    m.id: m
    for m in (
        ModelInfo(
            "3d",
            "Developed 3D trailer model",
            "Eqs. 6.1-6.2, 6.17-6.18",
            "Moreno (thesis), Ch. 6",
            ("bank", "slope", "trailer_angle", "d1", "d2", "d3", "overweight", "rear_llt_limit", "stage"),
            "Davies-method mechanism of the last trailer: tires, leaf springs, fifth wheel, chassis.",
        ),
        ModelInfo(
            "2d",
            "Developed 2D trailer model",
            "Eqs. 5.1-5.2, 5.22",
            "Moreno (thesis), Ch. 5",
            ("bank", "d1", "d2", "d3", "overweight", "rear_llt_limit"),
            "Planar mechanism of one axle group: tires and leaf-spring suspension.",
        ),
        ModelInfo("rigid", "Rigid vehicle", "Eq. 2.6", "Gillespie (1992)", ("d1", "d3"), "SRT = t/2h."),
        ModelInfo(
            "rigid-bank",
            "Rigid vehicle on a banked road",
            "Eq. 2.8",
            "Chang (2001)",
            ("bank", "d1", "d3"),
            "SRT = t/2h + e.",
        ),
        ModelInfo(
            "winkler",
            "Winkler model",
            "Eq. 2.10",
            "Winkler et al. (1992)",
            ("d1", "d2", "d3", "overweight"),
            "SRT = (t/2 - Delta t)/h2, CG shift from roll compliance.",
        ),
        ModelInfo(
            "rill",
            "Rill model",
            "Eq. 2.20",
            "Rill (2011)",
            ("d1", "d2", "d3", "overweight"),
            "Tire and suspension roll compliance, small angles.",
        ),
        ModelInfo(
            "chang",
            "Chang model",
            "Eq. 2.22",
            "Chang (2001)",
            ("bank", "d1", "d2", "d3", "overweight"),
            "Suspension roll on a banked road.",
        ),
        ModelInfo(
            "gillespie",
            "Gillespie model",
            "Eq. 2.28",
            "Gillespie (1992)",
            ("d1", "d2", "d3", "overweight"),
            "Roll about the axis through front and rear roll centres.",
        ),
        ModelInfo(
            "navin",
            "Navin model",
            "Eq. 2.30",
            "Navin (1992)",
            ("bank", "d1", "d2", "d3", "overweight"),
            "Roll axis from the fifth wheel to the rear outer tire.",
        ),
    )
}
CLASSIC_MODELS = ("rigid", "rigid-bank", "winkler", "rill", "chang", "gillespie", "navin")


@dataclass(frozen=True)
class ClassicResult:
    model: str
    srt: float  # [g]
    roll_angle_deg: float | None  # [deg], None for the rigid models
    parameters: dict[str, float] = field(default_factory=dict)  # the mapped symbols, for transparency


def _refuse_unsupported(
    model: str, road: Road, trailer_angle_deg: float, load: LoadCase, rear_llt_limit: float
) -> None:
    takes = MODELS[model].takes
    checks = (
        ("bank", "road.bank_percent", road.bank_percent, InvalidRoad),
        ("slope", "road.slope_percent", road.slope_percent, InvalidRoad),
        ("trailer_angle", "trailer_angle_deg", trailer_angle_deg, InvalidRoad),
        ("d1", "load.lateral_offset_m", load.lateral_offset_m, InvalidLoad),
        ("d2", "load.longitudinal_offset_m", load.longitudinal_offset_m, InvalidLoad),
        ("d3", "load.vertical_offset_m", load.vertical_offset_m, InvalidLoad),
        ("overweight", "load.overweight_percent", load.overweight_percent, InvalidLoad),
    )
    for key, name, value, exc in checks:
        if value != 0 and key not in takes:
            raise exc(
                f"the {model} model ({MODELS[model].equation}) does not account for {name}; "
                f"use a model that does (2d or 3d)",
                field=name,
                value=value,
            )
    if rear_llt_limit != 1.0 and "rear_llt_limit" not in takes:
        raise InvalidLoad(
            f"the {model} model is defined at wheel lift-off only (LLT = 1)",
            field="rear_llt_limit",
            value=rear_llt_limit,
        )


def classic_threshold(
    vehicle: Vehicle,
    model: str,
    road: Road = Road(),
    load: LoadCase = LoadCase(),
    trailer_angle_deg: float = 0.0,
    rear_llt_limit: float = 1.0,
) -> ClassicResult:
    """SRT of one closed-form model of Ch. 2 for ``vehicle`` (see the module docstring for the mapping)."""
    if model not in CLASSIC_MODELS:
        raise InvalidInput(f"unknown closed-form model {model!r}", field="model", value=model)
    validate_vehicle(vehicle, model=model)
    check_case(vehicle, road, trailer_angle_deg, load)
    _refuse_unsupported(model, road, trailer_angle_deg, load, rear_llt_limit)

    v = vehicle
    t = v.rear_track_m
    d1, d2, d3 = load.lateral_offset_m, load.longitudinal_offset_m, load.vertical_offset_m
    t_eff = t - 2.0 * d1  # (t/2 - d1) written as a track: the CG sits d1 closer to the outer tires
    h0 = v.rolling_radius_m + v.suspension_height_m
    l12 = v.cg_height_above_chassis_m + d3
    h = h0 + l12
    bank = road.bank_rad
    w_total = load.weight_kn(v.weight_kn)
    _, w_rear = static_axle_loads(v, d2, weight_kn=w_total)
    rear = group_stiffness(v, "rear")
    k_theta_r = rear.roll_stiffness(v.spring_separation_m)
    params = {"t": t_eff, "h": h, "h0": h0, "l12": l12}

    if model == "rigid":
        return ClassicResult(model, float(rigid(t_eff, h)), None, params)
    if model == "rigid-bank":
        e = math.tan(bank)
        return ClassicResult(model, float(rigid_bank(t_eff, h, e)), None, {**params, "e": e})

    k_t = rear.tire_side_kn_per_m
    if model in ("rill", "winkler", "chang"):
        if k_theta_r <= w_rear * l12:
            raise InvalidLoad(
                "the suspension roll stiffness does not exceed m g l12 for this load (Eq. 2.17)",
                field="load.overweight_percent",
                value=load.overweight_percent,
            )
        params.update(W=w_rear, k_theta=k_theta_r, kT=k_t)
        if model in ("rill", "winkler"):
            srt = rill(t_eff, h, l12, k_theta_r, k_t, w_rear)
            th1, th2 = rill_roll_angles(srt, t_eff, l12, k_theta_r, k_t, w_rear)
            if model == "winkler":
                delta_t = h * th1 + l12 * th2
                params.update(delta_t=delta_t, h2=h)
                srt = winkler(t_eff, delta_t, h)
            return ClassicResult(model, float(srt), math.degrees(th1 + th2), params)
        # Chang: theta (suspension roll, Eq. 2.17) is linear in ay, so Eq. 2.22 is solved exactly
        th1, _ = rill_roll_angles(0.0, t_eff, l12, k_theta_r, k_t, w_rear)
        a = w_rear * l12 / (k_theta_r - w_rear * l12)
        c = 1.0 - h0 / h
        srt = ((t_eff / 2.0) / h + c * (bank - a * th1)) / (1.0 + c * a)
        theta = a * srt + a * th1
        params.update(phi=bank, theta=theta)
        return ClassicResult(model, float(chang(t_eff, h, h0, bank, theta)), math.degrees(theta), params)

    # 3D closed forms: the whole vehicle over both groups
    k_theta_f = 0.0
    if v.front_axles is not None:
        k_theta_f = group_stiffness(v, "front").roll_stiffness(v.spring_separation_m)
    if k_theta_f + k_theta_r <= w_total * (h - h0):
        raise InvalidLoad(
            "the total roll stiffness does not exceed W (h - h0) (Eq. 2.27)",
            field="load.overweight_percent",
            value=load.overweight_percent,
        )
    params.update(W=w_total, k_theta_f=k_theta_f, k_theta_r=k_theta_r)
    if model == "gillespie":
        srt = gillespie(t_eff, h, h0, w_total, k_theta_f, k_theta_r)
        theta = gillespie_roll(srt, h, h0, w_total, k_theta_f, k_theta_r)
        return ClassicResult(model, float(srt), math.degrees(theta), params)
    # Navin: theta = B SRT (Eq. 2.27) makes Eq. 2.30 linear in the SRT
    lre = v.wheelbase_m - v.front_axle_to_cg_m + d2
    h5 = h0 + ((v.fifth_wheel_height_m or 0.0) if v.has_fifth_wheel else 0.0)
    b = gillespie_roll(1.0, h, h0, w_total, k_theta_f, k_theta_r)
    r = lre / v.wheelbase_m
    n0 = (t_eff / 2.0) * (1.0 - r) + h * bank - h5 * r * bank
    d0 = (t_eff * bank / 2.0) * (r - 1.0) + h - h5 * r
    srt = n0 / (d0 + (h - h0) * b)
    theta = b * srt
    params.update(lre=lre, L=v.wheelbase_m, h5=h5, phi=bank, theta=theta)
    return ClassicResult(
        model, float(navin(t_eff, h, h0, h5, lre, v.wheelbase_m, bank, theta)), math.degrees(theta), params
    )

"""The speed profile of a truck along a sequence of curves: desired speed on the tangents, braking into each curve at a
stated rate, accelerating out of it within the truck's power on the grade, never above a curve's speed.

Model
-----
The alignment is a chain of nodes (each curve's start and end). On every element the squared speed v^2 is bounded
three ways: by the element's cap (the desired speed on a tangent; on a curve the lowest of the desired, safe and
advisory speeds), by acceleration from the node before (v^2 = v0^2 + 2 a s, a the element's acceleration) and by
braking to the node after (v^2 = v1^2 + 2 d (L - s), d the stated deceleration). The profile is the pointwise minimum:
the forward pass is a min-plus recurrence solved with a cumulative minimum, the backward pass likewise, so 100,000
curves take a few numpy passes. Between the returned stations v^2 is linear in station (constant rate).

Rates
-----
- deceleration: 10 ft/s^2 = 3.048 m/s^2 and a 2.5 s reaction time by default, the basis of MUTCD 11e Table 2C-3
  (as transcribed; unverified against the manual). The largest accepted is 15 ft/s^2 = 4.572 m/s^2, the emergency
  braking rate NCHRP Report 774 (2014, Summary) studied for trucks on curves (its other rate: 11.2 ft/s^2, the
  stopping-sight-distance rate); beyond it a loaded truck does not brake, so it is refused.
- acceleration: a vehicle-dynamics model (tractive power against rolling, grade and air resistance; the form of
  Rakha et al., ASCE J. Transp. Eng. 2001, whose abstract was read) evaluated at the desired speed, the lowest
  acceleration over the speeds the truck passes through below it. The weight-to-power ratio default, 120 kg/kW
  (200 lb/hp), is the HCM's typical truck named by Rakha and Yu; the efficiency, rolling and air coefficients are
  assumed (:data:`ACCELERATION_DEFAULTS`). NCHRP's 2003 truck speed-profile model (Review of Truck Characteristics,
  App. E) could not be read. Where the truck cannot accelerate at the desired speed (a steep upgrade) it holds the
  speed it leaves the curve with (a stated simplification: the model's crawl speed is not computed).

Per curve: the speed the truck can reach at the curve's start without braking for it (``approach_speed_kmh``), whether
the tangent before lets it slow to the advisory and to the safe speed at the rate with the reaction distance
(too close exactly when L < (v1^2 - v2^2) / (2 d) + v1 t), the deceleration it would need, the advance-sign distance
and the speed drop. Curves whose stations overlap or run backwards carry a reason instead of a profile.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from engine.errors import InvalidRoad

G = 9.81
FT = 0.3048
#: MUTCD 11e Table 2C-3 basis (as transcribed; unverified): 10 ft/s^2 deceleration, 2.5 s reaction
DECELERATION_MPS2 = 10.0 * FT
REACTION_TIME_S = 2.5
#: NCHRP Report 774 (2014), Summary: emergency braking, -15 ft/s^2, the most a truck was taken to brake in a curve
MAX_TRUCK_DECELERATION_MPS2 = 15.0 * FT
#: NCHRP Report 774 (2014), Summary: stopping-sight-distance braking, -11.2 ft/s^2
SSD_DECELERATION_MPS2 = 11.2 * FT

#: acceleration model: weight-to-power 120 kg/kW (HCM typical truck, as named by Rakha and Yu); the rest assumed
ACCELERATION_DEFAULTS = {
    "weight_to_power_kg_per_kw": 120.0,
    "transmission_efficiency": 0.94,  # assumed
    "rolling_resistance": 0.0075,  # assumed, [-] of the weight
    "drag_area_m2_per_t": 0.17,  # assumed C_d A per tonne (about 6 m^2 for 36 t)
    "air_density_kg_m3": 1.2,  # assumed
}


#: elements per chunk of the profile's arithmetic (the acceleration, the passes, the per-curve figures, the points):
#: the temporaries of a chunk stay in the allocator's free memory, where whole-road temporaries (megabytes each) come
#: back from the system as fresh pages, which cost more to touch than the arithmetic on them (at 100,000 curves, half
#: the profile's time)
_CHUNK = 8192


def check_deceleration(deceleration_mps2: float, field: str = "deceleration_mps2") -> None:
    """Refuse a deceleration a loaded truck cannot brake at (> NCHRP 774's 15 ft/s^2) or <= 0."""
    if not (math.isfinite(deceleration_mps2) and 0 < deceleration_mps2 <= MAX_TRUCK_DECELERATION_MPS2 + 1e-12):
        raise InvalidRoad(
            f"deceleration must lie in (0, {MAX_TRUCK_DECELERATION_MPS2:.3f}] m/s^2: 15 ft/s^2 is the emergency "
            "braking rate NCHRP Report 774 takes for trucks in curves; a loaded truck does not brake harder",
            field=field,
            value=deceleration_mps2,
        )


#: the share of the crawl speed (the speed the truck holds on a grade, acceleration 0) taken as its top speed there
#: (assumed: at the crawl speed itself the model leaves no acceleration to reach it)
CRAWL_FRACTION = 0.9


def crawl_speed_kmh(grade_percent, **params) -> np.ndarray:
    """The speed at which the truck's acceleration on a grade falls to 0 [km/h], at most 200.

    a(v) = 0 with a = c1 / v - c2 - c3 v^2 (:func:`acceleration_mps2`) is the cubic c3 v^3 + c2 v - c1 = 0; since
    c1, c3 > 0 it has one positive root (negative at 0, and once rising it keeps rising), solved in closed form
    (Cardano; the trigonometric form's largest root where the cubic has three real roots, a steep downgrade).
    """
    p = {**ACCELERATION_DEFAULTS, **params}
    g = np.atleast_1d(np.asarray(grade_percent, dtype=float))
    c1 = p["transmission_efficiency"] * 1000.0 / p["weight_to_power_kg_per_kw"]
    c2 = G * (p["rolling_resistance"] + 0.01 * g)
    c3 = 0.5 * p["air_density_kg_m3"] * p["drag_area_m2_per_t"] / 1000.0
    pp, qq = c2 / c3, -c1 / c3  # v^3 + pp v + qq = 0
    disc = (qq / 2.0) ** 2 + (pp / 3.0) ** 3
    with np.errstate(invalid="ignore"):
        root = np.sqrt(np.maximum(disc, 0.0))
        v = np.cbrt(-qq / 2.0 + root) + np.cbrt(-qq / 2.0 - root)
        # the trigonometric form only where the discriminant is negative (a downgrade steeper than the rolling
        # resistance; nan too): where the crawl speed binds, on upgrades, mostly nowhere
        three = np.flatnonzero(~(disc >= 0))
        if len(three):
            m = np.sqrt(np.maximum(-pp[three] / 3.0, 0.0))
            arg = np.clip(np.where(m > 0, (-qq / 2.0) / np.where(m > 0, m, 1.0) ** 3, 1.0), -1.0, 1.0)
            v[three] = 2.0 * m * np.cos(np.arccos(arg) / 3.0)
    return np.minimum(v * 3.6, 200.0)


def acceleration_mps2(speed_kmh, grade_percent, out=None, **params) -> np.ndarray:
    """The truck's largest acceleration at a speed on a grade [m/s^2] (may be negative):
    a = eta P / (m v) - g (C_r + G) - rho C_d A v^2 / (2 m), P/m from the weight-to-power ratio.

    Parameters
    ----------
    speed_kmh : speed [km/h]
    grade_percent : grade along travel, + uphill [%]
    out : an array of the speeds' length (1-D) to write the accelerations into (None: a new one)
    params : overrides of :data:`ACCELERATION_DEFAULTS`
    """
    speed, grade_percent = np.asarray(speed_kmh, dtype=float), np.asarray(grade_percent, dtype=float)
    if speed.ndim == 1 and grade_percent.shape == speed.shape and (len(speed) > _CHUNK or out is not None):
        # in chunks: small temporaries; each chunk's figures written into ``out`` (which may be ``speed`` itself)
        if out is None:
            out = np.empty(len(speed))
        for lo in range(0, len(speed), _CHUNK):
            k = slice(lo, lo + _CHUNK)
            out[k] = acceleration_mps2(speed[k], grade_percent[k], **params)
        return out
    p = {**ACCELERATION_DEFAULTS, **params}
    v = np.maximum(speed / 3.6, 0.1)
    power_per_kg = 1000.0 / p["weight_to_power_kg_per_kw"]  # W/kg
    grade = 0.01 * np.asarray(grade_percent, dtype=float)
    drag = 0.5 * p["air_density_kg_m3"] * p["drag_area_m2_per_t"] / 1000.0 * v**2
    a = p["transmission_efficiency"] * power_per_kg / v - G * (p["rolling_resistance"] + grade) - drag
    if out is not None:
        out[...] = a
        return out
    return a


@dataclass
class SpeedProfile:
    """A truck's profile along the curves: ``station_m``/``speed_kmh`` (empty when a curve's stations make a
    profile impossible), and per curve (arrays, nan when no profile): the approach speed, the speed at the curve's
    start in the profile, the required deceleration, the approach checks, the advance-sign distance, the speed drop
    and a reason (None when the curve is fine)."""

    station_m: np.ndarray
    speed_kmh: np.ndarray
    approach_speed_kmh: np.ndarray
    entry_speed_kmh: np.ndarray | None  # (this and the checks below None where ``all_figures`` was False)
    curve_speed_kmh: np.ndarray  # the cap the truck takes the curve at (lowest of desired, safe, advisory)
    required_deceleration_mps2: np.ndarray  # to the curve speed, with the reaction distance (inf: no room; nan: the
    # first curve's approach length is unknown)
    slows_to_advisory: np.ndarray | None  # bool; True where there is no advisory below the approach
    slows_to_safe: np.ndarray | None
    advance_sign_distance_m: np.ndarray | None
    speed_drop_kmh: np.ndarray | None
    reasons: list[str | None]
    deceleration_mps2: float
    reaction_time_s: float
    notes: list[str] = field(default_factory=list)
    #: the part (its label) of each of ``station_m``'s points, where the curves lie on several unconnected parts
    #: (:func:`speed_profiles_by_part`: one profile per part, its stations along its part); None: one part
    point_part: np.ndarray | None = None

    @classmethod
    def none(cls, reasons: list[str | None], deceleration_mps2: float, reaction_time_s: float, note: str):
        """No profile: empty stations and speeds, nan per-curve figures, a reason per curve."""
        n = len(reasons)
        nan = np.full(n, np.nan)
        no = np.zeros(n, dtype=bool)
        return cls(
            np.empty(0), np.empty(0), nan, nan.copy(), nan.copy(), nan.copy(), no, no.copy(), nan.copy(), nan.copy(),
            reasons, deceleration_mps2, reaction_time_s, [note],
        )  # fmt: skip


def check_stations(start_m: np.ndarray, length_m: np.ndarray, first_index: int = 0) -> list[str | None]:
    """A reason per curve whose stations cannot carry a profile (None where fine): no station or length, a start
    before the previous curve's start (out of order) or before its end (overlap). ``first_index``: the first curve's
    index in the reasons' wording (``curves[i]``)."""
    n = len(start_m)
    reasons: list[str | None] = [None] * n
    bad_station = ~np.isfinite(start_m) | ~np.isfinite(length_m) | (length_m <= 0)
    for i in np.flatnonzero(bad_station):
        reasons[i] = "no start station or no positive length: the curve cannot be placed in the profile"
    if n > 1:
        end = start_m + length_m
        order = np.flatnonzero(start_m[1:] < start_m[:-1]) + 1
        overlap = np.flatnonzero((start_m[1:] < end[:-1] - 1e-9) & ~(start_m[1:] < start_m[:-1])) + 1
        o = first_index
        for i in order:
            if reasons[i] is None:
                reasons[i] = (
                    f"out of order: starts at {start_m[i]:g} m, before curves[{o + i - 1}] ({start_m[i - 1]:g} m)"
                )
        for i in overlap:
            if reasons[i] is None:
                reasons[i] = (
                    f"overlaps curves[{o + i - 1}]: starts at {start_m[i]:g} m, before its end at {end[i - 1]:g} m"
                )
    return reasons


def _cummin_forward(caps2, rate, gaps, out=None):
    """u_0 = caps2_0, u_i = min(caps2_i, u_{i-1} + 2 rate_{i-1} gaps_{i-1}): u_i = K_i + cummin(caps2 - K)_i, K the
    cumulative sum of the increments 2 rate gaps (K_0 = 0; ``rate`` an array or one number). In chunks of
    :data:`_CHUNK`, each chunk's sums and minima carried on from the chunk before's last (the same sums and minima in
    the same order as over the whole array: the carried sum is added to the chunk's first increment, the carried
    minimum taken with its first term). ``out``: an array of u's length whose entries become min(out, u) (the
    backward pass kept only as its minimum with the forward one: no array of its own); None: u in a new array."""
    n = len(caps2)
    new = out is None
    if new:
        out = np.empty(n)
    k_last = m_last = None
    for lo in range(0, n, _CHUNK):
        hi = min(lo + _CHUNK, n)
        g = slice(max(lo - 1, 0), hi - 1)  # the increments into the chunk's nodes
        k = np.empty(hi - lo)
        increments = k[1:] if lo == 0 else k
        if np.ndim(rate) == 0:
            np.multiply(2.0 * rate, gaps[g], out=increments)
        else:
            np.multiply(np.multiply(rate[g], 2.0, out=increments), gaps[g], out=increments)
        if lo == 0:
            k[0] = 0.0
        else:
            k[0] += k_last
        np.cumsum(k, out=k)
        m = np.subtract(caps2[lo:hi], k)
        if lo > 0:
            m[0] = np.minimum(m_last, m[0])
        np.minimum.accumulate(m, out=m)
        k_last, m_last = k[-1], m[-1]
        if new:
            np.add(k, m, out=out[lo:hi])
        else:
            np.minimum(out[lo:hi], np.add(k, m, out=m), out=out[lo:hi])
    return out


def speed_profile(
    start_station_m,
    length_m,
    desired_speed_kmh,
    safe_speed_kmh=None,
    advisory_speed_kmh=None,
    grade_percent=None,
    *,
    alignment_start_m: float | None = None,
    alignment_end_m: float | None = None,
    deceleration_mps2: float = DECELERATION_MPS2,
    reaction_time_s: float = REACTION_TIME_S,
    acceleration: dict | None = None,
    first_index: int = 0,
    all_figures: bool = True,
) -> SpeedProfile:
    """The truck's speed profile along curves given by their start stations and lengths.

    Parameters
    ----------
    start_station_m : curve start stations, in travel order [m]
    length_m : curve lengths [m]
    desired_speed_kmh : the speed on tangents (posted, or given): one value or one per curve (the tangent before
        each curve) [km/h]
    safe_speed_kmh : each curve's safe speed (Eq. 9.1 against side friction), nan = none [km/h]
    advisory_speed_kmh : each curve's advisory speed, nan = none [km/h]
    grade_percent : each curve's grade (also the tangent after it), + uphill [%]
    alignment_start_m : where the road starts; None = the first curve is approached from far away at the desired
        speed [m]
    alignment_end_m : where the road ends (a last tangent); None = the last curve's end [m]
    deceleration_mps2 : braking rate, at most :data:`MAX_TRUCK_DECELERATION_MPS2` [m/s^2]
    reaction_time_s : reaction time before braking [s]
    acceleration : overrides of :data:`ACCELERATION_DEFAULTS`
    first_index : the first curve's index where the curves are part of a longer list (the reasons' ``curves[i]``)
    all_figures : False: of the per-curve figures only the approach speed and the required deceleration (the
        entry speed, the two approach checks, the advance-sign distance and the speed drop are None: an answer that
        shows none of them)

    Returns
    -------
    SpeedProfile
    """
    check_deceleration(deceleration_mps2)
    if not (math.isfinite(reaction_time_s) and 0 <= reaction_time_s <= 10):
        raise InvalidRoad("reaction time must lie in [0, 10] s", field="reaction_time_s", value=reaction_time_s)
    s0 = np.atleast_1d(np.asarray(start_station_m, dtype=float))
    n = len(s0)
    shape = (n,)

    def column(x, fill):  # (read-only views, not copies: nothing below writes into them)
        return np.full(shape, fill) if x is None else np.broadcast_to(np.asarray(x, dtype=float), shape)

    length = column(length_m, np.nan)
    desired = column(desired_speed_kmh, np.nan)
    # (two reductions, no whole-road temporaries: a nan makes the minimum nan, which fails the test like inf)
    if n and not (desired.min() > 0 and desired.max() < math.inf):
        i = int(np.flatnonzero(~np.isfinite(desired) | (desired <= 0))[0])
        raise InvalidRoad(
            "the desired speed must be a positive speed", field=f"curves[{first_index + i}].desired_speed_kmh"
        )
    safe = column(safe_speed_kmh, np.nan)
    advisory = column(advisory_speed_kmh, np.nan)
    grade = column(grade_percent, 0.0)
    if not np.isfinite(grade).all():
        grade = np.where(np.isfinite(grade), grade, 0.0)
    cap = np.fmin(desired, safe)  # fmin: nan (no safe/advisory speed) does not cap
    np.fmin(cap, advisory, out=cap)

    reasons = check_stations(s0, length, first_index) if n else []
    if reasons.count(None) < n:  # (not any(): a Python pass over 100,000 Nones)
        first = first_index + next(i for i, r in enumerate(reasons) if r)
        reasons = [r or f"no profile: curves[{first}] cannot be placed (see its reason)" for r in reasons]
        note = "no profile: the curves' stations overlap, run backwards or are missing"
        return SpeedProfile.none(reasons, deceleration_mps2, reaction_time_s, note)
    if n == 0:
        return SpeedProfile.none([], deceleration_mps2, reaction_time_s, "no curves")

    end = s0 + length
    d = deceleration_mps2
    acc_params = acceleration or {}
    # tangent i lies before curve i; the first one is unbounded unless the road's start is given
    tangent_before = np.empty(shape)
    tangent_before[0] = np.inf if alignment_start_m is None else max(s0[0] - alignment_start_m, 0.0)
    tangent_before[1:] = s0[1:] - end[:-1]
    # the top speed on an element: the desired speed, or a fraction of the crawl speed on its grade (the tangent
    # after curve i keeps curve i's grade); the element's acceleration is the model's at that top speed, the lowest
    # over the speeds below it, so every step stays within the truck's power
    # (each whole-road array below is written in place where it can be: at 100,000 curves every new one is fresh
    # pages, which cost more to touch than the arithmetic on them)
    tangent_cap = np.append(desired[1:], desired[-1])  # the tangent after curve i is the one before curve i + 1
    # the crawl speed only where it can bind: where the truck has no acceleration left at the higher of the curve's
    # and the next tangent's desired speed over CRAWL_FRACTION; there both caps are lowered to its share of it
    # (indices, not a boolean mask: a masked gather over a random mask costs ten times an arithmetic pass)
    at_top = np.maximum(desired, tangent_cap)
    at_top /= CRAWL_FRACTION
    binds = np.flatnonzero(acceleration_mps2(at_top, grade, **acc_params, out=at_top) <= 0)
    del at_top
    top_first = top_last = math.inf  # the top speed of the first and the last curve
    if len(binds):
        top = CRAWL_FRACTION * crawl_speed_kmh(grade[binds], **acc_params)
        cap[binds] = np.minimum(cap[binds], top)
        tangent_cap[binds] = np.minimum(tangent_cap[binds], top)
        if binds[0] == 0:
            top_first = top[0]
        if binds[-1] == n - 1:
            top_last = top[-1]
    # the elements' accelerations (curve 0, tangent 0, curve 1, ...), the curves' and the tangents' written in place
    acc_all = np.empty(2 * n)
    acceleration_mps2(cap, grade, **acc_params, out=acc_all[0::2])
    a_tangent = acceleration_mps2(tangent_cap, grade, **acc_params, out=acc_all[1::2])
    acc = acc_all[:-1]

    # nodes: start_0, end_0, start_1, end_1, ...; v^2 in (m/s)^2; a node is under both elements' caps
    cap2 = np.empty(2 * n)  # written in place, node by node (start, end): fewer whole-road temporaries
    cap2[0], cap2[-1] = cap[0], cap[-1]
    np.minimum(cap[1:], tangent_cap[:-1], out=cap2[2::2])
    np.minimum(cap[:-1], tangent_cap[:-1], out=cap2[1:-1:2])
    np.square(np.divide(cap2, 3.6, out=cap2), out=cap2)
    lead_cap = min(desired[0], top_first)
    node_s = np.column_stack((s0, end)).ravel()
    gaps = np.diff(node_s)  # curve, tangent, curve, tangent, ...
    v2 = _cummin_forward(cap2, acc, gaps)  # the forward pass, then its minimum with the backward one
    _cummin_forward(cap2[::-1], d, gaps[::-1], out=v2[::-1])

    # the per-curve figures, curve by curve in chunks of _CHUNK (each curve's own arithmetic, the chunk's temporaries
    # kept small); the approach: from the previous curve's exit accelerating along the tangent, capped by the
    # desired speed
    t = reaction_time_s
    approach_kmh, required = np.empty(shape), np.empty(shape)
    entry_kmh = sign_m = drop_kmh = slows_adv = slows_safe = None
    if all_figures:
        entry_kmh, sign_m, drop_kmh = np.empty(shape), np.empty(shape), np.empty(shape)
        slows_adv, slows_safe = np.empty(shape, dtype=bool), np.empty(shape, dtype=bool)
    for lo in range(0, n, _CHUNK):
        hi = min(lo + _CHUNK, n)
        k = slice(lo, hi)
        approach2 = np.empty(hi - lo)
        j = max(lo, 1)  # curves with a curve before
        approach2[j - lo :] = np.minimum(
            (tangent_cap[j - 1 : hi - 1] / 3.6) ** 2,
            v2[2 * j - 1 : 2 * hi - 1 : 2] + 2.0 * a_tangent[j - 1 : hi - 1] * tangent_before[j:hi],
        )
        if lo == 0:
            approach2[0] = (lead_cap / 3.6) ** 2
        _curve_figures(
            approach2, cap[k], tangent_before[k], advisory[k], safe[k], v2[2 * lo : 2 * hi : 2], d, t,
            (approach_kmh[k], required[k])
            + ((entry_kmh[k], slows_adv[k], slows_safe[k], sign_m[k], drop_kmh[k]) if all_figures else ()),
        )  # fmt: skip

    # the profile's stations: per element the acceleration line, the cap, the braking line
    element_caps = gaps  # curve 0, tangent 0, curve 1, ... (in the gaps' array: the passes are done with it)
    element_caps[0::2] = cap
    element_caps[1::2] = tangent_cap[:-1]
    stations, speeds = _profile_points(node_s, v2, acc, d, element_caps)
    if alignment_start_m is not None and alignment_start_m < s0[0]:
        lead_len = s0[0] - alignment_start_m
        lead_start2 = min(
            (lead_cap / 3.6) ** 2, v2[0] + 2.0 * d * lead_len
        )  # braked for the first curve within the lead
        lead = _profile_points(
            np.array([alignment_start_m, s0[0]]), np.array([lead_start2, v2[0]]),
            acceleration_mps2(np.array([lead_cap]), grade[:1], **acc_params), d, np.array([lead_cap]),
        )  # fmt: skip
        stations = np.concatenate((lead[0][:-1], stations))
        speeds = np.concatenate((lead[1][:-1], speeds))
    if alignment_end_m is not None and alignment_end_m > end[-1]:
        tail_len = alignment_end_m - end[-1]
        tail_cap = min(desired[-1], top_last)
        tail_a = acceleration_mps2(np.array([tail_cap]), grade[-1:], **acc_params)
        tail_end2 = min((tail_cap / 3.6) ** 2, v2[-1] + 2.0 * float(tail_a[0]) * tail_len)
        tail = _profile_points(
            np.array([end[-1], alignment_end_m]), np.array([v2[-1], tail_end2]),
            tail_a, d, np.array([tail_cap]),
        )  # fmt: skip
        stations = np.concatenate((stations, tail[0][1:]))
        speeds = np.concatenate((speeds, tail[1][1:]))

    return SpeedProfile(
        station_m=stations,
        speed_kmh=speeds,
        approach_speed_kmh=approach_kmh,
        entry_speed_kmh=entry_kmh,
        curve_speed_kmh=cap,
        required_deceleration_mps2=required,
        slows_to_advisory=slows_adv,
        slows_to_safe=slows_safe,
        advance_sign_distance_m=sign_m,
        speed_drop_kmh=drop_kmh,
        reasons=[None] * n,
        deceleration_mps2=d,
        reaction_time_s=t,
    )


def _curve_figures(approach2, cap, tangent_before, advisory, safe, entry2, d, t, out):
    """Per curve (arrays of a chunk of curves): from the approach speed^2 [(m/s)^2], the curve's speed [km/h], the
    tangent before it [m], its advisory and safe speeds [km/h] and v^2 at its start, the approach and entry speeds,
    the required deceleration, whether the tangent lets the truck slow to the advisory and to the safe speed, the
    advance-sign distance and the speed drop, written into ``out`` (the approach, the required deceleration and then,
    where ``out`` has them, the entry speed, the two checks, the sign distance and the speed drop)."""
    approach_kmh, required = out[:2]
    v1 = np.sqrt(approach2)
    target = cap / 3.6

    def too_close(v2_target):
        need = (approach2 - v2_target**2) / (2.0 * d) + v1 * t
        with np.errstate(invalid="ignore"):
            return (v1 > v2_target) & (tangent_before < need)

    room = tangent_before - v1 * t
    with np.errstate(divide="ignore", invalid="ignore"):
        required[...] = np.where(
            v1 <= target, 0.0, np.where(room > 0, (approach2 - target**2) / (2.0 * np.where(room > 0, room, 1)), np.inf)
        )
    # the first curve approached from an unknown distance (no road start given): the rate it needs is unknown
    required[~np.isfinite(tangent_before) & (v1 > target)] = np.nan
    approach_kmh[...] = v1 * 3.6
    if len(out) == 2:
        return
    entry_kmh, slows_adv, slows_safe, sign_m, drop_kmh = out[2:]
    adv = advisory / 3.6
    safe_v = safe / 3.6
    slows_adv[...] = ~np.where(np.isfinite(adv), too_close(np.where(np.isfinite(adv), adv, 0.0)), False)
    slows_safe[...] = ~np.where(np.isfinite(safe_v), too_close(np.where(np.isfinite(safe_v), safe_v, 0.0)), False)
    # advance sign: reaction distance plus braking from the approach to the advisory speed (Table 2C-3's basis);
    # without an advisory below the approach, the reaction distance alone
    drop_to = np.where(np.isfinite(adv), np.minimum(adv, v1), v1)
    sign_m[...] = v1 * t + (approach2 - drop_to**2) / (2.0 * DECELERATION_MPS2)
    entry_kmh[...] = np.sqrt(entry2) * 3.6
    drop_kmh[...] = np.maximum(v1 * 3.6 - cap, 0.0)


def _profile_points(node_s, v2, acc, d, caps_kmh):
    """Stations and speeds [km/h] of the profile over the elements between nodes: for each element the point where
    acceleration from its start reaches the cap, the point where braking to its end leaves it, or where the two
    lines meet below the cap. v^2 is linear in station between consecutive points. (Computed in chunks of
    :data:`_CHUNK` elements, the same arithmetic per element.)"""
    m = len(node_s) - 1
    # the kept points written straight into arrays of the most there can be (three an element, the last node thrice):
    # no chunk's pieces joined at the end, and the pages past the last point written are never touched
    out_s, out_v = np.empty(3 * m + 3), np.empty(3 * m + 3)
    end = 0
    prev = None  # the chunk before's last candidate point (station, v^2): a point equal to it is dropped
    for lo in range(0, m, _CHUNK):
        hi = min(lo + _CHUNK, m)
        # (acc: positive by construction, every cap below the crawl speed; the floor guards the division)
        c2, a = (caps_kmh[lo:hi] / 3.6) ** 2, np.maximum(acc[lo:hi], 1e-12)
        pts_s, pts_v = _element_points(node_s[lo : hi + 1], v2[lo : hi + 1], a, d, c2, last=hi == m)
        keep = np.empty(len(pts_s), dtype=bool)
        keep[0] = prev is None or (pts_s[0] - prev[0] > 1e-9) | (np.abs(pts_v[0] - prev[1]) > 1e-9)
        keep[1:] = (np.diff(pts_s) > 1e-9) | (np.abs(np.diff(pts_v)) > 1e-9)
        prev = (pts_s[-1], pts_v[-1])
        keep = np.flatnonzero(keep)  # indices, not a mask: gathers by a random mask are slow
        k = slice(end, end + len(keep))
        end = k.stop
        np.take(pts_s, keep, out=out_s[k], mode="clip")  # (indices in range: "clip" writes without a buffer)
        v = np.take(pts_v, keep, out=out_v[k], mode="clip")
        np.multiply(np.sqrt(np.maximum(v, 0.0, out=v), out=v), 3.6, out=v)
    return out_s[:end], out_v[:end]


def _element_points(node_s, v2, acc, d, c2, last):
    """The candidate points of the elements between ``node_s`` (three per element: its start, the end of the
    acceleration line, the start of the braking line; ``last``: and the last node, thrice), as stations and v^2."""
    s_p, s_q = node_s[:-1], node_s[1:]
    v2p, v2q = v2[:-1], v2[1:]
    c2 = np.maximum(c2, np.maximum(v2p, v2q))  # a node at its cap is never above the element's cap
    s1 = s_p + (c2 - v2p) / (2.0 * acc)
    s2 = s_q - (c2 - v2q) / (2.0 * d)
    meet = np.flatnonzero(s1 > s2)
    m = len(s_p)
    rows = m + 1 if last else m
    pts_s = np.empty((rows, 3))
    pts_v = np.empty((rows, 3))
    pts_s[:m, 0], pts_v[:m, 0] = s_p, v2p
    # the middle points in the chunk's own contiguous arrays (s1, s2, c2), the meeting points scattered into them,
    # then each copied once into its column: scatters into a column of the (rows, 3) arrays by a mixed index cost
    # more than a contiguous scatter
    np.minimum(s1, s_q, out=s1)
    np.maximum(s2, s_p, out=s2)
    if len(meet):  # where the lines meet below the cap: v2p + 2 a (s - s_p) = v2q + 2 d (s_q - s)
        a, sp, sq, vp, vq = acc[meet], s_p[meet], s_q[meet], v2p[meet], v2q[meet]
        s_star = np.clip((vq - vp + 2.0 * d * sq + 2.0 * a * sp) / (2.0 * (a + d)), sp, sq)
        v_star2 = np.minimum(vp + 2.0 * a * (s_star - sp), vq + 2.0 * d * (sq - s_star))
        s1[meet] = s_star
        s2[meet] = s_star
        c2[meet] = v_star2
    pts_s[:m, 1], pts_s[:m, 2] = s1, s2
    pts_v[:m, 1] = pts_v[:m, 2] = c2
    if last:
        pts_s[m], pts_v[m] = s_q[-1], v2q[-1]  # the last node (thrice: the duplicates are dropped)
    return pts_s.ravel(), pts_v.ravel()


def speed_profiles_by_part(part, start_station_m, length_m, desired_speed_kmh, safe_speed_kmh=None,
                           advisory_speed_kmh=None, grade_percent=None, **options) -> SpeedProfile:  # fmt: skip
    """One :func:`speed_profile` per part of a road made of unconnected parts (a route's tracks or segments): the
    curves of each run of equal ``part`` (any labels; their stations along their own part, each part's restarting)
    make one profile, which does not run across the gap to the next part (the truck's speed there is unknown: each
    part's first curve is approached as a road's first curve is). The per-curve figures and reasons are each part's,
    in the curves' order (a part whose stations cannot carry a profile has none, the others keep theirs); the
    profiles' points follow each other part by part, ``point_part`` giving each point's part label, and each note
    names the part it is about. ``options``: :func:`speed_profile`'s keywords (no road start or end: a road of
    several parts has none). One part: :func:`speed_profile` itself."""
    part = np.atleast_1d(np.asarray(part))
    s0 = np.atleast_1d(np.asarray(start_station_m, dtype=float))
    n = len(s0)
    starts = np.flatnonzero(np.r_[True, part[1:] != part[:-1]]) if n else np.zeros(0, dtype=int)
    if len(starts) <= 1:
        return speed_profile(start_station_m, length_m, desired_speed_kmh, safe_speed_kmh, advisory_speed_kmh,
                             grade_percent, **options)  # fmt: skip
    if options.get("alignment_start_m") is not None or options.get("alignment_end_m") is not None:
        raise ValueError("a road of several parts has no one start and end: give none")

    def column(x, fill):
        return np.full(n, fill) if x is None else np.array(np.broadcast_to(np.asarray(x, dtype=float), (n,)))

    cols = [column(length_m, np.nan), column(desired_speed_kmh, np.nan), column(safe_speed_kmh, np.nan),
            column(advisory_speed_kmh, np.nan), column(grade_percent, 0.0)]  # fmt: skip
    pieces = []
    for a, b in zip(starts.tolist(), [*starts[1:].tolist(), n], strict=True):
        p = speed_profile(s0[a:b], *(c[a:b] for c in cols), first_index=a, **options)
        pieces.append((part[a], p))
    ps = [p for _, p in pieces]

    def joined(name):
        arrays = [getattr(p, name) for p in ps]
        return None if any(a is None for a in arrays) else np.concatenate(arrays)

    notes = [f"part {k}: {note}" for k, p in pieces for note in p.notes]
    return SpeedProfile(
        station_m=joined("station_m"),
        speed_kmh=joined("speed_kmh"),
        approach_speed_kmh=joined("approach_speed_kmh"),
        entry_speed_kmh=joined("entry_speed_kmh"),
        curve_speed_kmh=joined("curve_speed_kmh"),
        required_deceleration_mps2=joined("required_deceleration_mps2"),
        slows_to_advisory=joined("slows_to_advisory"),
        slows_to_safe=joined("slows_to_safe"),
        advance_sign_distance_m=joined("advance_sign_distance_m"),
        speed_drop_kmh=joined("speed_drop_kmh"),
        reasons=[r for p in ps for r in p.reasons],
        deceleration_mps2=ps[0].deceleration_mps2,
        reaction_time_s=ps[0].reaction_time_s,
        notes=notes,
        point_part=np.concatenate([np.full(len(p.station_m), k) for k, p in pieces]),
    )

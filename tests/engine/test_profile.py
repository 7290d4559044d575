"""The truck's speed profile (engine.road.profile) against its invariants and the closed form of the approach check.

Expected numbers: the caps (desired, safe, advisory speeds) the profile may not exceed; the stated rates (braking
10 ft/s^2, MUTCD 11e Table 2C-3's basis as transcribed; acceleration within the vehicle-dynamics model at every
speed); the too-close condition L < (v1^2 - v2^2) / (2 d) + v1 t; NCHRP 774's 15 ft/s^2 as the most a truck brakes.
"""

from __future__ import annotations

import numpy as np
import pytest

from engine.errors import InvalidRoad
from engine.road import profile as prof


def _random_alignment(rng, n):
    gaps = rng.uniform(0.0, 800.0, n)
    length = rng.uniform(30.0, 400.0, n)
    start = np.cumsum(gaps + np.concatenate(([0.0], length[:-1])))
    safe = rng.uniform(30.0, 110.0, n)
    advisory = np.where(rng.random(n) < 0.3, np.nan, rng.uniform(25.0, 100.0, n))
    grade = rng.uniform(-6.0, 6.0, n)
    return start, length, safe, advisory, grade


def _speed_at(p, s):
    """The profile's speed at stations s: v^2 is linear between its points."""
    v2 = np.interp(s, p.station_m, p.speed_kmh**2)
    return np.sqrt(v2)


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_never_above_desired_safe_or_advisory_and_steps_within_rates(seed):
    rng = np.random.default_rng(seed)
    start, length, safe, advisory, grade = _random_alignment(rng, 200)
    desired = rng.choice([50.0, 70.0, 90.0, 110.0], 200)  # the tangent before each curve
    p = prof.speed_profile(start, length, desired, safe, advisory, grade, alignment_start_m=start[0] - 500.0,
                           alignment_end_m=start[-1] + length[-1] + 500.0)  # fmt: skip
    assert p.reasons == [None] * 200
    assert np.all(np.isfinite(p.speed_kmh)) and np.all(np.isfinite(p.approach_speed_kmh))
    assert np.all(np.diff(p.station_m) >= 0)
    # on each tangent (the one before curve i) at most its desired speed
    for i in range(1, 200):
        s = np.linspace(start[i - 1] + length[i - 1], start[i], 7)
        assert np.all(_speed_at(p, s) <= desired[i] + 1e-6), i
    # inside every curve, at its ends and at 9 points between, no cap is exceeded
    caps = np.fmin(np.fmin(safe, advisory), desired)  # a curve: at most its own tangent's desired speed too
    for i in range(200):
        s = np.linspace(start[i], start[i] + length[i], 11)
        assert np.all(_speed_at(p, s) <= caps[i] + 1e-6), i
    # every step: braking at most d, accelerating at most the model's acceleration at the step's end speed on the
    # grade of the element it lies on (the model's acceleration falls with speed, so the end is the binding one)
    ds = np.diff(p.station_m)
    dv2 = np.diff((p.speed_kmh / 3.6) ** 2)
    step = ds > 1e-9
    rate = dv2[step] / (2.0 * ds[step])
    assert np.all(rate >= -prof.DECELERATION_MPS2 * (1 + 1e-9) - 1e-12)
    mid = 0.5 * (p.station_m[:-1] + p.station_m[1:])[step]
    element = np.clip(np.searchsorted(start, mid, side="right") - 1, 0, 199)
    a_max = prof.acceleration_mps2(p.speed_kmh[1:][step], grade[element])
    up = rate > 1e-12
    assert np.all(rate[up] <= a_max[up] + 1e-9)


def test_regains_desired_speed_on_a_long_level_tangent():
    p = prof.speed_profile([1000.0, 21000.0], [200.0, 200.0], 90.0, [50.0, 50.0], None, [0.0, 0.0])
    between = (p.station_m > 1200.0) & (p.station_m < 21000.0)
    assert p.speed_kmh[between].max() == pytest.approx(90.0, abs=1e-9)
    assert p.approach_speed_kmh[1] == pytest.approx(90.0, abs=1e-9)


@pytest.mark.parametrize("delta", [-0.01, 0.01])
def test_too_close_exactly_at_the_braking_plus_reaction_distance(delta):
    # curve 0 does not slow the truck (safe speed above the desired 80 km/h), so it approaches curve 1 at 80 km/h
    v1, v2, d, t = 80.0 / 3.6, 50.0 / 3.6, prof.DECELERATION_MPS2, prof.REACTION_TIME_S
    need = (v1**2 - v2**2) / (2.0 * d) + v1 * t
    tangent = need + delta
    p = prof.speed_profile([0.0, 100.0 + tangent], [100.0, 100.0], 80.0, [120.0, 60.0], [np.nan, 50.0], [0.0, 0.0])
    assert p.approach_speed_kmh[1] == pytest.approx(80.0, abs=1e-9)
    assert bool(p.slows_to_advisory[1]) is (delta > 0)
    assert bool(p.slows_to_safe[1]) is True  # 60 km/h needs less room
    # the required deceleration over the room left after reacting, to the curve's speed (50 km/h)
    assert p.required_deceleration_mps2[1] == pytest.approx((v1**2 - v2**2) / (2.0 * (tangent - v1 * t)), rel=1e-12)
    assert p.required_deceleration_mps2[0] == 0.0  # the first curve does not slow the truck
    # a first curve that does, approached from an unknown distance (no road start): no rate can be given
    q = prof.speed_profile([0.0], [100.0], 80.0, [60.0])
    assert np.isnan(q.required_deceleration_mps2[0]) and bool(q.slows_to_safe[0]) is True


def test_overlapping_or_backward_stations_give_reasons_not_a_profile():
    p = prof.speed_profile([0.0, 50.0, 400.0], [100.0, 100.0, 100.0], 90.0)
    assert p.station_m.size == 0 and np.all(np.isnan(p.approach_speed_kmh))
    assert p.reasons[1].startswith("overlaps curves[0]")
    assert p.reasons[0].startswith("no profile") and p.reasons[2].startswith("no profile")
    q = prof.speed_profile([500.0, 100.0], [100.0, 100.0], 90.0)
    assert q.reasons[1].startswith("out of order")
    r = prof.speed_profile([0.0, np.nan], [100.0, 100.0], 90.0)
    assert r.reasons[1].startswith("no start station")


def test_deceleration_beyond_a_loaded_truck_is_refused():
    prof.check_deceleration(15.0 * 0.3048)
    with pytest.raises(InvalidRoad) as e:
        prof.speed_profile([0.0], [100.0], 90.0, deceleration_mps2=5.0)
    assert e.value.field == "deceleration_mps2"
    with pytest.raises(InvalidRoad):
        prof.check_deceleration(0.0)


@pytest.mark.parametrize("bad", [np.nan, 0.0, -50.0, np.inf, -np.inf])
def test_a_desired_speed_that_is_not_a_positive_speed_is_refused_naming_its_curve(bad):
    start, length = [0.0, 200.0, 400.0, 600.0], [100.0, 100.0, 100.0, 100.0]
    desired = np.array([90.0, 80.0, bad, bad])
    with pytest.raises(InvalidRoad) as e:
        prof.speed_profile(start, length, desired, first_index=10)
    assert e.value.field == "curves[12].desired_speed_kmh"  # the first bad one, as the request numbers it
    # any finite positive speed passes, however large or small
    assert len(prof.speed_profile(start, length, [1e6, 1e-3, 90.0, 90.0]).station_m)


def test_crawl_speed_is_where_the_model_stops_accelerating():
    g = np.array([0.0, 3.0, 6.0])
    v = prof.crawl_speed_kmh(g)
    assert np.allclose(prof.acceleration_mps2(v, g), 0.0, atol=1e-9)
    assert np.all(np.diff(v) < 0)  # steeper, slower


def test_advance_sign_distance_in_metric_and_us_forms():
    # the US form of the same distance (AASHTO's stopping-sight-distance form): d [ft] = 1.47 V t + 1.075 (V1^2 -
    # V2^2) / a, V in mph, a in ft/s^2; its constants are rounded (1.4667, 1.0756), so within 0.3 %
    p = prof.speed_profile([0.0], [200.0], 100.0, [120.0], [60.0], [0.0])
    v1_mph, v2_mph = 100.0 / 1.609344, 60.0 / 1.609344
    us_ft = 1.47 * v1_mph * 2.5 + 1.075 * (v1_mph**2 - v2_mph**2) / 10.0
    assert p.advance_sign_distance_m[0] == pytest.approx(us_ft * 0.3048, rel=0.003)


def test_a_road_of_parts_has_each_parts_own_profile_and_none_across_the_gap():
    """Parts (a route's unconnected tracks, stations restarting on each): the profile of each part is the one the
    part alone has, point for point and curve for curve (the second formulation: speed_profile on the part); a part
    whose stations cannot carry a profile has its reasons, worded with the curves' indices in the whole list, and
    leaves the other parts' profiles as they are."""
    rng = np.random.default_rng(3)
    a, b = _random_alignment(rng, 7), _random_alignment(rng, 5)
    bad = _random_alignment(rng, 4)
    bad[0][2] = bad[0][1] - 10.0  # runs backwards: this part has no profile
    parts = [a, bad, b]
    label = np.repeat(["A", "bad", "B"], [7, 4, 5])
    whole = [np.concatenate([p[k] for p in parts]) for k in range(5)]
    start, length, safe, advisory, grade = whole
    got = prof.speed_profiles_by_part(label, start, length, 80.0, safe, advisory, grade)
    at = 0
    for name, p in zip(("A", "bad", "B"), parts, strict=True):
        alone = prof.speed_profile(p[0], p[1], 80.0, p[2], p[3], p[4])
        sl = slice(at, at + len(p[0]))
        mine = got.point_part == name
        np.testing.assert_array_equal(got.station_m[mine], alone.station_m)
        np.testing.assert_array_equal(got.speed_kmh[mine], alone.speed_kmh)
        np.testing.assert_array_equal(got.approach_speed_kmh[sl], alone.approach_speed_kmh)
        np.testing.assert_array_equal(got.required_deceleration_mps2[sl], alone.required_deceleration_mps2)
        if name == "bad":
            assert all(r is not None for r in got.reasons[sl]) and len(alone.station_m) == 0
            assert "before curves[8]" in got.reasons[at + 2]  # its third curve, the whole list's 10th
        else:
            assert got.reasons[sl] == [None] * len(p[0])
            # each part's first curve: approached from an unknown distance (as a road's first), not from the gap
            assert np.isnan(got.required_deceleration_mps2[at]) or got.required_deceleration_mps2[at] == 0.0
        at += len(p[0])
    assert list(dict.fromkeys(got.point_part.tolist())) == ["A", "B"]  # the points part by part
    assert got.notes and all(n.startswith("part bad: ") for n in got.notes)
    # one part: speed_profile itself
    one = prof.speed_profiles_by_part(np.zeros(7), a[0], a[1], 80.0, a[2], a[3], a[4])
    assert one.point_part is None and np.array_equal(one.speed_kmh, prof.speed_profile(*a[:2], 80.0, *a[2:]).speed_kmh)


def test_no_shared_sign_across_parts():
    from engine.road.advisory import sign_groups

    # tangents of 50 m (< 600 ft): one sign; the third curve's station is along another part (the numbers alone
    # would put it 50 m after the second's end)
    start, length = [0.0, 150.0, 300.0], [100.0, 100.0, 100.0]
    assert list(sign_groups(start, length)) == [0, 0, 0]
    assert list(sign_groups(start, length, ["p", "p", "q"])) == [0, 0, 2]


# ----------------------------------------------------------------- the fast profile against a plain one, curve by curve


def _reference_profile(start, length, desired, safe, advisory, grade, d, t, alignment_start=None):
    """The profile the module docstring describes, written as plain loops over the curves (the second formulation):
    the forward recurrence u_j = min(cap_j^2, u_{j-1} + 2 a gap) and the backward one w_j = min(cap_j^2, w_{j+1} +
    2 d gap), v^2 = min(u, w) at the nodes; between two nodes v^2(s) = min(c^2, v_p^2 + 2 a (s - s_p), v_q^2 + 2 d
    (s_q - s)). Returns v^2(s) as a function, the per-curve approach and entry speeds and the required deceleration.
    The truck's acceleration and crawl speed are the model's (prof.acceleration_mps2, prof.crawl_speed_kmh)."""
    n = len(start)
    mps = 1 / 3.6

    def accel(v_kmh, g):
        return float(prof.acceleration_mps2(np.array([v_kmh]), np.array([g]))[0])

    top, cap, tcap = [], [], []
    for i in range(n):
        after = desired[i + 1] if i + 1 < n else desired[i]
        g = grade[i]
        crawl = float(prof.crawl_speed_kmh(np.array([g]))[0]) * prof.CRAWL_FRACTION
        top.append(crawl if accel(max(desired[i], after) / prof.CRAWL_FRACTION, g) <= 0 else np.inf)
        c = desired[i]
        for x in (safe[i], advisory[i]):
            if np.isfinite(x):
                c = min(c, x)
        cap.append(min(c, top[i]))
        tcap.append(min(after, top[i]))
    a_curve = [accel(cap[i], grade[i]) for i in range(n)]
    a_tan = [accel(tcap[i], grade[i]) for i in range(n)]
    s, c2, a = [], [], []  # nodes, their caps^2; the element after each node: its acceleration and cap^2
    el_c2 = []
    for i in range(n):
        s += [start[i], start[i] + length[i]]
        c2 += [(min(cap[i], tcap[i - 1]) if i else cap[i]) ** 2, (min(cap[i], tcap[i]) if i < n - 1 else cap[i]) ** 2]
        a += [a_curve[i], a_tan[i]]
        el_c2 += [cap[i] ** 2, tcap[i] ** 2]
    c2 = [x * mps**2 for x in c2]
    el_c2 = [x * mps**2 for x in el_c2]
    m = len(s)
    u, w = c2[:], c2[:]
    for j in range(1, m):
        u[j] = min(c2[j], u[j - 1] + 2 * a[j - 1] * (s[j] - s[j - 1]))
    for j in range(m - 2, -1, -1):
        w[j] = min(c2[j], w[j + 1] + 2 * d * (s[j + 1] - s[j]))
    v2 = [min(x, y) for x, y in zip(u, w, strict=True)]

    def v2_at(x):
        j = min(max(int(np.searchsorted(s, x, side="right")) - 1, 0), m - 2)
        cc = max(el_c2[j], v2[j], v2[j + 1])
        return min(cc, v2[j] + 2 * max(a[j], 1e-12) * (x - s[j]), v2[j + 1] + 2 * d * (s[j + 1] - x))

    approach, entry, required = [], [], []
    for i in range(n):
        if i == 0:
            v1sq = (min(desired[0], top[0]) * mps) ** 2
            room = np.inf if alignment_start is None else max(start[0] - alignment_start, 0.0)
        else:
            room = start[i] - start[i - 1] - length[i - 1]
            v1sq = min((tcap[i - 1] * mps) ** 2, v2[2 * i - 1] + 2 * a_tan[i - 1] * room)
        v1, target = np.sqrt(v1sq), cap[i] * mps
        approach.append(v1 / mps)
        entry.append(np.sqrt(v2[2 * i]) / mps)
        if v1 <= target:
            required.append(0.0)
        elif not np.isfinite(room):
            required.append(np.nan)
        elif room - v1 * t > 0:
            required.append((v1sq - target**2) / (2 * (room - v1 * t)))
        else:
            required.append(np.inf)
    return v2_at, np.array(approach), np.array(entry), np.array(required)


@pytest.mark.parametrize("seed", range(6))
def test_fast_profile_equals_a_plain_curve_by_curve_one(seed, monkeypatch):
    """The vectorised, chunked profile (cumulative minima over transformed stations, points per element) against the
    plain loops of _reference_profile on random roads: the profile's v^2, linear between its points, equals the
    reference's at every point, midway between points and at random stations; the per-curve approach and entry
    speeds and the required deceleration (inf: no room to brake after reacting; nan: the first curve approached
    from an unknown distance) equal it curve by curve. Tangents of 0-30 m on some roads (no room), of up to 800 m
    on others; grades to 9 % (the crawl speed binds); chunks of 7 elements, so the chunks' carries are crossed."""
    monkeypatch.setattr(prof, "_CHUNK", 7)
    rng = np.random.default_rng(seed)
    n = 60
    short = seed % 2 == 1
    gaps = rng.uniform(0.0, 30.0 if short else 800.0, n) * (rng.random(n) < 0.9)
    length = rng.uniform(5.0, 400.0, n)
    start = np.cumsum(gaps + np.concatenate(([0.0], length[:-1])))
    safe = np.where(rng.random(n) < 0.1, np.nan, rng.uniform(20.0, 120.0, n))
    safe[0] = 40.0  # the first curve slows the truck
    advisory = np.where(rng.random(n) < 0.3, np.nan, rng.uniform(20.0, 110.0, n))
    grade = rng.uniform(-9.0, 9.0, n)
    desired = rng.choice([50.0, 70.0, 90.0, 110.0], n)
    d, t = (prof.DECELERATION_MPS2, prof.REACTION_TIME_S) if seed < 3 else (2.0, 1.5)
    lead = None if seed % 3 == 0 else start[0] - 300.0
    p = prof.speed_profile(start, length, desired, safe, advisory, grade, deceleration_mps2=d, reaction_time_s=t,
                           alignment_start_m=lead)  # fmt: skip
    v2_at, approach, entry, required = _reference_profile(start, length, desired, safe, advisory, grade, d, t, lead)
    on_curves = p.station_m >= start[0]  # (the lead before the first curve: not in the reference)
    s = p.station_m[on_curves]
    probes = np.concatenate((s, 0.5 * (s[1:] + s[:-1]), rng.uniform(s[0], s[-1], 500)))
    got = np.interp(probes, p.station_m, (p.speed_kmh / 3.6) ** 2)
    want = np.array([v2_at(x) for x in probes])
    np.testing.assert_allclose(got, want, rtol=1e-9, atol=1e-6)
    np.testing.assert_allclose(p.approach_speed_kmh, approach, rtol=1e-9)
    np.testing.assert_allclose(p.entry_speed_kmh, entry, rtol=1e-9)
    # inf and nan where the same; not where the approach equals the curve's speed to rounding (a zero tangent after
    # a curve at the same speed: 0 or, by a rounding's worth of speed and no room, inf)
    tie = np.abs(approach - p.curve_speed_kmh) < 1e-7
    assert tie.sum() < n // 4
    np.testing.assert_allclose(p.required_deceleration_mps2[~tie], required[~tie], rtol=1e-9)
    assert np.isinf(required).any() or not short  # the no-room case is exercised
    assert bool(np.isnan(p.required_deceleration_mps2[0])) is (lead is None)  # the first curve slows the truck


def test_chunks_do_not_change_the_profile(monkeypatch):
    """The passes and the points computed in chunks give the same bytes whatever the chunk (carries exact), and a
    road of parts (a route's) the same as each part alone."""
    rng = np.random.default_rng(11)
    start, length, safe, advisory, grade = _random_alignment(rng, 500)
    part = np.repeat([0, 1, 2], [200, 1, 299])
    whole = prof.speed_profiles_by_part(part, start, length, 90.0, safe, advisory, grade)
    for chunk in (1, 2, 3, 64, 999):
        monkeypatch.setattr(prof, "_CHUNK", chunk)
        got = prof.speed_profiles_by_part(part, start, length, 90.0, safe, advisory, grade)
        for name in ("station_m", "speed_kmh", "approach_speed_kmh", "entry_speed_kmh", "required_deceleration_mps2"):
            assert getattr(got, name).tobytes() == getattr(whole, name).tobytes(), (chunk, name)


def test_fewer_figures_leave_the_profile_and_the_rate_as_they_are():
    """``all_figures=False`` (the rows' call) computes only the approach speed and the required deceleration: those,
    the points and the curve speeds are the full call's byte for byte, on one road and on a road of parts, with the
    first curve's rate unknown (no road start) and known (a start given); the other figures are absent, not
    invented."""
    rng = np.random.default_rng(5)
    start, length, safe, advisory, grade = _random_alignment(rng, 300)
    kept = ("station_m", "speed_kmh", "curve_speed_kmh", "approach_speed_kmh", "required_deceleration_mps2")
    dropped = ("entry_speed_kmh", "slows_to_advisory", "slows_to_safe", "advance_sign_distance_m", "speed_drop_kmh")
    part = np.repeat([0, 1], [120, 180])
    for call, options in (
        (prof.speed_profile, {}),
        (prof.speed_profile, {"alignment_start_m": start[0] - 50.0}),
        (lambda *a, **k: prof.speed_profiles_by_part(part, *a, **k), {}),
    ):
        full = call(start, length, 80.0, safe, advisory, grade, **options)
        few = call(start, length, 80.0, safe, advisory, grade, all_figures=False, **options)
        for name in kept:
            assert getattr(few, name).tobytes() == getattr(full, name).tobytes(), name
        for name in dropped:
            assert getattr(full, name) is not None and getattr(few, name) is None, name

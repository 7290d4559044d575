"""Performance-Based Standards: the standards this model can judge, with the limits' sources, as indicative screening.

Rules: NTC, *Performance Based Standards Scheme - The Standards and Vehicle Assessment Rules*, as at 10 November
2008 (made 30 July 2007, approved 3 October 2007, amendments consented to on 7 November 2008; the title page and
contents were read, the body text - the manoeuvres' speeds and amplitudes and the limits by level - could not be
read here). No limit by level is therefore given: every one is ``limit: None``, ``verified: False``, with a source
saying the rules' text could not be read (:data:`NOT_READ`). A limit read in a primary text goes in
:data:`VERIFIED_LIMITS` with that text named; the level a vehicle meets is computed from verified limits only
(:func:`best_level`), so it stays null while none is. The manoeuvres' default speeds and amplitude are unverified
too: the answer's ``conditions`` say so, and the caller sets them to the rules' values. The length check by network
level uses NHVR's road-access levels (recorded in the project's source notes from NHVR's page): Level 1 up to 20 m;
Level 2 up to 26 m (Class A) / 30 m (Class B); Level 3 up to 36.5 / 42 m; Level 4 up to 53.5 / 60 m.

Judged here: SRT (the static combination model's lowest roll-coupled unit), rearward amplification and high-speed
transient offtracking (single lane change), yaw damping (pulse steer), low-speed swept path, tail swing and frontal
swing (the 90 degree turn). Not judged (they need longitudinal, braking, tyre-force or infrastructure models):
:data:`NOT_JUDGED`.

The answer is an indicative screening, not a certification: a linear passive model (no tyre saturation, no lift-off,
no stability control) with estimated parameters where the description has none.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from engine.dynamics.lowspeed import low_speed_turn
from engine.dynamics.manoeuvres import Unstable, body_offsets, lane_change, pulse_steer
from engine.dynamics.model import YawRollModel
from engine.models.combination import solve_combination

RULES_VERSION = (
    "NTC, Performance Based Standards Scheme - The Standards and Vehicle Assessment Rules, as at 10 November 2008 "
    "(made 30 July 2007; amendments consented to 7 November 2008)"
)
SCREENING_NOTE = "indicative screening, not a certification"
NOT_READ = "unverified: the rules' text (the limits by level) could not be read, so no limit is given"
NOT_JUDGED = (
    "startability",
    "gradeability",
    "acceleration capability",
    "tracking ability on a straight path",
    "steer-tyre friction demand",
    "directional stability under braking",
    "pavement vertical loading",
    "pavement horizontal loading",
    "tyre contact pressure distribution",
    "bridge loading",
)
#: the manoeuvres' default conditions: values as commonly cited, NOT read in the rules (module docstring); the
#: caller sets them to the rules' values. 0.4 Hz is confirmed only second-hand (an open PBS implementation citing
#: NTC 2008) and is fixed.
LANE_CHANGE_SPEED_KMH = 88.0
LANE_CHANGE_AMPLITUDE_G = 0.15
LANE_CHANGE_FREQUENCY_HZ = 0.4
PULSE_STEER_SPEED_KMH = 100.0
CONDITIONS_SOURCE = (
    "unverified: the rules' manoeuvre conditions could not be read. The default lane-change speed (88 km/h) and "
    "amplitude (0.15 g) and pulse-steer speed (100 km/h) are values as commonly cited, not read in the rules: set "
    "lane_change_speed_kmh, lane_change_amplitude_g and pulse_steer_speed_kmh to the rules' values. The lane "
    "change's 0.4 Hz is confirmed only second-hand (an open PBS implementation citing NTC 2008)."
)

#: level -> (limit, the text it was read in) of one standard
LevelLimits = dict[int, tuple[float, str]]

#: standard id -> (unit, sense, what the standard applies to)
STANDARDS: dict[str, tuple[str, str, str]] = {
    "srt": ("g", "min", "the lowest roll-coupled unit's SRT"),
    "rearward_amplification": ("-", "max", "the rearmost unit over the steer axle (`ra_definition`)"),
    "high_speed_transient_offtracking": ("m", "max", "the rearmost axle"),
    "yaw_damping": ("-", "min", "the rearmost articulation"),
    "low_speed_swept_path": ("m", "max", "the 90 degree turn"),
    "tail_swing": ("m", "max", "every unit's outside rear corner"),
    "frontal_swing": ("m", "max", "the prime mover's outside front corner"),
}
LEVELS = (1, 2, 3, 4)
#: limits read in a primary text: standard id -> {level: (limit in the standard's unit, the text it was read in)}.
#: Empty: no primary text of the limits could be read (searched twice on 2026-12-07: the rules' copies found show
#: only their title page and contents; NHVR's pages define the standards without limits; what was tried is listed in
#: docs/dynamics.md).
VERIFIED_LIMITS: dict[str, LevelLimits] = {}
#: NHVR network levels by length [m]: level -> (Class A, Class B)
LENGTH_LEVELS = {1: (20.0, 20.0), 2: (26.0, 30.0), 3: (36.5, 42.0), 4: (53.5, 60.0)}
LENGTH_SOURCE = "NHVR, PBS road access: network levels by length (recorded in the project's source notes, 2026-12-07)"
#: New Zealand's minimum SRT for heavy vehicles (not a PBS level limit, listed beside the screening)
NZ_SRT_G = 0.35
NZ_SRT_SOURCE = (
    "NZ Transport Agency, 'Static roll thresholds' (the agency's statement of the legal requirements of Land "
    "Transport Rule: Vehicle Dimensions and Mass 2016, Rule 41001, its 'Stability performance requirements: Static "
    "Roll Threshold'): goods service vehicles with a GVM over 12 tonnes (class NC) and trailers with a GVM over 10 "
    "tonnes (class TD) need an SRT of at least 0.35 g; the same value under the 2002 Rule's section 3.2 in the "
    "agency's SRT calculator pages. Read in the regulator's pages, not in the Rule's own clause: unverified"
)


@dataclass
class Standard:
    id: str
    value: float | None
    unit: str
    limits: list[dict]
    level: int | None
    source: str
    note: str = ""


@dataclass
class Screening:
    standards: list[Standard]
    rules_version: str
    not_judged: list[str]
    length_m: float
    network_level_by_length: dict
    validity: list[str]
    conditions: dict
    screening: bool = True
    note: str = SCREENING_NOTE
    other_limits: list[dict] = field(default_factory=list)


def limit_rows(sid: str, sense: str) -> list[dict]:
    """Per level: the verified limit and its source where one was read (:data:`VERIFIED_LIMITS`), else a null limit
    with :data:`NOT_READ` as its source; never a number that was not read."""
    read = VERIFIED_LIMITS.get(sid, {})
    return [{"level": lv, "limit": read[lv][0], "sense": sense, "source": read[lv][1], "verified": True} if lv in read
            else {"level": lv, "limit": None, "sense": sense, "source": NOT_READ, "verified": False}
            for lv in LEVELS]  # fmt: skip


def best_level(value: float | None, rows: list[dict], *, settles: bool = False) -> int | None:
    """The best (highest) level whose limit the value meets, from verified limits only; None without a verified
    limit, without a value, or where none is met. ``settles``: a response that settles without sway meets any
    minimum damping."""
    verified = [r for r in rows if r["verified"] and r["limit"] is not None]
    if settles:
        return max((r["level"] for r in verified if r["sense"] == "min"), default=None)
    if value is None:
        return None
    ok = [r["level"] for r in verified if (value <= r["limit"] if r["sense"] == "max" else value >= r["limit"])]
    return max(ok, default=None)


def vehicle_length_m(model: YawRollModel) -> float:
    """Overall length: the prime mover's front to the rearmost point of any unit, straight [m] (estimated extents
    where not given)."""
    p = model.parameters
    offs = body_offsets(model)
    rear = max(offs[model.main_body[i]] + p.units[i].rear_extent_m.value for i in range(len(p.units)))
    return p.units[0].front_overhang_m.value + rear


def screen(model: YawRollModel, *, lane_change_speed_kmh: float = LANE_CHANGE_SPEED_KMH,
           lane_change_amplitude_g: float = LANE_CHANGE_AMPLITUDE_G,
           pulse_steer_speed_kmh: float = PULSE_STEER_SPEED_KMH, ra_definition: str = "cg") -> Screening:  # fmt: skip
    """Every standard this model judges (module docstring), with limits per level and their sources.

    Parameters
    ----------
    lane_change_speed_kmh, lane_change_amplitude_g, pulse_steer_speed_kmh
        The manoeuvres' conditions [km/h, g, km/h]. The defaults are unverified (values as commonly cited, not read
        in the rules): set them to the rules' values; ``conditions`` names those left at their default.
    ra_definition
        ``cg`` or ``axle`` (:func:`engine.dynamics.manoeuvres.lane_change`).
    """
    c = model.combination
    detail = solve_combination(c)
    srts = [r.srt for r in detail.roll_coupled_units]
    values: dict[str, float | None] = {"srt": min(srts)}
    notes: dict[str, str] = {}
    validity: list[str] = []
    try:
        lc = lane_change(model, lane_change_speed_kmh, frequency_hz=LANE_CHANGE_FREQUENCY_HZ,
                         amplitude_g=lane_change_amplitude_g, ra_definition=ra_definition, srt_g=srts)  # fmt: skip
        values["rearward_amplification"] = lc.rearward_amplification
        values["high_speed_transient_offtracking"] = lc.high_speed_transient_offtracking_m
        validity += lc.validity
    except Unstable as exc:
        values["rearward_amplification"] = values["high_speed_transient_offtracking"] = None
        notes["rearward_amplification"] = notes["high_speed_transient_offtracking"] = f"unstable: {exc}"
    try:
        ps = pulse_steer(model, pulse_steer_speed_kmh)
        values["yaw_damping"] = ps.yaw_damping_ratio
        if ps.yaw_damping_ratio is None and ps.articulation != "none":
            # no two same-sign peaks: the articulation settles without swaying, more than any minimum damping
            notes["yaw_damping"] = "no sway: the rearmost articulation settles without overshoot after the pulse"
        validity += ps.validity
    except Unstable as exc:
        values["yaw_damping"] = None
        notes["yaw_damping"] = f"unstable: {exc}"
    ls = low_speed_turn(model, path_every_m=5.0)
    values["low_speed_swept_path"] = ls.swept_path_width_m
    values["tail_swing"] = ls.tail_swing_m
    values["frontal_swing"] = ls.frontal_swing_m
    standards = []
    for sid, (unit, sense, what) in STANDARDS.items():
        rows = limit_rows(sid, sense)
        level = best_level(values[sid], rows, settles=notes.get(sid, "").startswith("no sway"))
        standards.append(Standard(sid, values[sid], unit, rows, level, f"{RULES_VERSION}: {what}",
                                  notes.get(sid, "")))  # fmt: skip
    length = vehicle_length_m(model)
    by_length = {
        "class_a": min((lv for lv, (a, _) in LENGTH_LEVELS.items() if length <= a), default=None),
        "class_b": min((lv for lv, (_, b) in LENGTH_LEVELS.items() if length <= b), default=None),
        "limits_m": {str(lv): {"class_a": a, "class_b": b} for lv, (a, b) in LENGTH_LEVELS.items()},
        "source": LENGTH_SOURCE,
        "verified": True,
    }
    other = [{
        "scheme": "New Zealand (NZ Transport Agency low-speed method)", "standard": "low_speed_swept_path",
        "limit": 7.0, "unit": "m", "source": "recorded in the project's source notes, not re-read here: unverified",
        "verified": False,
    }, {
        "scheme": "New Zealand, Land Transport Rule: Vehicle Dimensions and Mass 2016 (class NC over 12 t GVM, "
                  "class TD over 10 t GVM)", "standard": "srt", "limit": NZ_SRT_G, "unit": "g", "sense": "min",
        "source": NZ_SRT_SOURCE, "verified": False, "met": bool(values["srt"] >= NZ_SRT_G),
    }]  # fmt: skip
    given = {"lane_change_speed_kmh": (lane_change_speed_kmh, LANE_CHANGE_SPEED_KMH),
             "lane_change_amplitude_g": (lane_change_amplitude_g, LANE_CHANGE_AMPLITUDE_G),
             "pulse_steer_speed_kmh": (pulse_steer_speed_kmh, PULSE_STEER_SPEED_KMH)}  # fmt: skip
    conditions = {
        "lane_change_speed_kmh": lane_change_speed_kmh, "lane_change_frequency_hz": LANE_CHANGE_FREQUENCY_HZ,
        "lane_change_amplitude_g": lane_change_amplitude_g, "pulse_steer_speed_kmh": pulse_steer_speed_kmh,
        "ra_definition": ra_definition, "verified": False,
        "unverified_defaults_used": [name for name, (v, default) in given.items() if v == default],
        "source": CONDITIONS_SOURCE,
    }  # fmt: skip
    return Screening(standards, RULES_VERSION, list(NOT_JUDGED), length, by_length, validity, conditions,
                     other_limits=other)  # fmt: skip

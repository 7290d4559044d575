"""Performance-Based Standards: the standards this model can judge, with the limits' sources, as indicative screening.

Rules: NTC, *Performance Based Standards Scheme - The Standards and Vehicle Assessment Rules*, as at 10 November
2008 (made 30 July 2007, approved 3 October 2007, amendments consented to on 7 November 2008; the title page was
read, the body text - the manoeuvres' speeds and amplitudes and the limits by level - could not be read here).
Every limit below is therefore marked ``verified: False`` with the note "unverified", and the level a vehicle meets
is computed from verified limits only, so it stays null; ``level_unverified`` says which level the unverified
limits would give. The length check by network level uses NHVR's road-access levels (recorded in the project's
source notes from NHVR's page): Level 1 up to 20 m; Level 2 up to 26 m (Class A) / 30 m (Class B); Level 3 up to
36.5 / 42 m; Level 4 up to 53.5 / 60 m.

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
UNVERIFIED = "unverified: the rules' text could not be read; value as commonly cited, not checked against the rules"
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
#: the manoeuvres' conditions (PBS values unverified; 0.4 Hz confirmed only second-hand)
LANE_CHANGE_SPEED_KMH = 88.0
LANE_CHANGE_AMPLITUDE_G = 0.15
LANE_CHANGE_FREQUENCY_HZ = 0.4
PULSE_STEER_SPEED_KMH = 100.0

#: (standard id, unit, sense, {level: limit}, what the limit applies to); every one unverified
_LIMITS: dict[str, tuple[str, str, dict[int, float], str]] = {
    "srt": ("g", "min", {1: 0.35, 2: 0.35, 3: 0.35, 4: 0.35}, "the lowest roll-coupled unit's SRT"),
    "rearward_amplification": ("-", "max", {}, "5.7 x the rearmost roll-coupled unit's SRT (all levels)"),
    "high_speed_transient_offtracking": ("m", "max", {1: 0.6, 2: 0.8, 3: 1.0, 4: 1.2}, "the rearmost axle"),
    "yaw_damping": ("-", "min", {1: 0.15, 2: 0.15, 3: 0.15, 4: 0.15}, "the rearmost articulation"),
    "low_speed_swept_path": ("m", "max", {1: 7.4, 2: 8.7, 3: 10.6, 4: 13.7}, "the 90 degree turn"),
    "tail_swing": ("m", "max", {1: 0.30, 2: 0.35, 3: 0.35, 4: 0.35}, "every unit's outside rear corner"),
    "frontal_swing": ("m", "max", {1: 0.7, 2: 0.7, 3: 0.7, 4: 0.7}, "the prime mover's outside front corner"),
}
#: NHVR network levels by length [m]: level -> (Class A, Class B)
LENGTH_LEVELS = {1: (20.0, 20.0), 2: (26.0, 30.0), 3: (36.5, 42.0), 4: (53.5, 60.0)}
LENGTH_SOURCE = "NHVR, PBS road access: network levels by length (recorded in the project's source notes, 2026-12-07)"


@dataclass
class Standard:
    id: str
    value: float | None
    unit: str
    limits: list[dict]
    level: int | None
    level_unverified: int | None
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


def _levels(value: float | None, sense: str, limits: dict[int, float]) -> int | None:
    if value is None:
        return None
    ok = [lv for lv, lim in limits.items() if (value <= lim if sense == "max" else value >= lim)]
    return max(ok) if ok else None


def vehicle_length_m(model: YawRollModel) -> float:
    """Overall length: the prime mover's front to the rearmost point of any unit, straight [m] (estimated extents
    where not given)."""
    p = model.parameters
    offs = body_offsets(model)
    rear = max(offs[model.main_body[i]] + p.units[i].rear_extent_m.value for i in range(len(p.units)))
    return p.units[0].front_overhang_m.value + rear


def screen(model: YawRollModel, *, lane_change_speed_kmh: float = LANE_CHANGE_SPEED_KMH,
           amplitude_g: float = LANE_CHANGE_AMPLITUDE_G, pulse_speed_kmh: float = PULSE_STEER_SPEED_KMH,
           ra_definition: str = "cg") -> Screening:  # fmt: skip
    """Every standard this model judges (module docstring), with limits per level and their sources."""
    c = model.combination
    detail = solve_combination(c)
    srts = [r.srt for r in detail.roll_coupled_units]
    values: dict[str, float | None] = {"srt": min(srts)}
    notes: dict[str, str] = {}
    validity: list[str] = []
    try:
        lc = lane_change(model, lane_change_speed_kmh, frequency_hz=LANE_CHANGE_FREQUENCY_HZ, amplitude_g=amplitude_g,
                         ra_definition=ra_definition, srt_g=srts)  # fmt: skip
        values["rearward_amplification"] = lc.rearward_amplification
        values["high_speed_transient_offtracking"] = lc.high_speed_transient_offtracking_m
        validity += lc.validity
    except Unstable as exc:
        values["rearward_amplification"] = values["high_speed_transient_offtracking"] = None
        notes["rearward_amplification"] = notes["high_speed_transient_offtracking"] = f"unstable: {exc}"
    try:
        ps = pulse_steer(model, pulse_speed_kmh)
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
    rrcu = srts[-1]  # the rearmost roll-coupled unit
    standards = []
    for sid, (unit, sense, limits, what) in _LIMITS.items():
        if sid == "rearward_amplification":
            limits = {lv: 5.7 * rrcu for lv in (1, 2, 3, 4)}
        rows = [{"level": lv, "limit": lim, "sense": sense, "source": UNVERIFIED, "verified": False}
                for lv, lim in limits.items()]  # fmt: skip
        verified = {r["level"]: r["limit"] for r in rows if r["verified"]}
        if notes.get(sid, "").startswith("no sway"):  # meets any minimum damping
            level, level_unverified = max(verified, default=None), max(limits)
        else:
            level, level_unverified = _levels(values[sid], sense, verified), _levels(values[sid], sense, limits)
        standards.append(Standard(sid, values[sid], unit, rows, level, level_unverified, f"{RULES_VERSION}: {what}",
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
    }]  # fmt: skip
    conditions = {
        "lane_change_speed_kmh": lane_change_speed_kmh, "lane_change_frequency_hz": LANE_CHANGE_FREQUENCY_HZ,
        "lane_change_amplitude_g": amplitude_g, "pulse_steer_speed_kmh": pulse_speed_kmh,
        "ra_definition": ra_definition,
        "source": "PBS manoeuvre conditions unverified (0.4 Hz confirmed only second-hand; speed and amplitude "
                  "as commonly cited)",
    }  # fmt: skip
    return Screening(standards, RULES_VERSION, list(NOT_JUDGED), length, by_length, validity, conditions,
                     other_limits=other)  # fmt: skip

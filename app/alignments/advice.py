"""What each assessed curve carries besides its safe speed: the advisory speed shown on the plaque, the sign treatment,
the W1-13 rule and the truck's speed profile (:func:`engine.road.advisory.advise_alignment`, once per vehicle over the
whole alignment: the profile and the shared signs run from curve to curve), as columns the renderers of
:mod:`app.alignments.rows` write (the synchronous answers, a job's parts and the routes' rows alike).

Non-finite figures are not written as numbers: a required deceleration of inf (no room to brake after the reaction
distance) and every figure of a curve without a profile are null, with the reason in the row's ``profile_reason``.
"""

from __future__ import annotations

from dataclasses import dataclass
from types import SimpleNamespace

import numpy as np

from app.compute.resolved import ResolvedAssessment
from app.formats.alignment_io import CurveTable
from engine.road import (
    BALL_BANK_2009,
    BODY_ROLL_DEG_PER_G,
    DESIGN_METHOD_NOTE,
    SIGN_INCREMENTS,
    TREATMENT_SOURCE,
    TREATMENTS,
    W1_13_RULE,
    AlignmentColumns,
    advise_alignment,
)
from engine.road import ROLLOVER_MARGIN_KMH as RULE_MARGIN_KMH

#: how an assessed curve's advisory speed is found: without a measured car speed (which only the one-curve
#: endpoint takes), every row's speed is the 2009 ball-bank criterion's (engine.road.advisory.advise_curves)
ROW_METHOD_SOURCE = f"{BALL_BANK_2009.source}; a passenger car's body roll of {BODY_ROLL_DEG_PER_G:g} deg/g assumed" + (
    "" if BALL_BANK_2009.verified else ": unverified"
)

#: the reason of a curve the truck cannot brake for: inf in the engine's required deceleration
NO_ROOM = (
    "no room to brake: the tangent before the curve is shorter than the reaction distance at the approach speed "
    "(required deceleration unbounded)"
)
#: the reason of a first curve approached from an unknown distance: nan in the engine's required deceleration
UNKNOWN_APPROACH = (
    "the tangent before the curve has no known length (the road's start is not given): the rate is unknown"
)


@dataclass(frozen=True)
class VehicleAdvice:
    """One vehicle's advice per curve (arrays, one entry per curve; nan: none) and its speed profile."""

    advisory_speed_kmh: np.ndarray
    treatment: np.ndarray  # index into engine.road.advisory.TREATMENTS; -1: no posted speed
    truck_rollover_warning: np.ndarray  # bool
    approach_speed_kmh: np.ndarray
    required_deceleration_mps2: np.ndarray  # finite or nan
    reason: np.ndarray  # index into ``reasons``; -1: none
    reasons: list[str]
    station_m: np.ndarray  # the profile's stations [m] (empty: no profile)
    speed_kmh: np.ndarray  # the profile's speeds [km/h]
    notes: list[str]
    #: each profile point's part where the curves lie on unconnected parts (a route's; None: one road)
    point_part: np.ndarray | None = None

    def sliced(self, start: int, stop: int) -> VehicleAdvice:
        """Curves [start, stop) (a job's part), the profile kept whole."""
        sl = slice(start, stop)
        return VehicleAdvice(
            self.advisory_speed_kmh[sl],
            self.treatment[sl],
            self.truck_rollover_warning[sl],
            self.approach_speed_kmh[sl],
            self.required_deceleration_mps2[sl],
            self.reason[sl],
            self.reasons,
            self.station_m,
            self.speed_kmh,
            self.notes,
            self.point_part,
        )


def curve_places(t: CurveTable) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """Each curve's start station [m], length [m] and deflection [deg] (None: unknown) from a road file's facts: the
    bend's start and end where the file gives them, else its station and arc length; nan (no profile, each row says
    why) for curves given as JSON or CSV."""
    b = t.bend_columns
    start = np.where(np.isfinite(b["bend_start_m"]), b["bend_start_m"], t.station_m)
    length = np.where(
        np.isfinite(b["bend_start_m"]) & np.isfinite(b["bend_end_m"]),
        b["bend_end_m"] - b["bend_start_m"],
        b["arc_length_m"],
    )
    deflection = b["deflection_deg"]
    return start, length, None if np.isnan(deflection).all() else deflection


#: the assessed columns :func:`advise` reads (of :class:`engine.road.AlignmentColumns`; a job gathers them from its
#: parts)
ADVICE_INPUTS = (
    "radius_m",
    "superelevation_percent",
    "grade_percent",
    "posted_speed_kmh",
    "rollover_speed_kmh",
    "safe_speed_kmh",
)


def advise(
    r: ResolvedAssessment,
    cols: AlignmentColumns | SimpleNamespace,
    start_m: np.ndarray,
    length_m: np.ndarray,
    deflection_deg: np.ndarray | None,
    part: np.ndarray | None = None,
) -> VehicleAdvice:
    """:func:`engine.road.advisory.advise_alignment` of one vehicle's assessed curves (``cols``: their
    :data:`ADVICE_INPUTS` at least) with the request's options, as the columns the renderers write. ``part``: each
    curve's part where the curves lie on unconnected parts, stations along each (a route's): a profile per part."""
    a = advise_alignment(
        cols,
        start_m,
        length_m,
        deflection_deg=deflection_deg,
        desired_speed_kmh=r.desired_speed_kmh,
        units=r.units,
        deceleration_mps2=r.deceleration_mps2,
        part=part,
        all_methods=False,  # the rows show the shown speed's method only (advisory_head names it)
        all_figures=False,  # and of the profile's per-curve figures the approach speed and the rate only
    )
    p = a.profile
    required = _own_floats(p.required_deceleration_mps2)
    n = len(required)
    reason = np.full(n, -1, dtype=np.intp)
    reasons: list[str] = []
    # (count, not any(): a Python pass over 100,000 Nones, a millisecond)
    if p.reasons.count(None) < len(p.reasons):  # no profile: every curve has its reason (per curve: only then a loop)
        # (of a road of several parts, the curves of the parts without a profile; the others' are None)
        reasons = sorted({x for x in p.reasons if x is not None})
        code = {x: k for k, x in enumerate(reasons)}
        reason = np.array([-1 if x is None else code[x] for x in p.reasons], dtype=np.intp)
    if not reasons or (reason == -1).any():  # a profile: the curves whose rate is not finite say why, on arrays
        for text, where in ((NO_ROOM, required == np.inf), (UNKNOWN_APPROACH, np.isnan(required))):
            where &= reason == -1
            if where.any():
                reason[where] = len(reasons)
                reasons.append(text)
    # the profile's arrays are this call's own (the engine made them for it): their figures are rounded in place,
    # not copied (at 100,000 curves the points are megabytes, each new one fresh pages to touch)
    approach = _own_floats(p.approach_speed_kmh)
    np.copyto(approach, np.nan, where=~np.isfinite(approach))
    np.copyto(required, np.nan, where=~np.isfinite(required))
    # the profile's points written to the millimetre and 0.001 km/h (floored: never above a cap it touches):
    # at full precision its 4 points a curve were a fifth of a large answer and as long to write
    station = _own_floats(p.station_m)
    np.round(station, 3, out=station)
    speed = _own_floats(p.speed_kmh)
    np.divide(np.floor(np.multiply(speed, 1000.0, out=speed), out=speed), 1000.0, out=speed)
    return VehicleAdvice(
        advisory_speed_kmh=np.asarray(a.advisory.advisory_speed_kmh, dtype=float),
        treatment=np.asarray(a.advisory.treatment, dtype=np.intp),
        truck_rollover_warning=np.asarray(a.advisory.truck_rollover_warning, dtype=bool),
        approach_speed_kmh=approach,
        required_deceleration_mps2=required,
        reason=reason,
        reasons=reasons,
        station_m=station,
        speed_kmh=speed,
        notes=list(p.notes),
        point_part=p.point_part,
    )


def _own_floats(x) -> np.ndarray:
    """``x`` as a writable float64 array: itself where it already is one, else a copy."""
    return x if isinstance(x, np.ndarray) and x.dtype == np.float64 and x.flags.writeable else np.array(x, dtype=float)


def treatment_devices(code: int) -> list[str]:
    """The devices of a treatment code (none without a posted speed: no difference to read the table by)."""
    return list(TREATMENTS[code]) if code >= 0 else []


def advisory_head(r: ResolvedAssessment) -> dict[str, object]:
    """The answer's ``advisory``: the options and the sources every row's advisory, treatment and warning follow
    (stated once, not per row)."""
    return {
        "units": r.units,
        "increment": SIGN_INCREMENTS[r.units],
        "desired_speed_kmh": r.desired_speed_kmh,
        "deceleration_mps2": r.deceleration_mps2,
        "method": BALL_BANK_2009.id,
        "method_source": ROW_METHOD_SOURCE,
        "primary_method": f"Design Method (FHWA-SA-11-22, TxDOT): {DESIGN_METHOD_NOTE}",
        "treatment_source": TREATMENT_SOURCE,
        "truck_rollover_warning_rule": W1_13_RULE.format(margin=RULE_MARGIN_KMH),
    }

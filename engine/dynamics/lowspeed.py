"""The low-speed 90 degree turn: kinematic (no slip) paths of every unit, swept path, tail swing, frontal swing.

Geometry (the NZ Transport Agency's approved low-speed method, which says it is the Australian PBS geometry, as
read second-hand in the project's source notes): a straight tangent, a 90 degree arc on which the outermost point
of the outside front steer tyre runs at 12.5 m radius, and a straight exit tangent, at crawl speed. Here the steer
axle's centre follows the arc at ``12.5 - T/2 - b_t/2`` (``T`` the steer track, ``b_t`` the tyre width, assumed
0.30 m), the steer angle's own small offset of the tyre's outer point left out.

Kinematics: every yaw body has a guiding point on a known path (the steer axle; a kingpin, drawbar eye or turntable
on the body ahead) and, behind it, an axle that does not slip sideways, so the body's heading follows the tractrix,
integrated exactly over each straight step of the guiding point (``tan(phi/2)`` decays as ``exp(-s/L_eq)``, ``phi``
the body axis's angle to the guide's motion; steps of 0.1 m of the steer axle's travel, the arc as chords). A group of
``n`` axles at offsets ``d_i`` from its centre ``L`` behind the guiding point acts as one **equivalent axle** at
``L_eq = L + sum(d_i^2) / (n L)``: the point of no lateral slip when ``n`` equal linear tyres carry no net yaw moment
about the guiding point (the moment balance ``sum C (x_p - x_i) x_i = 0``), the "effective wheelbase" of Gillespie
and Winkler (1978) and Winkler (1998). The steady-state limit is the sum-of-squares rule ``R_E^2 = R_P^2 - L_eq^2``
(tested on the linear model's steady turn at crawl speed).

Measures (their PBS measurement rules unverified): **swept path width** = 12.5 m less the smallest distance from the
arc's centre of any unit's body (a ``width x length`` rectangle) during the manoeuvre; **tail swing** per unit = the
largest outward (away from the turn) displacement of its outside rear corner from that corner's line on the entry
tangent; **frontal swing** per unit = the largest distance by which its outside front corner passes outside the
outer steer tyre's path. Steer-tyre friction demand needs forces: not judged.

References
----------
.. [1] Gillespie, T. D. and Winkler, C. B. (1978), On the directional response characteristics of heavy trucks,
   The Dynamics of Vehicles on Roads and on Tracks, Swets and Zeitlinger, pp. 165-183 (effective wheelbase).
.. [2] Winkler, C. B. (1998), Simplified analysis of the steady-state turning of complex vehicles, Vehicle System
   Dynamics 29(3).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from engine.dynamics.model import YawRollModel

OUTER_RADIUS_M = 12.5
TYRE_WIDTH_M = 0.30
STEP_M = 0.1


@dataclass
class LowSpeedTurn:
    swept_path_width_m: float
    tail_swing_m: float
    frontal_swing_m: float
    units: list[dict]
    paths: list[dict]
    steer_axle_radius_m: float
    step_m: float


def equivalent_axle(xs: tuple[float, ...], guide: float) -> float:
    """Distance of the equivalent axle behind the guiding point [m] (module docstring)."""
    n = len(xs)
    centre = sum(xs) / n
    big_l = centre - guide
    return big_l + sum((x - centre) ** 2 for x in xs) / (n * big_l)


def _chain(model: YawRollModel) -> list[tuple[int, float, float, int | None, float]]:
    """Per yaw body: (body, guide x on it, equivalent axle distance behind the guide, towing body, guide x on it)."""
    c = model.combination
    out = []
    for b, body in enumerate(model.bodies):
        u = c.units[body.unit]
        groups = [j for j in range(len(u.groups)) if model.group_body[(body.unit, j)] == b and not u.groups[j].steer]
        if body.part == "drawbar":
            guide, towing, tx = 0.0, model.main_body[body.unit - 1], c.couplings[body.unit - 1].position_m
        elif u.kind == "full-trailer":
            xt = u.groups[0].position_m
            guide, towing, tx = xt, b - 1, xt
        elif body.unit == 0:
            guide, towing, tx = 0.0, None, 0.0
        else:
            guide, towing, tx = 0.0, model.main_body[body.unit - 1], c.couplings[body.unit - 1].position_m
        xs = tuple(x for j in groups for x in model.parameters.groups[(body.unit, j)].axle_positions_m)
        out.append((b, guide, equivalent_axle(xs, guide), towing, tx))
    return out


def low_speed_turn(model: YawRollModel, *, step_m: float = STEP_M, path_every_m: float = 0.5,
                   turn_deg: float = 90.0) -> LowSpeedTurn:  # fmt: skip
    """The 90 degree turn (module docstring); ``paths`` every ``path_every_m`` of steer-axle travel; ``turn_deg``
    another angle (the tests turn full circles to reach the steady state)."""
    c = model.combination
    p = model.parameters
    steer = c.units[0].groups[0]
    rc = OUTER_RADIUS_M - steer.track_m / 2.0 - TYRE_WIDTH_M / 2.0
    total = sum(u.rear_extent_m.value + u.front_overhang_m.value for u in p.units) + 10.0
    turn = math.radians(turn_deg)
    arc = rc * turn
    s_all = np.arange(0.0, total + arc + total + step_m / 2, step_m)

    # the steer axle's centre; turn centre at the origin, a left turn
    e = np.clip(s_all - total - arc, 0.0, None)
    a = np.clip(s_all - total, 0.0, arc) / rc
    px = np.where(s_all <= total, s_all - total, rc * np.sin(a) + e * math.cos(turn))
    py = np.where(s_all <= total, -rc, -rc * np.cos(a) + e * math.sin(turn))

    chain = _chain(model)
    nb = len(model.bodies)
    n = len(s_all)
    heads = np.zeros((n, nb))
    refs = np.zeros((n, nb, 2))
    for b, guide, leq, towing, tx in chain:
        if towing is None:
            gx, gy = px - guide, py  # the steer axle is the first body's reference and guide (guide = 0)
        else:
            gx = refs[:, towing, 0] - tx * np.cos(heads[:, towing])
            gy = refs[:, towing, 1] - tx * np.sin(heads[:, towing])
        dx, dy = np.diff(gx), np.diff(gy)
        ds = np.hypot(dx, dy)
        beta = np.arctan2(dy, dx).tolist()
        decay = np.exp(-ds / leq).tolist()
        moving = (ds > 0.0).tolist()
        # exact tractrix over each straight step of the guide: tan(phi/2) decays as exp(-ds/L_eq), phi the body
        # axis's angle to the guide's motion; the vehicle starts straight on the entry tangent
        h = [0.0] * n
        cur = 0.0
        two_pi, pi = 2.0 * math.pi, math.pi
        for k in range(n - 1):
            if moving[k]:
                phi = (cur - beta[k] + pi) % two_pi - pi
                cur = beta[k] + 2.0 * math.atan(math.tan(phi / 2.0) * decay[k])
            h[k + 1] = cur
        heads[:, b] = h
        refs[:, b, 0] = gx + guide * np.cos(heads[:, b])
        refs[:, b, 1] = gy + guide * np.sin(heads[:, b])
    # bodies of the units (a full trailer's body is its second yaw body): rectangles in their own frames
    units, paths = [], []
    every = max(1, round(path_every_m / step_m))
    r_min = math.inf
    for i, u in enumerate(c.units):
        b = model.main_body[i]
        up = p.units[i]
        front = -up.front_overhang_m.value
        if u.kind == "full-trailer":
            front += u.groups[0].position_m  # a full trailer's body front is measured from its turntable
        rear = up.rear_extent_m.value
        half = up.width_m.value / 2.0
        cos, sin = np.cos(heads[:, b]), np.sin(heads[:, b])
        rx, ry = refs[:, b, 0], refs[:, b, 1]

        def corner(x: float, lat: float, rx=rx, ry=ry, cos=cos, sin=sin) -> tuple[np.ndarray, np.ndarray]:
            # x behind the reference, lat + left
            return rx - x * cos - lat * sin, ry - x * sin + lat * cos

        fl, fr, rl, rr = corner(front, half), corner(front, -half), corner(rear, half), corner(rear, -half)
        # the origin in the body frame: along (+ forward of the reference), lateral (+ left)
        along = -(rx * cos + ry * sin)
        lateral = -(-rx * sin + ry * cos)
        da = np.maximum(0.0, np.maximum(-rear - along, along + front))
        dl = np.maximum(0.0, np.abs(lateral) - half)
        r_min = min(r_min, float(np.min(np.hypot(da, dl))))
        tail = float(max(0.0, np.max(rr[1][0] - rr[1])))
        outside = _outside(fr[0], fr[1], turn)
        units.append({"unit": u.id, "tail_swing_m": tail, "frontal_swing_m": float(max(0.0, np.max(outside)))})
        for name, (xx, yy) in (("front-left", fl), ("front-right", fr), ("rear-left", rl), ("rear-right", rr)):
            paths.append({"unit": u.id, "corner": name,
                          "points_m": np.column_stack([xx[::every], yy[::every]]).round(3).tolist()})  # fmt: skip
    return LowSpeedTurn(
        swept_path_width_m=OUTER_RADIUS_M - r_min,
        tail_swing_m=max(e["tail_swing_m"] for e in units),
        frontal_swing_m=units[0]["frontal_swing_m"],
        units=units,
        paths=paths,
        steer_axle_radius_m=rc,
        step_m=step_m,
    )


def _outside(x: np.ndarray, y: np.ndarray, turn: float) -> np.ndarray:
    """Signed distance outside the outer steer tyre's path: the entry line y = -R, the arc of R through ``turn``
    [rad], the exit tangent [m]."""
    r = OUTER_RADIUS_M
    alpha = np.arctan2(x, -y) % (2.0 * math.pi)
    alpha = np.where(alpha > math.pi + turn / 2.0, alpha - 2.0 * math.pi, alpha)
    exit_ = x * math.sin(turn) - y * math.cos(turn) - r
    return np.where(alpha < 0.0, -r - y, np.where(alpha > turn, exit_, np.hypot(x, y) - r))

"""The dynamics figures as SVG (app.formats.svg): lateral acceleration of every unit in the lane change, rearward
amplification against frequency, and the low-speed turn's corner paths to scale.

Each is cached under the key of its resolved request (the same as the JSON answer's, under its own operation) and
:data:`SVG_VERSION` (bump it when the drawing changes: the engine version does not cover the renderer).
"""

from __future__ import annotations

import numpy as np

from app.formats.svg import Marker, Panel, Series, line_chart, nice_ticks

SVG_VERSION = 1
SCREENING = "Indicative screening by a linear model, not a certification."


def lane_change_svg(label: str, history: dict, ra: float, hsto: float, speed_kmh: float, f_hz: float,
                    a_g: float) -> str:  # fmt: skip
    t = history["time_s"]
    series = [Series(unit, t, ay) for unit, ay in history["lateral_acceleration_g"].items()]
    caption = (f"Single lane change at {speed_kmh:g} km/h: one sine period of the steer axle's lateral acceleration, "
               f"{a_g:g} g at {f_hz:g} Hz. Rearward amplification {ra:.3f}, high-speed transient offtracking "
               f"{hsto:.3f} m. Lateral acceleration at each unit's sprung CG. {SCREENING}")  # fmt: skip
    return line_chart(f"Lateral acceleration of every unit: {label}", "time t [s]",
                      [Panel("lateral acceleration [g]", series)], caption=caption)  # fmt: skip


def frequency_response_svg(label: str, freqs: list[float], ra: list[float], worst_f: float, worst_ra: float,
                           speed_kmh: float, definition: str) -> str:  # fmt: skip
    what = "the rearmost unit's CG" if definition == "cg" else "the rearmost axle"
    caption = (f"Rearward amplification RA(f) = |a_rear| / |a_steer| at {speed_kmh:g} km/h, a_rear at {what}; "
               f"worst {worst_ra:.3f} at {worst_f:.3f} Hz. {SCREENING}")  # fmt: skip
    return line_chart(f"Rearward amplification against frequency: {label}", "frequency f [Hz]",
                      [Panel("rearward amplification [-]", [Series("RA", freqs, ra)],
                             [Marker(worst_f, f"worst {worst_f:.2f} Hz")])], caption=caption)  # fmt: skip


def low_speed_turn_svg(label: str, paths: list[dict], outer_radius_m: float, spw: float, tail: float,
                       frontal: float) -> str:  # fmt: skip
    """The corners' paths to scale: the panel's height is chosen so that a metre is as long on both axes."""
    series = []
    for p in paths:
        pts = np.asarray(p["points_m"], dtype=float)
        series.append(Series(f"{p['unit']} {p['corner']}", pts[:, 0].tolist(), pts[:, 1].tolist()))
    a = np.linspace(0.0, np.pi / 2, 91)
    series.append(Series("outer steer tyre path", (outer_radius_m * np.sin(a)).tolist(),
                         (-outer_radius_m * np.cos(a)).tolist(), dashed=True))  # fmt: skip
    xs = [v for s in series for v in s.x]
    ys = [v for s in series for v in s.y]
    xt, yt = nice_ticks(min(xs), max(xs)), nice_ticks(min(ys), max(ys))
    plot_w = 760 - 78 - 190  # line_chart's plot width at its default width
    height = round(plot_w * (yt[-1] - yt[0]) / (xt[-1] - xt[0]))
    caption = (f"Low-speed 90 degree turn, the outer steer tyre on {outer_radius_m:g} m (no slip; to scale; turn "
               f"centre at the origin). Swept path width {spw:.3f} m, tail swing {tail:.3f} m, frontal swing "
               f"{frontal:.3f} m. {SCREENING}")  # fmt: skip
    return line_chart(f"Low-speed turn, corner paths: {label}", "x [m]", [Panel("y [m]", series)], caption=caption,
                      panel_height=max(120, min(height, 2000)))  # fmt: skip

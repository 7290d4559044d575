"""Road-design formulas of Ch. 9: maximum curve speed and minimum curve radius.

Units follow road practice: speeds in km/h, radii in m, superelevation in %, SRT in g. The constant 127
is 3.6^2 * g = 12.96 * 9.81 (km/h to m/s, and g).

Side-friction factor (Table 21)
-------------------------------
Table 21 (AASHTO 2003, DNER 1999, DNIT 2009) gives a *range* of design side-friction factors per design
speed. We take the **low end** by default: it is the conservative choice for a minimum radius (smaller f,
larger radius). It is not AASHTO's maximum side-friction factor for design: the current Green Book (2018,
Table 3-7) gives 0.19/0.17/0.15 at 50/60/70 km/h where the low end reads 0.16/0.15/0.14 (the named
standards, with their sources, are in :mod:`engine.standards`).
``bound="high"`` or ``"mid"`` select the upper end or the middle of the range. Between tabulated speeds
the factor is interpolated linearly in speed; outside 30-120 km/h the table says nothing and the caller
must give ``side_friction`` explicitly (:class:`InvalidRoad` otherwise).

References
----------
Thesis Eqs. 9.1-9.3 and Table 21; AASHTO (2001, 2003); DNIT (2009).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .domain import check
from .errors import InvalidRoad

KMH2_PER_M_G = 127.0  # V^2 / (127 R) is the lateral acceleration in g for V in km/h, R in m

#: Table 21: design speed [km/h], side-friction factor range (low, high) [-]
TABLE21_SPEEDS_KMH = np.array([30.0, 40.0, 50.0, 60.0, 70.0, 80.0, 90.0, 100.0, 110.0, 120.0])
TABLE21_F_LOW = np.array([0.17, 0.17, 0.16, 0.15, 0.14, 0.14, 0.13, 0.12, 0.11, 0.09])
TABLE21_F_HIGH = np.array([0.28, 0.23, 0.19, 0.17, 0.15, 0.14, 0.14, 0.13, 0.12, 0.11])
FRICTION_BOUNDS = ("low", "mid", "high")


def max_curve_speed_kmh(srt_g, radius_m):
    """Maximum speed on a curve before rollover, V = sqrt(127 SRT R) [km/h] (Eq. 9.1).

    ``srt_g`` must be the SRT on *that* curve's bank and slope: the thesis's SRT already contains the
    bank angle (Eq. 6.18), so no superelevation term is added here.
    """
    srt = np.asarray(srt_g, dtype=float)
    r = np.asarray(radius_m, dtype=float)
    return np.sqrt(KMH2_PER_M_G * srt * r)


def side_friction_factor(speed_kmh, bound: str = "low"):
    """Design side-friction factor f from Table 21, interpolated linearly in speed [-].

    The ``thesis-table21`` standard of :mod:`engine.standards` at ``bound``. Raises :class:`InvalidRoad` for
    a speed outside 30-120 km/h or an unknown ``bound``.
    """
    from .standards import get_standard
    from .standards import side_friction_factor as standard_side_friction_factor

    return standard_side_friction_factor(get_standard("thesis-table21", bound), speed_kmh)


def aashto_min_radius_m(speed_kmh, superelevation_percent, side_friction):
    """Minimum radius by the simplified curve formula R = V^2 / (127 (0.01 e + f)) [m] (Eq. 9.2)."""
    v = np.asarray(speed_kmh, dtype=float)
    demand = 0.01 * np.asarray(superelevation_percent, dtype=float) + np.asarray(side_friction, dtype=float)
    if np.any(demand <= 0):
        raise InvalidRoad("0.01 e + f must be positive for Eq. 9.2", field="superelevation_percent")
    return v**2 / (KMH2_PER_M_G * demand)


def rollover_min_radius_m(speed_kmh, srt_g):
    """Minimum radius against rollover R = V^2 / (127 SRT) [m] (Eq. 9.3), SRT on that bank and slope."""
    v = np.asarray(speed_kmh, dtype=float)
    srt = np.asarray(srt_g, dtype=float)
    if np.any(srt <= 0):
        raise InvalidRoad("the SRT must be positive for Eq. 9.3", field="srt")
    return v**2 / (KMH2_PER_M_G * srt)


@dataclass(frozen=True)
class MinRadius:
    aashto_min_radius_m: float
    rollover_min_radius_m: float
    governing_min_radius_m: float
    governed_by: str  # "side-friction" or "rollover"
    side_friction: float


def min_radius(
    design_speed_kmh: float,
    superelevation_percent: float,
    srt_g: float,
    side_friction: float | None = None,
    bound: str = "low",
) -> MinRadius:
    """Both minimum radii (Eqs. 9.2 and 9.3) and the governing (larger) one."""
    check_speed(design_speed_kmh)
    f = float(side_friction_factor(design_speed_kmh, bound)) if side_friction is None else float(side_friction)
    if not (math.isfinite(f) and 0.0 < f < 1.0):
        raise InvalidRoad(f"side_friction must be in (0, 1), got {f}", field="side_friction", value=f)
    r_f = float(aashto_min_radius_m(design_speed_kmh, superelevation_percent, f))
    r_r = float(rollover_min_radius_m(design_speed_kmh, srt_g))
    gov = "rollover" if r_r > r_f else "side-friction"
    return MinRadius(r_f, r_r, max(r_f, r_r), gov, f)


def check_speed(speed_kmh: float, field: str = "design_speed_kmh") -> None:
    """Refuse a speed outside (0, 200] km/h (:data:`engine.domain.BOUNDS`)."""
    check("speed_kmh", speed_kmh, field)


def side_friction_speed_kmh(radius_m, superelevation_percent, bound: str = "low"):
    """Speed at which a curve uses up the design side friction: V = sqrt(127 R (0.01 e + f(V))) [km/h].

    f depends on V through Table 21, so the equation is implicit; the right-hand side falls as V rises,
    so there is one root. It is found by bisection on the table's range and clamped to it: a curve that
    needs V < 30 km/h uses f(30) and one above 120 km/h uses f(120) (the table says nothing outside).
    Works elementwise on arrays. The ``thesis-table21`` case of
    :func:`engine.standards.side_friction_speed_kmh`, which also reports the clamping.
    """
    from .standards import get_standard
    from .standards import side_friction_speed_kmh as standard_side_friction_speed_kmh

    return standard_side_friction_speed_kmh(get_standard("thesis-table21", bound), radius_m, superelevation_percent)

"""Superelevation distribution of a design standard: AASHTO Method 5, DNIT IPR-706 (e over the radii).

References
----------
AASHTO (2018) Sec. 3.3.5-3.3.6; DNER (1999) IPR-706 Sec. 5.4; NYSDOT HDM Exhibits M2-13, M2-14.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from engine.errors import InvalidRoad
from engine.road.formulas import (
    KMH2_PER_M_G,
    side_friction_min_radius_m,
)
from engine.road.standards import (
    AASHTO_METHOD,
    STANDARDS,
    DesignStandard,
    check_e_max,
    check_radii,
    resolve_standard,
    side_friction_factor,
)

# ------------------------------------------------------------------------- superelevation


@dataclass(frozen=True)
class SuperelevationResult:
    """Design superelevation on a curve and the side friction it leaves at the design speed."""

    superelevation_percent: float
    side_friction: float  # V^2/(127 R) - e/100 [-]
    min_radius_m: float  # Eq. 9.2 R_min for e_max (unrounded: where the distribution reaches e_max)
    method: str
    f_max: float
    standard: str


def _aashto_method5_f(std: DesignStandard, v: float, inv_r: np.ndarray, e_max: float, f_max: float) -> np.ndarray:
    """Side friction at the design speed for curvature 1/R by Method 5 (Green Book Sec. 3.3.5-3.3.6).

    The f distribution is two parabolic arcs with a PI at 1/R_PI, the curvature at which a vehicle at the
    running speed V_R is held by e_max alone; the arcs are tangent to the lines through the origin and
    through (1/R_min, f_max) and join at the PI with the vertical offset M_O.
    """
    v_r = float(np.interp(v, std.speeds_kmh, std.running_speeds_kmh))
    inv_r_min = (e_max + f_max) * KMH2_PER_M_G / v**2  # 1/R_min = (e_max + f_max) / (V_D^2 / 127)
    inv_r_pi = e_max * KMH2_PER_M_G / v_r**2  # 1/R_PI = e_max / (V_R^2 / 127)
    h = e_max * v**2 / v_r**2 - e_max  # f at the design speed at the PI
    tan1 = (v**2 - v_r**2) / KMH2_PER_M_G  # slope of the first leg, h / (1/R_PI) with e_max cancelled
    tan2 = (f_max - h) / (inv_r_min - inv_r_pi)  # slope of the second leg
    m_o = inv_r_pi * (inv_r_min - inv_r_pi) * (tan2 - tan1) / (2.0 * inv_r_min)  # middle ordinate at the PI
    f1 = m_o * (inv_r / inv_r_pi) ** 2 + inv_r * tan1  # 1/R <= 1/R_PI
    f2 = m_o * ((inv_r_min - inv_r) / (inv_r_min - inv_r_pi)) ** 2 + h + (inv_r - inv_r_pi) * tan2  # 1/R > 1/R_PI
    return np.where(inv_r <= inv_r_pi, f1, f2)


def distribution_min_radius_m(std: DesignStandard, speed_kmh: float, e_max_percent: float) -> float:
    """The smallest radius the superelevation distribution takes [m]: Eq. 9.2's R_min with the standard's f_max, or
    the published, rounded R_min where that is smaller (AASHTO rounds to the metre, sometimes down: 229 m for
    229.06 m; between the two the curve is at R_min, e = e_max)."""
    f_max = float(side_friction_factor(std, speed_kmh))
    r_min = float(side_friction_min_radius_m(speed_kmh, e_max_percent, f_max))  # Eq. 9.2
    published = std.min_radius_table.get(float(e_max_percent), {}).get(float(speed_kmh))
    return min(r_min, published) if published is not None else r_min


def _superelevation_arrays(std: DesignStandard, speed_kmh: float, e_max_percent: float, radii_m):
    """(e [%], f [-], R_min [m], f_max [-]) on an array of radii, refusing radii below R_min."""
    if std.superelevation_method is None:
        have = [s.id for s in STANDARDS.values() if s.superelevation_method is not None]
        raise InvalidRoad(
            f"{std.id} has no superelevation distribution of its own; standards with one: {', '.join(have)}",
            field="design_standard",
            value=std.id,
        )
    f_max = float(side_friction_factor(std, speed_kmh))
    e_max = check_e_max(std, e_max_percent, positive=True)
    lowest = min(std.max_superelevations_percent)
    if e_max < lowest:  # the distributions are published (and Method 5's PI defined) for the tabulated e_max only
        raise InvalidRoad(
            f"max_superelevation_percent {e_max:g} % is below the e_max values {std.id} tabulates "
            f"({lowest:g}-{max(std.max_superelevations_percent):g} %): its superelevation distribution is not "
            "defined there",
            field="max_superelevation_percent",
            value=e_max,
        )
    v = float(speed_kmh)
    r = check_radii(radii_m)
    r_min = float(side_friction_min_radius_m(v, e_max, f_max))  # Eq. 9.2
    published = std.min_radius_table.get(e_max, {}).get(v)
    limit = distribution_min_radius_m(std, v, e_max)
    if np.any(r < limit * (1.0 - 1e-12)):
        first = float(r[r < limit * (1.0 - 1e-12)].flat[0]) if r.ndim else float(r)
        table = f" (published: {published:g} m)" if published is not None else ""
        raise InvalidRoad(
            f"radius_m {first:g} m is below the minimum radius R_min = {r_min:.1f} m{table} of {std.id} at "
            f"{v:g} km/h with e_max {e_max:g} % (f_max {f_max:g})",
            field="radius_m",
            value=first,
        )
    demand = v**2 / (KMH2_PER_M_G * r)  # e/100 + f = V^2 / (127 R), at the curve's own radius
    r = np.maximum(r, r_min)  # at R_min (or the published rounding of it) the distribution gives e_max
    if std.superelevation_method == AASHTO_METHOD:
        f = _aashto_method5_f(std, v, 1.0 / r, 0.01 * e_max, f_max)
        e = np.minimum(100.0 * (v**2 / (KMH2_PER_M_G * r) - f), e_max)  # e_max exactly at R_min, no round-off
        f = demand - 0.01 * e
    else:
        x = r_min / r
        e = e_max * (2.0 * x - x**2)  # DNER (1999): e = e_max (2 R_min/R - R_min^2/R^2)
        f = demand - 0.01 * e
    return e, f, r_min, f_max


def superelevation_percent(
    standard: DesignStandard | str, speed_kmh: float, radius_m: float, max_superelevation_percent: float
) -> SuperelevationResult:
    """Design superelevation of a curve by the standard's distribution method.

    AASHTO: Method 5, the parabolic f distribution with its PI at the curvature that e_max alone holds at
    the running speed. DNIT: e = e_max (2 R_min/R - R_min^2/R^2). Both give e_max at R_min (Eq. 9.2,
    unrounded), fall monotonically toward 0 as R grows, and leave f = V^2/(127 R) - e/100 <= f_max. A radius
    between the published, rounded R_min (AASHTO rounds 229.06 m to 229 m) and Eq. 9.2's is accepted as R_min:
    e = e_max there, and f exceeds f_max by what the table's rounding implies (at most ~0.05 %). The
    value is the method's exact e, not rounded: the AASHTO tables list radii for e in 0.2 % steps, and
    DNIT practice (the two implementations found) rounds e up to 0.1 %; rounding is the caller's choice.

    Parameters
    ----------
    standard : DesignStandard or str
        ``aashto-2018`` or ``dnit-1999`` (``thesis-table21`` has no distribution and is refused).
    speed_kmh : float
        Design speed [km/h].
    radius_m : float
        Curve radius, at least R_min [m].
    max_superelevation_percent : float
        Maximum superelevation e_max, (0, 12] [%].

    Returns
    -------
    SuperelevationResult

    Raises
    ------
    InvalidRoad
        A standard without a distribution (``field="design_standard"``), a radius below R_min
        (``field="radius_m"``, the message names R_min), a speed outside the range or a bad e_max.
    """
    std = resolve_standard(standard, None)
    e, f, r_min, f_max = _superelevation_arrays(std, speed_kmh, max_superelevation_percent, float(radius_m))
    return SuperelevationResult(float(e), float(f), r_min, str(std.superelevation_method), f_max, std.id)


@dataclass(frozen=True)
class SuperelevationTable:
    """e and f over a set of radii at one design speed and e_max (for plots and tables)."""

    radius_m: np.ndarray
    superelevation_percent: np.ndarray
    side_friction: np.ndarray
    min_radius_m: float
    f_max: float
    method: str


def superelevation_table(
    standard: DesignStandard | str, speed_kmh: float, max_superelevation_percent: float, radii_m
) -> SuperelevationTable:
    """Vectorised :func:`superelevation_percent` over an array of radii [m] (all at least R_min)."""
    std = resolve_standard(standard, None)
    r = np.atleast_1d(np.asarray(radii_m, dtype=float))
    e, f, r_min, f_max = _superelevation_arrays(std, speed_kmh, max_superelevation_percent, r)
    return SuperelevationTable(r, e, f, r_min, f_max, str(std.superelevation_method))

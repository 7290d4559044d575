"""Road-design formulas of Ch. 9: maximum curve speed and minimum curve radius.

Units follow road practice: speeds in km/h, radii in m, superelevation in %, SRT in g. The constant 127
is 3.6^2 * g = 12.96 * 9.81 (km/h to m/s, and g).

Side friction
-------------
Eq. 9.2 needs a design side-friction factor f. :func:`min_radius` reads it from a named design standard
(:mod:`engine.road.standards`: ``aashto-2018``, the default, ``dnit-1999`` or ``thesis-table21``). The thesis's
Table 21 (AASHTO 2003, DNER 1999, DNIT 2009) gives a *range* of f per design speed; :func:`side_friction_factor`
here reads that range at a bound (``low`` by default, the conservative choice: smaller f, larger radius).
Neither bound is any one standard: the current Green Book (2018, Table 3-7) gives 0.19/0.17/0.15 at
50/60/70 km/h where the low end reads 0.16/0.15/0.14. Between tabulated speeds the factor is interpolated
linearly in speed; outside a table's range nothing is extrapolated (:class:`InvalidRoad` names the range).

References
----------
Thesis Eqs. 9.1-9.3 and Table 21; AASHTO (2018), *A Policy on Geometric Design of Highways and Streets*, 7th
ed., Eq. 3-8 and Table 3-7; DNER (1999), IPR-706, Sec. 5.4 (see :mod:`engine.road.standards`).
"""

from __future__ import annotations

import numpy as np

from engine.domain import check
from engine.errors import InvalidRoad

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


#: the smallest 0.01 e + f [-] Eq. 9.2 accepts: the floor of the SRT (``srt_g`` >= 0.01 g) for Eq. 9.3, so both
#: radii stay bounded alike (V^2 / (127 * 0.01) at 130 km/h is 13,300 m)
MIN_LATERAL_DEMAND = 0.01


def side_friction_min_radius_m(speed_kmh, superelevation_percent, side_friction):
    """Minimum radius by the simplified curve formula R = V^2 / (127 (0.01 e + f)) [m] (Eq. 9.2).

    The point-mass curve formula of AASHTO (Green Book Eq. 3-8) and DNIT (IPR-706 Sec. 5.4); with a standard's
    f_max and e_max it gives that standard's minimum radius (:func:`engine.road.min_radius.min_radius_m`).
    """
    v = np.asarray(speed_kmh, dtype=float)
    demand = 0.01 * np.asarray(superelevation_percent, dtype=float) + np.asarray(side_friction, dtype=float)
    if np.any(demand < MIN_LATERAL_DEMAND):
        raise InvalidRoad(
            f"0.01 e + f = {float(np.min(demand)):.4g}: Eq. 9.2 needs at least {MIN_LATERAL_DEMAND:g} (below it the "
            "radius grows without bound: the road holds next to no lateral acceleration)",
            field="superelevation_percent",
        )
    return v**2 / (KMH2_PER_M_G * demand)


#: deprecated name of :func:`side_friction_min_radius_m` (Eq. 9.2 is not only AASHTO's); kept for one version
aashto_min_radius_m = side_friction_min_radius_m


def rollover_min_radius_m(speed_kmh, srt_g):
    """Minimum radius against rollover R = V^2 / (127 SRT) [m] (Eq. 9.3), SRT on that bank and slope."""
    v = np.asarray(speed_kmh, dtype=float)
    srt = np.asarray(srt_g, dtype=float)
    if np.any(srt <= 0):
        raise InvalidRoad("the SRT must be positive for Eq. 9.3", field="srt")
    return v**2 / (KMH2_PER_M_G * srt)


def check_speed(speed_kmh: float, field: str = "design_speed_kmh") -> None:
    """Refuse a speed outside (0, 200] km/h (:data:`engine.domain.BOUNDS`)."""
    check("speed_kmh", speed_kmh, field)

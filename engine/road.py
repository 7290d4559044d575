"""Road-design formulas of Ch. 9: maximum curve speed and minimum curve radius.

Units follow road practice: speeds in km/h, radii in m, superelevation in %, SRT in g. The constant 127
is 3.6^2 * g = 12.96 * 9.81 (km/h to m/s, and g).

Side friction
-------------
Eq. 9.2 needs a design side-friction factor f. :func:`min_radius` reads it from a named design standard
(:mod:`engine.standards`: ``aashto-2018``, the default, ``dnit-1999`` or ``thesis-table21``). The thesis's
Table 21 (AASHTO 2003, DNER 1999, DNIT 2009) gives a *range* of f per design speed; :func:`side_friction_factor`
here reads that range at a bound (``low`` by default, the conservative choice: smaller f, larger radius).
Neither bound is any one standard: the current Green Book (2018, Table 3-7) gives 0.19/0.17/0.15 at
50/60/70 km/h where the low end reads 0.16/0.15/0.14. Between tabulated speeds the factor is interpolated
linearly in speed; outside a table's range nothing is extrapolated (:class:`InvalidRoad` names the range).

References
----------
Thesis Eqs. 9.1-9.3 and Table 21; AASHTO (2018), *A Policy on Geometric Design of Highways and Streets*, 7th
ed., Eq. 3-8 and Table 3-7; DNER (1999), IPR-706, Sec. 5.4 (see :mod:`engine.standards`).
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


def side_friction_min_radius_m(speed_kmh, superelevation_percent, side_friction):
    """Minimum radius by the simplified curve formula R = V^2 / (127 (0.01 e + f)) [m] (Eq. 9.2).

    The point-mass curve formula of AASHTO (Green Book Eq. 3-8) and DNIT (IPR-706 Sec. 5.4); with a standard's
    f_max and e_max it gives that standard's minimum radius (:func:`engine.standards.min_radius_m`).
    """
    v = np.asarray(speed_kmh, dtype=float)
    demand = 0.01 * np.asarray(superelevation_percent, dtype=float) + np.asarray(side_friction, dtype=float)
    if np.any(demand <= 0):
        raise InvalidRoad("0.01 e + f must be positive for Eq. 9.2", field="superelevation_percent")
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


@dataclass(frozen=True)
class MinRadius:
    """Both minimum radii of a design speed and superelevation, and which governs.

    side_friction_min_radius_m : Eq. 9.2 with f [m]; rollover_min_radius_m : Eq. 9.3 with the SRT [m]
    governing_min_radius_m : the larger [m]; governed_by : ``side-friction`` or ``rollover``
    side_friction : f used [-]; side_friction_source : ``given`` or the standard's table it was read from
    design_standard : the standard's id [-]
    """

    side_friction_min_radius_m: float
    rollover_min_radius_m: float
    governing_min_radius_m: float
    governed_by: str  # "side-friction" or "rollover"
    side_friction: float
    side_friction_source: str
    design_standard: str

    @property
    def aashto_min_radius_m(self) -> float:
        """Deprecated name of :attr:`side_friction_min_radius_m`."""
        return self.side_friction_min_radius_m


def min_radius(
    design_speed_kmh: float,
    superelevation_percent: float,
    srt_g: float,
    side_friction: float | None = None,
    *,
    design_standard: str | None = None,
    bound: str | None = None,
) -> MinRadius:
    """Both minimum radii (Eqs. 9.2 and 9.3) and the governing (larger) one.

    Parameters
    ----------
    design_speed_kmh : design speed V; inside the standard's range unless ``side_friction`` is given [km/h]
    superelevation_percent : superelevation e of the curve [%]
    srt_g : the vehicle's SRT on that bank and slope [g]
    side_friction : design side friction f; default: the standard's f_max at V [-]
    design_standard : id of :data:`engine.standards.STANDARDS`; default
        :data:`engine.standards.DEFAULT_DESIGN_STANDARD` [-]
    bound : Table 21 bound (``low``/``mid``/``high``), ``thesis-table21`` only [-]

    Raises
    ------
    InvalidRoad : a speed outside the standard's range (naming it), an unknown standard or bound, f outside (0, 1).
    """
    from .standards import DEFAULT_DESIGN_STANDARD, get_standard
    from .standards import side_friction_factor as standard_f

    check_speed(design_speed_kmh)
    std = get_standard(design_standard or DEFAULT_DESIGN_STANDARD, bound)
    if side_friction is None:
        f = float(standard_f(std, design_speed_kmh))  # f_max of the standard's table, linear between rows
        source = f"table21-{std.bound}" if std.bound else std.id
    else:
        f, source = float(side_friction), "given"
    if not (math.isfinite(f) and 0.0 < f < 1.0):
        raise InvalidRoad(f"side_friction must be in (0, 1), got {f}", field="side_friction", value=f)
    r_f = float(side_friction_min_radius_m(design_speed_kmh, superelevation_percent, f))  # Eq. 9.2
    r_r = float(rollover_min_radius_m(design_speed_kmh, srt_g))  # Eq. 9.3
    gov = "rollover" if r_r > r_f else "side-friction"
    return MinRadius(r_f, r_r, max(r_f, r_r), gov, f, source, std.id)


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

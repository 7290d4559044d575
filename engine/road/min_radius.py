"""Minimum curve radius: Eq. 9.2 (side friction, with a standard's f_max) against Eq. 9.3 (rollover), and
the minimum radii of the design standards (their tables, or Eq. 9.2 at e_max and f_max).

References
----------
Thesis Eqs. 9.2-9.3; AASHTO (2018) Table 3-7, Eq. 3-8; DNER (1999) IPR-706 Quadro 5.4.3.2.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from engine.domain import BOUNDS
from engine.errors import InvalidRoad
from engine.road.formulas import (
    check_speed,
    rollover_min_radius_m,
    side_friction_min_radius_m,
)
from engine.road.standards import (
    E_MAX_LIMIT_PERCENT,
    DesignStandard,
    check_design_speeds,
    check_e_max,
    check_radii,
    resolve_standard,
    side_friction_factor,
)


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
    design_standard : id of :data:`engine.road.standards.STANDARDS`; default
        :data:`engine.road.standards.DEFAULT_DESIGN_STANDARD` [-]
    bound : Table 21 bound (``low``/``mid``/``high``), ``thesis-table21`` only [-]

    Raises
    ------
    InvalidRoad : a speed outside the standard's range (naming it), an unknown standard or bound, f outside
        ``BOUNDS['side_friction']``.
    """
    from engine.road.standards import DEFAULT_DESIGN_STANDARD, get_standard
    from engine.road.standards import side_friction_factor as standard_f

    check_speed(design_speed_kmh)
    std = get_standard(design_standard or DEFAULT_DESIGN_STANDARD, bound)
    if side_friction is None:
        f = float(standard_f(std, design_speed_kmh))  # f_max of the standard's table, linear between rows
        source = f"table21-{std.bound}" if std.bound else std.id
    else:
        f, source = float(side_friction), "given"
    bound = BOUNDS["side_friction"]
    if not bound.contains(f):
        raise InvalidRoad(f"side_friction must be in {bound.text()} ({bound.why})", field="side_friction", value=f)
    r_f = float(side_friction_min_radius_m(design_speed_kmh, superelevation_percent, f))  # Eq. 9.2
    r_r = float(rollover_min_radius_m(design_speed_kmh, srt_g))  # Eq. 9.3
    gov = "rollover" if r_r > r_f else "side-friction"
    return MinRadius(r_f, r_r, max(r_f, r_r), gov, f, source, std.id)


# ------------------------------------------------------------------------------- minimum radius


@dataclass(frozen=True)
class MinRadiusResult:
    """A standard's minimum radius: ``source`` is ``table`` (published, rounded) or ``formula`` (Eq. 9.2)."""

    radius_m: float
    source: str
    f_max: float
    formula_radius_m: float  # Eq. 9.2, unrounded, for comparison with a table value
    standard: str
    max_superelevation_percent: float
    speed_kmh: float


def min_radius_m(
    standard: DesignStandard | str,
    speed_kmh: float,
    max_superelevation_percent: float,
    *,
    tabulated: bool = True,
    bound: str | None = None,
) -> MinRadiusResult:
    """The standard's minimum radius for a design speed and maximum superelevation.

    With ``tabulated`` (default) the published, rounded value where the standard tabulates that cell
    (exact table reproduction), else R_min = V^2 / (127 (0.01 e_max + f_max)) (thesis Eq. 9.2) with f_max
    from :func:`side_friction_factor` (interpolated between rows). ``source`` says which.

    Parameters
    ----------
    standard : DesignStandard or str
        The standard or its id.
    speed_kmh : float
        Design speed [km/h].
    max_superelevation_percent : float
        Maximum superelevation e_max [%], 0-12 (0 only for the formula).
    tabulated : bool
        Prefer the published table value where there is one.
    bound : str, optional
        Table 21 bound, ``thesis-table21`` only [-].

    Returns
    -------
    MinRadiusResult
        ``radius_m`` [m], ``source``, ``f_max`` [-] and the unrounded formula radius [m].
    """
    std = resolve_standard(standard, bound)
    f = float(side_friction_factor(std, speed_kmh))
    e = check_e_max(std, max_superelevation_percent, positive=False)
    v = float(speed_kmh)
    r_formula = float(side_friction_min_radius_m(v, e, f))  # Eq. 9.2
    row = std.min_radius_table.get(e, {}) if tabulated else {}
    if v in row:
        return MinRadiusResult(row[v], "table", f, r_formula, std.id, e, v)
    return MinRadiusResult(r_formula, "formula", f, r_formula, std.id, e, v)


def min_radius_array(standard: DesignStandard | str, speed_kmh, max_superelevation_percent, bound: str | None = None):
    """:func:`min_radius_m` on arrays of design speeds and e_max (speeds inside the range, e_max in [0, 12] %) [m].

    Eq. 9.2 everywhere, replaced by the published value where the standard tabulates that (e_max, speed) cell.
    """
    std = resolve_standard(standard, bound)
    v = check_design_speeds(std, speed_kmh)
    e = np.broadcast_to(np.asarray(max_superelevation_percent, dtype=float), v.shape)
    if np.any(~np.isfinite(e) | (e < 0) | (e > E_MAX_LIMIT_PERCENT)):
        bad = float(e[~np.isfinite(e) | (e < 0) | (e > E_MAX_LIMIT_PERCENT)].flat[0])
        check_e_max(std, bad, positive=False)
    f = np.interp(v, std.speeds_kmh, std.f_max)
    radius = np.asarray(side_friction_min_radius_m(v, e, f), dtype=float)  # Eq. 9.2
    for e_row, row in std.min_radius_table.items():  # the published cells, to the table's rounding
        for speed, r_table in row.items():
            radius = np.where((e == e_row) & (v == speed), r_table, radius)
    return radius


@dataclass(frozen=True)
class MinRadiusCheck:
    """Whether a curve meets a standard's minimum radius at a posted speed."""

    meets: bool
    radius_m: float
    min_radius_m: float
    source: str  # "table" or "formula"
    f_max: float
    margin_m: float  # radius - R_min


def meets_min_radius(
    standard: DesignStandard | str,
    posted_speed_kmh: float,
    radius_m: float,
    max_superelevation_percent: float,
    bound: str | None = None,
) -> MinRadiusCheck:
    """Whether a curve's radius meets the standard's R_min for a posted speed.

    At a tabulated speed the published R_min is used where the standard tabulates it (what a designer reads
    off the table); at a posted speed between rows, or for a cell no source gives, Eq. 9.2 with f_max
    interpolated linearly in speed. The published values are rounded (AASHTO to 1 m, DNIT to 5 m), so at a
    tabulated speed the limit can differ from the formula's by up to that rounding.

    Parameters
    ----------
    standard : DesignStandard or str
        The standard or its id.
    posted_speed_kmh : float
        Posted (design) speed of the curve [km/h].
    radius_m : float
        Curve radius [m].
    max_superelevation_percent : float
        Maximum superelevation the road is designed to [%].
    bound : str, optional
        Table 21 bound, ``thesis-table21`` only [-].

    Returns
    -------
    MinRadiusCheck
    """
    std = resolve_standard(standard, bound)
    check_design_speeds(std, posted_speed_kmh, field="posted_speed_kmh")
    r = float(check_radii(radius_m))
    lim = min_radius_m(std, posted_speed_kmh, max_superelevation_percent)
    return MinRadiusCheck(r >= lim.radius_m, r, lim.radius_m, lim.source, lim.f_max, r - lim.radius_m)

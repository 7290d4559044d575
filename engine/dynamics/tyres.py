"""Truck tyres' linear cornering stiffness against vertical load, by tyre type, each from a readable table.

A tyre type is chosen per axle group (``tyre_type``, :mod:`engine.dynamics.parameters`); the axle's cornering
stiffness is then ``n_tyres x C(N)`` with ``C`` the type's stiffness at the tyre's static load ``N``. Every type keeps
the cells of its source as printed there, and one stated rule turns them into a stiffness (:attr:`TyreType.rule`):

* the TruckSim example tables ("Example Fy Data", 2000 / 3000 / 3500 kg load rating) are smooth carpets that are
  linear to 1 deg (the 2 deg row is 1.94-1.96 x the 1 deg row), so ``C = Fy(1 deg)`` per degree: the rule used since
  the yaw-roll model was written, kept so that the default answers do not change. The three tables are one
  normalised tyre scaled by its load rating (the 2000 and 3500 kg cells are the 3000 kg cells x 2/3 and x 7/6 at
  loads x 2/3 and x 7/6), so they differ only in where a given load falls on the curve;
* the two SAE tyres are measurements (SAE Cooperative Research program of the 1990s, a 295/75 | 275/80R22.5 steer
  tyre and drive tyre), scattered and, for the steer tyre, offset at zero slip (conicity and ply steer: -538 N to
  +2131 N at 0 deg), so ``C`` is the slope of the least-squares line through the measured points within +-2 deg:
  with the intercept for the steer tyre (rows -2, -1, 0, 1, 2 deg); through the origin for the drive tyre, whose
  table the source symmetrised and zeroed (rows 1 and 2 deg; the same line as the fit with intercept over the
  symmetric +-2 deg data);
* ``openpbs-constant`` is OpenPBS's one coefficient for every axle, 5.5 /rad of the axle's load.

Between the table's loads ``C`` is linear in the load; below its lowest load the coefficient ``C/N`` of that load is
kept (a line through the origin: assumed, the tables start at or above 4.9 kN a tyre); above its highest load it is
extended by the last two points (assumed).

Sources (the TruckSim 2022.1 / 2023.0 example database as published in github.com/Steve-Krug/Axicle,
``04-Trucksim/Tires/Fy/``; each file's ``FY_TIRE_CARPET`` table, load in N across, slip angle in deg down, lateral
force in N):

* ``TireFy_0c489aa9-7ede-4283-98f3-536301dc1dbe.par``: 'Fy: 2000 kg Load Rating', category 'Example Fy Data';
* ``TireFy_b8272e0f-2e5f-4858-a7d6-acdddd5b2c55.par``: 'Fy: 3000 kg Load Rating', 'Example Fy Data';
* ``TireFy_bd6c4a75-59f8-4c6a-883f-57341dd73d70.par``: 'Fy: 3500 kg Load Rating', 'Example Fy Data';
* ``TireFy_3dad5b50-dc94-4194-9ae4-ee937249cd75.par``: 'Fy; Steer Tire Asymmetric', category 'SAE Steer Tire';
  embedded notes: "a direct copy of the Fy data measured for a 295/75|275/80R22.5 steer tire" from "the SAE
  Cooperative Research program conducted in the 1990s";
* ``TireFy_97aa7f3c-7063-4c16-8664-d468aa6af3be.par``: 'Fy: Drive Tire Symmetric', category 'SAE Drive Tire';
  notes: the same program's 295/75|275/80R22.5 drive tyre "after removing asymmetries (i.e., adjusting for zero
  offset and averaging tests results for the left and right directions)";
* OpenPBS (github.com/performance-based-standards/OpenPBS), ``OpenPBS/Parameters/Base/VehicleModel.mo``:
  ``Cc = 5.5``, 'Cornering coefficient per axle'.

No trailer tyre, no 385/65R22.5 super-single and no 11R22.5 table could be read (UMTRI's 1986 factbook, Fancher et
al., UMTRI-86-12, has tyre tables but only its title pages were readable); those types are not offered.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

_AXICLE = "TruckSim example database (github.com/Steve-Krug/Axicle, 04-Trucksim/Tires/Fy/"


@dataclass(frozen=True)
class TyreType:
    """One tyre type: its source's cells and the rule that turns them into a cornering stiffness.

    ``loads_n`` are the table's vertical loads [N]; ``rows`` maps a slip angle [deg] to the lateral force at each
    load [N], as printed (sign included); ``rule`` is ``"1deg"``, ``"lsq-intercept"`` (least squares with an
    intercept over the rows) or ``"lsq-origin"`` (least squares through the origin over the rows); a type with a
    ``constant_per_rad`` has no table.
    """

    id: str
    name: str
    source: str
    rule: str
    loads_n: tuple[float, ...] = ()
    rows: tuple[tuple[float, tuple[float, ...]], ...] = ()
    constant_per_rad: float | None = None

    def table_stiffness_n_per_deg(self) -> np.ndarray:
        """The cornering stiffness at each of the table's loads [N/deg] (magnitude), by :attr:`rule`."""
        alpha = np.array([a for a, _ in self.rows])
        fy = np.array([f for _, f in self.rows])  # (rows, loads)
        if self.rule == "1deg":
            (row,) = [f for a, f in zip(alpha, fy, strict=True) if a == 1.0]
            return np.abs(row)
        if self.rule == "lsq-intercept":
            da = alpha - alpha.mean()
            return np.abs(da @ (fy - fy.mean(axis=0)) / (da @ da))
        if self.rule == "lsq-origin":
            return np.abs(alpha @ fy / (alpha @ alpha))
        raise ValueError(self.rule)

    def stiffness_n_per_rad(self, load_n: float) -> float:
        """One tyre's cornering stiffness at a vertical load [N/rad] (module docstring: between, below and above
        the table's loads)."""
        if self.constant_per_rad is not None:
            return self.constant_per_rad * load_n
        fz = np.array(self.loads_n)
        c = self.table_stiffness_n_per_deg()
        pos = fz > 0
        fz, c = fz[pos], c[pos]
        if load_n <= fz[0]:
            per_deg = c[0] / fz[0] * load_n
        elif load_n > fz[-1]:
            per_deg = c[-1] + (c[-1] - c[-2]) / (fz[-1] - fz[-2]) * (load_n - fz[-1])
        else:
            per_deg = float(np.interp(load_n, fz, c))
        return per_deg * 180.0 / math.pi  # as the model always computed it (bit for bit)


#: the TruckSim example tables' 1 deg row [N] at their loads [N]
TRUCKSIM_3000 = TyreType(
    "trucksim-3000kg",
    "TruckSim example tyre, 3000 kg load rating (the presets' tyre class: 305/75R22.5, 11.00R22, 12R24.5)",
    f"{_AXICLE}TireFy_b8272e0f-2e5f-4858-a7d6-acdddd5b2c55.par, 'Fy: 3000 kg Load Rating', FY_TIRE_CARPET, 1 deg "
    "row), the tyre of the '510 mm Radius (Trailer)' 3000 kg dataset the presets use",
    "1deg",
    (0.0, 7357.5, 14715.0, 29430.0, 44145.0, 58860.0),
    ((1.0, (0.0, 1253.8, 2418.0, 4477.9, 6179.4, 7612.3)),),
)
TRUCKSIM_2000 = TyreType(
    "trucksim-2000kg",
    "TruckSim example tyre, 2000 kg load rating",
    f"{_AXICLE}TireFy_0c489aa9-7ede-4283-98f3-536301dc1dbe.par, 'Fy: 2000 kg Load Rating', FY_TIRE_CARPET, 1 deg row)",
    "1deg",
    (0.0, 4905.0, 9810.0, 19620.0, 29430.0, 39240.0),
    ((1.0, (0.0, 835.9, 1612.0, 2985.2, 4119.6, 5074.9)),),
)
TRUCKSIM_3500 = TyreType(
    "trucksim-3500kg",
    "TruckSim example tyre, 3500 kg load rating",
    f"{_AXICLE}TireFy_bd6c4a75-59f8-4c6a-883f-57341dd73d70.par, 'Fy: 3500 kg Load Rating', FY_TIRE_CARPET, 1 deg row)",
    "1deg",
    (0.0, 8583.75, 17167.5, 34335.0, 51502.5, 68670.0),
    ((1.0, (0.0, 1462.8, 2821.0, 5224.2, 7209.3, 8881.1)),),
)
SAE_STEER = TyreType(
    "sae-steer-295-75r22.5",
    "steer tyre 295/75R22.5 | 275/80R22.5, measured (SAE Cooperative Research program, 1990s)",
    f"{_AXICLE}TireFy_3dad5b50-dc94-4194-9ae4-ee937249cd75.par, 'Fy; Steer Tire Asymmetric', category 'SAE Steer "
    "Tire', FY_TIRE_CARPET rows -2 to 2 deg; 'a direct copy of the Fy data measured for a 295/75|275/80R22.5 steer "
    "tire' in the SAE Cooperative Research program of the 1990s); least-squares slope with intercept over -2..2 deg",
    "lsq-intercept",
    (6868.0, 13736.0, 20604.0, 27468.0, 34336.0, 41204.0, 54936.0),
    (
        (-2.0, (1339.0, 3554.0, 5707.0, 7460.0, 10146.0, 10231.0, 11806.0)),
        (-1.0, (609.0, 1842.0, 3848.0, 4542.0, 5267.0, 5680.0, 7144.0)),
        (0.0, (-538.0, 22.0, 574.0, 867.0, 1406.0, 1637.0, 2131.0)),
        (1.0, (-1690.0, -1793.0, -2700.0, -2807.0, -2451.0, -2411.0, -2878.0)),
        (2.0, (-2624.0, -4172.0, -4866.0, -6050.0, -5889.0, -7380.0, -6548.0)),
    ),
)
SAE_DRIVE = TyreType(
    "sae-drive-295-75r22.5",
    "drive tyre 295/75R22.5 | 275/80R22.5, measured (SAE Cooperative Research program, 1990s), symmetrised",
    f"{_AXICLE}TireFy_97aa7f3c-7063-4c16-8664-d468aa6af3be.par, 'Fy: Drive Tire Symmetric', category 'SAE Drive "
    "Tire', FY_TIRE_CARPET rows 1 and 2 deg; the 295/75|275/80R22.5 drive tyre of the SAE Cooperative Research "
    "program, zero offset removed and left and right averaged by the source); least-squares slope through the "
    "origin over 0..2 deg",
    "lsq-origin",
    (6868.0, 13736.0, 20604.0, 27468.0, 34336.0, 41204.0, 54936.0),
    (
        (1.0, (1032.0, 1814.5, 2747.0, 3322.5, 3905.5, 4005.5, 4637.0)),
        (2.0, (1835.0, 3401.0, 4855.0, 6149.5, 7155.0, 7597.5, 8487.5)),
    ),
)
OPENPBS = TyreType(
    "openpbs-constant",
    "OpenPBS's constant coefficient: 5.5 /rad of the axle's load on every axle",
    "OpenPBS, OpenPBS/Parameters/Base/VehicleModel.mo: Cc = 5.5, 'Cornering coefficient per axle'",
    "constant",
    constant_per_rad=5.5,
)

#: every tyre type by id; the default is what the model used before tyre types existed
TYRE_TYPES: dict[str, TyreType] = {t.id: t for t in (TRUCKSIM_3000, TRUCKSIM_2000, TRUCKSIM_3500, SAE_STEER,
                                                     SAE_DRIVE, OPENPBS)}  # fmt: skip
DEFAULT_TYRE_TYPE = TRUCKSIM_3000.id

"""Result records of the engine (small frozen dataclasses the HTTP layer wraps)."""

from __future__ import annotations

from dataclasses import asdict, dataclass, field, fields
from typing import Any


@dataclass(frozen=True)
class Curves:
    """Quantities against the lateral acceleration, from rest to the limit (Figs. 92-97).

    Every list has one entry per value of ``ay_g``. Loads in kN, angles in degrees, lengths in m.
    Front entries are None for the 2D model (one axle group).
    """

    ay_g: list[float]
    fz_front_outer_kn: list[float] | None  # Fz1
    fz_front_inner_kn: list[float] | None  # Fz3
    fz_rear_outer_kn: list[float]  # Fz17 (2D: Fz1)
    fz_rear_inner_kn: list[float]  # Fz19 (2D: Fz3)
    llt_front: list[float] | None
    llt_rear: list[float]
    roll_angle_deg: list[float]  # theta_3D = theta17 + theta21 + theta23 + theta27 (2D: theta1+6+8)
    cg_lateral_m: list[float]  # h1 (Eq. 6.1 / 5.1)
    cg_height_m: list[float]  # h2 (Eq. 6.2 / 5.2)

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)


@dataclass(frozen=True)
class TireLoads:
    """Tire normal loads at one state [kN] (thesis numbering: 1/3 front outer/inner, 17/19 rear)."""

    front_outer_kn: float | None
    front_inner_kn: float | None
    rear_outer_kn: float
    rear_inner_kn: float


@dataclass(frozen=True)
class LiftEvent:
    """An axle group's inner tyres leaving the road: the unit, the group and the lateral acceleration [g]."""

    unit: str
    group: str
    ay_g: float


@dataclass(frozen=True)
class GroupState:
    """One axle group at a roll-coupled unit's limit.

    llt : lateral load transfer (Fz_outer - Fz_inner) / (Fz_outer + Fz_inner) [-]
    outer_kn / inner_kn : the normal loads of the outer and inner tyre lines [kN]
    axle_roll_deg : the axle's roll relative to the road (tyre deflection) [deg]
    suspension_moment_knm : the roll moment the suspension passes between the axle and the sprung mass [kN m]
    lifted : the inner tyres are off the road [-]
    """

    unit: str
    group: str
    llt: float
    outer_kn: float
    inner_kn: float
    axle_roll_deg: float
    suspension_moment_knm: float
    lifted: bool


@dataclass(frozen=True)
class CouplingState:
    """A coupling at a roll-coupled unit's limit: the roll moment it passes [kN m] and the vertical load [kN]."""

    towing_unit: str
    towed_unit: str
    kind: str
    roll_moment_knm: float
    vertical_load_kn: float


@dataclass(frozen=True)
class RollCoupledUnitResult:
    """The SRT of one roll-coupled unit (units joined by fifth wheels / B-couplings) and its state there.

    units : the ids of its units, front to rear [-]
    srt : the largest lateral acceleration it holds, or where a group reached the LLT limit [g]
    limit : ``"rollover"`` (the largest ay it holds: past it every equilibrium needs less) or ``"llt-limit"``
    ended_by : what happened at the limit, in words [-]
    roll_angle_deg : each unit's sprung-mass roll relative to the road [deg]
    groups / couplings : the state of every group and coupling at the limit
    lift_sequence : the groups whose inner tyres left the road, in order, up to the limit
    """

    units: tuple[str, ...]
    srt: float
    limit: str
    ended_by: str
    roll_angle_deg: dict[str, float]
    groups: tuple[GroupState, ...]
    couplings: tuple[CouplingState, ...]
    lift_sequence: tuple[LiftEvent, ...]

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)


@dataclass(frozen=True)
class CombinationDetail:
    """The whole-combination answer: every roll-coupled unit, the governing one, and the ratio for the 3D model.

    governing : index into ``roll_coupled_units`` of the lowest SRT [-]
    last_unit_front_llt_ratio : LLTf/LLTr of the last unit (its front support is the towing unit's group under
        its coupling) when its own group reaches the LLT limit, or at its roll-coupled unit's limit if that
        comes first [-]
    """

    roll_coupled_units: tuple[RollCoupledUnitResult, ...]
    governing: int
    last_unit_front_llt_ratio: float | None

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)


@dataclass(frozen=True)
class RolloverResult:
    """Static rollover threshold of one vehicle on one road with one load case.

    srt : lateral acceleration at the limit, ay/g [g]
    roll_angle_deg : total body roll at the limit [deg] (None for the rigid closed forms)
    limit : what ended the load ramp: ``"rear-inner-lift-off"`` (Fz19 = 0), ``"rear-llt-limit"`` (LLTr
        reached ``rear_llt_limit``) or ``"closed-form"`` (Ch. 2 models)
    stage_values : for the 3D model, ``{"srt_ts": ..., "srt_3d": ...}`` (tires+suspension only, and the
        full system) when both were computed
    """

    model: str
    stage: str | None
    srt: float
    roll_angle_deg: float | None
    limit: str
    rear_llt_limit: float
    llt_front: float | None = None
    llt_rear: float | None = None
    tire_loads: TireLoads | None = None
    cg_lateral_m: float | None = None
    cg_height_m: float | None = None
    stage_values: dict[str, float] = field(default_factory=dict)
    iterations: int | None = None
    parameters: dict[str, float] = field(default_factory=dict)
    curves: Curves | None = None
    notes: list[str] = field(default_factory=list)  # caveats about this case (e.g. kingpin uplift)
    combination: CombinationDetail | None = None  # the whole-combination model's per-unit answer

    def to_dict(self) -> dict[str, Any]:
        """A plain dict, as ``dataclasses.asdict`` gives it (copies of the dicts and lists) without its recursive
        deep copy of every float: the service does this for every answer."""
        out = {name: getattr(self, name) for name in _RESULT_FIELDS}
        out["stage_values"] = dict(self.stage_values)
        out["parameters"] = dict(self.parameters)
        out["notes"] = list(self.notes)
        if self.tire_loads is not None:
            out["tire_loads"] = {name: getattr(self.tire_loads, name) for name in _TIRE_LOAD_FIELDS}
        if self.curves is not None:
            out["curves"] = self.curves.to_dict()
        if self.combination is not None:
            out["combination"] = self.combination.to_dict()
        else:  # only the whole-combination model has it
            del out["combination"]
        return out


_RESULT_FIELDS = tuple(f.name for f in fields(RolloverResult))
_TIRE_LOAD_FIELDS = tuple(f.name for f in fields(TireLoads))

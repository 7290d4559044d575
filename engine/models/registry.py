"""The model registry: one entry per SRT model, used by every place that needs to know the models.

An entry says what the model is (id, name, equations, reference, one-line summary), what it needs (the vehicle
fields beyond the rear group's, whether it models the front group as a mechanism), which road and load inputs it
accounts for (``takes``: it refuses the others when non-zero, rather than ignore them), whether it has curves
against ay/g, and how to solve one case (``solve``) and many cases of one vehicle at once (``batch``, None when
the model is solved case by case). :func:`engine.models.rollover_threshold`, the sweeps, the vehicle
validation, the presets' model lists and the HTTP layer's model list all read this table: adding a model is one
entry here.

References
----------
Thesis Ch. 2 (closed forms), Ch. 5 (2D), Ch. 6 (3D); Gillespie (1992); Winkler et al. (1992); Navin (1992);
Chang (2001); Rill (2011).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from engine.case import Case, check_case, check_road, check_stage_and_limit
from engine.errors import InvalidInput, InvalidLoad, InvalidRoad, MissingParameter
from engine.models import classic, combination_batch, stepping
from engine.models import combination as whole
from engine.results import RolloverResult
from engine.vehicle.combination import (
    Combination,
    UnitLoad,
    check_combination_load,
    kingpin_group,
    validate_combination,
)
from engine.vehicle.record import Vehicle, validate_vehicle

#: every road/load input a model may account for: (name in ``takes``, request field, getter, error class)
INPUTS: tuple[tuple[str, str, Callable[[Case], float], type[InvalidInput]], ...] = (
    ("bank", "road.bank_percent", lambda c: c.road.bank_percent, InvalidRoad),
    ("slope", "road.slope_percent", lambda c: c.road.slope_percent, InvalidRoad),
    ("trailer_angle", "trailer_angle_deg", lambda c: c.trailer_angle_deg, InvalidRoad),
    ("d1", "load.lateral_offset_m", lambda c: c.load.lateral_offset_m, InvalidLoad),
    ("d2", "load.longitudinal_offset_m", lambda c: c.load.longitudinal_offset_m, InvalidLoad),
    ("d3", "load.vertical_offset_m", lambda c: c.load.vertical_offset_m, InvalidLoad),
    ("overweight", "load.overweight_percent", lambda c: c.load.overweight_percent, InvalidLoad),
)
ALL_INPUTS = (*(i[0] for i in INPUTS), "rear_llt_limit", "stage")

_WHEELBASE = ("wheelbase_m", "front_axle_to_cg_m")
_FRONT_GROUP = ("front_track_m", "front_axle_width_m", "front_axles", "front_tires_per_axle")


@dataclass(frozen=True)
class Model:
    """One SRT model (see the module docstring)."""

    id: str
    name: str
    equation: str
    reference: str
    summary: str
    takes: tuple[str, ...]
    requires: tuple[str, ...] = ()
    front_group: bool = False
    curves: bool = False
    solve: Callable[..., RolloverResult] | None = None
    batch: Callable[..., Any] | None = None
    #: solves a :class:`~engine.vehicle.Combination` itself (else it sees a combination's last unit as a record,
    #: :func:`record_view`), and which road and load inputs it then accounts for
    solve_combination: Callable[..., RolloverResult] | None = None
    combination_takes: tuple[str, ...] = ()
    #: solves a vehicle record (False: a combination only)
    records: bool = True

    def validate(self, vehicle: Vehicle | Combination) -> None:
        """Refuse a vehicle this model cannot use (:func:`engine.vehicle.validate_vehicle` with its needs, or
        :func:`engine.vehicle.validate_combination`)."""
        if isinstance(vehicle, Combination):
            if self.solve_combination is not None:
                validate_combination(vehicle)
                return
            record = last_unit_record(vehicle)
            requires = tuple(n for n in self.requires if n != "front_llt_ratio")  # computed (record_view)
            validate_vehicle(record, requires=requires, front_group=self.front_group)
            return
        if not self.records:
            raise InvalidInput(
                f"the {self.id} model needs a combination (a preset of GET /v1/combinations or "
                '{"combination": {...}}), not a single vehicle record',
                field="model",
                value=self.id,
            )
        validate_vehicle(vehicle, requires=self.requires, front_group=self.front_group)

    def supports(self, vehicle: Vehicle | Combination) -> bool:
        """Whether the vehicle has what this model needs (a combination: itself, or its last unit's record; the
        front LLT ratio of a combination's last unit is computed)."""
        if isinstance(vehicle, Combination):
            if self.solve_combination is not None:
                return True
            if vehicle.last_unit_record is None:
                return False
            return all(
                getattr(vehicle.last_unit_record, n) is not None for n in self.requires if n != "front_llt_ratio"
            )
        return self.records and all(getattr(vehicle, n) is not None for n in self.requires)

    def check(self, case: Case, *, vehicle: bool = True) -> None:
        """Refuse a case outside this model's domain, before solving: the vehicle (unless ``vehicle`` is False: the
        caller validated this record already), the road and load inputs (within the engine's bounds, and only those
        the model accounts for), the stage and the LLT limit."""
        check_stage_and_limit(case)
        if vehicle:
            self.validate(case.vehicle)
        native = isinstance(case.vehicle, Combination) and self.solve_combination is not None
        if native:
            check_road(case.road, case.trailer_angle_deg)
            check_combination_load(case.vehicle, _unit_load(case))
        else:
            check_case(case.vehicle, case.road, case.trailer_angle_deg, case.load)
        takes = self.combination_takes if native else self.takes
        for key, name, get, exc in INPUTS:
            value = get(case)
            if value != 0 and key not in takes:
                raise exc(
                    f"the {self.id} model ({self.equation}) does not account for {name}; use a model that does "
                    f"({', '.join(m.id for m in MODELS.values() if key in m.takes)})",
                    field=name,
                    value=value,
                )
        if case.rear_llt_limit != 1.0 and "rear_llt_limit" not in takes:
            raise InvalidLoad(
                f"the {self.id} model is defined at wheel lift-off only (LLT = 1)",
                field="rear_llt_limit",
                value=case.rear_llt_limit,
            )


def _unit_load(case: Case) -> UnitLoad:
    ld = case.load
    return UnitLoad(ld.lateral_offset_m, ld.longitudinal_offset_m, ld.vertical_offset_m, ld.overweight_percent)


def last_unit_record(c: Combination) -> Vehicle:
    """The combination's last unit as the thesis's record (its ``last_unit_record``), with the combination's explicit
    ``front_llt_ratio`` when it gives one; :class:`MissingParameter` when the combination has no record."""
    if c.last_unit_record is None:
        raise MissingParameter(
            "this model sees the last unit of a combination through its thesis record, and the combination gives "
            "none (combination.last_unit_record); use the combination or rigid model",
            field="combination.last_unit_record",
        )
    if c.front_llt_ratio is not None:
        return c.last_unit_record.replace(front_llt_ratio=c.front_llt_ratio)
    return c.last_unit_record


def record_view(case: Case) -> tuple[Case, str | None]:
    """The case as a record model sees it: a combination's last unit as its thesis record, whose front support (the
    towing unit's group under the fifth wheel) acts through LLTf/LLTr computed by the whole-combination model on a
    level road with the nominal load at the case's LLT limit (the reference case of the 3D model's chassis-constant
    closure, docs/model.md), unless the combination gives ``front_llt_ratio``. Returns the case and a note saying
    where the ratio came from (None for a record, or for a model that solves combinations itself)."""
    c = case.vehicle
    model = get_model(case.model)
    if not isinstance(c, Combination) or model.solve_combination is not None:
        return case, None
    validate_combination(c)
    record = last_unit_record(c)
    model.validate(c)  # the last unit's record, before the combination is solved for its ratio
    if c.front_llt_ratio is not None:
        note = f"front_llt_ratio = {c.front_llt_ratio:g} as the combination gives it (combination.front_llt_ratio)"
        return case.replace(vehicle=record), note
    detail = whole.solve_combination(c, llt_limit=case.rear_llt_limit)
    ratio = detail.last_unit_front_llt_ratio
    if ratio is None or not 0.0 < ratio <= 1.0:
        raise InvalidInput(
            f"the whole-combination model gives LLTf/LLTr = {ratio} for the last unit, outside (0, 1]: its front "
            "support takes more load transfer than its own group; give combination.front_llt_ratio explicitly",
            field="combination.front_llt_ratio",
            value=ratio,
        )
    last = c.last_unit
    note = (
        f"front_llt_ratio = {ratio:.4f}: LLTf/LLTr of {last.id!r} computed by the whole-combination model (its own "
        f"group at LLT {case.rear_llt_limit:g} on a level road with the nominal load) instead of an assumed value"
    )
    return case.replace(vehicle=record.replace(front_llt_ratio=ratio)), note


def _solve_whole(case: Case, **_options: Any) -> RolloverResult:
    """The whole-combination model: the governing (lowest) roll-coupled unit's SRT, with every unit's answer."""
    c: Combination = case.vehicle  # type: ignore[assignment]
    detail = whole.solve_combination(
        c,
        bank_percent=case.road.bank_percent,
        slope_percent=case.road.slope_percent,
        load=_unit_load(case),
        llt_limit=case.rear_llt_limit,
    )
    gov = detail.roll_coupled_units[detail.governing]
    last = detail.roll_coupled_units[-1]
    rear = next(g for g in last.groups if g.unit == c.last_unit.id)
    front = None
    if len(c.units) > 1 and c.couplings[-1].transmits_roll:
        fu, fg = kingpin_group(c, len(c.units) - 1)
        front = next(g for g in last.groups if (g.unit, g.group) == (c.units[fu].id, c.units[fu].groups[fg].id))
    params = {}
    if detail.last_unit_front_llt_ratio is not None:
        params["last_unit_front_llt_ratio"] = detail.last_unit_front_llt_ratio
    return RolloverResult(
        model="combination",
        stage=None,
        srt=gov.srt,
        roll_angle_deg=max(gov.roll_angle_deg.values()),
        limit="rear-llt-limit" if gov.limit == "llt-limit" else "rollover",
        rear_llt_limit=case.rear_llt_limit,
        llt_front=None if front is None else front.llt,
        llt_rear=rear.llt,
        parameters=params,
        combination=detail,
    )


def _solve_rigid_whole(case: Case, **_options: Any) -> RolloverResult:
    """The rigid roll-coupled units (no compliance): sum(N T/2 - W d1) / sum(W h) on a level road, per unit."""
    srts = whole.rigid_srt(
        case.vehicle, bank_percent=case.road.bank_percent, slope_percent=case.road.slope_percent, load=_unit_load(case)
    )  # type: ignore[arg-type]
    gov = min(range(len(srts)), key=srts.__getitem__)
    return RolloverResult(
        model="rigid",
        stage=None,
        srt=srts[gov],
        roll_angle_deg=None,
        limit="closed-form",
        rear_llt_limit=1.0,
        parameters={f"roll_coupled_unit_{k}_srt": v for k, v in enumerate(srts)},
    )


def _closed_form(solver: Callable[[Case], classic.ClassicResult]) -> Callable[..., RolloverResult]:
    """A closed form of Ch. 2 as a model solve (no curves, no stages, no LLT limit below 1)."""

    def solve(case: Case, **_options: Any) -> RolloverResult:
        r = solver(case)
        return RolloverResult(
            model=r.model,
            stage=None,
            srt=r.srt,
            roll_angle_deg=r.roll_angle_deg,
            limit="closed-form",
            rear_llt_limit=1.0,
            parameters=r.parameters,
        )

    return solve


_PLANAR = ("d1", "d2", "d3", "overweight")

MODELS: dict[str, Model] = {
    m.id: m
    for m in (
        Model(
            "3d",
            "Developed 3D trailer model",
            "Eqs. 6.1-6.2, 6.17-6.18",
            "Moreno (thesis), Ch. 6",
            "Davies-method mechanism of the last trailer: tires, leaf springs, fifth wheel, chassis.",
            takes=ALL_INPUTS,
            requires=(*_FRONT_GROUP, *_WHEELBASE, "front_llt_ratio"),
            front_group=True,
            curves=True,
            solve=stepping.solve_3d,
            batch=stepping.batch_3d,
        ),
        Model(
            "2d",
            "Developed 2D trailer model",
            "Eqs. 5.1-5.2, 5.22",
            "Moreno (thesis), Ch. 5",
            "Planar mechanism of one axle group: tires and leaf-spring suspension.",
            takes=("bank", *_PLANAR, "rear_llt_limit"),
            curves=True,
            solve=stepping.solve_2d,
            batch=stepping.batch_2d,
        ),
        Model(
            "rigid",
            "Rigid vehicle",
            "Eq. 2.6",
            "Gillespie (1992)",
            "SRT = t/2h.",
            takes=("d1", "d3"),
            solve=_closed_form(classic.solve_rigid),
            solve_combination=_solve_rigid_whole,
            combination_takes=("bank", "slope", *_PLANAR),
        ),
        Model(
            "rigid-bank",
            "Rigid vehicle on a banked road",
            "Eq. 2.8",
            "Chang (2001)",
            "SRT = t/2h + e.",
            takes=("bank", "d1", "d3"),
            solve=_closed_form(classic.solve_rigid_bank),
        ),
        Model(
            "winkler",
            "Winkler model",
            "Eq. 2.10",
            "Winkler et al. (1992)",
            "SRT = (t/2 - Delta t)/h2, CG shift from roll compliance.",
            takes=_PLANAR,
            solve=_closed_form(classic.solve_winkler),
        ),
        Model(
            "rill",
            "Rill model",
            "Eq. 2.20",
            "Rill (2011)",
            "Tire and suspension roll compliance, small angles.",
            takes=_PLANAR,
            solve=_closed_form(classic.solve_rill),
        ),
        Model(
            "chang",
            "Chang model",
            "Eq. 2.22",
            "Chang (2001)",
            "Suspension roll on a banked road.",
            takes=("bank", *_PLANAR),
            solve=_closed_form(classic.solve_chang),
        ),
        Model(
            "gillespie",
            "Gillespie model",
            "Eq. 2.28",
            "Gillespie (1992)",
            "Roll about the axis through front and rear roll centres.",
            takes=_PLANAR,
            requires=("front_axles", "front_tires_per_axle"),
            solve=_closed_form(classic.solve_gillespie),
        ),
        Model(
            "navin",
            "Navin model",
            "Eq. 2.30",
            "Navin (1992)",
            "Roll axis from the fifth wheel to the rear outer tire.",
            takes=("bank", *_PLANAR),
            requires=_WHEELBASE,
            solve=_closed_form(classic.solve_navin),
        ),
        Model(
            "combination",
            "Whole-combination static roll model",
            "UMTRI static roll model; Eqs. 2.5, 2.11, 4.24-4.27",
            "Ervin (1986); Winkler and Fancher (1992); Winkler and Ervin (1999), UMTRI-99-19",
            "Every unit, axle group and coupling in roll: tyres, suspensions with roll centres and lash, fifth "
            "wheels; the SRT of each roll-coupled unit, stepped from lift-off to lift-off.",
            takes=(),
            curves=False,
            batch=combination_batch.batch,
            solve_combination=_solve_whole,
            combination_takes=("bank", "slope", *_PLANAR, "rear_llt_limit"),
            records=False,
        ),
    )
}
MODEL_IDS = tuple(MODELS)


def get_model(model_id: str) -> Model:
    """The registered model with this id; :class:`InvalidInput` naming the known ids otherwise."""
    try:
        return MODELS[model_id]
    except (KeyError, TypeError):
        raise InvalidInput(
            f"model must be one of {', '.join(MODELS)}, got {model_id!r}", field="model", value=model_id
        ) from None


def supported_models(vehicle: Vehicle) -> list[str]:
    """The ids of the models whose required fields the record has (a preset's model list)."""
    return [m.id for m in MODELS.values() if m.supports(vehicle)]

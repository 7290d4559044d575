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

from engine.case import Case, check_case, check_stage_and_limit
from engine.errors import InvalidInput, InvalidLoad, InvalidRoad
from engine.models import classic, stepping
from engine.results import RolloverResult
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

    def validate(self, vehicle: Vehicle) -> None:
        """Refuse a record this model cannot use (:func:`engine.vehicles.validate_vehicle` with its needs)."""
        validate_vehicle(vehicle, requires=self.requires, front_group=self.front_group)

    def supports(self, vehicle: Vehicle) -> bool:
        """Whether the record has every field this model needs."""
        return all(getattr(vehicle, n) is not None for n in self.requires)

    def check(self, case: Case, *, vehicle: bool = True) -> None:
        """Refuse a case outside this model's domain, before solving: the vehicle (unless ``vehicle`` is False: the
        caller validated this record already), the road and load inputs (within the engine's bounds, and only those
        the model accounts for), the stage and the LLT limit."""
        check_stage_and_limit(case)
        if vehicle:
            self.validate(case.vehicle)
        check_case(case.vehicle, case.road, case.trailer_angle_deg, case.load)
        for key, name, get, exc in INPUTS:
            value = get(case)
            if value != 0 and key not in self.takes:
                raise exc(
                    f"the {self.id} model ({self.equation}) does not account for {name}; use a model that does "
                    f"({', '.join(m.id for m in MODELS.values() if key in m.takes)})",
                    field=name,
                    value=value,
                )
        if case.rear_llt_limit != 1.0 and "rear_llt_limit" not in self.takes:
            raise InvalidLoad(
                f"the {self.id} model is defined at wheel lift-off only (LLT = 1)",
                field="rear_llt_limit",
                value=case.rear_llt_limit,
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

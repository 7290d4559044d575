"""A combination vehicle in and out: units, axle groups and couplings (the records of engine.vehicle.combination).

A combination is given wherever a vehicle is taken, as a preset id of ``GET /v1/combinations`` or as
``{"combination": {...}}``; its values are checked by the engine (plausible ranges with the likely unit slip, a
roll centre below the CG, a fifth wheel on its group, every support loaded: a 422 naming the field as typed).
"""

from __future__ import annotations

from typing import Literal

from pydantic import Field

from app.http.schemas import InputModel, OutputModel, describe, json_int
from app.vehicle_forms.schemas import VehicleRecord
from engine.vehicle import COUPLING_KINDS, UNIT_KINDS

UnitKind = Literal[tuple(UNIT_KINDS)]  # type: ignore[valid-type]
CouplingKind = Literal[tuple(COUPLING_KINDS)]  # type: ignore[valid-type]
_REF = "; ".join(f"{k}: {v[0]}" for k, v in UNIT_KINDS.items())


class AxleGroupIn(InputModel):
    """One axle group: load-sharing axles under one suspension, with per-axle values."""

    id: str = Field(min_length=1, max_length=40, description=describe("A name unique within its unit.", unit="-"))
    axles: json_int(ge=1, le=8) = Field(description=describe("Number of axles.", unit="count"))  # type: ignore[valid-type]
    tyres_per_axle: json_int(ge=2, le=8, multiple_of=2) = Field(  # type: ignore[valid-type]
        description=describe("Tyres per axle: 2 single, 4 dual.", unit="count")
    )
    track_m: float = Field(
        description=describe("Track: tyre-contact spacing; for duals between the centres of the pairs.", unit="m",
                             symbol="T")
    )  # fmt: skip
    position_m: float = Field(
        description=describe(f"The group centre behind the unit's reference point ({_REF}).", unit="m")
    )
    tyre_stiffness_kn_per_m: float = Field(
        description=describe("Vertical (radial) rate of one tyre.", unit="kN/m", symbol="kT")
    )
    roll_stiffness_knm_per_rad: float = Field(
        description=describe("Suspension roll stiffness of one axle (springs and anti-roll).", unit="kN m/rad",
                             symbol="k_theta (Eq. 2.11: kLs b^2/2 for leaf springs)")
    )  # fmt: skip
    roll_centre_height_m: float = Field(
        description=describe("Height of the suspension's roll centre above the road.", unit="m", symbol="h_r")
    )
    unsprung_mass_kg: float = Field(description=describe("Mass of one axle with wheels and tyres.", unit="kg"))
    unsprung_cg_height_m: float = Field(
        description=describe("Height of the unsprung CG above the road (about the loaded radius).", unit="m")
    )
    lash_deg: float = Field(
        0.0, description=describe("Suspension roll free play, each way from centre.", unit="deg", symbol="lash")
    )
    spring_spacing_m: float | None = Field(
        None, description=describe("Lateral spring spacing (recorded).", unit="m", symbol="b")
    )
    steer: bool = Field(False, description=describe("A steer group (left out of the LLT limit).", unit="-"))


class UnitIn(InputModel):
    """One unit of the combination."""

    id: str = Field(
        min_length=1, max_length=40, description=describe("A name unique within the combination.", unit="-")
    )
    kind: UnitKind = Field(description=describe(f"The unit's kind (its reference point: {_REF}).", unit="-"))
    sprung_mass_kg: float = Field(description=describe("The sprung mass: body, tare and payload, no axles.", unit="kg"))
    cg_height_m: float = Field(description=describe("Sprung CG height above the road.", unit="m", symbol="h"))
    cg_position_m: float = Field(description=describe("Sprung CG behind the unit's reference point.", unit="m"))
    groups: list[AxleGroupIn] = Field(
        min_length=1, max_length=2, description=describe("Axle groups, front to rear.", unit="-")
    )
    title: str | None = Field(None, max_length=200, description=describe("A name for people.", unit="-"))


class CouplingIn(InputModel):
    """The coupling between a unit (towing) and the next one (towed)."""

    kind: CouplingKind = Field(
        description=describe("`fifth-wheel` (tractor, dolly), `b-coupling` (B-train lead trailer) or `pintle` "
                             "(drawbar: no roll moment).", unit="-")
    )  # fmt: skip
    position_m: float = Field(description=describe("On the towing unit, behind its reference point.", unit="m"))
    height_m: float = Field(description=describe("Height of the plate or pintle above the road.", unit="m"))
    roll_stiffness_knm_per_rad: float | None = Field(
        None, description=describe("Roll stiffness of a fifth wheel; null for a pintle.", unit="kN m/rad")
    )
    lash_deg: float = Field(0.0, description=describe("Roll free play each way before it takes a moment.", unit="deg"))


class CombinationIn(InputModel):
    """A combination vehicle: its units front to rear and the couplings between them."""

    units: list[UnitIn] = Field(min_length=1, max_length=8, description=describe("Units, towing first.", unit="-"))
    couplings: list[CouplingIn] = Field(
        default_factory=list,
        max_length=7,
        description=describe("One coupling between each two consecutive units.", unit="-"),
    )
    title: str | None = Field(None, max_length=200, description=describe("A name for people.", unit="-"))
    last_unit_record: VehicleRecord | None = Field(  # type: ignore[valid-type]
        None,
        description=describe(
            "The last unit as the thesis's vehicle record, for the 3D model of the last unit (its front_llt_ratio "
            "is computed by the whole-combination model unless `front_llt_ratio` is given).",
            unit="-",
        ),
    )
    front_llt_ratio: float | None = Field(
        None,
        gt=0,
        le=1,
        description=describe(
            "LLTf/LLTr for the 3D model of the last unit, given instead of computed.", unit="-", symbol="LLTf/LLTr"
        ),
    )

    def engine_dict(self) -> dict:
        data = self.model_dump()
        if self.last_unit_record is not None:
            data["last_unit_record"] = self.last_unit_record.record()
        return data


class CombinationRef(InputModel):
    """``{"combination": {...}}``: a combination given in full."""

    combination: CombinationIn = Field(description=describe("The combination.", unit="-"))


# ------------------------------------------------------------------------------------------------ out


class CombinationPresetSummary(OutputModel):
    """A combination preset in the list."""

    id: str = Field(description=describe("Preset id, usable as `vehicle` in the POST endpoints.", unit="-"))
    title: str = Field(description=describe("What the combination is.", unit="-"))
    summary: str = Field(description=describe("In a sentence.", unit="-"))
    units: list[str] = Field(description=describe("Its units' kinds, front to rear.", unit="-"))
    roll_coupled_units: list[list[str]] = Field(
        description=describe("The units that roll together (cut at every pintle).", unit="-")
    )
    models: list[str] = Field(description=describe("Model ids it can be solved with.", unit="-"))


class CombinationPreset(CombinationPresetSummary):
    """A combination preset in full, with the source of every value."""

    combination: dict = Field(description=describe('The combination (as `{"combination": ...}` takes it).', unit="-"))
    sources: dict[str, str] = Field(
        description=describe("Where each value comes from: field path -> source (or 'assumed' and why).", unit="-")
    )


class LiftEventOut(OutputModel):
    unit: str = Field(description=describe("Unit id.", unit="-"))
    group: str = Field(description=describe("Axle group id.", unit="-"))
    ay_g: float = Field(description=describe("Lateral acceleration at which its inner tyres lift off.", unit="g"))


class GroupStateOut(OutputModel):
    unit: str = Field(description=describe("Unit id.", unit="-"))
    group: str = Field(description=describe("Axle group id.", unit="-"))
    llt: float = Field(description=describe("Lateral load transfer at the limit.", unit="-", symbol="LLT (Eq. 2.5)"))
    outer_kn: float = Field(description=describe("Outer tyre line's normal load.", unit="kN"))
    inner_kn: float = Field(description=describe("Inner tyre line's normal load.", unit="kN"))
    axle_roll_deg: float = Field(description=describe("Axle roll relative to the road.", unit="deg"))
    suspension_moment_knm: float = Field(description=describe("Roll moment through the suspension.", unit="kN m"))
    lifted: bool = Field(description=describe("The inner tyres are off the road.", unit="-"))


class CouplingStateOut(OutputModel):
    towing_unit: str = Field(description=describe("Towing unit id.", unit="-"))
    towed_unit: str = Field(description=describe("Towed unit id.", unit="-"))
    kind: str = Field(description=describe("Coupling kind.", unit="-"))
    roll_moment_knm: float = Field(description=describe("Roll moment it passes at the limit.", unit="kN m"))
    vertical_load_kn: float = Field(description=describe("Vertical load it passes at the limit.", unit="kN"))


class RollCoupledUnitOut(OutputModel):
    """One roll-coupled unit's SRT and its state at the limit."""

    units: list[str] = Field(description=describe("Its units, front to rear.", unit="-"))
    srt: float = Field(description=describe("Its static rollover threshold on this road.", unit="g", symbol="SRT"))
    limit: str = Field(
        description=describe("`rollover` (the largest ay it holds) or `llt-limit` (a group at the limit).", unit="-")
    )
    ended_by: str = Field(description=describe("What happened at the limit, in words.", unit="-"))
    roll_angle_deg: dict[str, float] = Field(description=describe("Each unit's sprung-mass roll.", unit="deg"))
    groups: list[GroupStateOut] = Field(description=describe("Every axle group at the limit.", unit="-"))
    couplings: list[CouplingStateOut] = Field(description=describe("Every coupling at the limit.", unit="-"))
    lift_sequence: list[LiftEventOut] = Field(description=describe("Lift-offs in order, up to the limit.", unit="-"))

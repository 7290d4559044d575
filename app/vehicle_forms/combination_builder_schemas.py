"""The combination builder over HTTP: ``POST /v1/combinations/build`` and ``{"combination_spec": {...}}`` as a vehicle.

The spec's models are generated from the engine's dataclasses (:mod:`engine.builder.combination`) by the
single-unit builder's generator (:func:`app.vehicle_forms.builder_schemas.spec_model`): fields, types, defaults and each
field's description and unit from the dataclass docstring, so the published schema and the engine cannot drift.
The tare, payloads and deck are the single-unit spec's own models. The engine checks what a schema cannot say (a
roll centre above the CG, a fifth wheel behind its group, a dolly towing nothing, a tare typed in tonnes) and
answers 422 naming the spec field as typed (``combination_spec.units[1].tare.mass_kg``).
"""

from __future__ import annotations

from typing import Any

from pydantic import ConfigDict, Field

from app.http.schemas import InputModel, OutputModel, describe
from app.vehicle_forms import builder_schemas as bs
from app.vehicle_forms.builder_schemas import DerivationOut, MassOut
from app.vehicle_forms.dynamic_data_schemas import GroupDynamicsSpec, UnitDynamicsSpec
from engine import builder as ec
from engine.vehicle import FIFTH_WHEELS, SUSPENSIONS_IN_ROLL, UNIT_KINDS

bs._CHOICES.update(
    {
        ("UnitSpec", "kind"): tuple(UNIT_KINDS),
        ("CouplingSpec", "kind"): ec.SPEC_COUPLING_KINDS,
        ("CouplingSpec", "fifth_wheel"): tuple(FIFTH_WHEELS),
        ("RollSuspensionSpec", "type"): tuple(SUSPENSIONS_IN_ROLL),
    }
)
# the yaw-roll model's data of a unit and of a group: generated from its one definition, not from a dataclass docstring
bs.MODELS["UnitData"], bs.MODELS["GroupData"] = UnitDynamicsSpec, GroupDynamicsSpec
for _cls in (
    ec.RollTyreSpec,
    ec.RollSuspensionSpec,
    ec.UnitGroupSpec,
    ec.CouplingSpec,
    ec.UnitSpec,
    ec.CombinationSpec,
):
    bs.MODELS[_cls.__name__] = bs.spec_model(_cls)

CombinationSpecIn = bs.MODELS["CombinationSpec"]

#: a 6x4 tractor and a tri-axle semitrailer with 22 t on its deck, as one would measure them
EXAMPLE_COMBINATION_SPEC: dict[str, Any] = {
    "title": "6x4 tractor and tri-axle semitrailer",
    "units": [
        {
            "kind": "tractor",
            "axle_groups": [
                {"axles": 1, "tyres_per_axle": 2, "track_m": 2.03, "position_m": 0.0, "tyre": {"size": "295/80R22.5"},
                 "suspension": {"type": "trucksim-steer-leaf-5.5t"}},
                {"axles": 2, "tyres_per_axle": 4, "track_m": 1.863, "position_m": 4.3, "axle_spacing_m": 1.3,
                 "tyre": {"size": "295/80R22.5"}, "suspension": {"type": "trucksim-tandem-leaf-15.5t"}},
            ],
            "tare": {"mass_kg": 8000.0, "cg_height_m": 1.0, "cg_from_kingpin_m": 1.9},
        },
        {
            "kind": "semitrailer",
            "axle_groups": [
                {"axles": 3, "tyres_per_axle": 4, "track_m": 1.863, "position_m": 9.5, "axle_spacing_m": 1.31,
                 "tyre": {"size": "295/80R22.5"}, "suspension": {"type": "trucksim-trailer-leaf-18t"}},
            ],
            "tare": {"mass_kg": 7500.0, "cg_height_m": 1.1, "cg_from_kingpin_m": 6.0},
            "deck": {"front_from_kingpin_m": -1.2, "length_m": 13.6},
            "payloads": [{"mass_kg": 22000.0, "deck_height_m": 1.3, "load_height_m": 2.6}],
        },
    ],
    "couplings": [
        {"kind": "fifth-wheel", "position_m": 4.0, "height_m": 1.1, "fifth_wheel": "trucksim-fifth-wheel"},
    ],
}  # fmt: skip


class CombinationSpecRef(InputModel):
    """A combination described by what can be measured of each unit; the builder turns it into the combination
    record (see `POST /v1/combinations/build` for the record and where each value comes from)."""

    combination_spec: CombinationSpecIn = Field(  # type: ignore[valid-type]
        description=describe("The combination in measurable terms (docs/vehicles.md).", unit="see its fields")
    )

    def engine_spec(self) -> ec.CombinationSpec:
        return ec.CombinationSpec.from_dict(self.combination_spec.model_dump(exclude_unset=True))


class BuildCombinationRequest(CombinationSpecRef):
    """A combination in measurable terms to build into the whole-combination model's record."""

    model_config = ConfigDict(json_schema_extra={"examples": [{"combination_spec": EXAMPLE_COMBINATION_SPEC}]})


# ---------------------------------------------------------------------------------------------- the result


class BuiltUnitOut(OutputModel):
    """One unit's masses: tare and payloads, their CG, and the sprung mass and CG of the roll model."""

    id: str = Field(description=describe("Unit id.", unit="-"))
    kind: str = Field(description=describe("Unit kind.", unit="-"))
    masses: list[MassOut] = Field(
        description=describe("The tare and each payload with its CG (behind the unit's reference point).", unit="-")
    )
    mass_kg: float = Field(description=describe("Tare plus payloads, the axles included.", unit="kg"))
    cg_height_m: float = Field(description=describe("CG height of that mass above the road.", unit="m", symbol="h"))
    cg_position_m: float = Field(description=describe("Its CG behind the unit's reference point.", unit="m"))
    unsprung_mass_kg: float = Field(description=describe("The axles' unsprung masses together.", unit="kg"))
    sprung_mass_kg: float = Field(description=describe("The sprung mass the roll model takes.", unit="kg"))
    sprung_cg_height_m: float = Field(description=describe("Sprung CG height above the road.", unit="m", symbol="h"))
    sprung_cg_position_m: float = Field(description=describe("Sprung CG behind the unit's reference point.", unit="m"))


class GroupLoadOut(OutputModel):
    """The static normal load of one axle group on a level road (Eq. 4.27 along the chain)."""

    unit: str = Field(description=describe("Unit id.", unit="-"))
    group: str = Field(description=describe("Axle group id.", unit="-"))
    load_kn: float = Field(description=describe("Normal load of the group.", unit="kN", symbol="N"))
    load_kg: float = Field(description=describe("The same as a mass, N / g.", unit="kg"))
    per_axle_kg: float = Field(description=describe("Per axle.", unit="kg"))


class BuildCombinationResult(OutputModel):
    """The combination record built from a spec, where each value comes from, each unit's masses and the loads."""

    combination: dict[str, Any] = Field(
        description=describe(
            'The combination record (as `{"combination": ...}` takes it, and `GET /v1/combinations/{id}` shows one).',
            unit="see its fields",
        )
    )
    derivation: dict[str, DerivationOut] = Field(
        description=describe(
            "Record path (`units[0].groups[1].tyre_stiffness_kn_per_m`) -> its value, how it was obtained and the "
            "source (the component library's, the spec input's, or `assumed: why`).",
            unit="-",
        )
    )
    units: list[BuiltUnitOut] = Field(description=describe("Each unit's masses and CG.", unit="-"))
    axle_loads: list[GroupLoadOut] = Field(description=describe("Every axle group's static load.", unit="-"))
    coupling_loads_kn: list[float] = Field(
        description=describe("The vertical load each coupling passes to the towing unit at rest.", unit="kN")
    )
    gross_mass_kg: float = Field(description=describe("All tares and payloads.", unit="kg", symbol="sum W/g"))
    notes: list[str] = Field(description=describe("What the model does not represent of this spec.", unit="-"))
    dynamics: dict[str, list[dict[str, Any]]] = Field(
        description=describe(
            "The spec's data for the yaw-roll model (its units' and groups' `dynamics`, and each group's "
            "`axle_spacing_m`), in the form of the dynamics requests' `dynamics` field: `units` (`unit` and the given "
            "fields) and `groups` (`unit`, `group` and the given fields). The combination record does not hold it: "
            "with the record, give it as the dynamics request's `dynamics`.",
            unit="see its fields",
        )
    )

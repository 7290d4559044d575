"""The vehicle record, in and out. Texts (unit, thesis symbol, description) come from engine.vehicles.FIELD_DOCS.

Bounds here are sanity limits of the schema (so a client sees them in the spec and absurd magnitudes are
refused early); the engine checks the physics (track = axle width, even tire counts, roll stiffness above
W l12, CG inside the wheelbase, ...) and answers 422 naming the field.
"""

from __future__ import annotations

from typing import Any

from pydantic import Field

from engine.vehicles import FIELD_DOCS

from .common import InputModel, OutputModel, describe


def vfield(name: str, *, required: bool = False, **bounds: Any) -> Any:
    doc = FIELD_DOCS[name]
    text = doc.description if required else doc.description + " Null when the table does not give it."
    return Field(... if required else None, description=describe(text, unit=doc.unit, symbol=doc.symbol), **bounds)


_IGNORED = describe("Preset metadata from GET /v1/vehicles/{id}; accepted and ignored.", unit="-")


class VehicleRecord(InputModel):
    """A full vehicle record (the last unit of a combination, or a rigid truck). Same fields as
    ``GET /v1/vehicles/{id}`` returns; the preset metadata (``id``, ``title``, ``source``, ``models``) is accepted
    and ignored so a fetched preset can be edited and posted back."""

    weight_kn: float = vfield("weight_kn", required=True, gt=0, le=5000)
    front_track_m: float | None = vfield("front_track_m", gt=0, le=5)
    rear_track_m: float = vfield("rear_track_m", required=True, gt=0, le=5)
    front_axle_width_m: float | None = vfield("front_axle_width_m", gt=0, le=5)
    rear_axle_width_m: float = vfield("rear_axle_width_m", required=True, gt=0, le=5)
    front_axles: int | None = vfield("front_axles", ge=1, le=8)
    rear_axles: int = vfield("rear_axles", required=True, ge=1, le=8)
    front_tires_per_axle: int | None = vfield("front_tires_per_axle", ge=2, le=8)
    rear_tires_per_axle: int = vfield("rear_tires_per_axle", required=True, ge=2, le=8)
    suspension_stiffness_kn_per_m: float = vfield("suspension_stiffness_kn_per_m", required=True, gt=0, le=1e6)
    tire_stiffness_kn_per_m: float = vfield("tire_stiffness_kn_per_m", required=True, gt=0, le=1e6)
    fifth_wheel_stiffness_kn_per_m: float | None = vfield("fifth_wheel_stiffness_kn_per_m", gt=0, le=1e6)
    suspension_height_m: float = vfield("suspension_height_m", required=True, gt=0, le=3)
    rolling_radius_m: float = vfield("rolling_radius_m", required=True, gt=0, le=3)
    fifth_wheel_height_m: float | None = vfield("fifth_wheel_height_m", gt=0, le=3)
    spring_separation_m: float = vfield("spring_separation_m", required=True, gt=0, le=5)
    fifth_wheel_width_m: float | None = vfield("fifth_wheel_width_m", gt=0, le=5)
    cg_height_above_chassis_m: float = vfield("cg_height_above_chassis_m", required=True, gt=0, le=10)
    fifth_wheel_to_front_axle_m: float | None = vfield("fifth_wheel_to_front_axle_m", ge=-50, le=50)
    wheelbase_m: float | None = vfield("wheelbase_m", gt=0, le=50)
    front_axle_to_cg_m: float | None = vfield("front_axle_to_cg_m", gt=0, le=50)
    front_llt_ratio: float | None = vfield("front_llt_ratio", gt=0, le=1)
    chassis_torsional_stiffness_knm2_per_rad: float | None = vfield(
        "chassis_torsional_stiffness_knm2_per_rad", gt=0, le=1e9
    )
    # preset metadata, accepted and ignored (not part of the record nor of the cache key)
    id: str | None = Field(None, max_length=200, description=_IGNORED)
    title: str | None = Field(None, max_length=500, description=_IGNORED)
    source: str | None = Field(None, max_length=500, description=_IGNORED)
    models: list[str] | None = Field(None, max_length=20, description=_IGNORED)

    def record(self) -> dict[str, Any]:
        """The engine record (metadata dropped)."""
        return self.model_dump(exclude=set(METADATA_FIELDS))


METADATA_FIELDS = ("id", "title", "source", "models")


def _out(name: str) -> Any:
    doc = FIELD_DOCS[name]
    return Field(description=describe(doc.description, unit=doc.unit, symbol=doc.symbol))


class VehiclePreset(OutputModel):
    """A thesis preset: its id, title, source table, the models it suits, and its full record."""

    id: str = Field(description="Preset id, usable as `vehicle` in the POST endpoints. Unit: -. Thesis symbol: -.")
    title: str = Field(description="What the vehicle is. Unit: -. Thesis symbol: -.")
    source: str = Field(description="Where the thesis gives it. Unit: -. Thesis symbol: -.")
    models: list[str] = Field(description="Model ids the record has the fields for. Unit: -. Thesis symbol: -.")
    weight_kn: float = _out("weight_kn")
    front_track_m: float | None = _out("front_track_m")
    rear_track_m: float = _out("rear_track_m")
    front_axle_width_m: float | None = _out("front_axle_width_m")
    rear_axle_width_m: float = _out("rear_axle_width_m")
    front_axles: int | None = _out("front_axles")
    rear_axles: int = _out("rear_axles")
    front_tires_per_axle: int | None = _out("front_tires_per_axle")
    rear_tires_per_axle: int = _out("rear_tires_per_axle")
    suspension_stiffness_kn_per_m: float = _out("suspension_stiffness_kn_per_m")
    tire_stiffness_kn_per_m: float = _out("tire_stiffness_kn_per_m")
    fifth_wheel_stiffness_kn_per_m: float | None = _out("fifth_wheel_stiffness_kn_per_m")
    suspension_height_m: float = _out("suspension_height_m")
    rolling_radius_m: float = _out("rolling_radius_m")
    fifth_wheel_height_m: float | None = _out("fifth_wheel_height_m")
    spring_separation_m: float = _out("spring_separation_m")
    fifth_wheel_width_m: float | None = _out("fifth_wheel_width_m")
    cg_height_above_chassis_m: float = _out("cg_height_above_chassis_m")
    fifth_wheel_to_front_axle_m: float | None = _out("fifth_wheel_to_front_axle_m")
    wheelbase_m: float | None = _out("wheelbase_m")
    front_axle_to_cg_m: float | None = _out("front_axle_to_cg_m")
    front_llt_ratio: float | None = _out("front_llt_ratio")
    chassis_torsional_stiffness_knm2_per_rad: float | None = _out("chassis_torsional_stiffness_knm2_per_rad")

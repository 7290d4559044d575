"""Saved vehicles and fleets (the catalog): request and response bodies."""

from __future__ import annotations

from dataclasses import fields as dataclass_fields
from datetime import datetime
from typing import Annotated, Any, Literal

from pydantic import BaseModel, ConfigDict, Discriminator, Field, Tag, create_model

from app.http.schemas import EXAMPLE_PRESET, WARNINGS_DESCRIPTION, InputModel, InputWarningOut, OutputModel, describe
from app.vehicle_forms.builder_schemas import SpecRef
from app.vehicle_forms.combination_builder_schemas import CombinationSpecRef
from app.vehicle_forms.combination_schemas import CombinationRef
from app.vehicle_forms.schemas import VehiclePreset, VehicleRecord
from engine.vehicle import Vehicle

#: a saved vehicle's id: ``veh_`` + 22 url-safe base64 characters (128 random bits); a fleet's: ``flt_`` + 22
SAVED_VEHICLE_ID_PATTERN = r"^veh_[A-Za-z0-9_-]{22}$"
FLEET_ID_PATTERN = r"^flt_[A-Za-z0-9_-]{22}$"
#: a fleet member: a saved vehicle's id or a preset's (lowercase letters, digits and hyphens)
MEMBER_ID_PATTERN = r"^(veh_[A-Za-z0-9_-]{22}|[a-z0-9-]{1,100})$"
EXAMPLE_VEHICLE_ID = "veh_3q2-7wLQz0mZb1cYkP4xVA"
EXAMPLE_FLEET_ID = "flt_Vd9xk2LmQ0a-7TzPp1bRcw"
TITLE_MAX_LENGTH = 200
#: schema bound of a fleet's members; the deployment's ROLLOVER_CATALOG_MAX_FLEET_MEMBERS is usually lower
FLEET_MEMBERS_HARD_MAX = 1000
#: a listing's cursor: base64url without padding (app.catalog.service.encode_cursor)
CURSOR_PATTERN = "^[A-Za-z0-9_-]+$"

_TITLE = describe("A name for it, shown back as given (1-200 characters).", unit="-")
_VERSION = describe(
    'Version, 1 when created, +1 at every change; the `ETag` header carries it (`"3"`): send it back in '
    "`If-Match` to change or delete.",
    unit="-",
)
_CREATED = describe("When it was created (UTC, RFC 3339).", unit="date-time")
_UPDATED = describe("When it was last changed (UTC, RFC 3339).", unit="date-time")
_NEXT = describe(
    "Cursor of the next page (pass it as `cursor`); null on the last page. Pages are in creation order (then "
    "id), so rows created while paging come at the end and no row is repeated or skipped.",
    unit="-",
)


class PageQuery(BaseModel):
    """The query of a listing: page size and cursor; any other parameter is refused (422)."""

    model_config = ConfigDict(extra="forbid")

    limit: int = Field(50, ge=1, le=200, description=describe("Page size, 1-200.", unit="items"))
    cursor: str | None = Field(
        None,
        max_length=400,
        # what encode_cursor writes (base64url, unpadded); published only: anything else is refused by
        # decode_cursor with its own message (422 naming `cursor`)
        json_schema_extra={"minLength": 1, "pattern": CURSOR_PATTERN},
        description=describe("`next_cursor` of the previous page; omit it for the first page.", unit="-"),
    )


def _saved_kind(value: Any) -> str | None:
    if isinstance(value, dict):
        for kind in ("spec", "combination_spec", "combination"):
            if kind in value:
                return kind
        return "record"
    return None


SavedVehicleIn = Annotated[
    Annotated[VehicleRecord, Tag("record")]
    | Annotated[SpecRef, Tag("spec")]
    | Annotated[CombinationRef, Tag("combination")]
    | Annotated[CombinationSpecRef, Tag("combination_spec")],
    Discriminator(
        _saved_kind,
        custom_error_type="invalid_vehicle",
        custom_error_message='vehicle must be a full vehicle record, {"spec": {...}}, {"combination": {...}} or '
        '{"combination_spec": {...}}',
    ),
]


def _btrain_record() -> dict[str, Any]:
    from engine.vehicle import get_preset

    return get_preset(EXAMPLE_PRESET).to_dict()


class VehicleWrite(InputModel):
    """What `POST /v1/vehicles` and `PUT /v1/vehicles/{id}` take: a title and the vehicle."""

    model_config = ConfigDict(
        json_schema_extra={"examples": [{"title": "Our B-train, rear unit (Table 16)", "vehicle": _btrain_record()}]}
    )

    title: str = Field(min_length=1, max_length=TITLE_MAX_LENGTH, description=_TITLE)
    vehicle: SavedVehicleIn = Field(
        description=describe(
            "The vehicle to save: a full vehicle record (the fields of `GET /v1/vehicles/{id}`; checked by the "
            "engine as for the 3D model, a record without the 3D fields is accepted for the 2D and closed-form "
            'models) or a builder spec `{"spec": {...}}`.',
            unit="-",
            symbol="Tables 14-16, 22, 23",
        )
    )


def _record_out_fields() -> dict[str, Any]:
    # the engine's record fields, typed and described as in VehiclePreset (one definition of each field)
    return {
        f.name: (VehiclePreset.model_fields[f.name].annotation, VehiclePreset.model_fields[f.name])
        for f in dataclass_fields(Vehicle)
    }


SavedRecord = create_model(
    "SavedRecord",
    __base__=OutputModel,
    __doc__="A saved full vehicle record: every field of the engine's record (null where it gives none).",
    **_record_out_fields(),
)


class SavedSpec(OutputModel):
    """A saved builder spec, as it was sent."""

    spec: dict[str, Any] = Field(description=describe("The builder spec as saved.", unit="-"))


class SavedCombination(OutputModel):
    """A saved combination, as it was sent."""

    combination: dict[str, Any] = Field(description=describe("The combination as saved.", unit="-"))


class SavedCombinationSpec(OutputModel):
    """A saved combination builder spec, as it was sent."""

    combination_spec: dict[str, Any] = Field(description=describe("The combination builder spec as saved.", unit="-"))


class SavedVehicle(OutputModel):
    """A saved vehicle of the caller's key."""

    id: str = Field(
        pattern=SAVED_VEHICLE_ID_PATTERN,
        description=describe(
            "Its id (`veh_` + 22 random characters); use it at `/v1/vehicles/{id}` with the same key.", unit="-"
        ),
        examples=[EXAMPLE_VEHICLE_ID],
    )
    title: str = Field(description=_TITLE)
    kind: Literal["record", "spec", "combination", "combination_spec"] = Field(
        description=describe(
            "`record`: a full vehicle record; `spec`: a builder spec; `combination`: a whole combination; "
            "`combination_spec`: a combination builder spec.",
            unit="-",
        )
    )
    vehicle: SavedRecord | SavedSpec | SavedCombination | SavedCombinationSpec = Field(  # type: ignore[valid-type]
        description=describe(
            'The vehicle as stored (a record with every field, `{"spec": {...}}`, `{"combination": {...}}` or '
            '`{"combination_spec": {...}}`).',
            unit="-",
        )
    )
    version: int = Field(ge=1, description=_VERSION)
    created_at: datetime = Field(description=_CREATED)
    updated_at: datetime = Field(description=_UPDATED)


class SavedVehicleWritten(SavedVehicle):
    """A vehicle just saved (`POST /v1/vehicles`, `PUT /v1/vehicles/{id}`): as `GET` answers it, with the input
    warnings of what was sent (a typed record's `weight_kn` that reads plausibly in tonnes too). `GET` leaves them
    out: every computation that uses the saved vehicle answers them again."""

    warnings: list[InputWarningOut] = Field(description=WARNINGS_DESCRIPTION)


class SavedVehiclePage(OutputModel):
    """One page of the caller's saved vehicles."""

    items: list[SavedVehicle] = Field(description=describe("The saved vehicles of this page.", unit="-"))
    next_cursor: str | None = Field(description=_NEXT)
    unreadable: list[str] = Field(
        description=describe(
            "Ids on this page whose stored record fails validation: logged, not served (`GET` answers 409); "
            "replace them with `PUT` or delete them.",
            unit="-",
        )
    )


class FleetWrite(InputModel):
    """What `POST /v1/fleets` and `PUT /v1/fleets/{id}` take: a title and the member vehicles."""

    model_config = ConfigDict(
        json_schema_extra={"examples": [{"title": "Grain haulers", "vehicles": [EXAMPLE_PRESET, "table22-truck"]}]}
    )

    title: str = Field(min_length=1, max_length=TITLE_MAX_LENGTH, description=_TITLE)
    vehicles: list[Annotated[str, Field(min_length=1, max_length=100, pattern=MEMBER_ID_PATTERN)]] = Field(
        min_length=1,
        max_length=FLEET_MEMBERS_HARD_MAX,
        json_schema_extra={"uniqueItems": True},
        description=describe(
            "The members, in order: ids of the caller's saved vehicles (`veh_...`) or preset ids "
            "(`table16-btrain`); each at most once; at most `ROLLOVER_CATALOG_MAX_FLEET_MEMBERS` (default 100).",
            unit="-",
        ),
    )


class Fleet(OutputModel):
    """A named fleet of the caller's key."""

    id: str = Field(
        pattern=FLEET_ID_PATTERN,
        description=describe("Its id (`flt_` + 22 random characters).", unit="-"),
        examples=[EXAMPLE_FLEET_ID],
    )
    title: str = Field(description=_TITLE)
    vehicles: list[str] = Field(
        # what FleetWrite accepted when it was saved (published only: a stored row is validated as it is read)
        json_schema_extra={"minItems": 1, "maxItems": FLEET_MEMBERS_HARD_MAX, "uniqueItems": True},
        description=describe("The member ids (saved vehicle or preset), in order.", unit="-"),
    )
    version: int = Field(ge=1, description=_VERSION)
    created_at: datetime = Field(description=_CREATED)
    updated_at: datetime = Field(description=_UPDATED)


class FleetPage(OutputModel):
    """One page of the caller's fleets."""

    items: list[Fleet] = Field(description=describe("The fleets of this page.", unit="-"))
    next_cursor: str | None = Field(description=_NEXT)
    unreadable: list[str] = Field(
        description=describe(
            "Ids on this page whose stored rows fail validation: logged, not served; replace or delete them.",
            unit="-",
        )
    )

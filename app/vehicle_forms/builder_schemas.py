"""The vehicle builder's spec, its result, the component library and the payload table, as HTTP schemas.

The spec's models are generated from the engine's dataclasses (:mod:`engine.builder`): their fields, types and
defaults, and each field's description and unit from the dataclass's docstring (``name : text [unit]``), so the
published schema and the engine cannot drift. The engine checks what a schema cannot say (a load height below its
deck, a CG outside the track, a payload over a rated load, an unknown component) and answers 422 naming the spec
field (``vehicle.spec.rear.tyre.id``).
"""

from __future__ import annotations

import dataclasses
import re
import types
import typing
from typing import Annotated, Any, Literal

from pydantic import ConfigDict, Field, create_model

from app.http.schemas import InputModel, OutputModel, describe, json_int
from engine import builder as eb
from engine.builder import SPEC_RANGES, SPEC_ZERO_ALLOWED
from engine.vehicle import FIELD_DOCS, RANGES, SUSPENSIONS, TYRES

#: thesis symbols a spec field's description may start with ("kLs, vertical rate ...")
_SYMBOLS = {d.symbol for d in FIELD_DOCS.values()} | {"kLs", "kT", "lr", "ls", "b", "kf", "lf", "b1", "k_theta"}
#: the largest number of payloads a spec may have (two decks, a tank and its contents, ...)
MAX_PAYLOADS = 10
#: text fields of the spec: at most this long
MAX_TEXT = 100

#: fields whose values are a closed list (the schema states it; the engine states it again in its 422)
_CHOICES: dict[tuple[str, str], tuple[str, ...]] = {
    ("VehicleSpec", "unit_type"): eb.UNIT_TYPES,
    ("PayloadSpec", "distribution"): tuple(eb.LOAD_DISTRIBUTIONS),
    ("TankSpec", "shape"): eb.TANK_SHAPES,
    ("TyreSpec", "id"): tuple(TYRES),
    ("SuspensionSpec", "type"): tuple(SUSPENSIONS),
}
_ENTRY = re.compile(r"^ {4}([a-z_0-9]+(?:, [a-z_0-9]+)*) : (.*)$")
_UNIT = re.compile(r"\s*\[([^\]]+)\]")
_ROLE = re.compile(r":[a-z]+:`~?([^`]+)`")


def field_docs(cls: type) -> dict[str, tuple[str, str, str | None]]:
    """``name -> (text, unit, thesis symbol)`` read from a dataclass docstring's ``name : text [unit]`` lines
    (continuation lines indented further; ``a, b : text`` documents both)."""
    out: dict[str, tuple[str, str, str | None]] = {}
    names: list[str] = []
    text = ""

    def flush() -> None:
        if not names:
            return
        body = _ROLE.sub(r"\1", " ".join(text.split())).replace("``", "`")
        units = _UNIT.findall(body)
        unit = units[-1] if units else "-"
        body = _UNIT.sub("", body)
        head = body.split(",", 1)[0].strip()
        symbol = head if head in _SYMBOLS else None
        if symbol is None and body:
            body = body[0].upper() + body[1:]
        for n in names:
            out[n] = (body.rstrip(".") + ".", unit, symbol)

    for line in (cls.__doc__ or "").splitlines():
        m = _ENTRY.match(line)
        if m:
            flush()
            names, text = m.group(1).split(", "), m.group(2)
        elif names and line.startswith(" " * 8):
            text += " " + line.strip()
        else:
            flush()
            names, text = [], ""
    flush()
    return out


def _python_type(owner: str, name: str, tp: Any) -> tuple[Any, bool]:
    """The pydantic type of a dataclass field's annotation, and whether it is optional."""
    optional = False
    if typing.get_origin(tp) in (typing.Union, types.UnionType):
        args = [a for a in typing.get_args(tp) if a is not type(None)]
        optional, tp = True, args[0]
    if (owner, name) in _CHOICES:
        return Literal[_CHOICES[(owner, name)]], optional  # type: ignore[valid-type]
    if dataclasses.is_dataclass(tp):
        return MODELS[tp.__name__], optional
    if typing.get_origin(tp) is tuple:
        item = typing.get_args(tp)[0]
        return Annotated[list[MODELS[item.__name__]], Field(max_length=MAX_PAYLOADS)], optional
    if tp is int:
        return json_int(ge=0, le=1000), optional
    if tp is float:
        return float, optional
    if tp is str:
        return Annotated[str, Field(min_length=1, max_length=MAX_TEXT)], optional
    raise TypeError(f"{owner}.{name}: no schema type for {tp!r}")


def _bounds(cls: type, name: str) -> dict[str, Any]:
    """The schema's bounds of a spec field: its plausible range (``engine.builder.plausible.SPEC_RANGES``),
    which the engine enforces (422 naming the likely unit slip); a count (axles, tyres) is at least 1. Published
    only: the engine's check says more than a schema error would (the slip)."""
    key = SPEC_RANGES.get((cls.__name__, name))
    if key is not None:
        r = RANGES[key]
        low = 0.0 if (cls.__name__, name) in SPEC_ZERO_ALLOWED else r.minimum  # 0: none (a payload of 0 kg)
        return {"json_schema_extra": {"minimum": low, "maximum": r.maximum}}
    if name in ("axles", "tyres_per_axle"):
        return {"json_schema_extra": {"minimum": 1}}
    return {}


def spec_model(cls: type) -> type[InputModel]:
    """The pydantic model of one builder dataclass (its nested dataclasses must be generated first)."""
    docs = field_docs(cls)
    hints = typing.get_type_hints(cls)
    fields: dict[str, Any] = {}
    for f in dataclasses.fields(cls):
        text, unit, symbol = docs[f.name]
        tp, optional = _python_type(cls.__name__, f.name, hints[f.name])
        if f.default is not dataclasses.MISSING:
            default = f.default
        elif f.default_factory is not dataclasses.MISSING:
            default = None  # a nested object left out takes its engine defaults
        else:
            default = ...
        if default is None or optional:
            tp = tp | None
        if isinstance(default, tuple):
            default = list(default)
        fields[f.name] = (
            tp,
            Field(default, description=describe(text, unit=unit, symbol=symbol), **_bounds(cls, f.name)),
        )
    summary = (cls.__doc__ or cls.__name__).strip().split("\n\n")[0].replace("\n", " ")
    return create_model(cls.__name__, __base__=InputModel, __doc__=summary, **fields)


MODELS: dict[str, type[InputModel]] = {}
for _cls in (
    eb.TyreSpec,
    eb.SuspensionSpec,
    eb.AxleGroupSpec,
    eb.TareSpec,
    eb.TankSpec,
    eb.PayloadSpec,
    eb.DeckSpec,
    eb.FrontUnitSpec,
    eb.VehicleSpec,
):
    MODELS[_cls.__name__] = spec_model(_cls)

VehicleSpecIn = MODELS["VehicleSpec"]

#: a semi-trailer as one would measure it (the thesis's Table 23 vehicle, restated in measurable terms)
EXAMPLE_SPEC: dict[str, Any] = {
    "unit_type": "semitrailer",
    "rear": {
        "axles": 3,
        "tyres_per_axle": 4,
        "track_m": 1.86,
        "centre_from_kingpin_m": 10.0,
        "tyre": {"id": "thesis-michelin-xza"},
        "suspension": {"type": "thesis-steel-leaf"},
    },
    "front": {"axles": 2, "tyres_per_axle": 4, "track_m": 1.86},
    "tare": {"mass_kg": 8000.0, "cg_height_m": 1.2, "cg_from_kingpin_m": 6.5},
    "deck": {"front_from_kingpin_m": 0.0, "length_m": 13.0},
    "payloads": [{"mass_kg": 22000.0, "deck_height_m": 1.25, "load_height_m": 2.6}],
}


class SpecRef(InputModel):
    """A vehicle described by what can be measured; the builder turns it into the full record (see
    `POST /v1/vehicles/build` for the record and how each field was obtained)."""

    spec: VehicleSpecIn = Field(  # type: ignore[valid-type]
        description=describe("The measurable spec (docs/vehicles.md).", unit="see its fields")
    )

    def engine_spec(self) -> eb.VehicleSpec:
        return eb.VehicleSpec.from_dict(self.spec.model_dump(exclude_unset=True))


class BuildRequest(SpecRef):
    """A measurable spec to build into the engine's vehicle record."""

    model_config = ConfigDict(json_schema_extra={"examples": [{"spec": EXAMPLE_SPEC}]})


# ---------------------------------------------------------------------------------------------- the result


class DerivationOut(OutputModel):
    """How one record field was obtained."""

    value: float | None = Field(description=describe("The record field's value.", unit="the field's unit"))
    unit: str = Field(description=describe("Its unit.", unit="-"))
    method: Literal[eb.METHODS] = Field(  # type: ignore[valid-type]
        description=describe(
            "`given` (an input as is), `computed` (a formula of inputs), `library` (a component library value) "
            "or `default` (a documented default).",
            unit="-",
        )
    )
    explanation: str = Field(description=describe("The formula or the reason, in one line.", unit="-"))
    source: str = Field(
        description=describe("The document, the spec input, or `assumed: why` where no source exists.", unit="-")
    )
    spec_path: str | None = Field(description=describe("The spec input the value comes from.", unit="-"))


class MassOut(OutputModel):
    """One mass of the composite CG: the tare or a payload."""

    name: str = Field(description=describe("`tare` or `payloads[i]`.", unit="-"))
    mass_kg: float = Field(description=describe("Mass.", unit="kg"))
    cg_height_m: float = Field(description=describe("CG height above the ground.", unit="m"))
    cg_from_kingpin_m: float = Field(
        description=describe("CG behind the kingpin (rigid truck: behind the front group centre).", unit="m")
    )
    explanation: str = Field(description=describe("How its CG was obtained.", unit="-"))


class BuildResult(OutputModel):
    """The engine record built from a spec, how every field was obtained, and the masses behind the CG."""

    vehicle: dict[str, Any] = Field(
        description=describe(
            "The full vehicle record (the fields of `GET /v1/vehicles/{id}`), usable as `vehicle` anywhere.",
            unit="see its fields",
            symbol="Tables 14-16, 22, 23",
        )
    )
    derivation: dict[str, DerivationOut] = Field(
        description=describe("Record field -> its value, method and source.", unit="-")
    )
    masses: list[MassOut] = Field(description=describe("The masses of the composite CG.", unit="-"))
    gross_mass_kg: float = Field(description=describe("Tare plus payloads.", unit="kg", symbol="W/g"))
    cg_height_m: float = Field(description=describe("Composite CG height above the ground.", unit="m"))
    cg_from_kingpin_m: float = Field(description=describe("Composite CG behind the kingpin.", unit="m"))
    group_loads_kg: dict[str, float] = Field(
        description=describe("Static loads on the `front` (kingpin) and `rear` groups, by the lever rule.", unit="kg")
    )
    notes: list[str] = Field(description=describe("What the model does not represent of this spec.", unit="-"))


# ------------------------------------------------------------------------------------------ components


class SourcedOut(OutputModel):
    """A library value with its unit and source."""

    value: float = Field(description=describe("The value.", unit="see `unit`"))
    unit: str = Field(description=describe("Its unit.", unit="-"))
    source: str = Field(description=describe("Document, edition, table or page; or `assumed: why`.", unit="-"))


class TyreOut(OutputModel):
    """A tyre of the library (use its `id` as `tyre.id` in a spec)."""

    id: str = Field(description=describe("Library id.", unit="-"))
    title: str = Field(description=describe("What it is.", unit="-"))
    size: str | None = Field(description=describe("Size designation, when the source names it.", unit="-"))
    loaded_radius_m: SourcedOut = Field(description=describe("Loaded (rolling) radius.", unit="m", symbol="lr"))
    stiffness_kn_per_m: SourcedOut = Field(
        description=describe("Vertical stiffness of one tyre.", unit="kN/m", symbol="kT")
    )
    rated_load_kg: SourcedOut | None = Field(description=describe("Rated load of one tyre.", unit="kg"))


class SuspensionOut(OutputModel):
    """A suspension of the library (use its `id` as `suspension.type` in a spec)."""

    id: str = Field(description=describe("Library id.", unit="-"))
    title: str = Field(description=describe("What it is.", unit="-"))
    kind: str = Field(description=describe("Its kind (steel leaf, air, ...).", unit="-"))
    stiffness_kn_per_m: SourcedOut = Field(
        description=describe("Vertical rate of the spring on one side of one axle.", unit="kN/m", symbol="kLs")
    )
    height_m: SourcedOut = Field(description=describe("Static suspension height.", unit="m", symbol="ls"))
    spring_separation_m: SourcedOut = Field(
        description=describe("Lateral spacing of the two springs.", unit="m", symbol="b")
    )
    roll_stiffness_knm_per_rad: float = Field(
        description=describe("Roll stiffness per axle kLs b^2 / 2 (Eq. 2.11).", unit="kN m/rad", symbol="k_theta")
    )


class ComponentLibrary(OutputModel):
    """The tyres and suspensions a spec can name, each value with its source, and what could not be sourced."""

    tyres: list[TyreOut] = Field(description=describe("Library tyres.", unit="-"))
    suspensions: list[SuspensionOut] = Field(description=describe("Library suspensions.", unit="-"))
    not_found: dict[str, str] = Field(
        description=describe("What was looked for and could not be read from a source, and why.", unit="-")
    )


# --------------------------------------------------------------------------------------- payload table


class PayloadLimitOut(OutputModel):
    value: float | None = Field(
        description=describe("The limit (kg or m, as the row says); null when no value meets the target.", unit="kg|m")
    )
    status: Literal["found", "always-met", "never-met"] = Field(
        description=describe(
            "`found`: the SRT equals the target at `value`; `always-met`: the whole range meets it (`value` is the "
            "range's end); `never-met`: none of it does.",
            unit="-",
        )
    )
    srt_g: float | None = Field(description=describe("SRT at the limit.", unit="g", symbol="SRT"))


class PayloadRowOut(OutputModel):
    load_height_m: float | None = Field(description=describe("Load height of this row (first table).", unit="m"))
    payload_mass_kg: float | None = Field(description=describe("Payload mass of this row (second table).", unit="kg"))
    limit: PayloadLimitOut = Field(
        description=describe(
            "The largest payload mass at this load height (first table) or the largest load height at this mass "
            "(second table).",
            unit="kg|m",
        )
    )


class PayloadTableResult(OutputModel):
    target_srt_g: float = Field(description=describe("The SRT target.", unit="g", symbol="SRT target"))
    payload_index: int = Field(description=describe("The payload varied.", unit="-"))
    unit_index: int | None = Field(
        None, description=describe("The combination's unit whose payload varied (null for a single unit).", unit="-")
    )
    srt_of_spec_g: float = Field(
        description=describe(
            "SRT of the spec as given (a combination's: the governing roll-coupled unit's).", unit="g", symbol="SRT"
        )
    )
    by_load_height: list[PayloadRowOut] = Field(
        description=describe("Largest payload mass for each load height.", unit="-")
    )
    by_payload_mass: list[PayloadRowOut] = Field(
        description=describe("Largest load height for each payload mass.", unit="-")
    )
    engine_version: str = Field(description=describe("Engine version.", unit="-"))

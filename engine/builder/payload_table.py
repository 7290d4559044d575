"""The payload table: the largest payload by load height (and load height by payload) that meets a target.

For a single unit (a :class:`VehicleSpec`) each SRT is the thesis's 3D model's; for a combination (a
:class:`CombinationSpec`, the payload of one of its units varied) the whole-combination model's governing SRT, the
lowest of its roll-coupled units (:mod:`engine.models.combination`)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace

from engine.bracket import bracketed_limit
from engine.builder.build import build_vehicle
from engine.builder.combination import CombinationSpec, build_combination
from engine.builder.spec import PayloadSpec, VehicleSpec
from engine.case import Case, LoadCase, Road
from engine.errors import InvalidInput, RolloverError
from engine.models.threshold import rollover_threshold

# ------------------------------------------------------------------------------------ payload table


def _srt_g(spec: VehicleSpec | CombinationSpec, road: Road, load: LoadCase) -> float:
    """The module's one engine call: the spec built and solved, the 3D model's SRT of a single unit, the
    whole-combination model's governing SRT of a combination [g]."""
    if isinstance(spec, CombinationSpec):
        return rollover_threshold(Case(build_combination(spec).combination, "combination", road=road, load=load)).srt
    return rollover_threshold(Case(build_vehicle(spec).vehicle, "3d", road=road, load=load)).srt


@dataclass(frozen=True)
class PayloadLimit:
    """The largest acceptable value of one input for a row of the table.

    value : the limit [kg or m]; None when never met. status : ``found``, ``always-met`` or ``never-met``.
    srt_at_limit_g : the SRT at ``value`` [g]; range : the searched range [kg or m]; evaluations : SRT solves
    """

    value: float | None
    status: str
    srt_at_limit_g: float | None
    range: tuple[float, float]
    evaluations: int


@dataclass(frozen=True)
class PayloadRow:
    """One row: a load height with the largest payload mass, or a payload mass with the largest load height."""

    load_height_m: float | None
    payload_mass_kg: float | None
    limit: PayloadLimit


@dataclass(frozen=True)
class PayloadTable:
    """TERNZ's table of acceptable payload mass / load height pairs, solved with the 3D model."""

    target_srt_g: float
    payload_index: int
    unit_index: int | None  # the combination's unit whose payload varies; None for a single unit
    srt_at_spec_g: float  # at the spec's own mass and load height
    by_load_height: tuple[PayloadRow, ...]  # largest mass for each load height
    by_payload_mass: tuple[PayloadRow, ...]  # largest load height for each mass


def _payloads_of(spec: VehicleSpec | CombinationSpec, unit_index: int | None) -> tuple[PayloadSpec, ...]:
    return spec.units[unit_index].payloads if isinstance(spec, CombinationSpec) else spec.payloads


def _with_payload(
    spec: VehicleSpec | CombinationSpec, unit_index: int | None, index: int, mass_kg: float, load_height_m: float
) -> VehicleSpec | CombinationSpec:
    p = _payloads_of(spec, unit_index)[index]
    rear = None if p.load_height_rear_m is None else p.load_height_rear_m + (load_height_m - p.load_height_m)
    payloads = list(_payloads_of(spec, unit_index))
    payloads[index] = replace(p, mass_kg=mass_kg, load_height_m=load_height_m, load_height_rear_m=rear)
    if isinstance(spec, CombinationSpec):
        units = list(spec.units)
        units[unit_index] = replace(units[unit_index], payloads=tuple(payloads))
        return replace(spec, units=tuple(units))
    return replace(spec, payloads=tuple(payloads))


def _unit_index(spec: CombinationSpec, unit_index: int | None) -> int:
    """The unit whose payload varies: the one asked for, else the last unit that carries a payload."""
    if unit_index is None:
        loaded = [k for k, u in enumerate(spec.units) if u.payloads]
        if not loaded:
            raise InvalidInput("no unit of the combination carries a payload", field="combination_spec.units")
        return loaded[-1]
    if isinstance(unit_index, bool) or not isinstance(unit_index, int) or not 0 <= unit_index < len(spec.units):
        raise InvalidInput(
            f"unit_index must select one of the combination's {len(spec.units)} units",
            field="unit_index",
            value=unit_index,
        )
    return unit_index


def payload_table(
    spec: VehicleSpec | CombinationSpec,
    target_srt_g: float,
    *,
    unit_index: int | None = None,
    load_heights_m: Sequence[float] | None = None,
    payload_masses_kg: Sequence[float] | None = None,
    payload_index: int = 0,
    road: Road = Road(),
    load: LoadCase = LoadCase(),
    mass_tolerance_kg: float = 1.0,
    height_tolerance_m: float = 1e-4,
    rows: int = 5,
) -> PayloadTable:
    """Largest payload mass for each load height and largest load height for each payload mass meeting a target.

    The SRT falls as the payload's load height rises (its CG rises) and, for a payload whose CG lies above the
    rest of the vehicle's, as its mass grows; each limit is a root of SRT - target found by Brent's method on a
    bracket over the physical range (mass 0 to the spec's mass; load height from 1 mm above the deck to the
    spec's load height), stepping off ends the model cannot solve (:func:`engine.bracket.bracketed_limit`). A value
    the spec itself refuses (a payload above a rated group load, a body that would fall over at rest) counts as
    unsolvable: the limit is then the last acceptable value, with status ``always-met``.

    Parameters
    ----------
    spec : the vehicle, or a combination; payload ``payload_index`` must be a deck load (deck and load heights)
    unit_index : for a combination, the unit whose payload varies (default the last unit with a payload) [-]
    target_srt_g : the SRT to meet [g]
    load_heights_m : load heights of the first table [m] (default ``rows`` heights up to the spec's)
    payload_masses_kg : payload masses of the second table [kg] (default ``rows`` masses up to the spec's)
    payload_index : which payload varies [-]
    road, load : road and load case of the SRT (default flat road, nominal load)
    mass_tolerance_kg, height_tolerance_m : tolerances of the limits [kg], [m]
    rows : rows of each default table [-]

    Raises
    ------
    InvalidInput : a bad target, row or payload; InvalidVehicle : the spec itself cannot be built.
    """
    if not (isinstance(target_srt_g, int | float) and math.isfinite(target_srt_g) and 0 < target_srt_g < 2):
        raise InvalidInput("target_srt_g must be in (0, 2) g", field="target_srt_g", value=target_srt_g)
    if isinstance(spec, CombinationSpec):
        unit_index = _unit_index(spec, unit_index)
        where = f"combination_spec.units[{unit_index}].payloads"
    else:
        unit_index, where = None, "spec.payloads"
    payloads = _payloads_of(spec, unit_index)
    if not (isinstance(payload_index, int) and 0 <= payload_index < len(payloads)):
        raise InvalidInput(
            f"payload_index must select one of the {len(payloads)} payloads of {where.rsplit('.', 1)[0]}",
            field="payload_index",
            value=payload_index,
        )
    p = payloads[payload_index]
    if p.deck_height_m is None or p.load_height_m is None:
        raise InvalidInput(
            "the payload table varies a deck load's mass and load height: the payload needs deck_height_m and "
            "load_height_m (not cg_height_m or a tank)",
            field=f"{where}[{payload_index}].load_height_m",
        )
    srt_spec = _srt_g(spec, road, load)  # errors of the spec itself pass through
    deck, full_height, full_mass = float(p.deck_height_m), float(p.load_height_m), float(p.mass_kg)
    if not full_mass > 0:
        raise InvalidInput("the payload's mass must be positive for a table", field=f"{where}[{payload_index}].mass_kg")
    heights = _rows(load_heights_m, "load_heights_m", deck, full_height, rows)
    masses = _rows(payload_masses_kg, "payload_masses_kg", 0.0, full_mass, rows)

    def margin(mass_kg: float, height_m: float) -> float | None:
        try:
            return _srt_g(_with_payload(spec, unit_index, payload_index, mass_kg, height_m), road, load) - target_srt_g
        except RolloverError:  # this value collapses the body or leaves the model's range: unsolvable
            return None

    low_height = deck + 1e-3
    by_height = tuple(
        PayloadRow(
            h,
            None,
            _limit(lambda m, h=h: margin(m, h), 0.0, full_mass, mass_tolerance_kg, target_srt_g, "payload_mass_kg"),
        )
        for h in heights
    )
    by_mass = tuple(
        PayloadRow(
            None,
            m,
            _limit(
                lambda h, m=m: margin(m, h), low_height, full_height, height_tolerance_m, target_srt_g, "load_height_m"
            ),
        )
        for m in masses
    )
    return PayloadTable(float(target_srt_g), payload_index, unit_index, srt_spec, by_height, by_mass)


def _rows(values: Sequence[float] | None, name: str, low: float, high: float, n: int) -> tuple[float, ...]:
    if values is None:
        return tuple(low + (high - low) * (k + 1) / n for k in range(n))
    out = []
    for i, v in enumerate(values):
        if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v) or v <= low:
            raise InvalidInput(f"{name}[{i}] must be a number above {low:g}, got {v!r}", field=f"{name}[{i}]", value=v)
        out.append(float(v))
    return tuple(out)


def _limit(margin, good: float, bad: float, xtol: float, target: float, name: str) -> PayloadLimit:
    r = bracketed_limit(margin, good, bad, xtol=xtol, field=name)
    srt = None if r.margin is None else target + r.margin
    return PayloadLimit(r.value, r.status, srt, (good, bad), r.evaluations)

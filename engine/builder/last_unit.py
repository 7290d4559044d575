"""The last unit of a built combination as the thesis's vehicle record, for the 3D model of the last unit.

The whole-combination roll model computes LLTf/LLTr at the limit; the thesis's 3D model of the last trailer takes
that ratio instead of an assumed one (:func:`engine.models.registry.last_unit_record`). A combination built from
measurable data (:func:`~engine.builder.build_combination`) has no thesis record of its own, so this module
writes the last unit's spec in the single-unit builder's terms (:class:`~engine.builder.VehicleSpec`) from the
same data and builds it (:func:`~engine.builder.build_vehicle`):

* the unit type: the last unit is a semitrailer behind a fifth wheel (``semitrailer``: on a tractor or a converter
  dolly) or behind a B-coupling (``btrain-rear``); the 3D model has no other (a full trailer's turntable, a rigid
  truck in a combination: no record, and the answer says why);
* the rear group: the semitrailer's own group (axles, tyres per axle, track, its centre behind the kingpin, the
  spread), with the values the combination's record resolved for it: the tyre's vertical rate and loaded radius, the
  suspension's roll stiffness and spring spacing (the single-unit builder maps them to the spring rate, Eq. 2.11);
* the front group: the towing unit's group under the coupling (the one whose centre is nearest the coupling), its
  centre behind the kingpin ``l13`` = its position less the coupling's on the towing unit;
* the suspension height ``ls``: the thesis's mechanism pivots the sprung body on the spring tops, at ``lr + ls``
  above the road; the combination's record has the suspension's roll centre there instead, so ``ls`` = roll-centre
  height - loaded radius (**assumed**: the two are the same point in the thesis's mechanism; for the TruckSim
  trailer axles the roll centre is at 0.725 m and the thesis's spring tops at 0.704 m, Tables 16, 22, 23);
* the tare, the payloads and the deck as given (both builders take them with the same meaning: positions behind the
  kingpin, heights above the road);
* the fifth wheel's springs (``kf``, ``lf``, ``b1``): the single-unit builder's documented defaults (the thesis's,
  Tables 15 and 16), which the combination's fifth wheel (a roll stiffness and lash) does not give.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from typing import TYPE_CHECKING

from engine.builder.build import build_vehicle
from engine.builder.spec import AxleGroupSpec, FieldDerivation, SuspensionSpec, TyreSpec, VehicleSpec
from engine.errors import InvalidInput
from engine.vehicle.combination import AxleGroup, Combination
from engine.vehicle.record import Vehicle

if TYPE_CHECKING:  # the combination builder calls this module: its spec types only for annotations
    from engine.builder.combination_spec import CombinationSpec, UnitGroupSpec

_UNIT_TYPE = {"fifth-wheel": "semitrailer", "b-coupling": "btrain-rear"}


def _group(g: UnitGroupSpec, rec: AxleGroup, lr: float | None, centre_from_kingpin_m: float) -> AxleGroupSpec:
    """The single-unit builder's group for one of the combination's (``lr``: its loaded radius as the combination's
    build resolved it, None where it has none)."""
    ls = None if lr is None else rec.roll_centre_height_m - lr
    return AxleGroupSpec(
        axles=rec.axles,
        tyres_per_axle=rec.tyres_per_axle,
        track_m=rec.track_m,
        centre_from_kingpin_m=centre_from_kingpin_m,
        axle_spacing_m=g.axle_spacing_m,
        tyre=TyreSpec(loaded_radius_m=lr, stiffness_kn_per_m=rec.tyre_stiffness_kn_per_m),
        suspension=SuspensionSpec(
            roll_stiffness_knm_per_rad=rec.roll_stiffness_knm_per_rad,
            spring_separation_m=rec.spring_spacing_m,
            height_m=ls,
        ),
    )


def last_unit_spec(
    spec: CombinationSpec, combination: Combination, derivation: Mapping[str, FieldDerivation]
) -> VehicleSpec:
    """The last unit of ``spec`` (whose record is ``combination`` and the build's ``derivation``, record path -> how
    its value was found) in the single-unit builder's terms (the module's docstring).

    Raises
    ------
    InvalidInput : why the last unit has no thesis record (not a semitrailer behind a fifth wheel or a B-coupling).
    """
    units, couplings = spec.units, spec.couplings
    last = units[-1]
    if len(units) < 2 or last.kind != "semitrailer" or couplings[-1].kind not in _UNIT_TYPE:
        what = last.kind if len(units) > 1 else f"a lone {last.kind}"
        behind = f" behind a {couplings[-1].kind}" if len(units) > 1 else ""
        raise InvalidInput(
            f"the thesis's 3D model is of a semitrailer behind a fifth wheel or a B-coupling; the last unit is "
            f"{what}{behind}: use the combination model",
            field="combination.last_unit_record",
        )
    coupling, towing = couplings[-1], units[-2]
    towing_rec, last_rec = combination.units[-2], combination.units[-1]
    j = min(range(len(towing.axle_groups)), key=lambda k: abs(towing.axle_groups[k].position_m - coupling.position_m))
    n = len(units)

    def lr(unit: int, group: int) -> float | None:
        d = derivation.get(f"units[{unit}].groups[{group}].tyre_loaded_radius_m")
        return None if d is None else d.value

    front_spec = towing.axle_groups[j]
    front = _group(front_spec, towing_rec.groups[j], lr(n - 2, j), front_spec.position_m - coupling.position_m)
    rear = _group(last.axle_groups[0], last_rec.groups[0], lr(n - 1, 0), last.axle_groups[0].position_m)
    return VehicleSpec(
        unit_type=_UNIT_TYPE[coupling.kind],
        rear=rear,
        front=front,
        tare=last.tare,
        payloads=last.payloads,
        deck=last.deck,
        title=last.title or f"{last_rec.id} of {spec.title or 'the combination'}",
    )


def last_unit_record(
    spec: CombinationSpec, combination: Combination, derivation: Mapping[str, FieldDerivation]
) -> tuple[Vehicle | None, str]:
    """The last unit's thesis record (None where the 3D model cannot take it) and a note saying how it was made or
    why there is none."""
    try:
        vspec = last_unit_spec(spec, combination, derivation)
        # LLTf/LLTr is the combination's to compute (as a preset's record, none of its own)
        record = dataclasses.replace(build_vehicle(vspec).vehicle, front_llt_ratio=None)
    except InvalidInput as exc:
        return None, f"no thesis record of the last unit for the 3D model: {exc}"
    return record, (
        f"the last unit's thesis record (for the 3D model) was built from the same data as a {vspec.unit_type} "
        "(engine/builder/last_unit.py: the suspension height from the roll centre, assumed; the fifth "
        "wheel's springs the thesis's defaults)"
    )

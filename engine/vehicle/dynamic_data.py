"""The optional data a combination's motion needs beyond its static description, as given: per unit
(:class:`UnitData`) and per axle group (:class:`GroupData`), gathered by unit and group id (:class:`DynamicsData`).

Below the builder and the yaw-roll model (:mod:`engine.dynamics`) so that both can name it: the builder carries what
a combination spec gives beside the combination it builds, the model estimates what is left out
(:func:`engine.dynamics.parameters.resolve`, where each field's description, unit and bounds are defined once,
``UNIT_DATA_DOCS`` and ``GROUP_DATA_DOCS``). The static roll model never reads it: a combination's record and its
static answers do not depend on it.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field
from typing import Any


@dataclass(frozen=True)
class UnitData:
    """Optional per-unit data (None: estimated). Extents are metres ahead of / behind the unit's reference point."""

    yaw_inertia_kgm2: float | None = None
    roll_inertia_kgm2: float | None = None
    front_overhang_m: float | None = None
    rear_extent_m: float | None = None
    width_m: float | None = None


@dataclass(frozen=True)
class GroupData:
    """Optional per-group data: cornering coefficient [1/rad], axle spacing [m] and tyre type (an id of
    :data:`~engine.dynamics.tyres.TYRE_TYPES`); None: estimated, the tyre type the presets'."""

    cornering_coefficient_per_rad: float | None = None
    axle_spacing_m: float | None = None
    tyre_type: str | None = None


@dataclass(frozen=True)
class DynamicsData:
    """What the caller gives beyond the description: ``units`` by unit id, ``groups`` by ``(unit id, group id)``.

    ``given_at`` says where each given value was typed, for the answer's sources and the errors' fields:
    ``"units[<unit id>].<field>"`` or ``"groups[<unit id>/<group id>].<field>"`` -> the request's path
    (``dynamics.units[0].width_m``, ``vehicle.combination_spec.units[1].dynamics.width_m``; a saved vehicle's:
    the field that gives its id and the stored path, ``vehicle (saved vehicle veh_...: combination_spec...)``); a
    value it does not list is named ``dynamics.units[<unit id>].<field>``.
    """

    units: dict[str, UnitData] = field(default_factory=dict)
    groups: dict[tuple[str, str], GroupData] = field(default_factory=dict)
    given_at: dict[str, str] = field(default_factory=dict)

    def __bool__(self) -> bool:
        return bool(self.units or self.groups)

    def as_lists(self) -> dict[str, list[dict[str, Any]]]:
        """The given values in the dynamics requests' form: ``units`` (``unit`` and the given fields) and ``groups``
        (``unit``, ``group`` and the given fields), what is left out omitted."""

        def given(d: UnitData | GroupData) -> dict[str, Any]:
            return {k: v for k, v in asdict(d).items() if v is not None}

        return {
            "units": [{"unit": uid, **given(d)} for uid, d in self.units.items()],
            "groups": [{"unit": uid, "group": gid, **given(d)} for (uid, gid), d in self.groups.items()],
        }

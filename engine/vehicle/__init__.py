"""Vehicles: the parameter record, the thesis presets and the component library.

- :mod:`~engine.vehicle.record`: :class:`Vehicle` (every field in :data:`FIELD_DOCS` with unit, symbol, bounds)
  and its validation;
- :mod:`~engine.vehicle.presets`: the vehicles of Tables 14, 15, 16, 22 and 23;
- :mod:`~engine.vehicle.components`: tyres and suspensions, each value with its source;
- :mod:`~engine.vehicle.plausibility`: the plausible range of every measurable input, and the likely unit slip;
- :mod:`~engine.vehicle.combination`: combinations (units, axle groups, couplings) and their static loads;
- :mod:`~engine.vehicle.roll_components`: suspensions in roll, tyres by size and fifth wheels, with sources;
- :mod:`~engine.vehicle.combination_presets`: the combination presets and the source of every value.

The builder (a vehicle from what can be measured) is :mod:`engine.builder`, a storey above: it builds on the
models.

Exports (the face's ``__all__``, by concept; every other name is the package's own, importable by its
module path for the package and its tests):

From :mod:`~engine.vehicle.combination`, A combination vehicle as a chain of units: axle groups, sprung masses and
couplings, and its static loads:

- ``AxleGroup``: One axle group of a unit (the load-sharing axles under one suspension), with per-axle values
- ``check_combination_load``: Refuse a load case that puts a load-carrying unit's CG outside its track, below its roll
  centres, or where a support would carry no load; and the load fields outside ``BOUNDS``
- ``Combination``: A combination vehicle: its units front to rear and the couplings between them
- ``Coupling``: The coupling between unit i (towing) and unit i + 1 (towed)
- ``COUPLING_KINDS``: which unit kinds a coupling may join
- ``G_M_PER_S2``: gravitational acceleration used for W = m g [m/s^2], as the builder's (``G_M_PER_S2``)
- ``kingpin_group``: (unit, group) of the towing unit's group under the coupling ahead of unit ``towed_index``: the
  group that the towed unit's front rests on (the 'front group' of the thesis's 3D model of a trailer)
- ``LEADING_KINDS``: the unit kinds that can lead a combination
- ``loaded_units``: Each unit's sprung weight and CG with the load case: overweight scales the sprung weight of the
  load-carrying units (the 3D model scales the trailer's weight, Sec. 9.4); d2 (+ forward) moves their ...
- ``roll_coupled_units``: The units that roll together: the chain cut at every coupling that transmits no roll moment (a
  pintle)
- ``static_loads``: The groups' and couplings' normal loads (see the module docstring), from the last unit forward
- ``Unit``: One unit of the combination
- ``UNIT_KINDS``: unit kinds, what reference point their positions are measured from, and how many axle groups they have
- ``UnitLoad``: The load case applied to one load-carrying unit
- ``validate_combination``: Refuse a combination that no real vehicle can be, naming the unit and the field

From :mod:`~engine.vehicle.combination_presets`, combination presets: the thesis's trailers behind sourced towing units,
and two doubles from sourced components:

- ``COMBINATION_INFO``: each combination preset's title and description
- ``COMBINATION_SOURCES``: where each value of a preset comes from: preset id -> {field path -> source}
- ``COMBINATIONS``: the combination presets by id
- ``get_combination``: The combination preset with this id

From :mod:`~engine.vehicle.components`, tyre and suspension library: the component values the vehicle builder can look
up, each with its source:

- ``get_suspension``: The library suspension ``suspension_id``
- ``get_tyre``: The library tyre ``tyre_id``
- ``NOT_FOUND``: what was looked for and could not be read from a source (so it is not in the library): id -> why
- ``parse_tyre_size``: Nominal section width, rim diameter and aspect ratio of a radial truck-tyre size designation
- ``rated_load_from_load_index_kg``: Load one tyre may carry in its fitment, from its load-index marking and the ISO
  table [kg]
- ``Sourced``: A library value with its unit and source (or ``"assumed: why"``)
- ``spring_rate_from_roll_stiffness``: The per-side spring rate kLs = 2 k_theta / b^2 that gives a roll stiffness per
  axle [kN/m] (Eq. 2.11)
- ``SUSPENSIONS``: the suspension library by id, each value with its source
- ``TYRES``: the tyre library by id, each value with its source

From :mod:`~engine.vehicle.plausibility`, plausibility of measurable inputs: the range a heavy vehicle's masses,
heights, lengths and stiffnesses can take, and the unit slip that most likely explains a value outside it:

- ``check_plausible``: ``value`` as a float if it is a finite number inside ``RANGES`` ``[quantity]``, else
  ``InvalidVehicle`` naming ``field`` and the likely unit slip
- ``check_record_plausible``: Refuse a vehicle record (typed by a user) whose weight or stiffnesses lie outside
  ``RANGES``, naming the field (``where`` + the record field) and the likely unit slip: a 31.5 kN semitrailer is ...
- ``InputWarning``: A value answered as given that reads plausibly in another unit too: the field as typed, the value,
  and both readings in the range's unit
- ``RANGES``: the plausible range of every measurable input, each with its source
- ``RECORD_SLIPS``: the slips worth suggesting for a record field outside its schema bounds, by the field's unit
- ``record_warnings``: The ``InputWarning`` of every field of a vehicle record (typed by a user) that reads plausibly in
  another unit too (``RECORD_RANGES``), named ``where`` + the record field (``vehicle.weight_kn``)
- ``unit_slip``: The first unit slip of ``slips`` that brings ``value`` into [minimum, maximum]

From :mod:`~engine.vehicle.presets`, the thesis presets: the vehicles of Tables 14, 15, 16, 22 and 23 as full records:

- ``get_preset``: The preset vehicle with this id
- ``PRESET_INFO``: each preset's title, table and description
- ``PRESETS``: the thesis's vehicles (Tables 14, 15, 16, 22 and 23) by id

From :mod:`~engine.vehicle.record`, the vehicle parameter record and the thesis presets (Tables 14, 15, 16, 22 and 23):

- ``cg_height_m``: Static CG height above the road h = lr + ls + l12 (+ d3) [m] (rigid-model h of Eq. 2.6)
- ``FIELD_DOCS``: every record field's unit, symbol, bounds and meaning
- ``FieldDoc``: One field of the vehicle record: its unit, thesis symbol, meaning and admissible range
- ``group_stiffness``: Per-side equivalent stiffnesses of the ``'front'`` or ``'rear'`` axle group [kN/m]
- ``static_axle_loads``: Static (flat road) loads on the front and rear groups [kN]
- ``validate_vehicle``: Refuse a record that no heavy vehicle can be, or that misses what a model needs, before solving
- ``Vehicle``: One vehicle (the last unit of a combination, or a rigid truck)

From :mod:`~engine.vehicle.roll_components`, component library of the whole-combination roll model: suspensions in roll,
tyres by size, fifth wheels, units:

- ``FIFTH_WHEELS``: the fifth-wheel library by id, each value with its source
- ``get_fifth_wheel``: the fifth wheel with this id
- ``get_roll_suspension``: the suspension in roll with this id
- ``roll_tyre_for_size``: The library tyre of a size designation (``"295/80R22.5"``, ``"11R22.5"``): a measured tyre of
  that size, else the TruckSim load-rating class that names it
- ``SUSPENSIONS_IN_ROLL``: the suspensions in roll by id, each value with its source
"""

from .combination import (
    COUPLING_KINDS,
    G_M_PER_S2,
    LEADING_KINDS,
    UNIT_KINDS,
    AxleGroup,
    Combination,
    Coupling,
    Unit,
    UnitLoad,
    check_combination_load,
    kingpin_group,
    loaded_units,
    roll_coupled_units,
    static_loads,
    validate_combination,
)
from .combination_presets import (
    COMBINATION_INFO,
    COMBINATION_SOURCES,
    COMBINATIONS,
    get_combination,
)
from .components import (
    NOT_FOUND,
    SUSPENSIONS,
    TYRES,
    Sourced,
    get_suspension,
    get_tyre,
    parse_tyre_size,
    rated_load_from_load_index_kg,
    spring_rate_from_roll_stiffness,
)
from .plausibility import (
    RANGES,
    RECORD_SLIPS,
    InputWarning,
    check_plausible,
    check_record_plausible,
    record_warnings,
    unit_slip,
)
from .presets import (
    PRESET_INFO,
    PRESETS,
    get_preset,
)
from .record import (
    FIELD_DOCS,
    FieldDoc,
    Vehicle,
    cg_height_m,
    group_stiffness,
    static_axle_loads,
    validate_vehicle,
)
from .roll_components import (
    FIFTH_WHEELS,
    SUSPENSIONS_IN_ROLL,
    get_fifth_wheel,
    get_roll_suspension,
    roll_tyre_for_size,
)

__all__ = [
    "COMBINATIONS",
    "COMBINATION_INFO",
    "COMBINATION_SOURCES",
    "COUPLING_KINDS",
    "FIELD_DOCS",
    "FIFTH_WHEELS",
    "G_M_PER_S2",
    "LEADING_KINDS",
    "NOT_FOUND",
    "PRESETS",
    "PRESET_INFO",
    "RANGES",
    "RECORD_SLIPS",
    "SUSPENSIONS",
    "SUSPENSIONS_IN_ROLL",
    "TYRES",
    "UNIT_KINDS",
    "AxleGroup",
    "Combination",
    "Coupling",
    "FieldDoc",
    "InputWarning",
    "Sourced",
    "Unit",
    "UnitLoad",
    "Vehicle",
    "cg_height_m",
    "check_combination_load",
    "check_plausible",
    "check_record_plausible",
    "get_combination",
    "get_fifth_wheel",
    "get_preset",
    "get_roll_suspension",
    "get_suspension",
    "get_tyre",
    "group_stiffness",
    "kingpin_group",
    "loaded_units",
    "parse_tyre_size",
    "rated_load_from_load_index_kg",
    "record_warnings",
    "roll_coupled_units",
    "roll_tyre_for_size",
    "spring_rate_from_roll_stiffness",
    "static_axle_loads",
    "static_loads",
    "unit_slip",
    "validate_combination",
    "validate_vehicle",
]

"""Vehicle builder: a specification in measurable terms -> the engine's vehicle record, with its derivation.

Certifiers and operators know a vehicle by its unit type, axle groups, tyres, suspension type, masses and deck and
load heights (the inputs of the TERNZ / NZTA SRT calculator), not by the thesis's 23 record fields. A
:class:`VehicleSpec` holds those measurable inputs; :func:`build_vehicle` turns it into the
:class:`engine.vehicle.Vehicle` record and says, for every record field, how its value was obtained
(``given``, ``computed``, ``library`` or ``default``), by what formula, and from which source.

Mapping (details and limits in ``docs/vehicles.md``)
------------------------------------------------------
* W = (tare + payloads) g, g = 9.81 m/s^2 (:data:`G_M_PER_S2`).
* Composite CG: h = sum(m_i z_i) / sum(m_i) above the ground, x = sum(m_i x_i) / sum(m_i) behind the kingpin
  (the front axle group of a rigid truck).
* l12 = h - (lr + ls): the record measures the CG from the chassis reference lr + ls
  (:func:`engine.vehicle.record.cg_height_m`); a = x; L = the rear group centre's distance; l13 = the front group
  centre's distance (0 for a truck).
* A payload's CG: uniform density between deck and load top: mid-height (TERNZ "uniform density"); "mixed
  freight", 70 % of the mass in the bottom half of the load space: 0.4 of the load height above the deck (TERNZ);
  a sloping deck (heights varying linearly along the load): the centroid of the side-view trapezoid, integrated
  exactly; a liquid in a circular or elliptical tank: the centroid of the liquid segment (closed form).
* The record's single kLs, kT, lr, ls and b are the **rear** group's (the unit's own group, whose inner tyre
  lift-off is the limit); the front group contributes its axles, tyres per axle and track. Where the front group's
  components differ, the derivation says so: the record cannot represent the difference.

References
----------
.. [1] Moreno, G. G., *Static rollover threshold of long combination vehicles* (doctoral thesis), Tables 15, 16,
   22, 23; Eqs. 2.11, 4.27; Sec. 4.1.1; Ch. 9 (Kamnik et al., 2003: LLTf = 0.7 LLTr).
.. [2] TERNZ / NZ Transport Agency, *SRT Calculator* help ("Load Categories", ternz.co.nz/SRT_Calculator/
   mainhelp.html; the same text on Main Roads WA's mrwebapps.mainroads.wa.gov.au/srtcalculator/mainhelp.html).
.. [3] Centroid of a circular segment, ybar = 4 R sin^3(theta/2) / (3 (theta - sin theta)) from the centre: the
   sector (area R^2 theta/2, centroid 4 R sin(theta/2) / (3 theta) from the centre; Wolfram MathWorld, "Circular
   Sector", after Gearhart and Schulz, 1990) minus its triangle (area R^2 sin(theta)/2, centroid 2/3 R cos(theta/2)).

Exports (the face's ``__all__``, by concept; every other name is the package's own, importable by its
module path for the package and its tests):

From :mod:`~engine.builder.build`, the build: a spec -> the record, every field with how it was obtained:

- ``build_vehicle``: The engine's vehicle record for a measurable spec, with the derivation of every field

From :mod:`~engine.builder.combination`, the combination builder: every unit of a combination from measurable data ->
the roll model's ``Combination``, every component value with its source:

- ``build_combination``: The whole-combination roll model's record for a measurable spec, every component value with its
  source
- ``BuiltCombination``: The combination record, every component value with its derivation, each unit's masses and the
  static loads
- ``SPEC_COUPLING_KINDS``: the coupling kinds a spec may name: the record's kinds, and ``ball`` (an A-dolly's ball
  coupling: a pintle)

From :mod:`~engine.builder.combination_spec`, the combination builder's input (``build_combination``): a combination
described by its units' parts (tare, payloads, axle groups with catalogue tyres and suspensions, couplings), as the
API's ...:

- ``CombinationSpec``: A combination in measurable terms: units front to rear and one coupling between each two
- ``CouplingSpec``: The coupling between a unit (towing) and the next one (towed)
- ``RollSuspensionSpec``: The suspension of an axle group in roll, per axle: a library type and/or explicit data
  (explicit values win)
- ``RollTyreSpec``: The tyres of an axle group, for the roll model: a size and/or explicit data (explicit values win)
- ``UnitGroupSpec``: One axle group of a unit (load-sharing axles under one suspension)
- ``UnitSpec``: One unit in measurable terms

From :mod:`~engine.builder.payload_table`, the payload table: the largest payload by load height (and load height by
payload) that meets a target:

- ``payload_table``: Largest payload mass for each load height and largest load height for each payload mass meeting a
  target
- ``PayloadTable``: TERNZ's table of acceptable payload mass / load height pairs, solved with the 3D model

From :mod:`~engine.builder.plausible`, plausibility of a builder spec's measurable inputs, checked field by field before
anything is derived:

- ``SPEC_RANGES``: (builder dataclass, field) -> the key of ``RANGES`` the builders judge it by: what
  ``check_spec_plausible``, ``check_payloads_plausible`` and the combination builder check, as data, for the ...
- ``SPEC_ZERO_ALLOWED``: spec fields whose 0 is taken (and means none) although the rest of the range starts above it: a
  payload of 0 kg is no payload (what the payload table's first row builds); any other mass under the ...

From :mod:`~engine.builder.spec`, the builder's inputs (``VehicleSpec`` and its parts) and its result records:

- ``AxleGroupSpec``: One axle group
- ``BuiltVehicle``: The record, the derivation of every field, the masses behind the CG and notes on what is not
  represented
- ``DeckSpec``: The load space
- ``FrontUnitSpec``: Front-unit and chassis data; every value defaults as documented in ``build_vehicle``
- ``G_M_PER_S2``: gravitational acceleration used for W = m g [m/s^2]
- ``LOAD_DISTRIBUTIONS``: height of a payload's CG above the deck as a fraction of the load thickness, per load category
  [2]
- ``METHODS``: how a record field's value was obtained: given, computed, library or default
- ``PayloadSpec``: One payload: its mass, how high it sits (one of three ways) and where along the unit
- ``SuspensionSpec``: Suspension of an axle group: a library ``type`` and/or explicit data (explicit values win)
- ``TANK_SHAPES``: the tank cross-sections a liquid payload may have
- ``TankSpec``: A liquid payload in a tank of circular or elliptical cross-section (constant along its length)
- ``TareSpec``: The unit's unladen mass with its CG
- ``TyreSpec``: Tyres of an axle group: a library ``id`` and/or explicit data (explicit values win)
- ``UNIT_TYPES``: the unit types a single-unit spec may describe
- ``VehicleSpec``: A vehicle in measurable terms (see the module docstring)
"""

from .build import (
    build_vehicle,
)
from .combination import (
    SPEC_COUPLING_KINDS,
    BuiltCombination,
    build_combination,
)
from .combination_spec import (
    CombinationSpec,
    CouplingSpec,
    RollSuspensionSpec,
    RollTyreSpec,
    UnitGroupSpec,
    UnitSpec,
)
from .payload_table import (
    PayloadTable,
    payload_table,
)
from .plausible import (
    SPEC_RANGES,
    SPEC_ZERO_ALLOWED,
)
from .spec import (
    G_M_PER_S2,
    LOAD_DISTRIBUTIONS,
    METHODS,
    TANK_SHAPES,
    UNIT_TYPES,
    AxleGroupSpec,
    BuiltVehicle,
    DeckSpec,
    FrontUnitSpec,
    PayloadSpec,
    SuspensionSpec,
    TankSpec,
    TareSpec,
    TyreSpec,
    VehicleSpec,
)

__all__ = [
    "G_M_PER_S2",
    "LOAD_DISTRIBUTIONS",
    "METHODS",
    "SPEC_COUPLING_KINDS",
    "SPEC_RANGES",
    "SPEC_ZERO_ALLOWED",
    "TANK_SHAPES",
    "UNIT_TYPES",
    "AxleGroupSpec",
    "BuiltCombination",
    "BuiltVehicle",
    "CombinationSpec",
    "CouplingSpec",
    "DeckSpec",
    "FrontUnitSpec",
    "PayloadSpec",
    "PayloadTable",
    "RollSuspensionSpec",
    "RollTyreSpec",
    "SuspensionSpec",
    "TankSpec",
    "TareSpec",
    "TyreSpec",
    "UnitGroupSpec",
    "UnitSpec",
    "VehicleSpec",
    "build_combination",
    "build_vehicle",
    "payload_table",
]

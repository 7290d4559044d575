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
"""

from .build import (
    build_vehicle,
)
from .combination import (
    SPEC_COUPLING_KINDS,
    BuiltCombination,
    BuiltUnit,
    CombinationSpec,
    CouplingSpec,
    GroupLoad,
    RollSuspensionSpec,
    RollTyreSpec,
    UnitGroupSpec,
    UnitSpec,
    build_combination,
)
from .groups import (
    ResolvedGroup,
    check_width,
    component_fields,
    resolve_group,
)
from .payload_table import (
    PayloadLimit,
    PayloadRow,
    PayloadTable,
    payload_table,
)
from .payloads import (
    payload_item,
    sloped_load_centroid,
    tank_liquid_cg_height_m,
    tare_item,
)
from .spec import (
    G_M_PER_S2,
    LOAD_DISTRIBUTIONS,
    METHODS,
    TANK_SHAPES,
    THESIS,
    TRAILER_TYPES,
    UNIT_TYPES,
    AxleGroupSpec,
    BuiltVehicle,
    DeckSpec,
    FieldDerivation,
    FrontUnitSpec,
    MassItem,
    PayloadSpec,
    SuspensionSpec,
    TankSpec,
    TareSpec,
    TyreSpec,
    VehicleSpec,
    check_choice,
    check_count,
    check_number,
)

__all__ = [
    "G_M_PER_S2",
    "LOAD_DISTRIBUTIONS",
    "METHODS",
    "SPEC_COUPLING_KINDS",
    "TANK_SHAPES",
    "THESIS",
    "TRAILER_TYPES",
    "UNIT_TYPES",
    "AxleGroupSpec",
    "BuiltCombination",
    "BuiltUnit",
    "BuiltVehicle",
    "CombinationSpec",
    "CouplingSpec",
    "DeckSpec",
    "FieldDerivation",
    "FrontUnitSpec",
    "GroupLoad",
    "MassItem",
    "PayloadLimit",
    "PayloadRow",
    "PayloadSpec",
    "PayloadTable",
    "ResolvedGroup",
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
    "check_choice",
    "check_count",
    "check_number",
    "check_width",
    "component_fields",
    "payload_item",
    "payload_table",
    "resolve_group",
    "sloped_load_centroid",
    "tank_liquid_cg_height_m",
    "tare_item",
]

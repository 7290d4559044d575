"""POST /v1/alignments/assess: the safe speed on every horizontal curve of a road alignment, for one or more
vehicles (rollover, Eq. 9.1, against side friction with a design standard's f_max)."""

from __future__ import annotations

from typing import Annotated, Any, Literal

from pydantic import AfterValidator, ConfigDict, Field, model_validator
from pydantic_core import PydanticCustomError

from app.advisory.schemas import INCREMENT_DESCRIPTION, UNITS_DESCRIPTION, AdvisoryOptions
from app.catalog.schemas import FLEET_ID_PATTERN
from app.formats.alignment_io import CURVE_ID_MAX_CHARS, CURVE_ID_PATTERN, MAX_CURVES, curve_id_problem
from app.http import problems
from app.http.schemas import (
    ABSENT,
    EXAMPLE_PRESET,
    WARNINGS_DESCRIPTION,
    InputModel,
    InputWarningOut,
    OutputModel,
    bounded,
    describe,
    exactly_one_schema,
    shape_error,
)
from app.road.standards_schemas import BOUND_ONLY_WITH_TABLE21, DesignOptions
from app.srt.schemas import (
    LEVEL_ROAD_SRT_TEXT,
    TARGETS_OUT,
    TILT_OUT,
    VEHICLE_DESCRIPTION,
    SrtOptions,
    SrtTargets,
    TargetCheckOut,
    VehicleRef,
)

MAX_VEHICLES = 10
#: curves x vehicles: the rows of one synchronous answer (about 450 bytes each in JSON: some 4.5 MB, rendered and
#: cached whole); larger work goes to a job
MAX_ROWS = 10_000
#: an ``alignments.assess`` job's limits (:mod:`app.jobs.op_alignments`), named by the synchronous limits' errors
MAX_JOB_CURVES = 1_000_000
MAX_JOB_ROWS = 1_000_000


def as_a_job(message: str) -> str:
    """A synchronous size limit's message, with how to send the work instead (an ``alignments.assess`` job)."""
    limits = f"{MAX_JOB_CURVES:,} curves and {MAX_JOB_ROWS:,} rows"
    document = 'a file as its "csv" text, or its "landxml" or "ifc" document'
    return problems.as_a_job(message, "alignments.assess", document, limits)


MAX_CSV_CHARS = 16_000_000
MAX_LANDXML_CHARS = 64_000_000
#: an IFC 4.3 file (ISO 10303-21 text) bounded as a LandXML document is; it holds more per curve (the geometric
#: representation, the cant and the referents besides the design parameters: examples/road.ifc is 15 kB where
#: examples/alignment.xml is 1.9 kB for the same two curves), so fewer curves fit
MAX_IFC_CHARS = 64_000_000
#: body limits [bytes]: the raw CSV, LandXML and IFC uploads as their documents' bounds (UTF-8 text of that many
#: characters); the JSON request may carry a LandXML or IFC document, JSON-escaped (every quote doubled in the worst
#: case)
CSV_UPLOAD_LIMIT = 16 * 2**20
LANDXML_UPLOAD_LIMIT = 64 * 2**20
IFC_UPLOAD_LIMIT = 64 * 2**20
ALIGNMENT_JSON_LIMIT = 128 * 2**20


def _curve_id(value: str) -> str:
    problem = curve_id_problem(value)
    if problem is not None:
        raise PydanticCustomError("curve_id", "{reason}", {"reason": problem})
    return value


#: the pattern is published; the rule is checked in words (curve_id_problem: which character, where)
CurveId = Annotated[
    str,
    Field(min_length=1, max_length=CURVE_ID_MAX_CHARS, json_schema_extra={"pattern": CURVE_ID_PATTERN}),
    AfterValidator(_curve_id),
]
_E = "Superelevation of the curve: the bank of its SRT and the e of the side-friction speed."
_E_SYMBOL = "e (Eqs. 9.2, 6.18)"
_GRADE = "Longitudinal grade in the direction of travel, + uphill, - downhill: the slope of the curve's SRT."
_GRADE_SYMBOL = "slope (Eq. 4.24)"
_POSTED = "Posted (or operating) speed on the curve; the margin is the safe speed minus it. Null: no margin."


class CurveIn(InputModel):
    """One horizontal curve."""

    id: CurveId = Field(
        description=describe(
            f"Curve id, unique in the request: 1-{CURVE_ID_MAX_CHARS} characters, not blank, no control or invisible "
            "(zero-width, direction mark) characters.",
            unit="-",
        )
    )
    radius_m: float = bounded("radius_m", text="Curve radius.", symbol="R (Eq. 9.1)")
    superelevation_percent: float | None = bounded(
        "bank_percent",
        None,
        text=_E + " Left out (or null): derived from the design standard's distribution at the curve's posted speed "
        "and the request's `max_superelevation_percent` (the row says so).",
        symbol=_E_SYMBOL,
    )
    grade_percent: float = bounded("slope_percent", 0.0, text=_GRADE, symbol=_GRADE_SYMBOL)
    posted_speed_kmh: float | None = bounded("speed_kmh", None, text=_POSTED, symbol="V")


class CurveOverrideIn(InputModel):
    """Values for one LandXML curve (by its id) that replace the document-wide defaults."""

    superelevation_percent: float | None = bounded("bank_percent", None, text=_E, symbol=_E_SYMBOL)
    grade_percent: float | None = bounded("slope_percent", None, text=_GRADE, symbol=_GRADE_SYMBOL)
    posted_speed_kmh: float | None = bounded("speed_kmh", None, text=_POSTED, symbol="V")


def keys_match_the_id_pattern(schema: dict[str, Any]) -> None:
    """JSON Schema's ``patternProperties`` lets a key that does not match through: state the curve-id rule for every
    key in ``propertyNames`` too, and no other key (a generated client and a validator then know it)."""
    for branch in schema.get("anyOf", []):
        if branch.get("type") == "object":
            branch.setdefault("propertyNames", {})["pattern"] = CURVE_ID_PATTERN
            branch["additionalProperties"] = False


class LandXmlIn(InputModel):
    """A LandXML 1.2 document, read whole (docs/uploads.md): its `Units`, every `Alignment`'s horizontal elements
    (`Line`, `Curve`, `Spiral`), station equations, profiles (`ProfAlign`), `Superelevation` and design cross
    sections. Each bend is a row: a `Curve` with its spirals (id: its `name`, else `<alignment name>#<n>`), or a bend
    made only of spirals (`<alignment name>#apex<m>`). The grade and superelevation the file gives are used; the
    values here are the fallbacks where it gives none (as defaults for every curve, and per curve id in
    `curve_overrides`); each row says where its values came from."""

    document: str = Field(
        min_length=1,
        max_length=MAX_LANDXML_CHARS,
        description=describe(
            "The LandXML 1.2 document (XML text; entities and DTDs are refused).", unit="-", symbol="-"
        ),
    )
    superelevation_percent: float | None = bounded(
        "bank_percent",
        None,
        text=_E + " Default for every curve; a curve left without one (here or in `curve_overrides`) is an error "
        "naming it.",
        symbol=_E_SYMBOL,
    )
    grade_percent: float = bounded(
        "slope_percent", 0.0, text=_GRADE + " Default for every curve.", symbol=_GRADE_SYMBOL
    )
    posted_speed_kmh: float | None = bounded("speed_kmh", None, text=_POSTED + " Default for every curve.", symbol="V")
    curve_overrides: dict[CurveId, CurveOverrideIn] | None = Field(
        None,
        max_length=MAX_CURVES,
        json_schema_extra=keys_match_the_id_pattern,
        description=describe(
            "Per-curve values by curve id, where the file gives none; an id that is not in the document is an error.",
            unit="%, km/h",
        ),
    )
    profile: str | None = Field(
        None,
        min_length=1,
        max_length=200,
        description=describe(
            "The vertical profile (`ProfAlign` name) whose grades the curves take; default: each alignment's first "
            "(the answer's `reading.profile` names it). A name that is in no alignment is an error.",
            unit="-",
        ),
    )


class IfcIn(LandXmlIn):
    """An IFC 4.3 file (ISO 16739-1:2024, schema `IFC4X3_ADD2`), read as its alignments' business logic
    (docs/uploads.md, "IFC 4.3"): the length unit, every top-level `IfcAlignment`'s horizontal segments (lines, arcs
    and transitions), its vertical layouts (one profile each) and cant (cross slopes), and its `STATION` referents.
    Each bend is a row: an arc with its transitions (id: its segment's `Name`, else `<alignment name>#<n>`), or a
    bend made only of transitions (`<alignment name>#apex<m>`). The grade and superelevation the file gives are
    used; the values here are the fallbacks where it gives none (as defaults for every curve, and per curve id in
    `curve_overrides`); each row says where its values came from."""

    document: str = Field(
        min_length=1,
        max_length=MAX_IFC_CHARS,
        description=describe(
            "The IFC 4.3 file (ISO 10303-21 text beginning `ISO-10303-21;`, `FILE_SCHEMA(('IFC4X3_ADD2'))`; another "
            "schema is refused naming it).",
            unit="-",
            symbol="-",
        ),
    )
    profile: str | None = Field(
        None,
        min_length=1,
        max_length=200,
        description=describe(
            "The vertical profile (the `IfcAlignmentVertical`'s `Name`, else its alignment's) whose grades the "
            "curves take; default: each alignment's first (the answer's `reading.profile` names it). A name that "
            "is in no alignment is an error.",
            unit="-",
        ),
    )


ALIGNMENT_CSV_EXAMPLE = (
    "id,radius_m,superelevation_percent,grade_percent,posted_speed_kmh\nC1,120,8,-4,70\nC2,350,6,0,90\nC3,90,8,2,60\n"
)
ALIGNMENT_LANDXML_EXAMPLE = (
    '<?xml version="1.0"?>\n'
    '<LandXML xmlns="http://www.landxml.org/schema/LandXML-1.2" version="1.2"><Alignments>'
    '<Alignment name="BR-101" length="410" staStart="0"><CoordGeom>'
    '<Line staStart="0" length="200"><Start>0 0</Start><End>0 200</End></Line>'
    '<Curve rot="cw" radius="250" length="120" staStart="200" name="K1"/>'
    '<Curve rot="ccw" radius="400" length="90" staStart="320" name="K2"/>'
    "</CoordGeom></Alignment></Alignments></LandXML>"
)

#: the LandXML example's road as IFC 4.3, the business logic alone (what the reader reads): a line, K1 and K2 (radii
#: signed + left, - right; start points and directions [rad] where the previous segment ends) and the closing
#: zero-length segment IFC 4.3 asks for
ALIGNMENT_IFC_EXAMPLE = """ISO-10303-21;
HEADER;
FILE_DESCRIPTION(('ViewDefinition[Alignment-basedView]'),'2;1');
FILE_NAME('br-101.ifc','2026-01-01T00:00:00',(''),(''),'','rollover example','');
FILE_SCHEMA(('IFC4X3_ADD2'));
ENDSEC;
DATA;
#1=IFCPROJECT('0Project00000000000001',$,'BR-101',$,$,$,$,$,#4);
#2=IFCSIUNIT(*,.LENGTHUNIT.,$,.METRE.);
#3=IFCSIUNIT(*,.PLANEANGLEUNIT.,$,.RADIAN.);
#4=IFCUNITASSIGNMENT((#2,#3));
#10=IFCALIGNMENT('1Alignment000000000001',$,'BR-101',$,$,$,$,$);
#11=IFCRELAGGREGATES('2Aggregates00000000001',$,$,$,#1,(#10));
#12=IFCALIGNMENTHORIZONTAL('1Horizontal00000000001',$,$,$,$,$,$);
#13=IFCRELNESTS('2Nests0000000000000001',$,$,$,#10,(#12));
#20=IFCCARTESIANPOINT((0.0,0.0));
#21=IFCALIGNMENTHORIZONTALSEGMENT($,$,#20,0.0,0.0,0.0,200.0,$,.LINE.);
#22=IFCALIGNMENTSEGMENT('1Segment00000000000000',$,$,$,$,$,$,#21);
#23=IFCCARTESIANPOINT((200.0,0.0));
#24=IFCALIGNMENTHORIZONTALSEGMENT($,$,#23,0.0,-250.0,-250.0,120.0,$,.CIRCULARARC.);
#25=IFCALIGNMENTSEGMENT('1Segment00000000000001',$,'K1',$,$,$,$,#24);
#26=IFCCARTESIANPOINT((315.4447938853707,-28.251269305178965));
#27=IFCALIGNMENTHORIZONTALSEGMENT($,$,#26,-0.48,400.0,400.0,90.0,$,.CIRCULARARC.);
#28=IFCALIGNMENTSEGMENT('1Segment00000000000002',$,'K2',$,$,$,$,#27);
#29=IFCCARTESIANPOINT((399.2583006482126,-60.51861846889557));
#30=IFCALIGNMENTHORIZONTALSEGMENT($,$,#29,-0.255,0.0,0.0,0.0,$,.LINE.);
#31=IFCALIGNMENTSEGMENT('1Segment00000000000003',$,$,$,$,$,$,#30);
#32=IFCRELNESTS('2Nests0000000000000002',$,$,$,#12,(#22,#25,#28,#31));
ENDSEC;
END-ISO-10303-21;
"""


class AlignmentRequest(SrtOptions, SrtTargets, DesignOptions, AdvisoryOptions):
    """The vehicle(s), the SRT options (model, stage, trailer angle, load, rear LLT limit; no `road`: each curve
    has its own bank and grade) and exactly one of `curves`, `csv`, `landxml` or `ifc`. At most 10,000 curves and
    10,000 rows (curves x vehicles) per request; larger work goes to a job (`POST /v1/jobs`, `alignments.assess`).

    The CSV, LandXML or IFC file can also be sent as it is, with the options as query parameters (presets only),
    to `/v1/alignments/assess/csv`, `/v1/alignments/assess/landxml` and `/v1/alignments/assess/ifc`."""

    model_config = ConfigDict(
        json_schema_extra={
            "allOf": [
                exactly_one_schema("vehicle", "vehicles", "fleet"),
                exactly_one_schema("curves", "csv", "landxml", "ifc"),
                BOUND_ONLY_WITH_TABLE21,
            ],
            "examples": [
                {
                    "vehicle": EXAMPLE_PRESET,
                    "rear_llt_limit": 0.6,
                    "curves": [
                        {
                            "id": "C1",
                            "radius_m": 120.0,
                            "superelevation_percent": 8.0,
                            "grade_percent": -4.0,
                            "posted_speed_kmh": 70.0,
                        },
                        {"id": "C2", "radius_m": 350.0, "superelevation_percent": 6.0, "posted_speed_kmh": 90.0},
                    ],
                },
                {"vehicles": [EXAMPLE_PRESET, "table23-semitrailer"], "csv": ALIGNMENT_CSV_EXAMPLE},
                {
                    "vehicle": EXAMPLE_PRESET,
                    "landxml": {
                        "document": ALIGNMENT_LANDXML_EXAMPLE,
                        "superelevation_percent": 6.0,
                        "posted_speed_kmh": 80.0,
                        "curve_overrides": {"K2": {"superelevation_percent": 4.0, "grade_percent": -3.0}},
                    },
                },
            ],
        }
    )

    vehicle: VehicleRef = Field(
        None, description=VEHICLE_DESCRIPTION + " Give one of `vehicle`, `vehicles`, `fleet`.", json_schema_extra=ABSENT
    )
    vehicles: list[VehicleRef] = Field(
        None,
        json_schema_extra=ABSENT,
        min_length=1,
        max_length=MAX_VEHICLES,
        description=describe(
            f"Several vehicles (1-{MAX_VEHICLES}, each as `vehicle` may be), each assessed on every curve. Give one "
            "of `vehicle`, `vehicles`, `fleet`.",
            unit="-",
            symbol="Tables 14-16, 22, 23",
        ),
    )
    fleet: str = Field(
        None,
        json_schema_extra=ABSENT,
        pattern=FLEET_ID_PATTERN,
        description=describe(
            f"A saved fleet's id (`flt_...`, with the bearer key that saved it): its vehicles (at most {MAX_VEHICLES}) "
            "in its order, each assessed on every curve. Give one of `vehicle`, `vehicles`, `fleet`.",
            unit="-",
        ),
    )  # type: ignore[assignment]
    max_superelevation_percent: float = bounded(
        "max_superelevation_percent",
        None,
        text="The road's maximum superelevation e_max: a curve without its own superelevation takes the standard's "
        "design value for its posted speed (AASHTO Method 5, DNIT's distribution), and each curve's minimum radius is "
        "the standard's for this e_max (without it, for the curve's own superelevation).",
        symbol="e_max",
    )
    curves: list[CurveIn] = Field(
        None,
        json_schema_extra=ABSENT,
        min_length=1,
        max_length=MAX_CURVES,
        description=describe(f"The curves (1-{MAX_CURVES}).", unit="per field", symbol="R, e, slope"),
    )
    csv: str = Field(
        None,
        json_schema_extra=ABSENT,
        min_length=1,
        max_length=MAX_CSV_CHARS,
        description=describe(
            "The curves as CSV text with a header row naming the columns (any order, case-insensitive): `id`, "
            "`radius_m`, `superelevation_percent`, optional `grade_percent` (empty = 0) and `posted_speed_kmh` "
            "(empty = none). A row that cannot be read is an error naming the row and the column.",
            unit="m, %, km/h (per column)",
            symbol="R, e, slope, V",
        ),
    )
    landxml: LandXmlIn = Field(
        None,
        json_schema_extra=ABSENT,
        description=describe(
            "The curves of a LandXML 1.2 alignment, with the superelevation and grade to use.",
            unit="see its fields",
            symbol="R, e, slope",
        ),
    )
    ifc: IfcIn = Field(
        None,
        json_schema_extra=ABSENT,
        description=describe(
            "The curves of an IFC 4.3 alignment (`IfcAlignment`), with the superelevation and grade to use where "
            "the file gives none.",
            unit="see its fields",
            symbol="R, e, slope",
        ),
    )

    @model_validator(mode="after")
    def _one_source_each(self) -> AlignmentRequest:
        for names in (("vehicle", "vehicles", "fleet"), ("curves", "csv", "landxml", "ifc")):
            present = [n for n in names if getattr(self, n) is not None]
            if len(present) != 1:
                what = "both " + " and ".join(present) if present else "none"
                raise shape_error(
                    "AlignmentRequest",
                    present[1] if len(present) > 1 else names[0],
                    f"give exactly one of {', '.join(names)} ({what} given)",
                )
        seen: dict[str, int] = {}
        for i, c in enumerate(self.curves or ()):
            if c.id in seen:
                raise shape_error(
                    "AlignmentRequest",
                    f"curves.{i}.id",
                    f"duplicate curve id {c.id!r} (also curves.{seen[c.id]}.id)",
                    c.id,
                )
            seen[c.id] = i
        return self


# ------------------------------------------------------------------------------------------- output


class TreatmentRowOut(OutputModel):
    devices: list[str] = Field(
        description=describe(
            "The devices by the posted-advisory difference (empty: none called for, or no posted speed).", unit="-"
        )
    )
    source: str = Field(description=describe("The table (its full text: the answer's `advisory`).", unit="-"))


class RolloverWarningRowOut(OutputModel):
    recommended: bool = Field(
        description=describe(
            "The vehicle's rollover speed less the margin falls below the advisory speed shown.", unit="-"
        )
    )
    rule: str = Field(description=describe("Whose rule (its full text: the answer's `advisory`).", unit="-"))


class SpeedPointOut(OutputModel):
    station_m: float = Field(description=describe("Station along the alignment.", unit="m"))
    speed_kmh: float = Field(description=describe("The truck's speed there.", unit="km/h"))


class AdvisoryOut(OutputModel):
    """The options and sources of the rows' advisory speeds, treatments, warnings and speed profiles."""

    units: Literal["us", "metric"] = Field(description=UNITS_DESCRIPTION)
    increment: float = Field(description=INCREMENT_DESCRIPTION)
    desired_speed_kmh: float | None = Field(
        description=describe("The request's tangent speed where a curve has no posted speed.", unit="km/h")
    )
    deceleration_mps2: float = Field(description=describe("The profile's braking rate.", unit="m/s^2"))
    method: str = Field(
        description=describe(
            "The method every row's advisory speed comes from (`ball-bank-2009`: the 2009 MUTCD ball-bank "
            "criterion, from the curve's radius and superelevation; a measured car speed, which TxDOT's Direct "
            "Method needs, is taken only by `POST /v1/advisory-speed`).",
            unit="-",
        )
    )
    method_source: str = Field(description=describe("Where that method was read, and its status.", unit="-"))
    primary_method: str = Field(
        description=describe("The primary method of FHWA-SA-11-22 and TxDOT, and why it gives no speed.", unit="-")
    )
    treatment_source: str = Field(description=describe("The treatment table and its status.", unit="-"))
    truck_rollover_warning_rule: str = Field(description=describe("The W1-13 rule (this service's).", unit="-"))


class CurveRow(OutputModel):
    """One curve, for one vehicle."""

    id: str = Field(description=describe("Curve id.", unit="-"))
    station_m: float | None = Field(
        description=describe(
            "A road file's curve: the station where its circular arc starts (a bend made only of spirals: its apex, "
            "where its radius is smallest), as the file writes it (an element's own `staStart`, else computed from "
            "the alignment's start station and the element lengths, station equations applied); null otherwise.",
            unit="m",
        )
    )
    distance_m: float | None = Field(
        description=describe(
            "A road file's curve: the distance along its alignment from the alignment's start to `station_m`'s "
            "point (the sum of the element lengths before it); null otherwise.",
            unit="m",
        )
    )
    bend_start_m: float | None = Field(
        description=describe("Station where the bend starts, its spiral in included (road files; else null).", unit="m")
    )
    bend_end_m: float | None = Field(
        description=describe("Station where the bend ends, its spiral out included (road files; else null).", unit="m")
    )
    direction: Literal["left", "right"] | None = Field(
        description=describe(
            "The side the bend turns to, looking ahead (road files: `rot` ccw/cw; else null).", unit="-"
        )
    )
    radius_m: float = Field(
        description=describe(
            "Curve radius: the arc's; a bend made only of spirals, its smallest.", unit="m", symbol="R"
        )
    )
    arc_length_m: float | None = Field(
        description=describe("Length of the circular arc (0 for a bend of spirals; road files, else null).", unit="m")
    )
    deflection_deg: float | None = Field(
        description=describe(
            "Change of direction over the row's arc and spirals: L/R over the arc, L (1/R1 + 1/R2)/2 over each "
            "spiral (road files; else null).",
            unit="deg",
        )
    )
    spiral_in_m: float | None = Field(
        description=describe("Length of the spirals before the arc (road files; else null).", unit="m")
    )
    spiral_out_m: float | None = Field(
        description=describe(
            "Length of the spirals after the arc, a spiral between two arcs included (road files; else null).",
            unit="m",
        )
    )
    compound: bool | None = Field(
        description=describe(
            "The arc is one of several arcs of different radii in one bend (road files; else null).", unit="-"
        )
    )
    reverse: bool | None = Field(
        description=describe(
            "The bend meets a bend turning the other way with no line between (road files; else null).", unit="-"
        )
    )
    superelevation_percent: float = Field(
        description=describe(
            "Superelevation used (see `superelevation_source`); negative: adverse (a normal crown through the curve).",
            unit="%",
            symbol="e",
        )
    )
    superelevation_source: Literal["given", "derived", "file", "cross-sections"] = Field(
        description=describe(
            "`file`: the road file's `Superelevation`; `cross-sections`: the outside lane's slope in its design cross "
            "sections; `given`: the request's (or the curve's own in JSON and CSV); `derived`: none given, the "
            "design standard's value for the posted speed and the request's `max_superelevation_percent`.",
            unit="-",
        )
    )
    grade_percent: float = Field(
        description=describe(
            "Grade, + uphill: a road file's profile at the bend's middle where it covers the bend, else the "
            "request's (see `grade_source`).",
            unit="%",
            symbol="slope",
        )
    )
    grade_source: Literal["profile", "request"] = Field(
        description=describe("`profile`: the road file's vertical profile; `request`: the request's.", unit="-")
    )
    grade_min_percent: float | None = Field(
        description=describe("Least grade over the bend (from the profile; else null).", unit="%")
    )
    grade_max_percent: float | None = Field(
        description=describe("Greatest grade over the bend (from the profile; else null).", unit="%")
    )
    srt_g: float | None = Field(
        description=describe(
            "SRT on this curve's bank and grade (it contains the bank): the curve's threshold, what its rollover "
            "speed uses; null when the engine refused the case (see `error`). The targets are judged on "
            "`level_road_srt`.",
            unit="g",
            symbol="SRT",
        )
    )
    level_road_srt: float | None = Field(
        description=LEVEL_ROAD_SRT_TEXT + " The vehicle's (the same on every curve: bank and grade zero); null when "
        "the engine refused the level case."
    )
    tilt_table_angle_deg: float | None = Field(description=TILT_OUT + " Null without an SRT.")
    targets: list[TargetCheckOut] = Field(
        description=TARGETS_OUT + " Empty without an SRT or a level-road SRT. The same verdict on every curve: the "
        "curve's own threshold is `srt_g` and its speeds."
    )
    rollover_speed_kmh: float | None = Field(
        description=describe(
            "Speed at which the vehicle reaches its SRT, sqrt(127 SRT R).", unit="km/h", symbol="V (Eq. 9.1)"
        )
    )
    side_friction_speed_kmh: float = Field(
        description=describe(
            "Speed at which the curve uses up the design side friction, V = sqrt(127 R (0.01 e + f_max(V))) with "
            "the design standard's f_max (held at its value at the end of the standard's speed range beyond it: see "
            "`side_friction_clamped`).",
            unit="km/h",
            symbol="V (Eq. 9.2 solved for V)",
        )
    )
    side_friction: float = Field(
        description=describe("The standard's f_max at that speed.", unit="-", symbol="f_max (Eq. 9.2)")
    )
    side_friction_clamped: bool = Field(
        description=describe(
            "The curve's side-friction speed falls outside the standard's speed range: f_max is the range end's.",
            unit="-",
        )
    )
    safe_speed_kmh: float | None = Field(
        description=describe("The smaller of the two speeds; null without an SRT.", unit="km/h", symbol="V")
    )
    governed_by: Literal["rollover", "side-friction"] | None = Field(
        description=describe("Which mechanism sets the safe speed; null without an SRT.", unit="-")
    )
    posted_speed_kmh: float | None = Field(description=describe("Posted speed, when given.", unit="km/h", symbol="V"))
    margin_kmh: float | None = Field(
        description=describe(
            "Safe speed minus posted speed; null without a posted speed or an SRT.", unit="km/h", symbol="-"
        )
    )
    flagged: bool = Field(
        description=describe("The margin is negative (the posted speed is unsafe), or the curve has no SRT.", unit="-")
    )
    standard_min_radius_m: float | None = Field(
        description=describe(
            "The design standard's minimum radius at the posted speed, for `max_superelevation_percent` (else the "
            "curve's own superelevation): the published value where tabulated, else Eq. 9.2. Null without a posted "
            "speed inside the standard's range.",
            unit="m",
            symbol="R_min (Eq. 9.2)",
        )
    )
    meets_standard_min_radius: bool | None = Field(
        description=describe("Whether radius_m >= standard_min_radius_m; null when that is null.", unit="-")
    )
    error: str | None = Field(
        description=describe("Why the engine refused this curve's case (null otherwise).", unit="-")
    )
    advisory_speed_kmh: float | None = Field(
        description=describe(
            "The advisory speed shown on the plaque, a multiple of the answer's `advisory.increment` (FHWA-SA-11-22 "
            "and TxDOT's Design Method; curves within 600 ft share one sign, its lowest speed: see docs/advisory.md); "
            "null where it cannot be computed.",
            unit="km/h",
        )
    )
    treatment: TreatmentRowOut = Field(
        description=describe("The signs the posted-advisory difference calls for.", unit="see its fields")
    )
    truck_rollover_warning: RolloverWarningRowOut = Field(
        description=describe("Whether a truck rollover warning (W1-13) is recommended.", unit="see its fields")
    )
    approach_speed_kmh: float | None = Field(
        description=describe(
            "The truck's speed in the profile where it starts to slow for this curve (the profile's speed at the "
            "curve's start, before braking); null without a profile (`profile_reason`).",
            unit="km/h",
        )
    )
    required_deceleration_mps2: float | None = Field(
        description=describe(
            "The deceleration the truck needs from the approach speed to the curve's speed after the reaction "
            "distance (0: no slowing); null without a profile, with no room to brake, or where the tangent before "
            "the curve has no known length (`profile_reason` says which).",
            unit="m/s^2",
        )
    )
    profile_reason: str | None = Field(
        description=describe("Why a profile figure of this row is null (null: none is).", unit="-")
    )


class AlignmentSummary(OutputModel):
    curves: int = Field(description=describe("Curves assessed.", unit="count"))
    flagged: int = Field(
        description=describe("Curves flagged: posted speed above the safe speed, or no SRT.", unit="count")
    )
    below_standard_min_radius: int = Field(
        description=describe(
            "Curves whose radius is below the standard's minimum for their posted speed.", unit="count"
        )
    )
    refused: int = Field(description=describe("Curves without an SRT (rows with `error`).", unit="count"))
    distinct_srt_solves: int = Field(
        description=describe(
            "SRT solves needed: one per distinct (superelevation, grade) pair, since the SRT does not depend on "
            "the radius.",
            unit="count",
        )
    )
    governed_by_rollover: int = Field(description=describe("Curves where rollover sets the safe speed.", unit="count"))
    governed_by_side_friction: int = Field(
        description=describe("Curves where side friction sets the safe speed.", unit="count")
    )
    min_margin_kmh: float | None = Field(
        description=describe("Smallest margin over the curves (null without posted speeds).", unit="km/h")
    )
    min_safe_speed_kmh: float | None = Field(
        description=describe("Lowest safe speed over the curves (null without any).", unit="km/h", symbol="V")
    )


class VehicleAssessment(OutputModel):
    index: int = Field(description=describe("Position of the vehicle in the request (0 for `vehicle`).", unit="-"))
    preset: str | None = Field(description=describe("The preset id, or null for another vehicle.", unit="-"))
    saved_vehicle_id: str | None = Field(
        description=describe("The saved vehicle's id (`veh_...`), or null for another vehicle.", unit="-")
    )
    warnings: list[InputWarningOut] = Field(description=WARNINGS_DESCRIPTION)
    summary: AlignmentSummary = Field(description=describe("Counts over the curves.", unit="see its fields"))
    rows: list[CurveRow] = Field(description=describe("One row per curve, in the request's order.", unit="per field"))
    speed_profile: list[SpeedPointOut] = Field(
        description=describe(
            "The truck's speed profile along the curves (engine/road/profile.py; docs/advisory.md): its speed at "
            "each station, linear in speed squared between them; empty where the curves' stations cannot carry one "
            "(the rows' `profile_reason`, `speed_profile_notes`).",
            unit="per field",
        )
    )
    speed_profile_notes: list[str] = Field(description=describe("Why there is no profile, if none.", unit="-"))


class CsvDialectOut(OutputModel):
    """How the uploaded CSV was written, as detected from its header and first rows (app/formats/csv_dialect.py)."""

    separator: Literal[",", ";", "\t"] = Field(
        description=describe("Field separator: `,`, `;` or a tab (`\\t`).", unit="-")
    )
    decimal: Literal[".", ","] = Field(
        description=describe(
            "Decimal mark of the numbers: `.`, or `,` (only with `;` or tab separators, as a spreadsheet in a "
            "decimal-comma locale saves CSV).",
            unit="-",
        )
    )
    bom: bool = Field(description=describe("Whether the text began with a UTF-8 byte-order mark.", unit="-"))
    line_ending: Literal["LF", "CRLF", "CR"] = Field(description=describe("Line ending of the header row.", unit="-"))


class SkippedOut(OutputModel):
    """Something in the file that was read but not used, and why."""

    what: str = Field(description=describe("The element, as the file names it.", unit="-"))
    why: str = Field(description=describe("Why it was not used.", unit="-"))


class ReadingOut(OutputModel):
    """What was read from a road file: nothing in it is left out silently."""

    format: str = Field(
        description=describe("The file's format and version (`LandXML 1.2`, `IFC 4.3 (IFC4X3_ADD2)`).", unit="-")
    )
    writer: str | None = Field(
        description=describe(
            "The application that wrote it (LandXML `<Application>`, IFC `IfcApplication`), where the file says.",
            unit="-",
        )
    )
    linear_unit: str = Field(
        description=describe("The file's length unit as it names it (`meter`, `foot`, `USSurveyFoot`...).", unit="-")
    )
    alignments: list[str] = Field(description=describe("The alignments read, by name.", unit="-"))
    elements: dict[str, int] = Field(
        description=describe(
            "Elements read, by the file's type name (LandXML `Curve`, `Spiral`...; IFC segments as "
            "`IfcAlignmentHorizontalSegment.CLOTHOID`, zero-length ones skipped).",
            unit="count",
        )
    )
    profile: str | None = Field(description=describe("The vertical profile used (null: none).", unit="-"))
    superelevation_from: Literal["file", "cross-sections", "request", "standard"] = Field(
        description=describe(
            "Where most rows' superelevation came from (each row's `superelevation_source` says its own).", unit="-"
        )
    )
    skipped: list[SkippedOut] = Field(description=describe("What was read but not used, and why.", unit="-"))
    notes: list[str] = Field(
        description=describe(
            "What the reader assumed where the file is silent or irregular, each prefixed by its alignment's name "
            "(e.g. no start station: 0 taken; names written in raw UTF-8 instead of ISO 10303-21's escapes).",
            unit="-",
        ),
    )


class AlignmentResult(OutputModel):
    """Every curve assessed for every vehicle."""

    model: str = Field(
        description=describe(
            "Model used: the request's, else `3d` for records, `combination` for combinations, `default` for a mix "
            "(each vehicle with its own).",
            unit="-",
        )
    )
    stage: str | None = Field(description=describe("Stage (3d only).", unit="-", symbol="SRT_TS / SRT_3D"))
    design_standard: str = Field(description=describe("The design standard used.", unit="-"))
    side_friction_bound: str | None = Field(
        description=describe("Table 21 bound used (thesis-table21 only; null otherwise).", unit="-", symbol="f range")
    )
    max_superelevation_percent: float | None = Field(
        description=describe("The request's e_max, when given.", unit="%", symbol="e_max")
    )
    curves: int = Field(description=describe("Curves in the request.", unit="count"))
    csv_dialect: CsvDialectOut | None = Field(
        description=describe(
            "The CSV dialect detected when the curves came as CSV (`csv`, or an upload to /assess/csv); null "
            "otherwise.",
            unit="see its fields",
        )
    )
    reading: ReadingOut | None = Field(
        description=describe(
            "What was read from a road file (LandXML, IFC): null when the curves came as JSON or CSV.",
            unit="see its fields",
        )
    )
    advisory: AdvisoryOut = Field(
        description=describe("The options and sources of the rows' advisory figures.", unit="see its fields")
    )
    vehicles: list[VehicleAssessment] = Field(description=describe("One entry per vehicle.", unit="see its fields"))
    engine_version: str = Field(description=describe("Engine version (part of the cache key).", unit="-"))

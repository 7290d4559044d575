"""POST /v1/routes/assess: a route as geometry (GeoJSON or GPX) -> its horizontal curves, each assessed for the
vehicles like a curve of an alignment."""

from __future__ import annotations

from typing import Any, Literal

from pydantic import ConfigDict, Field, model_validator

from app.advisory.schemas import AdvisoryOptions
from app.alignments.schemas import MAX_VEHICLES, AdvisoryOut, CurveRow, SpeedPointOut, VehicleAssessment
from app.catalog.schemas import FLEET_ID_PATTERN
from app.formats.route_io import MAX_LENGTH_M, MAX_PARTS, MAX_VERTICES
from app.http.schemas import (
    ABSENT,
    EXAMPLE_PRESET,
    InputModel,
    InputWarningOut,
    OutputModel,
    bounded,
    describe,
    exactly_one_schema,
    shape_error,
)
from app.road.standards_schemas import BOUND_ONLY_WITH_TABLE21, DesignOptions
from app.srt.schemas import VEHICLE_DESCRIPTION, SrtOptions, SrtTargets, VehicleRef
from engine import BOUNDS

#: the model's domain of a curve (:data:`engine.domain.BOUNDS`): a route's curve outside it is a row with ``error``
MIN_RADIUS_M = BOUNDS["radius_m"].minimum
MAX_GRADE_PERCENT = BOUNDS["slope_percent"].maximum

#: the synchronous request's vertices: a track of 200 km at 10 m, two fifths of the route docs/routes.md "Speed" times
#: (the correlated-noise row is the slow one), what a page waits for; the page sends a larger file as a job, and a job
#: reads up to :data:`~app.formats.route_io.MAX_VERTICES`
MAX_SYNC_VERTICES = 20_000

#: a GeoJSON document or GPX text: 100,000 vertices are about 5 MB of GeoJSON and 10 MB of GPX
ROUTE_BODY_LIMIT = 32 * 2**20
MAX_GPX_CHARS = 30_000_000

#: a short S-bend on a hillside (two curves of about 150 m and 250 m radius), lon/lat/ele as a GPS logs it
_EXAMPLE_COORDS = [
    [-47.06000, -22.90000, 600.0],
    [-47.05800, -22.90000, 604.0],
    [-47.05700, -22.89990, 606.0],
    [-47.05620, -22.89965, 608.0],
    [-47.05560, -22.89925, 609.0],
    [-47.05520, -22.89870, 610.0],
    [-47.05500, -22.89800, 611.0],
    [-47.05500, -22.89600, 614.0],
    [-47.05490, -22.89500, 616.0],
    [-47.05460, -22.89420, 617.0],
    [-47.05410, -22.89360, 618.0],
    [-47.05340, -22.89320, 619.0],
    [-47.05250, -22.89300, 620.0],
    [-47.05000, -22.89300, 623.0],
]
EXAMPLE_GEOJSON: dict[str, Any] = {
    "type": "FeatureCollection",
    "features": [
        {
            "type": "Feature",
            "properties": {"name": "SP-083 km 12", "posted_speed_kmh": 60},
            "geometry": {"type": "LineString", "coordinates": _EXAMPLE_COORDS},
        }
    ],
}
EXAMPLE_GPX = (
    '<gpx version="1.1" creator="example" xmlns="http://www.topografix.com/GPX/1/1"><trk><name>S-bend</name><trkseg>'
    + "".join(f'<trkpt lat="{la}" lon="{lo}"><ele>{el}</ele></trkpt>' for lo, la, el in _EXAMPLE_COORDS)
    + "</trkseg></trk></gpx>"
)


class Detection(InputModel):
    """How the curves are found (docs/routes.md): the defaults suit GPS tracks and GIS centrelines."""

    noise_m: float = Field(
        None,
        ge=0,
        le=50,
        json_schema_extra=ABSENT,
        description=describe(
            "Position noise of the vertices (GPS: 2-5 m; a surveyed centreline: 0); default: estimated from the "
            "vertices.",
            unit="m",
            symbol="sigma",
        ),
    )  # type: ignore[assignment]
    max_radius_m: float = Field(
        5000.0,
        ge=200,
        le=20_000,
        description=describe(
            "Curves flatter than this are tangents (at 120 km/h a 5000 m radius needs 0.023 g).", unit="m", symbol="R"
        ),
    )
    min_deflection_deg: float = Field(
        1.0, ge=0.1, le=45, description=describe("Smaller changes of direction are not curves.", unit="deg")
    )


class RouteRequest(SrtOptions, SrtTargets, DesignOptions, AdvisoryOptions):
    """The vehicle(s), the SRT options, the design standard, and the route as `geojson` (a GeoJSON object:
    `FeatureCollection`/`Feature` of `LineString`/`MultiLineString`, WGS84 lon/lat, optional elevation [m] as the
    third coordinate) or `gpx` (GPX 1.1 text: tracks and routes, with `<ele>`). Limits: {vertices} vertices,
    {parts} line parts and {km} km of route per request; a longer track (up to {job_vertices} vertices) or a
    larger network: `POST /v1/jobs` (`routes.assess`)."""

    model_config = ConfigDict(
        json_schema_extra={
            "allOf": [
                exactly_one_schema("vehicle", "vehicles", "fleet"),
                exactly_one_schema("geojson", "gpx"),
                BOUND_ONLY_WITH_TABLE21,
            ],
            "examples": [
                {
                    "vehicle": EXAMPLE_PRESET,
                    "geojson": EXAMPLE_GEOJSON,
                    "superelevation_percent": 6.0,
                    "rear_llt_limit": 0.6,
                },
                {
                    "vehicle": EXAMPLE_PRESET,
                    "gpx": EXAMPLE_GPX,
                    "max_superelevation_percent": 8.0,
                    "posted_speed_kmh": 60.0,
                },
            ],
        }
    )

    vehicle: VehicleRef = Field(
        None, description=VEHICLE_DESCRIPTION + " Give one of `vehicle`, `vehicles`, `fleet`.", json_schema_extra=ABSENT
    )  # type: ignore[assignment]
    vehicles: list[VehicleRef] = Field(
        None,
        json_schema_extra=ABSENT,
        min_length=1,
        max_length=MAX_VEHICLES,
        description=describe(
            f"Several vehicles (1-{MAX_VEHICLES}), each assessed on every curve.", unit="-", symbol="Tables 14-16"
        ),
    )  # type: ignore[assignment]
    fleet: str = Field(
        None,
        json_schema_extra=ABSENT,
        pattern=FLEET_ID_PATTERN,
        description=describe("A saved fleet's id (`flt_...`, with the key that saved it).", unit="-"),
    )  # type: ignore[assignment]
    geojson: dict[str, Any] = Field(
        None,
        json_schema_extra=ABSENT,
        description=describe(
            "The route as a GeoJSON object (RFC 7946): a `FeatureCollection`, a `Feature` or a bare `LineString` / "
            "`MultiLineString`; positions `[lon, lat]` or `[lon, lat, elevation_m]` (WGS84). A feature's "
            "`properties` may give `superelevation_percent`, `posted_speed_kmh`, `name`, `id` for its curves.",
            unit="deg, m",
            symbol="-",
        ),
    )  # type: ignore[assignment]
    gpx: str = Field(
        None,
        json_schema_extra=ABSENT,
        min_length=1,
        max_length=MAX_GPX_CHARS,
        description=describe(
            "The route as GPX 1.1 text: every track segment (`trk/trkseg/trkpt`) and route (`rte/rtept`), with "
            "`<ele>` when logged.",
            unit="deg, m",
        ),
    )  # type: ignore[assignment]
    superelevation_percent: float = bounded(
        "design_superelevation_percent",
        None,
        text="Superelevation of every curve that gives none (a feature's `superelevation_percent` wins). Without "
        "it and without a feature value, `max_superelevation_percent` derives it from the standard.",
        symbol="e",
    )
    max_superelevation_percent: float = bounded(
        "max_superelevation_percent",
        None,
        text="The road's e_max: curves without a superelevation take the standard's design value for their posted "
        "speed, and each curve's minimum radius is the standard's for this e_max.",
        symbol="e_max",
    )
    posted_speed_kmh: float = bounded(
        "speed_kmh",
        None,
        text="Posted speed of every curve that gives none (a feature's `posted_speed_kmh` wins); the margin and the "
        "flag are against it.",
        symbol="V",
    )
    grade_percent: float = bounded(
        "slope_percent",
        None,
        text="Grade of every curve whose grade is not read from elevations (no elevations, or `use_elevation` "
        "false); default 0.",
        symbol="slope",
    )
    parts: Literal["trk", "rte", "all"] = Field(
        None,
        json_schema_extra=ABSENT,
        description=describe(
            "GPX: which parts are read: `trk` (the track segments: the geometry a device logged or a router drew), "
            "`rte` (the routes: a plan's or a router's turn points), `all`. Default: the tracks when the file has any "
            "with points, else its routes; a router's file that holds the same path as `<rte>` turn points and as "
            "`<trk>` geometry is read once, its route listed in `reading.skipped`. Ignored for GeoJSON.",
            unit="-",
        ),
    )  # type: ignore[assignment]
    use_elevation: bool = Field(
        True,
        description=describe(
            "Whether the grades come from the document's elevations (GPX `<ele>`, a GeoJSON position's third "
            "coordinate): a least-squares line of elevation against distance over each curve (docs/routes.md), "
            f"clipped to +/-{MAX_GRADE_PERCENT:g} % (`grade_clipped`). False: every curve takes `grade_percent` (0 "
            "by default), e.g. when the elevations are a GPS's or a coarse DEM's.",
            unit="-",
        ),
    )
    detection: Detection = Field(
        default_factory=Detection,
        description=describe("How the curves are found (defaults suit GPS tracks).", unit="see its fields"),
    )

    @model_validator(mode="after")
    def _one_source_each(self) -> RouteRequest:
        for names in (("vehicle", "vehicles", "fleet"), ("geojson", "gpx")):
            present = [n for n in names if getattr(self, n) is not None]
            if len(present) != 1:
                what = "both " + " and ".join(present) if present else "none"
                raise shape_error(
                    "RouteRequest",
                    present[1] if len(present) > 1 else names[0],
                    f"give exactly one of {', '.join(names)} ({what} given)",
                )
        return self


RouteRequest.__doc__ = (RouteRequest.__doc__ or "").format(
    vertices=f"{MAX_SYNC_VERTICES:,}",
    job_vertices=f"{MAX_VERTICES:,}",
    parts=f"{MAX_PARTS:,}",
    km=f"{MAX_LENGTH_M / 1000:,.0f}",
)


# ------------------------------------------------------------------------------------------- output


class RouteCurveRow(CurveRow):
    """A vehicle's assessment of a route's curve: an alignment's row; on a curve outside the model's domain (a radius
    below the smallest a heavy vehicle can turn on: a car park's or a junction's manoeuvre) `error` says why, `flagged`
    is true and every computed value (SRT, speeds, side friction, a superelevation derived from the radius) is null."""

    superelevation_percent: float | None = Field(
        description=describe(
            "Superelevation used (given, or derived: see `superelevation_source`); null on a row outside the model's "
            "domain whose superelevation would be derived from its radius.",
            unit="%",
            symbol="e",
        )
    )
    side_friction_speed_kmh: float | None = Field(
        description=describe(
            "Side-friction speed (Eq. 9.2 solved for V); null on a row outside the model's domain.",
            unit="km/h",
            symbol="V_f",
        )
    )
    side_friction: float | None = Field(
        description=describe(
            "The standard's side-friction factor at that speed; null on a row outside the model's domain.",
            unit="-",
            symbol="f",
        )
    )
    side_friction_clamped: bool | None = Field(
        description=describe(
            "The side-friction speed lies outside the standard's table (its end value used); null on a row outside "
            "the model's domain.",
            unit="-",
        )
    )


class RouteCurveProperties(OutputModel):
    """A curve found on the route, and its assessment for the vehicle that governs it (the lowest safe speed)."""

    id: str = Field(description=describe("Curve id: `<part>-C<k>`, numbered along the part from 1.", unit="-"))
    part: str = Field(
        description=describe("The line part it lies on (`features[0]`, `trk[1] 'A1' trkseg[1]`).", unit="-")
    )
    name: str | None = Field(description=describe("The part's `name` property, if any.", unit="-"))
    direction: Literal["left", "right"] = Field(description=describe("Turning direction in travel order.", unit="-"))
    radius_m: float = Field(
        description=describe(
            "Radius of the circular part as fitted (the sharpest arc of a compound curve); the safe speed uses "
            "`radius_lower_m`.",
            unit="m",
            symbol="R",
        )
    )
    radius_lower_m: float = Field(
        description=describe(
            "Conservative radius: one-sided 95 % lower confidence bound of the circular part's radius (the true "
            "radius is at least this with 95 % confidence given the track's noise), allowing for transition spirals "
            "the noise hides (such a curve is fitted as a simple curve of a larger `radius_m`); the assessment and "
            "its safe speed (Eq. 9.1) use it, so GPS noise lowers a safe speed rather than raising it. Equal to "
            "`radius_m` without noise (docs/routes.md: the method and its calibration).",
            unit="m",
            symbol="R_lower (95 %)",
        )
    )
    radius_std_m: float | None = Field(
        description=describe(
            "Standard error (1 sigma) of the fitted radius from the vertex noise, the error of the tangents and with "
            "them of the curve's ends included, with white or correlated noise (`parts[].noise_corr_m`); null "
            "without noise (the radius is then exact). Calibrated on synthetic tracks of known geometry "
            "(docs/routes.md).",
            unit="m",
            symbol="sigma_R",
        )
    )
    start_m: float = Field(
        description=describe("Chainage of the curve's start (tangent to spiral or curve).", unit="m")
    )
    end_m: float = Field(description=describe("Chainage of the curve's end.", unit="m"))
    arc_start_m: float = Field(description=describe("Chainage where the circular arc starts.", unit="m"))
    arc_end_m: float = Field(description=describe("Chainage where the circular arc ends.", unit="m"))
    length_m: float = Field(description=describe("Length of the whole curve.", unit="m"))
    deflection_deg: float = Field(description=describe("Total change of direction over the curve.", unit="deg"))
    spiral_in_m: float | None = Field(description=describe("Entry transition length, if resolved.", unit="m"))
    spiral_out_m: float | None = Field(description=describe("Exit transition length, if resolved.", unit="m"))
    grade_percent: float | None = Field(
        description=describe(
            "Grade over the curve from the elevations as read: the slope of the least-squares line of elevation "
            "against distance along the curve, + uphill in the direction of travel; null without elevations or with "
            "`use_elevation` false. The assessment uses it clipped to the model's domain (`grade_clipped`), or the "
            "request's `grade_percent` (`grade_source`).",
            unit="%",
            symbol="slope",
        )
    )
    grade_source: Literal["elevations", "request"] = Field(
        description=describe(
            "Where the assessed grade came from: the document's `elevations`, or the `request` (`grade_percent`, 0 by "
            "default) where there are none or `use_elevation` is false.",
            unit="-",
        )
    )
    grade_clipped: bool = Field(
        description=describe(
            f"The grade from the elevations lies beyond +/-{MAX_GRADE_PERCENT:g} %, the model's domain (what GPS or "
            "DEM elevations make between close fixes): the assessment used the bound, `grade_percent` keeps the "
            "value read.",
            unit="-",
        )
    )
    compound: bool = Field(description=describe("Several arcs of one direction with no tangent between.", unit="-"))
    sparse: bool = Field(
        description=describe("Fewer than 3 vertices on the arc: the radius is less certain.", unit="-")
    )
    truncated: bool = Field(description=describe("The curve runs into the start or end of its part.", unit="-"))
    vertices: list[int] = Field(
        description=describe(
            "First and last vertex of the curve in the part's vertex list, as in the document (on a road joined "
            "from OSM ways, along the joined road: `parts[].ways`).",
            unit="-",
        )
    )
    governing_vehicle: int = Field(
        description=describe("Index of the vehicle with the lowest safe speed (its row is `assessment`).", unit="-")
    )
    assessment: RouteCurveRow = Field(
        description=describe(
            "The governing vehicle's assessment, of the conservative radius (its `radius_m` is `radius_lower_m`); a "
            "curve outside the model's domain has `error` and no speeds.",
            unit="see its fields",
        )
    )
    vehicles: list[RouteCurveRow] | None = Field(
        description=describe("Every vehicle's assessment, in the request's order (only with several).", unit="-")
    )
    advisory_speed_kmh: float | None = Field(
        description=describe(
            "The lowest advisory speed shown over the vehicles (`assessment.advisory_speed_kmh` per vehicle): flat, "
            "for a GIS to label or colour by.",
            unit="km/h",
        )
    )
    treatment_devices: str | None = Field(
        description=describe(
            "The devices the curve's treatment calls for (the lowest advisory speed's), joined by `;`; null: none or "
            "no posted speed. Flat, for a GIS to colour by.",
            unit="-",
        )
    )
    truck_rollover_warning: bool = Field(
        description=describe("A W1-13 is recommended for any vehicle (this service's rule; see `advisory`).", unit="-")
    )


class RouteCurve(RouteCurveProperties):
    """A curve found on the route with its assessment, and its vertices."""

    coordinates: list[list[float]] = Field(
        description=describe(
            "The curve's vertices as in the route: [lon, lat] or [lon, lat, ele] (WGS84 degrees, metres).",
            unit="deg, deg, m",
        )
    )


class RouteFeature(OutputModel):
    type: Literal["Feature"] = Field(description=describe("GeoJSON object type.", unit="-"))
    geometry: dict[str, Any] = Field(
        description=describe(
            "The curve as a GeoJSON `LineString` of the route's vertices [lon, lat(, ele)].", unit="deg"
        )
    )
    properties: RouteCurveProperties = Field(description=describe("The curve and its assessment.", unit="-"))


class RouteCurves(OutputModel):
    type: Literal["FeatureCollection"] = Field(description=describe("GeoJSON object type.", unit="-"))
    features: list[RouteFeature] = Field(description=describe("One feature per curve, in route order.", unit="-"))
    reading: RouteReading = Field(
        description=describe("What was read from the file (a foreign member, RFC 7946 section 6.1).", unit="-")
    )
    advisory: AdvisoryOut = Field(
        description=describe(
            "The options and sources of the advisory figures (a foreign member, RFC 7946 section 6.1).",
            unit="see its fields",
        )
    )
    warnings: list[InputWarningOut] = Field(
        description=describe(
            "Every vehicle's inputs answered as given that read plausibly in another unit too, each naming its "
            "vehicle (`vehicles[1].weight_kn`; the JSON answer lists them per vehicle), empty when none: check "
            "them (a foreign member, RFC 7946 section 6.1).",
            unit="see its fields",
        )
    )


class RoutePartOut(OutputModel):
    part: str = Field(description=describe("Where the part is in the document.", unit="-"))
    name: str | None = Field(description=describe("Its `name` property, if any.", unit="-"))
    vertices: int = Field(description=describe("Distinct vertices read.", unit="count"))
    length_m: float = Field(
        description=describe("Length along the road (GPS noise taken out of the polyline's length).", unit="m")
    )
    curves: int = Field(description=describe("Curves found.", unit="count"))
    noise_m: float = Field(description=describe("Position noise used (given or estimated).", unit="m", symbol="sigma"))
    noise_corr_m: float = Field(
        description=describe(
            "Correlation length of the position noise along the track, estimated (0: white noise, the fixes' errors "
            "independent; a GPS receiver's drift is correlated over tens of metres): the radius uncertainties count "
            "it (docs/routes.md).",
            unit="m",
            symbol="L",
        )
    )
    has_elevation: bool = Field(
        description=describe("Whether the part has elevations (used unless `use_elevation` is false).", unit="-")
    )
    ways: list[str] | None = Field(
        description=describe(
            "An OSM road joined from ways that meet end to end: its features in travel order (` reversed` where a "
            "way is drawn the other way); its `vertices` then count along the joined road. Null for a single line.",
            unit="-",
        )
    )


class RouteSkippedOut(OutputModel):
    """Something in the document that was read but not used, and why."""

    what: str = Field(description=describe("What was not used: the part, feature or tag as in the document.", unit="-"))
    why: str = Field(description=describe("Why it was not used.", unit="-"))


class RouteReading(OutputModel):
    """What was read from the file and what was not (nothing is dropped silently)."""

    format: str = Field(description=describe("The document's format: `GPX 1.1`, `GPX 1.0` or `GeoJSON`.", unit="-"))
    writer: str | None = Field(
        description=describe(
            "The application that wrote it, where the file says: the GPX `creator`, the GeoJSON `generator`.", unit="-"
        )
    )
    linear_unit: str = Field(
        description=describe(
            "Length unit of the file's elevations (GPX and GeoJSON: `meter`; positions are WGS84 degrees).", unit="-"
        )
    )
    alignments: list[str] = Field(
        description=describe("The parts read (tracks' segments, routes, lines, joined roads), in order.", unit="-")
    )
    elements: dict[str, int] = Field(
        description=describe(
            "What the document holds, by type (GPX: `trk`, `trkseg`, `trkpt`, `rte`, `rtept`, `wpt`; GeoJSON: "
            "features by geometry type, and the roads joined from OSM ways).",
            unit="count",
        )
    )
    profile: str | None = Field(
        description=describe(
            "Where the grades came from: `elevations` (the document's), or null (none read: the request's "
            "`grade_percent`).",
            unit="-",
        )
    )
    superelevation_from: Literal["file", "request", "standard"] | None = Field(
        description=describe(
            "Where the curves' superelevation came from: the features' `superelevation_percent` (`file`, where any "
            "gives it), the request's `superelevation_percent`, or the standard's distribution "
            "(`max_superelevation_percent`); null without curves.",
            unit="-",
        )
    )
    skipped: list[RouteSkippedOut] = Field(
        description=describe(
            "What was read but not used, and why: empty track segments, a router's `<rte>` beside its `<trk>`, "
            "features that are not lines, `maxspeed` values that are not a speed.",
            unit="-",
        )
    )


class RouteSpeedPointOut(SpeedPointOut):
    part: str = Field(
        description=describe(
            "The line part the point lies on (as the curves' `part`): each part has its own profile, its stations "
            "along that part (the parts are not connected: no profile runs from one to the next).",
            unit="-",
        )
    )


class RouteVehicleAssessment(VehicleAssessment):
    speed_profile: list[RouteSpeedPointOut] = Field(  # type: ignore[assignment]
        description=describe(
            "The truck's speed profile along the curves of each part (engine/road/profile.py; docs/advisory.md): "
            "its speed at each station of a part, linear in speed squared between them, the parts one after the "
            "other; a part whose curves' stations cannot carry one has none (the rows' `profile_reason`, "
            "`speed_profile_notes`).",
            unit="per field",
        )
    )


class RouteResult(OutputModel):
    """The route's curves, each with its geometry, vertices and assessment; per-vehicle summaries; what was read.
    `Accept: application/geo+json` answers the curves as a GeoJSON FeatureCollection instead (ready for a GIS)."""

    model: str = Field(
        description=describe(
            "Model used: the request's, else `3d` for records, `combination` for combinations, `default` for a mix "
            "(each vehicle with its own).",
            unit="-",
        )
    )
    stage: str | None = Field(description=describe("Stage (3d only).", unit="-", symbol="SRT_TS / SRT_3D"))
    design_standard: str = Field(description=describe("The design standard used.", unit="-"))
    length_m: float = Field(description=describe("Total route length.", unit="m"))
    parts: list[RoutePartOut] = Field(description=describe("The line parts read, in document order.", unit="-"))
    vehicles: list[RouteVehicleAssessment] = Field(
        description=describe(
            "One entry per vehicle: its summary over the curves (`rows` empty: see `curves`).", unit="-"
        )
    )
    curves: list[RouteCurve] = Field(
        description=describe("The curves, in route order (none on a road without a curve).", unit="-")
    )
    reading: RouteReading = Field(description=describe("What was read from the file and what was not.", unit="-"))
    advisory: AdvisoryOut = Field(
        description=describe("The options and sources of the rows' advisory figures.", unit="see its fields")
    )
    engine_version: str = Field(description=describe("Engine version (part of the cache key).", unit="-"))

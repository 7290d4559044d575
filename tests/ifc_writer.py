"""A writer of IFC 4.3 (``IFC4X3_ADD2``) alignments for the tests and the examples: the neutral records of
:mod:`engine.road.geometry` written with IfcOpenShell's alignment API (``ifcopenshell.api.alignment``: business
logic, the geometric representation it derives from it, the closing zero-length segments and the stationing
referents), in metres, feet or US survey feet.

What it writes, so that :func:`app.formats.ifc_io.read_ifc` has something to read back:

- each element as an ``IfcAlignmentHorizontalSegment`` placed where the previous one ends (the end placement the
  API returns): radii signed + left / - right, 0 for a straight end, the spiral type in upper case;
- each profile of an alignment as an ``IfcAlignmentVertical`` (the first in the alignment, the others in child
  alignments as IFC 4.3 nests several profiles), a circular arc's radius signed + sag / - crest;
- the cross slopes (both sides equal: a cant is one plane) as ``IfcAlignmentCant`` segments between consecutive
  samples, the high side raised by ``RailHeadDistance * sin(atan(slope))`` above the other (on the profile);
- the start station and the station equations as ``STATION`` referents with ``Pset_Stationing``.
"""

from __future__ import annotations

import hashlib
import math
import re
from collections.abc import Sequence

import ifcopenshell
import ifcopenshell.api.alignment
import ifcopenshell.api.project
import ifcopenshell.api.root
import ifcopenshell.api.unit
import ifcopenshell.guid
import numpy as np

from engine.road.geometry import AlignmentGeometry

#: metres per unit, and the name the unit is written with
UNITS = {
    "metre": (1.0, None),
    "foot": (0.3048, "FOOT"),
    "us survey foot": (1200 / 3937, "US SURVEY FOOT"),
}
RAIL_HEAD_DISTANCE_M = 1.5


def _length_unit(f: ifcopenshell.file, unit: str):
    metres, name = UNITS[unit]
    metre = f.createIfcSIUnit(None, "LENGTHUNIT", None, "METRE")
    if name is None:
        return metre
    return f.createIfcConversionBasedUnit(
        f.createIfcDimensionalExponents(1, 0, 0, 0, 0, 0, 0),
        "LENGTHUNIT",
        name,
        f.createIfcMeasureWithUnit(f.createIfcLengthMeasure(metres), metre),
    )


def _horizontal(f, layout, a: AlignmentGeometry, u: float) -> None:
    point, direction = (0.0, 0.0), 0.0
    for e in a.elements:
        sign = 1.0 if e.direction == "left" else -1.0

        def signed(r: float, sign=sign) -> float:
            return 0.0 if math.isinf(r) else sign * r / u

        kind = {"line": "LINE", "arc": "CIRCULARARC"}.get(e.kind) or (e.spiral_type or "clothoid").upper()
        dp = f.createIfcAlignmentHorizontalSegment(
            StartPoint=f.createIfcCartesianPoint(point),
            StartDirection=direction,
            StartRadiusOfCurvature=signed(e.radius_start_m),
            EndRadiusOfCurvature=signed(e.radius_end_m),
            SegmentLength=e.length_m / u,
            PredefinedType=kind,
        )
        end = ifcopenshell.api.alignment.create_layout_segment(f, layout, dp)
        if e.name is not None:
            (segment,) = (s for r in layout.IsNestedBy for s in r.RelatedObjects if s.DesignParameters == dp)
            segment.Name = e.name
        m = np.asarray(end)
        point, direction = (float(m[0, 3]), float(m[1, 3])), math.atan2(float(m[1, 0]), float(m[0, 0]))


def _vertical(f, layout, segments, u: float) -> None:
    for s in segments:
        kind = {"constant": "CONSTANTGRADIENT", "parabolic": "PARABOLICARC", "circular": "CIRCULARARC"}[s.kind]
        if s.kind == "parabolic":
            radius = s.length_m / (s.end_grade - s.start_grade) / u
        elif s.kind == "circular":
            radius = math.copysign(s.radius_m, s.end_grade - s.start_grade) / u
        else:
            radius = None
        dp = f.createIfcAlignmentVerticalSegment(
            StartDistAlong=s.start_distance_m / u,
            HorizontalLength=s.length_m / u,
            StartHeight=s.start_elevation_m / u,
            StartGradient=s.start_grade,
            EndGradient=s.end_grade,
            RadiusOfCurvature=radius,
            PredefinedType=kind,
        )
        ifcopenshell.api.alignment.create_layout_segment(f, layout, dp)


def _cant(f, layout, a: AlignmentGeometry, u: float) -> None:
    layout.RailHeadDistance = RAIL_HEAD_DISTANCE_M / u

    def rise(percent: float) -> float:
        return RAIL_HEAD_DISTANCE_M * math.sin(math.atan(percent / 100)) / u

    for p, q in zip(a.cross_slopes, a.cross_slopes[1:], strict=False):
        assert p.left_percent == p.right_percent and q.left_percent == q.right_percent, "a cant is one plane"
        h0, h1 = rise(p.left_percent), rise(q.left_percent)
        if h0 != h1 and abs(h0) == abs(h1):
            # the high side raised, the other on the profile: IfcOpenShell's mapping of a linear transition
            # divides by the change of the mean height, which a reversal of equal magnitude keeps at zero
            raise ValueError(f"a cross slope reversal of equal magnitude at {p.distance_m} m is not written")
        dp = f.createIfcAlignmentCantSegment(
            StartDistAlong=p.distance_m / u,
            HorizontalLength=(q.distance_m - p.distance_m) / u,
            StartCantLeft=max(0.0, -h0),
            EndCantLeft=max(0.0, -h1),
            StartCantRight=max(0.0, h0),
            EndCantRight=max(0.0, h1),
            PredefinedType="CONSTANTCANT" if h0 == h1 else "LINEARTRANSITION",
        )
        ifcopenshell.api.alignment.create_layout_segment(f, layout, dp)


def write_ifc(
    alignments: Sequence[AlignmentGeometry],
    *,
    unit: str = "metre",
    application: tuple[str, str] = ("rollover tests/ifc_writer.py", "1"),
    stable: bool = False,
) -> bytes:
    """The alignments as an IFC 4.3 (IFC4X3_ADD2) file in ``unit`` (``"metre"``, ``"foot"``,
    ``"us survey foot"``); ``application`` (name, version) is written as the file's IfcApplication and in the header;
    ``stable``: GUIDs numbered instead of random, so that the same records give the same bytes."""
    u = UNITS[unit][0]
    f = ifcopenshell.api.project.create_file(version="IFC4X3")
    org = f.createIfcOrganization(Name="rollover")
    f.createIfcApplication(org, application[1], application[0], application[0].split()[0])
    # no IfcOwnerHistory (optional in IFC 4.3): with one, IfcOpenShell's API stamps every change with the time
    ifcopenshell.api.root.create_entity(f, ifc_class="IfcProject", name="rollover road")
    ifcopenshell.api.unit.assign_unit(
        f, units=[_length_unit(f, unit), f.createIfcSIUnit(None, "PLANEANGLEUNIT", None, "RADIAN")]
    )
    for a in alignments:
        # several profiles: each in a child alignment (IFC CT 4.1.4.4.1.2, what add_vertical_layout builds), and
        # the cant is then written with none of them
        has_cant = len(a.cross_slopes) > 1 and len(a.profiles) <= 1
        alignment = ifcopenshell.api.alignment.create(
            f, a.name, include_vertical=len(a.profiles) == 1, include_cant=has_cant
        )
        _horizontal(f, ifcopenshell.api.alignment.get_horizontal_layout(alignment), a, u)
        if len(a.profiles) == 1:
            vertical = ifcopenshell.api.alignment.get_vertical_layout(alignment)
            vertical.Name = a.profiles[0].name
            _vertical(f, vertical, a.profiles[0].segments, u)
        elif a.profiles:
            for p in a.profiles:
                layout = ifcopenshell.api.alignment.add_vertical_layout(f, alignment)
                layout.Name = p.name
                _vertical(f, layout, p.segments, u)
        if has_cant:
            _cant(f, ifcopenshell.api.alignment.get_cant_layout(alignment), a, u)
        ifcopenshell.api.alignment.add_stationing_referent(
            f, f"{a.start_station_m / u:g}", alignment, 0.0, a.start_station_m / u
        )
        for eq in a.station_equations:
            ifcopenshell.api.alignment.add_stationing_referent(
                f,
                f"{eq.station_ahead_m / u:g}",
                alignment,
                eq.distance_m / u,
                eq.station_ahead_m / u,
                incoming_station=eq.station_back_m / u,
            )
    header = f.header.file_name
    header.name = "rollover.ifc"
    header.time_stamp = "2026-01-01T00:00:00"
    header.originating_system = header.preprocessor_version = application[0]
    text = f.to_string()
    if stable:  # the same file every time (examples/ is checked against what make_examples.py writes)
        guids: dict[str, str] = {}

        def stable_guid(m: re.Match) -> str:
            g = guids.setdefault(m[2], ifcopenshell.guid.compress(hashlib.md5(f"{len(guids)}".encode()).hexdigest()))
            return f"{m[1]}{g}'"

        text = re.sub(r"(=IFC[A-Z0-9]+\(')([0-9A-Za-z_$]{22})'", stable_guid, text)
    return text.encode()

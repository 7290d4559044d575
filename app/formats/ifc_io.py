"""IFC 4.3 (ISO 16739-1:2024, schema ``IFC4X3_ADD2``) alignments read into the neutral road geometry of
:mod:`engine.road.geometry`, with IfcOpenShell.

What is read (the business logic of the alignment, not its geometric representation):

- **Units**: the project's ``IfcUnitAssignment`` ``LENGTHUNIT``: an ``IfcSIUnit`` metre with any SI prefix, or an
  ``IfcConversionBasedUnit`` whose ``ConversionFactor`` is a length in another length unit (recursively). A unit
  named as a foot (``FOOT``, ``FEET``), a US survey foot, an inch, a yard or a mile takes the exact definition
  (0.3048 m, 1200/3937 m, 0.0254 m, 0.9144 m, 1609.344 m) when the file's factor agrees with it to 1e-7, and is
  refused when it does not (a US survey foot and an international foot differ by 2e-6); any other name takes the
  file's own factor. Every length read is converted: segment lengths, radii, distances along, heights, cants, the
  rail head distance, stations. No angle is used (the horizontal ``StartDirection`` and ``StartPoint`` only place
  the road in the plane), so the plane angle unit is not read.
- **Horizontal**: ``IfcAlignment`` > ``IfcAlignmentHorizontal`` > ``IfcAlignmentSegment.DesignParameters``
  (``IfcAlignmentHorizontalSegment``) in nesting order: ``SegmentLength``, ``StartRadiusOfCurvature`` and
  ``EndRadiusOfCurvature`` (signed: + centre of curvature on the left (counter-clockwise), - on the right; 0 =
  straight), ``PredefinedType``. ``LINE`` (both radii 0), ``CIRCULARARC`` (both radii equal), and the transitions
  ``CLOTHOID``, ``CUBIC``, ``HELMERTCURVE``, ``BLOSSCURVE``, ``COSINECURVE``, ``SINECURVE`` as spirals between their
  two end radii, ``spiral_type`` the IFC name in lower case: the radius of each never falls below the smaller end
  radius (the curvature of the clothoid, Bloss, cosine, sine and Helmert transitions varies monotonically from end
  to end; the cubic parabola y = x^3 / (6 R L) has curvature (x / R L) / (1 + (x^2 / 2 R L)^2)^1.5, at most
  1 / R), so the smaller end radius is the one a bend's assessment takes. ``VIENNESEBEND`` is refused: its plan
  curvature has a term of the cant and the height of the centre of gravity (``GravityCenterLineHeight``), so its
  end radii do not bound it. A clothoid whose end radii have opposite signs (an S through an inflection) is split
  at the inflection (its curvature is linear in length, so at ``L k1 / (k1 - k2)``); another transition that
  changes side is refused. Zero-length segments (the closing segment IFC 4.3 asks for) are listed as skipped.
- **Vertical**: each ``IfcAlignmentVertical`` (the alignment's own, then those of its child alignments,
  ``IfcRelAggregates``, in entity-id order) is one :class:`~engine.road.geometry.Profile`: ``CONSTANTGRADIENT``,
  ``PARABOLICARC`` (the grade linear from ``StartGradient`` to ``EndGradient``) and ``CIRCULARARC``
  (``RadiusOfCurvature``, + sag, - crest; checked against the grades) segments. A profile with a vertical
  ``CLOTHOID`` is skipped whole and listed.
- **Cant**: ``IfcAlignmentCant`` (``RailHeadDistance``) segments' ``StartCantLeft``/``StartCantRight`` and
  ``EndCantLeft``/``EndCantRight`` (heights of the two sides above the profile) become a
  :class:`~engine.road.geometry.CrossSlope` at each segment's start and end: the plane through both sides, rising
  from left to right, ``100 tan(asin((right - left) / RailHeadDistance))`` percent, the rail head distance being
  the distance between the two points (its definition: "between the nominal centre points of the two contact
  patches") as IfcOpenShell's cant mapping takes it. Between the samples a transition's own shape is not kept.
- **Stations**: ``IfcReferent`` nested in the alignment with ``PredefinedType`` ``STATION`` and
  ``Pset_Stationing.Station``, placed by an ``IfcLinearPlacement`` (``IfcPointByDistanceExpression.DistanceAlong``):
  the one at distance 0 (or the first one without a linear placement, as ``ifcopenshell.api.alignment`` reads it)
  is the start station; one further along is a station equation (``IncomingStation`` its back station, else the
  station the running stationing gives there). Without one the start station is 0 and the alignment's notes say so.
  Decreasing stationing (``HasIncreasingStation`` false) is refused.
- **Writer**: the project's ``OwnerHistory.OwningApplication``, else the file's only ``IfcApplication``, else the
  header's originating system.

The schema is checked on the header before anything is parsed: a file labelled with another schema (IFC2X3, IFC4,
an IFC4X3 release candidate such as ``IFC4X3_RC3``, or an earlier IFC 4.3 such as ``IFC4X3_ADD1``) is refused with
its schema's name. IfcOpenShell accepts a value of the wrong type without complaint (a string where a length
belongs, an unknown enumeration as null), so every value read is checked here. Errors are
:class:`app.formats.alignment_io.AlignmentFormatError` naming the entity (``#id`` and type), the attribute and the
value.
"""

from __future__ import annotations

import dataclasses
import math
import re
from collections import Counter
from collections.abc import Iterable
from typing import Any

from app.formats.alignment_io import AlignmentFormatError
from engine.road import (
    AlignmentGeometry,
    CrossSlope,
    HorizontalElement,
    Profile,
    RoadFile,
    StationEquation,
    VerticalSegment,
)

SCHEMA = "IFC4X3_ADD2"
FORMAT = "IFC 4.3 (IFC4X3_ADD2)"

#: SI prefixes (IfcSIPrefix) as powers of ten
_SI_PREFIX = {
    "EXA": 18,
    "PETA": 15,
    "TERA": 12,
    "GIGA": 9,
    "MEGA": 6,
    "KILO": 3,
    "HECTO": 2,
    "DECA": 1,
    "DECI": -1,
    "CENTI": -2,
    "MILLI": -3,
    "MICRO": -6,
    "NANO": -9,
    "PICO": -12,
    "FEMTO": -15,
    "ATTO": -18,
}
#: named length units and their exact definitions [m]: the international foot, inch, yard and mile (1959
#: international yard and pound agreement: 1 yd = 0.9144 m) and the US survey foot (1200/3937 m, the Mendenhall
#: order of 1893, as NIST SP 811 gives it); keys are the names with case, spaces, '-', '_' and '.' removed
_NAMED_LENGTH = {
    "foot": 0.3048,
    "feet": 0.3048,
    "ft": 0.3048,
    "internationalfoot": 0.3048,
    "ussurveyfoot": 1200 / 3937,
    "ussurveyfeet": 1200 / 3937,
    "surveyfoot": 1200 / 3937,
    "usfoot": 1200 / 3937,
    "inch": 0.0254,
    "inches": 0.0254,
    "yard": 0.9144,
    "mile": 1609.344,
}
#: the agreement a named unit's factor must have with its definition (a US survey foot and an international foot
#: differ by 2.0e-6 relative; writers round the factor to 8-15 digits)
_NAMED_TOLERANCE = 1e-7

_SPIRALS = ("CLOTHOID", "CUBIC", "HELMERTCURVE", "BLOSSCURVE", "COSINECURVE", "SINECURVE")
_CANT_TYPES = (
    "CONSTANTCANT",
    "LINEARTRANSITION",
    "BLOSSCURVE",
    "COSINECURVE",
    "SINECURVE",
    "HELMERTCURVE",
    "VIENNESEBEND",
)
_HEADER_SCAN = 64 * 1024  # the header section comes first; FILE_SCHEMA is found within this many bytes
_FILE_SCHEMA = re.compile(rb"FILE_SCHEMA\s*\(\s*\(\s*'([^']*)'", re.IGNORECASE)
_NON_ASCII = re.compile(r"[^\x00-\x7f]+")


def _step_escape(run: re.Match[str]) -> str:
    """A run of characters outside ASCII as ISO 10303-21 writes it in a string: ``\\X2\\`` and four hex digits per
    UTF-16 code unit, or ``\\X4\\`` and eight per character where one lies beyond the Basic Multilingual Plane."""
    chars = run.group(0)
    if all(ord(c) <= 0xFFFF for c in chars):
        return "\\X2\\" + "".join(f"{ord(c):04X}" for c in chars) + "\\X0\\"
    return "\\X4\\" + "".join(f"{ord(c):08X}" for c in chars) + "\\X0\\"


#: a circular vertical arc's horizontal length against the one its radius and end grades give (relative)
_ARC_TOLERANCE = 1e-3
_Entity: Any = None  # ifcopenshell.entity_instance, once ifcopenshell is imported (on the first file read)


def _ref(e: Any) -> str:
    return f"#{e.id()} {e.is_a()}"


def _is(v: Any, ifc_type: str) -> bool:
    """``v`` is an entity of ``ifc_type`` (IfcOpenShell hands over whatever the file wrote where an entity belongs:
    None, a number, a string, a list)."""
    return _Entity is not None and isinstance(v, _Entity) and v.is_a(ifc_type)


def _entities(v: Any) -> list[Any]:
    """The entities of an aggregate attribute (anything else in it dropped)."""
    return [o for o in v if _Entity is not None and isinstance(o, _Entity)] if isinstance(v, tuple | list) else []


def _describe(v: Any) -> str:
    return _ref(v) if _Entity is not None and isinstance(v, _Entity) else repr(v)[:80]


def _real(e: Any, attr: str, where: str, *, optional: bool = False) -> float | None:
    """Attribute ``attr`` of entity ``e`` as a finite float (None when optional and unset)."""
    v = getattr(e, attr)
    if v is None:
        if optional:
            return None
        raise AlignmentFormatError(f"{attr} is not set", where, attr)
    if hasattr(v, "wrappedValue"):  # a typed measure (IFCLENGTHMEASURE(12.))
        v = v.wrappedValue
    if isinstance(v, bool) or not isinstance(v, int | float):
        raise AlignmentFormatError(f"{attr} is not a number: {v!r}"[:300], where, attr)
    v = float(v)
    if not math.isfinite(v):
        raise AlignmentFormatError(f"{attr} must be finite, got {v!r}", where, attr)
    return v


def _length(e: Any, attr: str, where: str, unit: float, *, nonnegative: bool = False) -> float:
    v = _real(e, attr, where)
    assert v is not None
    if nonnegative and v < 0:
        raise AlignmentFormatError(f"{attr} must not be negative, got {v!r}", where, attr)
    return v * unit


def _enum(e: Any, attr: str, where: str, allowed: Iterable[str]) -> str:
    v = getattr(e, attr)
    if not isinstance(v, str) or not v:
        # IfcOpenShell reads an enumeration value the schema does not define as null
        raise AlignmentFormatError(f"{attr} is not set or not a value the schema defines", where, attr)
    if v not in allowed:
        raise AlignmentFormatError(f"{attr} {v} is not read (read: {', '.join(allowed)})", where, attr)
    return v


def _text(v: Any) -> str | None:
    return v.strip() or None if isinstance(v, str) else None


# -- the file ---------------------------------------------------------------------------------------------------


def _schema_of(data: bytes) -> str:
    head = data[:_HEADER_SCAN]
    if not head.lstrip(b"\xef\xbb\xbf \t\r\n").startswith(b"ISO-10303-21;"):
        raise AlignmentFormatError(
            "not an IFC file: an IFC 4.3 file is ISO 10303-21 text (STEP) that begins with 'ISO-10303-21;'"
        )
    m = _FILE_SCHEMA.search(head)
    if m is None:
        raise AlignmentFormatError("the header names no schema (FILE_SCHEMA)", "HEADER", "FILE_SCHEMA")
    return m.group(1).decode("ascii", "replace").strip()


def _open(data: bytes) -> tuple[Any, str | None]:
    """The parsed file, and a note for the reading when raw characters outside ASCII had to be escaped."""
    schema = _schema_of(data)
    if schema.upper() != SCHEMA:
        raise AlignmentFormatError(
            f"the file's schema is {schema[:60]!r}; only IFC 4.3 ({SCHEMA}, ISO 16739-1:2024) is read. "
            "Export the alignment as IFC 4.3 ADD2 (a file labelled IFC2X3, IFC4, an IFC4X3 release candidate "
            "such as IFC4X3_RC3, or IFC4X3_ADD1 has other entities and attributes)",
            "HEADER",
            "FILE_SCHEMA",
        )
    note = None
    if not data.isascii():
        # ISO 10303-21 is 7-bit text (other characters as \X2\ escapes); some writers put UTF-8 or Latin-1 in
        # strings, which only names carry. IfcOpenShell's parser drops such characters ("Straße" reads "Strae"),
        # so they are escaped as the standard writes them and a name keeps every letter.
        try:
            text, encoding = data.decode("utf-8-sig"), "UTF-8"  # an editor's byte-order mark is no character
        except UnicodeDecodeError:
            text, encoding = data.decode("latin-1"), "Latin-1"
        text = _NON_ASCII.sub(_step_escape, text)
        note = (
            f"characters outside ASCII written as they are (ISO 10303-21 asks for \\X2\\ escapes) were read as "
            f"{encoding}"
        )
    else:
        text = data.decode("ascii")
    global _Entity
    import ifcopenshell  # ~0.2 s on first use: imported only when an IFC file is read

    _Entity = ifcopenshell.entity_instance
    try:
        f = ifcopenshell.file.from_string(text)
        # a header the parser could not read leaves the file without a schema ("No schema loaded")
        parsed_schema = f.schema_identifier
    except Exception as exc:  # the parser's own errors (RuntimeError and the like) name what it could not read
        reason = str(exc)
        if reason == "No schema loaded":
            reason = "the parser could not read its header and data sections (ISO 10303-21 syntax)"
        raise AlignmentFormatError(f"unreadable IFC file: {reason}"[:300]) from None
    if parsed_schema.upper() != SCHEMA:
        raise AlignmentFormatError(f"the file's schema is {parsed_schema[:60]!r}", "HEADER", "FILE_SCHEMA")
    return f, note


def _length_unit(f: Any) -> tuple[float, str]:
    """The project's length unit: (metres per unit, its name)."""
    projects = f.by_type("IfcProject")
    if len(projects) != 1:
        raise AlignmentFormatError(
            f"an IFC file has exactly one IfcProject; this one has {len(projects)}", "IfcProject", "IfcProject"
        )
    p = projects[0]
    ua = p.UnitsInContext
    if not _is(ua, "IfcUnitAssignment"):
        raise AlignmentFormatError(
            f"has no UnitsInContext (IfcUnitAssignment), got {_describe(ua)}: the length unit is unknown",
            _ref(p),
            "UnitsInContext",
        )
    lengths = [u for u in _entities(ua.Units) if u.is_a("IfcNamedUnit") and u.UnitType == "LENGTHUNIT"]
    if len(lengths) != 1:
        raise AlignmentFormatError(f"assigns {len(lengths)} LENGTHUNIT units; exactly one is needed", _ref(ua), "Units")
    return _unit_factor(lengths[0], 0)


def _unit_factor(u: Any, depth: int) -> tuple[float, str]:
    where = _ref(u)
    if depth > 4:
        raise AlignmentFormatError("conversion-based units nest more than 4 deep", where, "ConversionFactor")
    if u.is_a("IfcSIUnit"):
        if u.Name != "METRE" or u.UnitType != "LENGTHUNIT":
            raise AlignmentFormatError(f"a length unit named {u.Name!r} is not a metre", where, "Name")
        prefix = u.Prefix
        if prefix is None:
            return 1.0, "metre"
        if prefix not in _SI_PREFIX:
            raise AlignmentFormatError(f"unknown SI prefix {prefix!r}", where, "Prefix")
        return 10.0 ** _SI_PREFIX[prefix], f"{prefix.lower()}metre"
    if u.is_a("IfcConversionBasedUnitWithOffset"):
        raise AlignmentFormatError("a length unit with an offset is not a length unit", where, "ConversionOffset")
    if u.is_a("IfcConversionBasedUnit"):
        name = _text(u.Name) or ""
        cf = u.ConversionFactor
        if not _is(cf, "IfcMeasureWithUnit"):
            raise AlignmentFormatError(
                f"ConversionFactor must be an IfcMeasureWithUnit, got {_describe(cf)}", where, "ConversionFactor"
            )
        vc = cf.ValueComponent
        value = getattr(vc, "wrappedValue", vc)
        if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value) or value <= 0:
            raise AlignmentFormatError(
                f"ConversionFactor {value!r} is not a positive length"[:200], _ref(cf), "ValueComponent"
            )
        if not _is(cf.UnitComponent, "IfcNamedUnit") or cf.UnitComponent.UnitType != "LENGTHUNIT":
            raise AlignmentFormatError("ConversionFactor is not in a length unit", _ref(cf), "UnitComponent")
        base, _ = _unit_factor(cf.UnitComponent, depth + 1)
        factor = float(value) * base
        key = re.sub(r"[\s\-_.]", "", name.lower())
        exact = _NAMED_LENGTH.get(key)
        if exact is not None:
            if abs(factor / exact - 1) > _NAMED_TOLERANCE:
                raise AlignmentFormatError(
                    f"names its unit {name!r} (1 {name} = {exact!r} m) but converts it as {factor!r} m",
                    where,
                    "ConversionFactor",
                )
            factor = exact
        if not name:
            raise AlignmentFormatError("a conversion-based length unit without a Name", where, "Name")
        return factor, name
    raise AlignmentFormatError(f"a {u.is_a()} length unit is not read", where, "Units")


def _writer(f: Any) -> str | None:
    def describe(app: Any) -> str | None:
        name = _text(app.ApplicationFullName) or _text(app.ApplicationIdentifier)
        version = _text(app.Version)
        return f"{name} {version}" if name and version else name

    history = f.by_type("IfcProject")[0].OwnerHistory
    if _is(history, "IfcOwnerHistory") and _is(history.OwningApplication, "IfcApplication"):
        return describe(history.OwningApplication)
    apps = f.by_type("IfcApplication")
    if len(apps) == 1:
        return describe(apps[0])
    try:
        system = f.header.file_name.originating_system
    except Exception:  # pragma: no cover - a header IfcOpenShell parsed always has it
        return None
    return _text(system)


# -- the alignment's structure --------------------------------------------------------------------------------------


def _nested(e: Any) -> list[Any]:
    """What ``e`` nests (IfcRelNests, in their order)."""
    out: list[Any] = []
    for rel in e.IsNestedBy or ():
        out.extend(_entities(rel.RelatedObjects))
    return out


def _children(alignment: Any) -> list[Any]:
    """Child alignments (IfcRelAggregates), in the order of their entity ids: an aggregation is a set, without order,
    and writers number entities as they create them."""
    out: list[Any] = []
    for rel in alignment.IsDecomposedBy or ():
        out.extend(o for o in _entities(rel.RelatedObjects) if o.is_a("IfcAlignment"))
    return sorted(out, key=lambda o: o.id())


def _is_child(alignment: Any) -> bool:
    return any(_is(rel.RelatingObject, "IfcAlignment") for rel in alignment.Decomposes or ())


def _segments(layout: Any, kind: str) -> list[tuple[Any, Any]]:
    """(IfcAlignmentSegment, its design parameters) nested in a layout, checked to be of the layout's kind."""
    out = []
    for seg in _nested(layout):
        if not seg.is_a("IfcAlignmentSegment"):
            continue
        dp = seg.DesignParameters
        if not _is(dp, kind):
            raise AlignmentFormatError(
                f"DesignParameters must be an {kind} in {_ref(layout)}, got {_describe(dp)}",
                _ref(seg),
                "DesignParameters",
            )
        out.append((seg, dp))
    return out


def _zero_length(i: int, segments: list) -> str:
    """Why a zero-length segment (the i-th, 1-based) is skipped."""
    if i == len(segments):
        return "a zero-length segment (the closing segment IFC 4.3 asks for at the end of a layout)"
    return "a zero-length segment"


# -- horizontal -------------------------------------------------------------------------------------------------


def _curvature(radius_m: float) -> float:
    return 0.0 if radius_m == 0 else 1.0 / radius_m


def _horizontal(
    layout: Any, unit: float, label: str, skipped: list[tuple[str, str]], counts: Counter[str]
) -> list[HorizontalElement]:
    elements: list[HorizontalElement] = []
    segments = _segments(layout, "IfcAlignmentHorizontalSegment")
    for i, (seg, dp) in enumerate(segments, start=1):
        where = f"{label} horizontal segment {i} ({_ref(seg)}, {_ref(dp)})"
        kind = _enum(dp, "PredefinedType", where, ("LINE", "CIRCULARARC", "VIENNESEBEND", *_SPIRALS))
        length = _length(dp, "SegmentLength", where, unit, nonnegative=True)
        r0 = _length(dp, "StartRadiusOfCurvature", where, unit)
        r1 = _length(dp, "EndRadiusOfCurvature", where, unit)
        name = _text(seg.Name)
        if length == 0:
            skipped.append((where, _zero_length(i, segments)))
            continue
        counts[f"IfcAlignmentHorizontalSegment.{kind}"] += 1
        if kind == "LINE":
            if r0 != 0 or r1 != 0:
                raise AlignmentFormatError(
                    f"a LINE has radius 0 (straight) at both ends, got {r0 / unit!r} and {r1 / unit!r}",
                    where,
                    "StartRadiusOfCurvature" if r0 else "EndRadiusOfCurvature",
                )
            elements.append(HorizontalElement("line", length, name=name, where=where))
        elif kind == "CIRCULARARC":
            if r0 == 0 or (r0 != r1 and abs(r1 / r0 - 1) > 1e-9):
                raise AlignmentFormatError(
                    f"a CIRCULARARC has one non-zero radius at both ends, got {r0 / unit!r} and {r1 / unit!r}",
                    where,
                    "StartRadiusOfCurvature" if r0 == 0 else "EndRadiusOfCurvature",
                )
            elements.append(
                HorizontalElement(
                    "arc",
                    length,
                    abs(r0),
                    abs(r0),
                    "left" if r0 > 0 else "right",
                    name=name,
                    where=where,
                )
            )
        elif kind == "VIENNESEBEND":
            raise AlignmentFormatError(
                "a VIENNESEBEND transition is not read: its plan curvature has a term of the cant and of the height "
                "of the centre of gravity (GravityCenterLineHeight), so its end radii do not bound its radius",
                where,
                "PredefinedType",
            )
        else:
            elements.extend(_spiral(kind, length, r0, r1, unit, name, where))
    return elements


def _spiral(
    kind: str, length: float, r0: float, r1: float, unit: float, name: str | None, where: str
) -> list[HorizontalElement]:
    spiral_type = kind.lower()
    if r0 == 0 and r1 == 0:
        raise AlignmentFormatError(
            f"a {kind} transition with both radii 0 (straight at both ends) is a line", where, "EndRadiusOfCurvature"
        )

    def part(part_length: float, ra: float, rb: float, part_where: str) -> HorizontalElement:
        side = ra if ra != 0 else rb
        return HorizontalElement(
            "spiral",
            part_length,
            abs(ra) if ra else math.inf,
            abs(rb) if rb else math.inf,
            "left" if side > 0 else "right",
            spiral_type=spiral_type,
            name=name,
            where=part_where,
        )

    if r0 * r1 >= 0:
        return [part(length, r0, r1, where)]
    if kind != "CLOTHOID":
        raise AlignmentFormatError(
            f"a {kind} transition whose radii change side ({r0 / unit!r} to {r1 / unit!r}) is not read; only a "
            "clothoid, whose curvature is linear in length, is split at its inflection",
            where,
            "EndRadiusOfCurvature",
        )
    k0, k1 = _curvature(r0), _curvature(r1)
    s0 = length * k0 / (k0 - k1)  # the inflection: k0 + (k1 - k0) s / L = 0
    return [
        part(s0, r0, 0.0, f"{where}, to its inflection"),
        part(length - s0, 0.0, r1, f"{where}, from its inflection"),
    ]


# -- vertical ---------------------------------------------------------------------------------------------------


def _profile(
    layout: Any, unit: float, label: str, default_name: str, skipped: list[tuple[str, str]], counts: Counter[str]
) -> Profile | None:
    name = _text(layout.Name) or default_name
    segments: list[VerticalSegment] = []
    kinds: Counter[str] = Counter()  # counted only if the profile is read
    segments_read = _segments(layout, "IfcAlignmentVerticalSegment")
    for i, (seg, dp) in enumerate(segments_read, start=1):
        where = f"{label} vertical segment {i} ({_ref(seg)}, {_ref(dp)})"
        kind = _enum(dp, "PredefinedType", where, ("CONSTANTGRADIENT", "PARABOLICARC", "CIRCULARARC", "CLOTHOID"))
        start = _length(dp, "StartDistAlong", where, unit, nonnegative=True)
        length = _length(dp, "HorizontalLength", where, unit, nonnegative=True)
        height = _length(dp, "StartHeight", where, unit)
        g0 = _real(dp, "StartGradient", where)
        g1 = _real(dp, "EndGradient", where)
        assert g0 is not None and g1 is not None
        if kind == "CLOTHOID":
            skipped.append((f"{label} profile {name!r} ({_ref(layout)})", f"{where}: a vertical CLOTHOID is not read"))
            return None
        if length == 0:
            skipped.append((where, _zero_length(i, segments_read)))
            continue
        kinds[f"IfcAlignmentVerticalSegment.{kind}"] += 1
        radius = None
        if kind == "CONSTANTGRADIENT":
            if g0 != g1 and abs(g1 - g0) > 1e-12 * max(1.0, abs(g0)):
                raise AlignmentFormatError(
                    f"a CONSTANTGRADIENT has one gradient, got StartGradient {g0!r} and EndGradient {g1!r}",
                    where,
                    "EndGradient",
                )
            vkind = "constant"
        elif kind == "PARABOLICARC":
            vkind = "parabolic"
        else:
            vkind = "circular"
            r = _length(dp, "RadiusOfCurvature", where, unit)
            if r == 0:
                raise AlignmentFormatError(
                    "a CIRCULARARC has a non-zero RadiusOfCurvature, got 0", where, "RadiusOfCurvature"
                )
            # x = distance along, y = height: a counter-clockwise (positive) arc is a sag, its grade rising; the
            # horizontal length of an arc between grade angles t0 and t1 is R (sin t1 - sin t0)
            expected = r * (math.sin(math.atan(g1)) - math.sin(math.atan(g0)))
            if abs(expected - length) > _ARC_TOLERANCE * length:
                raise AlignmentFormatError(
                    f"RadiusOfCurvature {r / unit!r} with gradients {g0!r} to {g1!r} spans {expected / unit!r} "
                    f"horizontally, not the HorizontalLength {length / unit!r} (+ is a sag, - a crest)",
                    where,
                    "RadiusOfCurvature",
                )
            radius = abs(r)
        segments.append(VerticalSegment(vkind, start, length, height, g0, g1, radius))
    if not segments:
        skipped.append((f"{label} profile {name!r} ({_ref(layout)})", "it has no segment of non-zero length"))
        return None
    counts.update(kinds)
    return Profile(name, tuple(segments))


# -- cant -------------------------------------------------------------------------------------------------------


def _cross_slopes(
    layout: Any, unit: float, label: str, skipped: list[tuple[str, str]], counts: Counter[str]
) -> list[CrossSlope]:
    lw = f"{label} ({_ref(layout)})"
    rhd = _length(layout, "RailHeadDistance", lw, unit)
    if rhd <= 0:
        raise AlignmentFormatError(f"RailHeadDistance must be positive, got {rhd / unit!r}", lw, "RailHeadDistance")
    out: list[CrossSlope] = []

    def slope(left: float, right: float, where: str, attr: str) -> float:
        rise = right - left
        if abs(rise) >= rhd:
            raise AlignmentFormatError(
                f"the cant difference {rise / unit!r} is not less than the RailHeadDistance {rhd / unit!r}",
                where,
                attr,
            )
        return 100.0 * math.tan(math.asin(rise / rhd))

    segments = _segments(layout, "IfcAlignmentCantSegment")
    for i, (seg, dp) in enumerate(segments, start=1):
        where = f"{label} cant segment {i} ({_ref(seg)}, {_ref(dp)})"
        kind = _enum(dp, "PredefinedType", where, _CANT_TYPES)
        start = _length(dp, "StartDistAlong", where, unit, nonnegative=True)
        length = _length(dp, "HorizontalLength", where, unit, nonnegative=True)
        sl = _length(dp, "StartCantLeft", where, unit)
        sr = _length(dp, "StartCantRight", where, unit)
        el = _real(dp, "EndCantLeft", where, optional=True)
        er = _real(dp, "EndCantRight", where, optional=True)
        el = sl if el is None else el * unit
        er = sr if er is None else er * unit
        s0 = slope(sl, sr, where, "StartCantRight")
        s1 = slope(el, er, where, "EndCantRight")
        if length == 0:
            skipped.append((where, _zero_length(i, segments)))
            continue
        counts[f"IfcAlignmentCantSegment.{kind}"] += 1
        for d, s in ((start, s0), (start + length, s1)):
            # a segment's start repeats the previous one's end (to rounding: start + length of the one before)
            if out and out[-1].left_percent == s and abs(out[-1].distance_m - d) <= 1e-9 * max(1.0, d):
                continue
            out.append(CrossSlope(d, s, s))
    return out


# -- stations ---------------------------------------------------------------------------------------------------


def _stations(
    alignment: Any, unit: float, label: str, notes: list[str], skipped: list[tuple[str, str]]
) -> tuple[float | None, list[StationEquation]]:
    """The start station and the station equations from the alignment's STATION referents."""
    marks: list[tuple[float | None, float, float | None, Any]] = []  # distance, station, incoming, referent
    for r in _nested(alignment):
        if not r.is_a("IfcReferent") or r.PredefinedType != "STATION":
            continue
        where = f"{label} {_ref(r)}"
        pset = _pset_stationing(r)
        if pset.get("HasIncreasingStation") is False:
            raise AlignmentFormatError(
                "decreasing stationing (Pset_Stationing.HasIncreasingStation false) is not read",
                where,
                "HasIncreasingStation",
            )
        if "Station" not in pset:
            continue
        station = _pset_length(pset, "Station", where, unit)
        incoming = (
            _pset_length(pset, "IncomingStation", where, unit) if pset.get("IncomingStation") is not None else None
        )
        marks.append((_distance_along(r, unit, where), station, incoming, r))
    if not marks:
        return None, []
    start = next((m for m in marks if m[0] == 0), None)
    if start is None and marks[0][0] is None:
        start = marks[0]
    for m in marks:
        if m[0] is None and m is not start:
            skipped.append((f"{label} {_ref(m[3])}", "a STATION referent without a linear placement"))
    ahead = sorted((m for m in marks if m is not start and m[0] is not None), key=lambda m: m[0])
    if start is not None:
        start_station = start[1]
    else:  # the stationing runs on unbroken from the first referent back to the start
        assert ahead[0][0] is not None
        start_station = ahead[0][1] - ahead[0][0]
        notes.append(
            f"the start station {start_station!r} m is the first STATION referent's ({_ref(ahead[0][3])}) "
            "less its distance along"
        )
    equations: list[StationEquation] = []
    last_d, last_sta = 0.0, start_station
    for d, station, incoming, _ in ahead:
        assert d is not None
        back = incoming if incoming is not None else last_sta + (d - last_d)
        if incoming is not None or abs(back - station) > 1e-9 * max(1.0, abs(station)):
            equations.append(StationEquation(d, back, station))
        last_d, last_sta = d, station
    return start_station, equations


def _pset_stationing(referent: Any) -> dict[str, Any]:
    """The single values of the referent's Pset_Stationing (``Station``, ``IncomingStation``,
    ``HasIncreasingStation``), as written (a measure's value unwrapped)."""
    out: dict[str, Any] = {}
    for rel in referent.IsDefinedBy or ():
        pset = getattr(rel, "RelatingPropertyDefinition", None)
        if not _is(pset, "IfcPropertySet") or pset.Name != "Pset_Stationing":
            continue
        for prop in _entities(pset.HasProperties):
            if prop.is_a("IfcPropertySingleValue") and isinstance(prop.Name, str):
                v = prop.NominalValue
                out[prop.Name] = getattr(v, "wrappedValue", v)
    return out


def _pset_length(pset: dict, key: str, where: str, unit: float) -> float:
    v = pset.get(key)
    if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v):
        raise AlignmentFormatError(f"Pset_Stationing.{key} is not a number: {v!r}"[:200], where, key)
    return float(v) * unit


def _distance_along(referent: Any, unit: float, where: str) -> float | None:
    p = referent.ObjectPlacement
    if not _is(p, "IfcLinearPlacement") or not _is(p.RelativePlacement, "IfcAxis2PlacementLinear"):
        return None
    loc = p.RelativePlacement.Location
    if not _is(loc, "IfcPointByDistanceExpression"):
        return None
    d = loc.DistanceAlong
    if not _is(d, "IfcLengthMeasure"):
        raise AlignmentFormatError(
            f"the linear placement's DistanceAlong is not a length: {d!r}"[:200],
            f"{where} ({_ref(loc)})",
            "DistanceAlong",
        )
    v = d.wrappedValue
    if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v) or v < 0:
        raise AlignmentFormatError(f"DistanceAlong {v!r} is not a distance", f"{where} ({_ref(loc)})", "DistanceAlong")
    return float(v) * unit


# -- the reader -------------------------------------------------------------------------------------------------


def _alignment(alignment: Any, unit: float, skipped: list[tuple[str, str]], counts: Counter[str]) -> AlignmentGeometry:
    name = _text(alignment.Name) or f"#{alignment.id()}"
    label = f"IfcAlignment {name[:100]!r} (#{alignment.id()})"
    notes: list[str] = []
    layouts = _nested(alignment)
    horizontals = [lay for lay in layouts if lay.is_a("IfcAlignmentHorizontal")]
    if not horizontals:
        raise AlignmentFormatError(
            "nests no IfcAlignmentHorizontal: an alignment given only as geometry (a polyline or curve without its "
            "segments' design parameters) is not read",
            label,
            "IsNestedBy",
        )
    if len(horizontals) > 1:
        raise AlignmentFormatError(
            f"nests {len(horizontals)} IfcAlignmentHorizontal; an alignment has exactly one", label, "IsNestedBy"
        )
    elements = _horizontal(horizontals[0], unit, label, skipped, counts)
    profiles: list[Profile] = []
    # several profiles over one horizontal: each in a child alignment (IfcRelAggregates), with its cant
    verticals = [(lay, label, name) for lay in layouts if lay.is_a("IfcAlignmentVertical")]
    cants = [(lay, label) for lay in layouts if lay.is_a("IfcAlignmentCant")]
    for child in _children(alignment):
        child_name = _text(child.Name) or f"#{child.id()}"
        child_label = f"{label} child IfcAlignment {child_name[:100]!r} (#{child.id()})"
        for lay in _nested(child):
            if lay.is_a("IfcAlignmentVertical"):
                verticals.append((lay, child_label, child_name))
            elif lay.is_a("IfcAlignmentCant"):
                cants.append((lay, child_label))
            elif lay.is_a("IfcAlignmentHorizontal"):
                skipped.append((f"{child_label} {_ref(lay)}", "a child alignment's horizontal (the parent's is read)"))
    for lay, lab, default_name in verticals:
        p = _profile(lay, unit, lab, default_name, skipped, counts)
        if p is not None:
            profiles.append(p)
    slopes: list[CrossSlope] = []
    for i, (lay, lab) in enumerate(cants):
        if i == 0:
            slopes = _cross_slopes(lay, unit, lab, skipped, counts)
        else:
            skipped.append((f"{lab} {_ref(lay)}", "a further IfcAlignmentCant (the first one is read)"))
    start_station, equations = _stations(alignment, unit, label, notes, skipped)
    if start_station is None:
        notes.append("no STATION referent with Pset_Stationing.Station: the start station is taken as 0")
    return AlignmentGeometry(
        name=name,
        start_station_m=0.0 if start_station is None else start_station,
        elements=tuple(elements),
        station_equations=tuple(equations),
        profiles=tuple(profiles),
        cross_slopes=tuple(slopes),
        where=label,
        notes=tuple(notes),
    )


def read_ifc(data: bytes) -> RoadFile:
    """The alignments of an IFC 4.3 (``IFC4X3_ADD2``) file in SI units (see the module's docstring for what is read).

    Parameters
    ----------
    data : bytes
        The file as uploaded (ISO 10303-21 text; its size is limited by the caller).

    Returns
    -------
    RoadFile
        ``format`` ``"IFC 4.3 (IFC4X3_ADD2)"``, one :class:`~engine.road.geometry.AlignmentGeometry` per top-level
        ``IfcAlignment`` (child alignments give their profiles to their parent), ``linear_unit`` as the file names
        it, ``writer``, ``skipped`` and ``elements``: how many segments of each type were read (zero-length ones
        are skipped), named ``<entity>.<PredefinedType>`` such as ``IfcAlignmentHorizontalSegment.CLOTHOID``.

    Raises
    ------
    AlignmentFormatError
        Not an ISO 10303-21 file, another schema (named), no ``IfcAlignment``, a unit or value that cannot be read
        (``location`` names the entity as ``#id Type`` within its alignment, ``field`` the attribute).
    """
    if not isinstance(data, bytes | bytearray | memoryview):
        raise TypeError("read_ifc takes the file's bytes")
    f, note = _open(bytes(data))
    skipped: list[tuple[str, str]] = []
    counts: Counter[str] = Counter()
    try:
        unit, unit_name = _length_unit(f)
        alignments = [a for a in f.by_type("IfcAlignment") if not _is_child(a)]
        if not alignments:
            raise AlignmentFormatError("the file has no IfcAlignment", None, "IfcAlignment")
        read = tuple(_alignment(a, unit, skipped, counts) for a in sorted(alignments, key=lambda a: a.id()))
        if note is not None:
            read = tuple(dataclasses.replace(a, notes=(*a.notes, note)) for a in read)
        writer = _writer(f)
    except AlignmentFormatError:
        raise
    except (AttributeError, TypeError, ValueError, RuntimeError, IndexError) as exc:
        # the last guard: an entity where the schema puts another kind (IfcOpenShell keeps what the file wrote)
        raise AlignmentFormatError(f"the file's alignment structure cannot be read: {exc}"[:300]) from None
    return RoadFile(
        FORMAT,
        read,
        linear_unit=unit_name,
        writer=writer,
        skipped=tuple(skipped),
        elements=tuple(sorted(counts.items())),
    )


def read_road_file(document: str | bytes) -> RoadFile:
    """:func:`read_ifc` of a document given as text (the JSON request's ``ifc``: ISO 10303-21 is 7-bit text, so
    its UTF-8 bytes are the file's) or as the uploaded bytes."""
    return read_ifc(document.encode("utf-8") if isinstance(document, str) else document)

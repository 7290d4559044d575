"""LandXML 1.2 road-design files read into the neutral records of :mod:`engine.road.geometry` (a
:class:`~engine.road.geometry.RoadFile`, every length in metres).

What is read, per ``Alignment``:

- ``<Units>``: ``Metric`` or ``Imperial`` with ``linearUnit`` (:data:`LINEAR_UNITS`: meter, kilometer, centimeter,
  millimeter, foot = 0.3048 m, USSurveyFoot = 1200/3937 m, inch, mile), applied to every length read (radii, lengths,
  stations, PVI stations and elevations, cross-section offsets and elevations); ``angularUnit``
  (:data:`ANGULAR_UNITS`) where an angle is read (a ``Curve``'s ``delta``). A unit not known is refused naming the
  attribute and the value; a file without ``<Units>`` is read in metres, and the reading says so.
- ``CoordGeom``: ``Line`` (``length``, else from its ``Start``/``End``), ``Curve`` (``rot``, ``radius``,
  ``length``; ``delta`` and ``chord`` where written compared with them: :meth:`_Reader.arc_check`), ``Spiral``
  (``rot``, ``radiusStart``/``radiusEnd`` with ``INF``, ``length``, ``spiType``: the transitions in
  :data:`SPIRAL_TYPES`, others refused by name), each with its optional ``staStart``. An
  ``IrregularLine`` (a polyline) counts its length for the stations but is not assessed; a ``Chain`` (references to
  elements elsewhere) is skipped; both are listed in the reading.
- ``StaEquation`` (``staBack``, ``staAhead``, ``staInternal``).
- ``Profile/ProfAlign`` (every one, by name): ``PVI``, ``ParaCurve``, ``UnsymParaCurve``, ``CircCurve``. A
  ``ProfSurf`` (a surface's ground line) is listed as skipped.
- ``Superelevation`` (``staStart``/``staEnd``; ``FullSuperSta``, ``FullSuperelev``, ``RunoffSta``): the full
  superelevation between ``FullSuperSta`` and ``RunoffSta`` (the element's ``staStart``/``staEnd`` where they are
  missing). ``FullSuperelev`` is read in percent, + banked toward the inside of the curve: assumed (the schema's text
  on its unit and sign was not read; docs/uploads.md says so).
- ``CrossSects/CrossSect`` (``sta``) > ``DesignCrossSectSurf`` > ``CrossSectPnt`` ("offset elevation"): each lane's
  slope from the surface's points, between the centreline (offset 0, interpolated) and the first point on each side;
  a negative offset is left of the centreline (assumed: the convention of Civil 3D's exports).
- ``<Application>`` names the writer.

Errors are :class:`~app.formats.alignment_io.AlignmentFormatError` naming the element (``Alignment 'A' CoordGeom
element 3 (Spiral)``) and the attribute.
"""

from __future__ import annotations

import itertools
import math
import operator
import re
import secrets
import time
import xml.etree.ElementTree as ET
from array import array
from collections import Counter
from collections.abc import Sequence

import numpy as np

from app.formats import xmlsafe

try:
    from app.formats import _xsectscan
except ImportError:  # built without a C compiler: the Python scan (the same numbers, slower)
    _xsectscan = None
from app.formats.alignment_io import AlignmentFormatError
from engine.road import (
    AlignmentGeometry,
    CrossSlope,
    ElementColumns,
    HorizontalElement,
    Profile,
    RangeColumns,
    RoadFile,
    SegmentColumns,
    SlopeColumns,
    StationEquation,
    SuperelevationRange,
    distance_at,
)

#: metres per unit of LandXML 1.2's ``linearUnit`` values; the foot (international, 1959) and the mile exactly; the
#: US survey foot 1200/3937 m exactly (its definition, 1893 Mendenhall order)
LINEAR_UNITS: dict[str, float] = {
    "meter": 1.0,
    "kilometer": 1000.0,
    "centimeter": 0.01,
    "millimeter": 0.001,
    "foot": 0.3048,
    "USSurveyFoot": 1200.0 / 3937.0,
    "inch": 0.0254,
    "mile": 1609.344,
}
#: radians per unit of ``angularUnit`` (``decimal dd.mm.ss`` is converted from its digits)
ANGULAR_UNITS: dict[str, float] = {
    "radians": 1.0,
    "grads": math.pi / 200.0,
    "decimal degrees": math.pi / 180.0,
    "decimal dd.mm.ss": math.pi / 180.0,
}
#: transitions whose curvature ramps point-symmetrically about their middle (clothoid: linear; bloss: 3t^2 - 2t^3;
#: sinusoid: t - sin(2 pi t)/(2 pi); cosinusoid: (1 - cos(pi t))/2; biquadratic: two quadratics): each turns the mean
#: of its end curvatures times its length and is sharpest at its end, all the assessment uses. Other ``spiType``
#: values (cubic parabolas, radioids, ...) are refused by name.
SPIRAL_TYPES = ("clothoid", "bloss", "sinusoid", "cosinusoid", "biquadratic")
FORMAT = "LandXML"
#: a Curve's ``delta`` (or ``chord``) and its ``length``/``radius`` agree where they differ by no more than the rounding
#: of the written numbers (half a unit in the last decimal of each, propagated) plus this share of the value: a
#: millionth, under any figure the answer reports (a radius a millionth off moves a safe speed half a millionth) and
#: above the double-precision geometry a writer derives its numbers from (coordinates of up to 10^7 units)
ARC_AGREEMENT = 1e-6
#: a disagreement beyond the rounding and beyond this share of the value (1 %: the radius a percent off moves the safe
#: speed, which goes with its square root, half a percent) is refused: which of the file's numbers is wrong is not
#: known; a smaller one is a note and the curve is read by its length and radius
ARC_GROSS = 0.01
#: notes of disagreeing Curves per alignment; the rest counted in one more
MAX_ARC_NOTES = 20


_TAG_OF = operator.attrgetter("tag")
_TAG_SLICE = 2**16  # children whose tags are gathered per C call (a few milliseconds)


def _children(el: ET.Element, name: str) -> list[ET.Element]:
    """``el``'s children named ``name`` in any namespace (a string test per child: there can be a million)."""
    suffix = "}" + name
    return [c for c in el if c.tag == name or c.tag.endswith(suffix)]


def _child(el: ET.Element, name: str) -> ET.Element | None:
    suffix = "}" + name
    for c in el:
        if c.tag == name or c.tag.endswith(suffix):
            return c
    return None


def _children_named(el: ET.Element, names: tuple[str, ...]) -> dict[str, list[ET.Element]]:
    """:func:`_children` for each of ``names`` (each name's list in document order), the children's tags looked at
    once: where one tag (one namespace) holds a name, its children are found by ``findall`` on that tag, which
    compares in C (an alignment has a Superelevation element per curve: a million children). The tags are
    gathered a slice at a time, each a short C call (the interpreter's lock is not held over a million)."""
    tags: set[str] = set()
    for at in range(0, len(el), _TAG_SLICE):
        tags.update(map(_TAG_OF, el[at : at + _TAG_SLICE]))
    out = {}
    for name in names:
        suffix = "}" + name
        mine = [t for t in tags if isinstance(t, str) and (t == name or t.endswith(suffix))]
        out[name] = el.findall(mine[0]) if len(mine) == 1 else _children(el, name) if mine else []
    return out


def _numbers(texts: list[str], where: str, what: str) -> list[float]:
    """The numbers of whitespace-separated texts; one not a number (or not finite) is refused naming ``what``."""
    words = " ".join(texts).split()
    try:
        values = [float(w) for w in words]
    except ValueError:
        values = []
    if len(values) != len(words) or not all(map(math.isfinite, values)):
        values = [_float(w, where, what) for w in words]  # raises, naming the first bad one
    return values


class _Units:
    def __init__(self, root: ET.Element) -> None:
        self.notes: list[tuple[str, str]] = []
        units = _child(root, "Units")
        system = None
        if units is not None:
            system = next((c for c in units if xmlsafe.local(c.tag) in ("Metric", "Imperial")), None)
        if system is None:
            self.linear_name, self.metres, self.angular_name = "meter", 1.0, "decimal degrees"
            self.notes.append(("<Units>", "absent: lengths read as metres (assumed)"))
            return
        where = f"Units/{xmlsafe.local(system.tag)}"
        linear = system.get("linearUnit")
        if linear is None:  # the schema requires it; which foot or which metric unit is not guessed
            raise AlignmentFormatError("has no linearUnit attribute (LandXML requires it)", where, "linearUnit")
        self.linear_name = linear
        if self.linear_name not in LINEAR_UNITS:
            raise AlignmentFormatError(
                f"linearUnit {self.linear_name!r} is not a LandXML 1.2 length unit (known: {', '.join(LINEAR_UNITS)})",
                where,
                "linearUnit",
            )
        self.metres = LINEAR_UNITS[self.linear_name]
        self.angular_name = system.get("angularUnit", "decimal degrees")
        self.where = where

    def angle_rad(self, text: str, where: str, attribute: str) -> float:
        if self.angular_name not in ANGULAR_UNITS:
            raise AlignmentFormatError(
                f"angularUnit {self.angular_name!r} is not a LandXML 1.2 angle unit "
                f"(known: {', '.join(ANGULAR_UNITS)})",
                getattr(self, "where", "Units"),
                "angularUnit",
            )
        v = _float(text, where, attribute)
        if self.angular_name == "decimal dd.mm.ss":  # 45.3025 is 45 deg 30 min 25 s
            sign, v = math.copysign(1.0, v), abs(v)
            deg = math.floor(v)
            mm = math.floor(round((v - deg) * 100, 9))
            ss = round((v - deg) * 100 - mm, 9) * 100
            v = sign * (deg + mm / 60 + ss / 3600)
        return v * ANGULAR_UNITS[self.angular_name]


_ROT = {"ccw": "left", "cw": "right"}
_ROT_CODE = {"ccw": 0, "cw": 1}  # ElementColumns.direction
_KIND_CODE = {"line": 0, "arc": 1, "spiral": 2}
_DIRECTION_CODE = {"left": 0, "right": 1, None: -1}
_VERTICAL = ("PVI", "ParaCurve", "UnsymParaCurve", "CircCurve")  # a ProfAlign's points
_SUPERELEVATION = ("FullSuperelev", "FullSuperSta", "RunoffSta")  # a Superelevation's children read


def _half_unit(text: str) -> float:
    """Half a unit in the last decimal a number's text writes: "15.594208" 5e-7, "2600" 0.5, "1.25e-3" 5e-6."""
    mantissa, _, exponent = text.strip().lower().partition("e")
    try:
        shift = int(exponent) if exponent else 0
    except ValueError:
        shift = 0
    try:
        return 0.5 * 10.0 ** (shift - len(mantissa.partition(".")[2]))
    except OverflowError:  # ("0.5e309" is no finite number: refused before; kept from raising here)
        return math.inf


def _plain_half(text: str) -> float:
    """:func:`_half_unit` where it is cheap: a number written with a point and no exponent (white space after it
    counts as decimals: less, never more), else 0."""
    dot = text.find(".")
    return 0.5 * 10.0 ** (dot + 1 - len(text)) if dot >= 0 and "e" not in text and "E" not in text else 0.0


def _half_unit_dms(text: str) -> float:
    """Half a unit in the last decimal of a ``decimal dd.mm.ss`` angle, in degrees: its first two decimals are
    minutes, the next two seconds, the rest fractions of a second (45.3025: half a second)."""
    k = len(text.strip().partition(".")[2])
    if k == 0:
        return 0.5
    return 0.5 * (10.0 ** (2 - k) / 60.0 if k <= 2 else 10.0 ** (4 - k) / 3600.0)


def _float(text: str | None, where: str, attribute: str) -> float:
    try:
        v = float(text or "")  # float() takes surrounding white space itself
    except ValueError:
        raise AlignmentFormatError(
            f"{attribute} is not a number: {(text or '').strip()[:40]!r}", where, attribute
        ) from None
    if not math.isfinite(v):
        raise AlignmentFormatError(f"{attribute} must be finite, got {(text or '').strip()[:40]!r}", where, attribute)
    return v


class _Places(Sequence[str]):
    """The places of an alignment's ``Superelevation`` elements (``<prefix><k>``, k from 1), each made when it is
    asked for: a design file has one per curve, and a range's place is read only where a record is made."""

    __slots__ = ("n", "prefix")

    def __init__(self, prefix: str, n: int) -> None:
        self.prefix, self.n = prefix, n

    def __len__(self) -> int:
        return self.n

    def __getitem__(self, i):  # type: ignore[override]
        if isinstance(i, slice):
            return [self[k] for k in range(*i.indices(self.n))]
        if not -self.n <= i < self.n:
            raise IndexError("place index out of range")
        return f"{self.prefix}{i % self.n + 1}"


class _Reader:
    def __init__(self, root: ET.Element, scanned: dict[str, _Scanned] | None = None) -> None:
        self.scanned = scanned or {}
        self.units = _Units(root)
        self.m = self.units.metres
        self.counts: Counter[str] = Counter()
        self.skipped: list[tuple[str, str]] = list(self.units.notes)
        # radians per unit of a Curve's delta where a float's product gives it (not dd.mm.ss, nor an unknown unit:
        # those Curves take the careful path, which converts or refuses)
        name = self.units.angular_name
        self.angle_factor = ANGULAR_UNITS.get(name) if name != "decimal dd.mm.ss" else None
        self.notes: list[str] = []  # the alignment's being read
        self.disagreeing = 0  # its Curves whose delta or chord disagrees with length/radius

    def length(self, el: ET.Element, attribute: str, where: str, *, required: bool = True) -> float | None:
        text = el.get(attribute)
        if text is None:
            if required:
                raise AlignmentFormatError(f"has no {attribute} attribute", where, attribute)
            return None
        v = _float(text, where, attribute) * self.m
        if v < 0.0 and attribute in ("length", "lengthIn", "lengthOut"):
            raise AlignmentFormatError(f"{attribute} must not be negative, got {text.strip()[:40]!r}", where, attribute)
        return v

    def radius(self, el: ET.Element, attribute: str, where: str) -> float:
        text = el.get(attribute)
        if text is None:
            raise AlignmentFormatError(f"has no {attribute} attribute", where, attribute)
        if text.strip().upper() == "INF":
            return math.inf
        r = _float(text, where, attribute) * self.m
        if r <= 0.0:  # the turn is rot's; a radius is positive
            raise AlignmentFormatError(
                f"{attribute} must be positive (or INF), got {text.strip()[:40]!r}", where, attribute
            )
        return r

    def direction(self, el: ET.Element, where: str) -> str:
        rot = el.get("rot")
        if rot == "ccw":
            return "left"
        if rot == "cw":
            return "right"
        raise AlignmentFormatError(f"rot must be 'cw' or 'ccw', got {rot!r}", where, "rot")

    def points(
        self, el: ET.Element, where: str, names: tuple[str, ...] = ("Start", "End")
    ) -> list[tuple[float, float]]:
        """The element's child points in metres as (east, north): LandXML writes "northing easting", and reading
        them in that order would mirror the plan (a ccw turn would read cw)."""
        out = []
        for name in names:
            p = _child(el, name)
            xy = (p.text or "").split() if p is not None else []
            if len(xy) < 2:
                raise AlignmentFormatError(f"has no length attribute and no <{name}> point", where, "length")
            out.append((_float(xy[1], where, name) * self.m, _float(xy[0], where, name) * self.m))
        return out

    def arc_from_points(self, el: ET.Element, where: str, direction: str) -> tuple[float, float]:
        """(radius, length) [m] of a Curve given by its Start, Center and End points (as Aplitop writes them): the
        radius from the centre to the start, the length the radius times the angle swept in the turn's sense."""
        (xs, ys), (xc, yc), (xe, ye) = self.points(el, where, ("Start", "Center", "End"))
        r = math.hypot(xs - xc, ys - yc)
        if r <= 0.0:
            raise AlignmentFormatError("its Start and Center points coincide", where, "radius")
        sweep = math.atan2(ys - yc, xs - xc), math.atan2(ye - yc, xe - xc)
        angle = (sweep[1] - sweep[0]) if direction == "left" else (sweep[0] - sweep[1])
        return r, r * (angle % (2 * math.pi))

    # ------------------------------------------------------------------------------ horizontal

    def arc_close(
        self, r_text: str, l_text: str, d_text: str | None, c_text: str | None, r: float, length: float
    ) -> bool:
        """Whether a Curve's delta and chord (those written) agree with its length and radius [m]: first within
        :data:`ARC_AGREEMENT` and the delta's or chord's own rounding (counted plainly: a share of what
        :meth:`arc_check` allows), else as :meth:`arc_check` compares them. False sends the Curve to the careful
        path, which notes or refuses it."""
        theta = length / r
        try:
            if d_text is not None:
                f = self.angle_factor
                if (
                    f is None
                    or not abs(abs(float(d_text)) * f - theta) <= ARC_AGREEMENT * theta + _plain_half(d_text) * f
                ):
                    return not self.arc_disagreements(r_text, l_text, d_text, c_text, r, length, "")
            if c_text is not None:
                chord = 2.0 * r * math.sin(0.5 * theta)
                tol = ARC_AGREEMENT * chord + _plain_half(c_text) * self.m
                if not abs(float(c_text) * self.m - chord) <= tol:
                    return not self.arc_disagreements(r_text, l_text, d_text, c_text, r, length, "")
        except (ValueError, AlignmentFormatError):  # (the careful path names it)
            return False
        return True

    def arc_check(self, el: ET.Element, r: float, length: float, where: str) -> None:
        """A Curve's ``delta`` and ``chord``, where written beside ``radius`` and ``length``, compared with them
        (:meth:`arc_disagreements`): a disagreement is a note (the curve read by length and radius), and one beyond
        :data:`ARC_GROSS` too a refusal naming the element, the attribute and both values."""
        r_text, l_text, d_text, c_text = el.get("radius"), el.get("length"), el.get("delta"), el.get("chord")
        if r_text is None or l_text is None or (d_text is None and c_text is None):
            return
        said = self.arc_disagreements(r_text, l_text, d_text, c_text, r, length, where)
        for attribute, gross, text in said:
            if gross:
                raise AlignmentFormatError(
                    f"{text}: the file contradicts itself by more than {100 * ARC_GROSS:g} % and which of its numbers"
                    " is wrong is not known",
                    where,
                    attribute,
                )
        if said:
            self.disagreeing += 1
            if self.disagreeing <= MAX_ARC_NOTES:
                self.notes.append(f"{where}: {'; '.join(t for _, _, t in said)}; read by its length and radius")

    def arc_disagreements(
        self, r_text: str, l_text: str, d_text: str | None, c_text: str | None, r: float, length: float, where: str
    ) -> list[tuple[str, bool, str]]:
        """(attribute, beyond :data:`ARC_GROSS`, what) for a ``delta`` (|delta|: Novapoint signs it by the turn)
        and a ``chord`` (2 R sin(|delta|/2)) that differ from length/radius [m] by more than the rounding of the
        written numbers (half a unit in the last decimal of each, propagated) and :data:`ARC_AGREEMENT`."""
        theta = length / r
        h_r, h_l = _half_unit(r_text) * self.m, _half_unit(l_text) * self.m  # [m]
        said = []
        if d_text is not None:
            delta = abs(self.units.angle_rad(d_text, where, "delta"))
            name = self.units.angular_name
            if name == "decimal dd.mm.ss":
                h_d, per, unit = _half_unit_dms(d_text) * math.pi / 180.0, math.pi / 180.0, "decimal degrees"
            else:
                per, unit = ANGULAR_UNITS[name], name
                h_d = _half_unit(d_text) * per
            # d(L/R) = dL/R - L dR/R^2
            tol = h_d + h_l / r + h_r * length / r**2 + ARC_AGREEMENT * theta
            diff = abs(delta - theta)
            if diff > tol:
                said.append(
                    (
                        "delta",
                        diff > ARC_GROSS * theta,
                        f"delta {d_text.strip()[:40]} ({unit}) and length/radius {l_text.strip()[:40]}/"
                        f"{r_text.strip()[:40]} = {theta / per:.9g} ({unit}) differ by {diff / per:.3g}"
                        f" ({100 * diff / theta if theta else math.inf:.3g} %), beyond the +-{tol / per:.2g}"
                        " the written decimals allow",
                    )
                )
        if c_text is not None:
            chord = _float(c_text, where, "chord") * self.m
            half = 0.5 * theta
            expected = 2.0 * r * math.sin(half)
            # dc = cos(theta/2) dL + (2 sin(theta/2) - theta cos(theta/2)) dR
            tol = (
                _half_unit(c_text) * self.m
                + abs(math.cos(half)) * h_l
                + abs(2.0 * math.sin(half) - theta * math.cos(half)) * h_r
                + ARC_AGREEMENT * expected
            )
            diff = abs(chord - expected)
            if diff > tol:
                said.append(
                    (
                        "chord",
                        diff > ARC_GROSS * expected,
                        f"chord {c_text.strip()[:40]} and 2 radius sin(length/(2 radius)) = "
                        f"{expected / self.m:.9g} ({self.units.linear_name}) differ by {diff / self.m:.3g}"
                        f" ({100 * diff / expected if expected else math.inf:.3g} %), beyond the +-{tol / self.m:.2g}"
                        " the written decimals allow",
                    )
                )
        return said

    def element(self, el: ET.Element, name: str, where: str, label: str | None) -> HorizontalElement | None:
        get = el.get
        sta_text = get("staStart")
        sta = None if sta_text is None else _float(sta_text, where, "staStart") * self.m
        if name == "Curve":  # the common case first: radius, length and rot given, as numbers (a million of them)
            r_text, l_text, direction = get("radius"), get("length"), _ROT.get(get("rot") or "")
            if r_text is not None and l_text is not None and direction is not None:
                try:
                    r, length = float(r_text) * self.m, float(l_text) * self.m
                except ValueError:
                    r = length = math.nan
                if 0.0 < r < math.inf and 0.0 <= length < math.inf:
                    self.arc_check(el, r, length, where)
                    return HorizontalElement("arc", length, r, r, direction, sta, None, label, where)
        if name == "Line":
            length = self.length(el, "length", where, required=False)
            if length is None:
                (x0, y0), (x1, y1) = self.points(el, where)
                length = math.hypot(x1 - x0, y1 - y0)
            return HorizontalElement("line", length, station_m=sta, name=label, where=where)
        if name == "Curve":
            length = self.length(el, "length", where, required=False)
            if el.get("radius") is None and _child(el, "Center") is not None:
                direction = self.direction(el, where)
                r, swept = self.arc_from_points(el, where, direction)
                length = swept if length is None else length
            else:
                r = self.radius(el, "radius", where)
                direction = self.direction(el, where)
            if math.isinf(r):
                raise AlignmentFormatError("radius is INF: a Curve must have a finite radius", where, "radius")
            if length is None:
                delta = el.get("delta")
                if delta is None:
                    raise AlignmentFormatError("has no length attribute (nor delta, nor points)", where, "length")
                length = r * abs(self.units.angle_rad(delta, where, "delta"))
            return HorizontalElement("arc", length, r, r, direction, sta, None, label, where)
        if name == "Spiral":
            kind = el.get("spiType", "clothoid")
            if kind not in SPIRAL_TYPES:
                raise AlignmentFormatError(
                    f"spiType {kind!r} is not read (read: {', '.join(SPIRAL_TYPES)}): its curvature along its "
                    "length is not the symmetric ramp the assessment uses",
                    where,
                    "spiType",
                )
            r1, r2 = self.radius(el, "radiusStart", where), self.radius(el, "radiusEnd", where)
            length = self.length(el, "length", where)
            return HorizontalElement("spiral", length, r1, r2, self.direction(el, where), sta, kind, label, where)
        if name == "IrregularLine":
            length = self.length(el, "length", where, required=False)
            if length is None:
                pts = _child(el, "PntList2D")  # (an element without children is false: no `or` here)
                pts = _child(el, "PntList3D") if pts is None else pts
                step = 2 if pts is not None and xmlsafe.local(pts.tag) == "PntList2D" else 3
                xs = [_float(t, where, "PntList") * self.m for t in (pts.text or "").split()] if pts is not None else []
                coords = list(zip(xs[0::step], xs[1::step], strict=False))
                length = sum(math.dist(a, b) for a, b in itertools.pairwise(coords))
            self.skipped.append((where, "a polyline: its length counts for the stations, its curvature is not given"))
            return HorizontalElement("line", length, station_m=sta, name=label, where=where)
        self.skipped.append((where, f"<{name}> is not a horizontal element read"))
        return None

    def alignment(self, el: ET.Element, index: int) -> AlignmentGeometry:
        a_name = el.get("name") or f"alignment {index}"
        where_a = f"Alignment {a_name[:100]!r}"
        start = self.length(el, "staStart", where_a, required=False) or 0.0
        # the elements as the columns of ElementColumns, appended to one by one (a million records would take
        # seconds to make and to free; a row tuple per element, a long C call to transpose)
        kinds, dirs = array("b"), array("b")
        lengths, r1s, r2s, stas = array("d"), array("d"), array("d"), array("d")
        types: list[str | None] = []
        names: list[str | None] = []
        wheres: list[str] = []
        ordinal: dict[str, int] = {}
        prefix, m, inf, nan = f"{where_a} CoordGeom ", self.m, math.inf, math.nan
        self.notes, self.disagreeing = [], 0
        # the alignment's children by name, looked at once (a design file has a Superelevation element per curve)
        kids = _children_named(el, ("CoordGeom", "StaEquation", "Profile", "Superelevation", "CrossSects"))
        for geom in kids["CoordGeom"]:
            for child in geom:
                tag = child.tag
                name = tag[tag.rfind("}") + 1 :]  # xmlsafe.local, inline: once per element of a large file
                if name == "Feature":
                    continue
                n = ordinal[name] = ordinal.get(name, 0) + 1
                get = child.get
                label = get("name")
                if name == "Curve":  # the curve's id as the answer names it: its name, else <alignment>#<n>
                    label = label or f"{a_name}#{n}"
                    where = f"{prefix}Curve #{n} ({label[:100]!r})"
                    # the common case inline (a million of them): radius, length, rot and staStart as plain numbers
                    r_text, l_text, s_text, direction = (
                        get("radius"),
                        get("length"),
                        get("staStart"),
                        _ROT_CODE.get(get("rot")),
                    )
                    try:
                        r, length = float(r_text) * m, float(l_text) * m
                        sta = nan if s_text is None else float(s_text) * m
                    except (TypeError, ValueError):
                        r = length = sta = inf
                    finite_sta = s_text is None or -inf < sta < inf
                    # a delta or chord written beside them (real exports write one) compared; one that is not close
                    # takes the careful path, which allows for the rounding and notes or refuses
                    d_text, c_text = get("delta"), get("chord")
                    if (
                        direction is not None
                        and 0.0 < r < inf
                        and 0.0 <= length < inf
                        and finite_sta
                        and (
                            (d_text is None and c_text is None)
                            or self.arc_close(r_text, l_text, d_text, c_text, r, length)
                        )
                    ):
                        kinds.append(1)
                        lengths.append(length)
                        r1s.append(r)
                        r2s.append(r)
                        dirs.append(direction)
                        stas.append(sta)  # nan: no staStart
                        types.append(None)
                        names.append(label)
                        wheres.append(where)
                        continue
                else:
                    where = f"{prefix}{name} #{n}" + (f" ({label[:100]!r})" if label else "")
                    l_text, s_text = get("length"), get("staStart")
                    if name == "Line" and l_text is not None:  # a line's common case inline too: its length
                        try:
                            length = float(l_text) * m
                            sta = nan if s_text is None else float(s_text) * m
                        except ValueError:
                            length = sta = inf
                        if 0.0 <= length < inf and (s_text is None or -inf < sta < inf):
                            kinds.append(0)
                            lengths.append(length)
                            r1s.append(inf)
                            r2s.append(inf)
                            dirs.append(-1)
                            stas.append(sta)
                            types.append(None)
                            names.append(label)
                            wheres.append(where)
                            continue
                e = self.element(child, name, where, label)  # the careful path: every refusal named
                if e is not None:
                    kinds.append(_KIND_CODE[e.kind])
                    lengths.append(e.length_m)
                    r1s.append(e.radius_start_m)
                    r2s.append(e.radius_end_m)
                    dirs.append(_DIRECTION_CODE[e.direction])
                    stas.append(nan if e.station_m is None else e.station_m)
                    types.append(e.spiral_type)
                    names.append(e.name)
                    wheres.append(e.where)
        for name, count in ordinal.items():
            self.counts[name] += count
        if self.disagreeing > MAX_ARC_NOTES:
            self.notes.append(
                f"and {self.disagreeing - MAX_ARC_NOTES} more Curves whose delta or chord disagrees with their length"
                " and radius beyond the written decimals: each read by its length and radius"
            )
        notes = tuple(self.notes)
        elements = ElementColumns(kinds, lengths, r1s, r2s, dirs, stas, types, names, wheres)
        a = AlignmentGeometry(a_name, start, elements, where=where_a)
        equations = self.equations(kids["StaEquation"], a, where_a)
        a = AlignmentGeometry(a_name, start, elements, equations, where=where_a)
        profiles = tuple(p for prof in kids["Profile"] for p in self.profiles(prof, a, where_a))
        ranges = self.superelevations(kids["Superelevation"], where_a)
        rows = [self.cross_sections(cs, a, where_a) for cs in kids["CrossSects"]]
        # the ranges' and sections' stations as distances along, in one call each
        supers: Sequence[SuperelevationRange] = ()
        if ranges is not None:  # as columns: no record per range (a design file has one per curve)
            sta0, sta1, full = ranges
            d0, d1 = distance_at(a, np.column_stack((sta0, sta1))).T
            # each range's nearer end first (min() and max() of the two, as the records were made: the first of equals)
            supers = RangeColumns(
                np.where(d1 < d0, d1, d0),
                np.where(d1 > d0, d1, d0),
                full,
                _Places(f"{where_a} Superelevation ", len(full)),
            )
        slopes: Sequence[CrossSlope] = ()
        if rows and sum(map(len, rows)):  # as columns: no record per section (a long road has 100,000s)
            sections = np.concatenate(rows)
            slopes = SlopeColumns(distance_at(a, sections[:, 0]), sections[:, 1].copy(), sections[:, 2].copy())
        return AlignmentGeometry(a_name, start, elements, equations, profiles, supers, slopes, where_a, notes)

    def equations(self, els: list[ET.Element], a: AlignmentGeometry, where_a: str) -> tuple[StationEquation, ...]:
        out: list[StationEquation] = []
        for k, eq in enumerate(els, start=1):
            self.counts["StaEquation"] += 1
            where = f"{where_a} StaEquation {k}"
            back = self.length(eq, "staBack", where)
            ahead = self.length(eq, "staAhead", where)
            internal = self.length(eq, "staInternal", where, required=False)
            if internal is not None:  # the continuous station: the start station plus the distance
                distance = internal - a.start_station_m
            else:
                so_far = AlignmentGeometry(a.name, a.start_station_m, (), tuple(out))
                distance = float(distance_at(so_far, back))
            out.append(StationEquation(distance, back, ahead))
        return tuple(out)

    # ------------------------------------------------------------------------------ vertical

    def profiles(self, prof: ET.Element, a: AlignmentGeometry, where_a: str) -> list[Profile]:
        out = []
        for k, child in enumerate(prof, start=1):
            name = xmlsafe.local(child.tag)
            if name == "ProfAlign":
                self.counts["ProfAlign"] += 1
                p_name = child.get("name") or f"profile {k}"
                out.append(self.profile(child, p_name, a, f"{where_a} ProfAlign {p_name[:100]!r}"))
            elif name == "ProfSurf":
                self.skipped.append((f"{where_a} ProfSurf {child.get('name') or k!r}", "a surface's ground line"))
        return out

    def profile(self, el: ET.Element, name: str, a: AlignmentGeometry, where_p: str) -> Profile:
        # each vertical point's numbers read here, one by one, into columns; the segments made below for every
        # point at once (a long road's profile has tens of thousands of points)
        stas: list[float] = []
        zs: list[float] = []
        befores: list[float] = []  # each vertical curve's extent before and after its point (parabolas)
        afters: list[float] = []
        radii: dict[int, float] = {}  # a circular vertical curve's radius, by its point's index
        wheres: list[str] = []
        for k, child in enumerate(el, start=1):
            tag = xmlsafe.local(child.tag)
            if tag not in _VERTICAL:
                continue
            self.counts[tag] += 1
            where = f"{where_p} element {k} ({tag})"
            xy = (child.text or "").split()
            if len(xy) < 2:
                raise AlignmentFormatError("needs 'station elevation' as its text", where, tag)
            stas.append(_float(xy[0], where, "station") * self.m)
            zs.append(_float(xy[1], where, "elevation") * self.m)
            before = after = 0.0
            if tag == "ParaCurve":
                before = after = 0.5 * (self.length(child, "length", where) or 0.0)
            elif tag == "UnsymParaCurve":
                before, after = self.length(child, "lengthIn", where), self.length(child, "lengthOut", where)
            elif tag == "CircCurve":
                # some writers (3D-Win) sign the radius: - on a crest; the grades say which it is
                radius = abs(self.length(child, "radius", where) or 0.0)
                if radius == 0.0:
                    raise AlignmentFormatError("radius must not be 0", where, "radius")
                radii[len(wheres)] = radius
            befores.append(before)  # type: ignore[arg-type]
            afters.append(after)  # type: ignore[arg-type]
            wheres.append(where)
        n = len(stas)
        if n < 2:
            raise AlignmentFormatError("needs at least two points (PVI)", where_p, "PVI")
        d = distance_at(a, np.array(stas))  # one call for every point
        late = np.flatnonzero(np.diff(d) <= 0)
        if len(late):
            k = int(late[0]) + 1
            raise AlignmentFormatError(
                f"station {stas[k] / self.m:g} is not after the previous point's", wheres[k], "station"
            )
        z = np.array(zs)
        grades = np.diff(z) / np.diff(d)
        before, after = np.array(befores), np.array(afters)
        before[[0, -1]] = after[[0, -1]] = 0.0  # the first and the last point have no vertical curve
        g1, g2 = np.r_[0.0, grades], np.r_[grades, 0.0]  # the grades before and after each point
        circle = np.zeros(n, dtype=bool)
        radius = np.full(n, np.nan)
        for i, r in radii.items():
            if 0 < i < n - 1:  # tangent length R tan(dtheta/2) along each tangent, projected
                t1, t2 = math.atan(g1[i]), math.atan(g2[i])
                tangent = r * math.tan(abs(t2 - t1) / 2)
                before[i], after[i] = tangent * math.cos(t1), tangent * math.cos(t2)
                circle[i], radius[i] = True, r
        # an unsymmetric parabola: two parabolas sharing the grade under the PVI, g1 + Lo (g2 - g1)/(Li + Lo)
        para = ~circle & ((before > 0) | (after > 0))
        with np.errstate(divide="ignore", invalid="ignore"):
            g_mid = np.where(para, g1 + after * (g2 - g1) / (before + after), np.nan)
        # each interval between points i and i + 1: its constant grade (slot 0), then point i + 1's vertical curve:
        # a circle (slot 1), or the parabolas before (slot 1) and after (slot 2) it
        d0, z0, nxt = d[:-1], z[:-1], slice(1, None)
        a_, b_ = d0 + after[:-1], d[nxt] - before[nxt]
        overlap = np.flatnonzero(b_ < a_ - 1e-9)
        if len(overlap):
            raise AlignmentFormatError(
                "its vertical curve overlaps the previous point's", wheres[int(overlap[0]) + 1], "length"
            )
        dn, bn, an, cn, pn = d[nxt], before[nxt], after[nxt], circle[nxt], para[nxt]
        starts = np.stack([a_, dn - bn, dn])
        ends = np.stack([b_, np.where(cn, dn + an, dn), dn + an])
        present = np.stack([b_ > a_, cn | (pn & (bn > 0)), ~cn & pn & (an > 0)])
        kinds = np.stack([np.zeros(n - 1), np.where(cn, 2, 1), np.ones(n - 1)]).astype(np.int8)
        g_in = np.stack([grades, g1[nxt], g_mid[nxt]])
        g_out = np.stack([grades, np.where(cn, g2[nxt], g_mid[nxt]), g2[nxt]])
        z_start = np.where(starts < dn, z0 + grades * (starts - d0), z[nxt])
        z_start[0] = z0 + grades * (a_ - d0)
        lengths = ends - starts
        radius_col = np.stack([np.full(n - 1, np.nan), radius[nxt], np.full(n - 1, np.nan)])
        # in the order of distance: interval by interval, slot by slot
        keep = present.T.ravel()
        cols = [c.T.ravel()[keep] for c in (starts, lengths, z_start, g_in, g_out, radius_col)]
        return Profile(name, SegmentColumns(kinds.T.ravel()[keep], *cols))

    # ------------------------------------------------------------------------------ crossfall

    def superelevations(self, els: list[ET.Element], where_a: str) -> tuple[array, array, array] | None:
        """The alignment's ``Superelevation`` elements (``els``) as columns: start station, end station, full
        superelevation, in the file's order (the stations made distances by the caller, all at once); None where
        there is none. A design file has one per curve: the common case (the three children, plain finite numbers)
        is read in one pass over each element's children; anything else by :meth:`superelevation`, which names
        every refusal."""
        if not els:
            return None
        starts, ends, fulls = array("d"), array("d"), array("d")
        m, quick, isfinite, nan = self.m, 0, math.isfinite, math.nan
        usual: tuple[str, str, str] | None = None  # the usual children's tags, in the elements' namespace
        head = els[0].tag
        if isinstance(head, str):
            ns = head[: head.rfind("}") + 1]
            usual = (ns + "FullSuperSta", ns + "FullSuperelev", ns + "RunoffSta")
        for k, s in enumerate(els, start=1):
            # the shape written most: the three children, in this order, in the elements' namespace
            if len(s) == 3 and s.tag == head and (s[0].tag, s[1].tag, s[2].tag) == usual:
                a, b, c = s
                try:
                    full, start, end = float(b.text), float(a.text), float(c.text)  # type: ignore[arg-type]
                except (TypeError, ValueError):  # (None: a TypeError)
                    full = start = end = nan
            else:
                full, start, end = self._usual(s)
            if isfinite(full) and isfinite(start) and isfinite(end):
                starts.append(start * m)
                ends.append(end * m)
                fulls.append(full)
                quick += 1
            else:
                start, end, full, _ = self.superelevation(s, f"{where_a} Superelevation {k}")
                starts.append(start)
                ends.append(end)
                fulls.append(full)
        if quick:
            self.counts["Superelevation"] += quick
        return starts, ends, fulls

    @staticmethod
    def _usual(s: ET.Element) -> tuple[float, float, float]:
        """(full, start, end) of a ``Superelevation`` from each name's first child (any namespace, as
        :func:`_child` finds it), nan where one is missing or not a number (the careful path then reads it)."""
        texts: dict[str, str | None] = {}
        for c in s:
            tag = c.tag
            name = tag[tag.rfind("}") + 1 :]
            if name in _SUPERELEVATION and name not in texts:
                texts[name] = c.text
        try:
            full, start, end = (float(texts[name]) for name in _SUPERELEVATION)  # type: ignore[arg-type]
        except (KeyError, TypeError, ValueError):  # (None: a TypeError)
            return math.nan, math.nan, math.nan
        return full, start, end

    def superelevation(self, el: ET.Element, where: str) -> tuple[float, float, float, str]:
        self.counts["Superelevation"] += 1

        def value(name: str) -> float | None:
            c = _child(el, name)
            return None if c is None or not (c.text or "").strip() else _float(c.text, where, name)

        full = value("FullSuperelev")
        if full is None:
            raise AlignmentFormatError("has no <FullSuperelev>", where, "FullSuperelev")
        start = value("FullSuperSta")
        end = value("RunoffSta")
        start = start * self.m if start is not None else self.length(el, "staStart", where)
        end = end * self.m if end is not None else self.length(el, "staEnd", where)
        return start, end, full, where  # type: ignore[return-value]  (stations: made distances by the caller)

    def cross_sections(self, el: ET.Element, a: AlignmentGeometry, where_a: str) -> np.ndarray:
        """The sections' rows (station, left slope, right slope) [m, %, %], in the file's order."""
        if self.scanned and len(el) == 1 and xmlsafe.local(el[0].tag) == _SCANNED:
            sc = self.scanned.get(el[0].get("key") or "")  # (a marker the file wrote itself has no key of this read)
            if sc is not None:
                return self.scanned_sections(sc, where_a)
        # each section's numbers read here, one by one; the slopes computed below for every section at once
        words: list[str] = []
        counts: list[int] = []  # how many numbers each section has
        stations: list[float] = []
        numbered: list[int] = []  # the section's number in the file (from 1), for messages
        for k, cs in enumerate(_children(el, "CrossSect"), start=1):
            self.counts["CrossSect"] += 1
            surf = _child(cs, "DesignCrossSectSurf")
            if surf is not None:  # LandXML 1.2: a design surface's points, "offset elevation" each
                texts = [" ".join((p.text or "").split()[:2]) for p in _children(surf, "CrossSectPnt")]
            else:  # as Aplitop writes it: a CrossSectSurf with a PntList2D of offset elevation pairs
                surf = _child(cs, "CrossSectSurf")
                plist = _child(surf, "PntList2D") if surf is not None else None
                if plist is None:
                    self.skipped.append(
                        (f"{where_a} CrossSect {k}", "no design surface (DesignCrossSectSurf) to take the slopes from")
                    )
                    continue
                texts = [plist.text or ""]
            mine = " ".join(texts).split()
            words += mine
            counts.append(len(mine))
            stations.append(self.length(cs, "sta", f"{where_a} CrossSect {k}"))  # a distance made by the caller
            numbered.append(k)
        if not counts:
            return np.empty((0, 3))
        try:
            values = np.array(words, dtype=float)
            bad = not np.isfinite(values).all()
        except ValueError:
            bad = True
        if bad:  # the first section with a word that is not a finite number, named
            first = 0
            for k, c in zip(numbered, counts, strict=True):
                _numbers(words[first : first + c], f"{where_a} CrossSect {k}", "CrossSectPnt")
                first += c
        return self.slopes(values, counts, stations, numbered, where_a)

    def scanned_sections(self, sc: _Scanned, where_a: str) -> np.ndarray:
        """The sections the scan read, checked and refused as :meth:`cross_sections` checks the tree's: the first
        station that is not a finite number, then the first section with a point that is not."""
        n = len(sc.counts)
        if n:  # (as the tree's reading counts them: no entry for none)
            self.counts["CrossSect"] += n
        if sc.station_values is not None:  # the compiled scan's: finite numbers, converted as float() converts
            sta, good = sc.station_values, True
        else:
            try:
                sta = np.array([float(t) for t in sc.stations])  # type: ignore[arg-type]  (None: a TypeError)
                good = bool(np.isfinite(sta).all())
            except (TypeError, ValueError):
                good = False
        if not good:  # the first bad one refused as the tree's reading refuses it
            for k, t in enumerate(sc.stations, start=1):
                attrib = {} if t is None else {"sta": _attribute_sta(f'sta="{t}"')}
                self.length(ET.Element("CrossSect", attrib), "sta", f"{where_a} CrossSect {k}")
        stations = sta * self.m
        if not n:
            return np.empty((0, 3))
        parts = []
        for first, many, values, words in sc.chunks:
            if values is None:
                at = 0
                for k in range(first, first + many):
                    _numbers(words[at : at + sc.counts[k]], f"{where_a} CrossSect {k + 1}", "CrossSectPnt")
                    at += sc.counts[k]
                values = np.array([float(w) for w in words])
            parts.append(values)
        return self.slopes(np.concatenate(parts), sc.counts, stations, range(1, n + 1), where_a, sc.picks)

    def slopes(
        self,
        values: np.ndarray,
        counts: list[int],
        stations: list[float] | np.ndarray,
        numbered: Sequence[int],
        where_a: str,
        picks: np.ndarray | None = None,
    ) -> np.ndarray:
        """The sections' (station, left, right) rows from their numbers (``counts`` of them each; the stations made
        distances by the caller; ``picks``: each section's points picked by the compiled scan), a section with no
        point on one side skipped and said so."""
        slopes = _slopes(values, np.array(counts)) if picks is None else _slopes_from(*picks.T)
        missing = np.isnan(slopes[:, 0])
        for i in np.flatnonzero(missing).tolist():
            self.skipped.append(
                (f"{where_a} CrossSect {numbered[i]}", "its design surface has no point on one side of the centreline")
            )
        return np.column_stack((np.array(stations, dtype=float).reshape(-1), slopes))[~missing]


# ---------------------------------------------------------------------------------------------- cross sections, scanned
# Design cross sections make a document several times larger (one every 50 m: four times) and were most of its
# reading time as a tree (five elements per section made and read one by one). Where a <CrossSects> element holds
# only sections of the shape design packages write (a CrossSect with one DesignCrossSectSurf of CrossSectPnt
# "offset elevation" points), its content is read here by regular expressions over the document's bytes, a chunk at
# a time, and left out of the tree (a marker element stands in its place). The scan only decides whether it
# recognises every element in the content, and where it does not (another element, a comment, a character
# reference, a point that is not two words, text not ASCII, a character XML forbids), the document is read as a
# tree as before. The numbers are then the tree's: the same words, converted by the same calls.
#
# Where the compiled scan was built (app.formats._xsectscan, app/formats/csrc/xsectscan.c), it reads the content
# first, in place, a chunk at a time: one pass in C that takes a strict subset of what the regular expressions take
# (white space only between the tags, no attribute on a point, every number a plain decimal and finite), converts
# the numbers as float() does and picks each section's points for its slopes. Anything outside that subset makes it
# decline the whole content, and the regular expressions read it as before (tests/road/test_landxml_scan.py
# compares the two, and both with the tree). At 200,000 curves the cross sections took 1.9-2.0 s of processor time
# with the regular expressions, as much as the rest of the document, and take 0.1-0.2 s in C (docs/uploads.md).
#
# The scan runs before the guard (xmlsafe.fromstring), and where it recognises a content that is well-formed by
# itself (only the three known tags, properly nested; attribute names plain and distinct; no reference, no "]]>",
# no character XML forbids, no markup declaration anywhere before it), that content is also left out of the
# guard's pass: removing balanced content from an element leaves every error of the rest where it was, and the
# guard reads a document that failed again whole, for its own error and position. Everything else in the document
# (its DOCTYPE, where entities would be declared) is guarded as before.

#: the element that stands in the tree for a scanned <CrossSects>'s content (its ``key``: the scan's, random)
_SCANNED = "rollover-scanned-cross-sections"
#: bytes per chunk of the scan (each a few C calls; the interpreter's lock is given up between chunks)
_SCAN_CHUNK = 2**20
#: an attribute name the scan takes: plain (no namespace prefix, not reserved to XML: both parsers read it alike)
_NAME = r"(?![xX][mM][lL])[A-Za-z_][A-Za-z0-9._-]*"
#: a start tag's attributes and its end (not "/>": an empty element is not taken), as XML writes them: every value
#: quoted and holding no '<' (it may hold '>' and the other quote)
_ATTRS = r"""(?:\s+""" + _NAME + r"""\s*=\s*(?:"[^"<]*"|'[^'<]*'))*\s*>"""
_POINT = r"<CrossSectPnt" + _ATTRS + r"\s*[^\s<&]+\s+[^\s<&]+\s*</CrossSectPnt\s*>"
_SECTION = re.compile(
    (
        r"<CrossSect(?:\s+sta\s*=\s*(\"[^\"<&]*\")\s*>|(" + _ATTRS[:-1] + r")>)[^<&]*"
        r"<DesignCrossSectSurf(" + _ATTRS[:-1] + r")>((?:\s*" + _POINT + r")*)\s*</DesignCrossSectSurf\s*>[^<&]*"
        r"</CrossSect\s*>"
    ).encode("ascii")
)
_OPEN = re.compile(r"<CrossSects(?:\s+[^\s=<>/]+\s*=\s*(?:\"[^\"<>]*\"|'[^'<>]*'))*\s*>")
_ATTRIBUTE = re.compile(r"([^\s=]+)\s*=\s*(?:\"([^\"]*)\"|'([^']*)')")
_TAG = re.compile(rb"""<(?:[^>"']|"[^"]*"|'[^']*')*>""")  # a tag, quoted values holding '>' included
#: the characters XML 1.0 forbids (ASCII controls but tab, line feed, carriage return) made '<', which no pattern
#: of the scan takes: a chunk holding one is not recognised
_FORBIDDEN_TO_LT = bytes(ord("<") if c < 0x20 and c not in (0x09, 0x0A, 0x0D) else c for c in range(256))


class _Scanned:
    """One <CrossSects>'s sections as the scan read them: each section's ``sta`` text (None: the attribute is
    absent), how many numbers its points have, and per chunk the points' numbers (``np.array(words, dtype=float)``)
    or, where that conversion failed, the words themselves (the reader names the first bad one, as the tree's
    reading does); ``proved``: whether the content is well-formed by itself (see above), and left out of the guard."""

    def __init__(self) -> None:
        self.stations: list[str | None] = []
        #: the stations as numbers, and each section's points picked for its slopes (:func:`_slopes_from`'s
        #: columns), where the compiled scan read them (then ``stations`` is empty)
        self.station_values: np.ndarray | None = None
        self.picks: np.ndarray | None = None
        self.counts: list[int] | np.ndarray = []
        self.chunks: list[tuple[int, int, np.ndarray | None, list[str]]] = []  # first section, sections, values, words
        self.proved = True


def _attribute_sta(attrs: str) -> str | None:
    """``sta`` from a start tag's attributes (their value as the tree has it: XML's white-space normalisation)."""
    for name, dq, sq in _ATTRIBUTE.findall(attrs):
        if name == "sta":
            value = dq if dq or not sq else sq
            return value.replace("\r\n", " ").replace("\r", " ").replace("\n", " ").replace("\t", " ")
    return None


def _distinct(attrs: bytes) -> bool:
    """Whether a start tag's attributes (as the scan's pattern took them) have distinct names."""
    if attrs.count(b"=") < 2:  # (the '=' of one attribute, perhaps more in its value: cheap for the usual one)
        return True
    names = [name for name, _, _ in _ATTRIBUTE.findall(attrs.decode("ascii"))]
    return len(names) == len(set(names))


def _scan_region(text: bytes, start: int, end: int) -> _Scanned | None:
    """The sections of one <CrossSects>'s content (``text[start:end]``), or None where it holds anything the scan
    does not recognise (the document is then read as a tree): by the compiled scan where it was built and takes the
    content (read in place), else by :func:`_scan_region_python` (the reference: the same numbers, more shapes)."""
    if _xsectscan is not None:
        compiled = _scan_region_compiled(text, start, end)
        if compiled is not None:
            return compiled
    content = text[start:end]
    return _scan_region_python(content) if content.isascii() else None


def _scan_region_compiled(text: bytes, start: int, end: int) -> _Scanned | None:
    """``text[start:end]``'s sections read by app.formats._xsectscan (app/formats/csrc/xsectscan.c), a chunk at a
    time (the interpreter's lock is held in each and given up between them), or None where a chunk holds anything it
    does not take (a shape, a word or a number the Python scan and the tree's reading must judge). What it takes is
    the Python scan's usual shape in ASCII, well-formed by itself (proved), every number finite."""
    stations, counts, values, picks = [], [], [], []
    view = memoryview(text)
    pos, n = start, end
    while pos < n:
        stop = _section_end(text, min(pos + _SCAN_CHUNK, n), n)
        got = _xsectscan.scan(view[pos:stop])
        if got is None:
            return None
        pos = stop
        stations.append(got[0])
        counts.append(got[1])
        values.append(got[2])
        picks.append(got[3])
        time.sleep(0)  # the lock given up between chunks, as xmlsafe's parse does
    out = _Scanned()
    out.station_values = np.frombuffer(b"".join(stations), dtype=np.float64)
    out.counts = np.frombuffer(b"".join(counts), dtype=np.int64)
    out.chunks = [(0, len(out.counts), np.frombuffer(b"".join(values), dtype=np.float64), [])]
    out.picks = np.frombuffer(b"".join(picks), dtype=np.float64).reshape(-1, 5)
    return out


def _section_end(text: bytes, at: int, end: int) -> int:
    """Where the first ``</CrossSect>`` end tag at or after ``at`` ends (white space before its '>' too: a chunk
    ends on it however the sections are written, and the compiled scan's calls stay short), or ``end``."""
    while True:
        k = text.find(b"</CrossSect", at, end)
        if k < 0:
            return end
        after = k + len(b"</CrossSect")
        while after < end and text[after] in b" \t\r\n":
            after += 1
        if after < end and text[after] == ord(">"):
            return after + 1
        at = k + 1  # </CrossSectPnt, </CrossSects...


def _scan_region_python(text: bytes) -> _Scanned | None:
    """:func:`_scan_region` by regular expressions (the reference, and where the compiled scan was not built)."""
    out = _Scanned()
    # a reference, or "]]>" (which character data may not hold): well-formed or not, not proved here
    out.proved = b"&" not in text and b"]]>" not in text
    pos, n = 0, len(text)
    while pos < n:
        stop = text.find(b"</CrossSect>", min(pos + _SCAN_CHUNK, n))
        stop = n if stop < 0 else stop + len(b"</CrossSect>")
        piece = text[pos:stop].translate(_FORBIDDEN_TO_LT)
        pos = stop
        found = _SECTION.findall(piece)
        counts = [block.count(b"<CrossSectPnt") for _, _, _, block in found]  # points, two numbers each
        # every element of the content is in a recognised section: its '<' are the sections' (4 tags each and 2
        # per point); what lies outside the sections is text, which the tree's reading ignores too
        if piece.count(b"<") != 4 * len(found) + 2 * sum(counts):
            return None
        stas = [sta for sta, _, _, _ in found]
        usual = len(stas) - stas.count(b"")  # sections with the usual start tag, <CrossSect sta="...">
        if usual == len(stas) and stas:  # the values in their quotes (which they cannot hold), decoded at once
            out.stations += b"".join(stas).decode("ascii")[1:-1].split('""')
        else:
            for sta, attrs, _, _ in found:
                if sta:
                    out.stations.append(sta[1:-1].decode("ascii"))
                elif b"&" in attrs:
                    return None  # a reference in an attribute: the tree's value is not the text's
                else:
                    out.stations.append(_attribute_sta(attrs.decode("ascii")))  # None: no sta
        # every tag's attributes distinct (a point's: none at all, else not proved); where the chunk's only '=' are
        # those of the usual start tags' sta, there is nothing to check
        if out.proved and piece.count(b"=") != usual:
            out.proved = all(_distinct(a) and _distinct(s) and b"=" not in block for _, a, s, block in found)
        joined = b" ".join(block for _, _, _, block in found)
        bare = joined.replace(b"<CrossSectPnt>", b" ").replace(b"</CrossSectPnt>", b" ")
        words = (_TAG.sub(b" ", joined) if b"<" in bare else bare).split()
        if len(words) != 2 * sum(counts):
            return None
        try:
            values: np.ndarray | None = np.array(words, dtype=float)
            keep: list[str] = []
        except ValueError:
            values, keep = None, [w.decode("ascii") for w in words]
        if values is not None and not np.isfinite(values).all():
            values, keep = None, [w.decode("ascii") for w in words]
        out.chunks.append((len(out.counts), len(found), values, keep))
        out.counts += [2 * c for c in counts]
        time.sleep(0)  # the lock given up between chunks, as xmlsafe's parse does
    return out


Pieces = list[str | bytes | memoryview]


def _find(text: str | bytes, sub: str | bytes, start: int) -> int:
    """``text.find(sub, start)``, searched ``_SCAN_CHUNK`` at a time with the lock given up between two (one call over
    a 64 MiB content held it for 20-30 ms)."""
    n, step = len(text), _SCAN_CHUNK
    while start < n:
        at = text.find(sub, start, min(n, start + step + len(sub) - 1))
        if at >= 0:
            return at
        start += step
        time.sleep(0)
    return -1


def _ascii(text: str, start: int, end: int) -> bytearray | None:
    """``text[start:end]`` encoded as ASCII, or None where it holds another character (the tree reads it): a chunk
    at a time, the lock given up between two (the content sliced, checked and encoded in one call each held it for
    about 100 ms at 64 MiB); a bytearray grows in place."""
    out = bytearray()
    for a in range(start, end, _SCAN_CHUNK):
        piece = text[a : min(end, a + _SCAN_CHUNK)]
        if not piece.isascii():
            return None
        out += piece.encode("ascii")
        time.sleep(0)
    return out


def _cross_section_scan(text: str | bytes) -> tuple[Pieces, dict[str, _Scanned], Pieces] | None:
    """The pieces of ``text`` to build the tree from (each scanned <CrossSects>'s content replaced by the marker),
    the scanned sections by their marker's key (random: a file cannot name them) and the pieces for the guard
    (``text`` without the contents the scan proved well-formed); or None where no <CrossSects> can be scanned (a
    document of another shape, or one with a comment, a processing instruction, a CDATA section or a document type
    before the last section: there the text <CrossSects> could be no element). ``text`` is not yet guarded: what is
    taken from it is used only once the guard has passed it."""
    is_bytes = isinstance(text, bytes | bytearray)
    open_tag, close_tag = ("<CrossSects", "</CrossSects") if not is_bytes else (b"<CrossSects", b"</CrossSects")
    spans: list[tuple[int, int]] = []
    at = text.find(open_tag)
    while at >= 0:
        head = text[at : at + 4096]
        head = head.decode("ascii", "replace") if is_bytes else head
        m = _OPEN.match(head)
        if m is None:
            if head[len("<CrossSects") : len("<CrossSects") + 1] not in ("", " ", "\t", "\r", "\n", ">", "/"):
                at = text.find(open_tag, at + 1)  # another name (<CrossSectsX>)
                continue
            return None  # an empty element or attributes the pattern does not take: the tree reads it
        start = at + m.end()
        end = _find(text, close_tag, start)
        if end < 0:
            return None
        spans.append((start, end))
        at = text.find(open_tag, end)
    if not spans:
        return None
    # no markup declaration, comment, CDATA section or processing instruction before the last section (but the XML
    # declaration): searched for between the contents only (a content the scan takes holds no '<' but its tags')
    bang, query = ("<!", "<?") if not is_bytes else (b"<!", b"<?")
    gaps = [(0, spans[0][0]), *((e, s) for (_, e), (s, _) in itertools.pairwise(spans))]
    if any(text.find(bang, a, b) >= 0 for a, b in gaps):
        return None
    declaration = ("<?xml", b"<?xml")[is_bytes]
    for a, b in gaps:
        q = text.find(query, a, b)
        if q < 0:
            continue
        # only the XML declaration, at the start (after a byte-order mark)
        if text[:q] not in ("", "\ufeff", b"", b"\xef\xbb\xbf") or not text.startswith(declaration, q):
            return None
        if text.find(query, q + 2, b) >= 0:
            return None
    scanned: dict[str, _Scanned] = {}
    pieces: Pieces = []
    guarded: Pieces = []
    key = secrets.token_hex(16)
    view = memoryview(text) if is_bytes else text
    done = guarded_to = 0
    for k, (start, end) in enumerate(spans):
        if is_bytes:  # read in place (a copy of the content only where the Python scan reads it)
            region = _scan_region(text, start, end)
        else:
            content = _ascii(text, start, end)
            region = None if content is None else _scan_region(content, 0, end - start)
        if region is None:
            return None
        marker = f'<{_SCANNED} key="{key}-{k}"/>'
        pieces += [view[done:start], marker.encode("ascii") if is_bytes else marker]
        done = end
        if region.proved:
            guarded.append(view[guarded_to:start])
            guarded_to = end
        scanned[f"{key}-{k}"] = region
    pieces.append(view[done:])
    guarded.append(view[guarded_to:])
    return pieces, scanned, guarded


def _slopes(values: np.ndarray, counts: np.ndarray) -> np.ndarray:
    """Each section's (left, right) lane slopes [%] from its numbers, "offset elevation" pairs (``counts``: how many
    numbers each section has; an odd one at a section's end is not a pair): between the point nearest the centreline
    on each side (the first of equals) and the centreline's elevation (the last point at offset 0, else interpolated
    between those two); + rising from left to right (engine.road.geometry's convention), a negative offset left of
    the centreline; nan where a side has no point. Slopes are ratios: the file's unit cancels."""
    n = len(counts)
    pairs = counts // 2
    first = np.cumsum(counts) - counts
    sec = np.repeat(np.arange(n), pairs)
    j = np.arange(len(sec)) - np.repeat(np.cumsum(pairs) - pairs, pairs)
    at = np.repeat(first, pairs) + 2 * j
    x, z = values[at], values[at + 1]
    order = np.arange(len(x))
    left, right, zero = x < 0, x > 0, x == 0
    # left: the greatest negative offset (the first of equals): the last of each section's (offset, -order) sort
    i = np.flatnonzero(left)[np.lexsort((-order[left], x[left], sec[left]))]
    last = np.r_[sec[i][1:] != sec[i][:-1], True] if len(i) else np.zeros(0, bool)
    xl, zl = np.full(n, np.nan), np.full(n, np.nan)
    xl[sec[i][last]], zl[sec[i][last]] = x[i][last], z[i][last]
    # right: the least positive offset (the first of equals): the first of each section's (offset, order) sort
    i = np.flatnonzero(right)[np.lexsort((order[right], x[right], sec[right]))]
    head = np.r_[True, sec[i][1:] != sec[i][:-1]] if len(i) else np.zeros(0, bool)
    xr, zr = np.full(n, np.nan), np.full(n, np.nan)
    xr[sec[i][head]], zr[sec[i][head]] = x[i][head], z[i][head]
    # the centreline: the last point at offset 0 (in each section's order)
    i = np.flatnonzero(zero)
    last = np.r_[sec[i][1:] != sec[i][:-1], True] if len(i) else np.zeros(0, bool)
    zc = np.full(n, np.nan)
    zc[sec[i][last]] = z[i][last]
    return _slopes_from(xl, zl, xr, zr, zc)


def _slopes_from(xl: np.ndarray, zl: np.ndarray, xr: np.ndarray, zr: np.ndarray, zc: np.ndarray) -> np.ndarray:
    """:func:`_slopes` from each section's points picked (the nearest on the left and on the right, the centreline's
    elevation where a point is at offset 0; nan where there is none): the compiled scan picks them as it reads."""
    out = np.empty((len(xl), 2))
    zc = np.where(np.isnan(zc), zl + (zr - zl) * (0 - xl) / (xr - xl), zc)
    out[:, 0] = 100.0 * (zc - zl) / (0 - xl)
    out[:, 1] = 100.0 * (zr - zc) / xr
    out[np.isnan(xl) | np.isnan(xr)] = np.nan
    return out


def writer_of(root: ET.Element) -> str | None:
    """The application that wrote the file (``<Application name= version= manufacturer=>``), or None."""
    app = _child(root, "Application")
    if app is None:
        return None
    name, version = app.get("name"), app.get("version")
    # Novapoint writes its name into its version too (name="Novapoint" version="Novapoint 21.05.FP4d ..."): named once
    if name and version and (version == name or version.startswith(name + " ")):
        name = None
    text = " ".join(p for p in (name, version) if p)
    maker = app.get("manufacturer")
    if maker:
        text = f"{text} ({maker})" if text else maker
    return text[:200] or None


def read_road_file(text: str | bytes) -> RoadFile:
    """A LandXML 1.2 document as a :class:`~engine.road.geometry.RoadFile` (every alignment, in metres); raises
    :class:`~app.formats.alignment_io.AlignmentFormatError`."""
    scanned: dict[str, _Scanned] = {}

    def edit(whole: str | bytes) -> tuple[Pieces, Pieces] | None:  # the sections scanned (before the guard)
        scan = _cross_section_scan(whole)
        if scan is None:
            return None
        scanned.update(scan[1])
        return scan[0], scan[2]

    with xmlsafe.collection_paused():  # the tree's million elements: no collector passes, freed in slices
        root = xmlsafe.document(text, "LandXML", "LandXML", AlignmentFormatError, edit)
        try:
            return _road_file(root, scanned)
        finally:
            xmlsafe.free(root)


def _road_file(root: ET.Element, scanned: dict[str, _Scanned]) -> RoadFile:
    alignments_el = [e for e in root.iter() if e.tag.endswith("Alignment") and xmlsafe.local(e.tag) == "Alignment"]
    if not alignments_el:
        raise AlignmentFormatError("no <Alignment> element", "LandXML")
    reader = _Reader(root, scanned)
    alignments = tuple(reader.alignment(el, k) for k, el in enumerate(alignments_el, start=1))
    version = root.get("version")
    return RoadFile(
        format=f"{FORMAT} {version}" if version else FORMAT,
        alignments=alignments,
        linear_unit=reader.units.linear_name,
        writer=writer_of(root),
        skipped=tuple(reader.skipped),
        elements=tuple(sorted(reader.counts.items())),
    )

"""A small LandXML 1.2 writer for tests and examples: an alignment designed in metres (lines, arcs, spirals; a
profile of PVIs with symmetric parabolic curves; superelevation ranges; cross sections) written in any of the
reader's length units, every number with repr's shortest round-tripping digits.

Independent of app/formats/landxml.py: it writes the elements as the LandXML 1.2 schema names them, in the file's
unit (metres divided by the unit's length), so a reading back in metres tests the unit's conversion and every
attribute the reader takes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

#: metres per unit, by their definitions (international foot 0.3048 m, 1959; US survey foot 1200/3937 m)
UNITS = {"meter": 1.0, "kilometer": 1000.0, "millimeter": 0.001, "foot": 0.3048, "USSurveyFoot": 1200.0 / 3937.0}


@dataclass(frozen=True)
class Element:
    """``kind``: Line, Curve or Spiral; lengths and radii in metres (``math.inf``: a straight end)."""

    kind: str
    length_m: float
    radius_start_m: float = math.inf
    radius_end_m: float = math.inf
    rot: str | None = None  # cw / ccw
    name: str | None = None


@dataclass(frozen=True)
class Pvi:
    """A vertical point: station and elevation [m], the symmetric parabola's length there [m] (0: none)."""

    station_m: float
    elevation_m: float
    curve_m: float = 0.0


@dataclass(frozen=True)
class Design:
    name: str
    start_station_m: float
    elements: list[Element]
    pvis: list[Pvi] = field(default_factory=list)
    #: (station where full superelevation starts, where it ends, full superelevation %)
    superelevation: list[tuple[float, float, float]] = field(default_factory=list)
    #: (station, left lane slope %, right lane slope %, lane width m): + rising from left to right
    cross_sections: list[tuple[float, float, float, float]] = field(default_factory=list)


def _n(metres: float, unit: float) -> str:
    return repr(metres / unit)


def _r(metres: float, unit: float) -> str:
    return "INF" if math.isinf(metres) else _n(metres, unit)


def landxml(
    design: Design,
    unit_name: str = "meter",
    *,
    element_stations: bool = False,
    application: str = "tests/landxml_writer.py",
) -> str:
    """The design as a LandXML 1.2 document in ``unit_name`` (``element_stations``: write every element's
    ``staStart``, as Aplitop and Novapoint do; else only the alignment's, as Civil 3D and OpenRoads do)."""
    u = UNITS[unit_name]
    system = "Metric" if unit_name in ("meter", "kilometer", "millimeter") else "Imperial"
    out = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        '<LandXML xmlns="http://www.landxml.org/schema/LandXML-1.2" version="1.2">',
        f'<Units><{system} linearUnit="{unit_name}" angularUnit="decimal degrees"/></Units>',
        f'<Application name="{application}" version="1"/>',
        "<Alignments>",
        f'<Alignment name="{design.name}" staStart="{_n(design.start_station_m, u)}"'
        f' length="{_n(sum(e.length_m for e in design.elements), u)}">',
        "<CoordGeom>",
    ]
    station = design.start_station_m
    for e in design.elements:
        sta = f' staStart="{_n(station, u)}"' if element_stations else ""
        name = f' name="{e.name}"' if e.name else ""
        if e.kind == "Line":
            out.append(f'<Line length="{_n(e.length_m, u)}"{sta}{name}/>')
        elif e.kind == "Curve":
            out.append(
                f'<Curve rot="{e.rot}" radius="{_r(e.radius_start_m, u)}" length="{_n(e.length_m, u)}"{sta}{name}/>'
            )
        else:
            out.append(
                f'<Spiral rot="{e.rot}" spiType="clothoid" radiusStart="{_r(e.radius_start_m, u)}" '
                f'radiusEnd="{_r(e.radius_end_m, u)}" length="{_n(e.length_m, u)}"{sta}{name}/>'
            )
        station += e.length_m
    out.append("</CoordGeom>")
    if design.pvis:
        out.append('<Profile><ProfAlign name="Design">')
        for p in design.pvis:
            text = f"{_n(p.station_m, u)} {_n(p.elevation_m, u)}"
            if p.curve_m > 0:
                out.append(f'<ParaCurve length="{_n(p.curve_m, u)}">{text}</ParaCurve>')
            else:
                out.append(f"<PVI>{text}</PVI>")
        out.append("</ProfAlign></Profile>")
    for k, (start, end, full) in enumerate(design.superelevation, start=1):
        out.append(
            f'<Superelevation staStart="{_n(start - 20.0, u)}" staEnd="{_n(end + 20.0, u)}" name="SE{k}">'
            f"<FullSuperSta>{_n(start, u)}</FullSuperSta><FullSuperelev>{full!r}</FullSuperelev>"
            f"<RunoffSta>{_n(end, u)}</RunoffSta></Superelevation>"
        )
    if design.cross_sections:
        out.append("<CrossSects>")
        for sta, left, right, width in design.cross_sections:
            # the centreline at 0; the left edge lower by left% x width when the lane rises toward the centre
            z0 = 100.0
            points = [(-width, z0 - left / 100.0 * width), (0.0, z0), (width, z0 + right / 100.0 * width)]
            pnts = "".join(f"<CrossSectPnt>{_n(x, u)} {_n(z, u)}</CrossSectPnt>" for x, z in points)
            surf = f'<DesignCrossSectSurf name="Top">{pnts}</DesignCrossSectSurf>'
            out.append(f'<CrossSect sta="{_n(sta, u)}">{surf}</CrossSect>')
        out.append("</CrossSects>")
    out += ["</Alignment>", "</Alignments>", "</LandXML>"]
    return "\n".join(out) + "\n"

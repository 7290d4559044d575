"""A road-design file's alignments (:class:`engine.road.geometry.RoadFile`, whatever reader made it: LandXML,
IFC) as the curves the assessment takes, one row per bend, and the reading summary the answer carries.

Each bend of :func:`engine.road.geometry.bends` is a row: its governing radius, where its arc starts (the station as
the file writes it, and the distance along), the bend's start and end, direction, arc length, deflection and
spiral lengths. The grade is the chosen profile's at the bend's middle where the profile covers the whole bend
(``grade_source`` ``profile``, with its least and greatest over the bend), else the request's; the superelevation the
file's (``Superelevation`` ranges first, else its cross sections: :func:`engine.road.geometry.bend_superelevation`),
else the request's (or the design standard's, derived later). The request's values (``superelevation_percent``,
``grade_percent``, ``posted_speed_kmh`` and the per-curve ``overrides``) are the fallbacks where the file gives
nothing: where both give one, the file's is used and the row's source says so.
"""

from __future__ import annotations

import dataclasses
import math
from collections import Counter
from collections.abc import Callable
from typing import Any

import numpy as np

from app.formats import landxml
from app.formats.alignment_io import (
    BEND_COLUMNS,
    MAX_CURVES,
    AlignmentFormatError,
    BendTable,
    CurveOverride,
    CurveTable,
    _Collector,
    check_curve_id,
)
from engine.road.geometry import (
    AlignmentGeometry,
    Profile,
    RoadFile,
    bend_superelevation,
    bends,
    covers,
    element_distances,
    grade_at,
    grade_range,
    station_at,
)

#: cross sections that differ from a ``Superelevation`` element by more than this [percentage points] are reported
#: (the element is used); below it, rounding in the file
DISAGREEMENT_PERCENT = 0.05
SUPERELEVATION_FROM = ("file", "cross-sections", "request", "standard")


#: the road-file readers by the request's field that holds their document: each takes the document's text and
#: returns a :class:`~engine.road.geometry.RoadFile` in SI units (or raises
#: :class:`~app.formats.alignment_io.AlignmentFormatError`); an IFC 4.3 reader is added here as ``"ifc"``
ROAD_READERS: dict[str, Callable[[str | bytes], RoadFile]] = {"landxml": landxml.read_road_file}


def read_road_document(kind: str, document: str | bytes, **options: Any) -> CurveTable:
    """The curves of a road file of ``kind`` (a key of :data:`ROAD_READERS`): its reader, then
    :func:`curves_from_road_file` with ``options``."""
    return curves_from_road_file(ROAD_READERS[kind](document), **options)


def _profile(a: AlignmentGeometry, name: str | None) -> Profile | None:
    if not a.profiles:
        return None
    if name is None:
        return a.profiles[0]
    return next((p for p in a.profiles if p.name == name), None)


def curves_from_road_file(
    road: RoadFile,
    *,
    superelevation_percent: float | None,
    grade_percent: float = 0.0,
    posted_speed_kmh: float | None = None,
    overrides: dict[str, CurveOverride] | None = None,
    max_curves: int = MAX_CURVES,
    profile: str | None = None,
) -> CurveTable:
    """The file's bends as curves (with their :class:`~app.formats.alignment_io.BendTable` and the ``reading``
    summary), the request's values where the file gives none (see the module's docstring). ``profile``: the
    profile's name (default: each alignment's first). Raises :class:`~app.formats.alignment_io.AlignmentFormatError`
    (an override or a profile that is not in the file, a curve out of the domain's bounds at its element)."""
    overrides = dict(overrides or {})
    curves = _Collector({"radius_m": "radius"}, id_column="name", max_curves=max_curves)
    extra: list[tuple[float, ...]] = []
    skipped = [{"what": what, "why": why} for what, why in road.skipped]
    profiles_used: list[str] = []
    sources: Counter[str] = Counter()
    if profile is not None and not any(p.name == profile for a in road.alignments for p in a.profiles):
        names = sorted({p.name for a in road.alignments for p in a.profiles})
        raise AlignmentFormatError(
            f"no profile (ProfAlign) named {profile!r}; the file's: {', '.join(map(repr, names)) or 'none'}",
            "profile",
            "profile",
        )
    for a in road.alignments:
        chosen = _profile(a, profile)
        if chosen is not None and chosen.name not in profiles_used:
            profiles_used.append(chosen.name)
        for p in a.profiles:
            if p is not chosen:
                why = f"profile {chosen.name!r} used" if chosen is not None else f"no profile named {profile!r} here"
                skipped.append({"what": f"{a.where} ProfAlign {p.name!r}", "why": f"{why} (choose one with `profile`)"})
        starts = element_distances(a)
        written = {float(starts[k]): e.station_m for k, e in enumerate(a.elements) if e.station_m is not None}

        def station(d: float, a: AlignmentGeometry = a, written: dict[float, float] = written) -> float:
            w = written.get(d)
            return w if w is not None else float(station_at(a, d))

        no_ranges = dataclasses.replace(a, superelevation=()) if a.superelevation and a.cross_slopes else None
        apexes = 0
        for b in bends(a):
            arc = next((a.elements[k] for k in b.elements if a.elements[k].kind == "arc"), None)
            if arc is not None:
                cid, where = arc.name or "", arc.where
            else:
                apexes += 1
                cid = f"{a.name}#apex{apexes}"
                first = a.elements[b.elements[0]]
                where = f"{first.where}: the bend of spirals {cid!r}"
            cid = check_curve_id(cid, where, "name")
            ov = overrides.pop(cid, CurveOverride())
            e_req = ov.superelevation_percent if ov.superelevation_percent is not None else superelevation_percent
            g_req = ov.grade_percent if ov.grade_percent is not None else grade_percent
            v = ov.posted_speed_kmh if ov.posted_speed_kmh is not None else posted_speed_kmh
            if chosen is not None and covers(chosen, b.start_m, b.end_m):
                g = 100.0 * grade_at(chosen, b.middle_m)
                g_lo, g_hi = (100.0 * x for x in grade_range(chosen, b.start_m, b.end_m))
                g_src = 1.0
            else:
                g, g_lo, g_hi, g_src = g_req, math.nan, math.nan, 0.0
            from_file = bend_superelevation(a, b)
            if from_file is not None:
                e, how = from_file
                e_src = float(("file", "cross-sections").index(how))
                sources[how] += 1
                if how == "file" and no_ranges is not None:
                    sections = bend_superelevation(no_ranges, b)
                    if sections is not None and abs(sections[0] - e) > DISAGREEMENT_PERCENT:
                        skipped.append(
                            {
                                "what": f"{a.where} cross sections at curve {cid!r}",
                                "why": f"they give {sections[0]:.2f} %, the <Superelevation> element {e:.2f} %: "
                                "the element is used",
                            }
                        )
            else:
                e, e_src = e_req, math.nan
                sources["request" if e_req is not None else "standard"] += 1
            try:
                curves.add(cid, where, b.radius_m, e, g, v, station(b.arc_start_m))
            except AlignmentFormatError as exc:
                if exc.field == "name":
                    raise AlignmentFormatError(f"duplicate curve name {cid!r}", where, "name") from None
                raise
            extra.append(
                (
                    b.arc_start_m,
                    station(b.start_m),
                    station(b.end_m),
                    0.0 if b.direction == "left" else 1.0,
                    b.arc_length_m,
                    b.deflection_deg,
                    b.spiral_in_m,
                    b.spiral_out_m,
                    float(b.compound),
                    float(b.reverse),
                    g_src,
                    g_lo,
                    g_hi,
                    e_src,
                )
            )
    if overrides:
        raise AlignmentFormatError(
            f"overrides name curves that are not in the file: {', '.join(sorted(overrides))}", "curve_overrides"
        )
    if not sources:
        sources["request" if superelevation_percent is not None else "standard"] += 1
    table = curves.table()
    cols = np.array(extra, dtype=float).reshape(-1, len(BEND_COLUMNS))
    reading: dict[str, Any] = {
        "format": road.format,
        "writer": road.writer,
        "linear_unit": road.linear_unit,
        "alignments": [a.name for a in road.alignments],
        "elements": dict(road.elements),
        "profile": ", ".join(profiles_used) or None,
        # the source of most rows (each row says its own)
        "superelevation_from": max(SUPERELEVATION_FROM, key=lambda s: (sources[s], -SUPERELEVATION_FROM.index(s))),
        "skipped": skipped,
    }
    bend_table = BendTable({name: cols[:, k].copy() for k, name in enumerate(BEND_COLUMNS)})
    return dataclasses.replace(table, bends=bend_table, reading=reading)

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

from app.formats import ifc_io, landxml
from app.formats.alignment_io import (
    BEND_COLUMNS,
    MAX_CURVES,
    AlignmentFormatError,
    BendTable,
    CurveOverride,
    CurveTable,
    check_curve_id,
    checked,
)
from engine.road import (
    AlignmentGeometry,
    ElementColumns,
    Profile,
    RoadFile,
    bend_columns,
    covers_many,
    element_columns,
    element_distances,
    grades_over,
    station_at,
    superelevations,
)

#: cross sections that differ from a ``Superelevation`` element by more than this [percentage points] are reported
#: (the element is used); below it, rounding in the file
DISAGREEMENT_PERCENT = 0.05
SUPERELEVATION_FROM = ("file", "cross-sections", "request", "standard")


#: a road-file reader: the document's text (or bytes) -> a :class:`~engine.road.geometry.RoadFile` in SI units (or
#: :class:`~app.formats.alignment_io.AlignmentFormatError`)
RoadReader = Callable[[str | bytes], RoadFile]

#: the road-file readers by the request's field that holds their document
ROAD_READERS: dict[str, RoadReader] = {
    "landxml": landxml.read_road_file,
    "ifc": ifc_io.read_road_file,
}


def read_road_document(kind: str, document: str | bytes, **options: Any) -> CurveTable:
    """The curves of a road file of ``kind`` (a key of :data:`ROAD_READERS`): its reader, then
    :func:`curves_from_road_file` with ``options``."""
    road = ROAD_READERS[kind](document)
    try:
        return curves_from_road_file(road, **options)
    finally:
        _release(road)


#: list entries freed per call (a few milliseconds)
_RELEASE_SLICE = 4096


def _release(road: RoadFile) -> None:
    """Empty the large lists of the file's columns a slice at a time, so a million names and places are not freed
    in one C call that holds the interpreter's lock (when the last reference goes, possibly in the event loop's
    thread: a refusal's traceback holds this frame)."""
    for a in road.alignments:
        if isinstance(a.elements, ElementColumns):
            for items in (a.elements.name, a.elements.where, a.elements.spiral_type):
                while items:
                    del items[-_RELEASE_SLICE:]


def _profile(a: AlignmentGeometry, name: str | None) -> Profile | None:
    if not a.profiles:
        return None
    if name is None:
        return a.profiles[0]
    return next((p for p in a.profiles if p.name == name), None)


def _written_stations(
    a: AlignmentGeometry, els: ElementColumns, starts: np.ndarray, distance_m: np.ndarray
) -> np.ndarray:
    """The station as the file writes it at each distance: an element's own ``staStart`` where the distance is that
    element's start, else the alignment's start station plus the distance (station equations applied)."""
    own = np.append(els.station_m, math.nan)
    d = np.asarray(distance_m, dtype=float)
    j = np.clip(np.searchsorted(starts, d), 0, len(starts) - 1)
    written = np.where(starts[j] == d, own[j], math.nan)
    return np.where(np.isnan(written), station_at(a, d), written)


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
    (an override or a profile that is not in the file, a curve out of the domain's bounds at its element). Computed
    on arrays per alignment (:func:`engine.road.geometry.bend_columns`): a million curves take seconds."""
    nan = math.nan
    overrides = dict(overrides or {})
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
    ids: list[str] = []
    where: list[str] = []
    parts: list[dict[str, np.ndarray]] = []
    for a in road.alignments:
        chosen = _profile(a, profile)
        if chosen is not None and chosen.name not in profiles_used:
            profiles_used.append(chosen.name)
        for p in a.profiles:
            if p is not chosen:
                why = f"profile {chosen.name!r} used" if chosen is not None else f"no profile named {profile!r} here"
                skipped.append({"what": f"{a.where} ProfAlign {p.name!r}", "why": f"{why} (choose one with `profile`)"})
        b = bend_columns(a)
        n = len(b)
        if not n:
            continue
        starts = element_distances(a)
        els, arcs = element_columns(a), b.arc_element.tolist()
        names, places = els.name, els.where
        if len(ids) + n > max_curves:  # refused before a list of every row's id is made (and freed again)
            k = max_curves - len(ids)  # the first row past the limit, in this alignment
            if arcs[k] >= 0:
                past = places[arcs[k]]
            else:  # named as the rows name it: <alignment>#apex<m>, m counting the bends of spirals
                cid = f"{a.name}#apex{sum(1 for x in arcs[: k + 1] if x < 0)}"
                past = f"{places[int(b.first_element[k])]}: the bend of spirals {cid!r}"
            raise AlignmentFormatError(f"more than {max_curves} curves", past)
        if min(arcs) >= 0:  # every row an arc (the common case): its element's name and place
            ids += [names[i] or "" for i in arcs]
            where += [places[i] for i in arcs]
        else:
            apex = 0
            for k, arc in enumerate(arcs):
                if arc >= 0:
                    ids.append(names[arc] or "")
                    where.append(places[arc])
                else:
                    apex += 1
                    cid = f"{a.name}#apex{apex}"
                    ids.append(cid)
                    where.append(f"{places[int(b.first_element[k])]}: the bend of spirals {cid!r}")
        middle = 0.5 * (b.start_m + b.end_m)
        if chosen is not None:
            covered = covers_many(chosen, b.start_m, b.end_m)
            g_lo, g_hi, g_mid = grades_over(chosen, b.start_m, b.end_m, middle)
            g_file = 100.0 * g_mid
        else:
            covered = np.zeros(n, dtype=bool)
            g_lo = g_hi = g_file = np.full(n, nan)
        e_file, e_from = superelevations(a, b)
        if a.superelevation and a.cross_slopes:  # the element wins; cross sections that say otherwise are reported
            e_sections, s_from = superelevations(dataclasses.replace(a, superelevation=()), b)
            differ = (e_from == 0) & (s_from == 1) & (np.abs(e_sections - e_file) > DISAGREEMENT_PERCENT)
            first = len(ids) - n
            given, used = e_sections.tolist(), e_file.tolist()  # (Python floats: formatted as numpy's, faster)
            for k in np.flatnonzero(differ).tolist():
                skipped.append(
                    {
                        "what": f"{a.where} cross sections at curve {ids[first + k]!r}",
                        "why": f"they give {given[k]:.2f} %, the <Superelevation> element {used[k]:.2f} %: "
                        "the element is used",
                    }
                )
        parts.append(
            {
                "radius_m": b.radius_m,
                "e_file": e_file,
                "superelevation_from": e_from,
                "g_file": np.where(covered, g_file, nan),
                "grade_source": covered.astype(float),
                "grade_min_percent": np.where(covered, 100.0 * g_lo, nan),
                "grade_max_percent": np.where(covered, 100.0 * g_hi, nan),
                "station_m": _written_stations(a, els, starts, b.arc_start_m),
                "distance_m": b.arc_start_m,
                "bend_start_m": _written_stations(a, els, starts, b.start_m),
                "bend_end_m": _written_stations(a, els, starts, b.end_m),
                "direction": b.direction.astype(float),
                "arc_length_m": b.arc_length_m,
                "deflection_deg": b.deflection_deg,
                "spiral_in_m": b.spiral_in_m,
                "spiral_out_m": b.spiral_out_m,
                "compound": b.compound.astype(float),
                "reverse": b.reverse.astype(float),
            }
        )
    seen: set[str] = set()
    for cid, w in zip(ids, where, strict=True):
        check_curve_id(cid, w, "name")
        if cid in seen:
            raise AlignmentFormatError(f"duplicate curve name {cid!r}", w, "name")
        seen.add(cid)
    n = len(ids)
    col = {k: np.concatenate([p[k] for p in parts]) if parts else np.empty(0) for k in _PART_COLUMNS}
    # the request's values, per curve where overridden: the fallbacks where the file gives nothing
    e_req = np.full(n, nan if superelevation_percent is None else superelevation_percent)
    g_req = np.full(n, float(grade_percent))
    v_req = np.full(n, nan if posted_speed_kmh is None else posted_speed_kmh)
    if overrides:
        index = {cid: k for k, cid in enumerate(ids)}
        unknown = sorted(set(overrides) - set(index))
        if unknown:
            raise AlignmentFormatError(
                f"overrides name curves that are not in the file: {', '.join(unknown)}", "curve_overrides"
            )
        for cid, ov in overrides.items():
            k = index[cid]
            if ov.superelevation_percent is not None:
                e_req[k] = ov.superelevation_percent
            if ov.grade_percent is not None:
                g_req[k] = ov.grade_percent
            if ov.posted_speed_kmh is not None:
                v_req[k] = ov.posted_speed_kmh
    from_file = ~np.isnan(col["superelevation_from"])
    sources["file"] += int((col["superelevation_from"] == 0).sum())
    sources["cross-sections"] += int((col["superelevation_from"] == 1).sum())
    sources["request"] += int((~from_file & ~np.isnan(e_req)).sum())
    sources["standard"] += int((~from_file & np.isnan(e_req)).sum())
    if not n:
        sources["request" if superelevation_percent is not None else "standard"] += 1
    table = checked(
        CurveTable(
            ids,
            col["radius_m"],
            np.where(from_file, col["e_file"], e_req),
            np.where(col["grade_source"] == 1.0, col["g_file"], g_req),
            v_req,
            col["station_m"],
            where=where,
        ),
        {"radius_m": "radius"},
    )
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
        # what the reader had to assume or read in a way the file did not say (e.g. a start station of 0)
        "notes": [f"{a.name}: {note}" for a in road.alignments for note in a.notes],
    }
    bend_table = BendTable({name: np.ascontiguousarray(col[name], dtype=float) for name in BEND_COLUMNS})
    return dataclasses.replace(table, bends=bend_table, reading=reading)


#: what each alignment contributes, concatenated over the alignments
_PART_COLUMNS = ("radius_m", "e_file", "g_file", "station_m", *BEND_COLUMNS)

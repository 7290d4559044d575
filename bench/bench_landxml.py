"""Reading a large LandXML alignment (app/formats/landxml.py + app/formats/road_file.py): the time to go from the
document's bytes to the curves' columns, for the shape of file the service always read (Curves only, metric) and
the same alignment with what a design package adds (lines between the curves, a profile of parabolic vertical
curves, a Superelevation element per curve and design cross sections).

The ceiling is the reader the service had before LandXML was read whole (``git show 09731d0~1:app/formats/
alignment_io.py``: Curves only, no profile, no stations computed), copied below as :func:`old_read_landxml` and
timed in the same run, interleaved with the reader of today on the same document (the machine is shared: a figure is
read against the ceiling beside it, not against another run's). The designed documents are timed in wall and in
processor time (the second varies less on a shared machine), and the one with cross sections twice more: by the
Python scan alone (what runs where the compiled scan, app.formats._xsectscan, was not built) and with the cross
sections' scan off (app/formats/landxml.py: every section read from the tree), the reading the scan replaces. The
row of the cross sections says which scan read them. With Superelevation elements the cross sections are banked
through each curve to its element's superelevation (they agree, as a design package writes them); a last row keeps
every section at the normal crown under them (they disagree under every curve, and the reading notes each).

    python bench/bench_landxml.py [--curves 200000] [--repeat 3] [--write]

``--write`` puts the figures into docs/uploads.md between the ``bench_landxml`` markers.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from datetime import UTC, datetime
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from app.formats import landxml, xmlsafe  # noqa: E402
from app.formats.alignment_io import (  # noqa: E402
    MAX_CURVES,
    AlignmentFormatError,
    CurveOverride,
    CurveTable,
    _number,
    check_curve_id,
    read_landxml,
)
from bench.bench_alignments import as_landxml, make_curves  # noqa: E402
from engine import InvalidRoad  # noqa: E402
from engine.road import check_columns  # noqa: E402
from scripts.docblock import machine, markers, write_block  # noqa: E402

DOCS = ROOT / "docs" / "uploads.md"
BEGIN, END = markers("bench_landxml")


# ---------------------------------------------------------------------------------------------- the ceiling
# The reader of 09731d0~1 (app/formats/alignment_io.py: _Collector, _landxml_curves, read_landxml), unchanged but for
# its names; _number, check_curve_id and xmlsafe are the same code today.


class _OldCollector:
    def __init__(self, columns, id_column="id", max_curves=MAX_CURVES):
        self.max_curves = max_curves
        self.ids, self.values, self.where, self.seen = [], [], [], set()
        self.columns = columns or {}
        self.id_column = id_column

    def add(self, cid, where, radius, e, grade, posted, station):
        if cid in self.seen:
            raise AlignmentFormatError(f"duplicate id {cid!r}", where, self.id_column)
        self.seen.add(cid)
        nan = float("nan")
        opt = (nan if e is None else e, grade, nan if posted is None else posted, nan if station is None else station)
        self.ids.append(cid)
        self.values.append((radius, *opt))
        self.where.append(where)
        if len(self.ids) > self.max_curves:
            raise AlignmentFormatError(f"more than {self.max_curves} curves", where)

    def table(self):
        import numpy as np

        a = np.array(self.values, dtype=float).reshape(-1, 5)
        t = CurveTable(self.ids, *(a[:, k].copy() for k in range(5)), where=self.where)
        try:
            check_columns(t.radius_m, t.superelevation_percent, t.grade_percent, t.posted_speed_kmh)
        except InvalidRoad as exc:
            raise AlignmentFormatError(str(exc)) from None
        return t


def _old_curves(root):
    alignments = [e for e in root.iter() if e.tag.endswith("Alignment") and xmlsafe.local(e.tag) == "Alignment"]
    if not alignments:
        raise AlignmentFormatError("no <Alignment> element", "LandXML")
    for a_index, alignment in enumerate(alignments, start=1):
        a_name = alignment.get("name") or f"alignment {a_index}"
        n = 0
        for geom in (e for e in alignment if xmlsafe.local(e.tag) == "CoordGeom"):
            for el in geom:
                if el.tag.endswith("Curve") and xmlsafe.local(el.tag) == "Curve":
                    n += 1
                    yield a_name, n, el


def old_read_landxml(text, *, superelevation_percent, grade_percent=0.0, posted_speed_kmh=None, max_curves=MAX_CURVES):
    overrides: dict[str, CurveOverride] = {}
    curves = _OldCollector({"radius_m": "radius"}, id_column="name", max_curves=max_curves)
    for a_name, n, el in _old_curves(xmlsafe.document(text, "LandXML", "LandXML", AlignmentFormatError)):
        where = f"Alignment {a_name[:100]!r} CoordGeom Curve #{n}"
        cid = check_curve_id(el.get("name") or f"{a_name}#{n}", where, "name")
        where = f"{where} ({cid!r})"
        r_text = el.get("radius")
        if r_text is None:
            raise AlignmentFormatError("has no radius attribute", where, "radius")
        sta = el.get("staStart")
        ov = overrides.pop(cid, CurveOverride())
        e = ov.superelevation_percent if ov.superelevation_percent is not None else superelevation_percent
        g = ov.grade_percent if ov.grade_percent is not None else grade_percent
        v = ov.posted_speed_kmh if ov.posted_speed_kmh is not None else posted_speed_kmh
        station = _number(sta, "staStart", where) if sta is not None else None
        curves.add(cid, where, _number(r_text, "radius", where), e, g, v, station)
    return curves.table()


# ---------------------------------------------------------------------------------------------- documents


def designed(
    curves: list[dict], *, profile: bool, superelevation: bool, sections: bool, banked: bool | None = None
) -> str:
    """The curves as a design package writes them: a 50 m line before each and every element's staStart; with
    ``profile`` a ProfAlign with a PVI every 500 m (150 m parabolas), with ``superelevation`` a Superelevation
    element per curve, with ``sections`` a design cross section every 50 m (one on each line, one at each curve's
    middle). ``banked`` (default: with ``superelevation``): the section at a curve's middle rotated about the
    centreline to the curve's full superelevation, as a design package writes the sections of a superelevated road
    (they agree with its Superelevation elements); else every section keeps the normal crown, -2 % on either side
    (with Superelevation elements of 0-12 %: cross sections that disagree with them under every curve)."""
    banked = superelevation if banked is None else banked
    items, supers, sta = [], [], 0.0
    middles: dict[int, float] = {}  # a curve's middle station: its superelevation [%]
    for c in curves:
        items.append(f'<Line length="50" staStart="{sta}"/>')
        sta += 50
        items.append(f'<Curve rot="cw" radius="{c["radius_m"]}" length="50" staStart="{sta}" name="{c["id"]}"/>')
        middles[int(sta) + 25] = c["superelevation_percent"]
        supers.append(
            f'<Superelevation staStart="{sta - 10}" staEnd="{sta + 60}"><FullSuperSta>{sta}</FullSuperSta>'
            f"<FullSuperelev>{c['superelevation_percent']}</FullSuperelev>"
            f"<RunoffSta>{sta + 50}</RunoffSta></Superelevation>"
        )
        sta += 50
    pvis = ["<PVI>0 100</PVI>"]
    for k, s in enumerate(range(500, int(sta) - 500, 500)):
        pvis.append(f'<ParaCurve length="150">{s} {100 + (k % 2) * 10}</ParaCurve>')
    pvis.append(f"<PVI>{sta} 100</PVI>")
    crown = (
        "<CrossSectPnt>-3.5 99.93</CrossSectPnt><CrossSectPnt>0 100</CrossSectPnt>"
        "<CrossSectPnt>3.5 99.93</CrossSectPnt>"
    )

    def surface(s: int) -> str:
        e = middles.get(s) if banked else None
        if e is None:
            return crown
        # every curve turns right (rot="cw"): banked toward the inside, the left edge up and the right edge down
        dz = 3.5 * e / 100
        return (
            f"<CrossSectPnt>-3.5 {100 + dz:.4f}</CrossSectPnt><CrossSectPnt>0 100</CrossSectPnt>"
            f"<CrossSectPnt>3.5 {100 - dz:.4f}</CrossSectPnt>"
        )

    sects = "".join(
        f'<CrossSect sta="{s}"><DesignCrossSectSurf>{surface(s)}</DesignCrossSectSurf></CrossSect>'
        for s in range(25, int(sta), 50)
    )
    return (
        '<?xml version="1.0"?><LandXML xmlns="http://www.landxml.org/schema/LandXML-1.2" version="1.2">'
        '<Units><Metric linearUnit="meter"/></Units><Alignments><Alignment name="A" staStart="0"><CoordGeom>'
        + "".join(items)
        + "</CoordGeom>"
        + (f'<Profile><ProfAlign name="P">{"".join(pvis)}</ProfAlign></Profile>' if profile else "")
        + ("".join(supers) if superelevation else "")
        + (f"<CrossSects>{sects}</CrossSects>" if sections else "")
        + "</Alignment></Alignments></LandXML>"
    )


def _once(fn, doc: bytes) -> float:
    t0 = time.perf_counter()
    fn(doc, superelevation_percent=6.0, max_curves=10**7)
    return time.perf_counter() - t0


def _once_cpu(fn, doc: bytes) -> tuple[float, float]:
    """(wall, processor) seconds of one reading: on a shared machine the processor time this process used varies
    less than the wall time (others' work is not in it; its waits for the processor are not either)."""
    t0, c0 = time.perf_counter(), time.process_time()
    fn(doc, superelevation_percent=6.0, max_curves=10**7)
    return time.perf_counter() - t0, time.process_time() - c0


def _python_scan(doc: bytes, **kw):
    """Today's reader with the compiled scan of the cross sections off: the regular expressions read them."""
    compiled = landxml._xsectscan
    landxml._xsectscan = None
    try:
        return read_landxml(doc, **kw)
    finally:
        landxml._xsectscan = compiled


def _as_tree(doc: bytes, **kw):
    """Today's reader with the cross sections' scan off: every section read from the tree, as before the scan."""
    scan = landxml._cross_section_scan
    landxml._cross_section_scan = lambda text: None
    try:
        return read_landxml(doc, **kw)
    finally:
        landxml._cross_section_scan = scan


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--curves", type=int, default=200_000)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--write", action="store_true", help="write the figures into docs/uploads.md")
    args = parser.parse_args()
    when = f"{datetime.now(UTC):%Y-%m-%d %H:%M} UTC; {machine()}"
    curves = make_curves(args.curves)
    rows: list[list[str]] = []
    today = as_landxml(curves).encode()
    old, new = [], []
    for _ in range(args.repeat):  # interleaved: the machine's load falls on both alike
        old.append(_once(old_read_landxml, today))
        new.append(_once(read_landxml, today))
    size = f"{len(today) / 2**20:.1f}"
    ceiling = min(old)
    rows.append(["Curves only: the reader before issue 39 (the ceiling)", size, f"{min(old):.2f}",
                 f"{statistics.median(old):.2f}", "", ""])  # fmt: skip
    rows.append(["Curves only: today's reader", size, f"{min(new):.2f}", f"{statistics.median(new):.2f}", "",
                 f"{100 * (min(new) / ceiling - 1):+.0f} % on the ceiling"])  # fmt: skip
    base = base_cpu = None
    for name, kw, reader in (
        ("lines and curves, every staStart", {"profile": False, "superelevation": False, "sections": False}, None),
        ("  + a profile", {"profile": True, "superelevation": False, "sections": False}, None),
        ("  + a profile and cross sections" + (", the compiled scan" if landxml._xsectscan else ", the Python scan "
         "(the compiled scan NOT BUILT)"), {"profile": True, "superelevation": False, "sections": True}, None),
        ("  + a profile and cross sections, the Python scan alone",
         {"profile": True, "superelevation": False, "sections": True}, _python_scan),
        ("  + a profile and cross sections, read as a tree (the scan off)",
         {"profile": True, "superelevation": False, "sections": True}, _as_tree),
        ("  + a profile, Superelevation, cross sections (banked through the curves, agreeing)",
         {"profile": True, "superelevation": True, "sections": True}, None),
        ("  + a profile, Superelevation, cross sections crowned under every curve (disagreeing: a note per curve)",
         {"profile": True, "superelevation": True, "sections": True, "banked": False}, None),
    ):  # fmt: skip
        data = designed(curves, **kw).encode()
        samples = [_once_cpu(reader or read_landxml, data) for _ in range(args.repeat)]
        best, cpu = min(w for w, _ in samples), min(c for _, c in samples)
        if base is None:
            base, base_cpu, more = best, cpu, ""
        else:
            more = f"{100 * (best / base - 1):+.0f} % on lines and curves ({100 * (cpu / base_cpu - 1):+.0f} % in cpu)"
        rows.append([name.strip(), f"{len(data) / 2**20:.1f}", f"{best:.2f}",
                     f"{statistics.median(w for w, _ in samples):.2f}", f"{cpu:.2f}", more])  # fmt: skip
    columns = ["document (200,000 curves)" if args.curves == 200_000 else f"document ({args.curves} curves)",
               "MiB", "best [s]", "median [s]", "cpu best [s]", "compared"]  # fmt: skip
    for r in rows:
        print(f"{r[0]:62s} {r[1]:>6s} MiB  best {r[2]:>6s} s  median {r[3]:>6s} s  cpu {r[4]:>6s} s  {r[5]}")
    print(when)
    if args.write:
        lines = [
            f"`python bench/bench_landxml.py --curves {args.curves} --repeat {args.repeat} --write`, {when}.",
            "",
            "| " + " | ".join(columns) + " |",
            "| " + " | ".join("---" for _ in columns) + " |",
            *("| " + " | ".join(r) + " |" for r in rows),
        ]
        write_block(DOCS, BEGIN, END, "\n".join(lines))


if __name__ == "__main__":
    main()

"""Reading a large LandXML alignment (app/formats/landxml.py + app/formats/road_file.py): the time to go from the
document's bytes to the curves' columns, for the shape of file the service always read (Curves only, metric) and
the same alignment with what a design package adds (lines between the curves, a profile of parabolic vertical
curves, a Superelevation element per curve and design cross sections). Prints figures only.

    python bench/bench_landxml.py [--curves 200000] [--repeat 3]
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from app.formats.alignment_io import read_landxml  # noqa: E402
from bench.bench_alignments import as_landxml, make_curves  # noqa: E402


def designed(curves: list[dict], *, profile: bool, superelevation: bool, sections: bool) -> str:
    """The curves as a design package writes them: a 50 m line before each and every element's staStart; with
    ``profile`` a ProfAlign with a PVI every 500 m (150 m parabolas), with ``superelevation`` a Superelevation
    element per curve, with ``sections`` a design cross section every 50 m (two per curve: a crowned road)."""
    items, supers, sta = [], [], 0.0
    for c in curves:
        items.append(f'<Line length="50" staStart="{sta}"/>')
        sta += 50
        items.append(f'<Curve rot="cw" radius="{c["radius_m"]}" length="50" staStart="{sta}" name="{c["id"]}"/>')
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
    sects = "".join(
        f'<CrossSect sta="{s}"><DesignCrossSectSurf><CrossSectPnt>-3.5 99.93</CrossSectPnt>'
        f"<CrossSectPnt>0 100</CrossSectPnt><CrossSectPnt>3.5 99.93</CrossSectPnt></DesignCrossSectSurf></CrossSect>"
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


def timed(doc: bytes, repeat: int) -> tuple[float, float]:
    samples = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        read_landxml(doc, superelevation_percent=6.0, max_curves=10**7)
        samples.append(time.perf_counter() - t0)
    return statistics.median(samples), min(samples)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--curves", type=int, default=200_000)
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    curves = make_curves(args.curves)
    base = None
    for name, doc in (
        ("Curves only (the shape read before issue 39)", as_landxml(curves)),
        ("lines and curves, every staStart", designed(curves, profile=False, superelevation=False, sections=False)),
        ("  + a profile", designed(curves, profile=True, superelevation=False, sections=False)),
        ("  + a profile and cross sections", designed(curves, profile=True, superelevation=False, sections=True)),
        (
            "  + a profile, Superelevation, cross sections",
            designed(curves, profile=True, superelevation=True, sections=True),
        ),
    ):
        data = doc.encode()
        median, best = timed(data, args.repeat)
        base = best if name.startswith("lines") else base
        more = f"  {100 * (best / base - 1):+.0f} %" if base and name.startswith("  ") else ""
        print(f"{name:48s} {len(data) / 2**20:7.1f} MiB  median {median:6.2f} s  best {best:6.2f} s{more}")


if __name__ == "__main__":
    main()

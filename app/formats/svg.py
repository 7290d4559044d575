"""A small, dependency-free SVG line-chart renderer for the plot endpoints.

Charts carry what a designer needs to read them without the thesis at hand: a title, labelled axes with
units, ticks at round values, a legend, optional vertical markers (e.g. SRT_ts and SRT_3D) and a caption in
the thesis's notation. Every series is a ``<g class="series" data-name="...">`` holding one ``<polyline>``
(a ``<path>`` for a series with gaps) with ``data-x``/``data-y`` attributes listing the plotted values, so tests
and scripts can read the data back from the document.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from xml.sax.saxutils import escape, quoteattr

PALETTE = ("#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#17becf", "#7f7f7f")
DASHES = ("", "6 4", "2 3", "8 3 2 3")


@dataclass(frozen=True)
class Series:
    name: str
    x: Sequence[float]
    y: Sequence[float]
    dashed: bool = False
    gaps: bool = False  # a non-finite y breaks the line (drawn as a <path>); else such points are left out


@dataclass(frozen=True)
class Marker:
    """A vertical line at ``x`` with a label (e.g. the SRT of a stage)."""

    x: float
    label: str


@dataclass(frozen=True)
class Panel:
    y_label: str
    series: Sequence[Series]
    markers: Sequence[Marker] = field(default_factory=tuple)


def nice_ticks(lo: float, hi: float, target: int = 6) -> list[float]:
    """Round tick values covering [lo, hi] (1, 2, 2.5 or 5 times a power of ten apart)."""
    if not (math.isfinite(lo) and math.isfinite(hi)):
        raise ValueError("axis limits must be finite")
    if hi - lo <= 1e-9 * max(1.0, abs(lo), abs(hi)):
        # a flat (or round-off flat) series: centre it in a range the ticks (rounded to 1e-10) can resolve
        mid = 0.5 * (lo + hi)
        half = max(0.05 * abs(mid), 0.5)
        lo, hi = mid - half, mid + half
    raw = (hi - lo) / max(target - 1, 1)
    mag = 10 ** math.floor(math.log10(raw))
    step = next(m * mag for m in (1, 2, 2.5, 5, 10) if m * mag >= raw)
    first = math.floor(lo / step + 1e-9) * step
    ticks = []
    v = first
    while v <= hi + step * 1e-9:
        ticks.append(round(v, 10))
        v += step
    if ticks[-1] < hi - 1e-12:
        ticks.append(round(v, 10))
    return ticks


def _fmt(v: float) -> str:
    if v == 0:
        return "0"
    a = abs(v)
    if 1000 <= a < 1e7 and v == round(v):
        return f"{v:.0f}"  # 1000, 2500: not 1e+03
    if a >= 1000 or a < 0.01:
        return f"{v:.3g}"
    return f"{v:.3f}".rstrip("0").rstrip(".")


def line_chart(
    title: str,
    x_label: str,
    panels: Sequence[Panel],
    caption: str = "",
    width: int = 760,
    panel_height: int = 320,
) -> str:
    """Render one or more stacked panels sharing the x axis; returns the SVG document as text."""
    if not panels or not any(s.x for p in panels for s in p.series):
        raise ValueError("nothing to plot")
    left, right, top_pad, bottom_pad, gap = 78, 190, 46, 58, 36
    caption_lines = _wrap(caption, 110) if caption else []
    height = top_pad + len(panels) * panel_height + (len(panels) - 1) * gap + bottom_pad + 16 * len(caption_lines)
    xs = [v for p in panels for s in p.series for v in s.x] + [m.x for p in panels for m in p.markers]
    x_ticks = nice_ticks(min(xs), max(xs))
    x0, x1 = x_ticks[0], x_ticks[-1]
    plot_w = width - left - right
    out = [
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
        f'viewBox="0 0 {width} {height}" font-family="Helvetica, Arial, sans-serif" font-size="12">',
        f"<title>{escape(title)}</title>",
        f'<rect width="{width}" height="{height}" fill="white"/>',
        f'<text x="{width / 2:.1f}" y="24" text-anchor="middle" font-size="15" font-weight="bold">'
        f"{escape(title)}</text>",
    ]
    color = 0
    for k, panel in enumerate(panels):
        py0 = top_pad + k * (panel_height + gap)
        ys = [v for s in panel.series for v in s.y if math.isfinite(v)]
        y_ticks = nice_ticks(min(ys), max(ys))
        ylo, yhi = y_ticks[0], y_ticks[-1]

        def sx(v, x0=x0, x1=x1):
            return left + (v - x0) / (x1 - x0) * plot_w

        def sy(v, ylo=ylo, yhi=yhi, py0=py0):
            return py0 + panel_height - (v - ylo) / (yhi - ylo) * panel_height

        out.append(f'<g class="panel" data-index="{k}">')
        out.append(f'<rect x="{left}" y="{py0}" width="{plot_w}" height="{panel_height}" fill="none" stroke="#333"/>')
        for t in y_ticks:
            y = sy(t)
            out.append(f'<line x1="{left}" x2="{left + plot_w}" y1="{y:.1f}" y2="{y:.1f}" stroke="#ddd"/>')
            out.append(f'<text x="{left - 6}" y="{y + 4:.1f}" text-anchor="end">{_fmt(t)}</text>')
        for t in x_ticks:
            x = sx(t)
            out.append(f'<line x1="{x:.1f}" x2="{x:.1f}" y1="{py0}" y2="{py0 + panel_height}" stroke="#eee"/>')
            if k == len(panels) - 1:
                out.append(f'<text x="{x:.1f}" y="{py0 + panel_height + 16}" text-anchor="middle">{_fmt(t)}</text>')
        cy = py0 + panel_height / 2
        out.append(
            f'<text class="y-label" x="18" y="{cy:.1f}" text-anchor="middle" '
            f'transform="rotate(-90 18 {cy:.1f})">{escape(panel.y_label)}</text>'
        )
        for i, m in enumerate(panel.markers):
            x = sx(m.x)
            # labels one under the other (close markers would overprint), and left of a line near the right edge
            ty = py0 + 14 + 14 * i
            right = x > left + 0.7 * plot_w
            label_x, anchor = (x - 3, ' text-anchor="end"') if right else (x + 3, "")
            out.append(
                f'<g class="marker" data-x="{m.x:.6g}"><line x1="{x:.1f}" x2="{x:.1f}" y1="{py0}" '
                f'y2="{py0 + panel_height}" stroke="#555" stroke-dasharray="3 3"/>'
                f'<text x="{label_x:.1f}" y="{ty}" font-size="11"{anchor} paint-order="stroke" stroke="white" '
                f'stroke-width="3">{escape(m.label)}</text></g>'
            )
        legend_y = py0 + 8
        for j, s in enumerate(panel.series):
            c = PALETTE[color % len(PALETTE)]
            dash = DASHES[(j // len(PALETTE)) % len(DASHES)] if not s.dashed else "6 4"
            color += 1
            data_x = " ".join(f"{a:.6g}" for a in s.x)
            data_y = " ".join(f"{b:.6g}" for b in s.y)
            dash_attr = f' stroke-dasharray="{dash}"' if dash else ""
            if s.gaps:  # a path whose pieces a non-finite value separates (each curve's speed on its own span)
                pieces, pen = [], "M"
                for a, b in zip(s.x, s.y, strict=True):
                    if math.isfinite(b):
                        pieces.append(f"{pen}{sx(a):.2f},{sy(b):.2f}")
                        pen = "L"
                    else:
                        pen = "M"
                shape = f'<path fill="none" stroke="{c}" stroke-width="2"{dash_attr} d="{" ".join(pieces)}" '
            else:
                pts = " ".join(f"{sx(a):.2f},{sy(b):.2f}" for a, b in zip(s.x, s.y, strict=True) if math.isfinite(b))
                shape = f'<polyline fill="none" stroke="{c}" stroke-width="2"{dash_attr} points="{pts}" '
            out.append(
                f'<g class="series" data-name={quoteattr(s.name)}>'
                f"<title>{escape(s.name)}</title>"
                f'{shape}data-x="{data_x}" data-y="{data_y}"/></g>'
            )
            ly = legend_y + 18 * j
            lx = left + plot_w + 14
            out.append(
                f'<g class="legend-item"><line x1="{lx}" x2="{lx + 24}" y1="{ly:.1f}" y2="{ly:.1f}" '
                f'stroke="{c}" stroke-width="2"{dash_attr}/>'
                f'<text x="{lx + 30}" y="{ly + 4:.1f}">{escape(s.name)}</text></g>'
            )
        out.append("</g>")
    base = top_pad + len(panels) * panel_height + (len(panels) - 1) * gap
    out.append(
        f'<text class="x-label" x="{left + plot_w / 2:.1f}" y="{base + 38}" text-anchor="middle">'
        f"{escape(x_label)}</text>"
    )
    for i, line in enumerate(caption_lines):
        out.append(
            f'<text class="caption" x="{left}" y="{base + 58 + 16 * i}" font-size="11" fill="#333">'
            f"{escape(line)}</text>"
        )
    out.append("</svg>")
    return "\n".join(out)


def _wrap(text: str, width: int) -> list[str]:
    words, lines, cur = text.split(), [], ""
    for w in words:
        if len(cur) + len(w) + 1 > width and cur:
            lines.append(cur)
            cur = w
        else:
            cur = f"{cur} {w}".strip()
    if cur:
        lines.append(cur)
    return lines

"""Road-design and compliance tools built on the SRT (the thesis's Ch. 9.6 and 11 proposals).

* **Targets**: whether an SRT meets configurable minimums (defaults: 0.35 g general freight, 0.40 g
  dangerous goods, as in Australia's Performance-Based Standards and New Zealand's SRT rule) and by how
  much; the tilt-table angle ``atan(SRT)`` a tilt test would show.
* **Inverse limits**: for a target SRT, the largest CG height above the chassis, overweight or outward
  lateral offset d1 -- or the smallest spring separation -- at which the vehicle still meets it, found
  exactly by Brent's bracketed root finder on the engine; and the table of that limit over a range of
  overweights (the exact counterpart of the TERNZ calculator's table of acceptable mass/load-height pairs).
* **Curve assessment**: for each horizontal curve (radius, superelevation, grade), the SRT on that bank
  and grade, the rollover speed (Eq. 9.1), the side-friction speed sqrt(127 R (0.01 e + f)) with f from
  Table 21, the governing safe speed and the margin against the posted speed. The SRT does not depend on
  the radius, so curves sharing bank and grade share one solve (all distinct pairs in one batched solve).

References
----------
Thesis Eqs. 9.1-9.3, Table 21; NTC Australia (2008) PBS scheme; NZTA (2008) SRT calculator (TERNZ).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from engine.domain import check

DEFAULT_TARGETS = {"general": 0.35, "dangerous_goods": 0.40}


# ------------------------------------------------------------------------------------- targets


@dataclass(frozen=True)
class TargetCheck:
    name: str
    target_g: float
    meets: bool
    margin_g: float  # srt - target


def check_targets(srt_g: float, targets: dict[str, float] | None = None) -> list[TargetCheck]:
    """Whether ``srt_g`` meets each target (SRT >= target) and the margin SRT - target [g]."""
    targets = DEFAULT_TARGETS if targets is None else targets
    out = []
    for name, t in targets.items():
        check("target_srt_g", t, f"targets.{name}")
        out.append(TargetCheck(name, float(t), srt_g >= t, srt_g - t))
    return out


def tilt_table_angle_deg(srt_g):
    """Tilt-table angle equivalent to an SRT: a rigid vehicle tips at tan(angle) = SRT [deg]."""
    return np.degrees(np.arctan(srt_g))

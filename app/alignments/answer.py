"""An assessed alignment as the renderers take it (:mod:`app.alignments.rows`): each vehicle's rows as arrays, what the
rows of one SRT share kept once per distinct SRT. Built by :mod:`app.alignments.service` for the synchronous answer
and by a job's part from its stored columns (:mod:`app.jobs.op_alignments`), the same way; kept apart from both so
that the renderer and the service do not import each other.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import Any

import numpy as np

from app.alignments.advice import VehicleAdvice
from app.compute.resolved import ResolvedAssessment
from app.formats.alignment_io import CurveTable
from app.srt.service import target_checks_many
from engine.road import AlignmentColumns, tilt_table_angle_deg


@dataclass(frozen=True)
class VehicleAnswer:
    """One vehicle's rows as arrays; what is shared by the curves of one SRT is kept once per distinct SRT."""

    index: int
    preset: str | None
    saved_id: str | None
    columns: AlignmentColumns
    pair_of_row: np.ndarray  # distinct-SRT index of each row, for the shared tilt angle and target checks
    srts: np.ndarray  # the distinct SRTs [g]; -1 for the rows without one
    tilt_deg: np.ndarray  # per distinct SRT [deg]; nan without an SRT
    targets: dict[str, float]
    advice: VehicleAdvice  # the advisory speed, treatment and speed profile of each row
    level_srt: float = math.nan  # the vehicle's level-road SRT (bank and grade zero) [g]; nan when refused
    warnings: tuple[dict[str, Any], ...] = ()  # a typed record's inputs that read plausibly in another unit too

    @cached_property
    def tilt(self) -> list[float | None]:  # per distinct SRT
        return [None if math.isnan(a) else a for a in self.tilt_deg.tolist()]

    @cached_property
    def level(self) -> float | None:
        return None if math.isnan(self.level_srt) else self.level_srt

    @cached_property
    def level_checks(self) -> list[dict[str, Any]]:  # the target checks of every row with an SRT ([] without a level)
        if math.isnan(self.level_srt):
            return []
        return target_checks_many(np.array([self.level_srt]), self.targets)[0]

    @cached_property
    def checks(self) -> list[list[dict[str, Any]]]:  # per distinct SRT: its rows' target checks (on the level SRT)
        return [self.level_checks if has_srt else [] for has_srt in (self.srts >= 0).tolist()]


@dataclass(frozen=True)
class AlignmentAnswer:
    """Every curve for every vehicle, as arrays: rendered to JSON or CSV in chunks."""

    resolved: ResolvedAssessment
    curves: CurveTable
    vehicles: list[VehicleAnswer]


def vehicle_answer(
    r: ResolvedAssessment, index: int, cols: AlignmentColumns, level: float, advice: VehicleAdvice
) -> VehicleAnswer:
    """Vehicle ``index``'s rows as the renderers take them, from its assessed columns, level-road SRT and advice
    (:mod:`app.alignments.advice`; a job's part builds it from its stored columns and its slice of the advice)."""
    srts, pair_of_row = np.unique(np.where(np.isnan(cols.srt_g), -1.0, cols.srt_g), return_inverse=True)
    # per distinct SRT (-1: none), on arrays: 100,000 distinct SRTs one by one took a second
    tilt = np.where(srts >= 0, tilt_table_angle_deg(srts), np.nan)
    preset, saved = r.presets[index], r.saved_ids[index]
    return VehicleAnswer(
        index,
        preset,
        saved,
        cols,
        pair_of_row.reshape(-1),
        srts,
        tilt,
        r.targets,
        advice,
        level,
        tuple(r.vehicle_warnings(index)),
    )

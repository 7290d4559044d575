"""The SRT models and the solves behind :func:`engine.rollover_threshold`.

- :mod:`~engine.models.registry`: one :class:`Model` entry per model (what it needs, takes and how it solves);
- :mod:`~engine.models.springs`: the force -> deformation laws of Table 2;
- :mod:`~engine.models.groups`: the axle-group sub-mechanisms (tyres, leaf springs, fifth wheel) of Ch. 4;
- :mod:`~engine.models.trailer2d`, :mod:`~engine.models.trailer3d` (+ its Davies reference path
  :mod:`~engine.models.trailer3d_davies`): the developed 2D (Ch. 5) and 3D (Ch. 6) models;
- :mod:`~engine.models.stepping`: the quasi-static load ramp to the limit;
- :mod:`~engine.models.classic`: the closed forms of Ch. 2;
- :mod:`~engine.models.threshold`: the entry points (one case, many cases, grids);
- :mod:`~engine.models.combination`: the whole-combination static roll model (every unit, group and coupling),
  its many-road batch :mod:`~engine.models.combination_batch`, the solve of its equations on their tree
  :mod:`~engine.models.roll_tree`, and :mod:`~engine.models.combination_reference`, the same equations solved as a
  general nonlinear equilibrium.

Exports (the face's ``__all__``, by concept; every other name is the package's own, importable by its
module path for the package and its tests):

From :mod:`~engine.models.combination`, the whole-combination static roll model: every unit, every axle group, every
coupling, solved step by step:

- ``solve_combination``: Every roll-coupled unit's SRT and state, the governing one, and LLTf/LLTr of the last unit

From :mod:`~engine.models.combination_reference`, the reference solution of the whole-combination roll model: the
equilibrium of every roll degree of freedom as a general nonlinear system, solved with scipy:

- ``reference_srt``: The largest ay of each roll-coupled unit, from the nonlinear equilibrium (see the module docstring)
  [g]

From :mod:`~engine.models.groups`, axle-group sub-mechanisms: tires (Sec. 4.1), leaf-spring suspension (Sec. 4.2), fifth
wheel (Sec. 4.3):

- ``group_statics``: All in-plane forces of a group whose top link carries force (fy, fz) at ``g.top`` and moment mx

From :mod:`~engine.models.registry`, the model registry: one entry per SRT model, used by every place that needs to know
the models:

- ``get_model``: The registered model with this id
- ``Model``: One SRT model (see the module docstring)
- ``MODELS``: every SRT model by id
- ``record_view``: The case as a record model sees it: a combination's last unit as its thesis record, whose front
  support (the towing unit's group under the fifth wheel) acts through LLTf/LLTr computed by the ...
- ``supported_models``: The ids of the models whose required fields the record has (a preset's model list)

From :mod:`~engine.models.stepping`, quasi-static load stepping to the rollover limit with the developed mechanisms (3D
of Ch. 6, 2D of Ch. 5):

- ``stage_model``: The 3D model of one stage of the case's vehicle (the case's own stage by default), calibrated

From :mod:`~engine.models.threshold`, the SRT entry points: one case (``rollover_threshold``), a list of cases and a
grid (``sweep``):

- ``BATCH_ROWS``: rows of one batch solve: larger batches are split into blocks of this many rows, in the rows' order
  (so the same request always gives the same bits)
- ``BlockMap``: how the blocks of a batch are run
- ``evaluate_arrays``: SRT [g] and roll [deg] of many cases of one vehicle, model and stage
- ``evaluate_cases``: SRT [g] and roll [deg] of a list of cases of one vehicle, model and stage (``evaluate_arrays``)
- ``map_blocks``: ``function`` of each block of ``rows`` consecutive positions of ``range(size)`` (the last one
  shorter), in order, run by ``block_map``; a single block is run in the caller
- ``MIN_ARRAY_CASES``: fewest 3D cases of one vehicle and stage that ``rollover_thresholds`` solves together on arrays:
  an array solve costs about as much as 15 one-case solves whatever its size up to a few hundred ...
- ``rollover_threshold``: Static rollover threshold of one case
- ``rollover_thresholds``: ``rollover_threshold`` of each case with the default options (no curves, the reduced statics,
  the default chassis closure): in each case's place its result, or the error it raises
- ``sweep``: SRT over the Cartesian product of ``grid`` (axes of ``SWEEP_AXES``) around ``case``, e.g
- ``SWEEP_AXES``: grid axes accepted by ``sweep``, with the part of the case each one sets
- ``SweepResult``: A grid of cases
"""

from .combination import (
    solve_combination,
)
from .combination_reference import (
    reference_srt,
)
from .groups import (
    group_statics,
)
from .registry import (
    MODELS,
    Model,
    get_model,
    record_view,
    supported_models,
)
from .stepping import (
    stage_model,
)
from .threshold import (
    BATCH_ROWS,
    MIN_ARRAY_CASES,
    SWEEP_AXES,
    BlockMap,
    SweepResult,
    evaluate_arrays,
    evaluate_cases,
    map_blocks,
    rollover_threshold,
    rollover_thresholds,
    sweep,
)

__all__ = [
    "BATCH_ROWS",
    "MIN_ARRAY_CASES",
    "MODELS",
    "SWEEP_AXES",
    "BlockMap",
    "Model",
    "SweepResult",
    "evaluate_arrays",
    "evaluate_cases",
    "get_model",
    "group_statics",
    "map_blocks",
    "record_view",
    "reference_srt",
    "rollover_threshold",
    "rollover_thresholds",
    "solve_combination",
    "stage_model",
    "supported_models",
    "sweep",
]

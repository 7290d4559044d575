"""The operations a job can run: adding one is one :class:`~app.jobs.base.Operation` entry here (its module
defines it; see :mod:`app.jobs.base` for what an operation says: parse, resolve, split, run a part, assemble).
"""

from __future__ import annotations

from app.jobs import op_alignments, op_routes, op_sweep
from app.jobs.base import Operation

OPERATIONS: dict[str, Operation] = {
    op.name: op for op in (op_alignments.OPERATION, op_routes.OPERATION, op_sweep.OPERATION)
}

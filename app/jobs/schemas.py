"""The jobs' request and status models: a submission (``operation`` and its ``request``, one variant per operation
of :data:`app.jobs.operations.OPERATIONS`) and a job's status with its progress."""

from __future__ import annotations

from typing import Annotated, Literal, Union

from pydantic import ConfigDict, Field, RootModel, create_model

from app.http.problems import Problem
from app.http.schemas import InputModel, OutputModel, describe
from app.jobs.operations import OPERATIONS


def _submission_model() -> type[RootModel]:
    variants = []
    for op in OPERATIONS.values():
        name = "".join(p.capitalize() for p in op.name.replace(".", "_").split("_")) + "Job"
        variants.append(
            create_model(
                name,
                __base__=InputModel,
                __doc__=op.description,
                operation=(Literal[op.name], Field(description=describe("The operation to run.", unit="-"))),
                request=(
                    op.request_model,
                    Field(description=describe("Its request, as the synchronous endpoint takes it.", unit="-")),
                ),
            )
        )
    union = Annotated[Union[tuple(variants)], Field(discriminator="operation")]  # noqa: UP007
    return create_model("JobSubmission", __base__=RootModel[union], __doc__="A job: `operation` and its `request`.")


JobSubmission = _submission_model()


class JobParts(OutputModel):
    total: int = Field(description=describe("Parts of the job (independent units a worker takes).", unit="-"))
    queued: int = Field(description=describe("Parts waiting for a worker.", unit="-"))
    running: int = Field(description=describe("Parts being computed.", unit="-"))
    done: int = Field(description=describe("Parts finished.", unit="-"))
    failed: int = Field(description=describe("Parts that failed.", unit="-"))


class JobStatus(OutputModel):
    """A job's status and progress."""

    model_config = ConfigDict(extra="forbid")

    id: str = Field(description=describe("The job's id: `job_` + 22 url-safe characters (128 random bits).", unit="-"))
    operation: str | None = Field(
        description=describe("The operation (null when the stored job cannot be read).", unit="-")
    )
    status: Literal["queued", "running", "done", "failed", "cancelled"] = Field(
        description=describe("Where the job is.", unit="-")
    )
    progress: float = Field(
        ge=0, le=1, description=describe("Work done / total work, updated while it runs.", unit="-")
    )
    unit: str | None = Field(
        description=describe("What `done` and `total` count: `rows` (alignments), `cases` (sweep).", unit="-")
    )
    done: int = Field(
        description=describe(
            "Units of work done (a lost worker's part counts again from 0).", unit="rows or cases (see `unit`)"
        )
    )
    total: int = Field(description=describe("Units of work of the job.", unit="rows or cases (see `unit`)"))
    parts: JobParts = Field(description=describe("The parts by status.", unit="-"))
    retries: int = Field(description=describe("Part runs started again after their worker was lost.", unit="-"))
    created_at: str | None = Field(description=describe("When the job was submitted (RFC 3339, UTC).", unit="-"))
    started_at: str | None = Field(description=describe("When its first part started (RFC 3339, UTC).", unit="-"))
    finished_at: str | None = Field(
        description=describe("When it became done, failed or cancelled (RFC 3339, UTC).", unit="-")
    )
    expires_at: str | None = Field(
        description=describe(
            "When a finished job and its result are deleted (ROLLOVER_JOBS_RESULT_TTL_S after it finished; RFC 3339, "
            "UTC).",
            unit="-",
        )
    )
    formats: list[str] = Field(
        description=describe("The result's formats: `json`, and `csv` when the operation offers it.", unit="-")
    )
    result: str | None = Field(description=describe("The result's path, when done.", unit="-"))
    error: Problem | None = Field(
        description=describe("Why it failed (a problem-details object), when failed.", unit="-")
    )

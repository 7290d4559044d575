"""A 1,000,000-curve ``alignments.assess`` job's submission in this process (``parse_submission``, the vehicle's
resolution and ``prepare``: the POST's work without HTTP and the job store), the same curves as CSV text and as JSON
objects, each through the columns reader (the default) and through the old reader (``orjson`` into a dict per curve,
``read_csv``), in the same run: the machine is shared and its speed varies between runs, so the figures read against
each other.

    python bench/bench_submission.py [--curves 1000000] [--repeat 3]

The curves are ``bench_jobs``' (:func:`bench.bench_jobs.curves_csv`: a fixed seed, one decimal); the JSON objects are
the same rows, ``orjson.dumps`` of ``{"id": ..., "radius_m": ..., ...}``. Prints the best of ``--repeat`` runs.
"""

from __future__ import annotations

import argparse
import sys
from contextlib import contextmanager
from pathlib import Path
from unittest import mock

import orjson

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from bench.bench_jobs import curves_csv, submission_in_process  # noqa: E402

KEYS = ("id", "radius_m", "superelevation_percent", "grade_percent", "posted_speed_kmh")


def bodies(n: int) -> dict[str, bytes]:
    """The job's body with the curves as CSV text and as JSON objects (the same values)."""
    text = curves_csv(n)
    rows = [line.split(",") for line in text.splitlines()[1:]]
    curves = [{"id": r[0], **{k: orjson.loads(v) for k, v in zip(KEYS[1:], r[1:], strict=True)}} for r in rows]
    head = {"operation": "alignments.assess"}
    return {
        "csv": orjson.dumps({**head, "request": {"vehicle": "table16-btrain", "csv": text}}),
        "json": orjson.dumps({**head, "request": {"vehicle": "table16-btrain", "curves": curves}}),
    }


@contextmanager
def old_readers():
    """The readers before the columns: the JSON curves through ``orjson`` and ``curves_from_json``, the CSV text
    through ``read_csv``."""
    with (
        mock.patch("app.jobs.op_alignments.read_json_curves", lambda *a, **k: None),
        mock.patch("app.jobs.op_alignments.read_csv_columns", lambda *a, **k: None),
    ):
        yield


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--curves", type=int, default=1_000_000)
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    for form, body in bodies(args.curves).items():
        submission_in_process(body)  # warm: imports, the vehicle's solves
        new = min(submission_in_process(body) for _ in range(args.repeat))
        with old_readers():
            old = min(submission_in_process(body) for _ in range(args.repeat))
        print(
            f"{args.curves:,} curves as {form.upper():4} ({len(body) / 2**20:6.1f} MiB): "
            f"old reader {old:5.2f} s, columns {new:5.2f} s ({old / new:.1f}x)"
        )


if __name__ == "__main__":
    main()

"""Every bench script runs (a smoke run: its smallest arguments) and exits 0, without writing any doc.

The bench scripts measure the speed figures quoted in docs/*.md; nothing else imports them, so a change of an app
or engine signature can break one unnoticed until the next time someone measures. The figures of these runs are
meaningless (tiny sizes, one repeat): only that each script still runs through is checked.

A script that needs an outside binary (wrk, redis-server) is skipped locally where it is missing and fails under CI,
like the server tests. A new script must be added to ``RUNS`` (the first test fails until it is).
"""

from __future__ import annotations

import hashlib
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

pytestmark = pytest.mark.slow

ROOT = Path(__file__).resolve().parents[2]
BENCH = ROOT / "bench"

#: script -> (smallest arguments it accepts, binaries it needs). None of these arguments writes a doc: the
#: scripts that can write one do it only with ``--write`` (bench_jobs: unless ``--no-docs``).
RUNS: dict[str, tuple[list[str], list[str]]] = {
    "bench_advice_rows.py": (["--curves", "2000", "--repeat", "1"], []),
    "bench_advisory.py": (["2000"], []),
    "bench_alignments.py": (["--curves", "2000", "--repeat", "1"], []),  # with its live uvicorn run
    "bench_api.py": (["--hits", "10", "--misses", "5"], []),
    "bench_builder.py": ([], []),  # about a second at its only size
    "bench_catalog.py": (["--n", "5"], []),
    "bench_combination.py": (["--quick"], []),
    "bench_dynamics.py": (["--repeat", "1"], []),
    "bench_engine.py": ([], []),  # a few seconds at its only size
    "bench_jobs.py": (["--curves", "2000", "--workers", "1", "--no-docs"], ["redis-server"]),
    "bench_landxml.py": (["--curves", "2000", "--repeat", "1"], []),
    "bench_render.py": (["--curves", "2000", "--repeat", "1"], []),
    "bench_routes.py": (["--km", "5", "--repeat", "1"], []),
    "bench_service.py": (["--quick"], ["wrk"]),  # the longest: 1-second wrk runs of every step, about a minute
    "bench_submission.py": (["--curves", "2000", "--repeat", "1"], []),
    "compare_published.py": ([], []),
    "route_accuracy.py": (["--quick", "--seeds", "1", "--tracks", "2"], []),
}


def written_files() -> dict[Path, str]:
    """What a bench can write: the docs and the stored route calibration."""
    paths = [*sorted((ROOT / "docs").glob("*.md")), BENCH / "route_calibration.json"]
    return {p: hashlib.sha256(p.read_bytes()).hexdigest() for p in paths if p.exists()}


def test_every_bench_script_has_a_smoke_run():
    assert sorted(p.name for p in BENCH.glob("*.py")) == sorted(RUNS)


@pytest.mark.parametrize("script", sorted(RUNS))
def test_bench_script_runs(script):
    args, binaries = RUNS[script]
    missing = [b for b in binaries if shutil.which(b) is None]
    if missing:
        if os.environ.get("CI"):
            pytest.fail(f"{script} needs {', '.join(missing)} (under CI every bench script must run)")
        pytest.skip(f"{script} needs {', '.join(missing)}")
    before = written_files()
    done = subprocess.run(
        [sys.executable, str(BENCH / script), *args], cwd=ROOT, capture_output=True, text=True, timeout=240
    )
    assert done.returncode == 0, f"{script} {' '.join(args)} exited {done.returncode}:\n{done.stderr[-3000:]}"
    assert done.stdout.strip(), f"{script} printed no figures"
    assert written_files() == before, f"{script} {' '.join(args)} changed a doc"

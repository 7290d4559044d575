"""The service runs OpenBLAS on one thread unless told otherwise (app/__init__.py; figures in docs/dynamics.md)."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

#: in a fresh interpreter: import the service the way uvicorn does, then ask OpenBLAS (numpy's bundled copy) how
#: many threads it runs
_PROBE = r"""
import ctypes, glob, os, sys
import app.main
import numpy
libs = glob.glob(os.path.join(os.path.dirname(numpy.__file__), os.pardir, "numpy.libs", "libscipy_openblas*"))
if not libs:
    print("no-bundled-openblas"); sys.exit(0)
dll = ctypes.CDLL(libs[0])
for name in ("scipy_openblas_get_num_threads64_", "scipy_openblas_get_num_threads", "openblas_get_num_threads"):
    if hasattr(dll, name):
        print(getattr(dll, name)()); sys.exit(0)
print("no-thread-query")
"""


def _threads(**env: str) -> str:
    environ = {k: v for k, v in os.environ.items() if k not in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS")}
    done = subprocess.run(
        [sys.executable, "-c", _PROBE], capture_output=True, text=True, env={**environ, **env}, timeout=120
    )
    assert done.returncode == 0, done.stderr[-2000:]
    out = done.stdout.strip()
    if out.startswith("no-"):
        pytest.skip(f"numpy here has no bundled OpenBLAS to ask ({out})")
    return out


@pytest.mark.slow
def test_the_service_runs_openblas_on_one_thread():
    assert _threads() == "1"


@pytest.mark.slow
def test_an_explicit_setting_is_kept():
    assert _threads(OPENBLAS_NUM_THREADS="2") == "2"

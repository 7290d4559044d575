#!/usr/bin/env bash
# Regenerate the lock files in requirements/ from pyproject.toml (run after adding, removing or bumping a
# dependency, and commit the result):
#   requirements/dev.txt      the project's dependencies + the test and dev extras (resolved first: the superset)
#   requirements/test.txt     dependencies + test extra (what CI installs: .ci/run)
#   requirements/runtime.txt  dependencies only (what the Docker image installs)
# The two smaller sets are resolved under the superset's pins, so a package has one version in all three files.
# Every line carries the sha256 of each file PyPI has for that version (pip then installs in --require-hashes mode),
# and the resolution is universal (markers for other platforms and Pythons >= 3.11), so the same files serve Linux
# CI, the Docker image and a developer's macOS or Windows machine.
#
#   scripts/lock.sh             keep the current pins where pyproject.toml still allows them (add what is new)
#   scripts/lock.sh --upgrade   move every package to the newest version pyproject.toml allows
set -euo pipefail
cd "$(dirname "$0")/.."

UV_VERSION=0.13.9  # the locking tool itself is pinned: the same version writes the same files
UV_VENV=.venv-lock
if [ ! -x "$UV_VENV/bin/uv" ] || [ "$("$UV_VENV/bin/uv" --version | cut -d' ' -f2)" != "$UV_VERSION" ]; then
    python3 -m venv "$UV_VENV"
    "$UV_VENV/bin/pip" install --quiet --disable-pip-version-check "uv==$UV_VERSION"
fi
UV="$UV_VENV/bin/uv"

# one index snapshot for the three files: nothing uploaded while this script runs can slip into one of them only
SNAPSHOT=$(date -u +%Y-%m-%dT%H:%M:%SZ)
COMMON=(--universal --python-version 3.11 --generate-hashes --index-url https://pypi.org/simple
        --exclude-newer "$SNAPSHOT" --custom-compile-command "scripts/lock.sh" --quiet "$@")

mkdir -p requirements
"$UV" pip compile pyproject.toml --extra test --extra dev "${COMMON[@]}" -o requirements/dev.txt
"$UV" pip compile pyproject.toml --extra test -c requirements/dev.txt "${COMMON[@]}" -o requirements/test.txt
"$UV" pip compile pyproject.toml -c requirements/dev.txt "${COMMON[@]}" -o requirements/runtime.txt
echo "requirements/{runtime,test,dev}.txt written: $(grep -c '==' requirements/runtime.txt) runtime packages," \
     "$(grep -c '==' requirements/test.txt) with the tests, $(grep -c '==' requirements/dev.txt) with the dev tools"

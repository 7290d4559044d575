#!/usr/bin/env bash
# Lint openapi/openapi.json with Redocly CLI (redocly.yaml) and Spectral (.spectral.yaml); exit non-zero on any
# error or warning. The tools are the versions locked in tools/openapi-lint/package-lock.json, installed there with
# `npm ci` when missing (CI: .ci/run; tests/api/test_openapi_lint.py runs this script).
set -euo pipefail
cd "$(dirname "$0")/.."
TOOLS=tools/openapi-lint
if [ ! -x "$TOOLS/node_modules/.bin/redocly" ] || [ ! -x "$TOOLS/node_modules/.bin/spectral" ]; then
    npm ci --prefix "$TOOLS" --no-audit --no-fund --ignore-scripts
fi
# no usage reports and no update checks: the linters run offline once installed
export REDOCLY_TELEMETRY=off REDOCLY_SUPPRESS_UPDATE_NOTICE=true SCARF_ANALYTICS=false
"$TOOLS/node_modules/.bin/redocly" lint openapi/openapi.json --config redocly.yaml --format=stylish
"$TOOLS/node_modules/.bin/spectral" lint openapi/openapi.json --ruleset .spectral.yaml --fail-severity=warn

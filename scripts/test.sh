#!/usr/bin/env bash
# Tests: sets everything up on a fresh machine, checks lint and formatting (ruff, LeRobot's rules),
# then runs the fast test suite on two workers with the 25 slowest tests listed. The slow ones:
# python -m pytest -m slow -n 0
set -euo pipefail
export ACTIVEARENA_TEST_BROWSER=1  # bootstrap installs headless Chromium for the report test
source "$(dirname "${BASH_SOURCE[0]}")/bootstrap.sh"
cd "$ROOT"
ruff check .
ruff format --check .
python -m pytest -q "$@"

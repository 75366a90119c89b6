#!/usr/bin/env bash
# Tests: sets everything up on a fresh machine, then runs the fast test suite (slow ones: -m slow).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/bootstrap.sh"
cd "$ROOT"
python -m pytest -q "$@"

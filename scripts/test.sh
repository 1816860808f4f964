#!/usr/bin/env bash
# The test suite: installs what it needs, then runs every test.
source "$(dirname "${BASH_SOURCE[0]}")/env.sh" test
.venv/bin/python -m pytest -q -n 2 "$@"

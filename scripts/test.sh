#!/usr/bin/env bash
# The test suite: installs what it needs, then runs every test.
source "$(dirname "${BASH_SOURCE[0]}")/env.sh" test
# Headless Chromium for the browser tests (Debian packages; installed only when missing).
# The browser tests are required unless ROCKING_REQUIRE_BROWSER=0 is set.
export ROCKING_REQUIRE_BROWSER="${ROCKING_REQUIRE_BROWSER:-1}"
bash scripts/browser-deps.sh
.venv/bin/python -m pytest -q -n 2 "$@"

#!/usr/bin/env bash
# Debian's Chromium and ChromeDriver for the browser tests (tests/test_browser.py), installed only
# if missing: quiet, idempotent, and 'apt-get update' only when apt does not know the packages yet
# or the first install attempt fails. Where they cannot be installed (no apt-get, not root) it says
# so and exits 0, and the browser tests skip; with ROCKING_REQUIRE_BROWSER set (CI) it exits 1.
set -euo pipefail

have() { command -v "$1" >/dev/null 2>&1; }

if have chromium && have chromedriver; then
  exit 0
fi

give_up() {
  echo "browser-deps: $1; the browser tests will be skipped" >&2
  if [ -n "${ROCKING_REQUIRE_BROWSER:-}" ] && [ "${ROCKING_REQUIRE_BROWSER}" != "0" ]; then
    exit 1
  fi
  exit 0
}

have apt-get || give_up "apt-get not found: install Chromium and ChromeDriver yourself"
SUDO=()
if [ "$(id -u)" -ne 0 ]; then
  if have sudo && sudo -n true 2>/dev/null; then
    SUDO=(sudo -n)
  else
    give_up "not root: run 'sudo apt-get install chromium chromium-driver'"
  fi
fi

export DEBIAN_FRONTEND=noninteractive
PACKAGES=(chromium chromium-driver)
install() { ${SUDO[@]+"${SUDO[@]}"} apt-get install -y -qq "${PACKAGES[@]}" >/dev/null 2>&1; }

# apt-cache policy prints "Candidate: (none)" for a package the lists do not offer (or no lists at all)
if apt-cache policy "${PACKAGES[@]}" 2>/dev/null | grep -q "Candidate: (none)" \
   || [ -z "$(apt-cache policy "${PACKAGES[@]}" 2>/dev/null)" ]; then
  ${SUDO[@]+"${SUDO[@]}"} apt-get update -qq >/dev/null 2>&1 || true
fi
if ! install; then
  ${SUDO[@]+"${SUDO[@]}"} apt-get update -qq >/dev/null 2>&1 || true
  install || give_up "apt-get install ${PACKAGES[*]} failed"
fi
have chromium && have chromedriver || give_up "chromium or chromedriver still not on PATH after the install"
echo "browser-deps: installed $(chromium --version 2>/dev/null | head -1)" >&2

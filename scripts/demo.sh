#!/usr/bin/env bash
# The main job: reproduce the paper's case studies (Tables 1-2, Figs. 9-12) and run a real record.
#
#   bash scripts/demo.sh [OUT]     OUT: output folder (default paper-out), relative to where you are
set -euo pipefail
case "${1:-}" in
  -h|--help) echo "usage: bash scripts/demo.sh [OUT]   (OUT: output folder, default paper-out)"; exit 0 ;;
  -*) echo "demo.sh: unknown option $1 (usage: bash scripts/demo.sh [OUT])" >&2; exit 2 ;;
esac
if [ "$#" -gt 1 ]; then
  echo "demo.sh: one output folder at most (usage: bash scripts/demo.sh [OUT])" >&2
  exit 2
fi
OUT="${1:-paper-out}"
# env.sh moves to the repository: resolve OUT against the caller's folder first
case "$OUT" in /*) ;; *) OUT="$PWD/$OUT" ;; esac
# "" = no optional extra; without an argument env.sh would see this script's own (OUT)
source "$(dirname "${BASH_SOURCE[0]}")/env.sh" ""
.venv/bin/rocking paper --out "$OUT"
.venv/bin/rocking run examples/statue_alone_record.toml --out "$OUT/record-run"
echo "Figures, tables and the record run are in $OUT/"

#!/usr/bin/env bash
# The main job: reproduce the paper's case studies (Tables 1-2, Figs. 9-12) and run a real record.
source "$(dirname "${BASH_SOURCE[0]}")/env.sh"
OUT="${1:-paper-out}"
.venv/bin/rocking paper --out "$OUT"
.venv/bin/rocking run examples/statue_alone_record.toml --out "$OUT/record-run"
echo "Figures, tables and the record run are in $OUT/"

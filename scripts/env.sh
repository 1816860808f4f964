# Shared by demo.sh and test.sh: create .venv beside the repository and install the package
# (with the optional dependency group named by the first argument, if any).
# Always source it with an argument ("" for none): `source env.sh` alone hands it the
# caller's own arguments, which are not extras.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
PY="${PYTHON:-python3}"
if [ ! -x .venv/bin/python ]; then
  "$PY" -m venv .venv
fi
.venv/bin/python -m pip install --quiet --upgrade pip >/dev/null 2>&1 || true
if [ -n "${1:-}" ]; then
  .venv/bin/python -m pip install --quiet -e ".[$1]"
else
  .venv/bin/python -m pip install --quiet -e .
fi
# Compile the solver and the stack engine now (once: numba keeps them on disk; about 40 s and 50 s
# of one core), so that the first command waits no more than any other. Prints what it does,
# or nothing when they are compiled already.
.venv/bin/python -c "from rocking.solver.warmup import main; raise SystemExit(main())"

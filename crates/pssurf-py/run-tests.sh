#!/usr/bin/env bash
# Builds the Python package from this clone (exactly as the README's `pip install` does) into
# a virtual environment outside the clone, and runs its pytest suite. The tests that compare
# with the command-line tool use the `pssurf` binary that `cargo test --workspace` built.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
venv="${PSSURF_VENV:-${XDG_CACHE_HOME:-$HOME/.cache}/pssurf/venv}"
python="${PYTHON:-python3}"

if [ ! -x "$venv/bin/python" ]; then
  "$python" -m venv "$venv"
fi
"$venv/bin/python" -m pip install -q --disable-pip-version-check "$here[test]"

target="${CARGO_TARGET_DIR:-$root/target}"
(cd "$root" && cargo build -q -p pssurf-cli)
export PSSURF_CLI="$target/debug/pssurf"
cd "$here"
"$venv/bin/python" -m pytest -q tests

#!/usr/bin/env bash
# Build the Python package `mdr_dem` and run its pytest suite.
#
# Creates (or reuses) a virtual environment, default ~/.cache/mdr-py-venv (override with
# MDR_PY_VENV), installs maturin, numpy and pytest from PyPI into it, builds the wheel from this
# crate and installs it, then runs tests/. The wheel is built with cargo's dev profile (its
# dependencies optimised, as the workspace's) in the workspace's target directory, so that it
# reuses the dependencies `cargo test --workspace` compiled; MDR_PY_PROFILE=release builds the
# optimised wheel that `pip install ./crates/mdr-py` gives. Extra arguments go to pytest.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
venv="${MDR_PY_VENV:-$HOME/.cache/mdr-py-venv}"
profile="${MDR_PY_PROFILE:-dev}"
start=$(date +%s)

if [ ! -x "$venv/bin/python" ]; then
  echo "== creating the virtual environment $venv"
  python3 -m venv "$venv"
fi
py="$venv/bin/python"
if ! "$py" -c "import maturin, numpy, pytest" >/dev/null 2>&1 \
   || ! [ -x "$venv/bin/maturin" ]; then
  echo "== installing maturin, numpy, pytest"
  "$py" -m pip install --quiet --disable-pip-version-check maturin numpy pytest
fi

echo "== building the wheel (cargo profile $profile)"
wheels="$(mktemp -d)"
trap 'rm -rf "$wheels"' EXIT
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$repo/target}"
(cd "$here" && "$venv/bin/maturin" build --quiet --locked --profile "$profile" --interpreter "$py" \
  --features demo-laws --out "$wheels")
"$py" -m pip install --quiet --disable-pip-version-check --no-deps --force-reinstall \
  "$wheels"/*.whl

echo "== pytest"
# From the tests' folder, so that the installed package is imported, not the source folder.
(cd "$here/tests" && "$py" -m pytest -q "$@")
echo "== crates/mdr-py/test.sh took $(( $(date +%s) - start )) s"

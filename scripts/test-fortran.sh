#!/usr/bin/env bash
# The Fortran bindings against an installed fc3d:
#
#   bash scripts/test-fortran.sh PREFIX        (PREFIX from scripts/install.sh --prefix PREFIX)
#
# Installs gfortran with apt-get when missing, copies the module (PREFIX/share/fc3d/fortran/fc3d.f90,
# or fortran/fc3d.f90 when the prefix has none) and fortran/example.f90 into a temporary directory,
# compiles them there (-std=f2018 -Wall -Werror -fcheck=all) against the native-only library found
# with pkg-config (shared, then static), and runs the example on shared Siconos problems
# (../shared/data/siconos, or $FC3D_DATA), and once under valgrind when it is installed.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$(pwd)
[ $# -eq 1 ] || { echo "usage: bash scripts/test-fortran.sh PREFIX" >&2; exit 2; }
PREFIX=$(cd "$1" && pwd)
DATA=${FC3D_DATA:-$ROOT/../shared/data/siconos}
[ -d "$DATA" ] || { echo "no shared problems at $DATA (set FC3D_DATA)" >&2; exit 1; }
DATA=$(cd "$DATA" && pwd)
PROBLEMS=(NESpheres_10_1 Rover1039 Confeti-ex13-Fc3D-SBM Capsules-i101-404)

packages=()
command -v gfortran >/dev/null || packages+=(gfortran)
command -v pkg-config >/dev/null || packages+=(pkg-config)
if [ ${#packages[@]} -gt 0 ]; then
  echo "== installing ${packages[*]}"
  SUDO=""; [ "$(id -u)" = 0 ] || SUDO=sudo
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${packages[@]}" >/dev/null
fi

export PKG_CONFIG_PATH=$PREFIX/lib/pkgconfig${PKG_CONFIG_PATH:+:$PKG_CONFIG_PATH}
export LD_LIBRARY_PATH=$PREFIX/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
pkg-config --exists fc3d-native || { echo "no fc3d-native.pc under $PREFIX/lib/pkgconfig" >&2; exit 1; }

WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
module=$PREFIX/share/fc3d/fortran/fc3d.f90
if [ -f "$module" ]; then
  cmp -s "$module" fortran/fc3d.f90 || echo "note: the installed fc3d.f90 differs from fortran/fc3d.f90"
else
  echo "note: $module is not installed; using fortran/fc3d.f90"
  module=fortran/fc3d.f90
fi
cp "$module" "$WORK/fc3d.f90"
cp fortran/example.f90 "$WORK/example.f90"
cd "$WORK"

FFLAGS=(-std=f2018 -Wall -Wextra -Wno-compare-reals -Werror -pedantic -fcheck=all -g -O2)
echo "== gfortran $(gfortran -dumpfullversion): module fc3d and the example, outside the source tree"
gfortran "${FFLAGS[@]}" -c fc3d.f90
gfortran "${FFLAGS[@]}" example.f90 fc3d.o $(pkg-config --libs fc3d-native) -o example
# The static library: the system libraries Rust's runtime needs come from Libs.private.
gfortran "${FFLAGS[@]}" example.f90 fc3d.o "$PREFIX/lib/libfc3d_native.a" \
  $(pkg-config --static --libs-only-l fc3d-native | sed 's/-lfc3d_native//') -o example_static

paths=()
for p in "${PROBLEMS[@]}"; do
  [ -f "$DATA/$p.dat" ] || { echo "missing shared problem $DATA/$p.dat" >&2; exit 1; }
  paths+=("$DATA/$p.dat")
done
echo "== example (shared library) on ${PROBLEMS[*]}"
./example "${paths[@]}"
echo "== example (static library) on ${PROBLEMS[0]}"
./example_static "${paths[0]}" | tail -1
if command -v valgrind >/dev/null; then
  echo "== example under valgrind"
  valgrind --quiet --error-exitcode=1 --leak-check=full --errors-for-leak-kinds=definite \
    ./example "${paths[0]}" | tail -1
fi
echo "== Fortran bindings: all checks passed"

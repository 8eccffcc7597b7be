#!/usr/bin/env bash
# The whole test suite, set-up included (README's test command; .ci/run calls it).
#  1. cargo test --workspace: Rust unit/integration tests and the C checks of capi-tests
#     (compiled with the cc crate against capi/include/), including all shared Siconos problems.
#  2. The C example built with plain cc against the compat headers and libfc3d, and run.
#  3. The C checks linked against libfc3d.so and run under valgrind (ownership, bad input).
#  4. Siconos compatibility: struct layouts and enum values compared with the installed Siconos
#     4.4 headers, and one unmodified Siconos host program built against both libraries, whose
#     results must agree.
set -euo pipefail
cd "$(dirname "$0")/.."
DATA=../shared/data/siconos

packages=()
command -v cc >/dev/null || packages+=(gcc libc6-dev)
command -v valgrind >/dev/null || packages+=(valgrind)
[ -f /usr/include/siconos/numerics/FrictionContactProblem.h ] || packages+=(libsiconos-numerics-dev)
command -v pkg-config >/dev/null || packages+=(pkg-config)
[ -f /usr/include/hdf5/serial/hdf5.h ] || packages+=(libhdf5-dev)
if [ ${#packages[@]} -gt 0 ]; then
  echo "== installing ${packages[*]}"
  SUDO=""; [ "$(id -u)" = 0 ] || SUDO=sudo
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${packages[@]}" >/dev/null
fi

echo "== cargo test --workspace --features fc3d-core/fclib"
cargo test --workspace --features fc3d-core/fclib
echo "== cargo test --test fclib (without the fclib feature: .hdf5 refused with a clear error)"
cargo test -p fc3d-core --test fclib

echo "== release library"
cargo build --release -p fc3d
LIB=target/release
BUILD=$(mktemp -d)
trap 'rm -rf "$BUILD"' EXIT
CFLAGS=(-std=c99 -Wall -Wextra -Werror -O2)

echo "== examples-c"
cc "${CFLAGS[@]}" -Icapi/include/siconos-compat examples-c/stack.c -L$LIB -lfc3d -lm -o "$BUILD/stack"
LD_LIBRARY_PATH=$LIB "$BUILD/stack"

echo "== C checks under valgrind"
cc "${CFLAGS[@]}" -Icapi/include/siconos-compat capi-tests/c/ownership_main.c capi-tests/c/capi_checks.c \
  capi-tests/c/nsgs_options.c \
  -L$LIB -lfc3d -lm -o "$BUILD/capi_checks"
LD_LIBRARY_PATH=$LIB valgrind --quiet --error-exitcode=1 --leak-check=full --errors-for-leak-kinds=definite \
  "$BUILD/capi_checks" "$DATA" "$BUILD"

echo "== Siconos 4.4 compatibility"
cc -Icapi/include/siconos-compat capi-tests/c/layout.c -o "$BUILD/layout_fc3d"
cc -I/usr/include/siconos/numerics -I/usr/include/siconos capi-tests/c/layout.c -o "$BUILD/layout_siconos"
diff <("$BUILD/layout_fc3d") <("$BUILD/layout_siconos")
echo "struct layouts and enum values identical ($("$BUILD/layout_fc3d" | wc -l) checks)"
cc -O2 -Icapi/include/siconos-compat examples-c/siconos_host.c -L$LIB -lfc3d -lm -o "$BUILD/host_fc3d"
cc -O2 -I/usr/include/siconos/numerics -I/usr/include/siconos examples-c/siconos_host.c -lsiconos_numerics -lm \
  -o "$BUILD/host_siconos"
agree=0
for p in Rover1039 Rover4396 Confeti-ex13-Fc3D-SBM Confeti-ex03-Fc3D-SBM OneObject-i1028-138.hdf5 NESpheres_10_1; do
  ours=$(LD_LIBRARY_PATH=$LIB "$BUILD/host_fc3d" "$DATA/$p.dat" 1e-8 10000)
  theirs=$("$BUILD/host_siconos" "$DATA/$p.dat" 1e-8 10000)
  # Same converged flag and iteration count; errors may differ in the last digits.
  if [ "$(echo "$ours" | cut -d' ' -f1-4)" != "$(echo "$theirs" | cut -d' ' -f1-4)" ]; then
    echo "disagreement on $p: fc3d [$ours] siconos [$theirs]"; exit 1
  fi
  echo "$p: fc3d [$ours] siconos [$theirs]"
  agree=$((agree + 1))
done
echo "Siconos host program: $agree problems, same info and iterations with both libraries"

echo "== side by side with Siconos (compare-siconos.sh --quick: same info, iterations, cross-scored errors)"
bash scripts/compare-siconos.sh --quick
echo "== all checks passed"

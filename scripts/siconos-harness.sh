# Sourced by scripts/compare-siconos.sh and scripts/compare-siconos-budget.sh (from the
# repository root): installs a C compiler and Siconos when missing, builds libfc3d and the report
# program named by $1 (a binary of fc3d-cli), and compiles bench/siconos_compare.c twice, against
# fc3d's compat headers and against the installed Siconos, into $BUILD/fc3d and $BUILD/siconos
# ($BUILD: a temporary directory removed on exit; the report is $BUILD/$1).
report=$1
packages=()
command -v cc >/dev/null || packages+=(gcc libc6-dev)
[ -f /usr/include/siconos/numerics/FrictionContactProblem.h ] || packages+=(libsiconos-numerics-dev)
if [ ${#packages[@]} -gt 0 ]; then
  echo "== installing ${packages[*]}"
  SUDO=""; [ "$(id -u)" = 0 ] || SUDO=sudo
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${packages[@]}" >/dev/null
fi

echo "== building libfc3d, $report and the two benchmark binaries"
cargo build --release -p fc3d
cargo build --release -p fc3d-cli --bin "$report"
BUILD=$(mktemp -d)
trap 'rm -rf "$BUILD"' EXIT
trap 'exit 130' INT TERM
# A private copy of libfc3d.so: a rebuild of target/release during a long run must not change
# the library under test halfway. FC3D_COMPARE_LIB names another build to test (an earlier
# commit's libfc3d.so, for a before/after comparison).
cp "${FC3D_COMPARE_LIB:-target/release/libfc3d.so}" "$BUILD/libfc3d.so.0"
ln -s libfc3d.so.0 "$BUILD/libfc3d.so"
cp "target/release/$report" "$BUILD/"
CFLAGS=(-std=c99 -O2 -Wall -Wextra -Werror)
cc "${CFLAGS[@]}" -Icapi/include/siconos-compat -Icapi/include bench/siconos_compare.c -L"$BUILD" -lfc3d -lm -o "$BUILD/fc3d"
cc "${CFLAGS[@]}" -I/usr/include/siconos/numerics -I/usr/include/siconos bench/siconos_compare.c \
  -lsiconos_numerics -lm -o "$BUILD/siconos"
# Both libraries single-threaded (fc3d is; Siconos' OpenBLAS would otherwise start a thread pool).
export LD_LIBRARY_PATH="$BUILD${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1

#!/usr/bin/env bash
# The whole test suite, set-up included (the README's full tier, docs/testing.md; .ci/run calls it).
#  1. cargo test --workspace: Rust unit/integration tests and the C checks of capi-tests
#     (compiled with the cc crate against capi/include/), including all shared Siconos problems.
#  2. scripts/install.sh into a temporary prefix, then hosts built from outside the source tree
#     against what was installed: a C host with pkg-config (shared and static library, and the
#     native-only library), a C host of the distributed solve (libfc3d_mpi) with mpicc and
#     pkg-config fc3d-mpi and with CMake's fc3d::mpi under mpirun, the Siconos-style hosts with
#     only the include path and the link flag changed, a C++ host with CMake's
#     find_package(fc3d), one program linking Siconos and fc3d's native library side by side, the
#     Fortran module and the Python package; the README's quickstarts and in-tree example as
#     written (scripts/test-readme.sh).
#  3. The C checks linked against the installed libfc3d.so and run under valgrind.
#  4. Siconos compatibility: struct layouts and enum values compared with the installed Siconos
#     4.4 headers, one unmodified Siconos host program built against both libraries, whose
#     results must agree, and the side-by-side agreement check of scripts/compare-siconos.sh.
#  5. Siconos 4.4.0's own friction tests (scripts/siconos-suite.sh), unmodified, built against the
#     installed compat headers and libfc3d and against the installed Siconos, case by case.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$(pwd)
DATA=$ROOT/../shared/data/siconos

packages=()
command -v cc >/dev/null || packages+=(gcc libc6-dev)
command -v c++ >/dev/null || packages+=(g++)
command -v cmake >/dev/null || packages+=(cmake)
command -v gfortran >/dev/null || packages+=(gfortran)
python3 -c 'import ensurepip' 2>/dev/null || packages+=(python3-venv)
command -v valgrind >/dev/null || packages+=(valgrind)
[ -f /usr/include/siconos/numerics/FrictionContactProblem.h ] || packages+=(libsiconos-numerics-dev)
command -v pkg-config >/dev/null || packages+=(pkg-config)
command -v ctags >/dev/null || packages+=(universal-ctags)
command -v xz >/dev/null || packages+=(xz-utils)
[ -f /usr/include/hdf5/serial/hdf5.h ] || packages+=(libhdf5-dev)
# fc3d-mpi (libfc3d_mpi) and its tests under mpirun.
command -v mpicc >/dev/null && command -v mpirun >/dev/null || packages+=(openmpi-bin libopenmpi-dev)
if [ ${#packages[@]} -gt 0 ]; then
  echo "== installing ${packages[*]}"
  SUDO=""; [ "$(id -u)" = 0 ] || SUDO=sudo
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${packages[@]}" >/dev/null
fi

echo "== cargo test --workspace --features fc3d-core/fclib"
# capi-tests' siconos_surface compares the constants and solver_options_create with the
# installed Siconos: here a missing prerequisite is a failure, not a skip.
export FC3D_REQUIRE_SICONOS=1
# fc3d-mpi builds empty without MPI and its mpirun tests skip: here both are failures.
export FC3D_REQUIRE_MPI=1
# Open MPI runs as root (CI machines) only when told.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
cargo test --workspace --features fc3d-core/fclib
echo "== FCLIB tests without the fclib feature (.hdf5 refused with a clear error by the core, the C ABI and fc3d convert)"
cargo test -p fc3d-core -p fc3d -p fc3d-cli --test fclib --test convert

echo "== allocation tests under an address-space limit (ulimit -v 1 GiB)"
bash scripts/test-memory-limit.sh

WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
PREFIX=$WORK/prefix
echo "== scripts/install.sh --prefix $PREFIX"
bash scripts/install.sh --prefix "$PREFIX"
export PKG_CONFIG_PATH=$PREFIX/lib/pkgconfig LD_LIBRARY_PATH=$PREFIX/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
SICONOS_INC=$(pkg-config --variable=siconos_includedir fc3d)
readelf -d "$PREFIX/lib/libfc3d.so" | grep -q 'SONAME.*libfc3d.so.0' || { echo "no SONAME"; exit 1; }

# Hosts are built from a copy outside the source tree: only the installed files are visible.
HOSTS=$WORK/hosts
mkdir -p "$HOSTS"
cp examples-c/*.c capi-tests/c/*.c "$HOSTS/"
cp -r examples-cmake "$HOSTS/cmake"
cd "$HOSTS"
CFLAGS=(-std=c99 -Wall -Wextra -Werror -O2)

echo "== C host with pkg-config (shared, static, native-only)"
cc "${CFLAGS[@]}" $(pkg-config --cflags fc3d) native_host.c $(pkg-config --libs fc3d) -lm -o native_host
./native_host "$DATA/Confeti-ex13-Fc3D-SBM.dat"
cc "${CFLAGS[@]}" $(pkg-config --cflags fc3d) native_host.c "$PREFIX/lib/libfc3d.a" \
  $(pkg-config --static --libs-only-l fc3d | sed 's/-lfc3d//') -o native_host_static
./native_host_static
cc "${CFLAGS[@]}" -DFC3D_NATIVE_ONLY $(pkg-config --cflags fc3d-native) native_host.c \
  $(pkg-config --libs fc3d-native) -lm -o native_only
./native_only "$DATA/NESpheres_10_1.dat"
if nm -D --defined-only "$PREFIX/lib/libfc3d_native.so" | grep -E ' (fc3d_driver|solver_options_create|NM_create|frictionContact_new_from_filename)$'; then
  echo "libfc3d_native exports Siconos names"; exit 1
fi

echo "== Siconos-style hosts (include path and link flag changed only)"
cc "${CFLAGS[@]}" -I"$SICONOS_INC" $(pkg-config --cflags fc3d) stack.c $(pkg-config --libs fc3d) -lm -o stack
./stack

echo "== C++ host with CMake find_package(fc3d)"
cmake -S cmake -B cmake-build -DCMAKE_PREFIX_PATH="$PREFIX" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build cmake-build >/dev/null
./cmake-build/host && ./cmake-build/host_static && ./cmake-build/siconos_style

echo "== C host of the distributed solve: mpicc + pkg-config fc3d-mpi, CMake fc3d::mpi; mpirun -np 1..4"
cp -r "$ROOT/examples-mpi" mpi
test -f "$PREFIX/include/fc3d_mpi.h" || { echo "scripts/install.sh did not install libfc3d_mpi"; exit 1; }
mpicc "${CFLAGS[@]}" $(pkg-config --cflags fc3d-mpi) mpi/mpi_host.c $(pkg-config --libs fc3d-mpi) -lm -o mpi_host
for l in libfc3d.so libfc3d_native.so; do
  if readelf -d "$PREFIX/lib/$l" | grep -q 'NEEDED.*libmpi'; then echo "$l links libmpi"; exit 1; fi
done
for np in 1 2 3 4; do
  mpirun --oversubscribe -np $np ./mpi_host "$DATA/Rover1040.dat" 1e-10 200
done
mpirun --oversubscribe -np 3 ./mpi_host "$DATA/Capsules-i101-404.dat" 1e-6 500
cmake -S mpi -B mpi-build -DCMAKE_PREFIX_PATH="$PREFIX" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build mpi-build >/dev/null
mpirun --oversubscribe -np 2 ./mpi-build/mpi_host "$DATA/NESpheres_30_1.dat" 1e-8 200
# The Fortran module of the distributed solve (the INTEGER communicator): same line on 1 and 3 ranks.
mpifort -Wall -Werror -fcheck=all -J mpi "$PREFIX/share/fc3d/fortran/fc3d.f90" \
  "$PREFIX/share/fc3d/fortran/fc3d_mpi.f90" "$ROOT/fortran/mpi_example.f90" \
  $(pkg-config --libs fc3d-mpi) -o mpi_example_f
one=$(mpirun --oversubscribe -np 1 ./mpi_example_f)
three=$(mpirun --oversubscribe -np 3 ./mpi_example_f)
echo "Fortran: np 1 [$one] np 3 [$three]"
[ "$one" = "$three" ] || { echo "the Fortran example differs between 1 and 3 ranks"; exit 1; }

echo "== Fortran module (installed source) and example"
bash "$ROOT/scripts/test-fortran.sh" "$PREFIX"

echo "== Python package (venv, pip install ./python, pytest, the README's Python quickstart)"
bash "$ROOT/scripts/test-python.sh"

echo "== the README's quickstarts and in-tree example, as written"
bash "$ROOT/scripts/test-readme.sh" "$PREFIX"

echo "== Siconos and fc3d's native library in one process"
cc -O2 -I/usr/include/siconos/numerics -I/usr/include/siconos $(pkg-config --cflags fc3d-native) side_by_side.c \
  $(pkg-config --libs fc3d-native) -lsiconos_numerics -lm -o side_by_side
for p in NESpheres_10_1 Rover1039 Confeti-ex13-Fc3D-SBM; do ./side_by_side "$DATA/$p.dat"; done

echo "== C checks under valgrind (installed libfc3d.so)"
cc "${CFLAGS[@]}" -I"$SICONOS_INC" $(pkg-config --cflags fc3d) ownership_main.c capi_checks.c nsgs_options.c matrix_hostile.c solver_entries.c workspace_checks.c \
  global_checks.c \
  $(pkg-config --libs fc3d) -lm -o capi_checks
valgrind --quiet --error-exitcode=1 --leak-check=full --errors-for-leak-kinds=definite \
  ./capi_checks "$DATA" "$WORK"

echo "== Siconos 4.4 compatibility"
cc -I"$SICONOS_INC" $(pkg-config --cflags fc3d) layout.c -o layout_fc3d
cc -I/usr/include/siconos/numerics -I/usr/include/siconos layout.c -o layout_siconos
diff <(./layout_fc3d) <(./layout_siconos)
echo "struct layouts and enum values identical ($(./layout_fc3d | wc -l) checks)"
cc -O2 -I"$SICONOS_INC" $(pkg-config --cflags fc3d) siconos_host.c $(pkg-config --libs fc3d) -lm -o host_fc3d
cc -O2 -I/usr/include/siconos/numerics -I/usr/include/siconos siconos_host.c -lsiconos_numerics -lm -o host_siconos
agree=0
for p in Rover1039 Rover4396 Confeti-ex13-Fc3D-SBM Confeti-ex03-Fc3D-SBM OneObject-i1028-138.hdf5 NESpheres_10_1; do
  ours=$(./host_fc3d "$DATA/$p.dat" 1e-8 10000)
  theirs=$(./host_siconos "$DATA/$p.dat" 1e-8 10000)
  # Same converged flag and iteration count; errors may differ in the last digits.
  if [ "$(echo "$ours" | cut -d' ' -f1-4)" != "$(echo "$theirs" | cut -d' ' -f1-4)" ]; then
    echo "disagreement on $p: fc3d [$ours] siconos [$theirs]"; exit 1
  fi
  echo "$p: fc3d [$ours] siconos [$theirs]"
  agree=$((agree + 1))
done
echo "Siconos host program: $agree problems, same info and iterations with both libraries"

cd "$ROOT"
echo "== side by side with Siconos (compare-siconos.sh --quick: same info, iterations, cross-scored errors)"
bash scripts/compare-siconos.sh --quick

echo "== Siconos 4.4.0's own friction tests against the installed libfc3d and the installed Siconos"
bash scripts/siconos-suite.sh --lib "$PREFIX/lib" --include "$SICONOS_INC" --include "$PREFIX/include"
echo "== all checks passed"

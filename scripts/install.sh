#!/usr/bin/env bash
# Installs fc3d like a system library:
#
#   bash scripts/install.sh --prefix DIR [--libdir lib] [--features fclib]
#
# into DIR:
#   include/fc3d.h, include/fc3d_native.h        the native headers
#   include/fc3d/siconos/*.h                     Siconos-named headers (SiconosNumerics.h, ...)
#   lib/libfc3d.so.X.Y.Z (+ .so.X, .so), lib/libfc3d.a
#                                                the drop-in library (Siconos' names)
#   lib/libfc3d_native.so.X.Y.Z (+ links), .a    the native entry only (links beside Siconos)
#   lib/pkgconfig/fc3d.pc, fc3d-native.pc        pkg-config (variable siconos_includedir)
#   lib/cmake/fc3d/fc3dConfig*.cmake             find_package(fc3d): fc3d::fc3d, fc3d::native,
#                                                fc3d::fc3d_static, fc3d_SICONOS_INCLUDE_DIR
#   share/fc3d/fortran/fc3d.f90                  the Fortran module (source)
#   share/doc/fc3d/                              README.md, LICENSE, CHANGELOG.md, docs/
# and, when MPI's compiler wrapper is found (`mpicc`, or $FC3D_MPICC; apt-get install openmpi-bin
# libopenmpi-dev), the distributed solve, so that hosts without MPI never link libmpi:
#   include/fc3d_mpi.h, lib/libfc3d_mpi.so.X.Y.Z (+ links), lib/pkgconfig/fc3d-mpi.pc,
#   lib/cmake/fc3d/fc3d-mpiTargets.cmake, share/fc3d/fortran/fc3d_mpi.f90
#                                                (fc3d::mpi, the Fortran module; --no-mpi skips it)
# --features fclib builds the FCLIB (.hdf5) readers and writers in (needs libhdf5-dev).
set -euo pipefail
cd "$(dirname "$0")/.."

prefix="" libdir=lib features="" mpi=auto
while [ $# -gt 0 ]; do
  case "$1" in
    --prefix) prefix=$2; shift ;;
    --libdir) libdir=$2; shift ;;
    --features) features=$2; shift ;;
    --no-mpi) mpi=no ;;
    -h|--help) sed -n '2,22p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
  shift
done
[ -n "$prefix" ] || { echo "--prefix DIR is required" >&2; exit 2; }
mkdir -p "$prefix"
prefix=$(cd "$prefix" && pwd)

version=$(sed -n 's/^version = "\(.*\)"/\1/p' Cargo.toml | head -1)
major=${version%%.*}
minor=${version#*.}; minor=${minor%%.*}
feature_args=()
[ -z "$features" ] || feature_args=(--features "$features")

echo "== building fc3d $version (release)"
cargo build --release -p fc3d "${feature_args[@]}"
# The native-only library in its own target directory, so both builds are kept.
cargo build --release -p fc3d --no-default-features "${feature_args[@]}" --target-dir target/native
mpicc=${FC3D_MPICC:-mpicc}
if [ "$mpi" = auto ] && command -v "$mpicc" >/dev/null; then
  echo "== building fc3d-mpi $version (release; MPI from $mpicc)"
  # Beside the native-only library: fc3d-mpi carries the same native entry, so the core and the
  # C layer built above are reused.
  mpi_features=()
  [ -z "$features" ] || mpi_features=(--features "$(echo "$features" | sed -E 's/([^, ]+)/fc3d\/\1/g')")
  FC3D_REQUIRE_MPI=1 cargo build --release -p fc3d-mpi --lib "${mpi_features[@]}" \
    --target-dir target/native
  mpi=yes
  # MPI's own flags for pkg-config (Open MPI's --showme, else MPICH's -compile_info/-link_info).
  mpi_cflags=$("$mpicc" --showme:compile 2>/dev/null ||
    "$mpicc" -compile_info | tr ' ' '\n' | grep -E '^-(I|D)' | tr '\n' ' ')
  mpi_libs=$("$mpicc" --showme:link 2>/dev/null ||
    "$mpicc" -link_info | tr ' ' '\n' | grep -E '^-(L|l|Wl)' | tr '\n' ' ')
elif [ "$mpi" = auto ]; then
  echo "== $mpicc not found: libfc3d_mpi not built (apt-get install openmpi-bin libopenmpi-dev)"
fi
private_libs=$(cargo rustc --release -p fc3d --lib --crate-type staticlib "${feature_args[@]}" -- \
  --print native-static-libs 2>&1 | sed -n 's/.*native-static-libs: //p' | tail -1)
[ -n "$private_libs" ] || private_libs="-lgcc_s -lutil -lrt -lpthread -lm -ldl -lc"

echo "== installing into $prefix"
inc="$prefix/include" lib="$prefix/$libdir"
install -d "$inc/fc3d/siconos" "$lib/pkgconfig" "$lib/cmake/fc3d" "$prefix/share/fc3d/fortran" \
  "$prefix/share/doc/fc3d"
install -m 644 capi/include/fc3d.h capi/include/fc3d_native.h "$inc/"
install -m 644 capi/include/siconos-compat/*.h "$inc/fc3d/siconos/"
for name in fc3d fc3d_native; do
  dir=target/release
  [ "$name" = fc3d ] || dir=target/native/release
  install -m 755 "$dir/libfc3d.so" "$lib/lib$name.so.$version"
  ln -sf "lib$name.so.$version" "$lib/lib$name.so.$major"
  ln -sf "lib$name.so.$major" "$lib/lib$name.so"
  install -m 644 "$dir/libfc3d.a" "$lib/lib$name.a"
done
substitute() {
  sed -e "s|@PREFIX@|$prefix|g" -e "s|@LIBDIR@|$libdir|g" -e "s|@VERSION@|$version|g" \
    -e "s|@MAJOR@|$major|g" -e "s|@MINOR@|$minor|g" -e "s|@PRIVATE_LIBS@|$private_libs|g" \
    -e "s|@CMAKE_PRIVATE_LIBS@|$(echo "$private_libs" | sed 's/-l//g; s/ /;/g')|g" \
    -e "s|@CMAKE_TO_PREFIX@|$(realpath --relative-to="$lib/cmake/fc3d" "$prefix")|g" "$1"
}
substitute capi/packaging/fc3d.pc.in > "$lib/pkgconfig/fc3d.pc"
substitute capi/packaging/fc3d-native.pc.in > "$lib/pkgconfig/fc3d-native.pc"
substitute capi/packaging/fc3dConfig.cmake.in > "$lib/cmake/fc3d/fc3dConfig.cmake"
substitute capi/packaging/fc3dConfigVersion.cmake.in > "$lib/cmake/fc3d/fc3dConfigVersion.cmake"
if [ "$mpi" = yes ]; then
  install -m 644 mpi/include/fc3d_mpi.h "$inc/"
  install -d "$prefix/share/fc3d/fortran"
  install -m 644 fortran/fc3d_mpi.f90 "$prefix/share/fc3d/fortran/"
  install -m 755 target/native/release/libfc3d_mpi.so "$lib/libfc3d_mpi.so.$version"
  ln -sf "libfc3d_mpi.so.$version" "$lib/libfc3d_mpi.so.$major"
  ln -sf "libfc3d_mpi.so.$major" "$lib/libfc3d_mpi.so"
  substitute mpi/packaging/fc3d-mpi.pc.in | sed -e "s|@MPI_CFLAGS@|$mpi_cflags|g" \
    -e "s|@MPI_LIBS@|$mpi_libs|g" > "$lib/pkgconfig/fc3d-mpi.pc"
  # For CMake: -I, -L and -l of those flags as ;-lists.
  cmake_list() { for f in $1; do case $f in "$2"*) printf '%s;' "${f#"$2"}" ;; esac; done | sed 's/;$//'; }
  substitute mpi/packaging/fc3d-mpiTargets.cmake.in |
    sed -e "s|@MPI_INCLUDE_DIRS@|$(cmake_list "$mpi_cflags" -I)|g" \
      -e "s|@MPI_LIBRARY_DIRS@|$(cmake_list "$mpi_libs" -L)|g" \
      -e "s|@MPI_LIBRARY_NAMES@|$(cmake_list "$mpi_libs" -l)|g" > "$lib/cmake/fc3d/fc3d-mpiTargets.cmake"
else
  rm -f "$inc/fc3d_mpi.h" "$lib"/libfc3d_mpi.so* "$lib/pkgconfig/fc3d-mpi.pc" \
    "$prefix/share/fc3d/fortran/fc3d_mpi.f90" \
    "$lib/cmake/fc3d/fc3d-mpiTargets.cmake"
fi
[ ! -f fortran/fc3d.f90 ] || install -m 644 fortran/fc3d.f90 "$prefix/share/fc3d/fortran/"
install -m 644 README.md LICENSE CHANGELOG.md "$prefix/share/doc/fc3d/"
install -d "$prefix/share/doc/fc3d/docs"
install -m 644 docs/*.md docs/*.png docs/*.svg "$prefix/share/doc/fc3d/docs/"
echo "installed fc3d $version: $(du -h "$lib/libfc3d.so.$version" | cut -f1) libfc3d.so, $(du -h "$lib/libfc3d.a" | cut -f1) libfc3d.a"

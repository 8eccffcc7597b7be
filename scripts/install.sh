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
# --features fclib builds the FCLIB (.hdf5) readers and writers in (needs libhdf5-dev).
set -euo pipefail
cd "$(dirname "$0")/.."

prefix="" libdir=lib features=""
while [ $# -gt 0 ]; do
  case "$1" in
    --prefix) prefix=$2; shift ;;
    --libdir) libdir=$2; shift ;;
    --features) features=$2; shift ;;
    -h|--help) sed -n '2,20p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
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
[ ! -f fortran/fc3d.f90 ] || install -m 644 fortran/fc3d.f90 "$prefix/share/fc3d/fortran/"
install -m 644 README.md LICENSE CHANGELOG.md "$prefix/share/doc/fc3d/"
install -d "$prefix/share/doc/fc3d/docs"
install -m 644 docs/*.md docs/*.png docs/*.svg "$prefix/share/doc/fc3d/docs/"
echo "installed fc3d $version: $(du -h "$lib/libfc3d.so.$version" | cut -f1) libfc3d.so, $(du -h "$lib/libfc3d.a" | cut -f1) libfc3d.a"

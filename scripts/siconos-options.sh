#!/usr/bin/env bash
# solver_options_create of libfc3d against the installed Siconos 4.4, slot for slot (issue 12):
# capi-tests/c/options_defaults.c is compiled twice, against fc3d's compat headers with -lfc3d
# and against Siconos' headers with -lsiconos_numerics, and the two outputs must be identical.
# The ids are every enumerator of FRICTION_SOLVER in the installed Friction_cst.h (not a
# hand-kept list) and of the VI, SOCLCP and ConvexQP solver enums that Siconos' friction tests
# use as internal solvers; the names are every SICONOS_*_STR variable the installed
# libsiconos_numerics defines for those headers.
#
#   scripts/siconos-options.sh [--fc3d-cflags "FLAGS"] [--fc3d-libs "FLAGS"] [--keep DIR]
#                              [--write-table]
#
# Defaults: the in-tree headers and target/release/libfc3d.so (cargo build --release -p fc3d
# first).
# --write-table regenerates capi/src/params/siconos_table.rs (the defaults fc3d returns) from
# the Siconos side and stops (rebuild, then compare).
# Exit status: 0 identical, 1 differences, 2 usage or a build failure, 77 a prerequisite is
# missing (Siconos' headers, ctags, Siconos' sources).
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
FC3D_CFLAGS="-I$ROOT/capi/include/siconos-compat -I$ROOT/capi/include"
FC3D_LIBS=""
KEEP=""
WRITE_TABLE=0
while [ $# -gt 0 ]; do
  case "$1" in
    --fc3d-cflags) FC3D_CFLAGS=$2; shift 2 ;;
    --fc3d-libs) FC3D_LIBS=$2; shift 2 ;;
    --keep) KEEP=$2; shift 2 ;;
    --write-table) WRITE_TABLE=1; shift ;;
    -h|--help) awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"; exit 0 ;;
    *) echo "siconos-options: unknown argument $1" >&2; exit 2 ;;
  esac
done
if [ -z "$FC3D_LIBS" ]; then
  # Built now (a no-op when up to date), so the comparison never runs a stale library.
  (cd "$ROOT" && cargo build --quiet --release -p fc3d)
  # The program loads libfc3d by its SONAME; a cargo build directory has only libfc3d.so.
  SONAME_DIR=$ROOT/target/siconos-options/lib
  mkdir -p "$SONAME_DIR"
  ln -sf "$ROOT/target/release/libfc3d.so" "$SONAME_DIR/libfc3d.so.0"
  FC3D_LIBS="-L$ROOT/target/release -Wl,-rpath,$SONAME_DIR -lfc3d"
fi
SIC=/usr/include/siconos/numerics
[ -f "$SIC/Friction_cst.h" ] || { echo "siconos-options: needs libsiconos-numerics-dev" >&2; exit 77; }
command -v ctags >/dev/null || { echo "siconos-options: needs universal-ctags" >&2; exit 77; }
SRC=$("$ROOT/scripts/siconos-src.sh") || { echo "siconos-options: needs Siconos 4.4.0's sources" >&2; exit 77; }
# VI_cst.h, SOCLCP_cst.h and ConvexQP_cst.h are not installed by Debian: the tarball's.
TARBALL_INC=(-I"$SRC/numerics/src/VI" -I"$SRC/numerics/src/SOCP" -I"$SRC/numerics/src/QP")

WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
enumerators() { # enumerators <header> <enum>: in the header's order
  ctags -u -f - --fields=+s --c-kinds=e --language-force=C "$1" | awk -F'\t' -v e="enum:$2" '$NF == e { print $1 }'
}
{
  enumerators "$SIC/Friction_cst.h" FRICTION_SOLVER
  # The internal solver families of Siconos' friction tests (test_fp_1.c: SOCLCP_VI_EG/FPP).
  enumerators "$SRC/numerics/src/VI/VI_cst.h" VI_SOLVER
  enumerators "$SRC/numerics/src/SOCP/SOCLCP_cst.h" SOCLCP_SOLVER
  enumerators "$SRC/numerics/src/QP/ConvexQP_cst.h" CONVEXQP_SOLVER
} | sed 's/.*/ID(&)/' > "$WORK/options_ids.inc"
# The _STR names the headers declare and libsiconos_numerics defines.
nm -D --defined-only "$(cc -print-file-name=libsiconos_numerics.so)" | awk '{ print $NF }' | sort -u > "$WORK/defined.txt"
for h in "$SIC/Friction_cst.h" "$SRC/numerics/src/VI/VI_cst.h" "$SRC/numerics/src/SOCP/SOCLCP_cst.h" "$SRC/numerics/src/QP/ConvexQP_cst.h"; do
  ctags -u -f - --c-kinds=x --language-force=C "$h" | cut -f1
done | grep '_STR$' | while read -r s; do
  if grep -qx "$s" "$WORK/defined.txt"; then echo "STR($s)"; fi
done > "$WORK/options_strs.inc"

cp "$ROOT/capi-tests/c/options_defaults.c" "$WORK/"
cd "$WORK"
# shellcheck disable=SC2086
cc -std=c99 -Wall -Werror -I. $FC3D_CFLAGS options_defaults.c $FC3D_LIBS -lm -o options_fc3d
cc -std=c99 -Wall -Werror -I. -I"$SIC" -I/usr/include/siconos "${TARBALL_INC[@]}" options_defaults.c \
  -lsiconos_numerics -lm -o options_siconos
status=0
./options_siconos > siconos.txt 2> siconos.err || { echo "siconos-options: the Siconos build failed (status $?)" >&2; exit 2; }
if [ "$WRITE_TABLE" = 1 ]; then
  awk -f "$ROOT/scripts/siconos-options/table.awk" siconos.txt > "$ROOT/capi/src/params/siconos_table.rs"
  echo "siconos-options: wrote capi/src/params/siconos_table.rs; rebuild libfc3d before comparing" >&2
  exit 0
fi
./options_fc3d > fc3d.txt 2> fc3d.err || { echo "siconos-options: the fc3d build failed (status $?): $(tail -3 fc3d.err)" >&2; status=1; }
[ -z "$KEEP" ] || { mkdir -p "$KEEP"; cp fc3d.txt fc3d.err siconos.txt options_ids.inc options_strs.inc "$KEEP/"; }
[ "$status" = 0 ] || exit "$status"
if ! diff -u siconos.txt fc3d.txt > diff.txt; then
  echo "solver_options_create: fc3d differs from Siconos 4.4 (- Siconos, + fc3d):"
  head -200 diff.txt
  exit 1
fi
echo "solver_options_create identical to Siconos 4.4 for $(wc -l < options_ids.inc) ids ($(wc -l < siconos.txt) lines, $(wc -l < options_strs.inc) _STR names)"

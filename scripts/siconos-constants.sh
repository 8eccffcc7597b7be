#!/usr/bin/env bash
# The constants side of the drop-in (issue 12): every enum, enumerator, macro and variable that
# Siconos 4.4's friction headers declare must be in fc3d's compat header of the same name, with
# Siconos' value. The headers are Friction_cst.h and SolverOptions.h (installed by
# libsiconos-numerics-dev) and every *_cst.h that Siconos' friction tests include (taken from
# the installed headers, or from Siconos 4.4.0's tarball for those Debian does not install).
# The names are extracted from Siconos' headers now (ctags), not kept in a list here.
#
#   scripts/siconos-constants.sh [--fc3d-libs "FLAGS"] [--keep DIR]
#
# Checks, per header: (1) the names (enums, enumerators, macros, extern variables) Siconos
# declares are all declared by fc3d's header or the fc3d.h it includes (fc3d's extra names
# are listed, not errors);
# (2) one C program, compiled against Siconos' headers (-lsiconos_numerics) and against fc3d's
# (-lfc3d), prints every enumerator's value, every macro's value (or that it is defined, for an
# empty one), each enum type's size and every variable's string: the outputs must be identical.
# Exit status: 0 identical, 1 differences, 77 a prerequisite is missing (Siconos' headers,
# ctags, a C compiler or Siconos' sources).
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
FC3D_INC=$ROOT/capi/include/siconos-compat
FC3D_LIBS=""
KEEP=""
while [ $# -gt 0 ]; do
  case "$1" in
    --fc3d-libs) FC3D_LIBS=$2; shift 2 ;;
    --keep) KEEP=$2; shift 2 ;;
    -h|--help) awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"; exit 0 ;;
    *) echo "siconos-constants: unknown argument $1" >&2; exit 2 ;;
  esac
done
SIC=/usr/include/siconos/numerics
[ -f "$SIC/Friction_cst.h" ] || { echo "siconos-constants: needs libsiconos-numerics-dev" >&2; exit 77; }
command -v ctags >/dev/null || { echo "siconos-constants: needs universal-ctags" >&2; exit 77; }
command -v cc >/dev/null || { echo "siconos-constants: needs a C compiler" >&2; exit 77; }
SRC=$("$ROOT/scripts/siconos-src.sh") || { echo "siconos-constants: needs Siconos 4.4.0's sources" >&2; exit 77; }
if [ -z "$FC3D_LIBS" ]; then
  # Built now (a no-op when up to date), so the comparison never runs a stale library.
  (cd "$ROOT" && cargo build --quiet --release -p fc3d)
  SONAME_DIR=$ROOT/target/siconos-options/lib
  mkdir -p "$SONAME_DIR"
  ln -sf "$ROOT/target/release/libfc3d.so" "$SONAME_DIR/libfc3d.so.0"
  FC3D_LIBS="-L$ROOT/target/release -Wl,-rpath,$SONAME_DIR -lfc3d"
fi

WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT

# The headers: the two the brief names, and every *_cst.h a friction test includes.
TESTS=$SRC/numerics/src/FrictionContact/test
{
  echo Friction_cst.h
  echo SolverOptions.h
  find "$TESTS" -maxdepth 1 \( -name '*.c' -o -name '*.h' -o -name '*.in' \) -print0 |
    xargs -0 grep -ho '#include *"[A-Za-z0-9_]*_cst\.h"' | sed 's/.*"\(.*\)"/\1/' || true
} | sort -u > "$WORK/headers.txt"
siconos_header() { # the path of Siconos' header $1: installed, else the tarball's
  if [ -f "$SIC/$1" ]; then echo "$SIC/$1"; else find "$SRC/numerics/src" -name "$1" -print -quit; fi
}
# names <header>: "kind name" for enums, enumerators, macros and extern variables.
names() {
  ctags -u -f - --c-kinds=gedx --fields=+K --language-force=C "$1" |
    awk -F'\t' '{ k = $4; if (k == "externvar") k = "variable"; print k, $1 }' | sort -u
}

status=0
INCDIRS=()
: > "$WORK/checks.inc"
: > "$WORK/includes.inc"
while read -r h; do
  sic=$(siconos_header "$h")
  [ -n "$sic" ] || { echo "siconos-constants: $h not found in Siconos' headers or sources" >&2; exit 77; }
  case " ${INCDIRS[*]-} " in *" -I$(dirname "$sic") "*) ;; *) INCDIRS+=("-I$(dirname "$sic")") ;; esac
  if [ ! -f "$FC3D_INC/$h" ]; then
    echo "MISSING header $h (fc3d has no compat header of that name)"
    status=1
    continue
  fi
  echo "#include \"$h\"" >> "$WORK/includes.inc"
  names "$sic" > "$WORK/sic.names"
  # What fc3d's header declares, with fc3d.h that every compat header includes.
  { names "$FC3D_INC/$h"; names "$ROOT/capi/include/fc3d.h"; } | sort -u > "$WORK/fc3d.names"
  missing=$(comm -23 "$WORK/sic.names" "$WORK/fc3d.names")
  extra=$(names "$FC3D_INC/$h" | comm -13 "$WORK/sic.names" - | grep -v ' FC3D_COMPAT_' || true)
  echo "$h: $(wc -l < "$WORK/sic.names") names in Siconos' header, $(echo -n "$missing" | grep -c . || true) missing from fc3d's"
  if [ -n "$missing" ]; then
    echo "$missing" | sed "s/^/  MISSING $h: /"
    status=1
  fi
  [ -z "$extra" ] || echo "$extra" | sed "s/^/  fc3d only: /"
  # The checks of the names both declare.
  comm -12 "$WORK/sic.names" "$WORK/fc3d.names" | while read -r kind name; do
    case "$kind" in
      enumerator) echo "ENUMERATOR($name)" ;;
      enum) echo "ENUM($name)" ;;
      variable) echo "VARIABLE($name)" ;;
      macro)
        # An include guard (empty) is checked as defined; any other macro by its value.
        if grep -Eq "^[[:space:]]*#[[:space:]]*define[[:space:]]+$name[[:space:]]*$" "$sic"; then
          echo "DEFINED($name)"
        else
          echo "MACRO($name)"
        fi ;;
    esac
  done >> "$WORK/checks.inc"
done < "$WORK/headers.txt"

cat > "$WORK/constants.c" <<'EOF'
/* Prints the value of every constant listed in checks.inc; compiled against Siconos' headers
   and against fc3d's, the two outputs must be identical. */
#include <stdio.h>
#include "includes.inc"
#define ENUMERATOR(x) printf("enumerator %s = %lld\n", #x, (long long)(x));
#define ENUM(x) printf("enum %s: size %zu\n", #x, sizeof(enum x));
#define VARIABLE(x) printf("variable %s = \"%s\"\n", #x, (x));
#define MACRO(x) printf("macro %s = %.17g\n", #x, (double)(x));
#define DEFINED(x) printf("macro %s defined\n", #x);
int main(void) {
#include "checks.inc"
  return 0;
}
EOF
cd "$WORK"
# shellcheck disable=SC2086
if ! cc -std=c99 -Wall -I. -I"$FC3D_INC" -I"$ROOT/capi/include" constants.c $FC3D_LIBS -lm -o constants_fc3d 2> fc3d-build.err; then
  echo "siconos-constants: the program does not build against fc3d's headers:"
  head -30 fc3d-build.err
  status=1
fi
cc -std=c99 -Wall -I. "${INCDIRS[@]}" -I"$SIC" -I/usr/include/siconos constants.c -lsiconos_numerics -lm \
  -o constants_siconos 2> siconos-build.err || { echo "siconos-constants: the program does not build against Siconos' headers:"; head -30 siconos-build.err; exit 2; }
./constants_siconos > siconos.txt
if [ -x constants_fc3d ]; then
  ./constants_fc3d > fc3d.txt
  if ! diff -u siconos.txt fc3d.txt > diff.txt; then
    echo "values differ (- Siconos 4.4, + fc3d):"
    grep '^[-+][^-+]' diff.txt | head -100
    status=1
  fi
fi
[ -z "$KEEP" ] || { mkdir -p "$KEEP"; cp ./*.txt ./*.inc constants.c "$KEEP/"; }
if [ "$status" = 0 ]; then
  echo "constants identical to Siconos 4.4: $(wc -l < siconos.txt) names in $(wc -l < headers.txt) headers ($(tr '\n' ' ' < headers.txt))"
fi
exit "$status"

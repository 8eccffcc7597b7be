#!/usr/bin/env bash
# Siconos 4.4.0's own friction tests, unmodified, run case by case against libfc3d and against the
# installed Siconos in the same run (issue 12). Siconos' sources are taken at test time by
# scripts/siconos-src.sh (Debian's source package through apt-get source, checksum pinned), never
# committed.
#
#   scripts/siconos-suite.sh [--lib DIR] [--fclib-lib DIR] [--include DIR]... [--jobs N]
#                            [--timeout SECONDS] [--only REGEX] [--out DIR] [--report-only]
#
#  --lib DIR      directory holding libfc3d.so (default: target/release, built with the fclib
#                 feature)
#  --fclib-lib DIR  libfc3d.so built with the fclib feature, for the FCLIB programs (default: the
#                 --lib one when it reads FCLIB files, else target/fclib/release, built)
#  --include DIR  fc3d's include directories (default: capi/include/siconos-compat and capi/include)
#  --jobs N       cases run in parallel (default: the number of cores)
#  --timeout S    wall-clock limit per case and library (default 120 s)
#  --only REGEX   only the collections or programs whose name matches
#  --out DIR      where results.tsv and the logs go (default target/siconos-suite)
#  --report-only  exit 0 even if a case that Siconos passes fails with fc3d
#  --write-open   rewrite scripts/siconos-suite/open-cases.txt from this run (the cases Siconos
#                 passes and fc3d does not, minus those of known-differences.txt)
#  --allow-unresolved  link the fc3d programs even if a function they call is missing from
#                 libfc3d (a developer's aid while the surface is incomplete: a case that calls the
#                 missing function crashes); never used by the test suite
#
# Every case of a collection runs in its own process (scripts/siconos-suite/case_runner.c builds
# the collection with Siconos' build_test_collection and runs one index through Siconos'
# frictionContact_test_function, or its rolling or global counterpart). A case passes when that
# function returns 0 within the time limit. The global FCLIB programs (gfc3d_*_FCLIB) run against
# fc3d only (Debian's Siconos is built without FCLIB): a case is judged by the will_fail mark of
# Siconos' own driver (gfc3d_test_collection.c.in), a marked case may fail.
# The run fails when a case that Siconos passes does not pass with fc3d, unless the case is listed
# in scripts/siconos-suite/known-differences.txt with the reason or in open-cases.txt (the work
# list, which only shrinks: a listed case that passes fails the run until its line is removed).
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$(pwd)

LIB=""
FCLIB_LIB=""
INCLUDES=()
JOBS=$(nproc)
TIMEOUT=120
ONLY=""
OUT=$ROOT/target/siconos-suite
REPORT_ONLY=0
UNRESOLVED=0
WRITE_OPEN=""
while [ $# -gt 0 ]; do
  case "$1" in
    --lib) LIB=$2; shift 2 ;;
    --fclib-lib) FCLIB_LIB=$2; shift 2 ;;
    --include) INCLUDES+=("$2"); shift 2 ;;
    --jobs) JOBS=$2; shift 2 ;;
    --timeout) TIMEOUT=$2; shift 2 ;;
    --only) ONLY=$2; shift 2 ;;
    --out) OUT=$2; shift 2 ;;
    --report-only) REPORT_ONLY=1; shift ;;
    --allow-unresolved) UNRESOLVED=1; shift ;;
    --write-open) WRITE_OPEN=$ROOT/scripts/siconos-suite/open-cases.txt; shift ;;
    -h|--help) sed -n '2,30p' "$0"; exit 0 ;;
    *) echo "siconos-suite: unknown argument $1" >&2; exit 2 ;;
  esac
done
[ ${#INCLUDES[@]} -gt 0 ] || INCLUDES=("$ROOT/capi/include/siconos-compat" "$ROOT/capi/include")
if [ -z "$LIB" ]; then
  cargo build --release -p fc3d --features fclib >/dev/null
  LIB=$ROOT/target/release
fi
if [ -z "$FCLIB_LIB" ]; then
  # A library reads FCLIB files when it links libhdf5 (grep reads all of nm's output: with -q
  # it would stop early and pipefail would see nm killed by SIGPIPE).
  if nm -D --undefined-only "$LIB/libfc3d.so" | grep ' H5Fopen' >/dev/null; then
    FCLIB_LIB=$LIB
  else
    cargo build --release -p fc3d --features fclib --target-dir "$ROOT/target/fclib" >/dev/null
    FCLIB_LIB=$ROOT/target/fclib/release
  fi
fi
[ -f /usr/include/siconos/numerics/FrictionContactProblem.h ] || {
  echo "siconos-suite: needs libsiconos-numerics-dev (the reference library)" >&2; exit 2; }

# --- Siconos 4.4.0's sources: Debian's source package, the same release as the installed library ---
SRC=$(bash "$ROOT/scripts/siconos-src.sh")
CACHE=$(dirname "$SRC")
NUM=$SRC/numerics
TESTDIR=$NUM/src/FrictionContact/test
UTILS=("$NUM/src/tools/test-utils/test_utils.c" "$NUM/src/FrictionContact/test-utils/frictionContact_test_function.c")
# Headers the tests include that Debian's package does not install are taken from the same tarball,
# one by one as the Siconos build asks for them (see build_siconos).
EXTRA=$CACHE/extra-include
mkdir -p "$EXTRA"
TEST_INC=(-I"$NUM/src/FrictionContact/test-utils" -I"$NUM/src/tools/test-utils")
SIC_FLAGS=(-I/usr/include/siconos/numerics -I/usr/include/siconos -I"$EXTRA" "${TEST_INC[@]}")
FC3D_FLAGS=()
for d in "${INCLUDES[@]}"; do FC3D_FLAGS+=(-I"$d"); done
# Helper headers of Siconos' tests that are not friction API (3x3 macros, timers, cycle
# counters): the fc3d build takes them from the same tarball, after fc3d's own headers. Nothing
# else is taken: a friction header missing from fc3d's compat set must fail the fc3d build.
HELPERS=$CACHE/test-helpers
mkdir -p "$HELPERS"
cp "$NUM/src/tools/op3x3.h" "$NUM/src/tools/internal/timers_interf.h" "$NUM/src/tools/internal/fftw_cycle.h" \
  "$HELPERS/"
FC3D_FLAGS+=("${TEST_INC[@]}" -I"$HELPERS")

rm -rf "$OUT"
mkdir -p "$OUT/bin" "$OUT/logs" "$OUT/run" "$OUT/lib"
BIN=$OUT/bin
# The programs load libfc3d by its SONAME; a cargo build directory has only libfc3d.so.
soname_dir() { # soname_dir <dir> <name>: a directory where <dir>'s libfc3d.so is also libfc3d.so.0
  local dir=$1
  if [ -e "$dir/libfc3d.so.0" ]; then echo "$dir"; return; fi
  mkdir -p "$OUT/$2"
  ln -s "$(cd "$dir" && pwd)/libfc3d.so" "$OUT/$2/libfc3d.so"
  ln -s "$(cd "$dir" && pwd)/libfc3d.so" "$OUT/$2/libfc3d.so.0"
  echo "$OUT/$2"
}
LIB=$(soname_dir "$LIB" lib)
FCLIB_LIB=$(soname_dir "$FCLIB_LIB" lib-fclib)

# --- the collections of numerics_tests.cmake, and the single-program friction tests ---
# A collection line reads "DRIVER fc_test_collection.c.in FORMULATION fc3d COLLECTION <NAME>",
# followed by "EXTRA_SOURCES <data_collection> <solvers>)"; the rolling collection's reads
# "DRIVER rfc3d_test_collection.c.in FORMULATION rolling_fc3d COLLECTION <NAME>", the global ones'
# "DRIVER gfc3d_test_collection.c.in FORMULATION gfc3d COLLECTION <NAME>" (the FCLIB ones too:
# they run against fc3d only).
COLLECTIONS=$OUT/collections.txt
awk '
  /new_tests_collection\(/ { in_call = 1; text = "" }
  in_call { text = text " " $0 }
  in_call && /\)/ {
    in_call = 0
    if ((text ~ /[^r]fc_test_collection\.c\.in/ && text ~ /FORMULATION (fc3d|fc2d)/ ||
         text ~ /rfc3d_test_collection\.c\.in/ && text ~ /FORMULATION rolling_fc3d/) && text !~ /FCLIB/ ||
        text ~ /gfc3d_test_collection\.c\.in/ && text ~ /FORMULATION gfc3d/) {
      gsub(/[()]/, " ", text)
      n = split(text, w, /[ \t]+/)
      form = ""; name = ""; srcs = ""
      for (i = 1; i <= n; i++) {
        if (w[i] == "FORMULATION") form = w[i + 1]
        if (w[i] == "COLLECTION") name = w[i + 1]
        if (w[i] == "EXTRA_SOURCES") { for (j = i + 1; j <= n && w[j] ~ /\.c$/; j++) srcs = srcs " " w[j] }
      }
      print form "_" name, name, srcs
    }
  }' "$NUM/numerics_tests.cmake" > "$COLLECTIONS"
# The will_fail marks Siconos' global driver sets after building its collections: its own lines
# (between build_test_collection and run_test_collection), printing left out, compiled into the
# global case runner.
MARKS=$OUT/gfc3d_marks.h
awk '/build_test_collection\(/ { on = 1; next } /run_test_collection\(/ { on = 0 } on && !/printf/' \
  "$TESTDIR/gfc3d_test_collection.c.in" > "$MARKS"
PROGRAMS=(fc3d_newFromFortranData fc3d_LmgcDriver_test1 fc3d_LmgcDriver_test2 fc3d_LmgcDriver_test3
          fc3d_LmgcDriver_test4 fc3d_LmgcDriver_test5 fc3d_AlartCurnierFunctions_test)

build() { # build <label> <output> <sources and flags...>
  local label=$1 output=$2; shift 2
  if cc -O2 -w "$@" -lm -o "$output" >"$OUT/logs/build-$label.log" 2>&1; then
    echo ok
  elif [ "$UNRESOLVED" = 1 ] && [[ $label == *-fc3d ]] && grep -q "undefined reference" "$OUT/logs/build-$label.log"; then
    # --allow-unresolved: each missing function aborts with its name when called.
    sed -n "s/.*undefined reference to \`\([A-Za-z_0-9]*\)'.*/\1/p" "$OUT/logs/build-$label.log" | sort -u |
      awk '{ printf "#include <stdio.h>\n#include <stdlib.h>\nvoid %s(void) { fputs(\"missing in libfc3d: %s\\n\", stderr); abort(); }\n", $1, $1 }' \
      > "$OUT/logs/missing-$label.c"
    if cc -O2 -w "$@" "$OUT/logs/missing-$label.c" -lm -o "$output" >>"$OUT/logs/build-$label.log" 2>&1; then
      echo "ok (missing functions abort)"
    else
      echo "build failed"
    fi
  else
    echo "build failed"
  fi
}
build_siconos() { # as build, copying into $EXTRA each header of the tarball that is not installed
  local label=$1 attempt missing found status
  for attempt in 1 2 3 4 5 6 7 8; do
    status=$(build "$@")
    [ "$status" = ok ] && break
    missing=$(sed -n 's/.*fatal error: \([^:]*\.h\): No such file.*/\1/p' "$OUT/logs/build-$label.log" | head -1)
    [ -n "$missing" ] || break
    found=$(find "$NUM/src" -name "$(basename "$missing")" | head -1)
    [ -n "$found" ] || break
    cp "$found" "$EXTRA/"
  done
  echo "$status"
}

TASKS=$OUT/tasks.txt
: > "$TASKS"
BUILD_REPORT=$OUT/build.tsv
: > "$BUILD_REPORT"
while read -r label name sources; do
  [ -z "$ONLY" ] || [[ $label =~ $ONLY ]] || continue
  srcs=()
  for s in $sources; do srcs+=("$TESTDIR/$s"); done
  # The rolling collections run their cases through rollingFrictionContact_test_function, the
  # global ones through globalFrictionContact_test_function with their driver's marks.
  if [[ $label == rolling_* ]]; then
    srcs+=(-DCASE_RUNNER_ROLLING=1 "$NUM/src/FrictionContact/test-utils/rollingFrictionContact_test_function.c")
  fi
  if [[ $label == gfc3d_* ]]; then
    srcs+=(-DCASE_RUNNER_GLOBAL=1 "-DCASE_RUNNER_MARKS=\"$MARKS\""
           "$NUM/src/FrictionContact/test-utils/globalFrictionContact_test_function.c")
  fi
  # Debian's Siconos has no FCLIB: the FCLIB programs are built against fc3d only.
  libraries=(siconos fc3d)
  fc3d_lib=$LIB
  if [[ $label == *FCLIB* ]]; then libraries=(fc3d); fc3d_lib=$FCLIB_LIB; fi
  for which in "${libraries[@]}"; do
    if [ $which = siconos ]; then flags=("${SIC_FLAGS[@]}"); link=(-lsiconos_numerics)
    else flags=("${FC3D_FLAGS[@]}"); link=(-L"$fc3d_lib" -Wl,-rpath,"$fc3d_lib" -lfc3d); fi
    builder=build; [ $which = siconos ] && builder=build_siconos
    status=$($builder "$label-$which" "$BIN/$label-$which" -D"$name"=1 "${flags[@]}" \
      "$ROOT/scripts/siconos-suite/case_runner.c" "${srcs[@]}" "${UTILS[@]}" "${link[@]}")
    printf '%s\t%s\t%s\n' "$label" "$which" "$status" >> "$BUILD_REPORT"
  done
  # The case list comes from Siconos' build (the reference; fc3d's build must list the same),
  # from fc3d's for the FCLIB programs.
  lister=$BIN/$label-${libraries[0]}
  if [ -x "$lister" ]; then
    (cd "$TESTDIR" && "$lister" --list) > "$OUT/logs/list-$label.txt"
    while IFS=$'\t' read -r index id sname file mark; do
      printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$label" "$index" "$id" "$sname" "$file" "$mark" >> "$TASKS"
    done < "$OUT/logs/list-$label.txt"
  fi
done < "$COLLECTIONS"
for prog in "${PROGRAMS[@]}"; do
  [ -z "$ONLY" ] || [[ $prog =~ $ONLY ]] || continue
  src=$TESTDIR/$prog.c
  [ -f "$src" ] || continue
  status=$(build_siconos "$prog-siconos" "$BIN/$prog-siconos" "${SIC_FLAGS[@]}" "$src" -lsiconos_numerics)
  printf '%s\t%s\t%s\n' "$prog" siconos "$status" >> "$BUILD_REPORT"
  status=$(build "$prog-fc3d" "$BIN/$prog-fc3d" "${FC3D_FLAGS[@]}" "$src" -L"$LIB" -Wl,-rpath,"$LIB" -lfc3d)
  printf '%s\t%s\t%s\n' "$prog" fc3d "$status" >> "$BUILD_REPORT"
  printf '%s\t-\t-\t-\t-\t0\n' "$prog" >> "$TASKS"
done

# --- run: every case in its own process and its own directory (the tests write checkinput.dat) ---
run_one() { # run_one <label> <index> <library>: prints "pass|fail|timeout|crash|nobuild seconds"
  local label=$1 index=$2 which=$3 exe=$BIN/$1-$3 dir rc start end
  [ -x "$exe" ] || { echo "nobuild 0"; return; }
  dir=$(mktemp -d "$OUT/run/$label-$index-$which.XXXX")
  ln -s "$TESTDIR/data" "$dir/data"
  # The fc3d programs find their library by RUNPATH, which a caller's LD_LIBRARY_PATH overrides
  # (test-all.sh points it at the installed library, built without FCLIB): put theirs first.
  local libdir=$LIB
  [[ $label == *FCLIB* ]] && libdir=$FCLIB_LIB
  local path=$libdir${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
  [ "$which" = fc3d ] || path=${LD_LIBRARY_PATH:-}
  start=$(date +%s.%N)
  set +e
  if [ "$index" = - ]; then
    (cd "$dir" && LD_LIBRARY_PATH=$path timeout -k 5 "$TIMEOUT" "$exe") > "$OUT/logs/$label-$which.log" 2>&1
  else
    (cd "$dir" && LD_LIBRARY_PATH=$path timeout -k 5 "$TIMEOUT" "$exe" "$index") > "$OUT/logs/$label-$index-$which.log" 2>&1
  fi
  rc=$?
  set -e
  end=$(date +%s.%N)
  rm -rf "$dir"
  local outcome
  case $rc in
    0) outcome=pass ;;
    124|137) outcome=timeout ;;
    1) outcome=fail ;;
    *) outcome="crash($rc)" ;;
  esac
  awk -v o="$outcome" -v a="$start" -v b="$end" 'BEGIN { printf "%s %.2f\n", o, b - a }'
}
export -f run_one
export OUT BIN TESTDIR TIMEOUT LIB FCLIB_LIB

RESULTS=$OUT/results.tsv
printf 'collection\tcase\tsolver_id\tsolver\tdata\tsiconos\tsiconos_s\tfc3d\tfc3d_s\twill_fail\n' > "$RESULTS"
total=$(wc -l < "$TASKS")
echo "== $total cases (collections and programs), $JOBS at a time, ${TIMEOUT}s limit per case and library"
# shellcheck disable=SC2016
tr '\t' '\037' < "$TASKS" | xargs -d '\n' -P "$JOBS" -I{} bash -c '
  IFS=$'"'"'\037'"'"' read -r label index id sname file mark <<< "$1"
  if [[ $label == *FCLIB* ]]; then s=none; st=0; else
    read -r s st <<< "$(run_one "$label" "$index" siconos)"; fi
  read -r f ft <<< "$(run_one "$label" "$index" fc3d)"
  printf "%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n" "$label" "$index" "$id" "$sname" "$file" "$s" "$st" "$f" "$ft" "$mark"
' _ {} >> "$RESULTS"

# --- report ---
KNOWN=$ROOT/scripts/siconos-suite/known-differences.txt
OPEN=$ROOT/scripts/siconos-suite/open-cases.txt
python3 "$ROOT/scripts/siconos-suite/report.py" "$RESULTS" "$BUILD_REPORT" "$KNOWN" "$OPEN" $WRITE_OPEN | tee "$OUT/report.txt"
status=${PIPESTATUS[0]}
if [ "$status" -ne 0 ] && [ "$REPORT_ONLY" = 1 ]; then
  echo "(--report-only: not failing)"
  status=0
fi
exit "$status"

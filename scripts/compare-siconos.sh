#!/usr/bin/env bash
# Side by side with Siconos Numerics 4.4: bench/siconos_compare.c is compiled twice, against fc3d's
# compat headers (-lfc3d) and against the installed Siconos (-lsiconos_numerics), and both
# binaries solve the same problems with the same solvers, tolerances and iteration limit. Every
# returned reaction is also scored by the other library's fc3d_compute_error. Results go to a CSV
# (one row per run) and src/bin/compare_report.rs turns it into a report.
#
#   bash scripts/compare-siconos.sh            # full comparison (all 3D local problems, 6 local solvers)
#   bash scripts/compare-siconos.sh --quick    # CI agreement check: 6 small problems, 500/565 and 500/552
#
# Options (lists are comma- or space-separated; $DATA is $FC3D_SICONOS_DATA, default ../shared/data/siconos):
#   --problems LIST    names in $DATA (with or without .dat) or paths to .dat files
#                      (default: every 3D local problem of $DATA; --quick: 6 small ones)
#   --solvers LIST     a solver id, or 500/<local id>, each optionally followed by ":i<k>=<v>" /
#                      ":d<k>=<v>" settings, e.g. 507 or 506:i10=1 (default: 500/565,500/550,500/551,
#                      500/552,500/553,500/557; --quick: 500/565,500/552)
#   --tols LIST        tolerances (default 1e-8)
#   --reps N           timed repetitions, median reported (default 3; --quick: 1)
#   --max-iter N       iteration limit (default 100000)
#   --timeout S        cap on each solve process, recorded as "timeout" (default 60)
#   --rep-budget S     repeat a solve only while the time spent plus its longest repetition stays
#                      within S seconds, so long solves get fewer repetitions (default: timeout / 2)
#   --out FILE         the CSV (default target/compare-siconos/{full,quick}.csv; the report is
#                      written next to it with the extension .txt)
#   --check / --no-check   exit non-zero when the libraries disagree (default: on with --quick)
#
# Environment: FC3D_COMPARE_LIB=<path>: test that libfc3d.so (e.g. an earlier commit's build)
# instead of the tree's.
#
# CSV columns: problem, solver, tol, library, info, iterations, error_self, error_by_other, seconds,
# reps, error_self_rescored. info is the driver's return code, or timeout / crash:<signal> / failed.
# error_self is the library's own dparam[1]; error_by_other the other library's fc3d_compute_error
# of the returned reaction; error_self_rescored the library's fc3d_compute_error of it (a check
# that dparam[1] measures the returned iterate); seconds the median fc3d_driver time.
set -euo pipefail
cd "$(dirname "$0")/.."
DATA=${FC3D_SICONOS_DATA:-../shared/data/siconos}

quick=0 check="" problems="" solvers="" tols="" reps="" max_iter=100000 cap=60 rep_budget="" out=""
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) quick=1 ;;
    --problems) problems=$2; shift ;;
    --solvers) solvers=$2; shift ;;
    --tols) tols=$2; shift ;;
    --reps) reps=$2; shift ;;
    --max-iter) max_iter=$2; shift ;;
    --timeout) cap=$2; shift ;;
    --rep-budget) rep_budget=$2; shift ;;
    --out) out=$2; shift ;;
    --check) check=1 ;;
    --no-check) check=0 ;;
    -h|--help) sed -n '2,34p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
  shift
done

if [ $quick = 1 ]; then
  : "${problems:=Rover1039 Rover4396 Confeti-ex13-Fc3D-SBM OneObject-i1028-138.hdf5 NESpheres_10_1 FC3D_Example1_SBM}"
  : "${solvers:=500/565 500/552}"
  : "${reps:=1}"
  : "${check:=1}"
  : "${out:=target/compare-siconos/quick.csv}"
else
  if [ -z "$problems" ]; then
    problems=$(cd "$DATA" && ls -- *.dat | grep -v -E '^(GFC3D_|gfc2d_|fc2d_|FC2D_|FrictionContactProblem|ACinputs)')
  fi
  : "${solvers:=500/565 500/550 500/551 500/552 500/553 500/557}"
  : "${reps:=3}"
  : "${check:=0}"
  : "${out:=target/compare-siconos/full.csv}"
fi
: "${tols:=1e-8}"
: "${rep_budget:=$(awk -v c="$cap" 'BEGIN { print c / 2 }')}"
read -r -a problems <<<"$(echo "$problems" | tr ",\n" "  ")"
read -r -a solvers <<<"$(echo "$solvers" | tr ",\n" "  ")"
read -r -a tols <<<"$(echo "$tols" | tr ",\n" "  ")"

# Builds libfc3d, the report and bench/siconos_compare.c against both libraries into $BUILD.
# shellcheck source=scripts/siconos-harness.sh
. scripts/siconos-harness.sh compare_report
export FC3D_COMPARE_REP_BUDGET=$rep_budget

paths=()
for p in "${problems[@]}"; do
  if [ -f "$p" ]; then paths+=("$p")
  elif [ -f "$DATA/$p" ]; then paths+=("$DATA/$p")
  elif [ -f "$DATA/$p.dat" ]; then paths+=("$DATA/$p.dat")
  else echo "no problem file $p (looked in $DATA)" >&2; exit 2
  fi
done

mkdir -p "$(dirname "$out")"
echo "problem,solver,tol,library,info,iterations,error_self,error_by_other,seconds,reps,error_self_rescored" >"$out"

# solve <library> <path> <solver> <tol>: sets R_<library>_* fields and writes $BUILD/r_<library>.
declare -A R
solve() {
  local lib=$1 path=$2 solver=$3 tol=$4 line rc=0
  rm -f "$BUILD/r_$lib"
  timeout -k 5 "$cap" "$BUILD/$lib" solve "$path" "$solver" "$tol" "$max_iter" "$reps" "$BUILD/r_$lib" \
    >"$BUILD/out_$lib" 2>"$BUILD/err_$lib" || rc=$?
  # Siconos prints its warnings to stdout: keep the result line only.
  line=$(grep -a '^info ' "$BUILD/out_$lib" | tail -n 1 || true)
  R[$lib.iter]="" R[$lib.err]="" R[$lib.sec]="" R[$lib.reps]="" R[$lib.rescored]="" R[$lib.other]=""
  if { [ $rc = 0 ] || [ $rc = 3 ]; } && [ -z "$line" ]; then rc=1; fi
  if [ $rc = 0 ] || [ $rc = 3 ]; then
    # info I iterations K error E seconds S self_score F reps N
    read -r _ R[$lib.info] _ R[$lib.iter] _ R[$lib.err] _ R[$lib.sec] _ R[$lib.rescored] _ R[$lib.reps] <<<"$line"
  elif [ $rc = 124 ] || [ $rc = 137 ]; then
    R[$lib.info]=timeout
  elif [ $rc -gt 128 ]; then
    R[$lib.info]=crash:$(kill -l $((rc - 128)) 2>/dev/null || echo $((rc - 128)))
  else
    R[$lib.info]=failed
  fi
  if [ $rc != 0 ] && [ $rc != 3 ]; then
    echo "   $lib: ${R[$lib.info]} (exit $rc): $(tail -c 300 "$BUILD/err_$lib" | tr '\n' ' ')" >&2
  fi
}

# score <scorer> <solution-owner> <path>: the scorer library's error of the owner's reaction.
score() {
  local scorer=$1 owner=$2 path=$3 line
  [ -s "$BUILD/r_$owner" ] || return 0
  if line=$(timeout -k 5 "$cap" "$BUILD/$scorer" score "$path" "$BUILD/r_$owner" 2>>"$BUILD/err_$scorer"); then
    line=$(grep -a '^error ' <<<"$line" | tail -n 1 || true)
    R[$owner.other]=${line#error }
  fi
}

row() {
  local name=$1 solver=$2 tol=$3 lib=$4
  echo "$name,$solver,$tol,$lib,${R[$lib.info]},${R[$lib.iter]},${R[$lib.err]},${R[$lib.other]},${R[$lib.sec]},${R[$lib.reps]},${R[$lib.rescored]}" >>"$out"
}

total=$(( ${#paths[@]} * ${#solvers[@]} * ${#tols[@]} ))
echo "== $total comparisons (${#paths[@]} problems x ${#solvers[@]} solvers x ${#tols[@]} tolerances), reps $reps," \
  "max_iter $max_iter, timeout ${cap}s, repetition budget ${rep_budget}s -> $out"
start=$SECONDS count=0
for path in "${paths[@]}"; do
  name=$(basename "$path" .dat)
  for solver in "${solvers[@]}"; do
    for tol in "${tols[@]}"; do
      count=$((count + 1))
      # Alternate which library goes first, so that slow phases of the machine hit both.
      if [ $((count % 2)) = 1 ]; then order=(fc3d siconos); else order=(siconos fc3d); fi
      for lib in "${order[@]}"; do solve "$lib" "$path" "$solver" "$tol"; done
      score siconos fc3d "$path"
      score fc3d siconos "$path"
      row "$name" "$solver" "$tol" fc3d
      row "$name" "$solver" "$tol" siconos
      printf '[%3d/%d %5ds] %-32s %-8s %-6s fc3d: %-7s %6s it %9.3gs | siconos: %-7s %6s it %9.3gs\n' \
        "$count" "$total" $((SECONDS - start)) "$name" "$solver" "$tol" \
        "${R[fc3d.info]}" "${R[fc3d.iter]:--}" "${R[fc3d.sec]:-0}" \
        "${R[siconos.info]}" "${R[siconos.iter]:--}" "${R[siconos.sec]:-0}"
    done
  done
done
echo "== done in $((SECONDS - start)) s: $out"

report_args=("$out")
[ "$check" = 1 ] && report_args+=(--check)
report="${out%.csv}.txt"
set +e
"$BUILD/compare_report" "${report_args[@]}" >"$report"
status=$?
set -e
cat "$report"
echo "(report saved to $report)"
exit $status

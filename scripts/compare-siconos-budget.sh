#!/usr/bin/env bash
# AUTO (fc3d id 590) against Siconos Numerics 4.4's friction solvers at equal time budget, through
# the C program of scripts/compare-siconos.sh (bench/siconos_compare.c, compiled against fc3d and
# against the installed Siconos). src/bin/budget_report.rs turns the CSV into the report.
#
#   bash scripts/compare-siconos-budget.sh                       # 30 problems, 29 Siconos solvers, 1ms..1s
#   bash scripts/compare-siconos-budget.sh --budgets 1ms,10ms,100ms --problems Capsules-i101-404
#
# Equal budget, defined in Siconos' favour (Siconos' solvers have no time budget):
# - each Siconos solver runs with the iteration limits 1, 2, 4, 8, ... (ladder mode of the C
#   program): every run from r = u = 0 with fresh options (tolerance --tol, default 1e-14), the
#   whole fc3d_driver call timed (set-up included, CLOCK_MONOTONIC), the median of up to --reps
#   repetitions; then per budget one more run whose limit aims at 95% of the budget. For each
#   budget the solver's result is its smallest error among the runs whose median time is within
#   the budget, chosen after the fact;
# - AUTO runs once per budget in budget mode (anytime mode of the C program): tolerance 0, no
#   iteration limit, dparam[FC3D_DPARAM_TIME_BUDGET] = the budget, cold start, timed the same way.
#   A run whose median time exceeds the budget does not count: it is run again with the budget
#   given to AUTO scaled down (0.9 b / t), up to 4 times; if none fits, AUTO has no result;
# - every final reaction is scored by one error function, fc3d's fc3d_compute_error (the error
#   (133) of Acary-Bremond-Huber, normalised by ||q||); Siconos' fc3d_compute_error of the same
#   reaction is the cross-check (both in the CSV; the report gives the largest difference).
#
# Options (lists comma- or space-separated; $DATA is $FC3D_SICONOS_DATA, default ../shared/data/siconos):
#   --problems LIST    names in $DATA (with or without .dat) or paths (default: every 3D local problem)
#   --solvers LIST     Siconos solvers (specs of siconos_compare.c: <id>, 500/<local id>, ...;
#                      default: NSGS with each of its 12 local solvers and every other 3D id of
#                      fc3d_driver but GAMS: 29 solvers)
#   --fc3d-solvers LIST  fc3d solvers run in budget mode (default 590: AUTO). Any fc3d id works
#                      (every fc3d solver honours the budget), e.g. 590,500/551,502,523
#   --budgets LIST     with unit us, ms or s (default 1ms,10ms,100ms,1s)
#   --tol X            Siconos' tolerance in the ladder (default 1e-14)
#   --reps N           repetitions of a timed run, median kept (default 3)
#   --rep-budget S     repeat a run only while the time spent plus its longest repetition stays
#                      within S seconds (default 0.1: runs over 50 ms are timed once)
#   --timeout S        cap of one ladder process (default 20 x the largest budget + 30 s)
#   --tie X            errors <= X count as equal in the report (default 1e-14)
#   --siconos-from CSV take Siconos' rows from an earlier run's CSV (same problems and budgets)
#                      instead of running Siconos again: re-measures fc3d's side only
#   --out FILE         the CSV (default target/compare-siconos/budget.csv; report next to it, .txt,
#                      and the picture, .svg)
#
# CSV columns: problem, library, solver, budget_s, info, iterations, limit, seconds, error_fc3d,
# error_siconos. One row per (problem, solver, budget): the run kept for that budget, its
# reaction scored by fc3d's and by Siconos' fc3d_compute_error. info is the driver's return code
# of that run, or none (no run within the budget), timeout, crash:<signal>, failed (then the
# other columns are empty). limit is the iteration limit of the kept run (ladder) or the budget
# given to the solver in ns (budget mode).
set -euo pipefail
cd "$(dirname "$0")/.."
DATA=${FC3D_SICONOS_DATA:-../shared/data/siconos}

problems="" solvers="" fc3d_solvers=590 budgets=1ms,10ms,100ms,1s tol=1e-14 reps=3 rep_budget=0.1
cap="" tie=1e-14 out=target/compare-siconos/budget.csv siconos_from=""
while [ $# -gt 0 ]; do
  case "$1" in
    --problems) problems=$2; shift ;;
    --solvers) solvers=$2; shift ;;
    --fc3d-solvers) fc3d_solvers=$2; shift ;;
    --budgets) budgets=$2; shift ;;
    --tol) tol=$2; shift ;;
    --reps) reps=$2; shift ;;
    --rep-budget) rep_budget=$2; shift ;;
    --timeout) cap=$2; shift ;;
    --tie) tie=$2; shift ;;
    --out) out=$2; shift ;;
    --siconos-from) siconos_from=$2; shift ;;
    -h|--help) awk 'NR > 1 && /^set -euo/ { exit } NR > 1' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
  shift
done

if [ -z "$problems" ]; then
  problems=$(cd "$DATA" && ls -- *.dat | grep -v -E '^(GFC3D_|gfc2d_|fc2d_|FC2D_|FrictionContactProblem|ACinputs)')
fi
: "${solvers:=500/550 500/551 500/565 500/552 500/553 500/554 500/555 500/557 500/564 500/561 500/562 500/563
  501 502 503 504 505 506 507 508 511 512 513 516 517 520 521 522 523}"
read -r -a problems <<<"$(echo "$problems" | tr ",\n" "  ")"
read -r -a solvers <<<"$(echo "$solvers" | tr ",\n" "  ")"
read -r -a fc3d_solvers <<<"$(echo "$fc3d_solvers" | tr ",\n" "  ")"
read -r -a budget_list <<<"$(echo "$budgets" | tr ",\n" "  ")"

# Budgets in seconds (the C program's unit).
seconds=()
for b in "${budget_list[@]}"; do
  s=$(awk -v b="$b" 'BEGIN {
    if (b ~ /us$/) v = substr(b, 1, length(b) - 2) * 1e-6
    else if (b ~ /ms$/) v = substr(b, 1, length(b) - 2) * 1e-3
    else if (b ~ /s$/) v = substr(b, 1, length(b) - 1) + 0
    else v = -1
    if (v > 0) printf "%.9g", v }')
  [ -n "$s" ] || { echo "budget $b: give a number with unit us, ms or s" >&2; exit 2; }
  seconds+=("$s")
done
budget_arg=$(IFS=,; echo "${seconds[*]}")
largest=$(printf '%s\n' "${seconds[@]}" | sort -g | tail -n 1)
: "${cap:=$(awk -v l="$largest" 'BEGIN { print int(20 * l + 30) }')}"

# Builds $BUILD/fc3d, $BUILD/siconos and $BUILD/budget_report.
# shellcheck source=scripts/siconos-harness.sh
. scripts/siconos-harness.sh budget_report
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
echo "problem,library,solver,budget_s,info,iterations,limit,seconds,error_fc3d,error_siconos" >"$out"

# run <library> <mode> <path> <solver> <tol> <name>: one ladder or budget-mode process, then
# one CSV row per budget, the kept reaction scored by both libraries.
run() {
  local lib=$1 mode=$2 path=$3 solver=$4 solver_tol=$5 name=$6 rc=0 other j line status
  rm -f "$BUILD"/r.*
  timeout -k 5 "$cap" "$BUILD/$lib" "$mode" "$path" "$solver" "$solver_tol" "$budget_arg" "$reps" "$BUILD/r" \
    >"$BUILD/out" 2>"$BUILD/err" || rc=$?
  if [ $rc = 124 ] || [ $rc = 137 ]; then status=timeout
  elif [ $rc -gt 128 ]; then status=crash:$(kill -l $((rc - 128)) 2>/dev/null || echo $((rc - 128)))
  elif [ $rc != 0 ]; then status=failed
  else status=none
  fi
  if [ $rc != 0 ]; then
    echo "   $lib $solver on $name: $status (exit $rc): $(tail -c 200 "$BUILD/err" | tr '\n' ' ')" >&2
  fi
  other=siconos; [ "$lib" = siconos ] && other=fc3d
  for j in "${!seconds[@]}"; do
    # best <j> budget <b> max_iter <k> info <i> iterations <it> score <e> seconds <t>
    line=$(grep -a "^best $j " "$BUILD/out" | tail -n 1 || true)
    if [ -z "$line" ] || [ ! -s "$BUILD/r.$j" ]; then
      echo "$name,$lib,$solver,${seconds[$j]},$status,,,,," >>"$out"
      continue
    fi
    local f_info f_iter f_limit f_err f_sec s_other
    read -r _ _ _ _ _ f_limit _ f_info _ f_iter _ f_err _ f_sec <<<"$line"
    s_other=$("$BUILD/$other" score "$path" "$BUILD/r.$j" 2>/dev/null | grep -a '^error ' | tail -n 1 || true)
    s_other=${s_other#error }
    if [ "$lib" = fc3d ]; then
      echo "$name,$lib,$solver,${seconds[$j]},$f_info,$f_iter,$f_limit,$f_sec,$f_err,$s_other" >>"$out"
    else
      echo "$name,$lib,$solver,${seconds[$j]},$f_info,$f_iter,$f_limit,$f_sec,$s_other,$f_err" >>"$out"
    fi
  done
}

total=$(( ${#paths[@]} * (${#solvers[@]} + ${#fc3d_solvers[@]}) ))
echo "== $total runs (${#paths[@]} problems x (${#fc3d_solvers[@]} fc3d + ${#solvers[@]} Siconos solvers))," \
  "budgets ${budget_list[*]}, reps $reps (rep budget ${rep_budget}s), Siconos tol $tol, cap ${cap}s -> $out"
start=$SECONDS count=0
for path in "${paths[@]}"; do
  name=$(basename "$path" .dat)
  for solver in "${fc3d_solvers[@]}"; do
    count=$((count + 1))
    run fc3d anytime "$path" "$solver" 0 "$name"
  done
  if [ -n "$siconos_from" ]; then
    grep -a "^$name,siconos," "$siconos_from" >>"$out" || echo "   no Siconos rows for $name in $siconos_from" >&2
  else
    for solver in "${solvers[@]}"; do
      count=$((count + 1))
      run siconos ladder "$path" "$solver" "$tol" "$name"
    done
  fi
  printf '[%4d/%d %5ds] %s\n' "$count" "$total" $((SECONDS - start)) "$name"
done
echo "== done in $((SECONDS - start)) s: $out"

report="${out%.csv}.txt"
"$BUILD/budget_report" "$out" --tie "$tie" --svg "${out%.csv}.svg" >"$report"
cat "$report"
echo "(report saved to $report, picture ${out%.csv}.svg)"

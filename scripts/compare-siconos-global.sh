#!/usr/bin/env bash
# Global problems side by side with Siconos Numerics 4.4: bench/gfc3d_compare.c is compiled twice,
# against fc3d's compat headers (-lfc3d) and against the installed Siconos (-lsiconos_numerics);
# both binaries solve the same global problems with the same ids, tolerance and iteration limit,
# alternating which library goes first, and each returned (r, v) is also scored by the other
# library's gfc3d_compute_error on a fresh copy of the problem. Writes a CSV (one row per run) and
# a Markdown table (time per id and problem, the ratio fc3d / Siconos, the geometric mean of the
# ratios over the runs of 1 ms or more where both converged).
#
#   bash scripts/compare-siconos-global.sh [--problems LIST] [--solvers LIST] [--tol T]
#        [--max-iter N] [--reps N] [--timeout S] [--scenes LIST] [--out FILE]
#
#   --problems LIST  global .dat names in $DATA (default: GFC3D_Example0 Example00 Example1
#                    OneContact TwoRods1) or paths
#   --scenes LIST    generated scenes written as global .dat by `fc3d scene --global` (specs
#                    `contacts=N,shape=spheres|boxes`, default: 1000 spheres and 1000 boxes; "none"
#                    for none)
#   --solvers LIST   global ids, each optionally with ":i<k>=<v>" / ":d<k>=<v>" settings
#                    (default: 600 602 603 604 605 606 607 610 611 612 613 614 615)
#   --tol T          tolerance (default 1e-6); --max-iter N (default 10000); --reps N (default 5,
#                    median); --timeout S per process (default 60)
#   --out FILE       the CSV (default target/compare-siconos-global/results.csv; the table is
#                    written next to it with the extension .md, the per-id summary of
#                    scripts/siconos-global-summary.py as -summary.md)
# CSV columns: problem, solver, library, info, iterations, error_self, error_by_other, seconds,
# reps, self_score (this library's gfc3d_compute_error of its own result on a fresh copy).
set -euo pipefail
cd "$(dirname "$0")/.."
DATA=${FC3D_SICONOS_DATA:-../shared/data/siconos}
problems="GFC3D_Example0 GFC3D_Example00 GFC3D_Example1 GFC3D_OneContact GFC3D_TwoRods1"
scenes="contacts=1000,shape=spheres contacts=1000,shape=boxes"
solvers="600 602 603 604 605 606 607 610 611 612 613 614 615"
tol=1e-6 max_iter=10000 reps=5 cap=60 out=target/compare-siconos-global/results.csv
while [ $# -gt 0 ]; do
  case "$1" in
    --problems) problems=$2; shift ;;
    --scenes) scenes=$2; shift ;;
    --solvers) solvers=$2; shift ;;
    --tol) tol=$2; shift ;;
    --max-iter) max_iter=$2; shift ;;
    --reps) reps=$2; shift ;;
    --timeout) cap=$2; shift ;;
    --out) out=$2; shift ;;
    -h|--help) sed -n '2,26p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
  shift
done
[ "$scenes" = none ] && scenes=""
read -r -a problems <<<"$(echo "$problems" | tr ",\n" "  ")"
read -r -a scenes <<<"$(echo "$scenes" | tr "\n" " ")"
read -r -a solvers <<<"$(echo "$solvers" | tr ",\n" "  ")"

[ -f /usr/include/siconos/numerics/GlobalFrictionContactProblem.h ] || {
  echo "compare-siconos-global: needs libsiconos-numerics-dev (the reference library)" >&2; exit 2; }
echo "== building libfc3d, the fc3d command and the two benchmark binaries"
cargo build --release -p fc3d -p fc3d-cli
BUILD=$(mktemp -d)
trap 'rm -rf "$BUILD"' EXIT
cp target/release/libfc3d.so "$BUILD/libfc3d.so.0"
ln -s libfc3d.so.0 "$BUILD/libfc3d.so"
CFLAGS=(-std=c99 -O2 -Wall -Wextra -Werror)
cc "${CFLAGS[@]}" -Icapi/include/siconos-compat -Icapi/include bench/gfc3d_compare.c -L"$BUILD" -lfc3d -lm \
  -o "$BUILD/fc3d"
cc "${CFLAGS[@]}" -I/usr/include/siconos/numerics -I/usr/include/siconos bench/gfc3d_compare.c \
  -lsiconos_numerics -lm -o "$BUILD/siconos"
export LD_LIBRARY_PATH="$BUILD${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1
export FC3D_COMPARE_REP_BUDGET=$((cap / 2))

paths=()
for p in "${problems[@]}"; do
  if [ -f "$p" ]; then paths+=("$p")
  elif [ -f "$DATA/$p.dat" ]; then paths+=("$DATA/$p.dat")
  else echo "no problem file $p (looked in $DATA)" >&2; exit 2
  fi
done
for spec in "${scenes[@]}"; do
  file="$BUILD/scene-$(echo "$spec" | tr ',=' '__').dat"
  target/release/fc3d scene "$spec" --global -o "$file" >/dev/null
  paths+=("$file")
done

mkdir -p "$(dirname "$out")"
echo "problem,solver,library,info,iterations,error_self,error_by_other,seconds,reps,self_score" >"$out"
declare -A R
solve() {
  local lib=$1 path=$2 solver=$3 line rc=0
  rm -f "$BUILD/r_$lib"
  timeout -k 5 "$cap" "$BUILD/$lib" solve "$path" "$solver" "$tol" "$max_iter" "$reps" "$BUILD/r_$lib" \
    >"$BUILD/out_$lib" 2>"$BUILD/err_$lib" || rc=$?
  line=$(grep -a '^info ' "$BUILD/out_$lib" | tail -n 1 || true)
  R[$lib.iter]="" R[$lib.err]="" R[$lib.sec]="" R[$lib.reps]="" R[$lib.self]="" R[$lib.other]=""
  if { [ $rc = 0 ] || [ $rc = 3 ]; } && [ -n "$line" ]; then
    read -r _ R[$lib.info] _ R[$lib.iter] _ R[$lib.err] _ R[$lib.sec] _ R[$lib.self] _ R[$lib.reps] <<<"$line"
  elif [ $rc = 124 ] || [ $rc = 137 ]; then R[$lib.info]=timeout
  elif [ $rc -gt 128 ]; then R[$lib.info]=crash:$(kill -l $((rc - 128)) 2>/dev/null || echo $((rc - 128)))
  else R[$lib.info]=failed
  fi
}
score() {
  local scorer=$1 owner=$2 path=$3 line
  [ -s "$BUILD/r_$owner" ] || return 0
  if line=$(timeout -k 5 "$cap" "$BUILD/$scorer" score "$path" "$BUILD/r_$owner" 2>/dev/null); then
    line=$(grep -a '^error ' <<<"$line" | tail -n 1 || true)
    R[$owner.other]=${line#error }
  fi
}
count=0
total=$(( ${#paths[@]} * ${#solvers[@]} ))
for path in "${paths[@]}"; do
  name=$(basename "$path" .dat)
  for solver in "${solvers[@]}"; do
    count=$((count + 1))
    if [ $((count % 2)) = 1 ]; then order=(fc3d siconos); else order=(siconos fc3d); fi
    for lib in "${order[@]}"; do solve "$lib" "$path" "$solver"; done
    score siconos fc3d "$path"
    score fc3d siconos "$path"
    for lib in fc3d siconos; do
      echo "$name,$solver,$lib,${R[$lib.info]},${R[$lib.iter]},${R[$lib.err]},${R[$lib.other]},${R[$lib.sec]},${R[$lib.reps]},${R[$lib.self]}" >>"$out"
    done
    printf '[%3d/%d] %-28s %-6s fc3d: %-8s %7s it %10.3gs | siconos: %-8s %7s it %10.3gs\n' "$count" "$total" \
      "$name" "$solver" "${R[fc3d.info]}" "${R[fc3d.iter]:--}" "${R[fc3d.sec]:-0}" \
      "${R[siconos.info]}" "${R[siconos.iter]:--}" "${R[siconos.sec]:-0}"
  done
done

# The table: one row per (problem, id); the geometric mean of the time ratios over the rows where
# both libraries converged (info 0) and Siconos took 1 ms or more.
table="${out%.csv}.md"
awk -F, -v tol="$tol" '
  NR == 1 { next }
  { key = $1 "," $2; lib = $3; info[key, lib] = $4; it[key, lib] = $5; sec[key, lib] = $8;
    err[key, lib] = ($10 != "" ? $10 : "-"); other[key, lib] = ($7 != "" ? $7 : "-");
    if (!(key in seen)) { seen[key] = 1; keys[++n] = key } }
  END {
    printf "Tolerance %s. Time: median of the repetitions (s); error: each library'"'"'s gfc3d_compute_error of its own (r, u, v) on a fresh copy, then scored by the other library.\n\n", tol
    print "| problem | id | fc3d info | fc3d it. | fc3d time | fc3d error (by Siconos) | Siconos info | Siconos it. | Siconos time | Siconos error (by fc3d) | fc3d / Siconos |"
    print "| --- | --- | --- | ---: | ---: | --- | --- | ---: | ---: | --- | ---: |"
    for (k = 1; k <= n; k++) {
      key = keys[k]; split(key, p, ",")
      ratio = "-"
      if (sec[key, "fc3d"] != "" && sec[key, "siconos"] > 0) {
        r = sec[key, "fc3d"] / sec[key, "siconos"]; ratio = sprintf("%.2f", r)
        if (info[key, "fc3d"] == "0" && info[key, "siconos"] == "0" && sec[key, "siconos"] >= 1e-3) { logs += log(r); m++ }
      }
      printf "| %s | %s | %s | %s | %s | %s (%s) | %s | %s | %s | %s (%s) | %s |\n", p[1], p[2],
        info[key, "fc3d"], it[key, "fc3d"], sec[key, "fc3d"], err[key, "fc3d"], other[key, "fc3d"],
        info[key, "siconos"], it[key, "siconos"], sec[key, "siconos"], err[key, "siconos"], other[key, "siconos"], ratio
    }
    if (m > 0) printf "\nGeometric mean of fc3d / Siconos over the %d runs of 1 ms or more that both converged: %.3f\n", m, exp(logs / m)
  }' "$out" >"$table"
cat "$table"
summary="${out%.csv}-summary.md"
if command -v python3 >/dev/null; then
  python3 scripts/siconos-global-summary.py "$out" "$tol" >"$summary"
  echo "(CSV $out, table $table, per-id summary $summary)"
else
  echo "(CSV $out, table $table; python3 scripts/siconos-global-summary.py $out gives the per-id summary)"
fi

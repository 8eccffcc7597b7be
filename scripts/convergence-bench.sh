#!/usr/bin/env bash
# Convergence at scale (issue 27 item 7; docs/convergence.md, "Convergence at scale"): time to
# each tolerance per method and size on the generated sphere and box piles, fc3d's methods and
# Siconos Numerics 4.4's solvers side by side in the same run, and a settling sequence solved
# step by step warm-started through the workspace. Not CI-timed (tens of minutes with the
# defaults); scripts/test-all.sh runs `--quick` through cli/tests/convergence_bench.rs.
#
#   bash scripts/convergence-bench.sh                                 # the table and the sequence
#   bash scripts/convergence-bench.sh --sizes 1000 --methods NSGS,TFP --no-settling
#   bash scripts/convergence-bench.sh --quick                         # seconds: the harness works
#   bash scripts/convergence-bench.sh --no-table --settling 35000:63 \
#        --settling-methods TFP,AUTO,NSGS_HFORM --settling-every 0      # 10^5 contacts (hours)
#
# Table: one process per (scene, method) and per (scene, Siconos id, tolerance), so that each
# run's peak memory is its own. fc3d: `convergence_bench solve` (cli/src/bin), one solve from
# r = 0 per tolerance cut by the budget (the solver's own wall-clock budget); Siconos:
# bench/scale.c `solve` linked against the installed libsiconos_numerics, one process per
# tolerance cut by `timeout` at the same budget. For both, the time is the CPU time of the call
# (set-up included) and the memory the peak the call adds to the process once the problem is
# in memory; a tighter tolerance is not run once a looser one was not reached. Siconos' best id
# per scene and tolerance is marked in the report.
# Settling: `convergence_bench settling` (pile_settling_in_bin: spheres dropped into a square bin),
# every step solved to --settling-tol through one fc3d Workspace (warm start by contact id), per
# fc3d method; every --settling-every-th step of the first method's run is written as .dat and
# solved from r = 0 (cold) by Siconos' ids and by the same fc3d methods. A global method
# (NSGS_HFORM or 691, ...) runs the sequence in the global form (M and H given,
# pile_settling_in_bin_global), warm-started by contact id; it writes no .dat files (list a
# local method first, or --settling-every 0).
#
# Options (lists comma-separated):
#   --shapes LIST          spheres,boxes (default both)
#   --sizes LIST           contact counts (default 1000,10000)
#   --piles P --seed S     scene generator (default 4 piles, seed 1)
#   --methods LIST         fc3d methods by name or id, local or global (a global one runs on the
#                          global form, GeneratedScene::generate_global)
#                          (default NSGS,TFP,TFP-APGD,ACLMFP-APGD,NSN-AC,ADMM,AUTO)
#   --siconos LIST         Siconos ids (default 500,503,504,523: NSGS, TFP, NSN-AC, ADMM; "" none)
#   --tols LIST            tolerances (default 1e-4,1e-6)
#   --budget S             wall-clock budget of each run, seconds (default 30)
#   --mem-limit-gb G       address-space limit of each run (default 8; 0: none)
#   --no-table / --no-settling
#   --settling N:K         N spheres in a K x K bin (default 3500:20, about 10^4 contacts at rest;
#                          35000:63 gives about 1.07 x 10^5)
#   --settling-steps S     steps (default 200)
#   --settling-methods L   fc3d methods of the sequence, local or global (default AUTO,TFP)
#   --settling-tol T       tolerance of every step (default 1e-4)
#   --settling-budget S    wall-clock budget of each step (default 5)
#   --settling-every K     write every K-th step for the cold comparison (default 40; 0: none)
#   --settling-siconos L   Siconos ids of the cold comparison (default 500,503)
#   --out DIR              results (default target/convergence-bench): results.csv, settling.csv,
#                          steps-*.csv, cold-steps.csv, report.md
#   --quick                tiny: spheres, 100 contacts, NSGS, 1e-4, 2 s, Siconos 500, settling of
#                          40 spheres in a 4 x 4 bin for 3 steps (the CI check of the harness)
set -euo pipefail
cd "$(dirname "$0")/.."

shapes=spheres,boxes sizes=1000,10000 piles=4 seed=1
methods=NSGS,TFP,TFP-APGD,ACLMFP-APGD,NSN-AC,ADMM,AUTO siconos=500,503,504,523
tols=1e-4,1e-6 budget=30 mem_gb=8 table=1 settling=1
settle=3500:20 settle_steps=200 settle_methods=AUTO,TFP settle_tol=1e-4 settle_budget=5
settle_every=40 settle_siconos=500,503 out=target/convergence-bench
while [ $# -gt 0 ]; do
  case "$1" in
    --shapes) shapes=$2; shift ;;
    --sizes) sizes=$2; shift ;;
    --piles) piles=$2; shift ;;
    --seed) seed=$2; shift ;;
    --methods) methods=$2; shift ;;
    --siconos) siconos=$2; shift ;;
    --tols) tols=$2; shift ;;
    --budget) budget=$2; shift ;;
    --mem-limit-gb) mem_gb=$2; shift ;;
    --no-table) table=0 ;;
    --no-settling) settling=0 ;;
    --settling) settle=$2; shift ;;
    --settling-steps) settle_steps=$2; shift ;;
    --settling-methods) settle_methods=$2; shift ;;
    --settling-tol) settle_tol=$2; shift ;;
    --settling-budget) settle_budget=$2; shift ;;
    --settling-every) settle_every=$2; shift ;;
    --settling-siconos) settle_siconos=$2; shift ;;
    --out) out=$2; shift ;;
    --quick)
      shapes=spheres sizes=100 methods=NSGS siconos=500 tols=1e-4 budget=2
      settle=40:4 settle_steps=3 settle_methods=NSGS settle_budget=2 settle_every=1
      settle_siconos=500 ;;
    -h|--help) sed -n '2,47p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
  shift
done
list() { tr ',' ' ' <<<"$1"; }

mkdir -p "$out/scenes" "$out/bin"
if [ -z "${FC3D_CONVERGENCE_BENCH_BIN:-}" ]; then
  echo "== building the fc3d command and convergence_bench"
  cargo build --release -p fc3d-cli --bin fc3d --bin convergence_bench
fi
bin_dir=${FC3D_CONVERGENCE_BENCH_BIN:-target/release}
bench=$bin_dir/convergence_bench fc3d=$bin_dir/fc3d
have_siconos=0
if [ -n "$siconos$settle_siconos" ] && [ -f /usr/include/siconos/numerics/SiconosNumerics.h ] \
  && cc -std=c99 -O2 -Wall -Wextra -Werror -I/usr/include/siconos/numerics -I/usr/include/siconos \
    bench/scale.c -lsiconos_numerics -lm -o "$out/bin/scale-siconos"; then
  have_siconos=1
else
  echo "== Siconos Numerics not installed (or no Siconos id asked): fc3d's rows only"
fi
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1

# Runs a command under the budget's wall-clock cap (plus room for reading/generating) and the
# memory limit; its status: 0, 124 (timeout) or another failure.
capped() {
  local cap=$1
  shift
  (
    if [ "$mem_gb" != 0 ]; then ulimit -v $((mem_gb * 1024 * 1024)); fi
    timeout -k 5 "$cap" "$@"
  )
}

# A Siconos solve of one .dat file to one tolerance, as a CSV row of convergence_bench's header.
siconos_row() { # columns-prefix file id tol
  local prefix=$1 file=$2 id=$3 tol=$4 line rc=0
  line=$(capped "$budget" "$out/bin/scale-siconos" solve "$file" "$id" 1000000 "$tol" 2>/dev/null) || rc=$?
  local load
  load=$(cut -d' ' -f1 /proc/loadavg)
  if [ $rc != 0 ] || [ -z "$line" ]; then
    local status=failed:$rc
    if [ $rc = 124 ] || [ $rc = 137 ]; then status=timeout; fi
    echo "$prefix,siconos,$id,$tol,$status,,$budget,,,,,,,,$load"
    return 1
  fi
  awk -v p="$prefix" -v id="$id" -v tol="$tol" -v load="$load" '{
    for (i = 1; i < NF; i += 2) v[$i] = $(i + 1)
    status = v["info"] == 0 ? "converged" : "info-" v["info"]
    # An NSGS sweep (500) reads W once: one product.
    printf "%s,siconos,%s,%s,%s,%.4f,%.4f,%s,%s,%.3e,,,%.1f,%.1f,%s\n", p, id, tol, status, v["cpu_s"],
      v["wall_s"], v["iterations"], id == 500 ? v["iterations"] : "-", v["error"], v["rss_after_read_kb"] / 1024,
      v["peak_solve_kb"] / 1024, load
  }' <<<"$line"
  awk '{ for (i = 1; i < NF; i += 2) if ($i == "info") exit ($(i + 1) == 0 ? 0 : 1) }' <<<"$line"
}

report=$out/report.md
: >"$report"
if [ "$table" = 1 ]; then
  csv=$out/results.csv
  "$bench" header >"$csv"
  for shape in $(list "$shapes"); do
    for n in $(list "$sizes"); do
      spec=contacts=$n,piles=$piles,seed=$seed,shape=$shape
      echo "== $shape, $n contacts (load $(cut -d' ' -f1-3 /proc/loadavg))"
      for m in $(list "$methods"); do
        ntols=$(list "$tols" | wc -w)
        rc=0
        capped $((ntols * (budget + 30) + 60)) "$bench" solve --scene "$spec" --method "$m" \
          --tols "$tols" --budget "$budget" >"$out/run.csv" 2>"$out/run.err" || rc=$?
        if [ $rc = 0 ]; then
          tee -a "$csv" <"$out/run.csv"
        else
          echo "   fc3d $m: failed ($rc): $(head -c 300 "$out/run.err")"
          echo "$shape,$n,$piles,$seed,fc3d,$m,$(list "$tols" | cut -d' ' -f1),failed:$rc,,,,,,,,,,$(cut -d' ' -f1 /proc/loadavg)" >>"$csv"
        fi
      done
      if [ "$have_siconos" = 1 ] && [ -n "$siconos" ]; then
        file=$out/scenes/$shape-c$n-p$piles-s$seed.dat
        [ -s "$file" ] || "$fc3d" scene --contacts "$n" --piles "$piles" --seed "$seed" --shape "$shape" -o "$file" >/dev/null
        for id in $(list "$siconos"); do
          for tol in $(list "$tols"); do
            siconos_row "$shape,$n,$piles,$seed" "$file" "$id" "$tol" | tee -a "$csv" | sed 's/^/   /' \
              && continue
            # A tolerance not reached: the tighter ones are not run.
            break
          done
        done
      fi
    done
  done
  echo "== $csv"
  {
    echo "## Time to tolerance ($(date -u '+%Y-%m-%d %H:%M UTC'), budget ${budget} s wall-clock a run)"
    echo
    "$bench" report --csv "$csv"
  } >>"$report"
fi

if [ "$settling" = 1 ]; then
  spheres=${settle%%:*} per_side=${settle##*:}
  scsv=$out/settling.csv
  "$bench" settling-header >"$scsv"
  first=1
  for m in $(list "$settle_methods"); do
    echo "== settling: $spheres spheres, ${per_side}x$per_side bin, $settle_steps steps, $m (load $(cut -d' ' -f1-3 /proc/loadavg))"
    dat=()
    if [ "$first" = 1 ] && [ "$settle_every" != 0 ]; then
      rm -rf "$out/steps" && dat=(--dat-dir "$out/steps" --dat-every "$settle_every")
    fi
    first=0
    capped $((settle_steps * (settle_budget + 5) + 300)) "$bench" settling --spheres "$spheres" \
      --per-side "$per_side" --steps "$settle_steps" --method "$m" --tol "$settle_tol" \
      --budget "$settle_budget" --steps-csv "$out/steps-$m.csv" "${dat[@]}" | tee -a "$scsv" \
      || echo "   settling with $m failed"
  done
  {
    echo
    echo "## Settling sequence ($(date -u '+%Y-%m-%d %H:%M UTC'), warm-started through the workspace, ${settle_budget} s wall-clock budget a step)"
    "$bench" report --settling "$scsv"
  } >>"$report"
  if [ -d "$out/steps" ]; then
    cold=$out/cold-steps.csv
    "$bench" header >"$cold"
    for file in "$out"/steps/*.dat; do
      for m in $(list "$settle_methods"); do
        capped $((settle_budget + 60)) "$bench" solve --scene "$file" --method "$m" \
          --tols "$settle_tol" --budget "$settle_budget" >>"$cold" || true
      done
      if [ "$have_siconos" = 1 ]; then
        name=$(basename "$file" .dat)
        nc=$(head -c 200 "$file" | awk 'NR == 2 { print $1 }')
        for id in $(list "$settle_siconos"); do
          budget=$settle_budget siconos_row "$name,$nc,," "$file" "$id" "$settle_tol" >>"$cold" || true
        done
      fi
    done
    {
      echo
      echo "## Steps of the sequence solved cold (every ${settle_every}th step of the first method's run, from r = 0, ${settle_budget} s a solve)"
      echo
      "$bench" report --csv "$cold"
    } >>"$report"
  fi
fi
echo "== $report"
cat "$report"

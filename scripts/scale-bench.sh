#!/usr/bin/env bash
# Scale benchmark: fc3d and Siconos Numerics 4.4 side by side on generated sphere piles from 1k to
# 500k contacts (`fc3d scene`, sparse-block W), through the same C program (bench/scale.c) linked
# against each library. Not CI-timed: a run takes minutes; run it on a quiet machine.
#
#   bash scripts/scale-bench.sh                       # default sizes, 4 piles, seed 1
#   bash scripts/scale-bench.sh --sizes 1000,10000 --timeout 60
#
# Per size and library, one process reads the .dat (peak RSS of the read alone), then measures
#   - per-call set-up and per-sweep time (CPU seconds of the process, robust on a shared machine): medians of fc3d_driver calls limited to 1 and 1 + SWEEPS (alternated)
#     sweeps (set-up = t(1) - one sweep: everything a call does besides its sweeps);
#   - peak RSS of the solving part alone (VmHWM reset after the read);
#   - time and sweeps to 1e-3, 1e-4, 1e-6 (NSGS with Siconos' defaults, 500 = local solver 565),
#     each tolerance continuing from the previous iterate, until the process time limit.
# The machine's streaming read bandwidth gives the floor of a sweep: the bytes a sweep must read
# (W's blocks and column indices, row pointers, q, r, mu) / bandwidth.
# Results: target/scale/results.csv, then target/scale/report.md and the picture
# docs/scale.svg (+ .png) drawn by the scale_report binary of the CLI crate.
#
# Options:
#   --sizes LIST     contact counts (default 1000,3000,10000,30000,100000,300000,500000)
#   --piles P        separate piles per scene (default 4)
#   --seed S         scene seed (default 1)
#   --solver ID      solver id for both libraries (default 500: NSGS)
#   --sweeps N       sweeps of the long timed call (default 10)
#   --reps N         repetitions of each timed call, median kept (default 3)
#   --tols LIST      tolerances (default 1e-3,1e-4,1e-6)
#   --max-iter N     sweep limit of the tolerance runs (default 1000000)
#   --timeout S      time limit of each process (default 120)
#   --libs LIST      fc3d,siconos (default both)
#   --threads N      also run fc3d's coloured NSGS on N threads (iparam[15] = 1, iparam[16] = N),
#                    rows "fc3d-coloured-Nt", timed in wall-clock seconds (CPU time would sum
#                    the threads; the CSV's clock column says which); default 0: no such rows
#   --in-place       also run fc3d through fc3d_driver_in_place (no copies of r and u): rows
#                    "fc3d-in-place"; with --threads N also "fc3d-in-place-coloured-Nt" (both)
set -euo pipefail
cd "$(dirname "$0")/.."

sizes=1000,3000,10000,30000,100000,300000,500000 piles=4 seed=1 solver=500 sweeps=10 reps=3
tols=1e-3,1e-4,1e-6 max_iter=1000000 cap=120 libs=fc3d,siconos threads=0 in_place=0
while [ $# -gt 0 ]; do
  case "$1" in
    --sizes) sizes=$2; shift ;;
    --piles) piles=$2; shift ;;
    --seed) seed=$2; shift ;;
    --solver) solver=$2; shift ;;
    --sweeps) sweeps=$2; shift ;;
    --reps) reps=$2; shift ;;
    --tols) tols=$2; shift ;;
    --max-iter) max_iter=$2; shift ;;
    --timeout) cap=$2; shift ;;
    --libs) libs=$2; shift ;;
    --threads) threads=$2; shift ;;
    --in-place) in_place=1 ;;
    -h|--help) sed -n '2,35p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
  shift
done
read -r -a sizes <<<"$(echo "$sizes" | tr ',' ' ')"
read -r -a tols <<<"$(echo "$tols" | tr ',' ' ')"
read -r -a libs <<<"$(echo "$libs" | tr ',' ' ')"
case "$threads" in ''|*[!0-9]*) echo "--threads needs a count" >&2; exit 2 ;; esac
# A run: its name in the results, the binary, and the options before the problem.
runs=()
for lib in "${libs[@]}"; do runs+=("$lib"); done
if [ "$threads" -gt 0 ]; then runs+=("fc3d-coloured-${threads}t"); fi
if [ "$in_place" = 1 ]; then runs+=("fc3d-in-place"); fi
if [ "$in_place" = 1 ] && [ "$threads" -gt 0 ]; then runs+=("fc3d-in-place-coloured-${threads}t"); fi

OUT=target/scale
mkdir -p "$OUT/scenes" "$OUT/bin"
echo "== building libfc3d, the fc3d command, scale_report and the two benchmark binaries"
cargo build --release -p fc3d
cargo build --release -p fc3d-cli --bins
cp target/release/libfc3d.so "$OUT/bin/libfc3d.so.0"
ln -sf libfc3d.so.0 "$OUT/bin/libfc3d.so"
CFLAGS=(-std=c99 -O2 -Wall -Wextra -Werror)
cc "${CFLAGS[@]}" -Icapi/include/siconos-compat -Icapi/include bench/scale.c -L"$OUT/bin" -lfc3d -lm \
  -o "$OUT/bin/scale-fc3d"
cc "${CFLAGS[@]}" -I/usr/include/siconos/numerics -I/usr/include/siconos bench/scale.c -lsiconos_numerics -lm \
  -o "$OUT/bin/scale-siconos"
export LD_LIBRARY_PATH="$PWD/$OUT/bin${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1

bandwidth=$("$OUT/bin/scale-fc3d" bandwidth 1024 | awk '{print $2}')
echo "== streaming read bandwidth: $bandwidth GB/s"

csv=$OUT/results.csv
tcols=$(printf 't_%s_s,' "${tols[@]}")
icols=$(printf 'it_%s,' "${tols[@]}")
echo "contacts,piles,library,clock,file_mb,blocks,rss_before_kb,peak_read_kb,rss_after_read_kb,peak_solve_kb,peak_converged_kb,sweep_s,setup_s,floor_s,$tcols${icols}status,bandwidth_gbs" >"$csv"
for n in "${sizes[@]}"; do
  file=$OUT/scenes/piles-c$n-p$piles-s$seed.dat
  if [ ! -s "$file" ]; then
    target/release/fc3d scene --contacts "$n" --piles "$piles" --seed "$seed" -o "$file"
  fi
  mb=$(awk -v b="$(stat -c %s "$file")" 'BEGIN { printf "%.1f", b / 1e6 }')
  for lib in "${runs[@]}"; do
    log=$OUT/run-$lib-$n.txt
    bin=$lib opts=()
    case "$lib" in
      fc3d-coloured-*) bin=fc3d opts=(--threads "$threads") ;;
      fc3d-in-place-coloured-*) bin=fc3d opts=(--threads "$threads" --in-place) ;;
      fc3d-in-place) bin=fc3d opts=(--in-place) ;;
    esac
    rc=0
    timeout -k 5 "$cap" "$OUT/bin/scale-$bin" setup "${opts[@]}" "$file" "$solver" "$sweeps" "$reps" "$max_iter" "${tols[@]}" \
      >"$log" 2>"$OUT/err-$lib-$n.txt" || rc=$?
    status=ok
    if [ $rc = 124 ] || [ $rc = 137 ]; then status=timeout; elif [ $rc != 0 ]; then status=failed:$rc; fi
    line=$(grep -a '^contacts ' "$log" || true)
    get() { awk -v k="$1" '{ for (i = 1; i < NF; i++) if ($i == k) print $(i + 1) }' <<<"$line"; }
    times=() its=()
    for t in "${tols[@]}"; do
      tl=$(grep -a "^tol $(awk -v t="$t" 'BEGIN { printf "%g", t }') info 0 " "$log" || true)
      times+=("$(awk '{print $10}' <<<"$tl")")
      its+=("$(awk '{print $6}' <<<"$tl")")
    done
    floor=""
    if [ -n "$line" ]; then
      floor=$(awk -v b="$(get stream_bytes)" -v g="$bandwidth" 'BEGIN { printf "%.6e", b / (g * 1e9) }')
    fi
    echo "$n,$piles,$lib,$(get clock),$mb,$(get blocks),$(get rss_before_kb),$(get peak_read_kb),$(get rss_after_read_kb),$(get peak_solve_kb),$(get peak_converged_kb),$(get sweep_s),$(get setup_s),$floor,$(IFS=,; echo "${times[*]}"),$(IFS=,; echo "${its[*]}"),$status,$bandwidth" >>"$csv"
    printf '%8s %-18s %-8s sweep %-12s setup %-12s peak read %8s kB solve %8s kB converged %8s kB  %s\n' "$n" "$lib" "$status" \
      "$(get sweep_s)" "$(get setup_s)" "$(get peak_read_kb)" "$(get peak_solve_kb)" "$(get peak_converged_kb)" "$(IFS=' '; echo "${its[*]}")"
  done
done
echo "== $csv"
target/release/scale_report "$csv" --picture docs/scale.svg | tee "$OUT/report.md"

#!/usr/bin/env bash
# 2D friction side by side with Siconos Numerics 4.4: bench/fc2d_compare.c is compiled against
# fc3d's compat headers (-lfc3d) and against the installed Siconos (-lsiconos_numerics), and both
# solve the same 2D problems with fc2d_driver (ids 400 NSGS, 402 CPG, 404 Lemke by default),
# tolerance 1e-5, 10000 iterations, median of 7 runs. Prints one line per run:
#   library  file  id  info  iterations  dparam[1]  median seconds
# Siconos' fc2d_driver aborts on W in sparse storage: the default problems are the dense and
# sparse-block 2D files of $FC3D_SICONOS_DATA (default ../shared/data/siconos).
#
#   bash scripts/compare-siconos-2d.sh [--ids "400 402 404"] [--reps 7] [FILES...]
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$(pwd)
DATA=${FC3D_SICONOS_DATA:-$ROOT/../shared/data/siconos}
IDS="400 402 404"
REPS=7
FILES=()
while [ $# -gt 0 ]; do
  case "$1" in
    --ids) IDS=$2; shift 2 ;;
    --reps) REPS=$2; shift 2 ;;
    -h|--help) sed -n '2,11p' "$0"; exit 0 ;;
    *) FILES+=("$1"); shift ;;
  esac
done
if [ ${#FILES[@]} -eq 0 ]; then
  for f in "$DATA"/FC2D_*.dat "$DATA"/FrictionContactProblem00*.dat; do FILES+=("$f"); done
fi
cargo build --release -p fc3d >/dev/null
OUT=$ROOT/target/compare-siconos-2d
mkdir -p "$OUT/lib"
ln -sf "$ROOT/target/release/libfc3d.so" "$OUT/lib/libfc3d.so.0"
gcc -O2 -std=c99 -I"$ROOT/capi/include/siconos-compat" -I"$ROOT/capi/include" \
  -o "$OUT/fc2d_compare-fc3d" bench/fc2d_compare.c -L"$ROOT/target/release" -Wl,-rpath,"$OUT/lib" -lfc3d -lm
gcc -O2 -std=c99 -I/usr/include/siconos/numerics -I/usr/include/siconos \
  -o "$OUT/fc2d_compare-siconos" bench/fc2d_compare.c -lsiconos_numerics -lm
for f in "${FILES[@]}"; do
  for id in $IDS; do
    for lib in siconos fc3d; do
      line=$(timeout 120 "$OUT/fc2d_compare-$lib" "$f" "$id" 1e-5 10000 "$REPS" 2>/dev/null || echo "$(basename "$f")	$id	failed")
      printf '%s\t%s\n' "$lib" "$line"
    done
  done
done

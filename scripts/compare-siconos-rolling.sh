#!/usr/bin/env bash
# Rolling friction side by side with Siconos Numerics 4.4: bench/rolling_compare.c is compiled
# against fc3d's compat headers (-lfc3d) and against the installed Siconos (-lsiconos_numerics),
# and both solve the rolling problems of Siconos 4.4.0's source package (the RFC3D_* and
# rfc3d_* files of numerics/src/FrictionContact/test/data, extracted by scripts/siconos-suite.sh
# into target/siconos-src) with rolling_fc3d_driver: NSGS 3000 with its local solvers 3002
# (default) and 3001, and ADMM 3003; tolerance 1e-8, 20000 iterations, median of 7 runs.
# Siconos' package has no 2D rolling problem: rows of 3, 10 and 50 disks on the ground, each
# touching its neighbours (W = H M^-1 H^T, q = H v of a falling row with random spins, seed 1;
# written by this script into target/), are solved with rolling_fc2d_driver, NSGS 4000 with the
# local solvers 3002 and 3001 (the ids Siconos' 2D NSGS takes). Prints one line per run:
#   library  file  id  local  info  iterations  dparam[1]  compute_error(norm ||q||)  seconds
#
#   bash scripts/compare-siconos-rolling.sh [--cases "3000:3002 3000:3001 3003:0"] [--tol 1e-8]
#                                            [--reps 7] [FILES...]
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$(pwd)
DATA=$ROOT/target/siconos-src/siconos-4.4.0/numerics/src/FrictionContact/test/data
CASES="3000:3002 3000:3001 3003:0"
CASES_2D="4000:3002 4000:3001"
TOL=1e-8
MAX_ITER=20000
REPS=7
FILES=()
while [ $# -gt 0 ]; do
  case "$1" in
    --cases) CASES=$2; shift 2 ;;
    --tol) TOL=$2; shift 2 ;;
    --reps) REPS=$2; shift 2 ;;
    -h|--help) sed -n '2,13p' "$0"; exit 0 ;;
    *) FILES+=("$1"); shift ;;
  esac
done
OUT=$ROOT/target/compare-siconos-rolling
mkdir -p "$OUT/lib"
if [ ${#FILES[@]} -eq 0 ]; then
  [ -d "$DATA" ] || { echo "run scripts/siconos-suite.sh first (it extracts Siconos' sources)" >&2; exit 2; }
  for f in "$DATA"/RFC3D_*.dat "$DATA"/rfc3d_*.dat; do FILES+=("$f"); done
  for nd in 3 10 50; do
    python3 - "$nd" "$OUT/rfc2d_disks_$nd.dat" <<'PY'
import random, sys
nd, path = int(sys.argv[1]), sys.argv[2]
random.seed(1)
R, m, inertia, mu, mur = 1.0, 1.0, 0.5, 0.3, 0.05
v = []
for i in range(nd):
    v += [random.uniform(-0.5, 0.5), -0.1, random.uniform(-1.0, 1.0)]
rows = []  # (normal, tangent, rolling) rows of H, 3 dofs (x, y, theta) per disk
def row(entries):
    h = [0.0] * (3 * nd)
    for k, x in entries:
        h[k] += x
    return h
for i in range(nd):  # disk i on the ground: n = +y, t = +x, contact point at the bottom
    rows += [row([(3*i+1, 1.0)]), row([(3*i, 1.0), (3*i+2, R)]), row([(3*i+2, 1.0)])]
for i in range(nd - 1):  # disk i+1 on disk i: n = +x, t = +y
    j = i + 1
    rows += [row([(3*j, 1.0), (3*i, -1.0)]),
             row([(3*j+1, 1.0), (3*j+2, -R), (3*i+1, -1.0), (3*i+2, -R)]),
             row([(3*j+2, 1.0), (3*i+2, -1.0)])]
minv = [1/m, 1/m, 1/inertia] * nd
n = len(rows)
W = [[sum(rows[a][k] * minv[k] * rows[b][k] for k in range(3*nd)) for b in range(n)] for a in range(n)]
q = [sum(rows[a][k] * v[k] for k in range(3*nd)) for a in range(n)]
nc = n // 3
with open(path, "w") as f:
    f.write(f"3\n{nc}\n0\n{n}\n{n}\n{n}\t{n}\n")
    for a in range(n):
        f.write(" ".join(repr(x) for x in W[a]) + "\n")
    f.write(" ".join(repr(x) for x in q) + "\n")
    f.write(" ".join([repr(mu)] * nc) + "\n")
    f.write(" ".join([repr(mur)] * nc) + "\n")
PY
    FILES+=("$OUT/rfc2d_disks_$nd.dat")
  done
fi
cargo build --release -p fc3d >/dev/null
ln -sf "$ROOT/target/release/libfc3d.so" "$OUT/lib/libfc3d.so.0"
gcc -O2 -std=c99 -I"$ROOT/capi/include/siconos-compat" -I"$ROOT/capi/include" \
  -o "$OUT/rolling_compare-fc3d" bench/rolling_compare.c -L"$ROOT/target/release" -Wl,-rpath,"$OUT/lib" -lfc3d -lm
gcc -O2 -std=c99 -I/usr/include/siconos/numerics -I/usr/include/siconos \
  -o "$OUT/rolling_compare-siconos" bench/rolling_compare.c -lsiconos_numerics -lm
for f in "${FILES[@]}"; do
  cases=$CASES
  [ "$(head -n 1 "$f" | tr -d '[:space:]')" = 3 ] && cases=$CASES_2D
  for c in $cases; do
    id=${c%%:*}; local=${c##*:}
    for lib in siconos fc3d; do
      line=$(timeout 120 "$OUT/rolling_compare-$lib" "$f" "$id" "$local" "$TOL" "$MAX_ITER" "$REPS" 2>/dev/null ||
        echo "$(basename "$f")	$id	$local	failed")
      printf '%s\t%s\n' "$lib" "$line"
    done
  done
done

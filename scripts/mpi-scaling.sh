#!/usr/bin/env bash
# fc3d-mpi's scaling measurements (docs/mpi.md): generated single piles split over 1 and 2 ranks in
# contiguous ranges, the distributed NSGS in the reproducible mode (and the fast mode at the
# largest size); one CSV line per run (columns: fc3d-mpi-bench's header) into
# bench/results/mpi-scaling.csv.
#
#   bash scripts/mpi-scaling.sh [--sizes 10000,100000,1000000] [--sweeps 5] [--limit 30] [--weak 200000]
#
# --weak N adds np 2 on N contacts (weak scaling against np 1 on N/2, which --sizes should hold).
# Minutes: each run generates its pile on every rank (about 50 s and 3 GB per rank at 10^6).
set -euo pipefail
cd "$(dirname "$0")/.."
sizes=10000,100000,1000000 sweeps=5 limit=30 weak=200000
while [ $# -gt 0 ]; do
  case "$1" in
    --sizes) sizes=$2; shift ;;
    --sweeps) sweeps=$2; shift ;;
    --limit) limit=$2; shift ;;
    --weak) weak=$2; shift ;;
    -h|--help) sed -n '2,11p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
  shift
done
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
cargo build --release -p fc3d-mpi --bins --target-dir target/native
bench=target/native/release/fc3d-mpi-bench
out=bench/results/mpi-scaling.csv
mkdir -p bench/results
echo "# $(date -u +%Y-%m-%dT%H:%MZ), load average $(cut -d' ' -f1-3 /proc/loadavg), $(nproc) cores" > "$out"
header=--header
run() { # run NP CONTACTS [extra arguments]
  local np=$1 n=$2; shift 2
  echo "== np $np, $n contacts $*" >&2
  mpirun --oversubscribe -np "$np" "$bench" "gen:contacts=$n,piles=1,seed=1" --sweeps "$sweeps" \
    --tols 1e-3,1e-4 --limit "$limit" $header "$@" | tee -a "$out"
  header=
}
for n in ${sizes//,/ }; do
  run 1 "$n" --core
  run 2 "$n"
done
[ -z "$weak" ] || run 2 "$weak"
largest=${sizes##*,}
run 2 "$largest" --mode fast
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)" >&2

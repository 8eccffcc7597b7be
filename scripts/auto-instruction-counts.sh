#!/bin/bash
# Instruction counts of AUTO and fixed solvers (callgrind, inclusive in solve_with_runner): the
# load-independent side of docs/auto.md's "AUTO against the best fixed solver".
# Usage: bash scripts/auto-instruction-counts.sh FC3D_BINARY [OUT.csv]
# (FC3D_BINARY built with --features fclib for the FCLIB problem; valgrind needed; ~15 min).
set -u
bin=${1:?usage: auto-instruction-counts.sh FC3D_BINARY [OUT.csv]}
out=${2:-target/auto-instruction-counts.csv}
D=../shared/data/siconos
echo "problem;tol;solver;Ir;status" > "$out"
for p in gen:contacts=35,seed=9 gen:contacts=40,seed=8 gen:contacts=50,seed=3 \
    $D/OneObject-i100000-316.hdf5.dat $D/OneObject-i1028-138.hdf5.dat \
    $D/BoxesStack1-i100000-32.hdf5.dat $D/LMGC_100_PR_PerioBox-i00361-60-03000.hdf5; do
  for t in 1e-4 1e-6; do
    for s in AUTO TFP TFP-APGD ADMM NSN-AC PROX PFP EG; do
      res=$(timeout 300 valgrind --tool=callgrind --callgrind-out-file=/dev/null \
        --toggle-collect='*solve_with_runner*' "$bin" solve "$p" --tol $t --solver $s \
        --budget 20s 2>&1)
      ir=$(echo "$res" | grep Collected | awk '{print $4}')
      st=$(echo "$res" | grep -v '^#\|^==\|^---\|^problem' | awk '{print $7}' | head -1)
      echo "$(basename "$p");$t;$s;$ir;$st" >> "$out"
    done
  done
done

#!/usr/bin/env bash
# The Newton comparison of docs/newton.md: fc3d and Siconos Numerics 4.4 run the nonsmooth Newton
# ids (504 NSN_AC, 513 NSN_FB, 520 NSN_NM, 521 NSN_AC_TEST) and the proximal point method (502,
# Newton inside) at 1e-8 on every shared 3D problem and on generated box towers (boxes stacked
# face on face, 4 contact points per face: W and the Newton matrix of sticking contacts are
# singular), written as .dat files by `cargo run -p fc3d-core --example write_towers` so that
# both libraries read the same problems. One run of scripts/compare-siconos.sh; the table is
# written next to its CSV as markdown (.md).
#
#   bash scripts/compare-newton.sh            # the table of docs/newton.md (about an hour on 2 cores)
#   bash scripts/compare-newton.sh --quick    # towers of up to 52 contacts and BoxesStack1, 1 repetition
#
# Options: --quick, --out FILE (default target/compare-siconos/newton.csv, quick: newton-quick.csv);
# any other option is passed to compare-siconos.sh (e.g. --timeout 120, --reps 1).
# Environment: FC3D_COMPARE_LIB=<path> compares another libfc3d.so build (see compare-siconos.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
DATA=${FC3D_SICONOS_DATA:-../shared/data/siconos}

quick=0 out="" pass=()
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) quick=1 ;;
    --out) out=$2; shift ;;
    -h|--help) sed -n '2,15p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) pass+=("$1") ;;
  esac
  shift
done

towers=target/newton-towers
rm -rf "$towers"
if [ $quick = 1 ]; then
  cargo run --release -q -p fc3d-core --example write_towers -- "$towers" quick >/dev/null
  problems="BoxesStack1-i100000-32.hdf5 $(ls "$towers"/*.dat | tr '\n' ' ')"
  : "${out:=target/compare-siconos/newton-quick.csv}"
  defaults=(--reps 1 --timeout 60)
else
  cargo run --release -q -p fc3d-core --example write_towers -- "$towers" >/dev/null
  shared=$(cd "$DATA" && ls -- *.dat | grep -v -E '^(GFC3D_|gfc2d_|fc2d_|FC2D_|FrictionContactProblem|ACinputs)')
  problems="$shared $(ls "$towers"/*.dat | tr '\n' ' ')"
  : "${out:=target/compare-siconos/newton.csv}"
  defaults=(--reps 3 --timeout 60)
fi

status=0
bash scripts/compare-siconos.sh --solvers "504 513 520 521 502" --tols 1e-8 --problems "$problems" \
  "${defaults[@]}" "${pass[@]}" --out "$out" --no-check || status=$?

# The table: one row per problem and id, iterations and median time of both libraries.
table="${out%.csv}.md"
awk -F, '
  NR == 1 { next }
  {
    key = $1 "," $2
    if (!(key in seen)) { seen[key] = 1; order[++n] = key }
    # info 0: converged; anything else is shown as it is (timeout, crash, info 1 = not converged).
    cell = ($5 == "0") ? sprintf("%s | %.3g", $6, $9) : sprintf("%s (%s) | -", ($6 == "" ? "-" : $6), $5)
    result[key "," $4] = cell
  }
  END {
    print "| problem | id | fc3d iterations | fc3d s | Siconos iterations | Siconos s |"
    print "| --- | --- | --- | --- | --- | --- |"
    for (i = 1; i <= n; i++) {
      split(order[i], k, ",")
      printf "| %s | %s | %s | %s |\n", k[1], k[2], result[order[i] ",fc3d"], result[order[i] ",siconos"]
    }
  }' "$out" >"$table"
echo "== table: $table"
cat "$table"
exit $status

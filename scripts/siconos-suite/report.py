#!/usr/bin/env python3
"""Summarises scripts/siconos-suite.sh's results.tsv: per collection, the cases Siconos 4.4 and fc3d
pass, and every case that Siconos passes and fc3d does not. Exit status 1 when such a case is not
listed in known-differences.txt ("<collection> <case> <reason>" per line, # for comments)."""
import sys
from collections import OrderedDict


def main(results_path, build_path, known_path):
    builds = {}
    with open(build_path) as f:
        for line in f:
            label, which, status = line.rstrip("\n").split("\t")
            builds[(label, which)] = status
    known = {}
    try:
        with open(known_path) as f:
            for line in f:
                line = line.strip()
                if not line or line.startswith("#"):
                    continue
                label, case, reason = (line.split(None, 2) + [""])[:3]
                known[(label, case)] = reason
    except FileNotFoundError:
        pass

    rows = []
    with open(results_path) as f:
        header = f.readline().rstrip("\n").split("\t")
        for line in f:
            rows.append(dict(zip(header, line.rstrip("\n").split("\t"))))
    rows.sort(key=lambda r: (r["collection"], int(r["case"]) if r["case"].isdigit() else -1))

    per = OrderedDict()
    for r in rows:
        c = per.setdefault(r["collection"], {"cases": 0, "siconos": 0, "fc3d": 0, "s_time": 0.0, "f_time": 0.0})
        c["cases"] += 1
        c["siconos"] += r["siconos"] == "pass"
        c["fc3d"] += r["fc3d"] == "pass"
        c["s_time"] += float(r["siconos_s"])
        c["f_time"] += float(r["fc3d_s"])

    print(f"{'collection / program':44} {'cases':>5} {'Siconos':>8} {'fc3d':>6} {'Siconos s':>10} {'fc3d s':>8}")
    tot = {"cases": 0, "siconos": 0, "fc3d": 0, "s_time": 0.0, "f_time": 0.0}
    for name, c in per.items():
        note = ""
        for which in ("siconos", "fc3d"):
            if builds.get((name, which), "ok") != "ok":
                note += f"  [{which}: {builds[(name, which)]}]"
        print(f"{name:44} {c['cases']:5} {c['siconos']:8} {c['fc3d']:6} {c['s_time']:10.1f} {c['f_time']:8.1f}{note}")
        for k in tot:
            tot[k] += c[k]
    print(f"{'total':44} {tot['cases']:5} {tot['siconos']:8} {tot['fc3d']:6} {tot['s_time']:10.1f} {tot['f_time']:8.1f}")

    regressions, listed, stale = [], [], []
    for r in rows:
        key = (r["collection"], r["case"])
        if r["siconos"] == "pass" and r["fc3d"] != "pass":
            (listed if key in known else regressions).append(r)
        elif key in known:
            stale.append(r)
    both_fail = sum(1 for r in rows if r["siconos"] != "pass" and r["fc3d"] != "pass")
    only_fc3d = sum(1 for r in rows if r["siconos"] != "pass" and r["fc3d"] == "pass")
    print(f"\nfc3d passes {only_fc3d} case(s) that Siconos fails; {both_fail} case(s) fail with both.")

    def show(title, items, with_reason=False):
        if not items:
            return
        print(f"\n{title} ({len(items)}):")
        for r in items:
            line = (f"  {r['collection']} {r['case']}: {r['solver']} ({r['solver_id']}) on {r['data']}: "
                    f"Siconos {r['siconos']} {r['siconos_s']}s, fc3d {r['fc3d']} {r['fc3d_s']}s")
            if with_reason:
                line += f"  -- {known[(r['collection'], r['case'])]}"
            print(line)

    show("Siconos passes, fc3d does not, listed in known-differences.txt", listed, True)
    show("Listed in known-differences.txt but no longer a difference (remove the line)", stale)
    show("REGRESSIONS: Siconos passes, fc3d does not", regressions)
    return 1 if regressions else 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:4]))

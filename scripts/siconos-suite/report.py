#!/usr/bin/env python3
"""Summarises scripts/siconos-suite.sh's results.tsv: per collection, the cases Siconos 4.4 and fc3d
pass, and every case that Siconos passes and fc3d does not.

Two lists, "<collection> <case> <text>" per line (# for comments), describe the expected differences:
- known-differences.txt: a difference with an evidenced reason (for example Siconos' result is wrong,
  checked independently); it stays until the reason goes away;
- open-cases.txt: the cases fc3d does not pass yet (the drop-in issue's work list). It only shrinks:
  a listed case that now passes must be removed (the run fails until it is), so a fix is recorded
  and never silently lost again.
Programs Siconos cannot run (its FCLIB programs: Debian's Siconos has no FCLIB) have "none" as
Siconos' result; their cases are judged by the will_fail mark of Siconos' driver: an unmarked case
that fc3d fails counts as one Siconos passes.
Exit status 1 on a difference listed in neither file, or on a stale line of either.
With a fifth argument, the current open differences (those not in known-differences.txt) are
written to that file in open-cases.txt's format instead."""
import sys
from collections import OrderedDict


def read_list(path):
    entries = {}
    try:
        with open(path) as f:
            for line in f:
                line = line.strip()
                if not line or line.startswith("#"):
                    continue
                label, case, reason = (line.split(None, 2) + [""])[:3]
                entries[(label, case)] = reason
    except FileNotFoundError:
        pass
    return entries


def main(results_path, build_path, known_path, open_path, write_open=None):
    builds = {}
    with open(build_path) as f:
        for line in f:
            label, which, status = line.rstrip("\n").split("\t")
            builds[(label, which)] = status
    known = read_list(known_path)
    open_cases = {} if write_open else read_list(open_path)

    rows = []
    with open(results_path) as f:
        header = f.readline().rstrip("\n").split("\t")
        for line in f:
            rows.append(dict(zip(header, line.rstrip("\n").split("\t"))))
    rows.sort(key=lambda r: (r["collection"], int(r["case"]) if r["case"].isdigit() else -1))

    def expected(r):
        """Whether the case must pass: Siconos passes it, or Siconos cannot run it and its driver
        does not mark it to fail."""
        if r["siconos"] == "none":
            return r.get("will_fail", "0") in ("", "0")
        return r["siconos"] == "pass"

    per = OrderedDict()
    for r in rows:
        c = per.setdefault(r["collection"], {"cases": 0, "siconos": 0, "fc3d": 0, "s_time": 0.0, "f_time": 0.0,
                                             "siconos_runs": True})
        c["cases"] += 1
        c["siconos"] += r["siconos"] == "pass"
        c["siconos_runs"] &= r["siconos"] != "none"
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
        siconos = c["siconos"] if c["siconos_runs"] else "-"
        if not c["siconos_runs"]:
            note += "  [Siconos without FCLIB: judged by will_fail marks]"
        print(f"{name:44} {c['cases']:5} {siconos:>8} {c['fc3d']:6} {c['s_time']:10.1f} {c['f_time']:8.1f}{note}")
        for k in tot:
            tot[k] += c[k]
    print(f"{'total':44} {tot['cases']:5} {tot['siconos']:8} {tot['fc3d']:6} {tot['s_time']:10.1f} {tot['f_time']:8.1f}")

    regressions, listed, still_open, stale, fixed, unexpected = [], [], [], [], [], []
    for r in rows:
        key = (r["collection"], r["case"])
        if r["siconos"] == "none" and r["fc3d"] == "pass" and not expected(r):
            unexpected.append(r)
        if expected(r) and r["fc3d"] != "pass":
            if key in known:
                listed.append(r)
            elif key in open_cases:
                still_open.append(r)
            else:
                regressions.append(r)
        elif key in known:
            stale.append(r)
        elif key in open_cases and r["fc3d"] == "pass":
            fixed.append(r)
    both_fail = sum(1 for r in rows if r["siconos"] not in ("pass", "none") and r["fc3d"] != "pass")
    only_fc3d = sum(1 for r in rows if r["siconos"] not in ("pass", "none") and r["fc3d"] == "pass")
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

    if write_open:
        with open(write_open, "w") as f:
            f.write("# Cases of Siconos 4.4.0's own friction tests that Siconos passes and fc3d does not pass yet:\n"
                    "# the work list of the drop-in issue. Only removals: scripts/siconos-suite.sh fails on a new\n"
                    "# difference and on a listed case that passes (remove its line). <collection> <case> <what fails>\n")
            for r in regressions:
                f.write(f"{r['collection']} {r['case']} {r['solver']} ({r['solver_id']}) on {r['data']}: fc3d {r['fc3d']}\n")
        print(f"\nwrote {len(regressions)} open case(s) to {write_open}")
        return 0

    print(f"\nSiconos passes and fc3d does not: {len(listed)} with an evidenced reason, "
          f"{len(still_open)} open (open-cases.txt), {len(regressions)} new.")
    show("Marked to fail by Siconos' driver (will_fail) and passed by fc3d", unexpected)
    show("Siconos passes, fc3d does not, listed in known-differences.txt", listed, True)
    show("Listed in known-differences.txt but no longer a difference (remove the line)", stale)
    show("FIXED: listed in open-cases.txt and now passing (remove the line)", fixed)
    show("REGRESSIONS: Siconos passes, fc3d does not, listed nowhere", regressions)
    return 1 if regressions or stale or fixed else 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:6]))

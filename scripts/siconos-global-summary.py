#!/usr/bin/env python3
"""The per-id summary of a `scripts/compare-siconos-global.sh` run, for docs/global.md:

    python3 scripts/siconos-global-summary.py target/compare-siconos-global/results.csv [TOL]

prints (Markdown) one row per global id: the geometric mean of fc3d's time over Siconos' on the
runs where both libraries report info 0 and Siconos takes 1 ms or more (the script's own rule),
the same over the runs where each library's result is also within 10 x TOL by the *other*
library's gfc3d_compute_error (Siconos' `_WR` ids report info 0 with a wrong global velocity when
M is sparse-block, and its relaxed ids report success on the convex relaxation), and how many
problems each library alone really solved; then the run table with times in ms.
"""

import collections
import csv
import math
import sys


def number(x):
    try:
        return float(x)
    except (TypeError, ValueError):
        return None


def main():
    path = sys.argv[1] if len(sys.argv) > 1 else "target/compare-siconos-global/results.csv"
    tol = float(sys.argv[2]) if len(sys.argv) > 2 else 1e-6
    runs = collections.OrderedDict()
    for row in csv.DictReader(open(path)):
        runs.setdefault((row["problem"], row["solver"]), {})[row["library"]] = row
    ids = list(collections.OrderedDict.fromkeys(s for _, s in runs))
    per = {s: {"all": [], "true": [], "fc3d": 0, "siconos": 0, "neither": 0} for s in ids}
    every, every_true = [], []
    for (_, solver), pair in runs.items():
        a, b = pair["fc3d"], pair["siconos"]
        e = per[solver]
        solved = [
            x["info"] == "0"
            and number(x["error_by_other"]) is not None
            and number(x["error_by_other"]) <= 10 * tol
            for x in (a, b)
        ]
        if solved[0] and not solved[1]:
            e["fc3d"] += 1
        elif solved[1] and not solved[0]:
            e["siconos"] += 1
        elif not any(solved):
            e["neither"] += 1
        ta, tb = number(a["seconds"]), number(b["seconds"])
        if a["info"] == "0" and b["info"] == "0" and ta and tb and tb >= 1e-3:
            ratio = math.log(ta / tb)
            e["all"].append(ratio)
            every.append(ratio)
            if all(solved):
                e["true"].append(ratio)
                every_true.append(ratio)

    def mean(logs):
        return "%.3f" % math.exp(sum(logs) / len(logs)) if logs else "-"

    print("| id | runs counted | fc3d / Siconos | both really solved | fc3d / Siconos there "
          "| solved by fc3d only | by Siconos only | by neither |")
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for s in ids:
        e = per[s]
        print("| %s | %d | %s | %d | %s | %d | %d | %d |" % (
            s, len(e["all"]), mean(e["all"]), len(e["true"]), mean(e["true"]), e["fc3d"],
            e["siconos"], e["neither"]))
    print()
    print("Geometric mean of fc3d / Siconos: %s over the %d runs both report converged with "
          "Siconos at 1 ms or more; %s over the %d of them where each result is within 10 x "
          "tol by the other library's error." % (mean(every), len(every), mean(every_true),
                                                  len(every_true)))
    print()

    def ms(x):
        t = number(x)
        if t is None:
            return "-"
        return "%.3g" % (1e3 * t) if t < 1 else "%.0f" % (1e3 * t)

    def err(x):
        v = number(x)
        return "-" if v is None else "%.1e" % v

    print("| problem | id | fc3d info | it. | ms | error (by Siconos) | Siconos info | it. | ms "
          "| error (by fc3d) | fc3d / Siconos |")
    print("| --- | ---: | --- | ---: | ---: | ---: | --- | ---: | ---: | ---: | ---: |")
    for (problem, solver), pair in runs.items():
        a, b = pair["fc3d"], pair["siconos"]
        ta, tb = number(a["seconds"]), number(b["seconds"])
        ratio = "%.2f" % (ta / tb) if ta and tb else "-"
        print("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
            problem, solver, a["info"], a["iterations"] or "-", ms(a["seconds"]),
            err(a["error_by_other"]), b["info"], b["iterations"] or "-", ms(b["seconds"]),
            err(b["error_by_other"]), ratio))


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""fc3d-mpi's communication model (docs/mpi.md): per-sweep efficiency of the reproducible mode on
P nodes of n contacts each, from what bench/results/mpi-scaling.csv measured on this machine.

    python3 scripts/mpi-model.py [bench/results/mpi-scaling.csv] [--nodes 64] [--svg FILE]

--svg also draws the measured sweeps (docs/mpi-scaling.svg): per pile size, the wall time of a
sweep on 1 and 2 ranks split into CPU compute, compute time spent descheduled, and MPI wait.

A sweep on one node of a P-node run costs

    T(P) = b * t_c * n                                  compute, the busiest rank of each colour
         + C * (alpha + f * o)                          one dependent exchange per colour
         + G * 24 / beta                                ghost reactions received (3 doubles each)
         + 2 * ceil(log2 P) * alpha + 1104 / beta       the sweep's exact-sum all-reduce

against T(1) = t_c * n, efficiency E = T(1) / T(P), with
    t_c    CPU seconds per contact and sweep, measured at np 1 on the largest pile;
    C      colours of the contact graph (measured: they depend on the graph, not on P);
    b      colour balance: each colour's contacts are spread by a hash, so a rank holds
           n/C +- sqrt(n/C) of them and the busiest of P ranks about 1 + z_P sqrt(C/n) times the
           mean (z_P the expected maximum of P standard normals);
    f      neighbour nodes (6 faces of a 3D block decomposition), o the per-message overhead;
    G      ghosts per node, f faces of k n^(2/3) contacts each, k fitted on the np 2 runs (one
           interface between two halves of a pile, contiguous ranges);
    alpha, beta  latency and bandwidth of the network.
No overlap of communication with the interior contacts is credited (the library overlaps each
colour's messages with its interior sweep), so the model is pessimistic there; it ignores OS
noise and imbalance beyond the colour balance.
"""
import csv
import math
import sys

NETWORKS = [
    # name, latency alpha (s), per-message overhead o (s), bandwidth beta (bytes/s)
    ("InfiniBand HDR 100 Gb/s", 1.5e-6, 0.5e-6, 12.0e9),
    ("10 Gb Ethernet, TCP", 25e-6, 5e-6, 1.1e9),
]
FACES = 6


def expected_max_normal(p):
    """E[max of p standard normals] (Blom's approximation)."""
    if p <= 1:
        return 0.0
    from statistics import NormalDist

    return NormalDist().inv_cdf((p - 0.375) / (p + 0.25))


def main():
    args = [a for a in sys.argv[1:] if a.endswith(".csv")]
    path = args[0] if args else "bench/results/mpi-scaling.csv"
    nodes = 64
    if "--nodes" in sys.argv:
        nodes = int(sys.argv[sys.argv.index("--nodes") + 1])
    rows = [r for r in csv.DictReader(l for l in open(path) if not l.startswith("#"))
            if r["mode"] == "reproducible"]
    if "--svg" in sys.argv:
        ones = {r["contacts"] for r in rows if r["ranks"] == "1"}
        svg([r for r in rows if r["contacts"] in ones], sys.argv[sys.argv.index("--svg") + 1])
    one = max((r for r in rows if r["ranks"] == "1"), key=lambda r: int(r["contacts"]))
    n1 = int(one["contacts"])
    t_c = float(one["compute_cpu_ms"]) * 1e-3 / n1
    colours = int(one["colours"])
    pairs = [r for r in rows if r["ranks"] == "2"]
    ks = [int(r["max_ghosts"]) / int(r["contacts"]) ** (2 / 3) for r in pairs]
    k = max(ks)
    print(f"measured: t_c = {t_c * 1e9:.0f} ns CPU per contact and sweep ({n1} contacts, np 1), "
          f"C = {colours} colours, interface k = {k:.2f} n^(2/3) contacts "
          f"(np 2 runs: {', '.join(f'{x:.2f}' for x in ks)})")
    print(f"model: {nodes} nodes, {FACES} neighbour nodes each\n")
    print("| network | contacts per node | compute ms | balance b | exchanges ms | ghosts | "
          "ghost transfer ms | all-reduce ms | efficiency |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for name, alpha, o, beta in NETWORKS:
        for n in (100_000, 500_000, 1_000_000):
            compute = t_c * n
            b = 1 + expected_max_normal(nodes) * math.sqrt(colours / n)
            exchanges = colours * (alpha + FACES * o)
            ghosts = FACES * k * n ** (2 / 3)
            transfer = ghosts * 24 / beta
            reduce = 2 * math.ceil(math.log2(nodes)) * alpha + 1104 / beta
            total = b * compute + exchanges + transfer + reduce
            print(f"| {name} | {n} | {1e3 * compute:.1f} | {b:.3f} | {1e3 * exchanges:.3f} | "
                  f"{ghosts:.0f} | {1e3 * transfer:.2f} | {1e3 * reduce:.3f} | "
                  f"{100 * compute / total:.1f}% |")


def svg(rows, path):
    """Stacked bars of the measured sweeps, each size's bars scaled to its tallest one (the
    labels give the wall milliseconds)."""
    sizes = sorted({int(r["contacts"]) for r in rows if r["ranks"] == "1"})
    width, height, left, bottom, bar = 640, 330, 60, 270, 60
    parts = [("compute_cpu_ms", "#2b6cb0", "CPU compute"),
             (None, "#90cdf4", "compute while descheduled"),
             ("wait_ms", "#e53e3e", "MPI wait")]
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
           'font-family="sans-serif" font-size="12">',
           f'<text x="{left}" y="18" font-size="14">One sweep of the reproducible mode, '
           '1 and 2 ranks (2 shared cores, load 5-10)</text>']
    scale = bottom - 45  # each size's tallest bar
    for g, n in enumerate(sizes):
        group = [r for r in rows if int(r["contacts"]) == n]
        ref = max(max(float(r["compute_ms"]), float(r["compute_cpu_ms"])) + float(r["wait_ms"])
                  for r in group)
        for b, r in enumerate(group):
            x = left + g * 190 + b * (bar + 10)
            y = bottom
            cpu, compute, wait = (float(r[k]) for k in ("compute_cpu_ms", "compute_ms", "wait_ms"))
            for (key, colour, _), v in zip(parts, (cpu, max(compute - cpu, 0), wait)):
                h = v / ref * scale
                y -= h
                out.append(f'<rect x="{x}" y="{y:.1f}" width="{bar}" height="{h:.1f}" '
                           f'fill="{colour}"/>')
            out.append(f'<text x="{x + bar / 2}" y="{y - 4:.1f}" text-anchor="middle">'
                       f'{float(r["sweep_ms"]):.0f} ms</text>')
            out.append(f'<text x="{x + bar / 2}" y="{bottom + 14}" text-anchor="middle">'
                       f'np {r["ranks"]}</text>')
        out.append(f'<text x="{left + g * 190 + bar + 5}" y="{bottom + 30}" '
                   f'text-anchor="middle">{n} contacts</text>')
    for i, (_, colour, label) in enumerate(parts):
        out.append(f'<rect x="{left + i * 190}" y="{height - 14}" width="10" height="10" '
                   f'fill="{colour}"/><text x="{left + i * 190 + 14}" y="{height - 5}">'
                   f'{label}</text>')
    out.append("</svg>")
    open(path, "w").write("\n".join(out) + "\n")


if __name__ == "__main__":
    main()

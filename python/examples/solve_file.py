"""Solve Siconos .dat problem files with fc3d and print one line per (file, solver).

    python examples/solve_file.py ../shared/data/siconos/Rover1039.dat
    python examples/solve_file.py PROBLEM.dat [MORE.dat] --solver NSGS,NSN_AC --tol 1e-8

Exit status 0 when every solve converged, 1 otherwise.
"""

import argparse
import sys

import numpy as np

import fc3d


def main(argv=None):
    """Parses the command line, solves every file with every solver, prints a table."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("files", nargs="+", help="Siconos .dat problem files")
    parser.add_argument("--solver", default="NSGS", help="comma-separated names or ids (NSGS)")
    parser.add_argument("--tol", type=float, default=1e-8, help="tolerance (1e-8)")
    parser.add_argument("--max-iter", type=int, default=100000, help="iteration limit (100000)")
    parser.add_argument("--time-budget", type=float, default=20.0, help="seconds per solve (20)")
    args = parser.parse_args(argv)

    print("fc3d %s (%s)" % (fc3d.__version__, fc3d.library_path))
    print("%-36s %8s %-8s %-11s %10s %10s %10s" % (
        "problem", "contacts", "solver", "status", "iterations", "error", "seconds"))
    all_converged = True
    for path in args.files:
        problem = fc3d.read_problem(path)
        for solver in args.solver.split(","):
            result = fc3d.solve(problem, solver=solver, tol=args.tol, max_iter=args.max_iter,
                                time_budget=args.time_budget)
            # The velocity the library returns is W r + q of the returned reaction.
            assert np.allclose(result.u, problem.W @ result.r + problem.q, atol=1e-9, rtol=1e-9)
            all_converged &= result.converged
            print("%-36s %8d %-8s %-11s %10d %10.2e %10.4f" % (
                path.rsplit("/", 1)[-1][:36], problem.n_contacts, result.solver_name,
                result.status, result.iterations, result.error, result.seconds))
    return 0 if all_converged else 1


if __name__ == "__main__":
    sys.exit(main())

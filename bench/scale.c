/* Scale benchmark of fc3d and Siconos Numerics 4.4: one source compiled twice, against fc3d's
 * compat headers (-lfc3d) or against the installed Siconos (-lsiconos_numerics), as
 * bench/siconos_compare.c is. scripts/scale-bench.sh builds both and runs them on generated piles.
 *
 * Modes (each prints one line of "key value" pairs):
 *   setup [--threads N] [--in-place] <problem.dat> <solver> <sweeps> <reps> [<max_iter> <tol>...]
 *       With --in-place (fc3d only) every call is fc3d_driver_in_place (no copies of r and u).
 *       Times are CPU seconds of the process (see now_seconds). With --threads N (fc3d only,
 *       NSGS 500): fc3d's coloured decomposition on N threads (iparam[FC3D_IPARAM_NSGS_
 *       DECOMPOSITION] = FC3D_NSGS_COLOURED, iparam[FC3D_IPARAM_NSGS_THREADS] = N), timed in
 *       wall-clock seconds (CPU time would sum the threads); the line then says clock wall.
 *       Reads the problem (peak RSS of the read measured alone), then times fc3d_driver calls
 *       from r = 0 limited to 1 and to 1 + <sweeps> iterations (<reps> each, alternated, medians):
 *       sweep = (t(1 + sweeps) - t(1)) / sweeps, setup = t(1) - sweep: what a call costs on top of
 *       its sweeps. Peak RSS of the solving part measured alone (VmHWM reset through
 *       /proc/self/clear_refs after the read). Prints
 *         contacts C blocks B rss_before_kb R0 peak_read_kb P1 rss_after_read_kb R1
 *         peak_solve_kb P2 call1_s T1 callN_s TN sweep_s S setup_s U stream_bytes Y clock cpu|wall
 *         peak_converged_kb P3 converged_info I converged_iterations K
 *       P3: peak RSS (reset before it) of one more call, from r = 0 to tolerance 5e-2 (a few sweeps
 *       on the piles), which converges: what a call that ends converged holds at its end.
 *       stream_bytes: what one sweep must read at least (every block, its column index, the block
 *       row pointers, q, r and mu).
 *       Then, for each tolerance (loosest first), solves on from where the previous one stopped
 *       (NSGS restarted from its own iterate follows the same iterates), so the times and
 *       iterations printed are cumulative from r = 0, one line per tolerance, flushed at once
 *       (a run stopped by a time limit keeps the lines it printed):
 *         tol T info I iterations K error E seconds S
 *   solve <problem.dat> <solver> <max_iter> <tol>
 *       One fc3d_driver call from r = 0 to <tol> (scripts/convergence-bench.sh: one process per
 *       solver and tolerance, cut by the script's time limit). Prints
 *         contacts C info I iterations K error E cpu_s S wall_s W rss_after_read_kb R peak_solve_kb P
 *       (S: CPU seconds of the process during the call, set-up included; P: the peak RSS of the
 *       call above what the process held once the problem was read).
 *   bandwidth <megabytes>
 *       Streaming read bandwidth of this machine (best of 5 sums over an array of that size):
 *       bandwidth_gbs G
 *
 * solver: a Friction_cst.h id with Siconos' defaults (500: NSGS with local solver 565). */
#define _POSIX_C_SOURCE 199309L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "SiconosNumerics.h"
#include "FrictionContactProblem.h"
#include "SolverOptions.h"
#include "Friction_cst.h"
#include "fc3d_Solvers.h"
#include "NonSmoothDrivers.h"
#include "NumericsMatrix.h"
#include "SparseBlockMatrix.h"

/* CPU time of the process (user + system: page faults included). The solves are single-threaded,
 * so on an idle machine it equals wall time; on a machine shared with other jobs it leaves out
 * the time the process waited for a core, which wall time would add at random. */
static double now_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static double wall_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Threads of fc3d's coloured NSGS (0: the library's defaults, one thread, CPU time). */
static int threads = 0;

/* Whether calls go through fc3d_driver_in_place (fc3d only: no copies of r and u). */
static int in_place = 0;

static int driver(FrictionContactProblem* problem, double* r, double* u, SolverOptions* options) {
#ifdef FC3D_IPARAM_NSGS_DECOMPOSITION
  if (in_place) return fc3d_driver_in_place(problem, r, u, options);
#endif
  return fc3d_driver(problem, r, u, options);
}

/* The clock of the timings: CPU time of the process, or wall time for a threaded run. */
static double clock_seconds(void) { return threads > 0 ? wall_seconds() : now_seconds(); }

/* Options of `solver` with Siconos' defaults, and the coloured decomposition on `threads`
 * threads when asked. */
static SolverOptions* create_options(int solver) {
  SolverOptions* options = solver_options_create(solver);
#ifdef FC3D_IPARAM_NSGS_DECOMPOSITION
  if (threads > 0) {
    options->iparam[FC3D_IPARAM_NSGS_DECOMPOSITION] = FC3D_NSGS_COLOURED;
    options->iparam[FC3D_IPARAM_NSGS_THREADS] = threads;
  }
#endif
  return options;
}

/* The tolerance of the converged call whose peak memory is measured. */
#define CONVERGED_TOL 5e-2

static int cmp_double(const void* a, const void* b) {
  double x = *(const double*)a, y = *(const double*)b;
  return (x > y) - (x < y);
}

/* A field of /proc/self/status in kB (VmRSS, VmHWM), -1 if unknown. */
static long status_kb(const char* field) {
  FILE* f = fopen("/proc/self/status", "r");
  if (!f) return -1;
  char line[256];
  long value = -1;
  size_t len = strlen(field);
  while (fgets(line, sizeof line, f)) {
    if (strncmp(line, field, len) == 0 && line[len] == ':') {
      value = strtol(line + len + 1, NULL, 10);
      break;
    }
  }
  fclose(f);
  return value;
}

/* Resets VmHWM to the current RSS (Linux >= 4.0). */
static void reset_peak(void) {
  FILE* f = fopen("/proc/self/clear_refs", "w");
  if (f) {
    fputs("5", f);
    fclose(f);
  }
}

static FrictionContactProblem* read_problem(const char* path) {
  FrictionContactProblem* problem = frictionContact_new_from_filename(path);
  if (!problem || problem->dimension != 3) {
    fprintf(stderr, "cannot read %s as a 3D problem\n", path);
    return NULL;
  }
  return problem;
}

static double call(FrictionContactProblem* problem, int solver, double tol, int max_iter, double* r,
                   double* u, int* info, int* iterations, double* error) {
  int n = 3 * problem->numberOfContacts;
  memset(r, 0, (size_t)n * sizeof(double));
  memset(u, 0, (size_t)n * sizeof(double));
  SolverOptions* options = create_options(solver);
  options->dparam[SICONOS_DPARAM_TOL] = tol;
  options->iparam[SICONOS_IPARAM_MAX_ITER] = max_iter;
  double t0 = clock_seconds();
  *info = driver(problem, r, u, options);
  double t = clock_seconds() - t0;
  *iterations = options->iparam[SICONOS_IPARAM_ITER_DONE];
  *error = options->dparam[SICONOS_DPARAM_RESIDU];
  solver_options_delete(options);
  free(options);
  return t;
}

static double median(double* times, int reps) {
  qsort(times, (size_t)reps, sizeof(double), cmp_double);
  return reps % 2 ? times[reps / 2] : 0.5 * (times[reps / 2 - 1] + times[reps / 2]);
}

/* Medians of `reps` calls limited to 1 sweep (*t1) and to 1 + `sweeps` sweeps (*tn), the two
 * kinds alternated so that a drift of the machine's speed during the measurement (this VM's
 * memory bandwidth moves by tens of percent from minute to minute) weighs on both alike: the
 * set-up is their difference, and a drift between two separate series of calls swung it by 2x. */
static void median_calls(FrictionContactProblem* problem, int solver, int sweeps, int reps, double* r,
                         double* u, double* t1, double* tn) {
  double* times1 = calloc((size_t)reps, sizeof(double));
  double* timesn = calloc((size_t)reps, sizeof(double));
  int info, iterations;
  double error;
  for (int k = 0; k < reps; k++) {
    /* A tolerance no sweep reaches: every call does exactly max_iter sweeps. */
    times1[k] = call(problem, solver, 1e-300, 1, r, u, &info, &iterations, &error);
    timesn[k] = call(problem, solver, 1e-300, 1 + sweeps, r, u, &info, &iterations, &error);
  }
  *t1 = median(times1, reps);
  *tn = median(timesn, reps);
  free(times1);
  free(timesn);
}

static int mode_setup(int argc, char** argv) {
  /* Options between "setup" and the problem: shift them out, the rest as without them. */
  while (argc >= 3 && strncmp(argv[2], "--", 2) == 0) {
    int used = 1;
    if (strcmp(argv[2], "--threads") == 0 && argc >= 4) {
      threads = atoi(argv[3]);
      used = 2;
#ifndef FC3D_IPARAM_NSGS_DECOMPOSITION
      fprintf(stderr, "--threads: this library has no coloured NSGS (fc3d only)\n");
      return 2;
#endif
      if (threads < 1) {
        fprintf(stderr, "--threads needs a positive count\n");
        return 2;
      }
    } else if (strcmp(argv[2], "--in-place") == 0) {
#ifndef FC3D_IPARAM_NSGS_DECOMPOSITION
      fprintf(stderr, "--in-place: fc3d_driver_in_place is fc3d's\n");
      return 2;
#endif
      in_place = 1;
    } else {
      fprintf(stderr, "unknown option %s\n", argv[2]);
      return 2;
    }
    argv[1 + used] = argv[1];
    argv[used] = argv[0];
    argv += used;
    argc -= used;
  }
  if (argc < 6 || argc == 7) {
    fprintf(stderr, "usage: %s setup [--threads N] [--in-place] <problem.dat> <solver> <sweeps> <reps> [<max_iter> <tol>...]\n",
            argv[0]);
    return 2;
  }
  int solver = atoi(argv[3]), sweeps = atoi(argv[4]), reps = atoi(argv[5]);
  long rss_before = status_kb("VmRSS");
  reset_peak();
  FrictionContactProblem* problem = read_problem(argv[2]);
  if (!problem) return 2;
  long peak_read = status_kb("VmHWM");
  long rss_after_read = status_kb("VmRSS");
  int nc = problem->numberOfContacts, n = 3 * nc;
  double* r = calloc((size_t)n + 1, sizeof(double));
  double* u = calloc((size_t)n + 1, sizeof(double));
  /* Touch r and u before the peak is reset: they belong to the host, not to the solve. */
  memset(r, 0, (size_t)n * sizeof(double));
  memset(u, 0, (size_t)n * sizeof(double));
  long blocks = 0;
  if (problem->M->storageType == NM_SPARSE_BLOCK) blocks = (long)problem->M->matrix1->nbblocks;
  reset_peak();
  double t1, tn;
  median_calls(problem, solver, sweeps, reps, r, u, &t1, &tn);
  /* The calls of 1 and of 1 + sweeps sweeps hold the same memory. */
  long peak_solve = status_kb("VmHWM");
  double sweep = (tn - t1) / sweeps;
  /* A call that converges (to CONVERGED_TOL, a few sweeps on the piles): its end (the final
   * error, fc3d's test for a ray of no solution) may hold memory that a call stopped at its
   * iteration limit does not. */
  reset_peak();
  int converged_info, converged_iterations;
  double converged_error;
  call(problem, solver, CONVERGED_TOL, 1000, r, u, &converged_info, &converged_iterations, &converged_error);
  long peak_converged = status_kb("VmHWM");
  double stream_bytes = (double)blocks * (72.0 + 8.0) + (double)nc * (8.0 + 3 * 8.0 * 2 + 8.0);
  printf("contacts %d blocks %ld rss_before_kb %ld peak_read_kb %ld rss_after_read_kb %ld peak_solve_kb %ld "
         "call1_s %.6e callN_s %.6e sweep_s %.6e setup_s %.6e stream_bytes %.0f clock %s "
         "peak_converged_kb %ld converged_info %d converged_iterations %d\n",
         nc, blocks, rss_before, peak_read, rss_after_read, peak_solve, t1, tn, sweep, t1 - sweep, stream_bytes,
         threads > 0 ? "wall" : "cpu", peak_converged, converged_info, converged_iterations);
  fflush(stdout);
  if (argc > 7) {
    int max_iter = atoi(argv[6]), total_iter = 0;
    double total = 0.0;
    memset(r, 0, (size_t)n * sizeof(double));
    memset(u, 0, (size_t)n * sizeof(double));
    for (int k = 7; k < argc; k++) {
      double tol = atof(argv[k]);
      SolverOptions* options = create_options(solver);
      options->dparam[SICONOS_DPARAM_TOL] = tol;
      options->iparam[SICONOS_IPARAM_MAX_ITER] = max_iter - total_iter;
      double t0 = clock_seconds();
      int info = driver(problem, r, u, options);
      total += clock_seconds() - t0;
      total_iter += options->iparam[SICONOS_IPARAM_ITER_DONE];
      printf("tol %g info %d iterations %d error %.6e seconds %.6e\n", tol, info, total_iter,
             options->dparam[SICONOS_DPARAM_RESIDU], total);
      fflush(stdout);
      solver_options_delete(options);
      free(options);
      if (info != 0 || total_iter >= max_iter) break;
    }
  }
  frictionContactProblem_free(problem);
  free(r);
  free(u);
  return 0;
}

static int mode_solve(int argc, char** argv) {
  if (argc != 6) {
    fprintf(stderr, "usage: %s solve <problem.dat> <solver> <max_iter> <tol>\n", argv[0]);
    return 2;
  }
  FrictionContactProblem* problem = read_problem(argv[2]);
  if (!problem) return 2;
  int solver = atoi(argv[3]), max_iter = atoi(argv[4]), n = 3 * problem->numberOfContacts;
  double tol = atof(argv[5]);
  double* r = calloc((size_t)n + 1, sizeof(double));
  double* u = calloc((size_t)n + 1, sizeof(double));
  memset(r, 0, (size_t)n * sizeof(double));
  memset(u, 0, (size_t)n * sizeof(double));
  long rss_after_read = status_kb("VmRSS");
  reset_peak();
  int info, iterations;
  double error, w0 = wall_seconds();
  double t = call(problem, solver, tol, max_iter, r, u, &info, &iterations, &error);
  double wall = wall_seconds() - w0;
  long peak = status_kb("VmHWM");
  printf("contacts %d info %d iterations %d error %.6e cpu_s %.6e wall_s %.6e rss_after_read_kb %ld "
         "peak_solve_kb %ld\n",
         problem->numberOfContacts, info, iterations, error, t, wall, rss_after_read,
         peak > rss_after_read ? peak - rss_after_read : 0);
  frictionContactProblem_free(problem);
  free(r);
  free(u);
  return 0;
}

static int mode_bandwidth(int argc, char** argv) {
  if (argc != 3) return 2;
  size_t n = (size_t)atol(argv[2]) * 1024 * 1024 / sizeof(double);
  double* a = malloc(n * sizeof(double));
  if (!a) return 2;
  for (size_t i = 0; i < n; i++) a[i] = (double)(i & 7);
  double best = 1e300, sink = 0.0;
  for (int rep = 0; rep < 5; rep++) {
    double t0 = wall_seconds();
    double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
    for (size_t i = 0; i + 3 < n; i += 4) {
      s0 += a[i];
      s1 += a[i + 1];
      s2 += a[i + 2];
      s3 += a[i + 3];
    }
    double t = wall_seconds() - t0;
    sink += s0 + s1 + s2 + s3;
    if (t < best) best = t;
  }
  printf("bandwidth_gbs %.3f checksum %.0f\n", (double)(n * sizeof(double)) / best / 1e9, sink);
  free(a);
  return 0;
}

int main(int argc, char** argv) {
  if (argc >= 2 && strcmp(argv[1], "setup") == 0) return mode_setup(argc, argv);
  if (argc >= 2 && strcmp(argv[1], "bandwidth") == 0) return mode_bandwidth(argc, argv);
  if (argc >= 2 && strcmp(argv[1], "solve") == 0) return mode_solve(argc, argv);
  fprintf(stderr, "usage: %s setup|solve|bandwidth ... (see the source)\n", argv[0]);
  return 2;
}

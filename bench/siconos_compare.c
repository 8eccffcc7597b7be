/* Side-by-side benchmark of fc3d and Siconos Numerics 4.4: one source compiled twice, against
 * fc3d's compat headers or against the installed Siconos (scripts/compare-siconos.sh does both).
 *
 *   cc -O2 -Icapi/include/siconos-compat -Icapi/include bench/siconos_compare.c -Ltarget/release -lfc3d -lm -o cmp_fc3d
 *   cc -O2 -I/usr/include/siconos/numerics -I/usr/include/siconos bench/siconos_compare.c \
 *      -lsiconos_numerics -lm -o cmp_siconos
 *
 * Modes:
 *   solve <problem.dat> <solver> <tol> <max_iter> <reps> <out_reaction_file>
 *       solver = a Friction_cst.h id with Siconos' defaults (500: NSGS, default local solver), or
 *       500/<local id> (solver_options_update_internal on internal solver 0), followed by any
 *       number of ":i<k>=<v>" / ":d<k>=<v>" settings of iparam[k] / dparam[k] (k < 20), e.g.
 *       "506:i10=1" (VI_FPP with the update inside the line search) or "512:d3=1" (EG, fixed rho).
 *       Each repetition starts from r = u = 0 with fresh options; only
 *       fc3d_driver is timed (CLOCK_MONOTONIC). Prints one line
 *         info <info> iterations <iter> error <dparam[1]> seconds <median> self_score <e> reps <done>
 *       where self_score is this library's fc3d_compute_error of the returned reaction (not timed),
 *       and writes the final reaction to the out file (first line: its length, then one %.17g
 *       value a line).
 *       Environment: FC3D_COMPARE_REP_BUDGET=<seconds> (optional) starts another repetition only
 *       while the solve time so far plus the longest repetition stays within the budget, so that a
 *       long solve is repeated fewer times (at least once); the line ends with "reps <done>".
 *   score <problem.dat> <reaction_file>
 *       Prints "error <e>": this library's fc3d_compute_error (norm = ||q||) of the reaction.
 *
 * Exit status: 0 when the mode ran (whatever the solver's info), 2 on bad usage or unreadable
 * input, 3 when fc3d_driver rejects the input (info < 0; the line is still printed). */
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
#include "fc3d_compute_error.h"
#include "NonSmoothDrivers.h"

static double now_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int cmp_double(const void* a, const void* b) {
  double x = *(const double*)a, y = *(const double*)b;
  return (x > y) - (x < y);
}

static FrictionContactProblem* read_problem(const char* path) {
  FrictionContactProblem* problem = frictionContact_new_from_filename(path);
  if (!problem) {
    fprintf(stderr, "cannot read %s\n", path);
    return NULL;
  }
  if (problem->dimension != 3) {
    fprintf(stderr, "%s: dimension %d, not a 3D problem\n", path, problem->dimension);
    frictionContactProblem_free(problem);
    return NULL;
  }
  return problem;
}

static double norm_q(const FrictionContactProblem* problem) {
  int n = problem->dimension * problem->numberOfContacts;
  double s = 0.0;
  for (int i = 0; i < n; i++) s += problem->q[i] * problem->q[i];
  return sqrt(s);
}

/* This library's fc3d_compute_error of `reaction` (w is scratch, size n). */
static double score(FrictionContactProblem* problem, double* reaction, double* w, double tol) {
  SolverOptions* options = solver_options_create(SICONOS_FRICTION_3D_NSGS);
  double error = -1.0;
  fc3d_compute_error(problem, reaction, w, tol, options, norm_q(problem), &error);
  solver_options_delete(options);
  free(options);
  return error;
}

/* A solver spec: <id>, or 500/<local id>, followed by any number of ":i<k>=<v>" / ":d<k>=<v>"
   settings applied to the created options (e.g. "506:i10=1", "512:d3=1"). */
#define MAX_SETTINGS 8
struct solver_spec {
  int id, local, n_settings;
  struct {
    char kind; /* 'i' or 'd' */
    int index;
    double value;
  } settings[MAX_SETTINGS];
};

static int parse_solver(const char* spec, struct solver_spec* out) {
  char* end = NULL;
  long id = strtol(spec, &end, 10);
  if (end == spec || id <= 0) return -1;
  out->id = (int)id;
  out->local = 0;
  out->n_settings = 0;
  if (*end == '/') {
    if (id != SICONOS_FRICTION_3D_NSGS) return -1;
    const char* rest = end + 1;
    long l = strtol(rest, &end, 10);
    if (end == rest || l <= 0) return -1;
    out->local = (int)l;
  }
  while (*end == ':') {
    if (out->n_settings == MAX_SETTINGS) return -1;
    char kind = end[1];
    if (kind != 'i' && kind != 'd') return -1;
    const char* rest = end + 2;
    long k = strtol(rest, &end, 10);
    if (end == rest || k < 0 || k >= 20 || *end != '=') return -1;
    rest = end + 1;
    double v = strtod(rest, &end);
    if (end == rest) return -1;
    out->settings[out->n_settings].kind = kind;
    out->settings[out->n_settings].index = (int)k;
    out->settings[out->n_settings].value = v;
    out->n_settings++;
  }
  return *end == '\0' ? 0 : -1;
}

static int mode_solve(int argc, char** argv) {
  if (argc != 8) {
    fprintf(stderr, "usage: %s solve <problem.dat> <solver> <tol> <max_iter> <reps> <out_reaction_file>\n",
            argv[0]);
    return 2;
  }
  struct solver_spec spec;
  if (parse_solver(argv[3], &spec) != 0) {
    fprintf(stderr, "solver must be <id>, 500/<local id>, then :i<k>=<v> or :d<k>=<v> settings; got %s\n",
            argv[3]);
    return 2;
  }
  double tol = atof(argv[4]);
  int max_iter = atoi(argv[5]);
  int reps = atoi(argv[6]);
  if (reps < 1 || max_iter < 1 || !(tol > 0.0)) {
    fprintf(stderr, "tol > 0, max_iter >= 1 and reps >= 1 required\n");
    return 2;
  }
  FrictionContactProblem* problem = read_problem(argv[2]);
  if (!problem) return 2;
  int n = problem->dimension * problem->numberOfContacts;
  double* reaction = calloc((size_t)n + 1, sizeof(double));
  double* velocity = calloc((size_t)n + 1, sizeof(double));
  double* times = calloc((size_t)reps, sizeof(double));
  if (!reaction || !velocity || !times) {
    fprintf(stderr, "out of memory\n");
    return 2;
  }

  const char* budget_env = getenv("FC3D_COMPARE_REP_BUDGET");
  double budget = budget_env ? atof(budget_env) : 0.0; /* 0: no budget */
  int info = 0, iterations = 0, done = 0;
  double error = -1.0, spent = 0.0, longest = 0.0;
  for (int rep = 0; rep < reps; rep++) {
    if (rep > 0 && budget > 0.0 && spent + longest > budget) break;
    memset(reaction, 0, ((size_t)n + 1) * sizeof(double));
    memset(velocity, 0, ((size_t)n + 1) * sizeof(double));
    SolverOptions* options = solver_options_create(spec.id);
    if (!options) {
      fprintf(stderr, "solver_options_create(%d) failed\n", spec.id);
      return 2;
    }
    if (spec.local) solver_options_update_internal(options, 0, spec.local);
    options->dparam[SICONOS_DPARAM_TOL] = tol;
    options->iparam[SICONOS_IPARAM_MAX_ITER] = max_iter;
    for (int k = 0; k < spec.n_settings; k++) {
      if (spec.settings[k].kind == 'i')
        options->iparam[spec.settings[k].index] = (int)spec.settings[k].value;
      else
        options->dparam[spec.settings[k].index] = spec.settings[k].value;
    }

    double t0 = now_seconds();
    int rep_info = fc3d_driver(problem, reaction, velocity, options);
    times[rep] = now_seconds() - t0;
    spent += times[rep];
    if (times[rep] > longest) longest = times[rep];
    done = rep + 1;

    int rep_iter = options->iparam[SICONOS_IPARAM_ITER_DONE];
    if (rep > 0 && (rep_info != info || rep_iter != iterations))
      fprintf(stderr, "warning: repetition %d gave info %d, %d iterations (first: info %d, %d iterations)\n",
              rep, rep_info, rep_iter, info, iterations);
    info = rep_info;
    iterations = rep_iter;
    error = options->dparam[SICONOS_DPARAM_RESIDU];
    solver_options_delete(options);
    free(options);
    if (info < 0) break; /* rejected input: nothing to time */
  }

  qsort(times, (size_t)done, sizeof(double), cmp_double);
  double median = done % 2 ? times[done / 2] : 0.5 * (times[done / 2 - 1] + times[done / 2]);

  double self_score = -1.0;
  if (info >= 0) {
    double* w = calloc((size_t)n + 1, sizeof(double));
    self_score = score(problem, reaction, w, tol);
    free(w);
    FILE* out = fopen(argv[7], "w");
    if (!out) {
      fprintf(stderr, "cannot write %s\n", argv[7]);
      return 2;
    }
    fprintf(out, "%d\n", n);
    for (int i = 0; i < n; i++) fprintf(out, "%.17g\n", reaction[i]);
    if (fclose(out) != 0) {
      fprintf(stderr, "cannot write %s\n", argv[7]);
      return 2;
    }
  }
  printf("info %d iterations %d error %.17g seconds %.9e self_score %.17g reps %d\n", info, iterations, error,
         median, self_score, done);

  frictionContactProblem_free(problem);
  free(reaction);
  free(velocity);
  free(times);
  return info < 0 ? 3 : 0;
}

static int mode_score(int argc, char** argv) {
  if (argc != 4) {
    fprintf(stderr, "usage: %s score <problem.dat> <reaction_file>\n", argv[0]);
    return 2;
  }
  FrictionContactProblem* problem = read_problem(argv[2]);
  if (!problem) return 2;
  int n = problem->dimension * problem->numberOfContacts;
  FILE* in = fopen(argv[3], "r");
  if (!in) {
    fprintf(stderr, "cannot read %s\n", argv[3]);
    return 2;
  }
  int len = -1;
  if (fscanf(in, "%d", &len) != 1 || len != n) {
    fprintf(stderr, "%s: length %d, the problem has %d unknowns\n", argv[3], len, n);
    return 2;
  }
  double* reaction = calloc((size_t)n + 1, sizeof(double));
  double* w = calloc((size_t)n + 1, sizeof(double));
  for (int i = 0; i < n; i++) {
    if (fscanf(in, "%lf", &reaction[i]) != 1) {
      fprintf(stderr, "%s: truncated at value %d\n", argv[3], i);
      return 2;
    }
  }
  fclose(in);
  printf("error %.17g\n", score(problem, reaction, w, 1.0));
  frictionContactProblem_free(problem);
  free(reaction);
  free(w);
  return 0;
}

int main(int argc, char** argv) {
  if (argc >= 2 && strcmp(argv[1], "solve") == 0) return mode_solve(argc, argv);
  if (argc >= 2 && strcmp(argv[1], "score") == 0) return mode_score(argc, argv);
  fprintf(stderr,
          "usage: %s solve <problem.dat> <solver> <tol> <max_iter> <reps> <out_reaction_file>\n"
          "       %s score <problem.dat> <reaction_file>\n",
          argv[0], argv[0]);
  return 2;
}

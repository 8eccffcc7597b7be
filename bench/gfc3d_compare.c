/* Side-by-side benchmark of fc3d and Siconos Numerics 4.4 on global problems (gfc3d_driver):
 * one source compiled twice, against fc3d's compat headers or against the installed Siconos
 * (scripts/compare-siconos-global.sh does both).
 *
 * Modes:
 *   solve <problem.dat> <solver> <tol> <max_iter> <reps> <out_file>
 *       solver: a global id (600-615) with Siconos' defaults, followed by any number of
 *       ":i<k>=<v>" / ":d<k>=<v>" settings of iparam[k] / dparam[k] (k < 20). Every repetition
 *       reads the problem afresh (Siconos' _WR ids invert a sparse-block M in place) and starts
 *       from r = u = v = 0 with fresh options; only gfc3d_driver is timed (CLOCK_MONOTONIC).
 *       Prints one line
 *         info <info> iterations <iter> error <dparam[1]> seconds <median> self_score <e> reps <n>
 *       where self_score is this library's gfc3d_compute_error of the returned (r, u, v) on a fresh
 *       copy of the problem, and writes r then v to the out file (first line: their lengths, then
 *       one %.17g value a line).
 *   score <problem.dat> <out_file>
 *       Prints "error <e>": this library's gfc3d_compute_error of the (r, v) in the file, on the
 *       problem read afresh.
 * Environment: FC3D_COMPARE_REP_BUDGET=<seconds> starts another repetition only while the time
 * spent plus the longest repetition stays within the budget.
 * Exit status: 0 when the mode ran (whatever the solver's info), 2 on bad usage or unreadable
 * input, 3 when gfc3d_driver rejects the input (info < 0). */
#define _POSIX_C_SOURCE 199309L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "SiconosNumerics.h"
#include "GlobalFrictionContactProblem.h"
#include "NumericsMatrix.h"
#include "SolverOptions.h"
#include "Friction_cst.h"
#include "gfc3d_Solvers.h"
#include "gfc3d_compute_error.h"
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

static GlobalFrictionContactProblem* read_problem(const char* path) {
  GlobalFrictionContactProblem* problem = globalFrictionContact_new_from_filename(path);
  if (!problem) {
    fprintf(stderr, "cannot read %s\n", path);
    return NULL;
  }
  if (problem->dimension != 3) {
    fprintf(stderr, "%s: dimension %d, not a 3D global problem\n", path, problem->dimension);
    globalFrictionContact_free(problem);
    return NULL;
  }
  return problem;
}

static void free_problem(GlobalFrictionContactProblem* problem) {
  /* Siconos' free asserts env == NULL. */
  problem->env = NULL;
  globalFrictionContact_free(problem);
}

static double norm2(const double* x, int n) {
  double s = 0.0;
  for (int i = 0; i < n; i++) s += x[i] * x[i];
  return sqrt(s);
}

/* This library's gfc3d_compute_error of (r, v) on `problem`; u is scratch (size m). */
static double score(GlobalFrictionContactProblem* problem, double* r, double* u, double* v) {
  SolverOptions* options = solver_options_create(SICONOS_GLOBAL_FRICTION_3D_NSGS);
  double error = -1.0;
  int n = problem->M->size0;
  gfc3d_compute_error(problem, r, u, v, 1e-300, options, norm2(problem->q, n), 0.0, &error);
  solver_options_delete(options);
  free(options);
  return error;
}

#define MAX_SETTINGS 8
struct solver_spec {
  int id, n_settings;
  struct {
    char kind;
    int index;
    double value;
  } settings[MAX_SETTINGS];
};

static int parse_solver(const char* spec, struct solver_spec* out) {
  char* end = NULL;
  long id = strtol(spec, &end, 10);
  if (end == spec || id <= 0) return -1;
  out->id = (int)id;
  out->n_settings = 0;
  while (*end == ':') {
    if (out->n_settings == MAX_SETTINGS) return -1;
    char kind = end[1];
    if (kind != 'i' && kind != 'd') return -1;
    const char* rest = end + 2;
    long k = strtol(rest, &end, 10);
    if (end == rest || k < 0 || k >= 20 || *end != '=') return -1;
    rest = end + 1;
    double value = strtod(rest, &end);
    if (end == rest) return -1;
    out->settings[out->n_settings].kind = kind;
    out->settings[out->n_settings].index = (int)k;
    out->settings[out->n_settings].value = value;
    out->n_settings++;
  }
  return *end == '\0' ? 0 : -1;
}

static int write_result(const char* path, const double* r, int m, const double* v, int n) {
  FILE* f = fopen(path, "w");
  if (!f) return -1;
  fprintf(f, "%d %d\n", m, n);
  for (int i = 0; i < m; i++) fprintf(f, "%.17g\n", r[i]);
  for (int i = 0; i < n; i++) fprintf(f, "%.17g\n", v[i]);
  return fclose(f);
}

static int read_result(const char* path, double** r, int* m, double** v, int* n) {
  FILE* f = fopen(path, "r");
  if (!f) return -1;
  int ok = fscanf(f, "%d %d", m, n) == 2 && *m >= 0 && *n >= 0;
  *r = ok ? calloc((size_t)*m + 1, sizeof(double)) : NULL;
  *v = ok ? calloc((size_t)*n + 1, sizeof(double)) : NULL;
  for (int i = 0; ok && i < *m; i++) ok = fscanf(f, "%lf", &(*r)[i]) == 1;
  for (int i = 0; ok && i < *n; i++) ok = fscanf(f, "%lf", &(*v)[i]) == 1;
  fclose(f);
  return ok ? 0 : -1;
}

static int solve_mode(const char* path, const char* solver, double tol, int max_iter, int reps,
                      const char* out_path) {
  struct solver_spec spec;
  if (parse_solver(solver, &spec) != 0 || reps < 1) {
    fprintf(stderr, "bad solver spec %s\n", solver);
    return 2;
  }
  const char* budget_env = getenv("FC3D_COMPARE_REP_BUDGET");
  double rep_budget = budget_env ? atof(budget_env) : 0.0;
  double* times = calloc((size_t)reps, sizeof(double));
  double *r = NULL, *u = NULL, *v = NULL;
  int info = 0, iterations = 0, done = 0, m = 0, n = 0;
  double error = -1.0, spent = 0.0, longest = 0.0;
  for (int rep = 0; rep < reps; rep++) {
    if (rep > 0 && rep_budget > 0.0 && spent + longest > rep_budget) break;
    GlobalFrictionContactProblem* problem = read_problem(path);
    if (!problem) return 2;
    n = problem->M->size0;
    m = problem->dimension * problem->numberOfContacts;
    free(r);
    free(u);
    free(v);
    r = calloc((size_t)m + 1, sizeof(double));
    u = calloc((size_t)m + 1, sizeof(double));
    v = calloc((size_t)n + 1, sizeof(double));
    SolverOptions* options = solver_options_create(spec.id);
    if (!options) {
      fprintf(stderr, "solver_options_create(%d) failed\n", spec.id);
      return 2;
    }
    options->dparam[SICONOS_DPARAM_TOL] = tol;
    options->iparam[SICONOS_IPARAM_MAX_ITER] = max_iter;
    for (int k = 0; k < spec.n_settings; k++) {
      if (spec.settings[k].kind == 'i')
        options->iparam[spec.settings[k].index] = (int)spec.settings[k].value;
      else
        options->dparam[spec.settings[k].index] = spec.settings[k].value;
    }
    double t0 = now_seconds();
    info = gfc3d_driver(problem, r, u, v, options);
    double t = now_seconds() - t0;
    times[done++] = t;
    spent += t;
    if (t > longest) longest = t;
    iterations = options->iparam[SICONOS_IPARAM_ITER_DONE];
    error = options->dparam[SICONOS_DPARAM_RESIDU];
    solver_options_delete(options);
    free(options);
    free_problem(problem);
    if (info < 0) break;
  }
  qsort(times, (size_t)done, sizeof(double), cmp_double);
  GlobalFrictionContactProblem* fresh = read_problem(path);
  if (!fresh) return 2;
  double self = score(fresh, r, u, v);
  free_problem(fresh);
  printf("info %d iterations %d error %.6e seconds %.6e self_score %.6e reps %d\n", info, iterations,
         error, times[done / 2], self, done);
  if (write_result(out_path, r, m, v, n) != 0) {
    fprintf(stderr, "cannot write %s\n", out_path);
    return 2;
  }
  free(times);
  free(r);
  free(u);
  free(v);
  return info < 0 ? 3 : 0;
}

static int score_mode(const char* path, const char* result_path) {
  double *r = NULL, *v = NULL;
  int m = 0, n = 0;
  if (read_result(result_path, &r, &m, &v, &n) != 0) {
    fprintf(stderr, "cannot read %s\n", result_path);
    return 2;
  }
  GlobalFrictionContactProblem* problem = read_problem(path);
  if (!problem) return 2;
  if (problem->M->size0 != n || problem->dimension * problem->numberOfContacts != m) {
    fprintf(stderr, "%s: sizes differ from the result's\n", path);
    return 2;
  }
  double* u = calloc((size_t)m + 1, sizeof(double));
  printf("error %.6e\n", score(problem, r, u, v));
  free_problem(problem);
  free(u);
  free(r);
  free(v);
  return 0;
}

int main(int argc, char** argv) {
  if (argc == 8 && strcmp(argv[1], "solve") == 0)
    return solve_mode(argv[2], argv[3], atof(argv[4]), atoi(argv[5]), atoi(argv[6]), argv[7]);
  if (argc == 4 && strcmp(argv[1], "score") == 0) return score_mode(argv[2], argv[3]);
  fprintf(stderr,
          "usage: %s solve <problem.dat> <solver> <tol> <max_iter> <reps> <out_file>\n"
          "       %s score <problem.dat> <out_file>\n",
          argv[0], argv[0]);
  return 2;
}

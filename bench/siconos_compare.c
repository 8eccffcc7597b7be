/* Side-by-side benchmark of fc3d and Siconos Numerics 4.4: one source compiled twice, against
 * fc3d's compat headers or against the installed Siconos (scripts/compare-siconos.sh does both).
 *
 *   cc -O2 -I$(pkg-config --variable=siconos_includedir fc3d) $(pkg-config --cflags fc3d) \
 *      bench/siconos_compare.c $(pkg-config --libs fc3d) -lm -o cmp_fc3d   (fc3d installed: README)
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
 *   ladder <problem.dat> <solver> <tol> <budgets> <reps> <out_prefix>
 *       Equal time budget for a solver without one (scripts/compare-siconos-budget.sh): runs the
 *       solver with the iteration limits 1, 2, 4, 8, ... (each run from r = u = 0 with fresh
 *       options, the whole fc3d_driver call timed, median of up to <reps> repetitions), until a
 *       run takes longer than half the largest budget, stops by itself (info 0, or fewer
 *       iterations than its limit) or the ladder has spent 10x the largest budget plus 10 s.
 *       Then, per budget, one more run whose limit aims at 95% of the budget (interpolated
 *       linearly in time between the last run within the budget and the next one, or
 *       extrapolated from the last run), so that the budget is used nearly in full. <budgets> is a
 *       comma-separated list of seconds. Prints one line per run,
 *         run max_iter <k> info <i> iterations <it> error <dparam[1]> score <e> seconds <t> reps <n>
 *       (score: this library's fc3d_compute_error of the returned reaction), and whenever a run
 *       within budget j has a smaller score than the best so far, writes its reaction to
 *       <out_prefix>.<j> (j = 0, 1, ... in the order given) and prints
 *         best <j> budget <b> max_iter <k> info <i> iterations <it> score <e> seconds <t>
 *       Lines are flushed at once: a ladder cut by a timeout keeps what it printed.
 *   anytime <problem.dat> <solver> <tol> <budgets> <reps> <out_prefix>   (fc3d only)
 *       Per budget b: the solver with tolerance <tol> (0: anytime), no iteration limit and the
 *       time budget dparam[FC3D_DPARAM_TIME_BUDGET] = b, timed as above. A run whose median time
 *       exceeds b is not counted: it is run again with the budget given to the solver scaled by
 *       0.9 b / t (at most 4 times). Prints and writes "best" lines and files as ladder does
 *       (max_iter is then the budget given to the solver, in ns).
 *
 * Modes solve, ladder and anytime accept the FC3D_COMPARE_REP_BUDGET environment variable.
 * Exit status: 0 when the mode ran (whatever the solver's info), 2 on bad usage or unreadable
 * input, 3 when fc3d_driver rejects the input (info < 0; the line is still printed). */
#define _POSIX_C_SOURCE 199309L
#include <limits.h>
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

/* The outcome of a timed solve: the last repetition's results and the median time; under a time
   budget (a solver whose result depends on time), the results and time of the median repetition. */
struct timed_run {
  int info, iterations, reps;
  double error, seconds;
};

/* Solves `problem` with `spec` up to `reps` times, each from r = u = 0 with fresh options
   (tolerance `tol`, iteration limit `max_iter`, and when `time_budget` > 0 fc3d's
   dparam[FC3D_DPARAM_TIME_BUDGET]), timing only fc3d_driver; another repetition starts only
   while the time spent plus the longest repetition stays within `rep_budget` (0: no limit).
   `times` has room for `reps` values. Returns 0, or 2 when the options cannot be created. */
static int timed_solve(FrictionContactProblem* problem, const struct solver_spec* spec, double tol,
                       int max_iter, double time_budget, int reps, double rep_budget, double* reaction,
                       double* velocity, double* times, struct timed_run* out) {
  int n = problem->dimension * problem->numberOfContacts;
  double spent = 0.0, longest = 0.0;
  /* Under a budget each repetition's result is kept, so that the one returned is the one timed. */
  struct rep_result {
    int info, iterations;
    double error, seconds;
  }* results = NULL;
  double* reactions = NULL;
  if (time_budget > 0.0 && reps > 1) {
    results = calloc((size_t)reps, sizeof *results);
    reactions = calloc((size_t)reps * ((size_t)n + 1), sizeof(double));
    if (!results || !reactions) {
      fprintf(stderr, "out of memory\n");
      free(results);
      free(reactions);
      return 2;
    }
  }
  out->info = 0;
  out->iterations = 0;
  out->reps = 0;
  out->error = -1.0;
  for (int rep = 0; rep < reps; rep++) {
    if (rep > 0 && rep_budget > 0.0 && spent + longest > rep_budget) break;
    memset(reaction, 0, ((size_t)n + 1) * sizeof(double));
    memset(velocity, 0, ((size_t)n + 1) * sizeof(double));
    SolverOptions* options = solver_options_create(spec->id);
    if (!options) {
      fprintf(stderr, "solver_options_create(%d) failed\n", spec->id);
      return 2;
    }
    if (spec->local) solver_options_update_internal(options, 0, spec->local);
    options->dparam[SICONOS_DPARAM_TOL] = tol;
    options->iparam[SICONOS_IPARAM_MAX_ITER] = max_iter;
    for (int k = 0; k < spec->n_settings; k++) {
      if (spec->settings[k].kind == 'i')
        options->iparam[spec->settings[k].index] = (int)spec->settings[k].value;
      else
        options->dparam[spec->settings[k].index] = spec->settings[k].value;
    }
#ifdef FC3D_DPARAM_TIME_BUDGET
    if (time_budget > 0.0) options->dparam[FC3D_DPARAM_TIME_BUDGET] = time_budget;
#else
    (void)time_budget;
#endif

    double t0 = now_seconds();
    int rep_info = fc3d_driver(problem, reaction, velocity, options);
    times[rep] = now_seconds() - t0;
    spent += times[rep];
    if (times[rep] > longest) longest = times[rep];
    out->reps = rep + 1;

    int rep_iter = options->iparam[SICONOS_IPARAM_ITER_DONE];
    if (rep > 0 && time_budget == 0.0 && (rep_info != out->info || rep_iter != out->iterations))
      fprintf(stderr, "warning: repetition %d gave info %d, %d iterations (first: info %d, %d iterations)\n",
              rep, rep_info, rep_iter, out->info, out->iterations);
    out->info = rep_info;
    out->iterations = rep_iter;
    out->error = options->dparam[SICONOS_DPARAM_RESIDU];
    solver_options_delete(options);
    free(options);
    if (results) {
      results[rep] = (struct rep_result){rep_info, rep_iter, out->error, times[rep]};
      memcpy(reactions + (size_t)rep * ((size_t)n + 1), reaction, ((size_t)n + 1) * sizeof(double));
    }
    if (rep_info < 0) break; /* rejected input: nothing to time */
  }
  int done = out->reps;
  qsort(times, (size_t)done, sizeof(double), cmp_double);
  out->seconds = done % 2 ? times[done / 2] : 0.5 * (times[done / 2 - 1] + times[done / 2]);
  if (results) {
    /* The repetition at rank done / 2 of the sorted times (the median, or the slower of the two
       middle ones): its reaction, outcome and time. */
    int median = 0;
    for (int rep = 0; rep < done; rep++)
      if (results[rep].seconds == times[done / 2]) median = rep;
    out->info = results[median].info;
    out->iterations = results[median].iterations;
    out->error = results[median].error;
    out->seconds = results[median].seconds;
    memcpy(reaction, reactions + (size_t)median * ((size_t)n + 1), ((size_t)n + 1) * sizeof(double));
    free(results);
    free(reactions);
  }
  return 0;
}

static double rep_budget_from_env(void) {
  const char* budget_env = getenv("FC3D_COMPARE_REP_BUDGET");
  return budget_env ? atof(budget_env) : 0.0; /* 0: no budget */
}

/* Writes the reaction (first line: its length, then one %.17g value a line). */
static int write_reaction(const char* path, const double* reaction, int n) {
  FILE* out = fopen(path, "w");
  if (!out) {
    fprintf(stderr, "cannot write %s\n", path);
    return 2;
  }
  fprintf(out, "%d\n", n);
  for (int i = 0; i < n; i++) fprintf(out, "%.17g\n", reaction[i]);
  if (fclose(out) != 0) {
    fprintf(stderr, "cannot write %s\n", path);
    return 2;
  }
  return 0;
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

  struct timed_run run;
  if (timed_solve(problem, &spec, tol, max_iter, 0.0, reps, rep_budget_from_env(), reaction, velocity, times,
                  &run) != 0)
    return 2;

  double self_score = -1.0;
  if (run.info >= 0) {
    double* w = calloc((size_t)n + 1, sizeof(double));
    self_score = score(problem, reaction, w, tol);
    free(w);
    if (write_reaction(argv[7], reaction, n) != 0) return 2;
  }
  printf("info %d iterations %d error %.17g seconds %.9e self_score %.17g reps %d\n", run.info, run.iterations,
         run.error, run.seconds, self_score, run.reps);

  frictionContactProblem_free(problem);
  free(reaction);
  free(velocity);
  free(times);
  return run.info < 0 ? 3 : 0;
}

#define MAX_BUDGETS 16

/* The best run within each budget so far: its score (+inf: none yet). */
struct budget_table {
  int count;
  double seconds[MAX_BUDGETS], best[MAX_BUDGETS];
};

static int parse_budgets(const char* list, struct budget_table* table) {
  table->count = 0;
  const char* p = list;
  while (*p) {
    if (table->count == MAX_BUDGETS) return -1;
    char* end = NULL;
    double b = strtod(p, &end);
    if (end == p || !(b > 0.0)) return -1;
    table->seconds[table->count] = b;
    table->best[table->count] = INFINITY;
    table->count++;
    p = end;
    if (*p == ',') p++;
    else if (*p) return -1;
  }
  return table->count > 0 ? 0 : -1;
}

/* Scores the run's reaction and records it for every budget j in [first, last] it fits and
   improves: writes <prefix>.<j> and prints a "best" line. `limit` is printed as max_iter. */
static int offer(FrictionContactProblem* problem, struct budget_table* table, int first, int last,
                 const struct timed_run* run, double run_score, long long limit, const double* reaction,
                 const char* prefix) {
  int n = problem->dimension * problem->numberOfContacts;
  if (run->info < 0 || !(run_score >= 0.0)) return 0; /* rejected, or NaN: never a best */
  for (int j = first; j <= last; j++) {
    if (run->seconds > table->seconds[j] || !(run_score < table->best[j])) continue;
    table->best[j] = run_score;
    char path[4096];
    snprintf(path, sizeof path, "%s.%d", prefix, j);
    if (write_reaction(path, reaction, n) != 0) return 2;
    printf("best %d budget %.9g max_iter %lld info %d iterations %d score %.17g seconds %.9e\n", j,
           table->seconds[j], limit, run->info, run->iterations, run_score, run->seconds);
    fflush(stdout);
  }
  return 0;
}

/* Shared set-up of the ladder and anytime modes. */
struct budget_mode {
  struct solver_spec spec;
  double tol;
  int reps;
  struct budget_table table;
  FrictionContactProblem* problem;
  double *reaction, *velocity, *times, *w;
  int n;
};

static int budget_mode_init(int argc, char** argv, struct budget_mode* m) {
  if (argc != 8) {
    fprintf(stderr, "usage: %s %s <problem.dat> <solver> <tol> <budgets> <reps> <out_prefix>\n", argv[0],
            argv[1]);
    return 2;
  }
  if (parse_solver(argv[3], &m->spec) != 0) {
    fprintf(stderr, "solver must be <id>, 500/<local id>, then :i<k>=<v> or :d<k>=<v> settings; got %s\n",
            argv[3]);
    return 2;
  }
  m->tol = atof(argv[4]);
  m->reps = atoi(argv[6]);
  if (parse_budgets(argv[5], &m->table) != 0 || m->reps < 1 || !(m->tol >= 0.0)) {
    fprintf(stderr, "budgets: comma-separated positive seconds (at most %d); tol >= 0; reps >= 1\n",
            MAX_BUDGETS);
    return 2;
  }
  m->problem = read_problem(argv[2]);
  if (!m->problem) return 2;
  m->n = m->problem->dimension * m->problem->numberOfContacts;
  m->reaction = calloc((size_t)m->n + 1, sizeof(double));
  m->velocity = calloc((size_t)m->n + 1, sizeof(double));
  m->w = calloc((size_t)m->n + 1, sizeof(double));
  m->times = calloc((size_t)m->reps, sizeof(double));
  if (!m->reaction || !m->velocity || !m->w || !m->times) {
    fprintf(stderr, "out of memory\n");
    return 2;
  }
  return 0;
}

static void budget_mode_free(struct budget_mode* m) {
  frictionContactProblem_free(m->problem);
  free(m->reaction);
  free(m->velocity);
  free(m->w);
  free(m->times);
}

/* One ladder run with iteration limit k: timed, scored, offered to every budget. */
static int ladder_run(struct budget_mode* m, int k, const char* prefix, struct timed_run* run) {
  if (timed_solve(m->problem, &m->spec, m->tol, k, 0.0, m->reps, rep_budget_from_env(), m->reaction, m->velocity,
                  m->times, run) != 0)
    return 2;
  double run_score = run->info >= 0 ? score(m->problem, m->reaction, m->w, m->tol) : NAN;
  printf("run max_iter %d info %d iterations %d error %.17g score %.17g seconds %.9e reps %d\n", k, run->info,
         run->iterations, run->error, run_score, run->seconds, run->reps);
  fflush(stdout);
  return offer(m->problem, &m->table, 0, m->table.count - 1, run, run_score, k, m->reaction, prefix);
}

#define LADDER_POINTS 31

static int mode_ladder(int argc, char** argv) {
  struct budget_mode m;
  int status = budget_mode_init(argc, argv, &m);
  if (status != 0) return status;
  if (!(m.tol > 0.0)) {
    fprintf(stderr, "ladder: tol > 0 required (the solver's own stopping test)\n");
    return 2;
  }
  const char* prefix = argv[7];
  double largest = 0.0;
  for (int j = 0; j < m.table.count; j++)
    if (m.table.seconds[j] > largest) largest = m.table.seconds[j];
  int limits[LADDER_POINTS];
  double seconds[LADDER_POINTS];
  int points = 0, stopped_by_itself = 0;
  double started = now_seconds();
  for (int k = 1; points < LADDER_POINTS; k *= 2) {
    struct timed_run run;
    if ((status = ladder_run(&m, k, prefix, &run)) != 0) return status;
    limits[points] = k;
    seconds[points] = run.seconds;
    points++;
    /* Converged, stopped by itself or rejected: a higher limit gives the same run. */
    stopped_by_itself = run.info <= 0 || run.iterations < k;
    /* Past half the largest budget the next point would be over it: extrapolate instead. */
    if (stopped_by_itself || run.seconds > 0.5 * largest || now_seconds() - started > 10.0 * largest + 10.0 ||
        k > (1 << 29))
      break;
  }
  /* Per budget, one run whose limit aims at 95% of it, interpolated linearly in time between
     the last ladder point within the budget and the next one (extrapolated from the last point
     when the ladder ended there). */
  for (int j = 0; j < m.table.count; j++) {
    double b = m.table.seconds[j], target = 0.95 * b;
    int lo = -1;
    for (int i = 0; i < points; i++)
      if (seconds[i] <= b) lo = i;
    if (lo < 0 || !(seconds[lo] > 0.0) || seconds[lo] >= target) continue;
    long long k;
    if (lo + 1 < points) {
      if (seconds[lo + 1] <= seconds[lo]) continue;
      double t = (target - seconds[lo]) / (seconds[lo + 1] - seconds[lo]);
      k = limits[lo] + (long long)(t * (double)(limits[lo + 1] - limits[lo]));
      if (k >= limits[lo + 1]) continue;
    } else {
      if (stopped_by_itself) continue;
      k = (long long)((double)limits[lo] * target / seconds[lo]);
      if (k > INT_MAX) k = INT_MAX;
    }
    if (k <= limits[lo]) continue;
    struct timed_run run;
    if ((status = ladder_run(&m, (int)k, prefix, &run)) != 0) return status;
  }
  budget_mode_free(&m);
  return 0;
}

static int mode_anytime(int argc, char** argv) {
#ifdef FC3D_DPARAM_TIME_BUDGET
  struct budget_mode m;
  int status = budget_mode_init(argc, argv, &m);
  if (status != 0) return status;
  const char* prefix = argv[7];
  for (int j = 0; j < m.table.count; j++) {
    double b = m.table.seconds[j], given = b;
    for (int attempt = 0; attempt < 5; attempt++) {
      struct timed_run run;
      if (timed_solve(m.problem, &m.spec, m.tol, INT_MAX, given, m.reps, rep_budget_from_env(), m.reaction,
                      m.velocity, m.times, &run) != 0)
        return 2;
      double run_score = run.info >= 0 ? score(m.problem, m.reaction, m.w, m.tol) : NAN;
      long long given_ns = (long long)(given * 1e9);
      printf("run max_iter %lld info %d iterations %d error %.17g score %.17g seconds %.9e reps %d\n", given_ns,
             run.info, run.iterations, run.error, run_score, run.seconds, run.reps);
      fflush(stdout);
      if ((status = offer(m.problem, &m.table, j, j, &run, run_score, given_ns, m.reaction, prefix)) != 0)
        return status;
      if (run.info < 0 || run.seconds <= b) break;
      given *= 0.9 * b / run.seconds;
    }
  }
  budget_mode_free(&m);
  return 0;
#else
  (void)argc;
  fprintf(stderr, "%s: anytime mode needs fc3d's time budget (dparam[FC3D_DPARAM_TIME_BUDGET])\n", argv[0]);
  return 2;
#endif
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
  if (argc >= 2 && strcmp(argv[1], "ladder") == 0) return mode_ladder(argc, argv);
  if (argc >= 2 && strcmp(argv[1], "anytime") == 0) return mode_anytime(argc, argv);
  fprintf(stderr,
          "usage: %s solve <problem.dat> <solver> <tol> <max_iter> <reps> <out_reaction_file>\n"
          "       %s score <problem.dat> <reaction_file>\n"
          "       %s ladder|anytime <problem.dat> <solver> <tol> <budgets> <reps> <out_prefix>\n",
          argv[0], argv[0], argv[0]);
  return 2;
}

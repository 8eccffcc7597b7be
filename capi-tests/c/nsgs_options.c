/* NSGS sweep options through the C API, set with Siconos' option indices as a host would:
 * shuffling (reproducible bit for bit with a seed), relaxation, freezing, local tolerance
 * strategies, evaluation frequency, Dumont's criterion, and the rejection of bad values with
 * FC3D_ERR_INVALID_OPTION and untouched outputs. Returns 0 on success. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "SiconosNumerics.h"
#include "FrictionContactProblem.h"
#include "SolverOptions.h"
#include "Friction_cst.h"
#include "NonSmoothDrivers.h"
#include "fc3d_compute_error.h"

#define FAIL(...)                                                                  \
  do {                                                                             \
    fprintf(stderr, "%s:%d: ", __FILE__, __LINE__);                                \
    fprintf(stderr, __VA_ARGS__);                                                  \
    fprintf(stderr, " [last fc3d error: %s]\n", fc3d_last_error_message());        \
    return 1;                                                                      \
  } while (0)

#define CHECK(cond, ...)                                                           \
  do {                                                                             \
    if (!(cond)) FAIL(__VA_ARGS__);                                                \
  } while (0)

typedef struct {
  int info;
  int iterations;
  double error;
  double dumont;
} Run;

/* Solves from r = 0 with NSGS options adjusted by `set`; r and u receive the result. */
static int solve_with(FrictionContactProblem* p, void (*set)(SolverOptions*), double* r,
                      double* u, Run* out) {
  int n = 3 * p->numberOfContacts;
  SolverOptions* o = solver_options_create(SICONOS_FRICTION_3D_NSGS);
  CHECK(o != NULL, "solver_options_create");
  o->dparam[SICONOS_DPARAM_TOL] = 1e-8;
  o->iparam[SICONOS_IPARAM_MAX_ITER] = 100000;
  o->dparam[FC3D_DPARAM_DUMONT_CRITERION] = -1.0;
  set(o);
  memset(r, 0, sizeof(double) * (size_t)n);
  memset(u, 0, sizeof(double) * (size_t)n);
  out->info = fc3d_driver(p, r, u, o);
  out->iterations = o->iparam[SICONOS_IPARAM_ITER_DONE];
  out->error = o->dparam[SICONOS_DPARAM_RESIDU];
  out->dumont = o->dparam[FC3D_DPARAM_DUMONT_CRITERION];
  double check = -1.0;
  double* w = calloc((size_t)n, sizeof(double));
  double nq = 0.0;
  for (int i = 0; i < n; i++) nq += p->q[i] * p->q[i];
  int e = fc3d_compute_error(p, r, w, 1e-8, o, sqrt(nq), &check);
  free(w);
  solver_options_delete(o);
  free(o);
  CHECK(e == 0 || e == 1, "fc3d_compute_error returned %d", e);
  /* dparam[1] is the natural-map error of what was returned, whatever the options. */
  CHECK(out->info < 0 || check == out->error, "reported %.17g, recomputed %.17g", out->error, check);
  return 0;
}

static void shuffle_each_sweep(SolverOptions* o) {
  o->iparam[SICONOS_FRICTION_3D_NSGS_SHUFFLE] = SICONOS_FRICTION_3D_NSGS_SHUFFLE_TRUE_EACH_LOOP;
  o->iparam[SICONOS_FRICTION_3D_NSGS_SHUFFLE_SEED] = 1234;
}
static void shuffle_once(SolverOptions* o) {
  o->iparam[SICONOS_FRICTION_3D_NSGS_SHUFFLE] = SICONOS_FRICTION_3D_NSGS_SHUFFLE_TRUE;
  o->iparam[SICONOS_FRICTION_3D_NSGS_SHUFFLE_SEED] = -5;
}
static void relax(SolverOptions* o) {
  o->iparam[SICONOS_FRICTION_3D_NSGS_RELAXATION] = SICONOS_FRICTION_3D_NSGS_RELAXATION_TRUE;
  o->dparam[SICONOS_FRICTION_3D_NSGS_RELAXATION_VALUE] = 1.2;
}
static void freeze(SolverOptions* o) { o->iparam[SICONOS_FRICTION_3D_NSGS_FREEZING_CONTACT] = 5; }
static void adaptive(SolverOptions* o) {
  o->iparam[SICONOS_FRICTION_3D_IPARAM_INTERNAL_ERROR_STRATEGY] =
      SICONOS_FRICTION_3D_INTERNAL_ERROR_STRATEGY_ADAPTIVE;
}
static void adaptive_n(SolverOptions* o) {
  o->iparam[SICONOS_FRICTION_3D_IPARAM_INTERNAL_ERROR_STRATEGY] =
      SICONOS_FRICTION_3D_INTERNAL_ERROR_STRATEGY_ADAPTIVE_N_CONTACT;
}
static void every_5(SolverOptions* o) {
  o->iparam[SICONOS_FRICTION_3D_IPARAM_ERROR_EVALUATION] = SICONOS_FRICTION_3D_NSGS_ERROR_EVALUATION_FULL;
  o->iparam[SICONOS_FRICTION_3D_IPARAM_ERROR_EVALUATION_FREQUENCY] = 5;
}
static void dumont(SolverOptions* o) {
  o->iparam[SICONOS_FRICTION_3D_IPARAM_ERROR_EVALUATION] = FC3D_ERROR_EVALUATION_DUMONT;
  o->dparam[SICONOS_DPARAM_TOL] = 1e-6;
}
static void rescale_scalar(SolverOptions* o) {
  o->iparam[SICONOS_FRICTION_3D_IPARAM_RESCALING] = SICONOS_FRICTION_3D_RESCALING_SCALAR;
}
static void bad_rescaling(SolverOptions* o) {
  o->iparam[SICONOS_FRICTION_3D_IPARAM_RESCALING] = SICONOS_FRICTION_3D_RESCALING_BALANCING_M;
}
static void bad_omega(SolverOptions* o) {
  relax(o);
  o->dparam[SICONOS_FRICTION_3D_NSGS_RELAXATION_VALUE] = 2.5;
}
static void bad_relaxation_flag(SolverOptions* o) { o->iparam[SICONOS_FRICTION_3D_NSGS_RELAXATION] = 7; }
static void bad_shuffle(SolverOptions* o) { o->iparam[SICONOS_FRICTION_3D_NSGS_SHUFFLE] = 3; }
static void bad_ratio(SolverOptions* o) {
  adaptive(o);
  o->dparam[SICONOS_FRICTION_3D_DPARAM_INTERNAL_ERROR_RATIO] = 0.0;
}
static void bad_strategy(SolverOptions* o) {
  o->iparam[SICONOS_FRICTION_3D_IPARAM_INTERNAL_ERROR_STRATEGY] = 9;
}
static void bad_frequency(SolverOptions* o) {
  o->iparam[SICONOS_FRICTION_3D_IPARAM_ERROR_EVALUATION_FREQUENCY] = -1;
}
static void bad_freezing(SolverOptions* o) { o->iparam[SICONOS_FRICTION_3D_NSGS_FREEZING_CONTACT] = -2; }
static void bad_evaluation(SolverOptions* o) {
  o->iparam[SICONOS_FRICTION_3D_IPARAM_ERROR_EVALUATION] = 3; /* Siconos' ADAPTIVE: not in fc3d */
}

int capi_check_nsgs_options(const char* data_dir) {
  char path[4096];
  snprintf(path, sizeof path, "%s/Confeti-ex13-Fc3D-SBM.dat", data_dir);
  FrictionContactProblem* p = frictionContact_new_from_filename(path);
  CHECK(p != NULL, "cannot read %s", path);
  int n = 3 * p->numberOfContacts;
  double* r1 = calloc((size_t)n, sizeof(double));
  double* u1 = calloc((size_t)n, sizeof(double));
  double* r2 = calloc((size_t)n, sizeof(double));
  double* u2 = calloc((size_t)n, sizeof(double));
  Run a, b;

  /* Shuffling with a seed: two runs, bit for bit the same. */
  void (*shuffles[])(SolverOptions*) = {shuffle_each_sweep, shuffle_once};
  for (int k = 0; k < 2; k++) {
    if (solve_with(p, shuffles[k], r1, u1, &a) || solve_with(p, shuffles[k], r2, u2, &b)) return 1;
    CHECK(a.info == 0, "shuffle %d: info %d, error %g", k, a.info, a.error);
    CHECK(a.iterations == b.iterations, "shuffle %d: %d vs %d iterations", k, a.iterations, b.iterations);
    CHECK(memcmp(r1, r2, sizeof(double) * (size_t)n) == 0, "shuffle %d: reactions differ", k);
    CHECK(memcmp(u1, u2, sizeof(double) * (size_t)n) == 0, "shuffle %d: velocities differ", k);
  }

  /* Each option converges, and reports its honest error (checked in solve_with). */
  void (*converging[])(SolverOptions*) = {relax, freeze, adaptive, adaptive_n, every_5, rescale_scalar};
  for (int k = 0; k < 6; k++) {
    if (solve_with(p, converging[k], r1, u1, &a)) return 1;
    CHECK(a.info == 0 && a.error <= 1e-8, "option %d: info %d, error %g", k, a.info, a.error);
  }
  if (solve_with(p, every_5, r1, u1, &a)) return 1;
  CHECK(a.iterations % 5 == 0, "frequency 5: %d iterations", a.iterations);

  /* Dumont's criterion: written to its own dparam, beside the natural-map error. */
  if (solve_with(p, dumont, r1, u1, &a)) return 1;
  CHECK(a.dumont >= 0.0 && a.dumont <= 1e-6, "Dumont criterion %g", a.dumont);
  CHECK((a.info == 0) == (a.error <= 1e-6), "info %d with error %g", a.info, a.error);

  /* Bad values: rejected, outputs untouched. */
  void (*bad[])(SolverOptions*) = {bad_omega,    bad_relaxation_flag, bad_shuffle,    bad_ratio,
                                   bad_strategy, bad_frequency,       bad_freezing,   bad_evaluation,
                                   bad_rescaling};
  for (int k = 0; k < 9; k++) {
    SolverOptions* o = solver_options_create(SICONOS_FRICTION_3D_NSGS);
    bad[k](o);
    for (int i = 0; i < n; i++) r1[i] = u1[i] = 42.0;
    o->iparam[SICONOS_IPARAM_ITER_DONE] = -7;
    int info = fc3d_driver(p, r1, u1, o);
    CHECK(info == FC3D_ERR_INVALID_OPTION, "bad option %d: returned %d", k, info);
    CHECK(strlen(fc3d_last_error_message()) > 0, "bad option %d: no message", k);
    CHECK(o->iparam[SICONOS_IPARAM_ITER_DONE] == -7, "bad option %d: iparam written", k);
    for (int i = 0; i < n; i++) CHECK(r1[i] == 42.0 && u1[i] == 42.0, "bad option %d: output written", k);
    solver_options_delete(o);
    free(o);
  }

  free(r1); free(u1); free(r2); free(u2);
  frictionContactProblem_free(p);
  return 0;
}

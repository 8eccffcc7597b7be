/* Rolling friction through the C API as a Siconos host uses it: rolling_fc3d_driver and
 * rolling_fc2d_driver on problems read from Siconos' rolling files and built by hand, the
 * struct's life cycle and files, rolling_fc3d_compute_error and its unitary form, the trivial
 * case, and the rejections (wrong id, wrong dimension, NULL pointers) with untouched outputs.
 * Returns 0 on success. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "SiconosNumerics.h"
#include "RollingFrictionContactProblem.h"
#include "SolverOptions.h"
#include "Friction_cst.h"
#include "NonSmoothDrivers.h"
#include "rolling_fc_Solvers.h"
#include "rolling_fc3d_compute_error.h"
#include "rolling_fc2d_compute_error.h"

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
  double reported_error;
  double api_error;
  double independent_error;
  int dimension;
} RollingResult;

/* Projection on the rolling cone written in plain C, independently of the library: for a fixed
 * normal part t the nearest point of the cone scales each part into its disk; t minimises a
 * convex piecewise quadratic whose minimiser is found by bisection on its derivative. */
static void project(double* x, int d, double mu, double mur) {
  int m = (d - 1) / 2;
  double nt = 0, nr = 0;
  for (int k = 1; k <= m; k++) {
    nt += x[k] * x[k];
    nr += x[k + m] * x[k + m];
  }
  nt = sqrt(nt);
  nr = sqrt(nr);
  if (nt <= mu * x[0] && nr <= mur * x[0]) return;
  if (mu * nt + mur * nr <= -x[0]) {
    for (int k = 0; k < d; k++) x[k] = 0;
    return;
  }
  /* f'(t)/2 = t - x0 - mu (nt - mu t)_+ - mur (nr - mur t)_+, increasing in t. */
  double lo = 0, hi = fabs(x[0]) + nt + nr + 1;
  for (int it = 0; it < 200; it++) {
    double t = 0.5 * (lo + hi);
    double g = t - x[0] - mu * fmax(0, nt - mu * t) - mur * fmax(0, nr - mur * t);
    if (g > 0) hi = t; else lo = t;
  }
  double t = 0.5 * (lo + hi);
  double st = nt > mu * t ? mu * t / nt : 1, sr = nr > mur * t ? mur * t / nr : 1;
  x[0] = t;
  for (int k = 1; k <= m; k++) {
    x[k] *= st;
    x[k + m] *= sr;
  }
}

/* The rolling natural-map error in plain C from W read entry by entry. */
static double independent_error(RollingFrictionContactProblem* p, const double* r) {
  int d = p->dimension, m = (d - 1) / 2, n = d * p->numberOfContacts;
  double* u = malloc(sizeof(double) * (size_t)n);
  for (int i = 0; i < n; i++) {
    u[i] = p->q[i];
    for (int j = 0; j < n; j++) u[i] += NM_get_value(p->M, i, j) * r[j];
  }
  double s = 0, nq = 0, nr = 0, nu = 0;
  for (int c = 0; c < p->numberOfContacts; c++) {
    const double* rc = r + d * c;
    const double* uc = u + d * c;
    double ut = 0, ur = 0, x[5];
    for (int k = 1; k <= m; k++) {
      ut += uc[k] * uc[k];
      ur += uc[k + m] * uc[k + m];
    }
    x[0] = rc[0] - (uc[0] + p->mu[c] * sqrt(ut) + p->mu_r[c] * sqrt(ur));
    for (int k = 1; k < d; k++) x[k] = rc[k] - uc[k];
    project(x, d, p->mu[c], p->mu_r[c]);
    for (int k = 0; k < d; k++) s += (rc[k] - x[k]) * (rc[k] - x[k]);
  }
  for (int i = 0; i < n; i++) {
    nq += p->q[i] * p->q[i];
    nr += r[i] * r[i];
    nu += u[i] * u[i];
  }
  free(u);
  double scale = fmax(sqrt(nq), fmax(sqrt(nr), sqrt(nu)));
  return scale > 0 ? sqrt(s) / scale : sqrt(s);
}

/* Solves a rolling file with NSGS (3000 / 4000 by the file's dimension) and local solver
 * `local_id` (0: the default), or with ADMM when `local_id` is 3003, from r = 0; the reaction
 * goes to `r_out` (n values). */
int capi_rolling_solve_file(const char* path, int local_id, double tolerance, int max_iter,
                            double* r_out, int n, RollingResult* out) {
  RollingFrictionContactProblem* p = rollingFrictionContact_new_from_filename(path);
  CHECK(p, "cannot read %s", path);
  int d = p->dimension, size = d * p->numberOfContacts;
  CHECK(size == n, "%s: %d unknowns, %d expected", path, size, n);
  SolverOptions* o = solver_options_create(
      local_id == SICONOS_ROLLING_FRICTION_3D_ADMM ? SICONOS_ROLLING_FRICTION_3D_ADMM
      : d == 5                                     ? SICONOS_ROLLING_FRICTION_3D_NSGS
                                                   : SICONOS_ROLLING_FRICTION_2D_NSGS);
  CHECK(o, "solver_options_create");
  if (local_id && local_id != SICONOS_ROLLING_FRICTION_3D_ADMM)
    solver_options_update_internal(o, 0, local_id);
  o->dparam[SICONOS_DPARAM_TOL] = tolerance;
  o->iparam[SICONOS_IPARAM_MAX_ITER] = max_iter;
  double* r = calloc((size_t)size, sizeof(double));
  double* u = calloc((size_t)size, sizeof(double));
  int info = d == 5 ? rolling_fc3d_driver(p, r, u, o) : rolling_fc2d_driver(p, r, u, o);
  CHECK(info >= 0, "%s: driver refused the problem (%d)", path, info);
  out->info = info;
  out->iterations = o->iparam[SICONOS_IPARAM_ITER_DONE];
  out->reported_error = o->dparam[SICONOS_DPARAM_RESIDU];
  out->dimension = d;
  double nq = 0;
  for (int i = 0; i < size; i++) nq += p->q[i] * p->q[i];
  double* w = calloc((size_t)size, sizeof(double));
  if (d == 5)
    rolling_fc3d_compute_error(p, r, w, tolerance, o, sqrt(nq), &out->api_error);
  else
    rolling_fc2d_compute_error(p, r, w, tolerance, o, sqrt(nq), &out->api_error);
  for (int i = 0; i < size; i++)
    CHECK(w[i] == u[i], "%s: compute_error's velocity differs from the driver's at %d", path, i);
  out->independent_error = independent_error(p, r);
  memcpy(r_out, r, sizeof(double) * (size_t)size);
  free(r);
  free(u);
  free(w);
  solver_options_delete(o);
  rollingFrictionContactProblem_free(p);
  return 0;
}

/* One sphere on a plane (5D, W = I): q_N < 0 with rolling slip; the answer in closed form. */
static RollingFrictionContactProblem* one_sphere(void) {
  NumericsMatrix* M = NM_create(NM_DENSE, 5, 5);
  for (int i = 0; i < 25; i++) M->matrix0[i] = (i % 6 == 0) ? 1.0 : 0.0;
  double* q = malloc(5 * sizeof(double));
  double qv[5] = {-1.0, 0.2, 0.0, 0.5, 0.0};
  memcpy(q, qv, sizeof qv);
  double* mu = malloc(sizeof(double));
  double* mur = malloc(sizeof(double));
  *mu = 0.5;
  *mur = 0.1;
  return rollingFrictionContactProblem_new_with_data(5, 1, M, q, mu, mur);
}

int capi_rolling_check_api(const char* scratch) {
  /* Closed-form case through the driver with both local solvers. */
  RollingFrictionContactProblem* p = one_sphere();
  CHECK(p && p->dimension == 5 && p->mu_r[0] == 0.1, "new_with_data keeps the pointers");
  const double expected[5] = {1.0, -0.2, 0.0, -0.1, 0.0};
  int locals[2] = {SICONOS_ROLLING_FRICTION_3D_ONECONTACT_ProjectionOnConeWithLocalIteration,
                   SICONOS_ROLLING_FRICTION_3D_ONECONTACT_ProjectionOnCone};
  for (int k = 0; k < 2; k++) {
    SolverOptions* o = solver_options_create(SICONOS_ROLLING_FRICTION_3D_NSGS);
    CHECK(o->numberOfInternalSolvers == 1 &&
              o->internalSolvers[0]->solverId ==
                  SICONOS_ROLLING_FRICTION_3D_ONECONTACT_ProjectionOnConeWithLocalIteration,
          "3000's default local solver is 3002");
    solver_options_update_internal(o, 0, locals[k]);
    o->dparam[SICONOS_DPARAM_TOL] = 1e-12;
    o->iparam[SICONOS_IPARAM_MAX_ITER] = 10000;
    double r[5] = {0}, u[5] = {0};
    int info = rolling_fc3d_driver(p, r, u, o);
    CHECK(info == 0, "local %d: info %d", locals[k], info);
    for (int i = 0; i < 5; i++)
      CHECK(fabs(r[i] - expected[i]) < 1e-10, "local %d: r[%d] = %g", locals[k], i, r[i]);
    CHECK(fabs(u[3] - 0.4) < 1e-10 && fabs(u[0]) < 1e-10, "u = W r + q");
    CHECK(o->dparam[SICONOS_DPARAM_RESIDU] <= 1e-12, "dparam[1] = %g",
          o->dparam[SICONOS_DPARAM_RESIDU]);
    /* The direct entry: with *info = 0 it returns at once, as Siconos' does. */
    int entry_info = 0;
    double r2[5] = {7, 7, 7, 7, 7};
    rolling_fc3d_nsgs(p, r2, u, &entry_info, o);
    CHECK(entry_info == 0 && r2[0] == 7, "rolling_fc3d_nsgs with *info = 0 does nothing");
    entry_info = -1;
    rolling_fc3d_nsgs(p, r2, u, &entry_info, o);
    CHECK(entry_info == 0 && fabs(r2[0] - 1.0) < 1e-10, "rolling_fc3d_nsgs solves");
    solver_options_delete(o);
  }

  /* Error functions. */
  double r[5] = {1.0, -0.2, 0.0, -0.1, 0.0}, w[5] = {0}, err = -1;
  int code = rolling_fc3d_compute_error(p, r, w, 1e-12, NULL, 1.0, &err);
  CHECK(code == 0 && err < 1e-15 && fabs(w[3] - 0.4) < 1e-15, "compute_error %d %g", code, err);
  double bad[5] = {0, 0, 0, 0, 0};
  code = rolling_fc3d_compute_error(p, bad, w, 1e-12, NULL, 0.0, &err);
  CHECK(code == 1 && fabs(err - independent_error(p, bad)) < 1e-15, "error of r = 0: %g", err);
  double e2 = 0, work[5];
  double uu[5] = {0, 0, 0, 0.4, 0};
  rolling_fc3d_unitary_compute_and_add_error(r, uu, 0.5, 0.1, &e2, work);
  CHECK(e2 < 1e-28, "unitary error %g", e2);
  CHECK(rolling_fc3d_compute_error(NULL, r, w, 1e-12, NULL, 1.0, &err) < 0, "NULL problem");

  /* Trivial case: a problem that is not trivial leaves the arrays as they were. */
  double vt[5] = {9, 9, 9, 9, 9}, rt[5] = {9, 9, 9, 9, 9};
  CHECK(rolling_fc3d_checkTrivialCase(p, vt, rt, NULL) == -1 && vt[0] == 9 && rt[0] == 9,
        "not trivial");
  p->q[0] = 0.5;
  CHECK(rolling_fc3d_checkTrivialCase(p, vt, rt, NULL) == 0 && vt[0] == 0.5 && vt[3] == 0.5 &&
            rt[0] == 0 && rt[3] == 0,
        "trivial: velocity = q, reaction = 0");
  p->q[0] = -1.0;

  /* Files: print, read back, same problem. */
  char path[4096];
  snprintf(path, sizeof path, "%s/rolling_one_sphere.dat", scratch);
  CHECK(rollingFrictionContact_printInFilename(p, path) == 0, "printInFilename");
  RollingFrictionContactProblem* back = rollingFrictionContact_new_from_filename(path);
  CHECK(back && back->dimension == 5 && back->numberOfContacts == 1 && back->mu_r[0] == 0.1 &&
            back->mu[0] == 0.5 && back->q[3] == 0.5 && NM_get_value(back->M, 4, 4) == 1.0,
        "file round trip");
  FILE* f = fopen(path, "r");
  CHECK(f, "fopen");
  RollingFrictionContactProblem* back2 = rollingFrictionContact_newFromFile(f);
  fclose(f);
  CHECK(back2 && back2->mu_r[0] == 0.1, "newFromFile");
  rollingFrictionContactProblem_compute_statistics(back2, r, uu, 1e-10, 0);
  rollingFrictionContactProblem_free(back2);
  rollingFrictionContactProblem_free(back);
  CHECK(rollingFrictionContact_new_from_filename("/nonexistent/rolling.dat") == NULL,
        "missing file gives NULL");

  /* ADMM on the same contact. */
  SolverOptions* o = solver_options_create(SICONOS_ROLLING_FRICTION_3D_ADMM);
  o->dparam[SICONOS_DPARAM_TOL] = 1e-10;
  double ra[5] = {0}, ua[5] = {0};
  CHECK(rolling_fc3d_driver(p, ra, ua, o) == 0, "ADMM");
  for (int i = 0; i < 5; i++)
    CHECK(fabs(ra[i] - expected[i]) < 1e-8, "ADMM r[%d] = %g", i, ra[i]);
  /* Rejections leave the outputs untouched. */
  double rr[5] = {3, 3, 3, 3, 3}, ru[5] = {3, 3, 3, 3, 3};
  o->iparam[SICONOS_FRICTION_3D_IPARAM_RESCALING] = 1;
  CHECK(rolling_fc3d_driver(p, rr, ru, o) < 0 && rr[0] == 3 && ru[0] == 3,
        "rescaled rolling ADMM refused, nothing written");
  solver_options_delete(o);
  o = solver_options_create(SICONOS_FRICTION_3D_NSGS);
  CHECK(rolling_fc3d_driver(p, rr, ru, o) == FC3D_ERR_UNSUPPORTED_SOLVER && rr[0] == 3,
        "500 refused by rolling_fc3d_driver");
  solver_options_delete(o);
  o = solver_options_create(SICONOS_ROLLING_FRICTION_3D_NSGS);
  CHECK(rolling_fc2d_driver(p, rr, ru, o) == FC3D_ERR_INVALID_PROBLEM && rr[0] == 3,
        "a 5D problem is refused by rolling_fc2d_driver");
  CHECK(rolling_fc3d_driver(NULL, rr, ru, o) == FC3D_ERR_NULL_POINTER, "NULL problem");
  CHECK(rolling_fc3d_driver(p, NULL, ru, o) < 0 && ru[0] == 3, "NULL reaction");
  p->mu_r[0] = -1.0;
  CHECK(rolling_fc3d_driver(p, rr, ru, o) < 0 && rr[0] == 3, "negative mu_r refused");
  p->mu_r[0] = 0.1;
  FrictionContactProblem fp = {5, 1, p->M, p->q, p->mu};
  CHECK(fc3d_driver(&fp, rr, ru, o) == FC3D_ERR_UNSUPPORTED_SOLVER ||
            fc3d_driver(&fp, rr, ru, o) == FC3D_ERR_INVALID_PROBLEM,
        "fc3d_driver refuses rolling");
  solver_options_delete(o);
  rollingFrictionContactProblem_free(p);
  rollingFrictionContactProblem_free(NULL);

  /* An empty problem from _new, freed. */
  RollingFrictionContactProblem* e = rollingFrictionContactProblem_new();
  CHECK(e && e->M == NULL && e->mu_r == NULL && e->dimension == 0, "new");
  rollingFrictionContactProblem_free(e);

  /* 2D: one contact (normal, tangent, rolling), W = I, rolling slip. */
  NumericsMatrix* M = NM_create(NM_DENSE, 3, 3);
  for (int i = 0; i < 9; i++) M->matrix0[i] = (i % 4 == 0) ? 1.0 : 0.0;
  double* q = malloc(3 * sizeof(double));
  q[0] = -1.0;
  q[1] = 0.2;
  q[2] = 0.5;
  double* mu = malloc(sizeof(double));
  double* mur = malloc(sizeof(double));
  *mu = 0.5;
  *mur = 0.1;
  RollingFrictionContactProblem* p2 = rollingFrictionContactProblem_new_with_data(3, 1, M, q, mu, mur);
  o = solver_options_create(SICONOS_ROLLING_FRICTION_2D_NSGS);
  o->dparam[SICONOS_DPARAM_TOL] = 1e-12;
  double r2[3] = {0}, u2[3] = {0};
  CHECK(rolling_fc2d_driver(p2, r2, u2, o) == 0, "2D driver");
  CHECK(fabs(r2[0] - 1) < 1e-10 && fabs(r2[1] + 0.2) < 1e-10 && fabs(r2[2] + 0.1) < 1e-10,
        "2D answer %g %g %g", r2[0], r2[1], r2[2]);
  CHECK(rolling_fc3d_driver(p2, r2, u2, o) == FC3D_ERR_INVALID_PROBLEM, "3D driver refuses 2D");
  double err2 = -1, w2[3];
  CHECK(rolling_fc2d_compute_error(p2, r2, w2, 1e-10, o, 1.0, &err2) == 0 && err2 < 1e-10,
        "2D error %g", err2);
  solver_options_delete(o);
  rollingFrictionContactProblem_free(p2);
  return 0;
}

/* The global family through the C API as a Siconos host uses it (issue 26): every global file
 * read, written, read back, copied, solved by gfc3d_driver (600, 614), its global velocity and
 * its reformulation computed, all released; a problem built by hand solved by gfc3d_LmgcDriver
 * and g_rolling_fc3d_driver (5000); the rejections (NULL pointers, wrong sizes, refused ids,
 * missing files) with untouched outputs. Run under valgrind by scripts/test-all.sh: every path
 * must release what it allocates. Returns 0 on success. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "SiconosNumerics.h"
#include "GlobalFrictionContactProblem.h"
#include "GlobalRollingFrictionContactProblem.h"
#include "FrictionContactProblem.h"
#include "SolverOptions.h"
#include "Friction_cst.h"
#include "NonSmoothDrivers.h"
#include "gfc3d_Solvers.h"
#include "gfc3d_compute_error.h"
#include "fc3d_solvers_wr.h"
#include "fclib_interface.h"

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

static const char* FILES[] = {"GFC3D_Example0.dat", "GFC3D_Example00.dat", "GFC3D_Example0_SBM.dat",
                              "GFC3D_Example1.dat", "GFC3D_OneContact.dat", "GFC3D_TwoRods1.dat"};

/* Solves `p` with `id` from zero, checks M v = q + H r through the problem's own velocity
 * function and that dparam[1] is gfc3d_compute_error of the result. */
static int solve(GlobalFrictionContactProblem* p, int id, const char* name) {
  int n = p->M->size0, m = 3 * p->numberOfContacts;
  double* r = calloc(m, sizeof(double));
  double* u = calloc(m, sizeof(double));
  double* v = calloc(n, sizeof(double));
  double* w = calloc(n, sizeof(double));
  double* u2 = calloc(m, sizeof(double));
  SolverOptions* options = solver_options_create(id);
  options->dparam[SICONOS_DPARAM_TOL] = 1e-8;
  options->iparam[SICONOS_IPARAM_MAX_ITER] = 10000;
  int info = gfc3d_driver(p, r, u, v, options);
  int status = 0;
  if (info != 0) {
    fprintf(stderr, "%s with %d: info %d (%s)\n", name, id, info, fc3d_last_error_message());
    status = 1;
  } else {
    double qn = 0, e = -1;
    for (int i = 0; i < n; i++) qn += p->q[i] * p->q[i];
    if (gfc3d_compute_error(p, r, u2, v, 1e-8, NULL, sqrt(qn), 0.0, &e) != 0 || e != options->dparam[1]) {
      fprintf(stderr, "%s with %d: error %g, dparam[1] %g\n", name, id, e, options->dparam[1]);
      status = 1;
    }
    if (globalFrictionContact_computeGlobalVelocity(p, r, w) != 0) status = 1;
    for (int i = 0; i < n; i++)
      if (fabs(w[i] - v[i]) > 1e-12 * (1 + fabs(v[i]))) status = 1;
    for (int i = 0; i < m; i++)
      if (u[i] != u2[i]) status = 1;
  }
  solver_options_delete(options);
  free(options);
  free(r);
  free(u);
  free(v);
  free(w);
  free(u2);
  return status;
}

static int check_files(const char* data_dir, const char* scratch) {
  char path[4096], out[4096];
  for (size_t k = 0; k < sizeof FILES / sizeof FILES[0]; k++) {
    snprintf(path, sizeof path, "%s/%s", data_dir, FILES[k]);
    GlobalFrictionContactProblem* p = globalFrictionContact_new_from_filename(path);
    CHECK(p, "%s not read", FILES[k]);
    /* Written, read back from the stream, copied. */
    snprintf(out, sizeof out, "%s/global-%zu.dat", scratch, k);
    FILE* f = fopen(out, "w");
    CHECK(f && globalFrictionContact_printInFile(p, f) == 0, "%s not written", FILES[k]);
    fclose(f);
    f = fopen(out, "r");
    GlobalFrictionContactProblem* again = globalFrictionContact_newFromFile(f);
    fclose(f);
    CHECK(again && again->numberOfContacts == p->numberOfContacts && again->M->storageType == p->M->storageType,
          "%s not read back", FILES[k]);
    GlobalFrictionContactProblem* copy = globalFrictionContact_copy(again);
    CHECK(copy, "%s not copied", FILES[k]);
    CHECK(globalFrictionContact_printInFileName(copy, out) == 0, "copy of %s not written", FILES[k]);
    for (int id = 600; id <= 614; id += 14) CHECK(solve(copy, id, FILES[k]) == 0, "%s", FILES[k]);
    /* To the local form and back. */
    FrictionContactProblem* local = globalFrictionContact_reformulation_FrictionContact(p);
    CHECK(local && local->numberOfContacts == p->numberOfContacts, "%s not reduced", FILES[k]);
    GlobalFrictionContactProblem* lifted = fc3d_reformulation_global_problem(local);
    CHECK(lifted && lifted->M->size0 == 6 * p->numberOfContacts, "%s not lifted", FILES[k]);
    CHECK(solve(lifted, 600, FILES[k]) == 0, "%s lifted", FILES[k]);
    globalFrictionContact_free(lifted);
    frictionContactProblem_free(local);
    globalFrictionContact_free(copy);
    globalFrictionContact_free(again);
    globalFrictionContact_free(p);
  }
  /* Missing files, a local file, a file of another kind. */
  CHECK(!globalFrictionContact_new_from_filename("/nonexistent/x.dat"), "missing file read");
  CHECK(fc3d_last_error_code() == FC3D_ERR_IO, "missing file: code %d", fc3d_last_error_code());
  snprintf(path, sizeof path, "%s/GFC3D_TwoRods1-condensed.dat", data_dir);
  CHECK(!globalFrictionContact_new_from_filename(path), "a local file read as a global one");
  CHECK(fc3d_last_error_code() == FC3D_ERR_PARSE, "local file: code %d", fc3d_last_error_code());
  CHECK(!globalFrictionContact_fclib_read("/nonexistent/x.hdf5"), "missing FCLIB file read");
  return 0;
}

static int check_rejections(void) {
  double r[6] = {0}, u[6] = {0}, v[6] = {0};
  SolverOptions* options = solver_options_create(SICONOS_GLOBAL_FRICTION_3D_NSGS_WR);
  CHECK(gfc3d_driver(NULL, r, u, v, options) == FC3D_ERR_NULL_POINTER, "NULL problem");
  GlobalFrictionContactProblem* empty = globalFrictionContactProblem_new();
  CHECK(empty && empty->M == NULL && empty->env == NULL, "new problem");
  CHECK(gfc3d_driver(empty, r, u, v, options) == FC3D_ERR_INVALID_PROBLEM, "dimension 0: %d",
        fc3d_last_error_code());
  empty->dimension = 3;
  CHECK(gfc3d_driver(empty, r, u, v, options) == FC3D_ERR_NULL_POINTER, "NULL M");
  globalFrictionContact_display(NULL);
  CHECK(globalFrictionContact_printInFile(empty, stdout) < 0, "NULL M written");
  CHECK(!globalFrictionContact_copy(empty), "NULL M copied");
  globalFrictionContact_free(empty);
  globalFrictionContact_free(NULL);
  double e = 0;
  CHECK(gfc3d_compute_error(NULL, r, u, v, 1e-8, NULL, 1.0, 0.0, &e) == FC3D_ERR_NULL_POINTER, "error of NULL");
  CHECK(globalFrictionContact_computeGlobalVelocity(NULL, r, v) == FC3D_ERR_NULL_POINTER, "velocity of NULL");
  CHECK(!globalFrictionContact_reformulation_FrictionContact(NULL), "NULL reduced");
  CHECK(!fc3d_reformulation_global_problem(NULL), "NULL lifted");
  int info = 7;
  gfc3d_AVI_gams_path(NULL, r, u, &info, options);
  CHECK(info == FC3D_ERR_UNSUPPORTED_SOLVER, "GAMS entry: %d", info);
  CHECK(gfc3d_checkTrivialCaseGlobal(6, NULL, u, r, v, options) == -1, "trivial case");
  solver_options_delete(options);
  free(options);
  return 0;
}

/* LMGC90's entry on two bodies of 3 unknowns (M = diag(2), H = I, 1-based coordinates), and the
 * global rolling driver on a problem built with its constructor. */
static int check_lmgc_and_rolling(void) {
  unsigned int rows[6], cols[6];
  double mdata[6], hdata[6];
  for (int i = 0; i < 6; i++) {
    rows[i] = cols[i] = (unsigned)i + 1;
    mdata[i] = 2.0;
    hdata[i] = 1.0;
  }
  double q[6] = {-1, 0.2, 0, -0.5, 0, 0.1}, b[6] = {0}, mu[2] = {0.5, 0.3};
  double r[6] = {0}, u[6] = {0}, v[6] = {0};
  int iparam[20] = {0};
  double dparam[20] = {0};
  dparam[0] = 1e-10;
  int info = gfc3d_LmgcDriver(r, u, v, q, b, mu, mdata, 6, rows, cols, hdata, 6, rows, cols, 6, 2,
                              SICONOS_GLOBAL_FRICTION_3D_NSGS_WR, 20, iparam, 20, dparam, 0, 0, 0);
  CHECK(info == 0 && iparam[1] > 0 && dparam[1] <= 1e-10, "LMGC: info %d, iterations %d, error %g", info,
        iparam[1], dparam[1]);
  for (int i = 0; i < 6; i++) CHECK(fabs(2 * v[i] - q[i] - r[i]) < 1e-12, "LMGC: M v != q + H r");
  /* Rolling: M and H dense (10 x 10), everything malloc'd and released by the problem. */
  int n = 10;
  NumericsMatrix* M = NM_create(NM_DENSE, n, n);
  NumericsMatrix* H = NM_create(NM_DENSE, n, n);
  double* rq = malloc(n * sizeof(double));
  double* rmu = malloc(2 * sizeof(double));
  double* rmur = malloc(2 * sizeof(double));
  for (int i = 0; i < n; i++) {
    for (int j = 0; j < n; j++) {
      M->matrix0[i + n * j] = i == j ? 1.0 + i : 0.0;
      H->matrix0[i + n * j] = i == j ? 1.0 : 0.0;
    }
    rq[i] = i % 5 == 0 ? -1.0 : 0.1;
  }
  rmu[0] = 0.5;
  rmu[1] = 0.4;
  rmur[0] = 0.05;
  rmur[1] = 0.1;
  GlobalRollingFrictionContactProblem* p = globalRollingFrictionContactProblem_new_with_data(5, 2, M, rq, rmu, rmur);
  CHECK(p && p->H == NULL && p->b == NULL, "rolling constructor");
  p->H = H;
  p->b = calloc(n, sizeof(double));
  double rr[10] = {0}, ru[10] = {0}, rv[10] = {0};
  SolverOptions* options = solver_options_create(SICONOS_GLOBAL_ROLLING_FRICTION_3D_NSGS_WR);
  options->dparam[0] = 1e-10;
  info = g_rolling_fc3d_driver(p, rr, ru, rv, options);
  CHECK(info == 0 && options->dparam[1] <= 1e-10, "rolling: info %d, error %g", info, options->dparam[1]);
  double w[10];
  CHECK(globalRollingFrictionContact_computeGlobalVelocity(p, rr, w) == 0, "rolling velocity");
  for (int i = 0; i < n; i++) CHECK(fabs(w[i] - rv[i]) < 1e-12, "rolling velocity %d", i);
  RollingFrictionContactProblem* local = globalRollingFrictionContact_reformulation_RollingFrictionContact(p);
  CHECK(local && local->dimension == 5, "rolling reduction");
  rollingFrictionContactProblem_free(local);
  solver_options_delete(options);
  free(options);
  globalRollingFrictionContactProblem_free(p);
  return 0;
}

int capi_check_global(const char* data_dir, const char* scratch_dir) {
  if (check_rejections() || check_lmgc_and_rolling()) return 1;
  return check_files(data_dir, scratch_dir);
}

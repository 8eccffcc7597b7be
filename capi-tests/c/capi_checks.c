/* C-side checks of the fc3d C API, written as a Siconos host would write them: only the
 * Siconos-named compat headers are included. Each check returns 0 on success and prints what
 * failed otherwise. Called from the Rust tests in ../tests and from ownership_main.c (valgrind). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "SiconosNumerics.h"
#include "FrictionContactProblem.h"
#include "NumericsMatrix.h"
#include "SolverOptions.h"
#include "Friction_cst.h"
#include "fc3d_Solvers.h"
#include "fc3d_compute_error.h"
#include "NonSmoothDrivers.h"
#include "SparseBlockMatrix.h"
#include "numerics_verbose.h"

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
  int storage;
} CSolveResult;

static double norm2(const double* x, int n) {
  double s = 0.0;
  for (int i = 0; i < n; i++) s += x[i] * x[i];
  return sqrt(s);
}

/* Plain-C natural-map error of (r, u = W r + q), Siconos' normalisation, with W as a dense
 * column-major array: nothing of fc3d is used. */
static double independent_error(const double* W, const double* q, const double* mu, const double* r,
                                 int nc, double* u) {
  int n = 3 * nc;
  for (int i = 0; i < n; i++) {
    double s = q[i];
    for (int j = 0; j < n; j++) s += W[i + (size_t)j * n] * r[j];
    u[i] = s;
  }
  double sum = 0.0;
  for (int c = 0; c < nc; c++) {
    const double* rc = r + 3 * c;
    const double* uc = u + 3 * c;
    double m = mu[c];
    double ut = hypot(uc[1], uc[2]);
    double x[3] = {rc[0] - (uc[0] + m * ut), rc[1] - uc[1], rc[2] - uc[2]};
    double xt = hypot(x[1], x[2]);
    double p[3];
    if (x[0] >= 0.0 && xt <= m * x[0]) { /* x[0] >= 0: with m = 0, 0 <= -0.0 holds */
      p[0] = x[0]; p[1] = x[1]; p[2] = x[2];
    } else if (m * xt <= -x[0]) {
      p[0] = p[1] = p[2] = 0.0;
    } else {
      double pn = (x[0] + m * xt) / (1.0 + m * m);
      p[0] = pn; p[1] = m * pn * x[1] / xt; p[2] = m * pn * x[2] / xt;
    }
    for (int k = 0; k < 3; k++) sum += (rc[k] - p[k]) * (rc[k] - p[k]);
  }
  double scale = fmax(norm2(q, n), fmax(norm2(r, n), norm2(u, n)));
  if (scale == 0.0) scale = 1.0;
  return sqrt(sum) / scale;
}

/* ---- building W in each storage from a dense copy ------------------------------------------ */

static NumericsMatrix* dense_matrix(const double* W, int n) {
  NumericsMatrix* M = NM_create(NM_DENSE, n, n);
  memcpy(M->matrix0, W, sizeof(double) * (size_t)n * n);
  return M;
}

static NumericsMatrix* csr_matrix(const double* W, int n) {
  size_t nnz = 0;
  for (size_t k = 0; k < (size_t)n * n; k++) nnz += W[k] != 0.0;
  CSparseMatrix* A = malloc(sizeof(CSparseMatrix));
  A->nzmax = (CS_INT)nnz;
  A->n = n; /* Siconos' CSR convention: n rows, m columns */
  A->m = n;
  A->nz = -2;
  A->p = malloc(sizeof(CS_INT) * (size_t)(n + 1));
  A->i = malloc(sizeof(CS_INT) * (nnz ? nnz : 1));
  A->x = malloc(sizeof(double) * (nnz ? nnz : 1));
  size_t k = 0;
  for (int i = 0; i < n; i++) {
    A->p[i] = (CS_INT)k;
    for (int j = 0; j < n; j++) {
      double v = W[i + (size_t)j * n];
      if (v != 0.0) { A->i[k] = j; A->x[k] = v; k++; }
    }
  }
  A->p[n] = (CS_INT)k;
  NumericsSparseMatrix* S = calloc(1, sizeof(NumericsSparseMatrix));
  S->csr = A;
  S->origin = NSM_CSR;
  return NM_create_from_data(NM_SPARSE, n, n, S);
}

/* Sparse-block W built the way LMGC-like hosts do: coordinate blocks, then SBCM_to_SBM.
 * The block values stay in *values_out, to be freed by the caller after SBM_free_from_SBCM. */
typedef struct {
  NumericsMatrix* M;
  SparseBlockCoordinateMatrix* coo;
  double* values;
  unsigned* rows;
  unsigned* cols;
} SbmBuild;

static SbmBuild sbm_matrix(const double* W, int nc) {
  int n = 3 * nc;
  SbmBuild b = {0};
  unsigned nb = 0;
  b.values = malloc(sizeof(double) * 9 * (size_t)nc * nc);
  b.rows = malloc(sizeof(unsigned) * (size_t)nc * nc);
  b.cols = malloc(sizeof(unsigned) * (size_t)nc * nc);
  for (int bj = nc - 1; bj >= 0; bj--) /* reverse order: SBCM_to_SBM groups them by row */
    for (int bi = 0; bi < nc; bi++) {
      int nonzero = (bi == bj);
      double blk[9];
      for (int c = 0; c < 3; c++)
        for (int r = 0; r < 3; r++) {
          blk[r + 3 * c] = W[(3 * bi + r) + (size_t)(3 * bj + c) * n];
          nonzero |= blk[r + 3 * c] != 0.0;
        }
      if (!nonzero) continue;
      memcpy(b.values + 9 * (size_t)nb, blk, sizeof blk);
      b.rows[nb] = (unsigned)bi + 1;
      b.cols[nb] = (unsigned)bj + 1;
      nb++;
    }
  b.coo = SBCM_new_3x3((unsigned)nc, (unsigned)nc, nb, b.rows, b.cols, b.values);
  SparseBlockStructuredMatrix* sbm = SBCM_to_SBM(b.coo);
  b.M = NM_new_SBM(n, n, sbm);
  return b;
}

static void sbm_release(SbmBuild* b) {
  /* Blocks belong to b->values: detach the SBM before NM_free. */
  SBM_free_from_SBCM(b->M->matrix1);
  b->M->matrix1 = NULL;
  NM_free(b->M);
  SBCM_free_3x3(b->coo);
  free(b->coo); /* Siconos: SBCM_free_3x3 frees the arrays, not the struct */
  free(b->values);
  free(b->rows);
  free(b->cols);
}

/* ---- solving a shared problem --------------------------------------------------------------- */

int capi_solve_file_with(const char* path, int storage, int solver_id, int internal_id, double tolerance,
                         int max_iter, double* reaction_out, double* velocity_out, int capacity,
                         CSolveResult* result);

int capi_solve_file(const char* path, int storage, int local_solver, double tolerance, int max_iter,
                    double* reaction_out, double* velocity_out, int capacity, CSolveResult* result) {
  return capi_solve_file_with(path, storage, SICONOS_FRICTION_3D_NSGS, local_solver, tolerance, max_iter,
                              reaction_out, velocity_out, capacity, result);
}

/* Any solver id with its Siconos defaults, tolerance and iteration limit overridden. */
int capi_solve_file_with_solver(const char* path, int storage, int solver_id, double tolerance, int max_iter,
                                double* reaction_out, double* velocity_out, int capacity, CSolveResult* result) {
  return capi_solve_file_with(path, storage, solver_id, 0, tolerance, max_iter, reaction_out, velocity_out,
                              capacity, result);
}

/* Solves the file's problem, W rebuilt in `storage` (-1: as stored), with solver `solver_id` and its
 * Siconos defaults; `internal_id` != 0 replaces the first internal solver (by
 * solver_options_update_internal, or, for ids without defaults of their own such as TFP's 566/567,
 * by renaming it as a host editing the options struct would). */
int capi_solve_file_with(const char* path, int storage, int solver_id, int internal_id, double tolerance,
                         int max_iter, double* reaction_out, double* velocity_out, int capacity,
                         CSolveResult* result) {
  FrictionContactProblem* file = frictionContact_new_from_filename(path);
  CHECK(file != NULL, "cannot read %s", path);
  int nc = file->numberOfContacts;
  int n = 3 * nc;
  CHECK(n <= capacity, "%s: %d unknowns do not fit %d", path, n, capacity);

  double* W = malloc(sizeof(double) * ((size_t)n * n + 1));
  for (int j = 0; j < n; j++)
    for (int i = 0; i < n; i++) W[i + (size_t)j * n] = NM_get_value(file->M, i, j);

  SbmBuild sbm = {0};
  NumericsMatrix* M = NULL;
  switch (storage) {
    case -1: M = file->M; break;
    case NM_DENSE: M = dense_matrix(W, n); break;
    case NM_SPARSE_BLOCK: sbm = sbm_matrix(W, nc); M = sbm.M; break;
    case NM_SPARSE: M = csr_matrix(W, n); break;
    default: FAIL("unknown storage %d", storage);
  }
  /* Hosts fill the problem struct on the stack. */
  FrictionContactProblem problem = {3, nc, M, file->q, file->mu};

  SolverOptions* options = solver_options_create(solver_id);
  CHECK(options != NULL, "solver_options_create(%d)", solver_id);
  if (internal_id != 0) {
    CHECK(options->numberOfInternalSolvers >= 1, "solver %d has no internal solver", solver_id);
    solver_options_update_internal(options, 0, internal_id);
    CHECK(options->internalSolvers[0] != NULL, "update_internal(%d)", internal_id);
    if (options->internalSolvers[0]->solverId != internal_id) options->internalSolvers[0]->solverId = internal_id;
  }
  options->dparam[SICONOS_DPARAM_TOL] = tolerance;
  options->iparam[SICONOS_IPARAM_MAX_ITER] = max_iter;

  double* r = calloc((size_t)n + 1, sizeof(double));
  double* u = calloc((size_t)n + 1, sizeof(double));
  double* w2 = calloc((size_t)n + 1, sizeof(double));
  double* u3 = calloc((size_t)n + 1, sizeof(double));
  int info = fc3d_driver(&problem, r, u, options);
  /* 4: the iterates grew without bound (e.g. DSFP/FPP with rho = 1 on a stiff W) and the solver
     stopped. */
  CHECK(info == 0 || info == 1 || info == FC3D_UNBOUNDED ||
            (solver_id == SICONOS_FRICTION_3D_SOCLCP && info == FC3D_RELAXED_NOT_COULOMB),
        "%s: fc3d_driver(%d) returned %d", path, solver_id, info);

  result->info = info;
  result->iterations = options->iparam[SICONOS_IPARAM_ITER_DONE];
  result->reported_error = options->dparam[SICONOS_DPARAM_RESIDU];
  result->storage = M->storageType;
  double api_error = -1.0;
  int e = fc3d_compute_error(&problem, r, w2, tolerance, options, norm2(file->q, n), &api_error);
  CHECK(e == 0 || e == 1, "fc3d_compute_error returned %d", e);
  result->api_error = api_error;
  result->independent_error = independent_error(W, file->q, file->mu, r, nc, u3);
  memcpy(reaction_out, r, sizeof(double) * (size_t)n);
  memcpy(velocity_out, u, sizeof(double) * (size_t)n);

  solver_options_delete(options);
  free(options);
  if (storage == NM_SPARSE_BLOCK) sbm_release(&sbm);
  else if (storage != -1) NM_free(M);
  frictionContactProblem_free(file);
  free(W); free(r); free(u); free(w2); free(u3);
  return 0;
}

/* ---- single contacts with analytic answers -------------------------------------------------- */

/* When >= 0, the Newton formulation (iparam[10]) set on the local solver: 1 = Jean-Moreau. */
static int g_formulation = -1;

static int solve_one(const char* name, int local, double W[9], double q[3], double mu, const double r_exp[3],
                     const double u_exp[3]) {
  NumericsMatrix M = {0};
  M.storageType = NM_DENSE;
  M.size0 = M.size1 = 3;
  M.matrix0 = W; /* host-owned: never freed by fc3d */
  FrictionContactProblem p = {3, 1, &M, q, &mu};
  SolverOptions* o = solver_options_create(SICONOS_FRICTION_3D_NSGS);
  solver_options_update_internal(o, 0, local);
  if (g_formulation >= 0) o->internalSolvers[0]->iparam[SICONOS_FRICTION_3D_NSN_FORMULATION] = g_formulation;
  /* 561's default local tolerance (1e-12, Siconos') is coarser than the 1e-14 asked here: a local
     solver that stops at 1e-12 leaves NSGS at ~3e-13 forever. */
  if (local == SICONOS_FRICTION_3D_NCPGlockerFBNewton) o->internalSolvers[0]->dparam[SICONOS_DPARAM_TOL] = 1e-16;
  o->dparam[SICONOS_DPARAM_TOL] = 1e-14;
  o->iparam[SICONOS_IPARAM_MAX_ITER] = 100000;
  double r[3] = {0, 0, 0}, u[3] = {0, 0, 0};
  int info = fc3d_driver(&p, r, u, o);
  double err = o->dparam[SICONOS_DPARAM_RESIDU];
  solver_options_delete(o);
  free(o);
  CHECK(info == 0, "%s with local solver %d: info %d, error %g", name, local, info, err);
  for (int k = 0; k < 3; k++) {
    CHECK(fabs(r[k] - r_exp[k]) <= 1e-10, "%s/%d: r[%d] = %.17g, expected %.17g", name, local, k, r[k], r_exp[k]);
    CHECK(fabs(u[k] - u_exp[k]) <= 1e-10, "%s/%d: u[%d] = %.17g, expected %.17g", name, local, k, u[k], u_exp[k]);
  }
  return 0;
}

static int check_single_contacts_with(void);

int capi_check_single_contacts(void) {
  if (check_single_contacts_with()) return 1;
  /* Jean-Moreau formulation (59) of the Newton solvers, with and without line search. */
  g_formulation = SICONOS_FRICTION_3D_NSN_FORMULATION_JEANMOREAU_STD;
  int jm = check_single_contacts_with();
  g_formulation = -1;
  return jm;
}

static int g_jm_ids[] = {SICONOS_FRICTION_3D_ONECONTACT_NSN, SICONOS_FRICTION_3D_ONECONTACT_NSN_GP,
                         SICONOS_FRICTION_3D_ONECONTACT_NSN_GP_HYBRID};

static int check_single_contacts_with(void) {
  int locals[] = {SICONOS_FRICTION_3D_ONECONTACT_NSN_GP_HYBRID, SICONOS_FRICTION_3D_ONECONTACT_NSN,
                  SICONOS_FRICTION_3D_ONECONTACT_NSN_GP, SICONOS_FRICTION_3D_ONECONTACT_ProjectionOnCone,
                  SICONOS_FRICTION_3D_ONECONTACT_ProjectionOnConeWithLocalIteration,
                  SICONOS_FRICTION_3D_ONECONTACT_ProjectionOnCylinder,
                  SICONOS_FRICTION_3D_ONECONTACT_ProjectionOnConeWithRegularization,
                  SICONOS_FRICTION_3D_ONECONTACT_ProjectionOnConeWithDiagonalization,
                  SICONOS_FRICTION_3D_ONECONTACT_ProjectionOnCone_velocity,
                  SICONOS_FRICTION_3D_NCPGlockerFBNewton,
                  SICONOS_FRICTION_3D_ONECONTACT_QUARTIC,
                  SICONOS_FRICTION_3D_ONECONTACT_ProjectionOnCylinderWithLocalIteration,
                  SICONOS_FRICTION_3D_ONECONTACT_FP_VI_UPK,
                  SICONOS_FRICTION_3D_ONECONTACT_EBP,
                  SICONOS_FRICTION_3D_ONECONTACT_EAL};
  size_t n = sizeof locals / sizeof locals[0];
  if (g_formulation >= 0) n = sizeof g_jm_ids / sizeof g_jm_ids[0];
  for (size_t k = 0; k < n; k++) {
    int l = g_formulation >= 0 ? g_jm_ids[k] : locals[k];
    double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    { /* take-off: q_N > 0 gives r = 0, u = q */
      double q[3] = {1, 0.5, 0}, re[3] = {0, 0, 0}, ue[3] = {1, 0.5, 0};
      if (solve_one("take-off", l, I, q, 0.3, re, ue)) return 1;
    }
    { /* stick: ||r_T|| = 0.1 < mu r_N = 0.5 */
      double q[3] = {-1, 0.1, 0}, re[3] = {1, -0.1, 0}, ue[3] = {0, 0, 0};
      if (solve_one("stick", l, I, q, 0.5, re, ue)) return 1;
    }
    { /* slide: stick would need ||r_T|| = 2 > mu r_N = 0.5; r_T opposes u_T */
      double q[3] = {-1, 2, 0}, re[3] = {1, -0.5, 0}, ue[3] = {0, 1.5, 0};
      if (solve_one("slide", l, I, q, 0.5, re, ue)) return 1;
    }
    { /* frictionless: r_T = 0 */
      double q[3] = {-2, 3, -1}, re[3] = {2, 0, 0}, ue[3] = {0, 3, -1};
      if (solve_one("mu=0", l, I, q, 0.0, re, ue)) return 1;
    }
    { /* slide on W = diag(2, 4, 4): r_N = 1, |r_T| = mu r_N = 0.5, u_T = 4 (-0.5) + 3 = 1 */
      double Wd[9] = {2, 0, 0, 0, 4, 0, 0, 0, 4};
      double q[3] = {-2, 3, 0}, re[3] = {1, -0.5, 0}, ue[3] = {0, 1, 0};
      if (solve_one("slide-diag", l, Wd, q, 0.5, re, ue)) return 1;
    }
  }
  return 0;
}

/* ---- rejected input --------------------------------------------------------------------------- */

#define EXPECT_CODE(call, code)                                                         \
  do {                                                                                  \
    fc3d_clear_last_error();                                                            \
    int got_ = (call);                                                                  \
    CHECK(got_ == (code), "%s returned %d, expected %d (%s)", #call, got_, code, #code);   \
    CHECK(strlen(fc3d_last_error_message()) > 0, "%s left no message", #call);          \
    CHECK(fc3d_last_error_code() == (code), "%s: last error code %d", #call, fc3d_last_error_code()); \
  } while (0)

static int untouched(const double* x, int n, double sentinel) {
  for (int i = 0; i < n; i++)
    if (x[i] != sentinel) return 0;
  return 1;
}

int capi_check_bad_input(const char* data_dir) {
  double W[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  double q[3] = {-1, 0.1, 0};
  double mu = 0.5;
  NumericsMatrix M = {0};
  M.storageType = NM_DENSE;
  M.size0 = M.size1 = 3;
  M.matrix0 = W;
  FrictionContactProblem p = {3, 1, &M, q, &mu};
  SolverOptions* o = solver_options_create(SICONOS_FRICTION_3D_NSGS);
  double r[3], u[3];
  const double S = 12345.0;
  for (int k = 0; k < 3; k++) r[k] = u[k] = S;

  EXPECT_CODE(fc3d_driver(NULL, r, u, o), FC3D_ERR_NULL_POINTER);
  EXPECT_CODE(fc3d_driver(&p, r, u, NULL), FC3D_ERR_NULL_POINTER);
  EXPECT_CODE(fc3d_driver(&p, NULL, u, o), FC3D_ERR_NULL_POINTER);
  EXPECT_CODE(fc3d_driver(&p, r, NULL, o), FC3D_ERR_NULL_POINTER);
  CHECK(untouched(r, 3, S) && untouched(u, 3, S), "outputs written on failure");
  CHECK(o->iparam[SICONOS_IPARAM_ITER_DONE] == 0 && isinf(o->dparam[SICONOS_DPARAM_RESIDU]),
        "iparam[1]/dparam[1] written on failure");

  /* sizes */
  p.numberOfContacts = -1;
  EXPECT_CODE(fc3d_driver(&p, r, u, o), FC3D_ERR_INVALID_SIZE);
  p.numberOfContacts = 2;
  EXPECT_CODE(fc3d_driver(&p, r, u, o), FC3D_ERR_INVALID_SIZE);
  p.numberOfContacts = 1;
  p.dimension = 2;
  EXPECT_CODE(fc3d_driver(&p, r, u, o), FC3D_ERR_INVALID_PROBLEM);
  p.dimension = 3;
  M.size0 = -3;
  EXPECT_CODE(fc3d_driver(&p, r, u, o), FC3D_ERR_INVALID_SIZE);
  M.size0 = 3;
  /* storage */
  M.storageType = 7;
  EXPECT_CODE(fc3d_driver(&p, r, u, o), FC3D_ERR_INVALID_STORAGE);
  M.storageType = NM_SPARSE_BLOCK; /* matrix1 is NULL */
  EXPECT_CODE(fc3d_driver(&p, r, u, o), FC3D_ERR_NULL_POINTER);
  M.storageType = NM_DENSE;
  M.matrix0 = NULL;
  EXPECT_CODE(fc3d_driver(&p, r, u, o), FC3D_ERR_NULL_POINTER);
  M.matrix0 = W;
  /* values */
  q[1] = NAN;
  EXPECT_CODE(fc3d_driver(&p, r, u, o), FC3D_ERR_NON_FINITE);
  q[1] = 0.1;
  W[4] = INFINITY;
  EXPECT_CODE(fc3d_driver(&p, r, u, o), FC3D_ERR_NON_FINITE);
  W[4] = 1.0;
  mu = -0.1;
  EXPECT_CODE(fc3d_driver(&p, r, u, o), FC3D_ERR_INVALID_PROBLEM);
  mu = NAN;
  EXPECT_CODE(fc3d_driver(&p, r, u, o), FC3D_ERR_NON_FINITE);
  mu = 0.5;
  CHECK(untouched(r, 3, S) && untouched(u, 3, S), "outputs written on failure");

  /* solver ids and options */
  CHECK(solver_options_create(9999) == NULL, "solver_options_create(9999) should fail");
  o->solverId = SICONOS_FRICTION_3D_GAMS_PATH; /* needs the commercial GAMS/PATH: not in fc3d */
  EXPECT_CODE(fc3d_driver(&p, r, u, o), FC3D_ERR_UNSUPPORTED_SOLVER);
  CHECK(strstr(fc3d_last_error_message(), "FC3D_GAMS_PATH") != NULL, "message should name the solver: %s",
        fc3d_last_error_message());
  /* Not top-level solvers in Siconos 4.4 either (its fc3d_driver: "Unknown solver"). */
  int not_top_level[] = {SICONOS_FRICTION_3D_NCPGlockerFBFixedPoint, SICONOS_FRICTION_3D_VI_FPP_Cylinder,
                         SICONOS_FRICTION_3D_CONVEXQP_PG_CYLINDER};
  for (size_t k = 0; k < sizeof not_top_level / sizeof not_top_level[0]; k++) {
    o->solverId = not_top_level[k];
    EXPECT_CODE(fc3d_driver(&p, r, u, o), FC3D_ERR_UNSUPPORTED_SOLVER);
    CHECK(strstr(fc3d_last_error_message(), "not a top-level friction solver") != NULL,
          "message should give the reason: %s", fc3d_last_error_message());
  }
  o->solverId = SICONOS_FRICTION_3D_NSGS;
  o->internalSolvers[0]->solverId = SICONOS_FRICTION_3D_NCPGlockerFBPATH; /* needs PATH too */
  EXPECT_CODE(fc3d_driver(&p, r, u, o), FC3D_ERR_UNSUPPORTED_SOLVER);
  solver_options_update_internal(o, 0, SICONOS_FRICTION_3D_ONECONTACT_NSN_GP_HYBRID);
  o->iparam[SICONOS_FRICTION_3D_NSGS_SHUFFLE] = 3;
  EXPECT_CODE(fc3d_driver(&p, r, u, o), FC3D_ERR_INVALID_OPTION);
  o->iparam[SICONOS_FRICTION_3D_NSGS_SHUFFLE] = 0;
  o->dparam[SICONOS_DPARAM_TOL] = NAN;
  EXPECT_CODE(fc3d_driver(&p, r, u, o), FC3D_ERR_INVALID_OPTION);
  o->dparam[SICONOS_DPARAM_TOL] = 1e-8;
  o->iparam[SICONOS_IPARAM_MAX_ITER] = -5;
  EXPECT_CODE(fc3d_driver(&p, r, u, o), FC3D_ERR_INVALID_OPTION);
  o->iparam[SICONOS_IPARAM_MAX_ITER] = 1000;
  int isize = o->iSize;
  o->iSize = 5;
  EXPECT_CODE(fc3d_driver(&p, r, u, o), FC3D_ERR_INVALID_OPTION);
  o->iSize = isize;
  int* ip = o->iparam;
  o->iparam = NULL;
  EXPECT_CODE(fc3d_driver(&p, r, u, o), FC3D_ERR_INVALID_OPTION);
  o->iparam = ip;
  CHECK(untouched(r, 3, S) && untouched(u, 3, S), "outputs written on failure");

  /* a valid call after all that works and writes outputs */
  r[0] = r[1] = r[2] = 0.0;
  int info = fc3d_driver(&p, r, u, o);
  CHECK(info == 0 && fabs(r[0] - 1.0) < 1e-12, "valid solve failed: info %d r0 %g", info, r[0]);

  /* sparse-block W missing its diagonal block */
  {
    double blk[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
    unsigned row[1] = {1}, col[1] = {2};
    double q2[6] = {-1, 0, 0, -1, 0, 0}, mu2[2] = {0.5, 0.5}, r2[6] = {0}, u2[6] = {0};
    SparseBlockCoordinateMatrix* coo = SBCM_new_3x3(2, 2, 1, row, col, blk);
    SparseBlockStructuredMatrix* sbm = SBCM_to_SBM(coo);
    NumericsMatrix Ms = {0};
    Ms.storageType = NM_SPARSE_BLOCK;
    Ms.size0 = Ms.size1 = 6;
    Ms.matrix1 = sbm;
    FrictionContactProblem p2 = {3, 2, &Ms, q2, mu2};
    EXPECT_CODE(fc3d_driver(&p2, r2, u2, o), FC3D_ERR_INVALID_PROBLEM);
    SBM_free_from_SBCM(sbm);
    SBCM_free_3x3(coo);
    free(coo); /* Siconos: SBCM_free_3x3 frees the arrays, not the struct */
  }
  /* CSC with unsorted and duplicate entries is accepted: W = I stored as 0.5 + 0.5 on (0,0) */
  {
    CS_INT colp[4] = {0, 3, 4, 5};
    CS_INT rowi[5] = {0, 0, 0, 1, 2};
    double x[5] = {0.25, 0.5, 0.25, 1.0, 1.0};
    CSparseMatrix A = {5, 3, 3, colp, rowi, x, -1};
    NumericsSparseMatrix S = {0};
    S.csc = &A;
    S.origin = NSM_CSC;
    NumericsMatrix Mc = {0};
    Mc.storageType = NM_SPARSE;
    Mc.size0 = Mc.size1 = 3;
    Mc.matrix2 = &S;
    double qc[3] = {-1, 2, 0}, muc = 0.5, rc[3] = {0}, uc[3] = {0};
    FrictionContactProblem pc = {3, 1, &Mc, qc, &muc};
    info = fc3d_driver(&pc, rc, uc, o);
    CHECK(info == 0 && fabs(rc[0] - 1.0) < 1e-10 && fabs(rc[1] + 0.5) < 1e-10,
          "CSC with duplicates: info %d r = (%g, %g, %g)", info, rc[0], rc[1], rc[2]);
    rowi[0] = 7; /* out of range */
    EXPECT_CODE(fc3d_driver(&pc, rc, uc, o), FC3D_ERR_INVALID_STORAGE);
  }
  solver_options_delete(o);
  free(o);

  /* files */
  fc3d_clear_last_error();
  CHECK(frictionContact_new_from_filename("/nonexistent/fc3d.dat") == NULL, "missing file accepted");
  CHECK(fc3d_last_error_code() == FC3D_ERR_IO, "missing file: code %d", fc3d_last_error_code());
  CHECK(frictionContact_new_from_filename(NULL) == NULL, "NULL filename accepted");
  CHECK(fc3d_last_error_code() == FC3D_ERR_NULL_POINTER, "NULL filename: code %d", fc3d_last_error_code());
  {
    char garbage[] = "3 1 0 3 3 3 3 1 0 0 0 1 0 0 0 oops";
    FILE* f = fmemopen(garbage, strlen(garbage), "r");
    CHECK(frictionContact_newFromFile(f) == NULL, "garbage accepted");
    CHECK(fc3d_last_error_code() == FC3D_ERR_PARSE, "garbage: code %d", fc3d_last_error_code());
    CHECK(strstr(fc3d_last_error_message(), "oops") != NULL, "message should name the token: %s",
          fc3d_last_error_message());
    fclose(f);
  }
  {
    char path[4096];
    snprintf(path, sizeof path, "%s/Rover1039.dat", data_dir);
    FILE* f = fopen(path, "r");
    CHECK(f != NULL, "cannot open %s", path);
    char buf[600];
    size_t got = fread(buf, 1, sizeof buf, f);
    fclose(f);
    CHECK(got == sizeof buf, "short read");
    FILE* t = fmemopen(buf, 500, "r"); /* truncated in the middle of W */
    CHECK(frictionContact_newFromFile(t) == NULL, "truncated file accepted");
    CHECK(fc3d_last_error_code() == FC3D_ERR_PARSE, "truncated: code %d", fc3d_last_error_code());
    fclose(t);
  }
  CHECK(frictionContact_newFromFile(NULL) == NULL, "NULL FILE accepted");
  return 0;
}

/* ---- matrix files: NM_write_in_file / NM_new_from_file / SBM_new_from_file ----------------- */

/* Every entry of A and B is the same double (bit for bit: -0 and +0 differ). */
static int same_matrix(const NumericsMatrix* A, const NumericsMatrix* B, const char* what) {
  CHECK(A->storageType == B->storageType, "%s: storage %d read back as %d", what, A->storageType, B->storageType);
  CHECK(A->size0 == B->size0 && A->size1 == B->size1, "%s: %dx%d read back as %dx%d", what, A->size0, A->size1,
        B->size0, B->size1);
  for (int i = 0; i < A->size0; i++)
    for (int j = 0; j < A->size1; j++) {
      double a = NM_get_value(A, i, j), b = NM_get_value(B, i, j);
      CHECK(memcmp(&a, &b, sizeof a) == 0, "%s: entry (%d, %d) is %.17g, read back as %.17g", what, i, j, a, b);
    }
  return 0;
}

static int write_text(const char* path, const char* text) {
  FILE* f = fopen(path, "w");
  CHECK(f != NULL, "create %s", path);
  fputs(text, f);
  fclose(f);
  return 0;
}

static int check_matrix_files(const char* scratch_dir) {
  char path[4096], path2[4096];
  snprintf(path, sizeof path, "%s/fc3d_matrices.txt", scratch_dir);
  snprintf(path2, sizeof path2, "%s/fc3d_matrix.txt", scratch_dir);

  /* a dense 2x3, a sparse 4x5 (triplet), a sparse-block 6x9 of 3x3 blocks */
  NumericsMatrix* D = NM_create(NM_DENSE, 2, 3);
  const double dv[6] = {1.0 / 3.0, -0.0, 5e-324, -1.7976931348623157e308, 0.1, 123456789.12345679};
  memcpy(D->matrix0, dv, sizeof dv);
  NumericsMatrix* T = NM_create(NM_SPARSE, 4, 5);
  NM_triplet_alloc(T, 1);
  NM_entry(T, 0, 0, 2.0 / 3.0);
  NM_entry(T, 3, 4, -2.5e-10);
  NM_entry(T, 1, 2, 1e300);
  NM_entry(T, 2, 0, -7.0);
  double blocks[27];
  for (int k = 0; k < 27; k++) blocks[k] = k + 1.0 / 7.0;
  unsigned brow[3] = {2, 1, 1}, bcol[3] = {3, 3, 1};
  SparseBlockCoordinateMatrix* coo = SBCM_new_3x3(2, 3, 3, brow, bcol, blocks);
  SparseBlockStructuredMatrix* sbm = SBCM_to_SBM(coo);
  NumericsMatrix* S = NM_new_SBM(6, 9, sbm);
  NumericsMatrix* written[3] = {D, T, S};
  const char* names[3] = {"dense", "sparse", "sparse-block"};

  /* all three in one file, then a tail: each read must stop at the end of its matrix */
  FILE* f = fopen(path, "w");
  CHECK(f != NULL, "create %s", path);
  fc3d_clear_last_error();
  for (int k = 0; k < 3; k++) NM_write_in_file(written[k], f);
  fprintf(f, "tail 7\n");
  fclose(f);
  CHECK(fc3d_last_error_code() == 0, "NM_write_in_file failed");
  f = fopen(path, "r");
  CHECK(f != NULL, "reopen %s", path);
  for (int k = 0; k < 3; k++) {
    NumericsMatrix* R = NM_new_from_file(f);
    CHECK(R != NULL, "NM_new_from_file (%s)", names[k]);
    int rc = same_matrix(written[k], R, names[k]);
    NM_free(R);
    if (rc) return rc;
  }
  char word[16] = "";
  int seven = 0;
  CHECK(fscanf(f, "%15s %d", word, &seven) == 2 && strcmp(word, "tail") == 0 && seven == 7,
        "NM_new_from_file read past its matrix");
  fclose(f);

  /* by file name */
  NM_write_in_filename(D, path2);
  NumericsMatrix* R = NM_new_from_filename(path2);
  CHECK(R != NULL, "NM_new_from_filename");
  if (same_matrix(D, R, "dense by name")) return 1;
  NM_free(R);
  /* a sparse-block matrix without blocks is written as Siconos does (a lone 0): zeros */
  {
    NumericsMatrix* E = NM_create(NM_SPARSE_BLOCK, 6, 3);
    NM_write_in_filename(E, path2);
    R = NM_new_from_filename(path2);
    CHECK(R != NULL && R->storageType == NM_SPARSE_BLOCK && R->size0 == 6 && R->size1 == 3 &&
              R->matrix1->nbblocks == 0 && NM_get_value(R, 5, 2) == 0.0,
          "empty sparse-block matrix");
    NM_free(R);
    NM_free(E);
  }

  /* SBM_new_from_file reads the sparse-block body without the `storageType size0 size1` header */
  f = fopen(path2, "w");
  CHECK(f != NULL, "create %s", path2);
  NM_write_in_file(S, f);
  fclose(f);
  f = fopen(path2, "r");
  CHECK(f != NULL, "reopen %s", path2);
  int header[3];
  CHECK(fscanf(f, "%d %d %d", &header[0], &header[1], &header[2]) == 3 && header[0] == NM_SPARSE_BLOCK &&
            header[1] == 6 && header[2] == 9,
        "sparse-block header");
  SparseBlockStructuredMatrix* B = SBM_new_from_file(f);
  fclose(f);
  CHECK(B != NULL, "SBM_new_from_file");
  CHECK(B->nbblocks == 3 && B->blocknumber0 == 2 && B->blocknumber1 == 3 && B->blocksize1[2] == 9,
        "SBM_new_from_file structure");
  NumericsMatrix* BM = NM_new_SBM(6, 9, B); /* takes B: NM_free releases it */
  if (same_matrix(S, BM, "SBM_new_from_file")) return 1;
  NM_free(BM);

  /* garbage: NULL, a parse error, and the stream is left where it was */
  if (write_text(path2, "garbage 1 2\n")) return 1;
  f = fopen(path2, "r");
  CHECK(f != NULL, "reopen %s", path2);
  CHECK(NM_new_from_file(f) == NULL, "garbage accepted by NM_new_from_file");
  CHECK(fc3d_last_error_code() == FC3D_ERR_PARSE, "garbage: code %d", fc3d_last_error_code());
  CHECK(strstr(fc3d_last_error_message(), "garbage") != NULL, "the message names the token: %s",
        fc3d_last_error_message());
  CHECK(SBM_new_from_file(f) == NULL && fc3d_last_error_code() == FC3D_ERR_PARSE, "garbage accepted by SBM_new_from_file");
  CHECK(fscanf(f, "%15s", word) == 1 && strcmp(word, "garbage") == 0, "a failed read moved the stream");
  fclose(f);
  /* a truncated matrix */
  if (write_text(path2, "0 2 2 2 2 1.0 2.0 3.0")) return 1;
  R = NM_new_from_filename(path2);
  CHECK(R == NULL && fc3d_last_error_code() == FC3D_ERR_PARSE, "truncated matrix accepted");
  /* sparse-block matrices of other than 3x3 blocks are not represented by fc3d */
  if (write_text(path2, "1\n4\n4\n4\n2\n2\n2\t4\t\n2\t4\t\n3\n4\n0\t2\t4\t\n0\t1\t0\t1\t\n"
                        "0 1 2 3 4\n1 1 2 3 4\n2 1 2 3 4\n3 1 2 3 4\n"))
    return 1;
  R = NM_new_from_filename(path2);
  CHECK(R == NULL && fc3d_last_error_code() == FC3D_ERR_INVALID_STORAGE, "2x2 blocks: code %d",
        fc3d_last_error_code());
  CHECK(NM_new_from_file(NULL) == NULL && fc3d_last_error_code() == FC3D_ERR_NULL_POINTER, "NULL FILE");
  CHECK(SBM_new_from_file(NULL) == NULL && fc3d_last_error_code() == FC3D_ERR_NULL_POINTER, "NULL FILE (SBM)");
  remove(path2);
  CHECK(NM_new_from_filename(path2) == NULL && fc3d_last_error_code() == FC3D_ERR_IO, "missing file");
  remove(path);

  NM_free(D);
  NM_free(T);
  SBM_free_from_SBCM(sbm);
  S->matrix1 = NULL;
  NM_free(S);
  SBCM_free_3x3(coo);
  free(coo); /* Siconos: SBCM_free_3x3 frees the arrays, not the struct */
  return 0;
}

/* ---- ownership paths (run under valgrind by CI) ---------------------------------------------- */

int capi_check_ownership(const char* data_dir, const char* scratch_dir) {
  char path[4096], out[4096];
  if (check_matrix_files(scratch_dir)) return 1;
  /* a problem read from a file, written back, read again, compared, freed */
  snprintf(path, sizeof path, "%s/Capsules-i100-889.dat", data_dir);
  snprintf(out, sizeof out, "%s/fc3d_roundtrip.dat", scratch_dir);
  FrictionContactProblem* a = frictionContact_new_from_filename(path);
  CHECK(a != NULL, "read %s", path);
  CHECK(frictionContact_printInFilename(a, out) == 0, "write %s", out);
  FILE* f = fopen(out, "r");
  CHECK(f != NULL, "reopen %s", out);
  FrictionContactProblem* b = frictionContact_newFromFile(f);
  fclose(f);
  CHECK(b != NULL, "read back %s", out);
  int n = 3 * a->numberOfContacts;
  CHECK(b->numberOfContacts == a->numberOfContacts && b->M->storageType == a->M->storageType, "round trip shape");
  for (int i = 0; i < n; i++) CHECK(a->q[i] == b->q[i], "q[%d] differs after round trip", i);
  for (int i = 0; i < n; i += 7)
    for (int j = 0; j < n; j += 5)
      CHECK(NM_get_value(a->M, i, j) == NM_get_value(b->M, i, j), "W(%d,%d) differs after round trip", i, j);
  remove(out);
  frictionContactProblem_free(a);
  frictionContactProblem_free(b);

  /* problem assembled by the host with malloc'd data handed over to fc3d */
  {
    NumericsMatrix* M = NM_create(NM_DENSE, 3, 3);
    M->matrix0[0] = M->matrix0[4] = M->matrix0[8] = 1.0;
    double* q = malloc(3 * sizeof(double));
    double* mu = malloc(sizeof(double));
    q[0] = -1; q[1] = 0.1; q[2] = 0; mu[0] = 0.5;
    FrictionContactProblem* p = frictionContactProblem_new_with_data(3, 1, M, q, mu);
    double r[3] = {0}, u[3] = {0};
    SolverOptions* o = solver_options_create(SICONOS_FRICTION_3D_NSGS);
    CHECK(fc3d_driver(p, r, u, o) == 0, "solve");
    SolverOptions* c = solver_options_copy(o);
    solver_options_update_internal(c, 0, SICONOS_FRICTION_3D_ONECONTACT_ProjectionOnCone);
    SolverOptions* local = solver_options_create(SICONOS_FRICTION_3D_ONECONTACT_NSN);
    solver_options_set_internal_solver(c, 0, local);
    CHECK(solver_options_get_internal_solver(c, 0) == local, "set_internal_solver");
    CHECK(fc3d_driver(p, r, u, c) == 0, "solve with copied options");
    solver_options_delete(c);
    free(c);
    solver_options_delete(o);
    free(o);
    frictionContactProblem_free(p);
  }
  /* empty problem */
  frictionContactProblem_free(frictionContactProblem_new());
  frictionContactProblem_free(NULL);
  /* sparse matrix built entry by entry, growing its triplet past nzmax, copied, freed */
  {
    NumericsMatrix* T = NM_create(NM_SPARSE, 6, 6);
    NM_triplet_alloc(T, 2);
    for (int i = 0; i < 6; i++) NM_entry(T, i, i, 2.0 + i);
    NM_entry(T, 0, 5, 0.5);
    CHECK(NM_get_value(T, 3, 3) == 5.0 && NM_get_value(T, 0, 5) == 0.5 && NM_get_value(T, 1, 0) == 0.0,
          "NM_entry/NM_get_value on a triplet");
    NumericsMatrix* D = NM_create(NM_DENSE, 6, 6);
    D->matrix0[7] = 3.0;
    NumericsMatrix* S = NM_create(NM_SPARSE, 6, 6);
    NM_copy_to_sparse(D, S, 1e-300);
    CHECK(NM_get_value(S, 1, 1) == 3.0 && NM_get_value(S, 2, 2) == 0.0, "NM_copy_to_sparse");
    NM_free(T);
    NM_free(D);
    NM_clear(S);
    free(S);
  }
  /* matrices wrapping host data that fc3d then owns */
  {
    double* data = calloc(9, sizeof(double));
    NumericsMatrix* M = NM_create_from_data(NM_DENSE, 3, 3, data);
    NM_entry(M, 1, 2, 4.0);
    CHECK(data[1 + 2 * 3] == 4.0, "NM_create_from_data must not copy");
    NM_free(M);
    NumericsMatrix* E = NM_new_SBM(0, 0, SBM_new());
    NM_free(E);
    NumericsMatrix* F = NM_new();
    NM_fill(F, NM_DENSE, 2, 2, calloc(4, sizeof(double)));
    NM_free(F);
    NumericsMatrix* G = NM_create(NM_SPARSE_BLOCK, 3, 3);
    NM_free(G);
  }
  /* sparse-block W assembled from coordinates and solved */
  {
    double blocks[18] = {2, 0, 0, 0, 2, 0, 0, 0, 2, /* (1,1) */ 1, 0, 0, 0, 1, 0, 0, 0, 1 /* (2,2) */};
    unsigned row[2] = {2, 1}, col[2] = {2, 1};
    double tmp[9];
    memcpy(tmp, blocks, sizeof tmp); /* reverse the order: (2,2) first */
    memcpy(blocks, blocks + 9, sizeof tmp);
    memcpy(blocks + 9, tmp, sizeof tmp);
    SparseBlockCoordinateMatrix* coo = SBCM_new_3x3(2, 2, 2, row, col, blocks);
    SparseBlockStructuredMatrix* sbm = SBCM_to_SBM(coo);
    CHECK(sbm->index2_data[0] == 0 && sbm->index2_data[1] == 1, "SBCM_to_SBM groups blocks by block row");
    NumericsMatrix* M = NM_new_SBM(6, 6, sbm);
    CHECK(NM_get_value(M, 0, 0) == 2.0 && NM_get_value(M, 4, 4) == 1.0 && NM_get_value(M, 0, 4) == 0.0,
          "NM_get_value on SBM");
    double q[6] = {-2, 0, 0, -1, 0, 0}, mu[2] = {0.3, 0.3}, r[6] = {0}, u[6] = {0};
    FrictionContactProblem p = {3, 2, M, q, mu};
    SolverOptions* o = solver_options_create(SICONOS_FRICTION_3D_NSGS);
    CHECK(fc3d_driver(&p, r, u, o) == 0 && fabs(r[0] - 1.0) < 1e-12 && fabs(r[3] - 1.0) < 1e-12, "SBM solve");
    solver_options_delete(o);
    free(o);
    SBM_free_from_SBCM(sbm);
    M->matrix1 = NULL;
    NM_free(M);
    SBCM_free_3x3(coo);
    free(coo); /* Siconos: SBCM_free_3x3 frees the arrays, not the struct */
  }
  /* LMGC90-style entry point, solving in place */
  {
    double W[18] = {2, 0, 0, 0, 2, 0, 0, 0, 2, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    unsigned row[2] = {1, 2}, col[2] = {1, 2};
    double q[6] = {-2, 0.1, 0, -1, 5, 0}, mu[2] = {0.3, 0.3}, r[6] = {0}, u[6] = {0};
    int info = fc3d_LmgcDriver(r, u, q, mu, W, row, col, 2, 2, SICONOS_FRICTION_3D_NSGS, 1e-12, 1000, 0, 0, 0, 0);
    CHECK(info == 0 && fabs(r[0] - 1.0) < 1e-12 && fabs(r[4] + 0.3) < 1e-12, "LMGC driver: info %d r = %g %g", info,
          r[0], r[4]);
  }
  return 0;
}

/* ---- per-iteration callback ------------------------------------------------------------------ */

typedef struct {
  int calls;
  int bad;
  double last_error;
} CallbackLog;

static void collect(void* env, int size, double* reaction, double* velocity, double error, void* extra) {
  CallbackLog* log = env;
  log->calls++;
  log->last_error = error;
  if (size != 6 || !reaction || !velocity || extra != NULL || !(error >= 0.0)) log->bad++;
  /* velocity must be W r + q for the reaction handed over (W = diag(2, 1), q below) */
  if (fabs(velocity[0] - (2.0 * reaction[0] - 2.0)) > 1e-12 || fabs(velocity[3] - (reaction[3] - 1.0)) > 1e-12)
    log->bad++;
}

int capi_check_callback(void) {
  double W[36] = {0};
  for (int i = 0; i < 3; i++) {
    W[i + 6 * i] = 2.0;
    W[(i + 3) + 6 * (i + 3)] = 1.0;
  }
  double q[6] = {-2, 0.3, 0, -1, 0, 0.2}, mu[2] = {0.5, 0.5}, r[6] = {0}, u[6] = {0};
  NumericsMatrix M = {0};
  M.storageType = NM_DENSE;
  M.size0 = M.size1 = 6;
  M.matrix0 = W;
  FrictionContactProblem p = {3, 2, &M, q, mu};
  CallbackLog log = {0, 0, -1.0};
  Callback cb = {&log, collect};
  SolverOptions* o = solver_options_create(SICONOS_FRICTION_3D_NSGS);
  o->callback = &cb;
  o->dparam[SICONOS_DPARAM_TOL] = 1e-12;
  o->iparam[SICONOS_FRICTION_3D_IPARAM_ERROR_EVALUATION] = SICONOS_FRICTION_3D_NSGS_ERROR_EVALUATION_FULL;
  int info = fc3d_driver(&p, r, u, o);
  int iterations = o->iparam[SICONOS_IPARAM_ITER_DONE];
  double error = o->dparam[SICONOS_DPARAM_RESIDU];
  o->callback = NULL; /* the callback is ours, not the options' */
  solver_options_delete(o);
  free(o);
  CHECK(info == 0, "callback run: info %d", info);
  CHECK(log.calls == iterations && log.calls >= 1, "callback called %d times for %d iterations", log.calls, iterations);
  CHECK(log.bad == 0, "callback got %d bad arguments", log.bad);
  /* With FULL evaluation the last reported error is the error of the returned reaction. */
  CHECK(fabs(log.last_error - error) <= 1e-15, "last callback error %g vs dparam[1] %g", log.last_error, error);
  return 0;
}

/* ---- options, names, defaults ---------------------------------------------------------------- */

int capi_check_options(void) {
  CHECK(strcmp(solver_options_id_to_name(SICONOS_FRICTION_3D_NSGS), "FC3D_NSGS") == 0, "name of 500");
  CHECK(solver_options_name_to_id("FC3D_ONECONTACT_NSN_GP_HYBRID") == 565, "id of hybrid");
  CHECK(solver_options_name_to_id("no such solver") == 0, "unknown name");
  CHECK(strcmp(solver_options_id_to_name(4242), "NONAME") == 0, "unknown id");
  SolverOptions* o = solver_options_create(SICONOS_FRICTION_3D_NSGS);
  CHECK(o->solverId == 500 && o->iSize == 20 && o->dSize == 20, "NSGS shape");
  CHECK(o->iparam[SICONOS_IPARAM_MAX_ITER] == 1000 && o->dparam[SICONOS_DPARAM_TOL] == 1e-4, "NSGS defaults");
  CHECK(o->iparam[SICONOS_FRICTION_3D_IPARAM_ERROR_EVALUATION] == SICONOS_FRICTION_3D_NSGS_ERROR_EVALUATION_LIGHT_WITH_FULL_FINAL,
        "NSGS error evaluation default");
  CHECK(o->numberOfInternalSolvers == 1, "one internal solver");
  SolverOptions* l = solver_options_get_internal_solver(o, 0);
  CHECK(l->solverId == SICONOS_FRICTION_3D_ONECONTACT_NSN_GP_HYBRID && l->iparam[0] == 10 && l->dparam[0] == 1e-14,
        "local defaults");
  CHECK(solver_options_get_internal_solver(o, 3) == NULL, "out-of-range internal solver");
  solver_options_update_internal(o, 0, SICONOS_FRICTION_3D_ONECONTACT_ProjectionOnCylinder);
  CHECK(o->internalSolvers[0]->solverId == 557, "update_internal");
  solver_options_delete(o);
  free(o);
  return 0;
}

/* ---- VI / fixed-point family (505, 506, 507, 511, 512) and ADMM (523) ------------------------ */

/* When 1, solve_one_with sets Siconos' in-line-search update (iparam[10] = 1) on 506/507. */
static int vi_update_in_line_search = 0;

static int solve_one_with(const char* name, int id, double W[9], double q[3], double mu, const double r_exp[3],
                          const double u_exp[3]) {
  NumericsMatrix M = {0};
  M.storageType = NM_DENSE;
  M.size0 = M.size1 = 3;
  M.matrix0 = W;
  FrictionContactProblem p = {3, 1, &M, q, &mu};
  SolverOptions* o = solver_options_create(id);
  CHECK(o != NULL, "solver_options_create(%d)", id);
  o->dparam[SICONOS_DPARAM_TOL] = 1e-13;
  o->iparam[SICONOS_IPARAM_MAX_ITER] = 100000;
  if (vi_update_in_line_search) o->iparam[10] = 1; /* SICONOS_VI_IPARAM_ACTIVATE_UPDATE */
  double r[3] = {0, 0, 0}, u[3] = {0, 0, 0};
  int info = fc3d_driver(&p, r, u, o);
  double err = o->dparam[SICONOS_DPARAM_RESIDU];
  int iter = o->iparam[SICONOS_IPARAM_ITER_DONE];
  solver_options_delete(o);
  free(o);
  CHECK(info == 0, "%s with solver %d: info %d, error %g after %d iterations", name, id, info, err, iter);
  CHECK(err <= 1e-13, "%s/%d: dparam[1] = %g", name, id, err);
  for (int k = 0; k < 3; k++) {
    CHECK(fabs(r[k] - r_exp[k]) <= 1e-9, "%s/%d: r[%d] = %.17g, expected %.17g", name, id, k, r[k], r_exp[k]);
    CHECK(fabs(u[k] - u_exp[k]) <= 1e-9, "%s/%d: u[%d] = %.17g, expected %.17g", name, id, k, u[k], u_exp[k]);
  }
  return 0;
}

int capi_check_vi_admm_single_contacts(void) {
  /* HP (508) is Siconos' algorithm: its search along W w + q (no De Saxce term) stalls on a
     sliding contact, so it is checked on take-off and stick only. */
  struct {
    int id, update, slides;
  } cases[] = {
      {SICONOS_FRICTION_3D_DSFP, 0, 1}, {SICONOS_FRICTION_3D_VI_FPP, 0, 1}, {SICONOS_FRICTION_3D_VI_EG, 0, 1},
      {SICONOS_FRICTION_3D_VI_FPP, 1, 1}, {SICONOS_FRICTION_3D_VI_EG, 1, 1}, {SICONOS_FRICTION_3D_HP, 0, 0},
      {SICONOS_FRICTION_3D_FPP, 0, 1},  {SICONOS_FRICTION_3D_EG, 0, 1},     {SICONOS_FRICTION_3D_ADMM, 0, 1},
  };
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
    int id = cases[k].id;
    vi_update_in_line_search = cases[k].update;
    /* W_NN = 1.25 keeps the fixed rho = 1 of 505/511 inside the stability range rho < 2 / W_NN. */
    double Wd[9] = {1.25, 0, 0, 0, 1, 0, 0, 0, 1};
    int failed = 0;
    { /* take-off: q_N > 0 gives r = 0, u = q */
      double q[3] = {1, 0.5, 0}, re[3] = {0, 0, 0}, ue[3] = {1, 0.5, 0};
      failed = failed || solve_one_with("take-off", id, Wd, q, 0.3, re, ue);
    }
    { /* stick: r_N = 2 / 1.25 = 1.6, ||r_T|| = 0.1 < mu r_N */
      double q[3] = {-2, 0.1, 0}, re[3] = {1.6, -0.1, 0}, ue[3] = {0, 0, 0};
      failed = failed || solve_one_with("stick", id, Wd, q, 0.5, re, ue);
    }
    if (cases[k].slides) { /* slide: r_N = 1.6, r_T = -mu r_N (0.6, 0.8), u_T = q_T + r_T along q_T */
      double q[3] = {-2, 3, 4}, re[3] = {1.6, -0.48, -0.64}, ue[3] = {0, 2.52, 3.36};
      failed = failed || solve_one_with("slide", id, Wd, q, 0.5, re, ue);
    }
    vi_update_in_line_search = 0;
    if (failed) return 1;
  }
  /* Siconos' VI solvers (506/507) hand their adapted rho back in dparam[3] as -rho; the others
     leave dparam[3] as it was. */
  int hands_back[] = {SICONOS_FRICTION_3D_VI_FPP, SICONOS_FRICTION_3D_VI_EG, SICONOS_FRICTION_3D_FPP,
                      SICONOS_FRICTION_3D_EG};
  for (size_t k = 0; k < sizeof hands_back / sizeof hands_back[0]; k++) {
    int id = hands_back[k];
    double Wd[9] = {1.25, 0, 0, 0, 1, 0, 0, 0, 1}, q[3] = {-2, 3, 4}, mu = 0.5;
    NumericsMatrix M = {0};
    M.storageType = NM_DENSE;
    M.size0 = M.size1 = 3;
    M.matrix0 = Wd;
    FrictionContactProblem p = {3, 1, &M, q, &mu};
    SolverOptions* o = solver_options_create(id);
    CHECK(o != NULL, "solver_options_create(%d)", id);
    o->dparam[SICONOS_DPARAM_TOL] = 1e-12;
    double before = o->dparam[3], r[3] = {0, 0, 0}, u[3] = {0, 0, 0};
    int info = fc3d_driver(&p, r, u, o);
    double after = o->dparam[3];
    solver_options_delete(o);
    free(o);
    CHECK(info == 0, "solver %d: info %d", id, info);
    if (id == SICONOS_FRICTION_3D_VI_FPP || id == SICONOS_FRICTION_3D_VI_EG)
      CHECK(after < 0 && isfinite(after), "solver %d: dparam[3] = %g after the solve, expected -rho", id, after);
    else
      CHECK(after == before, "solver %d: dparam[3] changed from %g to %g", id, before, after);
  }
  return 0;
}

/* Options fc3d does not implement are rejected with FC3D_ERR_INVALID_OPTION, r and u untouched. */
int capi_check_vi_admm_options(void) {
  double Wd[9] = {1.25, 0, 0, 0, 1, 0, 0, 0, 1};
  NumericsMatrix M = {0};
  M.storageType = NM_DENSE;
  M.size0 = M.size1 = 3;
  M.matrix0 = Wd;
  double q[3] = {-2, 3, 4}, mu = 0.5;
  FrictionContactProblem p = {3, 1, &M, q, &mu};
  struct {
    int id, is_real, index;
    double value;
  } bad[] = {
      {SICONOS_FRICTION_3D_DSFP, 1, 3, -1.0},   /* DSFP needs a fixed rho > 0 */
      {SICONOS_FRICTION_3D_FPP, 1, 3, 0.0},     /* rho = 0 */
      {SICONOS_FRICTION_3D_VI_FPP, 0, 6, 2},    /* Han-Sun line search */
      {SICONOS_FRICTION_3D_VI_EG, 0, 7, 3},     /* adaptive error evaluation */
      {SICONOS_FRICTION_3D_VI_EG, 0, 10, 2},    /* update inside the line search: 0 or 1 */
      {SICONOS_FRICTION_3D_VI_FPP, 1, 6, 1.5},  /* L outside (0, 1) */
      {SICONOS_FRICTION_3D_ADMM, 0, 9, 1},      /* unknown rho strategy */
      {SICONOS_FRICTION_3D_ADMM, 0, 12, 3},     /* symmetrizing W */
      {SICONOS_FRICTION_3D_ADMM, 0, 15, 1},     /* frozen De Saxce term */
      {SICONOS_FRICTION_3D_ADMM, 0, 3, 2},      /* balancing rescaling (Siconos ADMM: scalar only) */
      {SICONOS_FRICTION_3D_ADMM, 1, 5, 0.5},    /* balancing tau <= 1 with balancing on */
  };
  for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
    SolverOptions* o = solver_options_create(bad[k].id);
    CHECK(o != NULL, "solver_options_create(%d)", bad[k].id);
    if (bad[k].is_real)
      o->dparam[bad[k].index] = bad[k].value;
    else
      o->iparam[bad[k].index] = (int)bad[k].value;
    if (bad[k].id == SICONOS_FRICTION_3D_ADMM && bad[k].index == 5) o->iparam[9] = 2;
    double r[3] = {7, 7, 7}, u[3] = {7, 7, 7};
    fc3d_clear_last_error();
    int got = fc3d_driver(&p, r, u, o);
    solver_options_delete(o);
    free(o);
    CHECK(got == FC3D_ERR_INVALID_OPTION, "solver %d with %sparam[%d] = %g: returned %d", bad[k].id,
          bad[k].is_real ? "d" : "i", bad[k].index, bad[k].value, got);
    CHECK(strlen(fc3d_last_error_message()) > 0, "solver %d: no message", bad[k].id);
    for (int i = 0; i < 3; i++) CHECK(r[i] == 7 && u[i] == 7, "solver %d: r or u touched", bad[k].id);
  }
  return 0;
}

/* ---- optimization-based solvers: TFP 503, PFP 522, ACLMFP 516, SOCLCP 517 ------------------ */


/* Solves one contact (W = I, mu = 0.5) with `id`; returns info, r and u through pointers. */
static int opt5_one(int id, double q[3], double r[3], double u[3], int* info) {
  double W[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  double mu = 0.5;
  NumericsMatrix M = {0};
  M.storageType = NM_DENSE;
  M.size0 = M.size1 = 3;
  M.matrix0 = W;
  FrictionContactProblem p = {3, 1, &M, q, &mu};
  SolverOptions* o = solver_options_create(id);
  CHECK(o != NULL, "solver_options_create(%d)", id);
  o->dparam[SICONOS_DPARAM_TOL] = 1e-12;
  r[0] = r[1] = r[2] = 0.0;
  *info = fc3d_driver(&p, r, u, o);
  solver_options_delete(o);
  free(o);
  return 0;
}

/* Analytic single contacts through fc3d_driver, option rejections, and SOCLCP's info 3. */
int opt5_check_single_contacts_and_options(void) {
  int ids[] = {SICONOS_FRICTION_3D_TFP, SICONOS_FRICTION_3D_PFP, SICONOS_FRICTION_3D_ACLMFP};
  for (size_t k = 0; k < sizeof ids / sizeof ids[0]; k++) {
    double r[3], u[3];
    int info = -100;
    /* Stick: r = -q, u = 0. */
    double q_stick[3] = {-1.0, 0.2, -0.1};
    if (opt5_one(ids[k], q_stick, r, u, &info)) return 1;
    CHECK(info == 0, "stick %d: info %d", ids[k], info);
    CHECK(fabs(r[0] - 1.0) + fabs(r[1] + 0.2) + fabs(r[2] - 0.1) <= 1e-10, "stick %d: r", ids[k]);
    /* Slide: r = (1, -0.5, 0), u = (0, 1.5, 0). */
    double q_slide[3] = {-1.0, 2.0, 0.0};
    if (opt5_one(ids[k], q_slide, r, u, &info)) return 1;
    CHECK(info == 0, "slide %d: info %d", ids[k], info);
    CHECK(fabs(r[0] - 1.0) + fabs(r[1] + 0.5) + fabs(r[2]) <= 1e-10, "slide %d: r = (%g %g %g)",
          ids[k], r[0], r[1], r[2]);
    CHECK(fabs(u[0]) + fabs(u[1] - 1.5) + fabs(u[2]) <= 1e-10, "slide %d: u", ids[k]);
  }
  /* SOCLCP: a sliding contact gives the relaxed (lifting) solution, reported with info 3. */
  {
    double r[3], u[3], q[3] = {-1.0, 2.0, 0.0};
    int info = -100;
    if (opt5_one(SICONOS_FRICTION_3D_SOCLCP, q, r, u, &info)) return 1;
    CHECK(info == FC3D_RELAXED_NOT_COULOMB, "SOCLCP slide: info %d", info);
    CHECK(fabs(r[0] - 1.6) + fabs(r[1] + 0.8) + fabs(r[2]) <= 1e-10, "SOCLCP slide: r");
    double q_stick[3] = {-1.0, 0.2, -0.1};
    if (opt5_one(SICONOS_FRICTION_3D_SOCLCP, q_stick, r, u, &info)) return 1;
    CHECK(info == 0, "SOCLCP stick: info %d", info);
  }
  /* Options fc3d does not implement are rejected, naming the index; nothing is written. */
  {
    double W[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, q[3] = {-1, 0, 0}, mu = 0.5;
    NumericsMatrix M = {0};
    M.storageType = NM_DENSE;
    M.size0 = M.size1 = 3;
    M.matrix0 = W;
    FrictionContactProblem p = {3, 1, &M, q, &mu};
    double r[3] = {7, 7, 7}, u[3] = {7, 7, 7};
    SolverOptions* o = solver_options_create(SICONOS_FRICTION_3D_TFP);
    o->iparam[3] = 1;
    CHECK(fc3d_driver(&p, r, u, o) == FC3D_ERR_INVALID_OPTION, "TFP rescaling accepted");
    CHECK(strstr(fc3d_last_error_message(), "iparam[3]") != NULL, "message: %s", fc3d_last_error_message());
    o->iparam[3] = 0;
    o->internalSolvers[0]->solverId = SICONOS_FRICTION_3D_ONECONTACT_ProjectionOnCone;
    CHECK(fc3d_driver(&p, r, u, o) == FC3D_ERR_INVALID_OPTION, "TFP internal 552 accepted");
    o->internalSolvers[0]->solverId = SICONOS_FRICTION_3D_NSGS;
    o->dparam[2] = 0.0;
    CHECK(fc3d_driver(&p, r, u, o) == FC3D_ERR_INVALID_OPTION, "TFP ratio 0 accepted");
    CHECK(strstr(fc3d_last_error_message(), "dparam[2]") != NULL, "message: %s", fc3d_last_error_message());
    solver_options_delete(o);
    free(o);
    o = solver_options_create(SICONOS_FRICTION_3D_SOCLCP);
    CHECK(o->dparam[8] == 1.0, "SOCLCP default relaxation");
    o->dparam[8] = 2.0;
    CHECK(fc3d_driver(&p, r, u, o) == FC3D_ERR_INVALID_OPTION, "SOCLCP relaxation 2 accepted");
    CHECK(strstr(fc3d_last_error_message(), "dparam[8]") != NULL, "message: %s", fc3d_last_error_message());
    solver_options_delete(o);
    free(o);
    CHECK(r[0] == 7 && u[0] == 7, "outputs written on rejection");
  }
  return 0;
}

/* ---- nonsmooth Newton (504, 513, 520) and PROX (502) ------------------------------------------ */


/* One contact (W = I) pushed in, one given by q2; solved by `id` with its defaults at 1e-12. */
static int newton_two_contacts(int id, int internal, const double q2[3], double mu2, const double r2_exp[3]) {
  double W[36] = {0};
  for (int i = 0; i < 6; i++) W[i + 6 * i] = 1.0;
  double q[6] = {-1, 0, 0, q2[0], q2[1], q2[2]};
  double mu[2] = {0.5, mu2};
  NumericsMatrix M = {0};
  M.storageType = NM_DENSE;
  M.size0 = M.size1 = 6;
  M.matrix0 = W;
  FrictionContactProblem p = {3, 2, &M, q, mu};
  SolverOptions* o = solver_options_create(id);
  CHECK(o != NULL, "solver_options_create(%d)", id);
  if (internal) solver_options_update_internal(o, 0, internal);
  o->dparam[SICONOS_DPARAM_TOL] = 1e-12;
  o->iparam[SICONOS_IPARAM_MAX_ITER] = 200;
  double r[6] = {0}, u[6] = {0};
  int info = fc3d_driver(&p, r, u, o);
  double err = o->dparam[SICONOS_DPARAM_RESIDU];
  solver_options_delete(o);
  free(o);
  CHECK(info == 0, "solver %d/%d: info %d, error %g", id, internal, info, err);
  CHECK(fabs(r[0] - 1.0) <= 1e-10, "solver %d: r[0] = %.17g", id, r[0]);
  for (int k = 0; k < 3; k++)
    CHECK(fabs(r[3 + k] - r2_exp[k]) <= 1e-9, "solver %d/%d: r[%d] = %.17g, expected %.17g", id, internal,
          3 + k, r[3 + k], r2_exp[k]);
  return 0;
}

int capi_check_newton_and_prox(void) {
  int ids[][2] = {{SICONOS_FRICTION_3D_NSN_AC, 0}, {SICONOS_FRICTION_3D_NSN_FB, 0},
                  {SICONOS_FRICTION_3D_NSN_NM, 0}, {SICONOS_FRICTION_3D_PROX, 0},
                  {SICONOS_FRICTION_3D_PROX, SICONOS_FRICTION_3D_NSGS}};
  for (size_t k = 0; k < sizeof ids / sizeof ids[0]; k++) {
    int id = ids[k][0], in = ids[k][1];
    { /* take-off */
      double q2[3] = {0.5, 0.3, -0.2}, re[3] = {0, 0, 0};
      if (newton_two_contacts(id, in, q2, 0.5, re)) return 1;
    }
    { /* stick */
      double q2[3] = {-1, 0.1, 0}, re[3] = {1, -0.1, 0};
      if (newton_two_contacts(id, in, q2, 0.5, re)) return 1;
    }
    { /* slide: r_T = -mu r_N u_T / |u_T| */
      double q2[3] = {-1, 2, 0}, re[3] = {1, -0.5, 0};
      if (newton_two_contacts(id, in, q2, 0.5, re)) return 1;
    }
  }

  /* Defaults read off Siconos 4.4 and options that are rejected with the index named. */
  SolverOptions* o = solver_options_create(SICONOS_FRICTION_3D_NSN_AC);
  CHECK(o->iparam[SICONOS_IPARAM_MAX_ITER] == 200 && o->dparam[SICONOS_DPARAM_TOL] == 1e-3, "504 defaults");
  CHECK(o->iparam[SICONOS_FRICTION_3D_NSN_RHO_STRATEGY] == 1, "504 rho strategy default");
  CHECK(o->iparam[SICONOS_FRICTION_3D_NSN_LINESEARCH] == 0, "504 line search default");
  solver_options_delete(o);
  free(o);
  o = solver_options_create(SICONOS_FRICTION_3D_PROX);
  CHECK(o->dparam[3] == 1e4 && o->dparam[4] == 5.0 && o->dparam[5] == 1.0, "502 alpha, sigma, nu");
  CHECK(o->numberOfInternalSolvers == 1 && o->internalSolvers[0]->solverId == SICONOS_FRICTION_3D_NSN_AC,
        "502 internal solver");
  solver_options_delete(o);
  free(o);

  double W[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  double q[3] = {-1, 0.2, 0}, mu = 0.5;
  NumericsMatrix M = {0};
  M.storageType = NM_DENSE;
  M.size0 = M.size1 = 3;
  M.matrix0 = W;
  FrictionContactProblem p = {3, 1, &M, q, &mu};
  struct { int id; int index; int value; int code; const char* needle; } bad[] = {
      {SICONOS_FRICTION_3D_NSN_AC, SICONOS_FRICTION_3D_NSN_RHO_STRATEGY, 4, FC3D_ERR_INVALID_OPTION, "iparam[9]"},
      {SICONOS_FRICTION_3D_NSN_AC, SICONOS_FRICTION_3D_NSN_FORMULATION, 4, FC3D_ERR_INVALID_OPTION, "iparam[10]"},
      {SICONOS_FRICTION_3D_NSN_AC, SICONOS_FRICTION_3D_NSN_LINESEARCH, 7, FC3D_ERR_INVALID_OPTION, "iparam[11]"},
      {SICONOS_FRICTION_3D_NSN_FB, SICONOS_FRICTION_3D_NSN_HYBRID_STRATEGY, 1, FC3D_ERR_INVALID_OPTION, "iparam[14]"},
      {SICONOS_FRICTION_3D_NSN_NM, SICONOS_FRICTION_3D_NSN_FORMULATION, 1, FC3D_ERR_INVALID_OPTION, "iparam[10]"},
      {SICONOS_FRICTION_3D_PROX, 9 /* proximal strategy */, 1, FC3D_ERR_INVALID_OPTION, "iparam[9]"},
      {SICONOS_FRICTION_3D_PROX, 8 /* proximal relaxation */, 1, FC3D_ERR_INVALID_OPTION, "iparam[8]"},
  };
  for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
    o = solver_options_create(bad[k].id);
    o->iparam[bad[k].index] = bad[k].value;
    double r[3] = {7, 7, 7}, u[3] = {7, 7, 7};
    int info = fc3d_driver(&p, r, u, o);
    solver_options_delete(o);
    free(o);
    CHECK(info == bad[k].code, "solver %d with iparam[%d] = %d: info %d", bad[k].id, bad[k].index, bad[k].value, info);
    CHECK(strstr(fc3d_last_error_message(), bad[k].needle) != NULL, "message '%s' does not name %s",
          fc3d_last_error_message(), bad[k].needle);
    CHECK(r[0] == 7 && u[2] == 7, "rejected options touched r or u");
  }
  /* PROX with an internal solver fc3d cannot use there. */
  o = solver_options_create(SICONOS_FRICTION_3D_PROX);
  solver_options_update_internal(o, 0, SICONOS_FRICTION_3D_NSN_FB);
  double r[3] = {0}, u[3] = {0};
  int info = fc3d_driver(&p, r, u, o);
  solver_options_delete(o);
  free(o);
  CHECK(info == FC3D_ERR_UNSUPPORTED_SOLVER, "PROX with internal NSN_FB: info %d", info);
  /* A negative sigma. */
  o = solver_options_create(SICONOS_FRICTION_3D_PROX);
  o->dparam[4] = -1.0;
  info = fc3d_driver(&p, r, u, o);
  solver_options_delete(o);
  free(o);
  CHECK(info == FC3D_ERR_INVALID_OPTION, "PROX with sigma = -1: info %d", info);
  return 0;
}

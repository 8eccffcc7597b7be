/* Siconos' direct solver entries of fc3d_Solvers.h, called as a Siconos host calls them: each one
 * gives fc3d_driver's answer for options of its id, refuses options of another id, and the ids
 * fc3d does not provide (GAMS, the Tresca sub-solvers) end with FC3D_ERR_UNSUPPORTED_SOLVER and a
 * message. Also fc3d_checkTrivialCase and fc3d_set_internalsolver_tolerance on a real problem, and
 * frictionContact_copy / frictionContact_rescaling in the three storages. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "FrictionContactProblem.h"
#include "Friction_cst.h"
#include "NonSmoothDrivers.h"
#include "SolverOptions.h"
#include "fc3d_Solvers.h"
#include "NumericsMatrix.h"
#include "SparseBlockMatrix.h"
#include "fc3d_compute_error.h"
#include "fc3d_AlartCurnier_functions.h"
#include "AlartCurnierGenerated.h"

#define FAIL(...)                                                                  \
  do {                                                                             \
    fprintf(stderr, "%s:%d: ", __FILE__, __LINE__);                                \
    fprintf(stderr, __VA_ARGS__);                                                  \
    fprintf(stderr, " [last fc3d error: %s]\n", fc3d_last_error_message());        \
    return 1;                                                                      \
  } while (0)
#define CHECK(cond, ...)            \
  do {                              \
    if (!(cond)) FAIL(__VA_ARGS__); \
  } while (0)

typedef void (*entry_fn)(FrictionContactProblem*, double*, double*, int*, SolverOptions*);

/* Runs `entry` and fc3d_driver from r = 0 with fresh options of `id`: same info, iterations,
 * reaction and velocity. */
static int same_as_driver(FrictionContactProblem* p, const char* name, entry_fn entry, int id) {
  int n = 3 * p->numberOfContacts;
  double* r1 = calloc(n, sizeof(double));
  double* u1 = calloc(n, sizeof(double));
  double* r2 = calloc(n, sizeof(double));
  double* u2 = calloc(n, sizeof(double));
  SolverOptions* o1 = solver_options_create(id);
  SolverOptions* o2 = solver_options_create(id);
  CHECK(o1 && o2, "%s: options of id %d", name, id);
  o1->iparam[0] = o2->iparam[0] = 200;
  int info1 = -100;
  entry(p, r1, u1, &info1, o1);
  int info2 = fc3d_driver(p, r2, u2, o2);
  CHECK(info1 == info2, "%s: info %d, fc3d_driver %d", name, info1, info2);
  CHECK(info1 >= 0, "%s: refused (%d)", name, info1);
  CHECK(o1->iparam[1] == o2->iparam[1], "%s: %d iterations, fc3d_driver %d", name, o1->iparam[1], o2->iparam[1]);
  CHECK(memcmp(r1, r2, n * sizeof(double)) == 0 && memcmp(u1, u2, n * sizeof(double)) == 0,
        "%s: another reaction or velocity than fc3d_driver's", name);
  CHECK(o1->dparam[1] == o2->dparam[1], "%s: error %g, fc3d_driver %g", name, o1->dparam[1], o2->dparam[1]);
  /* Options of another id are refused, nothing written. */
  double r3[3] = {7, 7, 7};
  SolverOptions* other = solver_options_create(id == SICONOS_FRICTION_3D_NSGS ? SICONOS_FRICTION_3D_DSFP
                                                                              : SICONOS_FRICTION_3D_NSGS);
  int info3 = 0;
  double* r4 = malloc(n * sizeof(double));
  for (int i = 0; i < n; i++) r4[i] = 7.0;
  entry(p, r4, u2, &info3, other);
  CHECK(info3 == FC3D_ERR_INVALID_OPTION && fc3d_last_error_code() == FC3D_ERR_INVALID_OPTION,
        "%s with options of id %d: info %d", name, other->solverId, info3);
  CHECK(strstr(fc3d_last_error_message(), name) != NULL, "%s: the message does not name it", name);
  CHECK(r4[0] == 7.0 && r4[n - 1] == 7.0, "%s wrote the reaction while refusing", name);
  (void)r3;
  /* A NULL info: recorded, nothing else happens. */
  entry(p, r1, u1, NULL, o1);
  CHECK(fc3d_last_error_code() == FC3D_ERR_NULL_POINTER, "%s with info NULL", name);
  solver_options_delete(other);
  solver_options_delete(o1);
  solver_options_delete(o2);
  free(other);
  free(o1);
  free(o2);
  free(r1);
  free(u1);
  free(r2);
  free(u2);
  free(r4);
  return 0;
}

static int refused(FrictionContactProblem* p, const char* name, entry_fn entry, int id) {
  int n = 3 * p->numberOfContacts;
  double* r = calloc(n, sizeof(double));
  double* u = calloc(n, sizeof(double));
  r[0] = 5.0;
  SolverOptions* o = solver_options_create(id);
  int info = 0;
  fc3d_clear_last_error();
  entry(p, r, u, &info, o);
  CHECK(info == FC3D_ERR_UNSUPPORTED_SOLVER && fc3d_last_error_code() == FC3D_ERR_UNSUPPORTED_SOLVER,
        "%s: info %d", name, info);
  CHECK(strlen(fc3d_last_error_message()) > 0, "%s: no message", name);
  CHECK(r[0] == 5.0 && r[1] == 0.0, "%s wrote the reaction while refusing", name);
  if (o) {
    solver_options_delete(o);
    free(o);
  }
  free(r);
  free(u);
  return 0;
}

/* NULL where Siconos' functions need data: a code and a message, nothing written, no crash. */
static int null_inputs(FrictionContactProblem* p) {
  double R[3] = {1, 0.1, 0}, u[3] = {-1, 0.2, 0.1}, rho[3] = {1, 1, 1};
  double F[3] = {9, 9, 9}, A[9], B[9];
  for (int i = 0; i < 9; i++) A[i] = B[i] = 9;
  fc3d_clear_last_error();
  computeAlartCurnierSTD(NULL, u, 0.3, rho, F, A, B);
  CHECK(fc3d_last_error_code() == FC3D_ERR_NULL_POINTER && F[0] == 9 && A[0] == 9, "AC with R NULL");
  fc3d_clear_last_error();
  computeAlartCurnierJeanMoreau(R, u, 0.3, NULL, F, A, B);
  CHECK(fc3d_last_error_code() == FC3D_ERR_NULL_POINTER && F[0] == 9 && B[0] == 9, "JM with rho NULL");
  fc3d_clear_last_error();
  fc3d_AlartCurnierFunctionGenerated(R, NULL, 0.3, rho, F, A, B);
  CHECK(fc3d_last_error_code() == FC3D_ERR_NULL_POINTER && F[0] == 9, "generated with velocity NULL");
  fc3d_clear_last_error();
  computeAlartCurnierSTD(R, u, 0.3, rho, NULL, A, B);
  CHECK(fc3d_last_error_code() == FC3D_ERR_NULL_POINTER && A[0] == 9, "STD with F NULL");
  /* The generated function computes A and B alone when F is NULL. */
  fc3d_clear_last_error();
  fc3d_AlartCurnierFunctionGenerated(R, u, 0.3, rho, NULL, A, B);
  CHECK(fc3d_last_error_code() == FC3D_OK && A[0] != 9, "generated A and B alone");
  /* F alone when A or B is NULL. */
  computeAlartCurnierSTD(R, u, 0.3, rho, F, NULL, NULL);
  CHECK(fc3d_last_error_code() == FC3D_OK && F[0] != 9, "STD F alone");

  double e = 0.5, work[3] = {7, 7, 7};
  fc3d_clear_last_error();
  fc3d_unitary_compute_and_add_error(R, u, 0.3, NULL, work);
  CHECK(fc3d_last_error_code() == FC3D_ERR_NULL_POINTER && work[0] == 7, "add_error with error NULL");
  fc3d_Tresca_unitary_compute_and_add_error(R, u, 0.3, &e, NULL);
  CHECK(fc3d_last_error_code() == FC3D_ERR_NULL_POINTER && e == 0.5, "Tresca add_error with worktmp NULL");

  int n = 3 * p->numberOfContacts;
  double* z = calloc(n, sizeof(double));
  double* w = calloc(n, sizeof(double));
  e = -1.0;
  CHECK(fc3d_compute_error_velocity(NULL, z, w, 1e-3, NULL, &e) == FC3D_ERR_NULL_POINTER && e == -1.0,
        "error_velocity with problem NULL");
  CHECK(fc3d_compute_error_velocity(p, NULL, w, 1e-3, NULL, &e) == FC3D_ERR_NULL_POINTER && e == -1.0,
        "error_velocity with z NULL");
  CHECK(fc3d_compute_error_velocity(p, z, w, 1e-3, NULL, NULL) == FC3D_ERR_NULL_POINTER, "error_velocity, error NULL");
  /* The Tresca error needs the radii in options->dWork, one per contact. */
  SolverOptions* o = solver_options_create(SICONOS_FRICTION_3D_NSGS);
  CHECK(fc3d_Tresca_compute_error(p, z, w, 1e-3, NULL, 1.0, &e) == FC3D_ERR_NULL_POINTER && e == -1.0,
        "Tresca error with options NULL");
  CHECK(fc3d_Tresca_compute_error(p, z, w, 1e-3, o, 1.0, &e) == FC3D_ERR_INVALID_OPTION && e == -1.0,
        "Tresca error without radii");
  double* radii = calloc(p->numberOfContacts, sizeof(double));
  o->dWork = radii;
  o->dWorkSize = (size_t)p->numberOfContacts;
  /* At z = 0 with radii 0: w = q and the error is |(q_N)_-| (Capsules has q_N < 0). */
  double expected = 0.0;
  for (int c = 0; c < p->numberOfContacts; c++)
    if (p->q[3 * c] < 0.0) expected += p->q[3 * c] * p->q[3 * c];
  expected = sqrt(expected);
  CHECK(fc3d_Tresca_compute_error(p, z, w, 1e-3, o, 1.0, &e) == 1 && fabs(e - expected) <= 1e-14 * expected &&
            memcmp(w, p->q, n * sizeof(double)) == 0,
        "Tresca error at z = 0: %g, expected %g", e, expected);
  o->dWork = NULL;
  o->dWorkSize = 0;
  free(radii);
  solver_options_delete(o);
  free(o);
  free(z);
  free(w);

  fc3d_clear_last_error();
  fc3d_set_internalsolver_tolerance(p, NULL, NULL, 1e-2);
  CHECK(fc3d_last_error_code() == FC3D_ERR_NULL_POINTER, "set_internalsolver_tolerance with NULL options");
  return 0;
}

int capi_check_solver_entries(const char* data_dir) {
  char path[4096];
  snprintf(path, sizeof path, "%s/Capsules-i101-404.dat", data_dir);
  FrictionContactProblem* p = frictionContact_new_from_filename(path);
  CHECK(p != NULL, "reading %s", path);
  struct {
    const char* name;
    entry_fn entry;
    int id;
  } solved[] = {
      {"fc3d_nsgs", fc3d_nsgs, SICONOS_FRICTION_3D_NSGS},
      {"fc3d_DeSaxceFixedPoint", fc3d_DeSaxceFixedPoint, SICONOS_FRICTION_3D_DSFP},
      {"fc3d_fixedPointProjection", fc3d_fixedPointProjection, SICONOS_FRICTION_3D_FPP},
      {"fc3d_ExtraGradient", fc3d_ExtraGradient, SICONOS_FRICTION_3D_EG},
      {"fc3d_VI_FixedPointProjection", fc3d_VI_FixedPointProjection, SICONOS_FRICTION_3D_VI_FPP},
      {"fc3d_VI_ExtraGradient", fc3d_VI_ExtraGradient, SICONOS_FRICTION_3D_VI_EG},
      {"fc3d_nonsmooth_Newton_AlartCurnier", fc3d_nonsmooth_Newton_AlartCurnier, SICONOS_FRICTION_3D_NSN_AC},
      {"fc3d_nonsmooth_Newton_FischerBurmeister", fc3d_nonsmooth_Newton_FischerBurmeister, SICONOS_FRICTION_3D_NSN_FB},
      {"fc3d_nonsmooth_Newton_NaturalMap", fc3d_nonsmooth_Newton_NaturalMap, SICONOS_FRICTION_3D_NSN_NM},
      {"fc3d_admm", fc3d_admm, SICONOS_FRICTION_3D_ADMM},
      {"fc3d_proximal", fc3d_proximal, SICONOS_FRICTION_3D_PROX},
      {"fc3d_TrescaFixedPoint", fc3d_TrescaFixedPoint, SICONOS_FRICTION_3D_TFP},
      {"fc3d_Panagiotopoulos_FixedPoint", fc3d_Panagiotopoulos_FixedPoint, SICONOS_FRICTION_3D_PFP},
      {"fc3d_SOCLCP", fc3d_SOCLCP, SICONOS_FRICTION_3D_SOCLCP},
      {"fc3d_ACLMFixedPoint", fc3d_ACLMFixedPoint, SICONOS_FRICTION_3D_ACLMFP},
  };
  for (size_t k = 0; k < sizeof solved / sizeof solved[0]; k++)
    if (same_as_driver(p, solved[k].name, solved[k].entry, solved[k].id)) return 1;
  struct {
    const char* name;
    entry_fn entry;
    int id;
  } rejected[] = {
      {"fc3d_AVI_gams_path", fc3d_AVI_gams_path, SICONOS_FRICTION_3D_GAMS_PATH},
      {"fc3d_AVI_gams_pathvi", fc3d_AVI_gams_pathvi, SICONOS_FRICTION_3D_GAMS_PATHVI},
      {"fc3d_lcp_gams_path", fc3d_lcp_gams_path, SICONOS_FRICTION_3D_GAMS_LCP_PATH},
      {"fc3d_lcp_gams_pathvi", fc3d_lcp_gams_pathvi, SICONOS_FRICTION_3D_GAMS_LCP_PATHVI},
      {"fc3d_VI_FixedPointProjection_Cylinder", fc3d_VI_FixedPointProjection_Cylinder, SICONOS_FRICTION_3D_VI_FPP_Cylinder},
      {"fc3d_ConvexQP_ProjectedGradient_Cylinder", fc3d_ConvexQP_ProjectedGradient_Cylinder, SICONOS_FRICTION_3D_CONVEXQP_PG_CYLINDER},
  };
  for (size_t k = 0; k < sizeof rejected / sizeof rejected[0]; k++)
    if (refused(p, rejected[k].name, rejected[k].entry, rejected[k].id)) return 1;

  /* fc3d_checkTrivialCase: Capsules has q_N < 0 somewhere: -1, nothing written. */
  int n = 3 * p->numberOfContacts;
  double* r = malloc(n * sizeof(double));
  double* u = malloc(n * sizeof(double));
  for (int i = 0; i < n; i++) r[i] = u[i] = 3.0;
  int has_negative = 0;
  for (int c = 0; c < p->numberOfContacts; c++) has_negative |= p->q[3 * c] < 0.0;
  CHECK(has_negative, "the problem was expected to have a q_N < 0");
  CHECK(fc3d_checkTrivialCase(p, u, r, NULL) == -1 && r[0] == 3.0 && u[0] == 3.0, "not a take-off");
  /* With q_N >= 0 everywhere: r = 0, u = q, 0 returned. */
  double* q_saved = malloc(n * sizeof(double));
  memcpy(q_saved, p->q, n * sizeof(double));
  for (int c = 0; c < p->numberOfContacts; c++) p->q[3 * c] = fabs(p->q[3 * c]);
  CHECK(fc3d_checkTrivialCase(p, u, r, NULL) == 0, "take-off");
  for (int i = 0; i < n; i++) CHECK(r[i] == 0.0 && u[i] == p->q[i], "take-off: r[%d] = %g, u = %g", i, r[i], u[i]);
  /* ... and it is a solution: Siconos' error is 0. */
  double err = 1.0;
  CHECK(fc3d_compute_error(p, r, u, 1e-14, NULL, 1.0, &err) == 0 && err == 0.0, "take-off error %g", err);
  memcpy(p->q, q_saved, n * sizeof(double));
  CHECK(fc3d_checkTrivialCase(NULL, u, r, NULL) == FC3D_ERR_NULL_POINTER, "NULL problem");

  /* fc3d_set_internalsolver_tolerance for the three strategies. */
  SolverOptions* outer = solver_options_create(SICONOS_FRICTION_3D_TFP);
  SolverOptions* inner = solver_options_create(SICONOS_FRICTION_3D_NSGS);
  outer->dparam[0] = 1e-6;
  outer->dparam[2] = 10.0;
  double nc = p->numberOfContacts;
  outer->iparam[2] = SICONOS_FRICTION_3D_INTERNAL_ERROR_STRATEGY_ADAPTIVE;
  fc3d_set_internalsolver_tolerance(p, outer, inner, 1e-2);
  CHECK(inner->dparam[0] == fmax(1e-2 / 10.0, 1e-6 / nc), "adaptive: %g", inner->dparam[0]);
  outer->iparam[2] = SICONOS_FRICTION_3D_INTERNAL_ERROR_STRATEGY_ADAPTIVE_N_CONTACT;
  fc3d_set_internalsolver_tolerance(p, outer, inner, 1e-2);
  CHECK(inner->dparam[0] == 1e-2 / (10.0 * nc), "adaptive per contact: %g", inner->dparam[0]);
  inner->dparam[0] = 0.125;
  outer->iparam[2] = SICONOS_FRICTION_3D_INTERNAL_ERROR_STRATEGY_GIVEN_VALUE;
  fc3d_set_internalsolver_tolerance(p, outer, inner, 1e-2);
  CHECK(inner->dparam[0] == 0.125, "given value: %g", inner->dparam[0]);
  outer->iparam[2] = 9;
  fc3d_clear_last_error();
  fc3d_set_internalsolver_tolerance(p, outer, inner, 1e-2);
  CHECK(inner->dparam[0] == 0.125 && fc3d_last_error_code() == FC3D_ERR_INVALID_OPTION, "unknown strategy");
  solver_options_delete(outer);
  solver_options_delete(inner);
  free(outer);
  free(inner);
  if (null_inputs(p)) return 1;
  free(q_saved);
  free(r);
  free(u);
  frictionContactProblem_free(p);
  return 0;
}

/* Every entry of M (n x n) times `factor` equals the entry of C. */
static int same_entries(NumericsMatrix* M, NumericsMatrix* C, double factor, const char* what) {
  for (int i = 0; i < M->size0; i++)
    for (int j = 0; j < M->size1; j++) {
      double a = NM_get_value(M, i, j), b = NM_get_value(C, i, j);
      CHECK(a * factor == b, "%s: entry (%d, %d) %g, expected %g", what, i, j, b, a * factor);
    }
  return 0;
}

/* frictionContact_copy keeps the storage and its layout, shares nothing; frictionContact_rescaling
 * scales M by alpha gamma^2 and q by alpha gamma, a sparse M ending in CSC form. */
static int copy_and_rescale(FrictionContactProblem* p, const char* what) {
  int n = 3 * p->numberOfContacts;
  FrictionContactProblem* c = frictionContact_copy(p);
  CHECK(c != NULL, "%s: copy", what);
  CHECK(c->M != p->M && c->q != p->q && c->mu != p->mu, "%s: the copy shares arrays", what);
  CHECK(c->dimension == p->dimension && c->numberOfContacts == p->numberOfContacts, "%s: sizes", what);
  CHECK(c->M->storageType == p->M->storageType && c->M->size0 == p->M->size0 && c->M->size1 == p->M->size1,
        "%s: storage %d, expected %d", what, c->M->storageType, p->M->storageType);
  CHECK(memcmp(c->q, p->q, n * sizeof(double)) == 0, "%s: q", what);
  CHECK(memcmp(c->mu, p->mu, p->numberOfContacts * sizeof(double)) == 0, "%s: mu", what);
  if (same_entries(p->M, c->M, 1.0, what)) return 1;
  switch (p->M->storageType) {
    case NM_DENSE:
      CHECK(c->M->matrix0 != p->M->matrix0, "%s: shared matrix0", what);
      break;
    case NM_SPARSE_BLOCK: {
      SparseBlockStructuredMatrix *a = p->M->matrix1, *b = c->M->matrix1;
      CHECK(a != b && a->nbblocks == b->nbblocks && a->filled1 == b->filled1 && a->filled2 == b->filled2,
            "%s: SBM counts", what);
      CHECK(memcmp(a->index1_data, b->index1_data, a->filled1 * sizeof(size_t)) == 0 &&
                memcmp(a->index2_data, b->index2_data, a->filled2 * sizeof(size_t)) == 0,
            "%s: SBM index arrays", what);
      for (unsigned k = 0; k < a->nbblocks; k++)
        CHECK(a->block[k] != b->block[k] && memcmp(a->block[k], b->block[k], 9 * sizeof(double)) == 0,
              "%s: SBM block %u", what, k);
      break;
    }
    default:
      CHECK(c->M->matrix2 != p->M->matrix2 && c->M->matrix2->origin == p->M->matrix2->origin,
            "%s: sparse origin %d", what, c->M->matrix2->origin);
  }
  /* The copy solves as the original. */
  double* r1 = calloc(n, sizeof(double));
  double* u1 = calloc(n, sizeof(double));
  double* r2 = calloc(n, sizeof(double));
  double* u2 = calloc(n, sizeof(double));
  SolverOptions* o = solver_options_create(SICONOS_FRICTION_3D_NSGS);
  o->dparam[0] = 1e-8;
  o->iparam[0] = 100000;
  int i1 = fc3d_driver(p, r1, u1, o), i2 = fc3d_driver(c, r2, u2, o);
  CHECK(i1 == i2 && memcmp(r1, r2, n * sizeof(double)) == 0, "%s: the copy solves differently (%d, %d)", what, i1, i2);
  CHECK(i1 == 0, "%s: not solved to 1e-8 (info %d, error %g)", what, i1, o->dparam[1]);

  /* Rescaling the copy: M * alpha gamma^2, q * alpha gamma; the original untouched. */
  fc3d_clear_last_error();
  frictionContact_rescaling(c, 2.0, 4.0);
  CHECK(fc3d_last_error_code() == FC3D_OK, "%s: rescaling", what);
  if (same_entries(p->M, c->M, 32.0, what)) return 1;
  for (int i = 0; i < n; i++) CHECK(c->q[i] == 8.0 * p->q[i], "%s: q[%d] not rescaled", what, i);
  if (p->M->storageType == NM_SPARSE) {
    CHECK(c->M->matrix2->origin == NSM_CSC && c->M->matrix2->csc && !c->M->matrix2->triplet,
          "%s: a rescaled sparse matrix is in CSC form", what);
  }
  /* With W' = alpha gamma^2 W and q' = alpha gamma q, r / gamma solves the rescaled problem
   * (u' = alpha gamma u; the cones are scale-invariant): its error there is small too (not the
   * same: the natural map weighs r and u alike, and they scale apart). */
  double err = 1.0;
  for (int i = 0; i < n; i++) r2[i] = r1[i] / 4.0;
  fc3d_compute_error(c, r2, u2, 1e-8, NULL, 1.0, &err);
  CHECK(err <= 1e-6, "%s: r / gamma has error %g on the rescaled problem", what, err);
  /* A non-finite factor is refused, nothing changed. */
  double q0 = c->q[0];
  frictionContact_rescaling(c, NAN, 1.0);
  CHECK(fc3d_last_error_code() == FC3D_ERR_NON_FINITE && c->q[0] == q0, "%s: NaN alpha", what);
  solver_options_delete(o);
  free(o);
  free(r1);
  free(u1);
  free(r2);
  free(u2);
  frictionContactProblem_free(c);
  return 0;
}

int capi_check_problem_copy(const char* data_dir) {
  char path[4096];
  const char* files[] = {"FC3D_Example1.dat", "FC3D_Example1_SBM.dat", "NESpheres_10_1.dat"};
  for (int f = 0; f < 3; f++) {
    snprintf(path, sizeof path, "%s/%s", data_dir, files[f]);
    FrictionContactProblem* p = frictionContact_new_from_filename(path);
    CHECK(p != NULL, "reading %s", path);
    if (copy_and_rescale(p, files[f])) return 1;
    /* The same problem with a sparse (triplet) M. */
    NumericsMatrix* sparse = NM_new();
    fc3d_clear_last_error();
    NM_copy_to_sparse(p->M, sparse, 0.0);
    CHECK(fc3d_last_error_code() == FC3D_OK && sparse->storageType == NM_SPARSE, "sparse copy");
    NumericsMatrix* dense_M = p->M;
    p->M = sparse;
    if (copy_and_rescale(p, "sparse")) return 1;
    p->M = dense_M;
    NM_free(sparse);
    frictionContactProblem_free(p);
  }
  CHECK(frictionContact_copy(NULL) == NULL && fc3d_last_error_code() == FC3D_ERR_NULL_POINTER, "copy of NULL");
  return 0;
}

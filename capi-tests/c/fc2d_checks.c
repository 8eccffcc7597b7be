/* 2D friction through the C API as a Siconos host uses it: fc2d_driver and the direct fc2d_*
 * entries on problems read from files and built by hand (dense and 2x2 sparse-block W), the
 * Siconos defaults of the 2D ids, fc2d_compute_error and its unitary form, the CPG projections,
 * and the rejections (wrong id, wrong dimension, NULL pointers) with untouched outputs.
 * Returns 0 on success. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "SiconosNumerics.h"
#include "FrictionContactProblem.h"
#include "SolverOptions.h"
#include "Friction_cst.h"
#include "NonSmoothDrivers.h"
#include "fc2d_Solvers.h"
#include "fc2d_compute_error.h"

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
} Fc2dResult;

/* The 2D natural-map error in plain C from W read entry by entry: sqrt(sum_c ||r_c -
 * P_K(r_c - (u_N + mu |u_T|, u_T))||^2) / max(||q||, ||r||, ||u||). */
static double independent_error(FrictionContactProblem* p, const double* r) {
  int n = 2 * p->numberOfContacts;
  double* u = malloc(sizeof(double) * (size_t)n);
  for (int i = 0; i < n; i++) {
    u[i] = p->q[i];
    for (int j = 0; j < n; j++) u[i] += NM_get_value(p->M, i, j) * r[j];
  }
  double s = 0, nq = 0, nr = 0, nu = 0;
  for (int c = 0; c < p->numberOfContacts; c++) {
    double mu = p->mu[c];
    double x0 = r[2 * c] - (u[2 * c] + mu * fabs(u[2 * c + 1]));
    double x1 = r[2 * c + 1] - u[2 * c + 1];
    double p0 = x0, p1 = x1;
    if (x0 >= 0 && fabs(x1) <= mu * x0) {
    } else if (mu * fabs(x1) <= -x0) {
      p0 = p1 = 0;
    } else {
      p0 = (x0 + mu * fabs(x1)) / (1 + mu * mu);
      p1 = x1 < 0 ? -mu * p0 : mu * p0;
    }
    s += (r[2 * c] - p0) * (r[2 * c] - p0) + (r[2 * c + 1] - p1) * (r[2 * c + 1] - p1);
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

/* Solves the file's problem with `solver_id` (Siconos defaults, tolerance and iteration limit
 * set) through fc2d_driver; r receives the reaction (capacity values at most). */
int capi_fc2d_solve_file(const char* path, int solver_id, double tolerance, int max_iter,
                         double* reaction_out, int capacity, Fc2dResult* result) {
  FrictionContactProblem* p = frictionContact_new_from_filename(path);
  CHECK(p != NULL, "cannot read %s", path);
  result->dimension = p->dimension;
  CHECK(p->dimension == 2, "%s: dimension %d", path, p->dimension);
  int n = 2 * p->numberOfContacts;
  CHECK(n <= capacity, "%d unknowns do not fit %d", n, capacity);
  double* r = calloc((size_t)n, sizeof(double));
  double* u = calloc((size_t)n, sizeof(double));
  SolverOptions* o = solver_options_create(solver_id);
  CHECK(o != NULL, "no options for %d", solver_id);
  o->dparam[SICONOS_DPARAM_TOL] = tolerance;
  o->iparam[SICONOS_IPARAM_MAX_ITER] = max_iter;
  result->info = fc2d_driver(p, r, u, o);
  result->iterations = o->iparam[SICONOS_IPARAM_ITER_DONE];
  result->reported_error = o->dparam[SICONOS_DPARAM_RESIDU];
  double nq = 0;
  for (int i = 0; i < n; i++) nq += p->q[i] * p->q[i];
  double* w = calloc((size_t)n, sizeof(double));
  CHECK(fc2d_compute_error(p, r, w, tolerance, sqrt(nq), &result->api_error) >= 0, "fc2d_compute_error");
  for (int i = 0; i < n; i++) CHECK(w[i] == u[i] || fabs(w[i] - u[i]) <= 1e-12 * (1 + fabs(w[i])), "u != W r + q at %d", i);
  result->independent_error = independent_error(p, r);
  memcpy(reaction_out, r, sizeof(double) * (size_t)n);
  free(w);
  free(r);
  free(u);
  solver_options_delete(o);
  free(o);
  frictionContactProblem_free(p);
  return 0;
}

/* One contact, W = [[2, 0.5], [0.5, 1]] (column-major the same: symmetric), mu = 0.5. With q =
 * (-1, 5) it slides, r = (1/1.75, -0.5/1.75); with q = -W (1, 0.2) = (-2.1, -0.7) it sticks at
 * r = (1, 0.2). */
static FrictionContactProblem* one_contact_q(int sbm, double q0, double q1) {
  double* q = malloc(2 * sizeof(double));
  double* mu = malloc(sizeof(double));
  q[0] = q0;
  q[1] = q1;
  mu[0] = 0.5;
  double w[4] = {2, 0.5, 0.5, 1};
  NumericsMatrix* M;
  if (!sbm) {
    M = NM_create(NM_DENSE, 2, 2);
    memcpy(M->matrix0, w, sizeof w);
  } else {
    SparseBlockStructuredMatrix* s = SBM_new();
    s->nbblocks = 1;
    s->blocknumber0 = s->blocknumber1 = 1;
    s->blocksize0 = malloc(sizeof(unsigned));
    s->blocksize1 = malloc(sizeof(unsigned));
    s->blocksize0[0] = s->blocksize1[0] = 2;
    s->filled1 = 2;
    s->filled2 = 1;
    s->index1_data = malloc(2 * sizeof(size_t));
    s->index1_data[0] = 0;
    s->index1_data[1] = 1;
    s->index2_data = calloc(1, sizeof(size_t));
    s->block = malloc(sizeof(double*));
    s->block[0] = malloc(sizeof w);
    memcpy(s->block[0], w, sizeof w);
    M = NM_new_SBM(2, 2, s);
  }
  return frictionContactProblem_new_with_data(2, 1, M, q, mu);
}

static FrictionContactProblem* one_contact(int sbm) { return one_contact_q(sbm, -1, 5); }

/* Siconos' CPG stops on the sliding contact after one step (p.Wp = 0; Siconos 4.4 returns info
 * 2 with the same reaction): fc3d measures the same error there, 0.1869, and reports info 1.
 * On the sticking contact it converges. */
static int check_cpg(int sbm) {
  FrictionContactProblem* p = one_contact(sbm);
  double r[2] = {0, 0}, u[2] = {0, 0};
  SolverOptions* o = solver_options_create(SICONOS_FRICTION_2D_CPG);
  o->dparam[SICONOS_DPARAM_TOL] = 1e-12;
  int info = fc2d_driver(p, r, u, o);
  CHECK(info == 1 && fabs(o->dparam[SICONOS_DPARAM_RESIDU] - 0.1869) < 1e-4, "CPG sliding: info %d error %g",
        info, o->dparam[SICONOS_DPARAM_RESIDU]);
  frictionContactProblem_free(p);
  p = one_contact_q(sbm, -2.1, -0.7);
  r[0] = r[1] = 0;
  info = fc2d_driver(p, r, u, o);
  CHECK(info == 0 && fabs(r[0] - 1) < 1e-12 && fabs(r[1] - 0.2) < 1e-12, "CPG stick: info %d r (%g, %g)", info,
        r[0], r[1]);
  solver_options_delete(o);
  free(o);
  frictionContactProblem_free(p);
  return 0;
}

static int check_one_contact(int sbm, int id) {
  FrictionContactProblem* p = one_contact(sbm);
  CHECK(p != NULL, "problem");
  double r[2] = {0, 0}, u[2] = {0, 0};
  SolverOptions* o = solver_options_create(id);
  o->dparam[SICONOS_DPARAM_TOL] = 1e-12;
  o->iparam[SICONOS_IPARAM_MAX_ITER] = 1000;
  int info = fc2d_driver(p, r, u, o);
  CHECK(info == 0, "id %d sbm %d: info %d", id, sbm, info);
  double rn = 1 / 1.75;
  CHECK(fabs(r[0] - rn) < 1e-12 && fabs(r[1] + 0.5 * rn) < 1e-12, "id %d sbm %d: r = (%g, %g)", id, sbm, r[0],
        r[1]);
  CHECK(fabs(u[0]) < 1e-12 && u[1] > 0, "id %d sbm %d: u = (%g, %g)", id, sbm, u[0], u[1]);
  CHECK(o->dparam[SICONOS_DPARAM_RESIDU] <= 1e-12, "id %d: dparam[1] = %g", id, o->dparam[SICONOS_DPARAM_RESIDU]);
  /* The direct entry of the same id gives the same answer. */
  double r2[2] = {0, 0}, u2[2] = {0, 0};
  int info2 = -100;
  switch (id) {
    case SICONOS_FRICTION_2D_NSGS: fc2d_nsgs_dense(p, r2, u2, &info2, o); break;
    case SICONOS_FRICTION_2D_LEMKE: fc2d_lexicolemke(p, r2, u2, &info2, o); break;
    default: fc2d_enum(p, r2, u2, &info2, o); break;
  }
  CHECK(info2 == 0 && r2[0] == r[0] && r2[1] == r[1], "direct entry of %d: info %d", id, info2);
  /* A direct entry refuses options of another id; nothing is written. */
  if (id != SICONOS_FRICTION_2D_NSGS) {
    double r3[2] = {7, 7};
    fc2d_nsgs_sbm(p, r3, u2, &info2, o);
    CHECK(info2 == FC3D_ERR_INVALID_OPTION && r3[0] == 7, "fc2d_nsgs_sbm with options of %d: %d", id, info2);
  }
  solver_options_delete(o);
  free(o);
  frictionContactProblem_free(p);
  return 0;
}

/* W of a 2D problem rebuilt by hand as a dense matrix (storage 0) or as a sparse-block matrix
 * of its non-zero 2x2 blocks (storage 1), the blocks column-major as Siconos stores them. */
static NumericsMatrix* rebuild_2d(NumericsMatrix* W, int nc, int storage) {
  int n = 2 * nc;
  if (storage == 0) {
    NumericsMatrix* M = NM_create(NM_DENSE, n, n);
    for (int j = 0; j < n; j++)
      for (int i = 0; i < n; i++) M->matrix0[i + (size_t)j * n] = NM_get_value(W, i, j);
    return M;
  }
  SparseBlockStructuredMatrix* s = SBM_new();
  s->blocknumber0 = s->blocknumber1 = (unsigned)nc;
  s->blocksize0 = malloc(sizeof(unsigned) * (size_t)nc);
  s->blocksize1 = malloc(sizeof(unsigned) * (size_t)nc);
  for (int b = 0; b < nc; b++) s->blocksize0[b] = s->blocksize1[b] = (unsigned)(2 * (b + 1));
  s->index1_data = malloc(sizeof(size_t) * (size_t)(nc + 1));
  s->index2_data = malloc(sizeof(size_t) * (size_t)nc * (size_t)nc);
  s->block = malloc(sizeof(double*) * (size_t)nc * (size_t)nc);
  size_t k = 0;
  for (int bi = 0; bi < nc; bi++) {
    s->index1_data[bi] = k;
    for (int bj = 0; bj < nc; bj++) {
      double v[4];
      int nonzero = bi == bj;
      for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++) {
          v[i + 2 * j] = NM_get_value(W, 2 * bi + i, 2 * bj + j);
          nonzero |= v[i + 2 * j] != 0;
        }
      if (!nonzero) continue;
      s->index2_data[k] = (size_t)bj;
      s->block[k] = malloc(sizeof v);
      memcpy(s->block[k], v, sizeof v);
      k++;
    }
  }
  s->index1_data[nc] = k;
  s->filled1 = (size_t)nc + 1;
  s->filled2 = k;
  s->nbblocks = k;
  return NM_new_SBM(n, n, s);
}

/* The file's problem solved with W as read, rebuilt dense and rebuilt as a 2x2 sparse-block
 * matrix: the same reaction, bit for bit (the sweep sees the same blocks). */
int capi_fc2d_check_storages(const char* path) {
  FrictionContactProblem* file = frictionContact_new_from_filename(path);
  CHECK(file != NULL && file->dimension == 2, "cannot read %s", path);
  int nc = file->numberOfContacts, n = 2 * nc;
  double* reference = NULL;
  for (int storage = -1; storage < 2; storage++) {
    FrictionContactProblem* p = file;
    if (storage >= 0) {
      double* q = malloc(sizeof(double) * (size_t)n);
      double* mu = malloc(sizeof(double) * (size_t)nc);
      memcpy(q, file->q, sizeof(double) * (size_t)n);
      memcpy(mu, file->mu, sizeof(double) * (size_t)nc);
      p = frictionContactProblem_new_with_data(2, nc, rebuild_2d(file->M, nc, storage), q, mu);
    }
    double* r = calloc((size_t)n, sizeof(double));
    double* u = calloc((size_t)n, sizeof(double));
    SolverOptions* o = solver_options_create(SICONOS_FRICTION_2D_NSGS);
    o->dparam[SICONOS_DPARAM_TOL] = 1e-10;
    o->iparam[SICONOS_IPARAM_MAX_ITER] = 100000;
    int info = fc2d_driver(p, r, u, o);
    CHECK(info == 0, "%s storage %d: info %d", path, storage, info);
    if (!reference) {
      reference = r;
    } else {
      for (int i = 0; i < n; i++)
        CHECK(r[i] == reference[i], "%s storage %d: r[%d] = %.17g, as read %.17g", path, storage, i, r[i],
              reference[i]);
      free(r);
    }
    free(u);
    solver_options_delete(o);
    free(o);
    if (p != file) frictionContactProblem_free(p);
  }
  free(reference);
  frictionContactProblem_free(file);
  return 0;
}

int capi_fc2d_check_api(void) {
  /* Siconos 4.4's defaults (solver_options_create of the installed library). */
  struct {
    int id, maxit, err_eval;
    double tol;
  } d[] = {{400, 1000, 2, 1e-4}, {402, 1000, 0, 1e-4}, {404, 10000, 0, 1e-6}, {405, 0, 0, 1e-6}};
  for (int k = 0; k < 4; k++) {
    SolverOptions* o = solver_options_create(d[k].id);
    CHECK(o != NULL && o->solverId == d[k].id && o->iSize == 20 && o->dSize == 20 && o->numberOfInternalSolvers == 0,
          "options of %d", d[k].id);
    CHECK(o->iparam[0] == d[k].maxit && o->dparam[0] == d[k].tol && o->iparam[7] == d[k].err_eval &&
              isinf(o->dparam[1]),
          "defaults of %d: %d %g %d", d[k].id, o->iparam[0], o->dparam[0], o->iparam[7]);
    for (int i = 1; i < 20; i++)
      CHECK(i == 7 || o->iparam[i] == 0, "id %d iparam[%d] = %d", d[k].id, i, o->iparam[i]);
    solver_options_delete(o);
    free(o);
  }
  CHECK(strcmp(solver_options_id_to_name(400), "F2D_NSGS") == 0 && solver_options_name_to_id("F2D_ENUM") == 405,
        "names");
  /* fc2d_nsgs_set_default writes iparam[5] and iparam[7] only. */
  {
    SolverOptions* o = solver_options_create(SICONOS_FRICTION_2D_NSGS);
    o->iparam[5] = 3;
    o->iparam[7] = 0;
    o->iparam[0] = 17;
    fc2d_nsgs_set_default(o);
    CHECK(o->iparam[5] == 0 && o->iparam[7] == 2 && o->iparam[0] == 17, "fc2d_nsgs_set_default");
    solver_options_delete(o);
    free(o);
  }

  /* A 2D problem whose sparse-block W has a 3x3 block: refused. */
  {
    FrictionContactProblem* p = one_contact(1);
    SparseBlockStructuredMatrix* s = p->M->matrix1;
    s->blocksize0[0] = s->blocksize1[0] = 3;
    double r[2] = {7, 7}, u[2] = {7, 7};
    SolverOptions* o = solver_options_create(SICONOS_FRICTION_2D_NSGS);
    int info = fc2d_driver(p, r, u, o);
    CHECK(info < 0 && r[0] == 7, "3x3 blocks in a 2D problem: %d", info);
    CHECK(strstr(fc3d_last_error_message(), "2x2") != NULL, "message: %s", fc3d_last_error_message());
    s->blocksize0[0] = s->blocksize1[0] = 2;
    solver_options_delete(o);
    free(o);
    frictionContactProblem_free(p);
  }

  int ids[] = {400, 404, 405};
  for (int k = 0; k < 3; k++)
    for (int sbm = 0; sbm < 2; sbm++)
      if (check_one_contact(sbm, ids[k])) return 1;
  for (int sbm = 0; sbm < 2; sbm++)
    if (check_cpg(sbm)) return 1;

  /* Rejections: nothing written, a code and a message. */
  {
    FrictionContactProblem* p = one_contact(0);
    double r[2] = {7, 7}, u[2] = {7, 7};
    SolverOptions* o3 = solver_options_create(SICONOS_FRICTION_3D_NSGS);
    int info = fc2d_driver(p, r, u, o3);
    CHECK(info == FC3D_ERR_UNSUPPORTED_SOLVER && r[0] == 7 && u[0] == 7, "fc2d_driver with 500: %d", info);
    CHECK(strstr(fc3d_last_error_message(), "not a 2D friction solver") != NULL, "message: %s",
          fc3d_last_error_message());
    SolverOptions* o2 = solver_options_create(SICONOS_FRICTION_2D_NSGS);
    info = fc3d_driver(p, r, u, o2);
    CHECK(info == FC3D_ERR_UNSUPPORTED_SOLVER && r[0] == 7, "fc3d_driver with 400: %d", info);
    CHECK(strstr(fc3d_last_error_message(), "fc2d_driver") != NULL, "message: %s", fc3d_last_error_message());
    info = fc3d_driver(p, r, u, o3);
    CHECK(info == FC3D_ERR_INVALID_PROBLEM && r[0] == 7, "fc3d_driver on a 2D problem: %d", info);
    CHECK(strstr(fc3d_last_error_message(), "fc2d_driver") != NULL, "message: %s", fc3d_last_error_message());
    p->dimension = 3;
    info = fc2d_driver(p, r, u, o2);
    CHECK(info == FC3D_ERR_INVALID_PROBLEM && r[0] == 7, "fc2d_driver on dimension 3: %d", info);
    p->dimension = 2;
    CHECK(fc2d_driver(NULL, r, u, o2) == FC3D_ERR_NULL_POINTER, "NULL problem");
    CHECK(fc2d_driver(p, NULL, u, o2) == FC3D_ERR_NULL_POINTER, "NULL reaction");
    CHECK(fc2d_driver(p, r, u, NULL) == FC3D_ERR_NULL_POINTER, "NULL options");
    o2->iparam[7] = 5;
    info = fc2d_driver(p, r, u, o2);
    CHECK(info == FC3D_ERR_INVALID_OPTION && r[0] == 7, "error evaluation 5: %d", info);
    o2->iparam[7] = 2;
    SolverOptions* ol = solver_options_create(SICONOS_FRICTION_2D_LEMKE);
    ol->iparam[5] = 1;
    info = fc2d_driver(p, r, u, ol);
    CHECK(info == FC3D_ERR_INVALID_OPTION && r[0] == 7, "Lemke pivoting 1: %d", info);
    int info_direct = 0;
    fc2d_cpg(p, r, u, NULL, o2);
    CHECK(r[0] == 7, "NULL info wrote");
    fc2d_cpg(p, r, u, &info_direct, o2);
    CHECK(info_direct == FC3D_ERR_INVALID_OPTION, "fc2d_cpg with 400 options: %d", info_direct);
    /* fc2d_compute_error on the exact answer, and its 3D counterpart refuses the 2D problem. */
    double rn = 1 / 1.75, z[2] = {rn, -0.5 * rn}, w[2], e = -1;
    CHECK(fc2d_compute_error(p, z, w, 1e-14, 0, &e) == 0 && e < 1e-15, "fc2d_compute_error %g", e);
    CHECK(fabs(w[0]) < 1e-15 && fabs(w[1] - (5 + 0.5 * rn - 0.5 * rn)) < 1e-14, "w = (%g, %g)", w[0], w[1]);
    z[0] = 0;
    CHECK(fc2d_compute_error(p, z, w, 1e-14, 0, &e) == 1 && e > 0.1, "fc2d_compute_error off %g", e);
    CHECK(fc3d_compute_error(p, z, w, 1e-4, NULL, 0, &e) == FC3D_ERR_INVALID_PROBLEM, "fc3d_compute_error 2D");
    /* Hostile problems: a code, a message, nothing written. */
    p->q[0] = NAN;
    info = fc2d_driver(p, r, u, o2);
    CHECK(info == FC3D_ERR_NON_FINITE && r[0] == 7, "NaN in q: %d", info);
    p->q[0] = -1;
    p->mu[0] = -0.5;
    info = fc2d_driver(p, r, u, o2);
    CHECK(info == FC3D_ERR_INVALID_PROBLEM && r[0] == 7, "mu < 0: %d", info);
    p->mu[0] = 0.5;
    p->numberOfContacts = -1;
    info = fc2d_driver(p, r, u, o2);
    CHECK(info == FC3D_ERR_INVALID_SIZE && r[0] == 7, "numberOfContacts -1: %d", info);
    p->numberOfContacts = 2;
    info = fc2d_driver(p, r, u, o2);
    CHECK(info == FC3D_ERR_INVALID_SIZE && r[0] == 7, "M 2x2 for 2 contacts: %d", info);
    p->numberOfContacts = 1;
    NumericsMatrix* M = p->M;
    p->M = NULL;
    info = fc2d_driver(p, r, u, o2);
    CHECK(info == FC3D_ERR_NULL_POINTER && r[0] == 7, "M NULL: %d", info);
    p->M = M;
    info = fc2d_driver(p, r, u, o2);
    CHECK(info == 0 && r[0] != 7, "the repaired problem: %d", info);
    solver_options_delete(o2);
    free(o2);
    solver_options_delete(o3);
    free(o3);
    solver_options_delete(ol);
    free(ol);
    frictionContactProblem_free(p);
  }

  /* The unitary error: r = (1, 0), u = (0, -1), mu = 1: r - u~ = (0, 1) projects on (0.5, 0.5). */
  {
    double r[2] = {1, 0}, u[2] = {0, -1}, e = 0.25, tmp[2];
    fc2d_unitary_compute_and_add_error(r, u, 1.0, &e, tmp);
    CHECK(fabs(tmp[0] - 0.5) < 1e-15 && fabs(tmp[1] + 0.5) < 1e-15 && fabs(e - 0.75) < 1e-15,
          "unitary: tmp (%g, %g) e %g", tmp[0], tmp[1], e);
  }
  /* The CPG projections. */
  {
    int n = 8;
    double xi[8] = {-1, 0, 1, -2, 1, 2, 1, 0.1};
    double pi[8] = {0, 0, 0, 1, 0, 1, 0, 0};
    double fric[4] = {0.5, 0.5, 0.5, 0.5};
    int before[4] = {2, 2, 2, 3};
    double out[8];
    int status[4];
    fc2d_projc(xi, &n, before, pi, fric, out, status);
    CHECK(out[0] == 0 && out[1] == 0 && status[0] == 0, "projc open");
    CHECK(out[2] == 1 && out[3] == -0.5 && status[1] == 1, "projc backward");
    CHECK(out[4] == 1 && out[5] == 0.5 && status[2] == 3, "projc forward");
    CHECK(out[6] == 1 && out[7] == 0.5 && status[3] == 3, "projc stays sliding: (%g, %g) %d", out[6], out[7],
          status[3]);
    int etat[4] = {0, 3, 1, 2};
    double y[8] = {-1, 4, 2, 3, 2, -3, 5, 6};
    fc2d_projf(etat, &n, y, fric, out);
    CHECK(out[0] == 0 && out[1] == 0 && out[2] == 2 && out[3] == 0 && out[4] == 2 && out[5] == 0 && out[6] == 5 &&
              out[7] == 6,
          "projf");
  }
  return 0;
}

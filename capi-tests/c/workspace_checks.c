/* C-side checks of fc3d's workspace (warm start across time steps by contact id) and of the
 * per-contact diagnostics. Called from ../tests/workspace.rs and from ownership_main.c
 * (valgrind). Returns 0 on success, prints what failed otherwise. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "SiconosNumerics.h"
#include "FrictionContactProblem.h"
#include "NumericsMatrix.h"
#include "SolverOptions.h"
#include "Friction_cst.h"
#include "NonSmoothDrivers.h"
#include <fc3d.h>

#define CHECK(cond, ...)                                                           \
  do {                                                                             \
    if (!(cond)) {                                                                 \
      fprintf(stderr, "%s:%d: ", __FILE__, __LINE__);                              \
      fprintf(stderr, __VA_ARGS__);                                                \
      fprintf(stderr, " [last fc3d error: %s]\n", fc3d_last_error_message());      \
      return 1;                                                                    \
    }                                                                              \
  } while (0)

/* nc independent spheres on a plane: W = blockdiag(diag(1, 3.5, 3.5)), q_c = (-push[c], 0.1, 0). */
typedef struct {
  double W[15 * 15];
  double q[15];
  double mu[5];
  NumericsMatrix M;
  FrictionContactProblem p;
} Spheres;

static void spheres(Spheres* s, int nc, const double* push) {
  int n = 3 * nc;
  memset(s, 0, sizeof *s);
  for (int c = 0; c < nc; c++) {
    double d[3] = {1.0, 3.5, 3.5};
    for (int i = 0; i < 3; i++) s->W[(3 * c + i) + (3 * c + i) * n] = d[i];
    s->q[3 * c] = -push[c];
    s->q[3 * c + 1] = 0.1;
    s->mu[c] = 0.5;
  }
  s->M.storageType = NM_DENSE;
  s->M.size0 = s->M.size1 = n;
  s->M.matrix0 = s->W;
  s->p.dimension = 3;
  s->p.numberOfContacts = nc;
  s->p.M = &s->M;
  s->p.q = s->q;
  s->p.mu = s->mu;
}

static SolverOptions* nsgs(void) {
  SolverOptions* o = solver_options_create(SICONOS_FRICTION_3D_NSGS);
  o->dparam[SICONOS_DPARAM_TOL] = 1e-12;
  o->iparam[SICONOS_IPARAM_MAX_ITER] = 1000;
  return o;
}

static int check_steps(void) {
  Fc3dWorkspace* ws = fc3d_workspace_new();
  CHECK(ws != NULL, "fc3d_workspace_new");
  SolverOptions* o = nsgs();
  Spheres s;
  double r[15], u[15];

  double push1[3] = {1, 2, 3};
  int64_t ids1[3] = {10, 20, 30};
  spheres(&s, 3, push1);
  int info = fc3d_workspace_driver(ws, &s.p, ids1, r, u, o);
  CHECK(info == 0, "step 1: info %d", info);
  for (int c = 0; c < 3; c++) CHECK(fabs(r[3 * c] - push1[c]) < 1e-12, "step 1: r_N[%d] = %g", c, r[3 * c]);

  /* Step 2: contact 20 vanished, 40 appeared, the others moved in the arrays; the ones kept did
     not change, so NSGS starts at their solution. */
  double push2[3] = {3, 5, 1};
  int64_t ids2[3] = {30, 40, 10};
  spheres(&s, 3, push2);
  for (int k = 0; k < 9; k++) r[k] = 1e300; /* ignored: the warm start replaces it */
  info = fc3d_workspace_driver(ws, &s.p, ids2, r, u, o);
  CHECK(info == 0, "step 2: info %d", info);
  for (int c = 0; c < 3; c++) CHECK(fabs(r[3 * c] - push2[c]) < 1e-12, "step 2: r_N[%d] = %g", c, r[3 * c]);

  /* The same step cold through fc3d_driver gives the same answer. */
  double rc[9] = {0}, uc[9] = {0};
  info = fc3d_driver(&s.p, rc, uc, o);
  CHECK(info == 0, "cold: info %d", info);
  for (int k = 0; k < 9; k++) CHECK(fabs(rc[k] - r[k]) < 1e-12, "cold r[%d] = %g, warm %g", k, rc[k], r[k]);

  /* Rejected input: nothing written, the workspace keeps the previous step. */
  int64_t twice[3] = {1, 2, 1};
  double keep[9];
  memcpy(keep, r, sizeof keep);
  CHECK(fc3d_workspace_driver(ws, &s.p, twice, r, u, o) == FC3D_ERR_INVALID_OPTION, "duplicate ids accepted");
  CHECK(memcmp(keep, r, sizeof keep) == 0, "reaction written on failure");
  CHECK(fc3d_workspace_driver(ws, &s.p, NULL, r, u, o) == FC3D_ERR_NULL_POINTER, "NULL ids accepted");
  CHECK(fc3d_workspace_driver(NULL, &s.p, ids2, r, u, o) == FC3D_ERR_NULL_POINTER, "NULL workspace accepted");
  CHECK(fc3d_workspace_driver(ws, NULL, ids2, r, u, o) == FC3D_ERR_NULL_POINTER, "NULL problem accepted");
  CHECK(fc3d_workspace_driver(ws, &s.p, ids2, r, u, NULL) == FC3D_ERR_NULL_POINTER, "NULL options accepted");

  /* Step 3 after the failures: the ids of step 2 are still known, one more iteration suffices. */
  info = fc3d_workspace_driver(ws, &s.p, ids2, r, u, o);
  CHECK(info == 0 && o->iparam[SICONOS_IPARAM_ITER_DONE] <= 2, "step 3: info %d after %d sweeps", info,
        o->iparam[SICONOS_IPARAM_ITER_DONE]);

  /* NSN through the same workspace (its Newton matrix kept between the two calls), then a
     step with one more contact (a new block pattern: everything rebuilt). */
  SolverOptions* nsn = solver_options_create(SICONOS_FRICTION_3D_NSN_AC);
  nsn->dparam[SICONOS_DPARAM_TOL] = 1e-12;
  for (int rep = 0; rep < 2; rep++) {
    info = fc3d_workspace_driver(ws, &s.p, ids2, r, u, nsn);
    CHECK(info == 0, "NSN step %d: info %d", rep, info);
    for (int c = 0; c < 3; c++) CHECK(fabs(r[3 * c] - push2[c]) < 1e-10, "NSN: r_N[%d] = %g", c, r[3 * c]);
  }
  double push4[4] = {3, 5, 1, 2};
  int64_t ids4[4] = {30, 40, 10, 50};
  spheres(&s, 4, push4);
  info = fc3d_workspace_driver(ws, &s.p, ids4, r, u, nsn);
  CHECK(info == 0, "4 contacts: info %d", info);
  for (int c = 0; c < 4; c++) CHECK(fabs(r[3 * c] - push4[c]) < 1e-10, "4 contacts: r_N[%d] = %g", c, r[3 * c]);
  solver_options_delete(nsn);
  free(nsn);

  solver_options_delete(o);
  free(o);
  fc3d_workspace_free(ws);
  fc3d_workspace_free(NULL);
  return 0;
}

static int check_diagnostics(void) {
  /* Stick, take-off, slide and apex on independent contacts with known answers. */
  Spheres s;
  double push[4] = {1, -2, 1, 0};
  spheres(&s, 4, push);
  s.q[3 * 2 + 1] = -7.0;         /* contact 2 slides: r = (1, 0.5, 0), u_T = 3.5 * 0.5 - 7 */
  s.q[3 * 3 + 1] = 0.5;          /* contact 3 grazes: r = 0, u = (0, 0.5, 0) */
  double r[12] = {1, -0.1 / 3.5, 0, 0, 0, 0, 1, 0.5, 0, 0, 0, 0};
  int status[4] = {-1, -1, -1, -1}, worst[6];
  double err[4], un[4];
  CHECK(fc3d_contact_diagnostics(&s.p, r, 0.0, status, err, un, 6, worst) == 0, "diagnostics");
  CHECK(status[0] == FC3D_CONTACT_STICK, "status[0] %d", status[0]);
  CHECK(status[1] == FC3D_CONTACT_TAKE_OFF, "status[1] %d", status[1]);
  CHECK(status[2] == FC3D_CONTACT_SLIDE, "status[2] %d", status[2]);
  CHECK(status[3] == FC3D_CONTACT_APEX, "status[3] %d", status[3]);
  CHECK(un[1] == 2.0 && un[0] == 0.0, "normal velocities %g %g", un[0], un[1]);
  for (int c = 0; c < 4; c++) CHECK(err[c] < 1e-15, "error contribution[%d] = %g", c, err[c]);
  CHECK(worst[4] == -1 && worst[5] == -1, "worst beyond the contacts: %d %d", worst[4], worst[5]);

  /* Why a step does not converge: contact 1 is frictionless with W_NN = 0 and pushed in. */
  s.W[3 + 3 * 12] = 0.0;
  s.mu[1] = 0.0;
  s.q[3] = -0.5;
  CHECK(fc3d_contact_diagnostics(&s.p, r, 1e-6, NULL, err, un, 1, worst) == 0, "diagnostics");
  CHECK(worst[0] == 1 && un[1] == -0.5, "worst %d, u_N %g", worst[0], un[1]);

  /* Rejected input, nothing written. */
  worst[0] = 42;
  CHECK(fc3d_contact_diagnostics(&s.p, r, 0.0, NULL, NULL, NULL, -1, worst) == FC3D_ERR_INVALID_SIZE, "k < 0");
  CHECK(fc3d_contact_diagnostics(&s.p, r, 0.0, NULL, NULL, NULL, 2, NULL) == FC3D_ERR_NULL_POINTER, "worst NULL");
  CHECK(fc3d_contact_diagnostics(&s.p, NULL, 0.0, status, NULL, NULL, 0, NULL) == FC3D_ERR_NULL_POINTER,
        "reaction NULL");
  CHECK(fc3d_contact_diagnostics(&s.p, r, NAN, status, NULL, NULL, 1, worst) == FC3D_ERR_INVALID_OPTION,
        "NaN tolerance");
  CHECK(worst[0] == 42, "worst written on failure");
  return 0;
}

int capi_check_workspace(void) {
  if (check_steps()) return 1;
  return check_diagnostics();
}

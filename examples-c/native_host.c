/* A host of fc3d's native entry (fc3d.h, or fc3d_native.h for the library without Siconos names):
 * one sliding contact in dense and block-sparse storage and in the global form (M, H), then, when a
 * path is given, a problem
 * read from a Siconos .dat file and solved with NSGS and NSN_AC. Exits non-zero on any wrong
 * answer. Built from outside the source tree by the test suite:
 *
 *   cc $(pkg-config --cflags fc3d) native_host.c $(pkg-config --libs fc3d) -lm -o native_host
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef FC3D_NATIVE_ONLY
#include <fc3d_native.h>
#else
#include <fc3d.h>
#endif

#define CHECK(cond, ...)                                \
  do {                                                  \
    if (!(cond)) {                                      \
      fprintf(stderr, "native_host: " __VA_ARGS__);     \
      fprintf(stderr, " (%s)\n", fc3d_last_error_message()); \
      return 1;                                         \
    }                                                   \
  } while (0)

int main(int argc, char** argv) {
  printf("fc3d %s (%d.%d.%d)\n", fc3d_version(), FC3D_VERSION_MAJOR, FC3D_VERSION_MINOR, FC3D_VERSION_PATCH);
  CHECK(strcmp(fc3d_version(), "0.0.0") != 0, "version");

  /* One contact, W = I, q = (-1, 2, 0), mu = 0.5: it slides, r = (1, -0.5, 0), u = (0, 1.5, 0). */
  double W[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  double q[3] = {-1, 2, 0}, mu[1] = {0.5};
  double r[3] = {0, 0, 0}, u[3];
  Fc3dSettings* s = fc3d_settings_new(500);
  CHECK(s != NULL, "settings");
  CHECK(fc3d_settings_set_tolerance(s, 1e-12) == 0, "tolerance");
  CHECK(fc3d_settings_set(s, "max_iter", 100) == 0, "max_iter by name");
  Fc3dResult res;
  int info = fc3d_solve_dense(1, W, q, mu, r, u, s, &res);
  CHECK(info == 0 && res.info == 0, "dense solve: info %d", info);
  CHECK(fabs(r[0] - 1) < 1e-10 && fabs(r[1] + 0.5) < 1e-10 && fabs(r[2]) < 1e-10, "dense r = (%g, %g, %g)",
        r[0], r[1], r[2]);
  CHECK(fabs(u[1] - 1.5) < 1e-10 && res.error <= 1e-12, "dense u, error %g", res.error);

  int64_t row_ptr[2] = {0, 1}, col_idx[1] = {0};
  double r2[3] = {0, 0, 0}, u2[3];
  info = fc3d_solve_blocks(1, 1, row_ptr, col_idx, W, q, mu, r2, u2, s, &res);
  CHECK(info == 0 && fabs(r2[1] + 0.5) < 1e-10, "block solve: info %d", info);

  /* Rejected input writes nothing and says why. */
  double bad_mu[1] = {-1}, r3[3] = {7, 7, 7};
  info = fc3d_solve_dense(1, W, q, bad_mu, r3, u2, s, &res);
  CHECK(info == FC3D_ERR_INVALID_PROBLEM && r3[0] == 7, "negative mu: info %d", info);
  CHECK(strstr(fc3d_last_error_message(), "mu") != NULL, "message names mu");
  CHECK(fc3d_settings_new(4242) == NULL && fc3d_last_error_code() == FC3D_ERR_UNSUPPORTED_SOLVER,
        "unknown solver id");
  fc3d_settings_free(s);

  /* Internal solvers: PROX with NSGS inside, TFP and PFP with the projected gradient (567 as
     PFP's single internal solver, or 1200, Siconos' ConvexQP projected gradient, in PFP's
     tangent slot); NSGS refuses a non-local solver and keeps its own. */
  int parents[4] = {502, 503, 522, 522}, internals[4] = {500, 567, 567, 1200};
  for (int k = 0; k < 4; k++) {
    Fc3dSettings* t = fc3d_settings_new(parents[k]);
    CHECK(t != NULL && fc3d_settings_set_internal_solver(t, internals[k]) == 0, "%d/%d", parents[k], internals[k]);
    fc3d_settings_set_tolerance(t, 1e-10);
    double ri[3] = {0, 0, 0}, ui[3];
    info = fc3d_solve_dense(1, W, q, mu, ri, ui, t, &res);
    CHECK(info == 0 && fabs(ri[1] + 0.5) < 1e-8, "%d with internal %d: info %d", parents[k], internals[k], info);
    fc3d_settings_free(t);
  }
  Fc3dSettings* g = fc3d_settings_new(500);
  CHECK(fc3d_settings_set_internal_solver(g, 504) == FC3D_ERR_INVALID_OPTION, "NSGS with 504 refused");
  CHECK(fc3d_settings_set(g, "max_iter", 1e10) == FC3D_ERR_INVALID_OPTION, "max_iter out of range");
  double rg[3] = {0, 0, 0}, ug[3];
  CHECK(fc3d_solve_dense(1, W, q, mu, rg, ug, g, &res) == 0, "NSGS still usable");
  fc3d_settings_free(g);

  /* The same contact in the global form: a body of mass 2 (M = 2 I), H = I, q = M (-1, 2, 0),
     b = 0: r = (2, -1, 0), u = v = (0, 1.5, 0), M v = q + H r. 607 (Newton on (v, u, r)) and the
     default (NULL: 600, NSGS on the reduced problem). */
  int64_t ptr3[4] = {0, 1, 2, 3}, idx3[3] = {0, 1, 2};
  double m3[3] = {2, 2, 2}, h3[3] = {1, 1, 1}, qg[3] = {-2, 4, 0}, bg[3] = {0, 0, 0};
  Fc3dSettings* gs = fc3d_settings_new(607);
  CHECK(gs != NULL && fc3d_settings_set_tolerance(gs, 1e-10) == 0, "settings of 607");
  for (int k = 0; k < 2; k++) {
    double rv[3] = {0, 0, 0}, uv[3], vv[3];
    info = fc3d_solve_global_csr(3, 1, 3, ptr3, idx3, m3, 3, ptr3, idx3, h3, qg, bg, mu, rv, uv, vv,
                                 k == 0 ? gs : NULL, &res);
    CHECK(info == 0 && fabs(rv[0] - 2) < 1e-8 && fabs(rv[1] + 1) < 1e-8 && fabs(vv[1] - 1.5) < 1e-8,
          "global solve %d: info %d, r = (%g, %g, %g)", k, info, rv[0], rv[1], rv[2]);
    CHECK(fabs(2 * vv[1] - qg[1] - rv[1]) < 1e-12 && fabs(uv[1] - vv[1]) < 1e-12, "M v = q + H r");
  }
  CHECK(fc3d_solve_dense(1, W, q, mu, rg, ug, gs, &res) == FC3D_ERR_UNSUPPORTED_SOLVER,
        "a global id is refused by a local solve");
  fc3d_settings_free(gs);

  if (argc > 1) {
    Fc3dProblem* p = fc3d_problem_read(argv[1]);
    CHECK(p != NULL, "read %s", argv[1]);
    int64_t nc = fc3d_problem_contacts(p), nnz = fc3d_problem_nnz(p);
    CHECK(nc > 0 && nnz > 0, "sizes");
    int64_t* rp = malloc(sizeof(int64_t) * (3 * nc + 1));
    int64_t* ci = malloc(sizeof(int64_t) * nnz);
    double* v = malloc(sizeof(double) * nnz);
    double* pq = malloc(sizeof(double) * 3 * nc);
    double* pmu = malloc(sizeof(double) * nc);
    double* pr = calloc(3 * nc, sizeof(double));
    double* pu = calloc(3 * nc, sizeof(double));
    CHECK(fc3d_problem_get(p, rp, ci, v, pq, pmu) == 0, "get");
    int ids[2] = {500, 504};
    for (int k = 0; k < 2; k++) {
      Fc3dSettings* t = fc3d_settings_new(ids[k]);
      fc3d_settings_set_tolerance(t, 1e-8);
      fc3d_settings_set_max_iter(t, 10000);
      for (int i = 0; i < 3 * nc; i++) pr[i] = 0;
      info = fc3d_solve_csr(nc, nnz, rp, ci, v, pq, pmu, pr, pu, t, &res);
      printf("%s: solver %d, %lld contacts: info %d, %lld iterations, error %.3e, %.3f ms\n", argv[1], ids[k],
             (long long)nc, info, (long long)res.iterations, res.error, 1e3 * res.seconds);
      CHECK(info == 0 && res.error <= 1e-8, "solver %d on %s", ids[k], argv[1]);
      for (int i = 0; i < 3 * nc; i++) pr[i] = 0;
      info = fc3d_problem_solve(p, pr, pu, t, &res);
      CHECK(info == 0 && res.error <= 1e-8, "solver %d on the file's storage", ids[k]);
      fc3d_settings_free(t);
    }
    free(rp); free(ci); free(v); free(pq); free(pmu); free(pr); free(pu);
    fc3d_problem_free(p);
  }
  printf("native_host: all checks passed\n");
  return 0;
}

/* fc3d's global results scored by the installed Siconos 4.4 (issue 26): each library opened with
   dlopen (RTLD_LOCAL). For each global .dat file and each id fc3d runs, fc3d's gfc3d_driver
   solves the problem it read; then Siconos reads the same file itself and computes
   gfc3d_compute_error of fc3d's (reaction, globalVelocity) on its own copy of M and H, with
   norm_q = ||q||, as Siconos' solvers call it. That error must equal fc3d's dparam[1] (to a
   relative 1e-10: the libraries sum in different orders), the velocity Siconos recomputes must
   equal fc3d's u = H^T v + b, and wherever fc3d reports info 0 Siconos' error is at most the
   tolerance. fc3d's gfc3d_compute_error and gfc3d_compute_error_convex are compared with
   Siconos' on the same arrays as well (the convex one with the velocity Siconos' reads: 4.4's
   does not recompute it).
   Usage: global_side_by_side <libfc3d.so> <libsiconos_numerics.so> <file.dat>...
   Compiled against fc3d's compat headers for the struct layouts (identical to Siconos'). */
#include <dlfcn.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "GlobalFrictionContactProblem.h"
#include "SolverOptions.h"

typedef GlobalFrictionContactProblem* (*read_fn)(const char*);
typedef void (*free_fn)(GlobalFrictionContactProblem*);
typedef SolverOptions* (*create_fn)(int);
typedef void (*delete_fn)(SolverOptions*);
typedef int (*driver_fn)(GlobalFrictionContactProblem*, double*, double*, double*, SolverOptions*);
typedef int (*error_fn)(GlobalFrictionContactProblem*, double*, double*, double*, double, SolverOptions*,
                        double, double, double*);

static void* libs[2];
static const char* names[2] = {"fc3d", "Siconos"};
static int failures = 0;

static void* sym(int which, const char* name) {
  void* f = dlsym(libs[which], name);
  if (!f) {
    fprintf(stderr, "%s: %s not found\n", names[which], name);
    exit(2);
  }
  return f;
}

static int close_to(double a, double b, double rel) {
  return fabs(a - b) <= rel * fmax(1.0, fmax(fabs(a), fabs(b)));
}

static double norm(const double* x, int n) {
  double s = 0.0;
  for (int i = 0; i < n; i++) s += x[i] * x[i];
  return sqrt(s);
}

static void fail(const char* file, int id, const char* what, double ours, double theirs) {
  if (failures < 40) fprintf(stderr, "%s, id %d: %s: fc3d %.17g, Siconos %.17g\n", file, id, what, ours, theirs);
  failures++;
}

static void check_file(const char* file) {
  static const int ids[] = {600, 602, 603, 604, 605, 606, 607, 610, 611, 612, 613, 614, 615};
  read_fn read[2] = {(read_fn)sym(0, "globalFrictionContact_new_from_filename"),
                     (read_fn)sym(1, "globalFrictionContact_new_from_filename")};
  free_fn release[2] = {(free_fn)sym(0, "globalFrictionContact_free"), (free_fn)sym(1, "globalFrictionContact_free")};
  create_fn create[2] = {(create_fn)sym(0, "solver_options_create"), (create_fn)sym(1, "solver_options_create")};
  delete_fn destroy[2] = {(delete_fn)sym(0, "solver_options_delete"), (delete_fn)sym(1, "solver_options_delete")};
  driver_fn driver = (driver_fn)sym(0, "gfc3d_driver");
  error_fn error[2] = {(error_fn)sym(0, "gfc3d_compute_error"), (error_fn)sym(1, "gfc3d_compute_error")};
  error_fn convex[2] = {(error_fn)sym(0, "gfc3d_compute_error_convex"),
                        (error_fn)sym(1, "gfc3d_compute_error_convex")};
  for (size_t k = 0; k < sizeof ids / sizeof ids[0]; k++) {
    int id = ids[k];
    GlobalFrictionContactProblem* ours = read[0](file);
    if (!ours) {
      fprintf(stderr, "%s: fc3d cannot read it\n", file);
      failures++;
      return;
    }
    int n = ours->M->size0, m = 3 * ours->numberOfContacts;
    double* r = calloc(m, sizeof(double));
    double* u = calloc(m, sizeof(double));
    double* v = calloc(n, sizeof(double));
    double* u_theirs = calloc(m, sizeof(double));
    SolverOptions* options = create[0](id);
    double tolerance = 1e-5;
    options->dparam[0] = tolerance;
    options->iparam[0] = 10000;
    int info = driver(ours, r, u, v, options);
    double reported = options->dparam[1];
    if (info < 0) {
      fprintf(stderr, "%s, id %d: fc3d refused it (%d)\n", file, id, info);
      failures++;
    } else {
      /* Siconos scores the result on its own copy of the problem. */
      GlobalFrictionContactProblem* theirs = read[1](file);
      SolverOptions* scratch = create[1](id);
      double q_norm = norm(theirs->q, n), e_theirs = NAN, e_ours = NAN;
      double* u_ours = calloc(m, sizeof(double));
      error[1](theirs, r, u_theirs, v, tolerance, scratch, q_norm, 0.0, &e_theirs);
      error[0](ours, r, u_ours, v, tolerance, NULL, q_norm, 0.0, &e_ours);
      if (!close_to(reported, e_theirs, 1e-10)) fail(file, id, "dparam[1] vs Siconos' gfc3d_compute_error", reported, e_theirs);
      if (!close_to(e_ours, e_theirs, 1e-10)) fail(file, id, "gfc3d_compute_error", e_ours, e_theirs);
      if (info == 0 && !(e_theirs <= tolerance)) fail(file, id, "info 0 but Siconos' error above the tolerance", reported, e_theirs);
      for (int i = 0; i < m; i++) {
        if (!close_to(u[i], u_theirs[i], 1e-12)) fail(file, id, "velocity", u[i], u_theirs[i]);
        if (!close_to(u_ours[i], u_theirs[i], 1e-12)) fail(file, id, "recomputed velocity", u_ours[i], u_theirs[i]);
      }
      /* The convex error: Siconos 4.4's reads the velocity it is given (u = H^T v + b here). */
      double c_theirs = NAN, c_ours = NAN;
      convex[1](theirs, r, u_theirs, v, tolerance, scratch, q_norm, 0.0, &c_theirs);
      convex[0](ours, r, u_ours, v, tolerance, NULL, q_norm, 0.0, &c_ours);
      if (!close_to(c_ours, c_theirs, 1e-10)) fail(file, id, "gfc3d_compute_error_convex", c_ours, c_theirs);
      printf("%s id %d: info %d, iterations %d, fc3d dparam[1] %.6e, Siconos' error %.6e\n", file, id, info,
             options->iparam[1], reported, e_theirs);
      free(u_ours);
      destroy[1](scratch);
      release[1](theirs);
    }
    destroy[0](options);
    release[0](ours);
    free(r);
    free(u);
    free(v);
    free(u_theirs);
  }
}

int main(int argc, char** argv) {
  if (argc < 4) {
    fprintf(stderr, "usage: %s <libfc3d.so> <libsiconos_numerics.so> <file.dat>...\n", argv[0]);
    return 2;
  }
  for (int w = 0; w < 2; w++) {
    libs[w] = dlopen(argv[1 + w], RTLD_NOW | RTLD_LOCAL);
    if (!libs[w]) {
      fprintf(stderr, "dlopen %s: %s\n", argv[1 + w], dlerror());
      return 2;
    }
  }
  for (int k = 3; k < argc; k++) check_file(argv[k]);
  if (failures) {
    fprintf(stderr, "%d values differ\n", failures);
    return 1;
  }
  fprintf(stderr, "all values agree\n");
  return 0;
}

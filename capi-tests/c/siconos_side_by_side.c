/* The small Siconos functions fc3d reimplements, called side by side with the installed Siconos
   4.4 in one process (each library opened with dlopen, RTLD_LOCAL) on the same inputs: every
   output value, and every output slot a function leaves alone, must agree.
   Usage: siconos_side_by_side <path of libfc3d.so> <path or name of libsiconos_numerics.so>
   Compiled against fc3d's compat headers for the struct layouts (identical to Siconos'). */
#include <dlfcn.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "FrictionContactProblem.h"
#include "NumericsMatrix.h"
#include "SolverOptions.h"
#include "SparseBlockMatrix.h"

typedef void (*ac_fn)(double*, double*, double, double*, double*, double*, double*);
typedef void (*add_error_fn)(double*, double*, double, double*, double*);
typedef int (*trivial_fn)(FrictionContactProblem*, double*, double*, SolverOptions*);
typedef int (*error_velocity_fn)(FrictionContactProblem*, double*, double*, double, SolverOptions*, double*);
typedef int (*tresca_error_fn)(FrictionContactProblem*, double*, double*, double, SolverOptions*, double, double*);
typedef void (*tolerance_fn)(FrictionContactProblem*, SolverOptions*, SolverOptions*, double);
typedef void (*statistics_fn)(FrictionContactProblem*, double*, double*, double, int);
typedef void (*verbose_fn)(int);
typedef FrictionContactProblem* (*copy_fn)(FrictionContactProblem*);
typedef void (*rescale_fn)(FrictionContactProblem*, double, double);
typedef void (*free_problem_fn)(FrictionContactProblem*);
typedef NumericsMatrix* (*nm_new_fn)(void);
typedef NumericsMatrix* (*nm_create_fn)(int, int, int);
typedef NumericsMatrix* (*nm_create_from_data_fn)(int, int, int, void*);
typedef void (*nm_null_fn)(NumericsMatrix*);
typedef NumericsMatrix* (*nm_free_fn)(NumericsMatrix*);
typedef SparseBlockCoordinateMatrix* (*sbcm_new_fn)(unsigned, unsigned, unsigned, unsigned*, unsigned*, double*);
typedef SparseBlockStructuredMatrix* (*sbcm_to_sbm_fn)(SparseBlockCoordinateMatrix*);
typedef void (*sbcm_free_fn)(SparseBlockCoordinateMatrix*);
typedef void (*sbm_free_fn)(SparseBlockStructuredMatrix*);

static void* libs[2];
static const char* lib_names[2] = {"fc3d", "Siconos"};
static int failures = 0;

static void* sym(int which, const char* name) {
  void* f = dlsym(libs[which], name);
  if (!f) {
    fprintf(stderr, "%s: %s not found\n", lib_names[which], name);
    exit(2);
  }
  return f;
}

static unsigned long long rng = 88172645463325252ULL;
static double uniform(double a, double b) {
  rng ^= rng << 13;
  rng ^= rng >> 7;
  rng ^= rng << 17;
  return a + (b - a) * (double)(rng >> 11) / 9007199254740992.0;
}

/* Equal, or both NaN, or within a relative 1e-12 (the libraries may round differently). */
static int same(double a, double b) {
  if (isnan(a) || isnan(b)) return isnan(a) && isnan(b);
  return fabs(a - b) <= 1e-12 * fmax(1.0, fmax(fabs(a), fabs(b)));
}

static void compare(const char* what, int k, const double* ours, const double* theirs, int n) {
  for (int i = 0; i < n; i++)
    if (!same(ours[i], theirs[i])) {
      if (failures < 40)
        fprintf(stderr, "%s, case %d, value %d: fc3d %.17g, Siconos %.17g\n", what, k, i, ours[i], theirs[i]);
      failures++;
    }
}

#define SENTINEL 12345.0

/* `reaction_in_half_space`: R_N >= 0 only (for the functions that differ from Siconos' outside
   the half-space, none today). */
static void check_alart_curnier(const char* name, int two_rhos, int reaction_in_half_space) {
  ac_fn f[2] = {(ac_fn)sym(0, name), (ac_fn)sym(1, name)};
  for (int k = 0; k < 20000; k++) {
    double R[3], u[3], rho[3], mu = k % 7 == 0 ? 0.0 : uniform(0.05, 1.0);
    for (int i = 0; i < 3; i++) {
      R[i] = uniform(-1.0, 1.0);
      u[i] = uniform(-1.0, 1.0);
    }
    if (reaction_in_half_space) R[0] = fabs(R[0]);
    /* Some cases on the axis. */
    if (k % 11 == 0) R[1] = R[2] = 0.0;
    if (k % 13 == 0) u[1] = u[2] = 0.0;
    rho[0] = uniform(0.1, 3.0);
    rho[1] = uniform(0.1, 3.0);
    rho[2] = two_rhos ? uniform(0.1, 3.0) : rho[1];
    /* The boundaries: R_N - rho_N u_N = 0, and R_T - rho_T u_T = 0. */
    if (k % 17 == 0) {
      rho[0] = 1.0;
      u[0] = R[0];
    }
    if (k % 19 == 0) {
      rho[1] = rho[2] = 1.0;
      u[1] = R[1];
      u[2] = R[2];
    }
    /* The outputs of each library, [F | A | B], and which blocks are passed (all, or F alone). */
    for (int mode = 0; mode < 2; mode++) {
      double out[2][21];
      for (int w = 0; w < 2; w++) {
        for (int i = 0; i < 21; i++) out[w][i] = SENTINEL;
        double Rc[3], uc[3], rhoc[3];
        memcpy(Rc, R, sizeof R);
        memcpy(uc, u, sizeof u);
        memcpy(rhoc, rho, sizeof rho);
        f[w](Rc, uc, mu, rhoc, out[w], mode == 0 ? out[w] + 3 : NULL, mode == 0 ? out[w] + 12 : NULL);
      }
      compare(name, 2 * k + mode, out[0], out[1], 21);
    }
  }
}

static void check_unitary_errors(void) {
  add_error_fn coulomb[2] = {(add_error_fn)sym(0, "fc3d_unitary_compute_and_add_error"),
                             (add_error_fn)sym(1, "fc3d_unitary_compute_and_add_error")};
  add_error_fn tresca[2] = {(add_error_fn)sym(0, "fc3d_Tresca_unitary_compute_and_add_error"),
                            (add_error_fn)sym(1, "fc3d_Tresca_unitary_compute_and_add_error")};
  for (int k = 0; k < 20000; k++) {
    double r[3], u[3], mu = k % 7 == 0 ? 0.0 : uniform(0.05, 1.0);
    for (int i = 0; i < 3; i++) {
      r[i] = uniform(-1.0, 1.0);
      u[i] = uniform(-1.0, 1.0);
    }
    double out[2][4];
    for (int w = 0; w < 2; w++) {
      out[w][0] = 0.25; /* the running sum */
      coulomb[w](r, u, mu, &out[w][0], &out[w][1]);
    }
    compare("fc3d_unitary_compute_and_add_error", k, out[0], out[1], 4);
    /* Siconos' cylinder routine is the projection when z_N - w_N >= 0. */
    if (r[0] - u[0] >= 0.0) {
      for (int w = 0; w < 2; w++) {
        out[w][0] = 0.25;
        tresca[w](r, u, mu, &out[w][0], &out[w][1]);
      }
      compare("fc3d_Tresca_unitary_compute_and_add_error", k, out[0], out[1], 4);
    }
  }
}

/* A dense problem with nc contacts: W = B^T B + I, q and mu random. */
typedef struct {
  FrictionContactProblem p;
  NumericsMatrix M;
  double* W;
  double* q;
  double* mu;
} Dense;

static void dense_problem(Dense* d, int nc) {
  int n = 3 * nc;
  memset(d, 0, sizeof *d);
  d->W = calloc((size_t)n * n, sizeof(double));
  d->q = malloc(sizeof(double) * n);
  d->mu = malloc(sizeof(double) * nc);
  double* B = malloc(sizeof(double) * n * n);
  for (int i = 0; i < n * n; i++) B[i] = uniform(-1.0, 1.0);
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++) {
      double s = i == j ? 1.0 : 0.0;
      for (int k = 0; k < n; k++) s += B[k + n * i] * B[k + n * j];
      d->W[i + n * j] = s;
    }
  free(B);
  for (int i = 0; i < n; i++) d->q[i] = uniform(-1.0, 1.0);
  for (int c = 0; c < nc; c++) d->mu[c] = uniform(0.1, 0.9);
  d->M.storageType = NM_DENSE;
  d->M.size0 = d->M.size1 = n;
  d->M.matrix0 = d->W;
  d->M.destructible = &d->M;
  d->p.dimension = 3;
  d->p.numberOfContacts = nc;
  d->p.M = &d->M;
  d->p.q = d->q;
  d->p.mu = d->mu;
}

static void check_problem_functions(void) {
  trivial_fn trivial[2] = {(trivial_fn)sym(0, "fc3d_checkTrivialCase"), (trivial_fn)sym(1, "fc3d_checkTrivialCase")};
  error_velocity_fn ev[2] = {(error_velocity_fn)sym(0, "fc3d_compute_error_velocity"),
                             (error_velocity_fn)sym(1, "fc3d_compute_error_velocity")};
  tresca_error_fn te[2] = {(tresca_error_fn)sym(0, "fc3d_Tresca_compute_error"),
                           (tresca_error_fn)sym(1, "fc3d_Tresca_compute_error")};
  tolerance_fn tol[2] = {(tolerance_fn)sym(0, "fc3d_set_internalsolver_tolerance"),
                         (tolerance_fn)sym(1, "fc3d_set_internalsolver_tolerance")};
  for (int k = 0; k < 200; k++) {
    int nc = 1 + k % 5, n = 3 * nc;
    Dense d;
    dense_problem(&d, nc);
    /* Take-off: every q_N >= 0 (half the cases), or not. */
    if (k % 2 == 0)
      for (int c = 0; c < nc; c++) d.q[3 * c] = fabs(d.q[3 * c]);
    double out[2][1 + 2 * 15];
    for (int w = 0; w < 2; w++) {
      for (int i = 0; i < 1 + 2 * n; i++) out[w][i] = SENTINEL;
      out[w][0] = trivial[w](&d.p, out[w] + 1, out[w] + 1 + n, NULL);
    }
    compare("fc3d_checkTrivialCase", k, out[0], out[1], 1 + 2 * n);

    /* The error on velocities: w is the argument, z is overwritten with q + M w. */
    double z[2][15], wv[15], e[2], info[2];
    for (int i = 0; i < n; i++) wv[i] = uniform(-1.0, 1.0);
    for (int w = 0; w < 2; w++) {
      double wc[15];
      memcpy(wc, wv, sizeof wc);
      for (int i = 0; i < n; i++) z[w][i] = SENTINEL;
      info[w] = ev[w](&d.p, z[w], wc, 1e-3, NULL, &e[w]);
    }
    compare("fc3d_compute_error_velocity z", k, z[0], z[1], n);
    compare("fc3d_compute_error_velocity error", k, e, e + 1, 1);
    compare("fc3d_compute_error_velocity info", k, info, info + 1, 1);

    /* The Tresca error: radii in options->dWork. */
    SolverOptions o;
    memset(&o, 0, sizeof o);
    double radii[5], zr[15], wt[2][15];
    for (int c = 0; c < nc; c++) radii[c] = uniform(0.0, 0.5);
    for (int i = 0; i < n; i++) zr[i] = uniform(0.0, 1.0);
    o.dWork = radii;
    o.dWorkSize = (size_t)nc;
    for (int w = 0; w < 2; w++) {
      for (int i = 0; i < n; i++) wt[w][i] = SENTINEL;
      double zc[15];
      memcpy(zc, zr, sizeof zc);
      info[w] = te[w](&d.p, zc, wt[w], 1e-2, &o, k % 3 == 0 ? 0.0 : 2.5, &e[w]);
    }
    /* Siconos' cylinder routine is the projection when z_N - w_N >= 0: compare those cases. */
    int projection = 1;
    for (int c = 0; c < nc; c++)
      if (zr[3 * c] - wt[1][3 * c] < 0.0) projection = 0;
    compare("fc3d_Tresca_compute_error w", k, wt[0], wt[1], n);
    if (projection) {
      compare("fc3d_Tresca_compute_error error", k, e, e + 1, 1);
      compare("fc3d_Tresca_compute_error info", k, info, info + 1, 1);
    }

    /* The internal solver's tolerance, for each strategy. */
    int ip[20] = {0};
    double dp[20] = {0}, inner_d[2][20];
    int inner_i[2][20];
    SolverOptions outer, inner[2];
    memset(&outer, 0, sizeof outer);
    outer.iSize = outer.dSize = 20;
    outer.iparam = ip;
    outer.dparam = dp;
    ip[2] = k % 3; /* adaptive, given value, adaptive per contact */
    dp[0] = uniform(1e-10, 1e-4);
    dp[2] = uniform(1.0, 20.0);
    double err = uniform(1e-8, 1.0);
    for (int w = 0; w < 2; w++) {
      memset(&inner[w], 0, sizeof inner[w]);
      for (int i = 0; i < 20; i++) {
        inner_d[w][i] = SENTINEL;
        inner_i[w][i] = 7;
      }
      inner[w].iSize = inner[w].dSize = 20;
      inner[w].iparam = inner_i[w];
      inner[w].dparam = inner_d[w];
      tol[w](&d.p, &outer, &inner[w], err);
    }
    compare("fc3d_set_internalsolver_tolerance", k, inner_d[0], inner_d[1], 20);
    free(d.W);
    free(d.q);
    free(d.mu);
  }
}

/* frictionContactProblem_compute_statistics prints one line per call to stdout: each library's
   line for the same input must be the same (the Rust test checks that every line printed comes
   in pairs). */
static void check_statistics(void) {
  statistics_fn st[2] = {(statistics_fn)sym(0, "frictionContactProblem_compute_statistics"),
                         (statistics_fn)sym(1, "frictionContactProblem_compute_statistics")};
  verbose_fn set_verbose[2] = {(verbose_fn)sym(0, "numerics_set_verbose"), (verbose_fn)sym(1, "numerics_set_verbose")};
  for (int w = 0; w < 2; w++) set_verbose[w](1);
  for (int k = 0; k < 50; k++) {
    Dense d;
    int nc = 1 + k % 9;
    dense_problem(&d, nc);
    double r[27], u[27];
    for (int i = 0; i < 3 * nc; i++) {
      r[i] = (k % 3 == 0) ? uniform(-1e-6, 1e-6) : uniform(-1.0, 1.0);
      u[i] = uniform(-1.0, 1.0);
    }
    for (int w = 0; w < 2; w++) {
      st[w](&d.p, r, u, 1e-7, 1);
      fflush(stdout);
    }
    /* do_print above the verbosity: nothing printed. */
    for (int w = 0; w < 2; w++) st[w](&d.p, r, u, 1e-7, 2);
    free(d.W);
    free(d.q);
    free(d.mu);
  }
  for (int w = 0; w < 2; w++) set_verbose[w](0);
}

/* A 2x2-block sparse-block problem (blocks (0,0), (0,1), (1,1)), every array malloc'd. */
static FrictionContactProblem* sbm_problem(void) {
  SparseBlockStructuredMatrix* s = calloc(1, sizeof *s);
  s->nbblocks = 3;
  s->blocknumber0 = s->blocknumber1 = 2;
  s->blocksize0 = malloc(2 * sizeof(unsigned));
  s->blocksize1 = malloc(2 * sizeof(unsigned));
  s->blocksize0[0] = s->blocksize1[0] = 3;
  s->blocksize0[1] = s->blocksize1[1] = 6;
  s->filled1 = 3;
  s->filled2 = 3;
  s->index1_data = malloc(3 * sizeof(size_t));
  s->index1_data[0] = 0;
  s->index1_data[1] = 2;
  s->index1_data[2] = 3;
  s->index2_data = malloc(3 * sizeof(size_t));
  s->index2_data[0] = 0;
  s->index2_data[1] = 1;
  s->index2_data[2] = 1;
  s->block = malloc(3 * sizeof(double*));
  for (int k = 0; k < 3; k++) {
    s->block[k] = malloc(9 * sizeof(double));
    for (int i = 0; i < 9; i++) s->block[k][i] = (i % 4 == 0 ? 3.0 : 0.0) + uniform(-0.2, 0.2);
  }
  NumericsMatrix* M = calloc(1, sizeof *M);
  M->storageType = NM_SPARSE_BLOCK;
  M->size0 = M->size1 = 6;
  M->matrix1 = s;
  M->destructible = M;
  FrictionContactProblem* p = calloc(1, sizeof *p);
  p->dimension = 3;
  p->numberOfContacts = 2;
  p->M = M;
  p->q = malloc(6 * sizeof(double));
  p->mu = malloc(2 * sizeof(double));
  for (int i = 0; i < 6; i++) p->q[i] = uniform(-1.0, 1.0);
  p->mu[0] = 0.3;
  p->mu[1] = 0.7;
  return p;
}

/* The values of a problem: q, mu, then M's (dense values, or every block in order). */
static int problem_values(FrictionContactProblem* p, double* out) {
  int k = 0, n = 3 * p->numberOfContacts;
  for (int i = 0; i < n; i++) out[k++] = p->q[i];
  for (int c = 0; c < p->numberOfContacts; c++) out[k++] = p->mu[c];
  out[k++] = p->M->storageType;
  if (p->M->storageType == NM_DENSE) {
    for (int i = 0; i < n * n; i++) out[k++] = p->M->matrix0[i];
  } else {
    SparseBlockStructuredMatrix* s = p->M->matrix1;
    out[k++] = s->nbblocks;
    out[k++] = s->filled1;
    out[k++] = s->filled2;
    for (size_t i = 0; i < s->filled1; i++) out[k++] = (double)s->index1_data[i];
    for (size_t i = 0; i < s->filled2; i++) out[k++] = (double)s->index2_data[i];
    for (unsigned i = 0; i < s->blocknumber0; i++) out[k++] = s->blocksize0[i];
    for (unsigned i = 0; i < s->blocknumber1; i++) out[k++] = s->blocksize1[i];
    for (unsigned b = 0; b < s->nbblocks; b++)
      for (int i = 0; i < 9; i++) out[k++] = s->block[b][i];
  }
  return k;
}

/* frictionContact_copy and frictionContact_rescaling: the same values and structure. */
static void check_copy_and_rescaling(void) {
  copy_fn cp[2] = {(copy_fn)sym(0, "frictionContact_copy"), (copy_fn)sym(1, "frictionContact_copy")};
  rescale_fn rs[2] = {(rescale_fn)sym(0, "frictionContact_rescaling"), (rescale_fn)sym(1, "frictionContact_rescaling")};
  free_problem_fn fr[2] = {(free_problem_fn)sym(0, "frictionContactProblem_free"),
                           (free_problem_fn)sym(1, "frictionContactProblem_free")};
  static double v[2][400];
  for (int k = 0; k < 20; k++) {
    FrictionContactProblem* source;
    Dense d;
    if (k % 2 == 0) {
      dense_problem(&d, 1 + k % 4);
      source = &d.p;
    } else {
      source = sbm_problem();
    }
    int len[2];
    for (int w = 0; w < 2; w++) {
      FrictionContactProblem* c = cp[w](source);
      if (!c) {
        fprintf(stderr, "%s: frictionContact_copy returned NULL\n", lib_names[w]);
        failures++;
        return;
      }
      rs[w](c, 1.5, 0.75);
      len[w] = problem_values(c, v[w]);
      fr[w](c);
    }
    if (len[0] != len[1]) {
      fprintf(stderr, "copy and rescaling, case %d: %d values, Siconos %d\n", k, len[0], len[1]);
      failures++;
    } else {
      compare("frictionContact_copy + frictionContact_rescaling", k, v[0], v[1], len[0]);
    }
    if (k % 2 == 0) {
      free(d.W);
      free(d.q);
      free(d.mu);
    } else {
      fr[1](source);
    }
  }
}

/* What a host can see of a matrix the library made: storage, sizes, versions, which storage
   pointers are set, whether it is its own destructible matrix. */
static int matrix_state(NumericsMatrix* M, double* out) {
  int k = 0;
  out[k++] = M->storageType;
  out[k++] = M->size0;
  out[k++] = M->size1;
  out[k++] = (double)M->version.number;
  out[k++] = M->destructible == M;
  out[k++] = M->matrix0 != NULL;
  out[k++] = M->matrix1 != NULL;
  out[k++] = M->matrix2 != NULL;
  out[k++] = M->internalData != NULL;
  if (M->matrix1) {
    out[k++] = (double)M->matrix1->version.number;
    out[k++] = M->matrix1->nbblocks;
    out[k++] = M->matrix1->filled1;
  }
  if (M->matrix2) {
    out[k++] = M->matrix2->origin;
    /* Slot 0 (NSM_UNKNOWN) is left uninitialised by Siconos' NSM_new. */
    for (int v = 1; v < 5; v++) out[k++] = (double)M->matrix2->versions[v].number;
    out[k++] = M->matrix2->triplet != NULL;
    out[k++] = M->matrix2->csc != NULL;
  }
  if (M->storageType == NM_DENSE && M->matrix0)
    for (int i = 0; i < M->size0 * M->size1; i++) out[k++] = M->matrix0[i];
  return k;
}

/* NM_new, NM_null, NM_create, NM_create_from_data: the same state (Siconos' NM_null state,
   versions counted alike, destructible). */
static void check_matrix_creation(void) {
  nm_new_fn nw[2] = {(nm_new_fn)sym(0, "NM_new"), (nm_new_fn)sym(1, "NM_new")};
  nm_create_fn cr[2] = {(nm_create_fn)sym(0, "NM_create"), (nm_create_fn)sym(1, "NM_create")};
  nm_create_from_data_fn cd[2] = {(nm_create_from_data_fn)sym(0, "NM_create_from_data"),
                                  (nm_create_from_data_fn)sym(1, "NM_create_from_data")};
  nm_null_fn nl[2] = {(nm_null_fn)sym(0, "NM_null"), (nm_null_fn)sym(1, "NM_null")};
  nm_free_fn fr[2] = {(nm_free_fn)sym(0, "NM_free"), (nm_free_fn)sym(1, "NM_free")};
  static double st[2][200];
  int len[2];
  for (int c = 0; c < 7; c++) {
    for (int w = 0; w < 2; w++) {
      NumericsMatrix* M = NULL;
      NumericsMatrix on_stack;
      switch (c) {
        case 0: M = nw[w](); break;
        case 1: M = cr[w](NM_DENSE, 3, 4); break;
        case 2: M = cr[w](NM_SPARSE_BLOCK, 6, 6); break;
        case 3: M = cr[w](NM_SPARSE, 6, 6); break;
        case 4: {
          double* data = malloc(6 * sizeof(double));
          for (int i = 0; i < 6; i++) data[i] = i + 0.5;
          M = cd[w](NM_DENSE, 2, 3, data);
          break;
        }
        case 5: {
          SparseBlockStructuredMatrix* s = calloc(1, sizeof *s);
          s->version.number = 5;
          M = cd[w](NM_SPARSE_BLOCK, 0, 0, s);
          break;
        }
        case 6:
          memset(&on_stack, 0x5a, sizeof on_stack);
          nl[w](&on_stack);
          len[w] = matrix_state(&on_stack, st[w]);
          continue;
      }
      len[w] = matrix_state(M, st[w]);
      fr[w](M);
    }
    if (len[0] != len[1]) {
      fprintf(stderr, "matrix creation %d: %d values, Siconos %d\n", c, len[0], len[1]);
      failures++;
    } else {
      compare("matrix creation", c, st[0], st[1], len[0]);
    }
  }
}

/* SBCM_new_3x3 and SBCM_to_SBM: the same coordinate and sparse-block structures, pointing at the
   same caller's values, sharing what Siconos shares. (At least as many blocks as block rows and
   columns: Siconos sizes blocksize0/1 by the block count and SBCM_to_SBM reads blocknumber0 of
   them.) */
static void check_coordinate_matrices(void) {
  sbcm_new_fn nw[2] = {(sbcm_new_fn)sym(0, "SBCM_new_3x3"), (sbcm_new_fn)sym(1, "SBCM_new_3x3")};
  sbcm_to_sbm_fn to[2] = {(sbcm_to_sbm_fn)sym(0, "SBCM_to_SBM"), (sbcm_to_sbm_fn)sym(1, "SBCM_to_SBM")};
  sbcm_free_fn fc[2] = {(sbcm_free_fn)sym(0, "SBCM_free_3x3"), (sbcm_free_fn)sym(1, "SBCM_free_3x3")};
  sbm_free_fn fs[2] = {(sbm_free_fn)sym(0, "SBM_free_from_SBCM"), (sbm_free_fn)sym(1, "SBM_free_from_SBCM")};
  static double out[2][600];
  for (int k = 0; k < 200; k++) {
    unsigned m = 1 + k % 5, n = 1 + (k / 5) % 5, nb = (m > n ? m : n) + k % 7;
    unsigned row[12], col[12];
    double W[9 * 12];
    for (unsigned b = 0; b < nb; b++) {
      row[b] = 1 + (unsigned)uniform(0.0, (double)m - 1e-9);
      col[b] = 1 + (unsigned)uniform(0.0, (double)n - 1e-9);
    }
    for (unsigned i = 0; i < 9 * nb; i++) W[i] = uniform(-1.0, 1.0);
    int len[2];
    for (int w = 0; w < 2; w++) {
      int j = 0;
      SparseBlockCoordinateMatrix* c = nw[w](m, n, nb, row, col, W);
      SparseBlockStructuredMatrix* s = to[w](c);
      out[w][j++] = c->nbblocks;
      out[w][j++] = c->blocknumber0;
      out[w][j++] = c->blocknumber1;
      out[w][j++] = c->row != row && c->column != col;
      for (unsigned b = 0; b < nb; b++) {
        out[w][j++] = c->row[b];
        out[w][j++] = c->column[b];
        out[w][j++] = c->block[b] - W;
        out[w][j++] = c->blocksize0[b];
        out[w][j++] = c->blocksize1[b];
      }
      out[w][j++] = s->nbblocks;
      out[w][j++] = s->blocknumber0;
      out[w][j++] = s->blocknumber1;
      out[w][j++] = (double)s->filled1;
      out[w][j++] = (double)s->filled2;
      out[w][j++] = s->blocksize0 == c->blocksize0 && s->blocksize1 == c->blocksize1;
      out[w][j++] = s->diagonal_blocks == NULL;
      for (unsigned i = 0; i <= m; i++) out[w][j++] = (double)s->index1_data[i];
      for (unsigned b = 0; b < nb; b++) {
        out[w][j++] = (double)s->index2_data[b];
        out[w][j++] = s->block[b] - W;
      }
      len[w] = j;
      fs[w](s);
      fc[w](c);
      free(c);
    }
    if (len[0] != len[1]) {
      fprintf(stderr, "coordinate matrices %d: %d values, Siconos %d\n", k, len[0], len[1]);
      failures++;
    } else {
      compare("SBCM_new_3x3 + SBCM_to_SBM", k, out[0], out[1], len[0]);
    }
  }
}

int main(int argc, char** argv) {
  if (argc != 3) {
    fprintf(stderr, "usage: %s <libfc3d.so> <libsiconos_numerics.so>\n", argv[0]);
    return 2;
  }
  for (int w = 0; w < 2; w++) {
    libs[w] = dlopen(argv[1 + w], RTLD_NOW | RTLD_LOCAL);
    if (!libs[w]) {
      fprintf(stderr, "dlopen %s: %s\n", argv[1 + w], dlerror());
      return 2;
    }
  }
  check_alart_curnier("computeAlartCurnierSTD", 0, 0);
  check_alart_curnier("computeAlartCurnierSTDOld", 0, 0);
  check_alart_curnier("computeAlartCurnierJeanMoreau", 0, 0);
  check_alart_curnier("fc3d_AlartCurnierFunctionGenerated", 1, 0);
  check_alart_curnier("fc3d_AlartCurnierJeanMoreauFunctionGenerated", 1, 0);
  check_unitary_errors();
  check_problem_functions();
  check_statistics();
  check_copy_and_rescaling();
  check_matrix_creation();
  check_coordinate_matrices();
  if (failures) {
    fprintf(stderr, "%d values differ\n", failures);
    return 1;
  }
  fprintf(stderr, "all values agree\n");
  return 0;
}

/* A host of fc3d's distributed solve (fc3d_mpi.h, libfc3d_mpi) that splits a problem over its
 * ranks itself: every rank reads the same Siconos .dat file, keeps the block rows of its share
 * of the contacts under its own global numbering (ids 1000 + 7c, not contiguous, listed in any
 * order) and calls fc3d_mpi_solve_blocks. It checks, and exits non-zero otherwise, that
 *   - every rank gets the same info, sweeps and error;
 *   - r and u gathered from the ranks satisfy u = W r + q and the reported error is the error
 *     this program measures itself (natural map, De Saxce's cone complementarity);
 *   - a second partition (contiguous ranges, listed backwards) gives the same bits;
 *   - a solver kept for time stepping, made from the communicator's Fortran handle, gives the
 *     same bits twice with one set-up (its statistics are printed).
 * Built from outside the source tree by the test suite:
 *
 *   mpicc $(pkg-config --cflags fc3d-mpi) mpi_host.c $(pkg-config --libs fc3d-mpi) -lm -o mpi_host
 *   mpirun -np 3 ./mpi_host problem.dat [tolerance] [max sweeps]
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <fc3d_mpi.h>

static int rank, size;

#define CHECK(cond, ...)                                                  \
  do {                                                                    \
    if (!(cond)) {                                                        \
      fprintf(stderr, "mpi_host rank %d: ", rank);                        \
      fprintf(stderr, __VA_ARGS__);                                       \
      fprintf(stderr, " (%s)\n", fc3d_last_error_message());              \
      MPI_Abort(MPI_COMM_WORLD, 1);                                       \
    }                                                                     \
  } while (0)

/* The whole problem in 3x3 block rows (column-major blocks), built from compressed rows. */
typedef struct {
  int64_t nc, *row_ptr, *cols;
  double *blocks, *q, *mu;
} Blocks;

static Blocks read_blocks(const char *path) {
  Fc3dProblem *p = fc3d_problem_read(path);
  CHECK(p != NULL, "cannot read %s", path);
  int64_t nc = fc3d_problem_contacts(p), nnz = fc3d_problem_nnz(p);
  int64_t *rp = malloc(sizeof(int64_t) * (3 * nc + 1)), *ci = malloc(sizeof(int64_t) * nnz);
  double *v = malloc(sizeof(double) * nnz);
  Blocks b = {nc, malloc(sizeof(int64_t) * (nc + 1)), malloc(sizeof(int64_t) * nnz), NULL,
              malloc(sizeof(double) * 3 * nc), malloc(sizeof(double) * nc)};
  CHECK(fc3d_problem_get(p, rp, ci, v, b.q, b.mu) == 0, "fc3d_problem_get");
  fc3d_problem_free(p);
  b.blocks = calloc(9 * (size_t)nnz, sizeof(double)); /* at most one block per entry */
  int64_t *slot = malloc(sizeof(int64_t) * nc);        /* block of column d in the current row */
  for (int64_t d = 0; d < nc; ++d) slot[d] = -1;
  int64_t n_blocks = 0;
  b.row_ptr[0] = 0;
  for (int64_t c = 0; c < nc; ++c) {
    for (int i = 0; i < 3; ++i)
      for (int64_t k = rp[3 * c + i]; k < rp[3 * c + i + 1]; ++k) {
        int64_t d = ci[k] / 3;
        if (slot[d] < 0) {
          slot[d] = n_blocks;
          b.cols[n_blocks++] = d;
        }
        b.blocks[9 * slot[d] + 3 * (ci[k] % 3) + i] += v[k];
      }
    for (int64_t k = b.row_ptr[c]; k < n_blocks; ++k) slot[b.cols[k]] = -1;
    b.row_ptr[c + 1] = n_blocks;
  }
  free(slot);
  free(rp);
  free(ci);
  free(v);
  return b;
}

static int64_t global_id(int64_t c) { return 1000 + 7 * c; }

/* One rank's arguments: the rows of `contacts` (indices into the whole problem). */
typedef struct {
  int64_t n, n_blocks, *ids, *row_ptr, *cols;
  double *blocks, *q, *mu, *r, *u;
} Rows;

static Rows rows_of(const Blocks *w, const int64_t *contacts, int64_t n) {
  int64_t n_blocks = 0;
  for (int64_t k = 0; k < n; ++k) n_blocks += w->row_ptr[contacts[k] + 1] - w->row_ptr[contacts[k]];
  Rows r = {n, n_blocks, malloc(sizeof(int64_t) * (n + 1)), malloc(sizeof(int64_t) * (n + 1)),
            malloc(sizeof(int64_t) * (n_blocks + 1)), malloc(sizeof(double) * 9 * (n_blocks + 1)),
            malloc(sizeof(double) * (3 * n + 1)), malloc(sizeof(double) * (n + 1)),
            calloc(3 * n + 1, sizeof(double)), calloc(3 * n + 1, sizeof(double))};
  int64_t at = 0;
  r.row_ptr[0] = 0;
  for (int64_t k = 0; k < n; ++k) {
    int64_t c = contacts[k];
    r.ids[k] = global_id(c);
    for (int64_t b = w->row_ptr[c]; b < w->row_ptr[c + 1]; ++b, ++at) {
      r.cols[at] = global_id(w->cols[b]);
      memcpy(r.blocks + 9 * at, w->blocks + 9 * b, 9 * sizeof(double));
    }
    r.row_ptr[k + 1] = at;
    memcpy(r.q + 3 * k, w->q + 3 * c, 3 * sizeof(double));
    r.mu[k] = w->mu[c];
  }
  return r;
}

static void rows_free(Rows *r) {
  free(r->ids), free(r->row_ptr), free(r->cols), free(r->blocks);
  free(r->q), free(r->mu), free(r->r), free(r->u);
}

/* r and u of every contact, from every rank's part (each contact is written by one rank). */
static void gather(const Rows *rows, const int64_t *contacts, int64_t nc, double *r, double *u) {
  memset(r, 0, sizeof(double) * 3 * nc);
  memset(u, 0, sizeof(double) * 3 * nc);
  for (int64_t k = 0; k < rows->n; ++k)
    for (int i = 0; i < 3; ++i) {
      r[3 * contacts[k] + i] = rows->r[3 * k + i];
      u[3 * contacts[k] + i] = rows->u[3 * k + i];
    }
  MPI_Allreduce(MPI_IN_PLACE, r, (int)(3 * nc), MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, u, (int)(3 * nc), MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
}

/* This program's own error of (r, u): sqrt(sum ||r - P_K(r - (u + mu |u_T| e_n))||^2) over
 * max(||q||, ||r||, ||u||), and the largest |u - (W r + q)| relative to max |u|. */
static double measure(const Blocks *w, const double *r, const double *u, double *velocity_gap) {
  double res = 0, nq = 0, nr = 0, nu = 0, gap = 0, umax = 0;
  for (int64_t c = 0; c < w->nc; ++c) {
    double wr[3] = {w->q[3 * c], w->q[3 * c + 1], w->q[3 * c + 2]};
    for (int64_t b = w->row_ptr[c]; b < w->row_ptr[c + 1]; ++b)
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) wr[i] += w->blocks[9 * b + 3 * j + i] * r[3 * w->cols[b] + j];
    const double *rc = r + 3 * c, *uc = u + 3 * c, mu = w->mu[c];
    for (int i = 0; i < 3; ++i) {
      gap = fmax(gap, fabs(wr[i] - uc[i]));
      umax = fmax(umax, fabs(uc[i]));
      nq += w->q[3 * c + i] * w->q[3 * c + i], nr += rc[i] * rc[i], nu += uc[i] * uc[i];
    }
    double x[3] = {rc[0] - uc[0] - mu * hypot(uc[1], uc[2]), rc[1] - uc[1], rc[2] - uc[2]};
    double t = hypot(x[1], x[2]), p[3];
    if (t <= mu * x[0]) {
      p[0] = x[0], p[1] = x[1], p[2] = x[2];
    } else if (mu * t <= -x[0]) {
      p[0] = p[1] = p[2] = 0;
    } else {
      double a = (x[0] + mu * t) / (1 + mu * mu);
      p[0] = a, p[1] = mu * a * x[1] / t, p[2] = mu * a * x[2] / t;
    }
    for (int i = 0; i < 3; ++i) res += (rc[i] - p[i]) * (rc[i] - p[i]);
  }
  *velocity_gap = umax > 0 ? gap / umax : gap;
  double scale = fmax(sqrt(nq), fmax(sqrt(nr), sqrt(nu)));
  return scale > 0 ? sqrt(res) / scale : sqrt(res);
}

static int64_t bits(double x) {
  int64_t b;
  memcpy(&b, &x, sizeof b);
  return b;
}

/* Every rank reported the same result. */
static void check_same_everywhere(const Fc3dResult *res, int code) {
  int64_t v[4] = {code, res->info, res->iterations, bits(res->error)}, lo[4], hi[4];
  MPI_Allreduce(v, lo, 4, MPI_INT64_T, MPI_MIN, MPI_COMM_WORLD);
  MPI_Allreduce(v, hi, 4, MPI_INT64_T, MPI_MAX, MPI_COMM_WORLD);
  CHECK(memcmp(lo, hi, sizeof lo) == 0, "the ranks report different results");
}

int main(int argc, char **argv) {
  MPI_Init(&argc, &argv);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  CHECK(argc >= 2, "usage: mpirun -np N mpi_host problem.dat [tolerance] [max sweeps]");
  double tolerance = argc > 2 ? atof(argv[2]) : 1e-8;
  int64_t max_sweeps = argc > 3 ? atoll(argv[3]) : 1000;
  Blocks w = read_blocks(argv[1]);
  int64_t nc = w.nc;

  Fc3dSettings *s = fc3d_settings_new(500);
  CHECK(s != NULL, "settings");
  CHECK(fc3d_settings_set_tolerance(s, tolerance) == 0, "tolerance");
  CHECK(fc3d_settings_set_max_iter(s, max_sweeps) == 0, "max_iter");

  /* Partition 1: round-robin. Partition 2: contiguous ranges, each listed backwards. */
  int64_t *mine = malloc(sizeof(int64_t) * (nc + 1)), n = 0;
  for (int64_t c = rank; c < nc; c += size) mine[n++] = c;
  Rows rows = rows_of(&w, mine, n);
  Fc3dResult res;
  int code = fc3d_mpi_solve_blocks(MPI_COMM_WORLD, rows.n, rows.ids, rows.n_blocks, rows.row_ptr,
                                   rows.cols, rows.blocks, rows.q, rows.mu, rows.r, rows.u, s,
                                   &res);
  CHECK(code >= 0, "fc3d_mpi_solve_blocks returned %d", code);
  check_same_everywhere(&res, code);
  double *r = malloc(sizeof(double) * 3 * nc), *u = malloc(sizeof(double) * 3 * nc);
  gather(&rows, mine, nc, r, u);
  double gap, error = measure(&w, r, u, &gap);
  CHECK(gap <= 1e-12, "u is not W r + q (relative gap %g)", gap);
  CHECK(fabs(error - res.error) <= 1e-9 * error + 1e-15, "reported error %.17g, measured %.17g",
        res.error, error);
  CHECK(res.info != 0 || error <= tolerance, "converged with error %g > %g", error, tolerance);

  int64_t *ranges = malloc(sizeof(int64_t) * (nc + 1)), m = 0;
  for (int64_t c = (rank + 1) * nc / size - 1; c >= rank * nc / size; --c) ranges[m++] = c;
  Rows other = rows_of(&w, ranges, m);
  Fc3dResult res2;
  /* The solver kept across time steps, from the Fortran handle of the communicator. */
  Fc3dMpiSolver *solver = fc3d_mpi_solver_new_f(MPI_Comm_c2f(MPI_COMM_WORLD), FC3D_MPI_REPRODUCIBLE);
  CHECK(solver != NULL, "fc3d_mpi_solver_new_f");
  double *r2 = malloc(sizeof(double) * 3 * nc), *u2 = malloc(sizeof(double) * 3 * nc);
  for (int step = 0; step < 2; ++step) {
    memset(other.r, 0, sizeof(double) * 3 * m);
    code = fc3d_mpi_solver_solve(solver, other.n, other.ids, other.n_blocks, other.row_ptr,
                                 other.cols, other.blocks, other.q, other.mu, other.r, other.u, s,
                                 &res2);
    CHECK(code >= 0, "fc3d_mpi_solver_solve returned %d", code);
    check_same_everywhere(&res2, code);
    CHECK(res2.info == res.info && res2.iterations == res.iterations &&
              bits(res2.error) == bits(res.error),
          "another partition, another result");
    gather(&other, ranges, nc, r2, u2);
    CHECK(memcmp(r, r2, sizeof(double) * 3 * nc) == 0 && memcmp(u, u2, sizeof(double) * 3 * nc) == 0,
          "another partition, other bits of r or u");
  }
  Fc3dMpiStats st;
  CHECK(fc3d_mpi_solver_stats(solver, &st) == 0, "stats");
  CHECK(st.setups == 1 && st.solves == 2 && st.total_contacts == nc, "one set-up for two solves");
  int64_t sent[2] = {st.messages_per_sweep, st.bytes_per_sweep};
  MPI_Allreduce(MPI_IN_PLACE, sent, 2, MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD);
  if (rank == 0)
    printf("%s on %d ranks: info %d, %lld sweeps, error %.3e (measured %.3e), %lld colours, "
           "%lld messages and %lld bytes per sweep; same bits for two partitions\n",
           argv[1], size, res.info, (long long)res.iterations, res.error, error,
           (long long)st.colours, (long long)sent[0], (long long)sent[1]);
  fc3d_mpi_solver_free(solver);
  fc3d_settings_free(s);
  rows_free(&rows);
  rows_free(&other);
  free(mine), free(ranges), free(r), free(u), free(r2), free(u2);
  free(w.row_ptr), free(w.cols), free(w.blocks), free(w.q), free(w.mu);
  MPI_Finalize();
  return 0;
}

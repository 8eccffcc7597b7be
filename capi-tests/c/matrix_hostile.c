/* The matrix helpers against a hostile host (issue 13, item 4), written as a C host would call
 * them: structs whose counts disagree with each other, NULL block pointers, index arrays
 * pointing anywhere, over heap arrays of exactly the lengths their counts declare. Run under
 * valgrind by scripts/test-all.sh (ownership_main.c): reading or writing one element past one of
 * these malloc'd arrays is a valgrind error, a leak too. Every call must give NaN, NULL or a
 * negative code with the struct unchanged, and valid input keeps Siconos' behaviour. */
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "SiconosNumerics.h"
#include "NumericsMatrix.h"
#include "SparseBlockMatrix.h"
#include "CSparseMatrix.h"
#include "FrictionContactProblem.h"
#include "SolverOptions.h"
#include "Friction_cst.h"
#include "NonSmoothDrivers.h"

#define FAIL(...)                                                           \
  do {                                                                      \
    fprintf(stderr, "%s:%d: ", __FILE__, __LINE__);                         \
    fprintf(stderr, __VA_ARGS__);                                           \
    fprintf(stderr, " [last fc3d error: %s]\n", fc3d_last_error_message()); \
    return 1;                                                               \
  } while (0)

#define CHECK(cond, ...)              \
  do {                                \
    if (!(cond)) FAIL(__VA_ARGS__);   \
  } while (0)

/* The code a call leaves (0: success). */
#define CODE_OF(call) (fc3d_clear_last_error(), (call), fc3d_last_error_code())

/* NM_get_value(M, i, j), and in *code the error it left (0: none). */
static double get(const NumericsMatrix* M, int i, int j, int* code) {
  fc3d_clear_last_error();
  double v = NM_get_value(M, i, j);
  *code = fc3d_last_error_code();
  return v;
}

static double* block_of(double scale) {
  double* b = calloc(9, sizeof(double));
  b[0] = b[4] = b[8] = scale;
  return b;
}

/* One 3x3 block row of `nb` blocks (all in block column 0), arrays malloc'd to the declared
 * lengths. */
static SparseBlockStructuredMatrix* sbm_one_row(unsigned nb) {
  SparseBlockStructuredMatrix* s = SBM_new();
  s->nbblocks = nb;
  s->blocknumber0 = s->blocknumber1 = 1;
  s->blocksize0 = malloc(sizeof(unsigned));
  s->blocksize1 = malloc(sizeof(unsigned));
  s->blocksize0[0] = s->blocksize1[0] = 3;
  s->filled1 = 2;
  s->filled2 = nb;
  s->index1_data = malloc(2 * sizeof(size_t));
  s->index1_data[0] = 0;
  s->index1_data[1] = nb;
  s->index2_data = calloc(nb, sizeof(size_t));
  s->block = calloc(nb, sizeof(double*));
  for (unsigned k = 0; k < nb; k++) s->block[k] = block_of(1.0 + k);
  return s;
}

static int check_get_value(void) {
  int code;
  NumericsMatrix* M = NM_new_SBM(3, 3, sbm_one_row(2));
  SparseBlockStructuredMatrix* s = M->matrix1;
  /* Two blocks at (0, 0): summed, as the solver and NM_copy_to_sparse see them. */
  CHECK(NM_get_value(M, 1, 1) == 3.0, "duplicate blocks not summed: %g", NM_get_value(M, 1, 1));
  /* A NULL block pointer where a block is declared. */
  double* b1 = s->block[1];
  s->block[1] = NULL;
  CHECK(isnan(NM_get_value(M, 0, 0)) && fc3d_last_error_code() == FC3D_ERR_NULL_POINTER, "NULL block");
  s->block[1] = b1;
  /* filled2 above nbblocks (the arrays hold nbblocks entries). */
  s->filled2 = 3;
  s->index1_data[1] = 3;
  CHECK(isnan(NM_get_value(M, 0, 0)) && fc3d_last_error_code() == FC3D_ERR_INVALID_STORAGE, "filled2 > nbblocks");
  s->filled2 = 2;
  /* The block row ends past filled2. */
  CHECK(isnan(NM_get_value(M, 0, 0)) && fc3d_last_error_code() == FC3D_ERR_INVALID_STORAGE, "row past filled2");
  s->index1_data[1] = 2;
  /* filled1 = 1: no end pointer for the block row. */
  s->filled1 = 1;
  CHECK(isnan(NM_get_value(M, 0, 0)) && fc3d_last_error_code() == FC3D_ERR_INVALID_STORAGE, "filled1 too small");
  s->filled1 = 2;
  /* A block column past blocknumber1. */
  s->index2_data[1] = 5;
  CHECK(isnan(NM_get_value(M, 0, 0)) && fc3d_last_error_code() == FC3D_ERR_INVALID_STORAGE, "column past the blocks");
  s->index2_data[1] = 0;
  /* A cumulative size of 0 (a block of no row). */
  s->blocksize0[0] = 0;
  CHECK(isnan(NM_get_value(M, 0, 0)) && fc3d_last_error_code() == FC3D_ERR_INVALID_STORAGE, "block size 0");
  s->blocksize0[0] = 3;
  /* Out of the matrix, at the int limits. */
  CHECK(isnan(NM_get_value(M, INT_MIN, 0)) && fc3d_last_error_code() == FC3D_ERR_INVALID_SIZE, "INT_MIN");
  CHECK(isnan(NM_get_value(M, 0, INT_MAX)) && fc3d_last_error_code() == FC3D_ERR_INVALID_SIZE, "INT_MAX");
  CHECK(get(M, 2, 2, &code) == 3.0 && code == 0, "valid again");
  NM_free(M);

  /* An empty sparse-block structure holds zeros. */
  NumericsMatrix* E = NM_create(NM_SPARSE_BLOCK, 6, 3);
  CHECK(get(E, 5, 2, &code) == 0.0 && code == 0, "empty SBM");
  NM_free(E);

  /* Dense: one entry is read, whatever the others hold. */
  NumericsMatrix* D = NM_create(NM_DENSE, 2, 2);
  D->matrix0[3] = NAN;
  D->matrix0[0] = 5.0;
  CHECK(get(D, 0, 0, &code) == 5.0 && code == 0, "dense entry");
  CHECK(isnan(get(D, 1, 1, &code)) && code == 0, "a stored NaN is a value");
  NM_free(D);
  return 0;
}

static int check_entry_and_triplets(void) {
  int code;
  /* A triplet of capacity 2 holding 2 entries: NM_entry grows it, keeping them. */
  NumericsMatrix* T = NM_create(NM_SPARSE, 4, 4);
  NM_triplet_alloc(T, 2);
  NM_entry(T, 0, 0, 1.0);
  NM_entry(T, 1, 1, 2.0);
  CHECK(CODE_OF(NM_entry(T, 3, 3, 4.0)) == 0, "growing a triplet");
  CSparseMatrix* t = T->matrix2->triplet;
  CHECK(t->nz == 3 && t->nzmax == 4 && NM_get_value(T, 0, 0) == 1.0 && NM_get_value(T, 1, 1) == 2.0 &&
            NM_get_value(T, 3, 3) == 4.0,
        "entries after growth");
  /* Counts a host may have broken: refused, nothing written (not even the arrays grown). */
  const CSparseMatrix saved = *t;
  const CS_INT cases[5][2] = {{-1, 4}, {5, 4}, {3, -4}, {1000, 1000}, {LLONG_MAX, LLONG_MAX}};
  const int want[5] = {FC3D_ERR_INVALID_STORAGE, FC3D_ERR_INVALID_STORAGE, FC3D_ERR_INVALID_SIZE,
                       FC3D_ERR_INVALID_STORAGE, FC3D_ERR_INVALID_SIZE};
  for (int k = 0; k < 5; k++) {
    t->nz = cases[k][0];
    t->nzmax = cases[k][1];
    const CSparseMatrix hostile = *t;
    CHECK(CODE_OF(NM_entry(T, 2, 2, 9.0)) == want[k], "nz %lld nzmax %lld", (long long)cases[k][0],
          (long long)cases[k][1]);
    CHECK(memcmp(&hostile, t, sizeof hostile) == 0, "nz %lld nzmax %lld: changed on failure",
          (long long)cases[k][0], (long long)cases[k][1]);
  }
  *t = saved;
  CHECK(get(T, 2, 2, &code) == 0.0 && code == 0 && get(T, 3, 3, &code) == 4.0, "entries written on failure");
  /* Out of range, at the int limits. */
  CHECK(CODE_OF(NM_entry(T, -1, 0, 1.0)) == FC3D_ERR_INVALID_SIZE, "i < 0");
  CHECK(CODE_OF(NM_entry(T, 0, INT_MAX, 1.0)) == FC3D_ERR_INVALID_SIZE, "j = INT_MAX");
  /* NM_triplet_alloc: all or nothing. */
  CSparseMatrix* before = T->matrix2->triplet;
  CHECK(CODE_OF(NM_triplet_alloc(T, -1)) == FC3D_ERR_INVALID_SIZE, "nzmax -1");
  CHECK(CODE_OF(NM_triplet_alloc(T, LLONG_MAX)) == FC3D_ERR_INVALID_SIZE, "nzmax LLONG_MAX");
  CHECK(T->matrix2->triplet == before && before->nz == 3, "NM_triplet_alloc changed A on failure");
  NM_free(T);

  /* A matrix in compressed columns: NM_entry inserts as Siconos does, the entries stay. */
  NumericsMatrix* C = NM_create(NM_SPARSE, 3, 3);
  CSparseMatrix* csc = calloc(1, sizeof(CSparseMatrix));
  csc->m = csc->n = 3;
  csc->nzmax = 1;
  csc->nz = -1;
  csc->p = calloc(4, sizeof(CS_INT));
  csc->p[1] = csc->p[2] = csc->p[3] = 1;
  csc->i = calloc(1, sizeof(CS_INT));
  csc->x = calloc(1, sizeof(double));
  csc->x[0] = 2.0;
  C->matrix2->csc = csc;
  C->matrix2->origin = NSM_CSC;
  CHECK(CODE_OF(NM_entry(C, 0, 1, 5.0)) == 0 && NM_get_value(C, 0, 0) == 2.0 && NM_get_value(C, 0, 1) == 5.0 &&
            C->matrix2->origin == NSM_CSC && C->matrix2->csc->nz == -1,
        "NM_entry on CSC storage");
  csc = C->matrix2->csc; /* rebuilt: 2 entries, (0,0) and (0,1) */
  CHECK(csc->nzmax == 2 && csc->p[3] == 2, "CSC after insertion");
  /* Column pointers past nzmax, a row index past the rows. */
  csc->p[3] = 3;
  CHECK(isnan(NM_get_value(C, 0, 2)) && fc3d_last_error_code() == FC3D_ERR_INVALID_STORAGE, "p[n] > nzmax");
  CHECK(CODE_OF(NM_entry(C, 1, 1, 5.0)) == FC3D_ERR_INVALID_STORAGE && csc == C->matrix2->csc, "NM_entry on a bad CSC");
  csc->p[3] = 2;
  csc->i[0] = 3;
  CHECK(isnan(NM_get_value(C, 0, 0)) && fc3d_last_error_code() == FC3D_ERR_INVALID_STORAGE, "row index 3");
  csc->i[0] = 0;
  NM_free(C);

  /* A 2^31 x 2^31 sparse matrix of one entry costs one entry. */
  NumericsMatrix* H = NM_create(NM_SPARSE, INT_MAX, INT_MAX);
  NM_entry(H, INT_MAX - 1, 7, 2.5);
  NumericsMatrix* Hc = NM_new();
  NM_copy_to_sparse(H, Hc, 0.0);
  CHECK(NM_get_value(H, INT_MAX - 1, 7) == 2.5 && NM_get_value(Hc, INT_MAX - 1, 7) == 2.5, "huge sparse matrix");
  NM_free(Hc);
  NM_free(H);

  /* Sizes no allocator gives. */
  CHECK(NM_create(NM_DENSE, INT_MAX, INT_MAX) == NULL && fc3d_last_error_code() == FC3D_ERR_INVALID_SIZE,
        "dense INT_MAX x INT_MAX");
  return 0;
}

static int check_coordinates_and_release(void) {
  unsigned row[2] = {1, 2}, col[2] = {1, 2};
  double blocks[18] = {0};
  for (int k = 0; k < 2; k++) blocks[9 * k] = blocks[9 * k + 4] = blocks[9 * k + 8] = 2.0; /* 2 I */
  CHECK(SBCM_new_3x3(UINT_MAX, 2, 2, row, col, blocks) == NULL && fc3d_last_error_code() == FC3D_ERR_INVALID_SIZE,
        "2^32 - 1 block rows");
  CHECK(SBCM_new_3x3(2, 0x55555556u, 2, row, col, blocks) == NULL &&
            fc3d_last_error_code() == FC3D_ERR_INVALID_SIZE,
        "3 n overflows");
  CHECK(SBCM_new_3x3(2, 2, 2, NULL, col, blocks) == NULL && fc3d_last_error_code() == FC3D_ERR_NULL_POINTER,
        "NULL rows");
  col[1] = 0;
  CHECK(SBCM_new_3x3(2, 2, 2, row, col, blocks) == NULL && fc3d_last_error_code() == FC3D_ERR_INVALID_SIZE,
        "1-based column 0");
  col[1] = 3;
  CHECK(SBCM_new_3x3(2, 2, 2, row, col, blocks) == NULL && fc3d_last_error_code() == FC3D_ERR_INVALID_SIZE,
        "column past the grid");
  col[1] = 2;
  SparseBlockCoordinateMatrix* coo = SBCM_new_3x3(2, 2, 2, row, col, blocks);
  CHECK(coo != NULL, "SBCM_new_3x3");
  /* Siconos' ownership: row and column copied, 0-based; the blocks point into the caller's values. */
  CHECK(coo->row != row && coo->column != col && coo->row[1] == 1 && coo->column[0] == 0 &&
            coo->block[1] == blocks + 9 && coo->blocksize0[1] == 6,
        "SBCM_new_3x3 copies the coordinates 0-based");
  /* A host editing the coordinate matrix afterwards is checked again by SBCM_to_SBM. */
  coo->column[1] = 2;
  CHECK(SBCM_to_SBM(coo) == NULL && fc3d_last_error_code() == FC3D_ERR_INVALID_SIZE, "0-based column past the grid");
  coo->column[1] = 1;
  double* b1 = coo->block[1];
  coo->block[1] = NULL;
  CHECK(SBCM_to_SBM(coo) == NULL && fc3d_last_error_code() == FC3D_ERR_NULL_POINTER, "NULL block");
  coo->block[1] = b1;
  coo->blocksize1[1] = 3;
  CHECK(SBCM_to_SBM(coo) == NULL && fc3d_last_error_code() == FC3D_ERR_INVALID_STORAGE, "sizes 3, 3");
  coo->blocksize1[1] = 6;
  SparseBlockStructuredMatrix* sbm = SBCM_to_SBM(coo);
  CHECK(sbm != NULL, "SBCM_to_SBM");
  CHECK(sbm->blocksize0 == coo->blocksize0 && sbm->blocksize1 == coo->blocksize1 && sbm->block[0] == blocks &&
            sbm->filled1 == 3 && sbm->index1_data[2] == 2 && sbm->diagonal_blocks == NULL,
        "SBCM_to_SBM shares the sizes and the blocks as Siconos does");
  NumericsMatrix* M = NM_new_SBM(6, 6, sbm);
  double q[6] = {-2, 0, 0, -2, 0, 0}, mu[2] = {0.3, 0.3}, r[6] = {0}, u[6] = {0};
  FrictionContactProblem p = {3, 2, M, q, mu};
  SolverOptions* o = solver_options_create(SICONOS_FRICTION_3D_NSGS);
  CHECK(fc3d_driver(&p, r, u, o) == 0 && fabs(r[0] - 1.0) < 1e-12, "solve");
  /* The same SBM with a block count above its arrays: the driver refuses, untouched outputs. */
  sbm->nbblocks = 3;
  r[0] = 7.0;
  CHECK(fc3d_driver(&p, r, u, o) == FC3D_ERR_INVALID_STORAGE && r[0] == 7.0, "nbblocks 3");
  sbm->nbblocks = 2;
  solver_options_delete(o);
  free(o);
  M->matrix1 = NULL;
  NM_free(M);
  SBM_free_from_SBCM(sbm);
  SBCM_free_3x3(coo);
  free(coo); /* Siconos: SBCM_free_3x3 frees the arrays, not the struct */

  /* Release with a block count beyond the block array: refused, nothing freed or read. */
  SparseBlockStructuredMatrix* s = sbm_one_row(1);
  s->nbblocks = 100000;
  SBM_clear(s);
  CHECK(fc3d_last_error_code() == FC3D_ERR_INVALID_STORAGE && s->block != NULL, "SBM_clear past the array");
  NumericsMatrix* W = NM_new_SBM(3, 3, s);
  CHECK(NM_free(W) == NULL && fc3d_last_error_code() == FC3D_ERR_INVALID_STORAGE && W->matrix1 == s,
        "NM_free past the array");
  s->nbblocks = 1;
  CHECK(CODE_OF(NM_free(W)) == 0, "NM_free");
  return 0;
}

/* Two contacts in one SBM, every block its own malloc (as Siconos' hosts allocate them); row 0
 * stores its blocks in column order, or reversed when `reverse_row0` (Siconos does not sort). */
typedef struct {
  SparseBlockStructuredMatrix* s;
  NumericsMatrix* M;
  double* blocks[4]; /* (0,0) (0,1) (1,0) (1,1) */
} TwoContacts;

static void two_contacts(TwoContacts* t, int reverse_row0) {
  const double diag[9] = {2.0, 0.1, 0.0, 0.1, 1.5, 0.2, 0.0, 0.3, 1.25}; /* column-major */
  const double off[9] = {0.5, 0.05, 0.01, 0.02, 0.25, 0.03, 0.04, 0.06, 0.125};
  for (int k = 0; k < 4; k++) {
    t->blocks[k] = malloc(9 * sizeof(double));
    for (int e = 0; e < 9; e++) t->blocks[k][e] = (k == 0 || k == 3 ? diag[e] : off[e]) * (1.0 + 0.1 * k);
  }
  SparseBlockStructuredMatrix* s = SBM_new();
  s->nbblocks = 4;
  s->blocknumber0 = s->blocknumber1 = 2;
  s->blocksize0 = malloc(2 * sizeof(unsigned));
  s->blocksize1 = malloc(2 * sizeof(unsigned));
  s->blocksize0[0] = s->blocksize1[0] = 3;
  s->blocksize0[1] = s->blocksize1[1] = 6;
  s->filled1 = 3;
  s->filled2 = 4;
  s->index1_data = malloc(3 * sizeof(size_t));
  s->index1_data[0] = 0;
  s->index1_data[1] = 2;
  s->index1_data[2] = 4;
  s->index2_data = malloc(4 * sizeof(size_t));
  s->block = malloc(4 * sizeof(double*));
  const size_t cols[4] = {0, 1, 0, 1};
  const int order[4] = {reverse_row0 ? 1 : 0, reverse_row0 ? 0 : 1, 2, 3};
  for (int k = 0; k < 4; k++) {
    s->index2_data[k] = cols[order[k]];
    s->block[k] = t->blocks[order[k]];
  }
  t->s = s;
  t->M = NM_new_SBM(6, 6, s);
}

static void two_contacts_free(TwoContacts* t) {
  for (int k = 0; k < 4; k++) t->s->block[k] = t->blocks[k]; /* whatever a check changed */
  NM_free(t->M);
}

static int solve_two(TwoContacts* t, double* r, double* u, int* code) {
  double q[6] = {-1.0, 0.3, -0.2, -0.5, -0.1, 0.4}, mu[2] = {0.5, 0.3};
  FrictionContactProblem p;
  memset(&p, 0, sizeof p);
  p.dimension = 3;
  p.numberOfContacts = 2;
  p.M = t->M;
  p.q = q;
  p.mu = mu;
  SolverOptions* o = solver_options_create(SICONOS_FRICTION_3D_NSGS);
  o->dparam[SICONOS_DPARAM_TOL] = 1e-12;
  fc3d_clear_last_error();
  *code = fc3d_driver(&p, r, u, o);
  solver_options_delete(o);
  free(o);
  return 0;
}

/* fc3d_driver reads the host's blocks in place (issue 14): the block table and index arrays are
 * checked, never the blocks copied; rows in any order give the same bits; a NULL or misaligned
 * block pointer and a NaN in a block are refused with the outputs untouched. */
static int check_driver_reads_blocks_in_place(void) {
  TwoContacts sorted, reversed;
  two_contacts(&sorted, 0);
  two_contacts(&reversed, 1);
  double r1[6] = {0}, u1[6] = {0}, r2[6] = {0}, u2[6] = {0};
  int code;
  solve_two(&sorted, r1, u1, &code);
  CHECK(code == 0 && r1[0] > 0.0, "two contacts: code %d", code);
  solve_two(&reversed, r2, u2, &code);
  CHECK(code == 0 && memcmp(r1, r2, sizeof r1) == 0 && memcmp(u1, u2, sizeof u1) == 0,
        "a row stored out of column order gives other bits (code %d)", code);

  double r[6], u[6];
  for (int k = 0; k < 6; k++) r[k] = u[k] = 7.0;
  sorted.s->block[1] = NULL;
  solve_two(&sorted, r, u, &code);
  CHECK(code == FC3D_ERR_NULL_POINTER && strstr(fc3d_last_error_message(), "block 1") && r[0] == 7.0 && u[5] == 7.0,
        "NULL block pointer: code %d", code);
  sorted.s->block[1] = (double*)((char*)sorted.blocks[1] + 4);
  solve_two(&sorted, r, u, &code);
  CHECK(code < 0 && strstr(fc3d_last_error_message(), "block 1") && r[0] == 7.0, "misaligned block pointer: code %d", code);
  sorted.s->block[1] = sorted.blocks[1];
  sorted.s->index2_data[1] = 2;
  solve_two(&sorted, r, u, &code);
  CHECK(code == FC3D_ERR_INVALID_STORAGE && r[0] == 7.0, "block column out of range: code %d", code);
  sorted.s->index2_data[1] = 1;
  sorted.blocks[1][4] = NAN;
  solve_two(&sorted, r, u, &code);
  CHECK(code == FC3D_ERR_NON_FINITE && strstr(fc3d_last_error_message(), "block 1") && r[0] == 7.0 && u[0] == 7.0,
        "NaN in a coupling block: code %d", code);
  sorted.blocks[1][4] = 0.25;
  sorted.blocks[3][0] = INFINITY;
  solve_two(&sorted, r, u, &code);
  CHECK(code == FC3D_ERR_NON_FINITE && r[0] == 7.0, "infinity in a diagonal block: code %d", code);
  two_contacts_free(&sorted);
  two_contacts_free(&reversed);
  return 0;
}

int capi_check_hostile_matrices(void) {
  if (check_get_value() || check_entry_and_triplets() || check_coordinates_and_release()) return 1;
  if (check_driver_reads_blocks_in_place()) return 1;
  return 0;
}

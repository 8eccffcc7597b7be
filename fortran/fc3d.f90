! Fortran bindings of fc3d's native entry (fc3d_native.h): the discrete 3D frictional contact
! problem FC(W, q, mu) -- find r, u in R^(3 nc) with u = W r + q, Signorini contact and Coulomb
! friction at every contact (components ordered normal, tangent 1, tangent 2).
!
! Installed as source to PREFIX/share/fc3d/fortran/fc3d.f90. Compile it with your program and
! link the native library (it has no Siconos names, so it links beside Siconos too):
!
!   export PKG_CONFIG_PATH=PREFIX/lib/pkgconfig
!   gfortran -c PREFIX/share/fc3d/fortran/fc3d.f90
!   gfortran my_program.f90 fc3d.o $(pkg-config --libs fc3d-native) -o my_program
!
! Two layers:
!
! 1. bind(C) interfaces, one per C function, with the C names and the C argument types
!    (sizes and indices integer(c_int64_t), handles type(c_ptr), settings may be c_null_ptr,
!    the result a type(fc3d_result)). The four functions taking or returning C strings are bound
!    under Fortran names ending in _c (fc3d_version_c, fc3d_last_error_message_c,
!    fc3d_settings_set_c, fc3d_problem_read_c); the plain names are the wrappers below.
!
! 2. Fortran-friendly wrappers:
!    fc3d_version()                      the library's version as a Fortran string
!    fc3d_last_error_message()           the message of the last failed call ("" if none)
!    fc3d_settings_set(s, name, value)   a setting by name ('tolerance', 'iparam[7]', ...)
!    fc3d_problem_read(path)             a problem read from a Siconos .dat file (c_null_ptr
!                                        on failure)
!    call fc3d_solve(w, q, mu, r, u, info [, solver, tolerance, max_iter, time_budget,
!                    local_solver | settings] [, result] [, errmsg])
!        w a dense Fortran array w(3nc, 3nc); or
!    call fc3d_solve(row_ptr, col_idx, values, q, mu, r, u, info, ...)
!        w in compressed rows, 0-based integer(c_int64_t) indices (as fc3d_problem_get gives);
!    call fc3d_solve(problem, r, u, info, ...)
!        a problem read by fc3d_problem_read.
!    call fc3d_solve_global(m_row_ptr, m_col_idx, m_values, h_row_ptr, h_col_idx, h_values,
!                           q, b, mu, r, u, v, info [, solver, ...])
!        the global problem M v = q + H r, u = H^T v + b (Siconos' gfc3d_driver): M (n x n) and
!        H (n x 3nc) in compressed rows, 0-based; v (n) receives the global velocity; solver a
!        global id (FC3D_GFC3D_*, default FC3D_GFC3D_NSGS_WR = 600).
!    r holds the initial reaction and receives the result, u receives W r + q. info is 0
!    (converged), 1 (iteration limit), 2 (time budget spent), 3 (SOCLCP: relaxed solution not
!    Coulomb), or a negative FC3D_ERR_* code, in which case r and u are unchanged and errmsg (if
!    present) says why. Without settings, a solver is made for the call (solver defaults to
!    FC3D_NSGS, every other option to Siconos' default); with settings (from fc3d_settings_new),
!    the other options must be absent.
!
! Arrays are passed to C by address: W dense is column-major, exactly Fortran's layout.
module fc3d
  use, intrinsic :: iso_c_binding
  implicit none
  private

  ! -- Return codes (fc3d_native.h).
  integer(c_int), parameter, public :: FC3D_OK = 0
  integer(c_int), parameter, public :: FC3D_NOT_CONVERGED = 1
  integer(c_int), parameter, public :: FC3D_TIME_BUDGET_EXHAUSTED = 2
  integer(c_int), parameter, public :: FC3D_RELAXED_NOT_COULOMB = 3
  integer(c_int), parameter, public :: FC3D_ERR_NULL_POINTER = -1
  integer(c_int), parameter, public :: FC3D_ERR_INVALID_SIZE = -2
  integer(c_int), parameter, public :: FC3D_ERR_INVALID_STORAGE = -3
  integer(c_int), parameter, public :: FC3D_ERR_NON_FINITE = -4
  integer(c_int), parameter, public :: FC3D_ERR_INVALID_OPTION = -5
  integer(c_int), parameter, public :: FC3D_ERR_UNSUPPORTED_SOLVER = -6
  integer(c_int), parameter, public :: FC3D_ERR_INVALID_PROBLEM = -7
  integer(c_int), parameter, public :: FC3D_ERR_PARSE = -8
  integer(c_int), parameter, public :: FC3D_ERR_IO = -9
  integer(c_int), parameter, public :: FC3D_ERR_INTERNAL = -99

  ! -- Solver ids: every solver the native entry accepts, named as Siconos' constants
  !    SICONOS_FRICTION_3D_<NAME> (ONECONTACT_ left out) and fc3d's FC3D_AUTO; docs/solvers.md
  !    says what each does. The library lists them (fc3d_solver_count, fc3d_solver_at), and
  !    capi/tests/bindings.rs checks that this module names each with its id.
  integer(c_int), parameter, public :: FC3D_AUTO = 590
  integer(c_int), parameter, public :: FC3D_NSGS = 500
  integer(c_int), parameter, public :: FC3D_PROX = 502
  integer(c_int), parameter, public :: FC3D_TFP = 503
  integer(c_int), parameter, public :: FC3D_NSN_AC = 504
  integer(c_int), parameter, public :: FC3D_DSFP = 505
  integer(c_int), parameter, public :: FC3D_VI_FPP = 506
  integer(c_int), parameter, public :: FC3D_VI_EG = 507
  integer(c_int), parameter, public :: FC3D_HP = 508
  integer(c_int), parameter, public :: FC3D_FPP = 511
  integer(c_int), parameter, public :: FC3D_EG = 512
  integer(c_int), parameter, public :: FC3D_NSN_FB = 513
  integer(c_int), parameter, public :: FC3D_ACLMFP = 516
  integer(c_int), parameter, public :: FC3D_SOCLCP = 517
  integer(c_int), parameter, public :: FC3D_NSN_NM = 520
  integer(c_int), parameter, public :: FC3D_NSN_AC_TEST = 521
  integer(c_int), parameter, public :: FC3D_PFP = 522
  integer(c_int), parameter, public :: FC3D_ADMM = 523
  ! The exact one-contact enumeration, as a top-level solver (NSGS sweeps with it) and as NSGS's
  ! local solver.
  integer(c_int), parameter, public :: FC3D_QUARTIC = 562
  integer(c_int), parameter, public :: FC3D_QUARTIC_NU = 563
  ! Local (one-contact) solvers of NSGS, for fc3d_settings_set_local_solver.
  integer(c_int), parameter, public :: FC3D_ONECONTACT_NSN = 550
  integer(c_int), parameter, public :: FC3D_ONECONTACT_NSN_GP = 551
  integer(c_int), parameter, public :: FC3D_ONECONTACT_PROJECTION_ON_CONE = 552
  integer(c_int), parameter, public :: FC3D_ONECONTACT_PROJECTION_ON_CONE_WITH_LOCAL_ITERATION = 553
  integer(c_int), parameter, public :: FC3D_ONECONTACT_NSN_GP_HYBRID = 565
  ! Global solvers (Siconos' SICONOS_GLOBAL_FRICTION_3D_<NAME>), for fc3d_solve_global.
  integer(c_int), parameter, public :: FC3D_GFC3D_NSGS_WR = 600, FC3D_GFC3D_PROX_WR = 602
  integer(c_int), parameter, public :: FC3D_GFC3D_DSFP_WR = 603, FC3D_GFC3D_TFP_WR = 604
  integer(c_int), parameter, public :: FC3D_GFC3D_NSGS = 605, FC3D_GFC3D_NSN_AC_WR = 606
  integer(c_int), parameter, public :: FC3D_GFC3D_NSN_AC = 607, FC3D_GFC3D_VI_FPP = 610
  integer(c_int), parameter, public :: FC3D_GFC3D_VI_EG = 611, FC3D_GFC3D_ACLMFP = 612
  integer(c_int), parameter, public :: FC3D_GFC3D_ADMM = 613, FC3D_GFC3D_ADMM_WR = 614
  integer(c_int), parameter, public :: FC3D_GFC3D_IPM = 615

  ! -- What a solve reports (struct Fc3dResult: int, int64_t, double, double).
  type, bind(C), public :: fc3d_result
    integer(c_int) :: info = 0            ! 0 converged, 1 iteration limit, 2 time budget, 3 relaxed
    integer(c_int64_t) :: iterations = 0  ! iterations (sweeps, Newton steps, ...) done
    real(c_double) :: error = 0           ! natural-map (global: Siconos' global) error
    real(c_double) :: seconds = 0         ! wall-clock time of the solve
  end type fc3d_result

  ! -- The C functions (fc3d_native.h), one by one.
  public :: fc3d_last_error_message_c, fc3d_last_error_code, fc3d_clear_last_error, fc3d_version_c
  public :: fc3d_settings_new, fc3d_settings_free, fc3d_settings_set_tolerance
  public :: fc3d_settings_set_max_iter, fc3d_settings_set_time_budget
  public :: fc3d_settings_set_local_solver, fc3d_settings_set_internal_solver
  public :: fc3d_settings_set_iparam, fc3d_settings_set_dparam
  public :: fc3d_settings_set_local_iparam, fc3d_settings_set_local_dparam, fc3d_settings_set_c
  public :: fc3d_solve_dense, fc3d_solve_csr, fc3d_solve_coo, fc3d_solve_blocks
  public :: fc3d_solve_global_csr, fc3d_solve_global_coo, fc3d_solve_global_blocks
  public :: fc3d_problem_read_c, fc3d_problem_free, fc3d_problem_contacts, fc3d_problem_nnz
  public :: fc3d_problem_get, fc3d_problem_solve, fc3d_solver_count, fc3d_solver_at
  ! -- The Fortran wrappers.
  public :: fc3d_version, fc3d_last_error_message, fc3d_settings_set, fc3d_problem_read
  public :: fc3d_solve, fc3d_solve_global

  interface
    ! const char *fc3d_last_error_message(void);
    function fc3d_last_error_message_c() bind(C, name="fc3d_last_error_message") result(message)
      import :: c_ptr
      type(c_ptr) :: message
    end function fc3d_last_error_message_c

    ! int fc3d_last_error_code(void);
    function fc3d_last_error_code() bind(C, name="fc3d_last_error_code") result(code)
      import :: c_int
      integer(c_int) :: code
    end function fc3d_last_error_code

    ! void fc3d_clear_last_error(void);
    subroutine fc3d_clear_last_error() bind(C, name="fc3d_clear_last_error")
    end subroutine fc3d_clear_last_error

    ! const char *fc3d_version(void);
    function fc3d_version_c() bind(C, name="fc3d_version") result(version)
      import :: c_ptr
      type(c_ptr) :: version
    end function fc3d_version_c

    ! struct Fc3dSettings *fc3d_settings_new(int solver_id);
    function fc3d_settings_new(solver_id) bind(C, name="fc3d_settings_new") result(settings)
      import :: c_int, c_ptr
      integer(c_int), value :: solver_id
      type(c_ptr) :: settings
    end function fc3d_settings_new

    ! void fc3d_settings_free(struct Fc3dSettings *settings);
    subroutine fc3d_settings_free(settings) bind(C, name="fc3d_settings_free")
      import :: c_ptr
      type(c_ptr), value :: settings
    end subroutine fc3d_settings_free

    ! int fc3d_settings_set_tolerance(struct Fc3dSettings *settings, double tolerance);
    function fc3d_settings_set_tolerance(settings, tolerance) &
        bind(C, name="fc3d_settings_set_tolerance") result(code)
      import :: c_ptr, c_double, c_int
      type(c_ptr), value :: settings
      real(c_double), value :: tolerance
      integer(c_int) :: code
    end function fc3d_settings_set_tolerance

    ! int fc3d_settings_set_max_iter(struct Fc3dSettings *settings, int64_t max_iter);
    function fc3d_settings_set_max_iter(settings, max_iter) &
        bind(C, name="fc3d_settings_set_max_iter") result(code)
      import :: c_ptr, c_int64_t, c_int
      type(c_ptr), value :: settings
      integer(c_int64_t), value :: max_iter
      integer(c_int) :: code
    end function fc3d_settings_set_max_iter

    ! int fc3d_settings_set_time_budget(struct Fc3dSettings *settings, double seconds);
    function fc3d_settings_set_time_budget(settings, seconds) &
        bind(C, name="fc3d_settings_set_time_budget") result(code)
      import :: c_ptr, c_double, c_int
      type(c_ptr), value :: settings
      real(c_double), value :: seconds
      integer(c_int) :: code
    end function fc3d_settings_set_time_budget

    ! int fc3d_settings_set_local_solver(struct Fc3dSettings *settings, int local_solver_id);
    function fc3d_settings_set_local_solver(settings, local_solver_id) &
        bind(C, name="fc3d_settings_set_local_solver") result(code)
      import :: c_ptr, c_int
      type(c_ptr), value :: settings
      integer(c_int), value :: local_solver_id
      integer(c_int) :: code
    end function fc3d_settings_set_local_solver

    ! int fc3d_settings_set_internal_solver(struct Fc3dSettings *settings, int internal_solver_id);
    function fc3d_settings_set_internal_solver(settings, internal_solver_id) &
        bind(C, name="fc3d_settings_set_internal_solver") result(code)
      import :: c_ptr, c_int
      type(c_ptr), value :: settings
      integer(c_int), value :: internal_solver_id
      integer(c_int) :: code
    end function fc3d_settings_set_internal_solver

    ! int fc3d_settings_set_iparam(struct Fc3dSettings *settings, int index, int value);
    ! (index is Siconos' 0-based iparam index)
    function fc3d_settings_set_iparam(settings, index, value) &
        bind(C, name="fc3d_settings_set_iparam") result(code)
      import :: c_ptr, c_int
      type(c_ptr), value :: settings
      integer(c_int), value :: index
      integer(c_int), value :: value
      integer(c_int) :: code
    end function fc3d_settings_set_iparam

    ! int fc3d_settings_set_dparam(struct Fc3dSettings *settings, int index, double value);
    function fc3d_settings_set_dparam(settings, index, value) &
        bind(C, name="fc3d_settings_set_dparam") result(code)
      import :: c_ptr, c_int, c_double
      type(c_ptr), value :: settings
      integer(c_int), value :: index
      real(c_double), value :: value
      integer(c_int) :: code
    end function fc3d_settings_set_dparam

    ! int fc3d_settings_set_local_iparam(struct Fc3dSettings *settings, int index, int value);
    function fc3d_settings_set_local_iparam(settings, index, value) &
        bind(C, name="fc3d_settings_set_local_iparam") result(code)
      import :: c_ptr, c_int
      type(c_ptr), value :: settings
      integer(c_int), value :: index
      integer(c_int), value :: value
      integer(c_int) :: code
    end function fc3d_settings_set_local_iparam

    ! int fc3d_settings_set_local_dparam(struct Fc3dSettings *settings, int index, double value);
    function fc3d_settings_set_local_dparam(settings, index, value) &
        bind(C, name="fc3d_settings_set_local_dparam") result(code)
      import :: c_ptr, c_int, c_double
      type(c_ptr), value :: settings
      integer(c_int), value :: index
      real(c_double), value :: value
      integer(c_int) :: code
    end function fc3d_settings_set_local_dparam

    ! int fc3d_settings_set(struct Fc3dSettings *settings, const char *name, double value);
    ! (name NUL-terminated: use the wrapper fc3d_settings_set)
    function fc3d_settings_set_c(settings, name, value) bind(C, name="fc3d_settings_set") &
        result(code)
      import :: c_ptr, c_char, c_double, c_int
      type(c_ptr), value :: settings
      character(kind=c_char), intent(in) :: name(*)
      real(c_double), value :: value
      integer(c_int) :: code
    end function fc3d_settings_set_c

    ! int fc3d_solve_dense(int64_t n_contacts, const double *w, const double *q,
    !                      const double *mu, double *r, double *u,
    !                      const struct Fc3dSettings *settings, struct Fc3dResult *result);
    function fc3d_solve_dense(n_contacts, w, q, mu, r, u, settings, result) &
        bind(C, name="fc3d_solve_dense") result(code)
      import :: c_int64_t, c_double, c_ptr, c_int, fc3d_result
      integer(c_int64_t), value :: n_contacts
      real(c_double), intent(in) :: w(*), q(*), mu(*)
      real(c_double), intent(inout) :: r(*), u(*)
      type(c_ptr), value :: settings
      type(fc3d_result), intent(inout) :: result
      integer(c_int) :: code
    end function fc3d_solve_dense

    ! int fc3d_solve_csr(int64_t n_contacts, int64_t nnz, const int64_t *row_ptr,
    !                    const int64_t *col_idx, const double *values, const double *q,
    !                    const double *mu, double *r, double *u,
    !                    const struct Fc3dSettings *settings, struct Fc3dResult *result);
    function fc3d_solve_csr(n_contacts, nnz, row_ptr, col_idx, values, q, mu, r, u, settings, &
        result) bind(C, name="fc3d_solve_csr") result(code)
      import :: c_int64_t, c_double, c_ptr, c_int, fc3d_result
      integer(c_int64_t), value :: n_contacts, nnz
      integer(c_int64_t), intent(in) :: row_ptr(*), col_idx(*)
      real(c_double), intent(in) :: values(*), q(*), mu(*)
      real(c_double), intent(inout) :: r(*), u(*)
      type(c_ptr), value :: settings
      type(fc3d_result), intent(inout) :: result
      integer(c_int) :: code
    end function fc3d_solve_csr

    ! int fc3d_solve_coo(int64_t n_contacts, int64_t nnz, const int64_t *rows,
    !                    const int64_t *cols, const double *values, const double *q,
    !                    const double *mu, double *r, double *u,
    !                    const struct Fc3dSettings *settings, struct Fc3dResult *result);
    function fc3d_solve_coo(n_contacts, nnz, rows, cols, values, q, mu, r, u, settings, result) &
        bind(C, name="fc3d_solve_coo") result(code)
      import :: c_int64_t, c_double, c_ptr, c_int, fc3d_result
      integer(c_int64_t), value :: n_contacts, nnz
      integer(c_int64_t), intent(in) :: rows(*), cols(*)
      real(c_double), intent(in) :: values(*), q(*), mu(*)
      real(c_double), intent(inout) :: r(*), u(*)
      type(c_ptr), value :: settings
      type(fc3d_result), intent(inout) :: result
      integer(c_int) :: code
    end function fc3d_solve_coo

    ! int fc3d_solve_blocks(int64_t n_contacts, int64_t n_blocks, const int64_t *block_row_ptr,
    !                       const int64_t *block_col_idx, const double *blocks,
    !                       const double *q, const double *mu, double *r, double *u,
    !                       const struct Fc3dSettings *settings, struct Fc3dResult *result);
    ! (blocks: 9 n_blocks values, each 3x3 block column-major, e.g. real(c_double) b(3,3,nb))
    function fc3d_solve_blocks(n_contacts, n_blocks, block_row_ptr, block_col_idx, blocks, q, &
        mu, r, u, settings, result) bind(C, name="fc3d_solve_blocks") result(code)
      import :: c_int64_t, c_double, c_ptr, c_int, fc3d_result
      integer(c_int64_t), value :: n_contacts, n_blocks
      integer(c_int64_t), intent(in) :: block_row_ptr(*), block_col_idx(*)
      real(c_double), intent(in) :: blocks(*), q(*), mu(*)
      real(c_double), intent(inout) :: r(*), u(*)
      type(c_ptr), value :: settings
      type(fc3d_result), intent(inout) :: result
      integer(c_int) :: code
    end function fc3d_solve_blocks

    ! int fc3d_solve_global_csr(int64_t ndof, int64_t n_contacts, int64_t m_nnz,
    !     const int64_t *m_row_ptr, const int64_t *m_col_idx, const double *m_values,
    !     int64_t h_nnz, const int64_t *h_row_ptr, const int64_t *h_col_idx,
    !     const double *h_values, const double *q, const double *b, const double *mu, double *r,
    !     double *u, double *v, const struct Fc3dSettings *settings, struct Fc3dResult *result);
    ! (fc3d_solve_global_coo: the same with (rows, cols, values) triplets for M and H.)
    function fc3d_solve_global_csr(ndof, n_contacts, m_nnz, m_row_ptr, m_col_idx, m_values, &
        h_nnz, h_row_ptr, h_col_idx, h_values, q, b, mu, r, u, v, settings, result) &
        bind(C, name="fc3d_solve_global_csr") result(code)
      import :: c_int64_t, c_double, c_ptr, c_int, fc3d_result
      integer(c_int64_t), value :: ndof, n_contacts, m_nnz, h_nnz
      integer(c_int64_t), intent(in) :: m_row_ptr(*), m_col_idx(*), h_row_ptr(*), h_col_idx(*)
      real(c_double), intent(in) :: m_values(*), h_values(*), q(*), b(*), mu(*)
      real(c_double), intent(inout) :: r(*), u(*), v(*)
      type(c_ptr), value :: settings
      type(fc3d_result), intent(inout) :: result
      integer(c_int) :: code
    end function fc3d_solve_global_csr

    function fc3d_solve_global_coo(ndof, n_contacts, m_nnz, m_rows, m_cols, m_values, &
        h_nnz, h_rows, h_cols, h_values, q, b, mu, r, u, v, settings, result) &
        bind(C, name="fc3d_solve_global_coo") result(code)
      import :: c_int64_t, c_double, c_ptr, c_int, fc3d_result
      integer(c_int64_t), value :: ndof, n_contacts, m_nnz, h_nnz
      integer(c_int64_t), intent(in) :: m_rows(*), m_cols(*), h_rows(*), h_cols(*)
      real(c_double), intent(in) :: m_values(*), h_values(*), q(*), b(*), mu(*)
      real(c_double), intent(inout) :: r(*), u(*), v(*)
      type(c_ptr), value :: settings
      type(fc3d_result), intent(inout) :: result
      integer(c_int) :: code
    end function fc3d_solve_global_coo

    ! int fc3d_solve_global_blocks(int64_t n_blocks, int64_t block_size, const double *m_blocks,
    !     int64_t n_contacts, int64_t h_nnz, const int64_t *h_row_ptr, const int64_t *h_col_idx,
    !     const double *h_values, const double *q, ..., struct Fc3dResult *result);
    ! (m_blocks: n_blocks dense diagonal blocks of M, each column-major, e.g. m(6,6,n_bodies))
    function fc3d_solve_global_blocks(n_blocks, block_size, m_blocks, n_contacts, h_nnz, &
        h_row_ptr, h_col_idx, h_values, q, b, mu, r, u, v, settings, result) &
        bind(C, name="fc3d_solve_global_blocks") result(code)
      import :: c_int64_t, c_double, c_ptr, c_int, fc3d_result
      integer(c_int64_t), value :: n_blocks, block_size, n_contacts, h_nnz
      integer(c_int64_t), intent(in) :: h_row_ptr(*), h_col_idx(*)
      real(c_double), intent(in) :: m_blocks(*), h_values(*), q(*), b(*), mu(*)
      real(c_double), intent(inout) :: r(*), u(*), v(*)
      type(c_ptr), value :: settings
      type(fc3d_result), intent(inout) :: result
      integer(c_int) :: code
    end function fc3d_solve_global_blocks

    ! struct Fc3dProblem *fc3d_problem_read(const char *path);
    ! (path NUL-terminated: use the wrapper fc3d_problem_read)
    function fc3d_problem_read_c(path) bind(C, name="fc3d_problem_read") result(problem)
      import :: c_char, c_ptr
      character(kind=c_char), intent(in) :: path(*)
      type(c_ptr) :: problem
    end function fc3d_problem_read_c

    ! void fc3d_problem_free(struct Fc3dProblem *problem);
    subroutine fc3d_problem_free(problem) bind(C, name="fc3d_problem_free")
      import :: c_ptr
      type(c_ptr), value :: problem
    end subroutine fc3d_problem_free

    ! int64_t fc3d_problem_contacts(const struct Fc3dProblem *problem);
    function fc3d_problem_contacts(problem) bind(C, name="fc3d_problem_contacts") result(nc)
      import :: c_ptr, c_int64_t
      type(c_ptr), value :: problem
      integer(c_int64_t) :: nc
    end function fc3d_problem_contacts

    ! int64_t fc3d_problem_nnz(const struct Fc3dProblem *problem);
    function fc3d_problem_nnz(problem) bind(C, name="fc3d_problem_nnz") result(nnz)
      import :: c_ptr, c_int64_t
      type(c_ptr), value :: problem
      integer(c_int64_t) :: nnz
    end function fc3d_problem_nnz

    ! int fc3d_problem_get(const struct Fc3dProblem *problem, int64_t *row_ptr,
    !                      int64_t *col_idx, double *values, double *q, double *mu);
    ! (row_ptr: 3nc + 1, col_idx and values: nnz, q: 3nc, mu: nc; indices 0-based)
    function fc3d_problem_get(problem, row_ptr, col_idx, values, q, mu) &
        bind(C, name="fc3d_problem_get") result(code)
      import :: c_ptr, c_int64_t, c_double, c_int
      type(c_ptr), value :: problem
      integer(c_int64_t), intent(inout) :: row_ptr(*), col_idx(*)
      real(c_double), intent(inout) :: values(*), q(*), mu(*)
      integer(c_int) :: code
    end function fc3d_problem_get

    ! int fc3d_problem_solve(const struct Fc3dProblem *problem, double *r, double *u,
    !                        const struct Fc3dSettings *settings, struct Fc3dResult *result);
    function fc3d_problem_solve(problem, r, u, settings, result) &
        bind(C, name="fc3d_problem_solve") result(code)
      import :: c_ptr, c_double, c_int, fc3d_result
      type(c_ptr), value :: problem
      real(c_double), intent(inout) :: r(*), u(*)
      type(c_ptr), value :: settings
      type(fc3d_result), intent(inout) :: result
      integer(c_int) :: code
    end function fc3d_problem_solve

    ! int fc3d_solver_count(void);
    function fc3d_solver_count() bind(C, name="fc3d_solver_count") result(count)
      import :: c_int
      integer(c_int) :: count
    end function fc3d_solver_count

    ! int fc3d_solver_at(int index, const char **constant, const char **name);
    ! (index 0-based; constant and name receive static C strings: do not free them)
    function fc3d_solver_at(index, constant, name) bind(C, name="fc3d_solver_at") result(id)
      import :: c_int, c_ptr
      integer(c_int), value :: index
      type(c_ptr) :: constant, name
      integer(c_int) :: id
    end function fc3d_solver_at

    ! size_t strlen(const char *), from the C library, to read C strings.
    function c_strlen(s) bind(C, name="strlen") result(n)
      import :: c_ptr, c_size_t
      type(c_ptr), value :: s
      integer(c_size_t) :: n
    end function c_strlen
  end interface

  interface fc3d_solve
    module procedure solve_dense_array, solve_csr_arrays, solve_problem
  end interface fc3d_solve

contains

  ! A NUL-terminated C string as a Fortran string ("" for a NULL pointer).
  function from_c_string(p) result(s)
    type(c_ptr), intent(in) :: p
    character(len=:), allocatable :: s
    character(kind=c_char), pointer :: chars(:)
    integer :: n, k
    if (.not. c_associated(p)) then
      s = ''
      return
    end if
    n = int(c_strlen(p))
    call c_f_pointer(p, chars, [n])
    allocate(character(len=n) :: s)
    do k = 1, n
      s(k:k) = chars(k)
    end do
  end function from_c_string

  ! A Fortran string (trailing blanks removed) as a NUL-terminated C string.
  pure function to_c_string(s) result(c)
    character(len=*), intent(in) :: s
    character(kind=c_char, len=len_trim(s) + 1) :: c
    c = trim(s) // c_null_char
  end function to_c_string

  !> The library's version, e.g. "0.2.0".
  function fc3d_version() result(version)
    character(len=:), allocatable :: version
    version = from_c_string(fc3d_version_c())
  end function fc3d_version

  !> The message of the last failed fc3d call on this thread ("" if none).
  function fc3d_last_error_message() result(message)
    character(len=:), allocatable :: message
    message = from_c_string(fc3d_last_error_message_c())
  end function fc3d_last_error_message

  !> A setting by name: 'tolerance', 'max_iter', 'time_budget', 'local_solver', 'iparam[K]',
  !> 'dparam[K]', 'local_iparam[K]', 'local_dparam[K]' (K 0-based, Siconos' indices).
  !> Returns 0 or a negative FC3D_ERR_* code.
  function fc3d_settings_set(settings, name, value) result(code)
    type(c_ptr), intent(in) :: settings
    character(len=*), intent(in) :: name
    real(c_double), intent(in) :: value
    integer(c_int) :: code
    code = fc3d_settings_set_c(settings, to_c_string(name), value)
  end function fc3d_settings_set

  !> Reads a Siconos .dat problem (or FCLIB .hdf5 when fc3d is built with FCLIB); c_null_ptr on
  !> failure (see fc3d_last_error_message). Release with fc3d_problem_free.
  function fc3d_problem_read(path) result(problem)
    character(len=*), intent(in) :: path
    type(c_ptr) :: problem
    problem = fc3d_problem_read_c(to_c_string(path))
  end function fc3d_problem_read

  ! The settings a wrapper solves with: the caller's, or new ones made from the options (owned:
  ! freed by finish). info < 0 and message on failure.
  subroutine prepare(settings, solver, tolerance, max_iter, time_budget, local_solver, handle, &
      owned, info, message, default_solver)
    type(c_ptr), intent(in), optional :: settings
    integer, intent(in), optional :: solver, max_iter, local_solver, default_solver
    real(c_double), intent(in), optional :: tolerance, time_budget
    type(c_ptr), intent(out) :: handle
    logical, intent(out) :: owned
    integer(c_int), intent(out) :: info
    character(len=:), allocatable, intent(out) :: message
    integer(c_int) :: id, code
    handle = c_null_ptr
    owned = .false.
    info = FC3D_OK
    message = ''
    if (present(settings)) then
      if (present(solver) .or. present(tolerance) .or. present(max_iter) .or. &
          present(time_budget) .or. present(local_solver)) then
        info = FC3D_ERR_INVALID_OPTION
        message = 'fc3d_solve: give either settings or solver/tolerance/max_iter/time_budget/' // &
            'local_solver, not both'
        return
      end if
      handle = settings
      return
    end if
    id = FC3D_NSGS
    if (present(default_solver)) id = int(default_solver, c_int)
    if (present(solver)) id = int(solver, c_int)
    handle = fc3d_settings_new(id)
    if (.not. c_associated(handle)) then
      info = fc3d_last_error_code()
      message = fc3d_last_error_message()
      return
    end if
    owned = .true.
    code = FC3D_OK
    if (present(tolerance)) code = fc3d_settings_set_tolerance(handle, tolerance)
    if (code == FC3D_OK .and. present(max_iter)) &
        code = fc3d_settings_set_max_iter(handle, int(max_iter, c_int64_t))
    if (code == FC3D_OK .and. present(time_budget)) &
        code = fc3d_settings_set_time_budget(handle, time_budget)
    if (code == FC3D_OK .and. present(local_solver)) &
        code = fc3d_settings_set_local_solver(handle, int(local_solver, c_int))
    if (code /= FC3D_OK) then
      info = code
      message = fc3d_last_error_message()
      call fc3d_settings_free(handle)
      handle = c_null_ptr
      owned = .false.
    end if
  end subroutine prepare

  ! After a solve: the message of a failure (the library's unless the wrapper gave one; "" on
  ! success), and the settings made for the call freed. (The optional outputs are set by the
  ! wrappers themselves: gfortran 12 mishandles optional deferred-length strings passed on.)
  subroutine finish(code, handle, owned, message)
    integer(c_int), intent(in) :: code
    type(c_ptr), intent(in) :: handle
    logical, intent(in) :: owned
    character(len=:), allocatable, intent(inout) :: message
    if (code < 0) then
      if (len(message) == 0) message = fc3d_last_error_message()
    else
      message = ''
    end if
    if (owned) call fc3d_settings_free(handle)
  end subroutine finish

  ! Sizes of r, u, q, mu: 3nc, 3nc, 3nc, nc. Returns a message when they disagree.
  function check_sizes(nc, q, mu, r, u) result(message)
    integer(c_int64_t), intent(in) :: nc
    real(c_double), intent(in) :: q(:), mu(:), r(:), u(:)
    character(len=:), allocatable :: message
    character(len=200) :: buffer
    message = ''
    if (size(mu, kind=c_int64_t) /= nc .or. size(q, kind=c_int64_t) /= 3 * nc .or. &
        size(r, kind=c_int64_t) /= 3 * nc .or. size(u, kind=c_int64_t) /= 3 * nc) then
      write (buffer, '(a,i0,a,i0,a,i0,a,i0,a,i0,a)') 'fc3d_solve: sizes disagree: ', nc, &
          ' contacts, size(q) = ', size(q), ', size(mu) = ', size(mu), ', size(r) = ', size(r), &
          ', size(u) = ', size(u), ' (want 3nc, nc, 3nc, 3nc)'
      message = trim(buffer)
    end if
  end function check_sizes

  !> call fc3d_solve(w, q, mu, r, u, info, ...) with W a dense Fortran array w(3nc, 3nc).
  subroutine solve_dense_array(w, q, mu, r, u, info, solver, tolerance, max_iter, time_budget, &
      local_solver, settings, result, errmsg)
    real(c_double), intent(in) :: w(:, :), q(:), mu(:)
    real(c_double), intent(inout) :: r(:), u(:)
    integer, intent(out) :: info
    integer, intent(in), optional :: solver, max_iter, local_solver
    real(c_double), intent(in), optional :: tolerance, time_budget
    type(c_ptr), intent(in), optional :: settings
    type(fc3d_result), intent(inout), optional :: result
    character(len=:), allocatable, intent(out), optional :: errmsg
    type(c_ptr) :: handle
    logical :: owned
    character(len=:), allocatable :: message
    character(len=200) :: buffer
    type(fc3d_result) :: res
    integer(c_int64_t) :: nc
    integer(c_int) :: code
    nc = size(mu, kind=c_int64_t)
    message = check_sizes(nc, q, mu, r, u)
    if (len(message) == 0 .and. (size(w, 1, kind=c_int64_t) /= 3 * nc .or. &
        size(w, 2, kind=c_int64_t) /= 3 * nc)) then
      write (buffer, '(a,i0,a,i0,a,i0)') 'fc3d_solve: w is ', size(w, 1), ' x ', size(w, 2), &
          ', want 3nc x 3nc with nc = size(mu) = ', nc
      message = trim(buffer)
    end if
    handle = c_null_ptr
    owned = .false.
    if (len(message) > 0) then
      code = FC3D_ERR_INVALID_SIZE
    else
      call prepare(settings, solver, tolerance, max_iter, time_budget, local_solver, handle, &
          owned, code, message)
      if (code == FC3D_OK) code = fc3d_solve_dense(nc, w, q, mu, r, u, handle, res)
    end if
    call finish(code, handle, owned, message)
    info = int(code)
    if (present(errmsg)) errmsg = message
    if (code >= 0 .and. present(result)) result = res
  end subroutine solve_dense_array

  !> call fc3d_solve(row_ptr, col_idx, values, q, mu, r, u, info, ...) with W in compressed
  !> rows: row_ptr(3nc + 1), col_idx(nnz) 0-based, values(nnz), nnz = row_ptr(3nc + 1).
  subroutine solve_csr_arrays(row_ptr, col_idx, values, q, mu, r, u, info, solver, tolerance, &
      max_iter, time_budget, local_solver, settings, result, errmsg)
    integer(c_int64_t), intent(in) :: row_ptr(:), col_idx(:)
    real(c_double), intent(in) :: values(:), q(:), mu(:)
    real(c_double), intent(inout) :: r(:), u(:)
    integer, intent(out) :: info
    integer, intent(in), optional :: solver, max_iter, local_solver
    real(c_double), intent(in), optional :: tolerance, time_budget
    type(c_ptr), intent(in), optional :: settings
    type(fc3d_result), intent(inout), optional :: result
    character(len=:), allocatable, intent(out), optional :: errmsg
    type(c_ptr) :: handle
    logical :: owned
    character(len=:), allocatable :: message
    character(len=200) :: buffer
    type(fc3d_result) :: res
    integer(c_int64_t) :: nc, nnz
    integer(c_int) :: code
    nc = size(mu, kind=c_int64_t)
    nnz = size(values, kind=c_int64_t)
    message = check_sizes(nc, q, mu, r, u)
    if (len(message) == 0 .and. (size(row_ptr, kind=c_int64_t) /= 3 * nc + 1 .or. &
        size(col_idx, kind=c_int64_t) /= nnz)) then
      write (buffer, '(a,i0,a,i0,a,i0,a,i0,a)') 'fc3d_solve: size(row_ptr) = ', size(row_ptr), &
          ', size(col_idx) = ', size(col_idx), ', size(values) = ', size(values), &
          ' with nc = size(mu) = ', nc, ' (want 3nc + 1, nnz, nnz)'
      message = trim(buffer)
    end if
    handle = c_null_ptr
    owned = .false.
    if (len(message) > 0) then
      code = FC3D_ERR_INVALID_SIZE
    else
      call prepare(settings, solver, tolerance, max_iter, time_budget, local_solver, handle, &
          owned, code, message)
      if (code == FC3D_OK) &
          code = fc3d_solve_csr(nc, nnz, row_ptr, col_idx, values, q, mu, r, u, handle, res)
    end if
    call finish(code, handle, owned, message)
    info = int(code)
    if (present(errmsg)) errmsg = message
    if (code >= 0 .and. present(result)) result = res
  end subroutine solve_csr_arrays

  !> call fc3d_solve(problem, r, u, info, ...) with a problem from fc3d_problem_read, in the
  !> storage of its file.
  subroutine solve_problem(problem, r, u, info, solver, tolerance, max_iter, time_budget, &
      local_solver, settings, result, errmsg)
    type(c_ptr), intent(in) :: problem
    real(c_double), intent(inout) :: r(:), u(:)
    integer, intent(out) :: info
    integer, intent(in), optional :: solver, max_iter, local_solver
    real(c_double), intent(in), optional :: tolerance, time_budget
    type(c_ptr), intent(in), optional :: settings
    type(fc3d_result), intent(inout), optional :: result
    character(len=:), allocatable, intent(out), optional :: errmsg
    type(c_ptr) :: handle
    logical :: owned
    character(len=:), allocatable :: message
    character(len=200) :: buffer
    type(fc3d_result) :: res
    integer(c_int64_t) :: nc
    integer(c_int) :: code
    handle = c_null_ptr
    owned = .false.
    allocate(character(len=0) :: message)
    nc = fc3d_problem_contacts(problem)
    if (nc < 0) then
      code = fc3d_last_error_code()
    else if (size(r, kind=c_int64_t) /= 3 * nc .or. size(u, kind=c_int64_t) /= 3 * nc) then
      write (buffer, '(a,i0,a,i0,a,i0,a)') 'fc3d_solve: size(r) = ', size(r), ', size(u) = ', &
          size(u), ' for a problem of ', nc, ' contacts (want 3nc)'
      message = trim(buffer)
      code = FC3D_ERR_INVALID_SIZE
    else
      call prepare(settings, solver, tolerance, max_iter, time_budget, local_solver, handle, &
          owned, code, message)
      if (code == FC3D_OK) code = fc3d_problem_solve(problem, r, u, handle, res)
    end if
    call finish(code, handle, owned, message)
    info = int(code)
    if (present(errmsg)) errmsg = message
    if (code >= 0 .and. present(result)) result = res
  end subroutine solve_problem

  !> call fc3d_solve_global(m_row_ptr, m_col_idx, m_values, h_row_ptr, h_col_idx, h_values, q,
  !> b, mu, r, u, v, info, ...): M (n x n, n = size(q)) and H (n x 3nc) in compressed rows
  !> (row_ptr(n + 1), 0-based col_idx); b(3nc), mu(nc), r and u (3nc), v (n). Options as
  !> fc3d_solve's; the solver a global id (default FC3D_GFC3D_NSGS_WR), local_solver the local
  !> solver of a _WR id.
  subroutine fc3d_solve_global(m_row_ptr, m_col_idx, m_values, h_row_ptr, h_col_idx, h_values, &
      q, b, mu, r, u, v, info, solver, tolerance, max_iter, time_budget, local_solver, settings, &
      result, errmsg)
    integer(c_int64_t), intent(in) :: m_row_ptr(:), m_col_idx(:), h_row_ptr(:), h_col_idx(:)
    real(c_double), intent(in) :: m_values(:), h_values(:), q(:), b(:), mu(:)
    real(c_double), intent(inout) :: r(:), u(:), v(:)
    integer, intent(out) :: info
    integer, intent(in), optional :: solver, max_iter, local_solver
    real(c_double), intent(in), optional :: tolerance, time_budget
    type(c_ptr), intent(in), optional :: settings
    type(fc3d_result), intent(inout), optional :: result
    character(len=:), allocatable, intent(out), optional :: errmsg
    type(c_ptr) :: handle
    logical :: owned
    character(len=:), allocatable :: message
    character(len=300) :: buffer
    type(fc3d_result) :: res
    integer(c_int64_t) :: nc, n
    integer(c_int) :: code
    nc = size(mu, kind=c_int64_t)
    n = size(q, kind=c_int64_t)
    allocate(character(len=0) :: message)
    if (size(b, kind=c_int64_t) /= 3 * nc .or. size(r, kind=c_int64_t) /= 3 * nc .or. &
        size(u, kind=c_int64_t) /= 3 * nc .or. size(v, kind=c_int64_t) /= n .or. &
        size(m_row_ptr, kind=c_int64_t) /= n + 1 .or. size(h_row_ptr, kind=c_int64_t) /= n + 1 &
        .or. size(m_col_idx) /= size(m_values) .or. size(h_col_idx) /= size(h_values)) then
      write (buffer, '(a,12(i0,a))') 'fc3d_solve_global: sizes disagree: n = size(q) = ', n, &
          ', nc = size(mu) = ', nc, ', size(b) = ', size(b), ', size(r) = ', size(r), &
          ', size(u) = ', size(u), ', size(v) = ', size(v), ', size(m_row_ptr) = ', &
          size(m_row_ptr), ', size(h_row_ptr) = ', size(h_row_ptr), ', M ', size(m_col_idx), &
          '/', size(m_values), ' and H ', size(h_col_idx), '/', size(h_values), &
          ' indices/values (want b, r, u: 3nc; v: n; row_ptr: n + 1)'
      message = trim(buffer)
    end if
    handle = c_null_ptr
    owned = .false.
    if (len(message) > 0) then
      code = FC3D_ERR_INVALID_SIZE
    else
      call prepare(settings, solver, tolerance, max_iter, time_budget, local_solver, handle, &
          owned, code, message, default_solver=int(FC3D_GFC3D_NSGS_WR))
      if (code == FC3D_OK) code = fc3d_solve_global_csr(n, nc, size(m_values, kind=c_int64_t), &
          m_row_ptr, m_col_idx, m_values, size(h_values, kind=c_int64_t), h_row_ptr, h_col_idx, &
          h_values, q, b, mu, r, u, v, handle, res)
    end if
    call finish(code, handle, owned, message)
    info = int(code)
    if (present(errmsg)) errmsg = message
    if (code >= 0 .and. present(result)) result = res
  end subroutine fc3d_solve_global

end module fc3d

! A Fortran host of fc3d's native entry through the module fc3d (fc3d.f90): one sliding contact
! with its known answer (also solved by every solver the library lists), three coupled contacts
! solved in dense, CSR, COO and block storage by NSGS and NSN_AC (which must agree and satisfy
! the Coulomb law checked here independently), rejected input, and, for every path given, a
! Siconos .dat problem read with fc3d_problem_read and solved with NSGS (500) and NSN_AC (504) to
! 1e-8, and a global problem (M, H) solved by fc3d_solve_global with three global ids. Any wrong answer stops with `error stop` (non-zero exit status). Built from outside the
! source tree by scripts/test-fortran.sh:
!
!   export PKG_CONFIG_PATH=PREFIX/lib/pkgconfig LD_LIBRARY_PATH=PREFIX/lib
!   gfortran -c fc3d.f90 && gfortran example.f90 fc3d.o $(pkg-config --libs fc3d-native) -o example
!   ./example problem.dat [more.dat]
program fc3d_example
  use, intrinsic :: iso_c_binding
  use fc3d
  implicit none

  character(len=:), allocatable :: version
  character(len=4096) :: path
  integer :: k, n_args

  version = fc3d_version()
  print '(a,a)', 'fc3d ', version
  call check(len(version) >= 5 .and. scan(version(1:1), '0123456789') == 1, &
      'version string "' // version // '"')

  call single_contact()
  call every_solver()
  call coupled_contacts()
  call rejected_input()
  call global_contact()

  n_args = command_argument_count()
  do k = 1, n_args
    call get_command_argument(k, path)
    call shared_problem(trim(path))
  end do
  deallocate(version)
  print '(a)', 'fortran example: all checks passed'

contains

  ! Stops with a non-zero exit status when cond is false.
  subroutine check(cond, what)
    logical, intent(in) :: cond
    character(len=*), intent(in) :: what
    if (.not. cond) then
      write (*, '(a,a)') 'fortran example: FAILED: ', what
      write (*, '(a,a)') '  last fc3d error: ', fc3d_last_error_message()
      error stop 1
    end if
  end subroutine check

  ! One contact, W = I, q = (-1, 2, 0), mu = 0.5: it slides, r = (1, -0.5, 0), u = (0, 1.5, 0).
  subroutine single_contact()
    real(c_double) :: w(3, 3), q(3), mu(1), r(3), u(3), blocks(3, 3, 1)
    real(c_double), parameter :: r_want(3) = [1d0, -0.5d0, 0d0], u_want(3) = [0d0, 1.5d0, 0d0]
    integer(c_int64_t) :: row_ptr(2), col_idx(1)
    type(fc3d_result) :: res
    type(c_ptr) :: s
    character(len=:), allocatable :: msg
    integer :: info, solver, k
    integer, parameter :: solvers(2) = [FC3D_NSGS, FC3D_NSN_AC]

    w = 0
    do k = 1, 3
      w(k, k) = 1
    end do
    q = [-1.0d0, 2.0d0, 0.0d0]
    mu = [0.5d0]

    ! The Fortran wrapper, with each solver.
    do k = 1, 2
      solver = solvers(k)
      r = 0
      u = -7
      call fc3d_solve(w, q, mu, r, u, info, solver=solver, tolerance=1d-12, max_iter=100, &
          result=res, errmsg=msg)
      print '(a,i0,a,i0,a,i0,a,es10.3,a,3f9.5)', 'single contact, solver ', solver, ': info ', &
          info, ', ', res%iterations, ' iterations, error ', res%error, ', r =', r
      call check(info == 0 .and. res%info == 0 .and. len(msg) == 0, 'single contact: info')
      call check(maxval(abs(r - r_want)) < 1d-10 .and. maxval(abs(u - u_want)) < 1d-10, &
          'single contact: r and u')
      call check(res%error <= 1d-12 .and. res%iterations >= 1 .and. res%seconds >= 0, &
          'single contact: result')
    end do

    ! The bind(C) layer directly: settings, setters, the result struct, block storage.
    s = fc3d_settings_new(FC3D_NSGS)
    call check(c_associated(s), 'fc3d_settings_new(500)')
    call check(fc3d_settings_set_tolerance(s, 1d-12) == 0, 'set_tolerance')
    call check(fc3d_settings_set_max_iter(s, 100_c_int64_t) == 0, 'set_max_iter')
    call check(fc3d_settings_set(s, 'max_iter', 200d0) == 0, 'set by name')
    call check(fc3d_settings_set(s, 'iparam[7]', 0d0) == 0, 'set iparam[7] by name')
    call check(fc3d_settings_set_local_solver(s, FC3D_ONECONTACT_NSN_GP_HYBRID) == 0, &
        'set_local_solver')
    ! (Fortran may evaluate the operands of .and. in any order: one call per statement.)
    info = fc3d_settings_set(s, 'no_such_setting', 1d0)
    msg = fc3d_last_error_message()
    call check(info == FC3D_ERR_INVALID_OPTION .and. index(msg, 'no_such_setting') > 0, &
        'unknown setting name rejected')
    call check(fc3d_settings_set_iparam(s, 99, 1) == FC3D_ERR_INVALID_OPTION, &
        'iparam index 99 rejected')
    call check(fc3d_settings_set_time_budget(s, 60d0) == 0, 'set_time_budget')
    call check(fc3d_settings_set_dparam(s, 19, 60d0) == 0, 'set_dparam (time budget)')
    call check(fc3d_settings_set_local_iparam(s, 0, 50) == 0, 'set_local_iparam (local iterations)')
    call check(fc3d_settings_set_local_dparam(s, 0, 1d-14) == 0, &
        'set_local_dparam (local tolerance)')
    call check(c_sizeof(res) == 32_c_size_t, 'sizeof(Fc3dResult) is 32 bytes')
    r = 0
    res = fc3d_result(info=-42, iterations=-1, error=-1, seconds=-1)
    info = fc3d_solve_dense(1_c_int64_t, w, q, mu, r, u, s, res)
    call check(info == 0 .and. res%info == 0 .and. res%iterations >= 1 .and. res%error <= 1d-12, &
        'fc3d_solve_dense: result struct')
    call check(maxval(abs(r - r_want)) < 1d-10 .and. maxval(abs(u - u_want)) < 1d-10, &
        'fc3d_solve_dense: r and u')

    row_ptr = [0_c_int64_t, 1_c_int64_t]
    col_idx = [0_c_int64_t]
    blocks(:, :, 1) = w
    r = 0
    info = fc3d_solve_blocks(1_c_int64_t, 1_c_int64_t, row_ptr, col_idx, blocks, q, mu, r, u, s, &
        res)
    call check(info == 0 .and. maxval(abs(r - r_want)) < 1d-10, 'fc3d_solve_blocks')

    ! The same settings given to the wrapper.
    r = 0
    call fc3d_solve(w, q, mu, r, u, info, settings=s, result=res)
    call check(info == 0 .and. maxval(abs(r - r_want)) < 1d-10, 'wrapper with settings')
    call fc3d_settings_free(s)

    ! settings = NULL: NSGS with Siconos' defaults (tolerance 1e-4).
    r = 0
    info = fc3d_solve_dense(1_c_int64_t, w, q, mu, r, u, c_null_ptr, res)
    call check(info == 0 .and. abs(r(2) + 0.5d0) < 1d-4, 'fc3d_solve_dense with NULL settings')
  end subroutine single_contact

  ! Every solver the library lists (fc3d_solver_count, fc3d_solver_at) is one of the module's
  ! named constants and solves the sliding contact of single_contact (SOCLCP, a relaxation,
  ! reports that its solution is not a Coulomb one).
  subroutine every_solver()
    integer(c_int), parameter :: named(20) = [FC3D_AUTO, FC3D_NSGS, FC3D_PROX, FC3D_TFP, &
        FC3D_NSN_AC, FC3D_DSFP, FC3D_VI_FPP, FC3D_VI_EG, FC3D_HP, FC3D_FPP, FC3D_EG, &
        FC3D_NSN_FB, FC3D_ACLMFP, FC3D_SOCLCP, FC3D_NSN_NM, FC3D_NSN_AC_TEST, FC3D_PFP, &
        FC3D_ADMM, FC3D_QUARTIC, FC3D_QUARTIC_NU]
    real(c_double) :: w(3, 3), q(3), mu(1), r(3), u(3)
    real(c_double), parameter :: r_want(3) = [1d0, -0.5d0, 0d0]
    type(fc3d_result) :: res
    type(c_ptr) :: constant, name
    integer(c_int) :: k, id, count
    integer :: info

    count = fc3d_solver_count()
    call check(count == size(named), 'fc3d_solver_count: every listed solver has a constant')
    w = 0
    w(1, 1) = 1
    w(2, 2) = 1
    w(3, 3) = 1
    q = [-1d0, 2d0, 0d0]
    mu = [0.5d0]
    do k = 0, count - 1
      id = fc3d_solver_at(k, constant, name)
      call check(any(named == id) .and. c_associated(constant) .and. c_associated(name), &
          'fc3d_solver_at: a named solver')
      r = 0
      call fc3d_solve(w, q, mu, r, u, info, solver=id, tolerance=1d-10, result=res)
      if (id == FC3D_SOCLCP) then
        call check(info == FC3D_RELAXED_NOT_COULOMB, 'SOCLCP: relaxed solution')
      else
        call check(info == 0 .and. maxval(abs(r - r_want)) < 1d-7, 'every solver: sliding contact')
      end if
    end do
    call check(fc3d_solver_at(count, constant, name) == FC3D_ERR_INVALID_SIZE, &
        'fc3d_solver_at: index out of range')
    print '(a,i0,a)', 'every solver: the library lists ', count, &
        ', each a named constant, each solves the sliding contact'
  end subroutine every_solver

  ! Three coupled contacts: sticking, sliding and taking off, with friction 0.5, 0.3, 0.8.
  subroutine coupled_contacts()
    integer, parameter :: nc = 3, n = 3 * nc
    real(c_double) :: w(n, n), q(n), mu(nc), r(n), u(n), r_ref(n), u_ref(n)
    integer(c_int64_t), allocatable :: row_ptr(:), col_idx(:), rows(:), cols(:), b_ptr(:), b_idx(:)
    real(c_double), allocatable :: values(:), blocks(:, :, :)
    type(fc3d_result) :: res
    type(c_ptr) :: s
    integer :: info, i, j, nb, solver, k
    integer, parameter :: solvers(2) = [FC3D_NSGS, FC3D_NSN_AC]

    w = 0
    do i = 1, n
      w(i, i) = 2
    end do
    call couple(w, 1, 4, 0.5d0)    ! normal 1 - normal 2
    call couple(w, 4, 7, 0.5d0)    ! normal 2 - normal 3
    call couple(w, 2, 5, 0.2d0)    ! tangent 1 of contacts 1 and 2
    call couple(w, 1, 5, 0.1d0)
    call couple(w, 3, 9, -0.1d0)
    q = [-1.0d0, 0.2d0, 0.0d0, -2.0d0, 3.0d0, 1.0d0, 0.5d0, 0.0d0, 0.0d0]
    mu = [0.5d0, 0.3d0, 0.8d0]

    ! Reference: the dense wrapper with NSN_AC; every other storage and solver must agree.
    r_ref = 0
    call fc3d_solve(w, q, mu, r_ref, u_ref, info, solver=FC3D_NSN_AC, tolerance=1d-12, result=res)
    call check(info == 0 .and. res%error <= 1d-12, 'coupled: NSN_AC dense')
    call check_solution(w, q, mu, r_ref, u_ref, res, 1d-12, 'coupled: NSN_AC dense')
    print '(a,i0,a,es10.3)', 'coupled contacts, NSN_AC dense: ', res%iterations, &
        ' iterations, error ', res%error
    print '(a,9f9.5)', '  r =', r_ref
    print '(a,9f9.5)', '  u =', u_ref
    call check(r_ref(7) == 0 .and. u_ref(7) > 0, 'coupled: contact 3 takes off')
    call check(abs(norm2(r_ref(5:6)) - mu(2) * r_ref(4)) < 1d-9 .and. norm2(u_ref(5:6)) > 1d-3, &
        'coupled: contact 2 slides')
    call check(norm2(r_ref(2:3)) < mu(1) * r_ref(1) .and. norm2(u_ref(1:3)) < 1d-9, &
        'coupled: contact 1 sticks')

    ! W in compressed rows, triplets and 3x3 blocks, from the dense array.
    allocate(row_ptr(n + 1), col_idx(0), values(0), rows(0), cols(0))
    row_ptr(1) = 0
    do i = 1, n
      do j = 1, n
        if (w(i, j) /= 0) then
          col_idx = [col_idx, int(j - 1, c_int64_t)]
          values = [values, w(i, j)]
          rows = [rows, int(i - 1, c_int64_t)]
          cols = [cols, int(j - 1, c_int64_t)]
        end if
      end do
      row_ptr(i + 1) = size(values)
    end do
    allocate(b_ptr(nc + 1), b_idx(0), blocks(3, 3, 0))
    b_ptr(1) = 0
    nb = 0
    do i = 1, nc
      do j = 1, nc
        if (any(w(3 * i - 2:3 * i, 3 * j - 2:3 * j) /= 0)) then
          nb = nb + 1
          b_idx = [b_idx, int(j - 1, c_int64_t)]
          blocks = reshape([reshape(blocks, [9 * (nb - 1)]), &
              reshape(w(3 * i - 2:3 * i, 3 * j - 2:3 * j), [9])], [3, 3, nb])
        end if
      end do
      b_ptr(i + 1) = nb
    end do

    do k = 1, 2
      solver = solvers(k)
      s = fc3d_settings_new(solver)
      call check(c_associated(s), 'coupled: settings')
      call check(fc3d_settings_set_tolerance(s, 1d-12) == 0, 'coupled: tolerance')
      call check(fc3d_settings_set_max_iter(s, 1000_c_int64_t) == 0, 'coupled: max_iter')

      r = 0
      call fc3d_solve(w, q, mu, r, u, info, settings=s, result=res)
      call agree('dense (wrapper)', solver, info, res, w, q, mu, r, u, r_ref, u_ref)
      r = 0
      call fc3d_solve(row_ptr, col_idx, values, q, mu, r, u, info, settings=s, result=res)
      call agree('CSR (wrapper)', solver, info, res, w, q, mu, r, u, r_ref, u_ref)
      r = 0
      info = fc3d_solve_csr(int(nc, c_int64_t), int(size(values), c_int64_t), row_ptr, col_idx, &
          values, q, mu, r, u, s, res)
      call agree('fc3d_solve_csr', solver, info, res, w, q, mu, r, u, r_ref, u_ref)
      r = 0
      info = fc3d_solve_coo(int(nc, c_int64_t), int(size(values), c_int64_t), rows, cols, values, &
          q, mu, r, u, s, res)
      call agree('fc3d_solve_coo', solver, info, res, w, q, mu, r, u, r_ref, u_ref)
      r = 0
      info = fc3d_solve_blocks(int(nc, c_int64_t), int(nb, c_int64_t), b_ptr, b_idx, blocks, q, &
          mu, r, u, s, res)
      call agree('fc3d_solve_blocks', solver, info, res, w, q, mu, r, u, r_ref, u_ref)
      call fc3d_settings_free(s)
    end do

  end subroutine coupled_contacts

  subroutine couple(a, i1, i2, v)
    real(c_double), intent(inout) :: a(:, :)
    integer, intent(in) :: i1, i2
    real(c_double), intent(in) :: v
    a(i1, i2) = v
    a(i2, i1) = v
  end subroutine couple

  ! A coupled-contacts solve: converged, equal to the reference, and a Coulomb solution.
  subroutine agree(storage, solver, info, res, w, q, mu, r, u, r_ref, u_ref)
    character(len=*), intent(in) :: storage
    integer, intent(in) :: solver, info
    type(fc3d_result), intent(in) :: res
    real(c_double), intent(in) :: w(:, :), q(:), mu(:), r(:), u(:), r_ref(:), u_ref(:)
    character(len=80) :: what
    write (what, '(a,a,a,i0)') 'coupled: ', storage, ', solver ', solver
    call check(info == 0 .and. res%info == 0, trim(what) // ': info')
    call check(maxval(abs(r - r_ref)) < 1d-9 .and. maxval(abs(u - u_ref)) < 1d-9, &
        trim(what) // ': agreement with the reference')
    call check_solution(w, q, mu, r, u, res, 1d-12, trim(what))
  end subroutine agree

  ! Bad input is rejected with a negative code, r and u unchanged, and a message saying why.
  subroutine rejected_input()
    real(c_double) :: w(3, 3), q(3), mu(1), r(3), u(3), w_small(2, 2)
    type(fc3d_result) :: res
    character(len=:), allocatable :: msg
    type(c_ptr) :: s, p
    integer :: info

    w = reshape([1d0, 0d0, 0d0, 0d0, 1d0, 0d0, 0d0, 0d0, 1d0], [3, 3])
    q = [-1d0, 2d0, 0d0]
    r = 7
    u = 7
    res = fc3d_result(info=42, iterations=42, error=42, seconds=42)

    call fc3d_solve(w, q, [-1d0], r, u, info, result=res, errmsg=msg)
    call check(info == FC3D_ERR_INVALID_PROBLEM .and. index(msg, 'mu') > 0, 'negative mu: ' // msg)
    call check(all(r == 7) .and. all(u == 7) .and. res%info == 42, &
        'negative mu: outputs untouched')
    info = fc3d_last_error_code()
    call check(info == FC3D_ERR_INVALID_PROBLEM, 'negative mu: last error code')

    mu = 0.5d0
    call fc3d_solve(w, [-1d0, ieee_nan(), 0d0], mu, r, u, info, errmsg=msg)
    call check(info == FC3D_ERR_NON_FINITE .and. all(r == 7), 'NaN in q: ' // msg)

    call fc3d_solve(w, q, mu, r, u, info, solver=4242, errmsg=msg)
    call check(info == FC3D_ERR_UNSUPPORTED_SOLVER .and. index(msg, '4242') > 0, &
        'unknown solver: ' // msg)
    s = fc3d_settings_new(4242)
    info = fc3d_last_error_code()
    call check(.not. c_associated(s) .and. info == FC3D_ERR_UNSUPPORTED_SOLVER, &
        'fc3d_settings_new(4242) is NULL')

    call fc3d_solve(w, q, mu, r, u, info, tolerance=-1d0, errmsg=msg)
    call check(info == FC3D_ERR_INVALID_OPTION .and. all(r == 7), 'negative tolerance: ' // msg)

    call fc3d_solve(w, q, mu, r, u, info, local_solver=FC3D_NSN_AC, errmsg=msg)
    call check(info == FC3D_ERR_INVALID_OPTION, '504 as local solver: ' // msg)

    call fc3d_solve(w_small, q, mu, r, u, info, errmsg=msg)
    call check(info == FC3D_ERR_INVALID_SIZE .and. index(msg, 'w is 2 x 2') > 0 .and. &
        all(r == 7), 'wrong size of w: ' // msg)
    call fc3d_solve(w, q, mu, r(1:2), u, info, errmsg=msg)
    call check(info == FC3D_ERR_INVALID_SIZE .and. all(r == 7), 'wrong size of r: ' // msg)

    s = fc3d_settings_new(FC3D_NSGS)
    call fc3d_solve(w, q, mu, r, u, info, settings=s, solver=FC3D_NSGS, errmsg=msg)
    call check(info == FC3D_ERR_INVALID_OPTION, 'settings and solver together: ' // msg)
    call fc3d_settings_free(s)
    call fc3d_settings_free(c_null_ptr)
    s = fc3d_settings_new(FC3D_NSN_AC)
    info = fc3d_settings_set_local_iparam(s, 0, 1)
    call check(info == FC3D_ERR_INVALID_OPTION, 'NSN_AC has no local solver')
    call fc3d_settings_free(s)

    info = fc3d_solve_dense(-1_c_int64_t, w, q, mu, r, u, c_null_ptr, res)
    call check(info == FC3D_ERR_INVALID_SIZE .and. res%info == 42, 'n_contacts = -1')

    p = fc3d_problem_read('/nonexistent/problem.dat')
    info = fc3d_last_error_code()
    msg = fc3d_last_error_message()
    call check(.not. c_associated(p) .and. info == FC3D_ERR_IO .and. &
        index(msg, '/nonexistent/problem.dat') > 0, 'missing file: ' // msg)
    call check(fc3d_problem_contacts(c_null_ptr) == -1, 'fc3d_problem_contacts(NULL)')
    call fc3d_problem_free(c_null_ptr)
    call fc3d_solve(c_null_ptr, r, u, info, errmsg=msg)
    call check(info == FC3D_ERR_NULL_POINTER, 'solve a NULL problem: ' // msg)

    call fc3d_clear_last_error()
    info = fc3d_last_error_code()
    msg = fc3d_last_error_message()
    call check(info == 0 .and. len(msg) == 0, 'fc3d_clear_last_error')
    print '(a)', 'rejected input: negative mu, NaN, unknown solver, bad options and sizes, ' // &
        'missing file: all rejected with their messages'
  end subroutine rejected_input

  function ieee_nan() result(x)
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    real(c_double) :: x
    x = ieee_value(x, ieee_quiet_nan)
  end function ieee_nan

  ! A Siconos .dat problem, read and solved with NSGS and NSN_AC to 1e-8.
  subroutine shared_problem(path)
    character(len=*), intent(in) :: path
    type(c_ptr) :: p, s
    integer(c_int64_t) :: nc, nnz
    integer(c_int64_t), allocatable :: row_ptr(:), col_idx(:)
    real(c_double), allocatable :: values(:), q(:), mu(:), r(:), u(:), r_file(:), u_file(:)
    type(fc3d_result) :: res
    character(len=:), allocatable :: msg
    integer :: info, k, solver
    integer, parameter :: solvers(2) = [FC3D_NSGS, FC3D_NSN_AC]
    real(c_double), parameter :: tol = 1d-8

    p = fc3d_problem_read(path)
    call check(c_associated(p), 'read ' // path)
    nc = fc3d_problem_contacts(p)
    nnz = fc3d_problem_nnz(p)
    call check(nc > 0 .and. nnz > 0, path // ': sizes')
    allocate(row_ptr(3 * nc + 1), col_idx(nnz), values(nnz), q(3 * nc), mu(nc))
    allocate(r(3 * nc), u(3 * nc), r_file(3 * nc), u_file(3 * nc))
    call check(fc3d_problem_get(p, row_ptr, col_idx, values, q, mu) == 0, path // ': get')
    call check(row_ptr(1) == 0 .and. row_ptr(3 * nc + 1) == nnz .and. all(mu >= 0), &
        path // ': structure')

    do k = 1, 2
      solver = solvers(k)
      ! In the file's storage, through the bind(C) layer.
      s = fc3d_settings_new(solver)
      call check(fc3d_settings_set_tolerance(s, tol) == 0, 'tolerance')
      call check(fc3d_settings_set_max_iter(s, 100000_c_int64_t) == 0, 'max_iter')
      r_file = 0
      info = fc3d_problem_solve(p, r_file, u_file, s, res)
      print '(a,a,i0,a,i0,a,i0,a,i0,a,es10.3,a,f9.3,a)', path, ': solver ', solver, ', ', nc, &
          ' contacts: info ', info, ', ', res%iterations, ' iterations, error ', res%error, ', ', &
          1d3 * res%seconds, ' ms'
      call check(info == 0 .and. res%info == 0 .and. res%error <= tol, path // ': file storage')
      call check_csr_solution(row_ptr, col_idx, values, q, mu, r_file, u_file, res, tol, path)
      call fc3d_settings_free(s)

      ! In compressed rows, through the wrapper with keyword options.
      r = 0
      call fc3d_solve(row_ptr, col_idx, values, q, mu, r, u, info, solver=solver, tolerance=tol, &
          max_iter=100000, result=res, errmsg=msg)
      call check(info == 0 .and. res%error <= tol .and. len(msg) == 0, path // ': CSR wrapper')
      call check_csr_solution(row_ptr, col_idx, values, q, mu, r, u, res, tol, path)
    end do
    call fc3d_problem_free(p)
  end subroutine shared_problem

  ! Checks a dense solution independently: u = W r + q, and the natural-map error computed here
  ! agrees with the library's.
  subroutine check_solution(w, q, mu, r, u, res, tol, what)
    real(c_double), intent(in) :: w(:, :), q(:), mu(:), r(:), u(:), tol
    type(fc3d_result), intent(in) :: res
    character(len=*), intent(in) :: what
    real(c_double) :: err
    call check(maxval(abs(matmul(w, r) + q - u)) <= 1d-12 * max(1d0, maxval(abs(u))), &
        what // ': u = W r + q')
    err = natural_map_error(q, mu, r, u)
    call check(err <= tol * (1 + 1d-6) + 1d-15 .and. &
        abs(err - res%error) <= 1d-3 * max(err, res%error) + 1d-15, &
        what // ': natural-map error recomputed')
  end subroutine check_solution

  ! The same with W in 0-based compressed rows.
  subroutine check_csr_solution(row_ptr, col_idx, values, q, mu, r, u, res, tol, what)
    integer(c_int64_t), intent(in) :: row_ptr(:), col_idx(:)
    real(c_double), intent(in) :: values(:), q(:), mu(:), r(:), u(:), tol
    type(fc3d_result), intent(in) :: res
    character(len=*), intent(in) :: what
    real(c_double) :: wr(size(q)), err
    integer(c_int64_t) :: i, k
    wr = 0
    do i = 1, size(q, kind=c_int64_t)
      do k = row_ptr(i) + 1, row_ptr(i + 1)
        wr(i) = wr(i) + values(k) * r(col_idx(k) + 1)
      end do
    end do
    call check(maxval(abs(wr + q - u)) <= 1d-10 * max(1d0, maxval(abs(u)), maxval(abs(q))), &
        what // ': u = W r + q')
    err = natural_map_error(q, mu, r, u)
    call check(err <= tol * (1 + 1d-6) .and. &
        abs(err - res%error) <= 1d-3 * max(err, res%error) + 1d-15, &
        what // ': natural-map error recomputed')
  end subroutine check_csr_solution

  ! ||r - P_K(r - u~)|| / max(||q||, ||r||, ||u||) with u~ = (u_N + mu ||u_T||, u_T), computed
  ! here from the definition (README.md), independently of the library.
  function natural_map_error(q, mu, r, u) result(err)
    real(c_double), intent(in) :: q(:), mu(:), r(:), u(:)
    real(c_double) :: err, z(3), t, scale
    integer :: c, i
    err = 0
    do c = 1, size(mu)
      i = 3 * c - 2
      z = r(i:i + 2) - u(i:i + 2)
      z(1) = z(1) - mu(c) * norm2(u(i + 1:i + 2))
      t = norm2(z(2:3))
      if (t <= mu(c) * z(1)) then
        continue
      else if (mu(c) * t <= -z(1)) then
        z = 0
      else
        z(1) = (z(1) + mu(c) * t) / (1 + mu(c)**2)
        z(2:3) = mu(c) * z(1) * z(2:3) / t
      end if
      err = err + sum((r(i:i + 2) - z)**2)
    end do
    scale = max(norm2(q), norm2(r), norm2(u))
    err = sqrt(err)
    if (scale > 0) err = err / scale
  end function natural_map_error

  ! The global form of a sliding contact: a body of mass 2 (M = 2 I), H = I, q = M (-1, 2, 0),
  ! b = 0, mu = 0.5: r = (2, -1, 0), u = v = (0, 1.5, 0), and M v = q + H r.
  subroutine global_contact()
    integer(c_int64_t), parameter :: ptr(4) = [0_c_int64_t, 1_c_int64_t, 2_c_int64_t, 3_c_int64_t]
    integer(c_int64_t), parameter :: idx(3) = [0_c_int64_t, 1_c_int64_t, 2_c_int64_t]
    real(c_double), parameter :: m(3) = [2d0, 2d0, 2d0], h(3) = [1d0, 1d0, 1d0]
    real(c_double), parameter :: q(3) = [-2d0, 4d0, 0d0], b(3) = 0d0, mu(1) = 0.5d0
    real(c_double), parameter :: r_want(3) = [2d0, -1d0, 0d0], v_want(3) = [0d0, 1.5d0, 0d0]
    integer, parameter :: solvers(3) = [FC3D_GFC3D_NSGS_WR, FC3D_GFC3D_NSGS, FC3D_GFC3D_NSN_AC]
    real(c_double) :: r(3), u(3), v(3)
    type(fc3d_result) :: res
    character(len=:), allocatable :: msg
    integer :: info, k
    do k = 1, size(solvers)
      r = 0
      call fc3d_solve_global(ptr, idx, m, ptr, idx, h, q, b, mu, r, u, v, info, &
          solver=solvers(k), tolerance=1d-10, max_iter=1000, result=res, errmsg=msg)
      call check(info == FC3D_OK .and. res%info == FC3D_OK .and. res%error <= 1d-10, &
          'global solve converges: ' // msg)
      call check(maxval(abs(r - r_want)) < 1d-6 .and. maxval(abs(v - v_want)) < 1d-6 .and. &
          maxval(abs(u - v_want)) < 1d-6, 'global solve: known r, u, v')
      call check(maxval(abs(m * v - q - h * r)) < 1d-12, 'global solve: M v = q + H r')
    end do
    call fc3d_solve_global(ptr, idx, m, ptr, idx, h, q, b, mu, r, u, v, info, errmsg=msg)
    call check(info == FC3D_OK, 'global solve with the default solver (600)')
    r = -7
    call fc3d_solve_global(ptr, idx, m, ptr, idx, h, q, b, mu, r, u, v, info, solver=FC3D_NSGS, &
        errmsg=msg)
    call check(info == FC3D_ERR_UNSUPPORTED_SOLVER .and. index(msg, 'global') > 0 .and. &
        all(r == -7), 'a local id is refused by the global solve, nothing written')
    call fc3d_solve_global(ptr, idx, m, ptr, idx, h, q, b, mu, r, u, v(1:2), info, errmsg=msg)
    call check(info == FC3D_ERR_INVALID_SIZE, 'global solve: wrong size of v')
    print '(a)', 'global contact: solved by 600, 605, 607; refusals checked'
  end subroutine global_contact

end program fc3d_example

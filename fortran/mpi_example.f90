! A Fortran MPI host of fc3d's distributed solve (module fc3d_mpi): a chain of contacts split in
! contiguous ranges over the ranks, each rank giving its block rows with global ids 3c + 1, the
! communicator passed as its INTEGER handle. Prints, on rank 0, info, sweeps and the bits of the
! error: the same line for any number of ranks (scripts/test-all.sh compares np 1 and np 3).
!
!   mpifort fc3d.f90 fc3d_mpi.f90 mpi_example.f90 $(pkg-config --libs fc3d-mpi) -o mpi_example
!   mpirun -np 3 ./mpi_example
program mpi_example
  use, intrinsic :: iso_c_binding
  use mpi
  use fc3d, only: fc3d_result, fc3d_settings_new, fc3d_settings_free, &
      fc3d_settings_set_tolerance, fc3d_settings_set_max_iter, fc3d_last_error_message
  use fc3d_mpi
  implicit none
  integer, parameter :: nc = 600
  integer :: ierr, rank, nranks, first, last, c, k, d
  integer(c_int64_t) :: n_local, n_blocks
  integer(c_int64_t), allocatable :: ids(:), row_ptr(:), cols(:)
  real(c_double), allocatable :: blocks(:), q(:), mu(:), r(:), u(:), r2(:)
  type(c_ptr) :: settings, solver
  type(fc3d_result) :: res, res2
  type(fc3d_mpi_stats) :: stats
  integer(c_int) :: info

  call MPI_Init(ierr)
  call MPI_Comm_rank(MPI_COMM_WORLD, rank, ierr)
  call MPI_Comm_size(MPI_COMM_WORLD, nranks, ierr)
  first = rank * nc / nranks
  last = (rank + 1) * nc / nranks - 1
  n_local = last - first + 1
  allocate(ids(n_local), row_ptr(n_local + 1), cols(3 * n_local), blocks(27 * n_local))
  allocate(q(3 * n_local), mu(n_local), r(3 * n_local), u(3 * n_local), r2(3 * n_local))
  ! Row of contact c: W_c,c-1 = -0.5 I, W_cc = 2 I (+ 0.1 coupling normal/tangent 1, not
  ! symmetric), W_c,c+1 = -0.5 I.
  n_blocks = 0
  row_ptr(1) = 0
  do k = 1, int(n_local)
    c = first + k - 1
    ids(k) = 3 * c + 1
    do d = max(c - 1, 0), min(c + 1, nc - 1)
      n_blocks = n_blocks + 1
      cols(n_blocks) = 3 * d + 1
      blocks(9 * n_blocks - 8:9 * n_blocks) = 0
      if (d == c) then
        blocks(9 * n_blocks - 8) = 2
        blocks(9 * n_blocks - 4) = 2
        blocks(9 * n_blocks) = 2
        blocks(9 * n_blocks - 5) = 0.1d0
      else
        blocks(9 * n_blocks - 8) = -0.5d0
        blocks(9 * n_blocks - 4) = -0.5d0
        blocks(9 * n_blocks) = -0.5d0
      end if
    end do
    row_ptr(k + 1) = n_blocks
    q(3 * k - 2) = -1 + 0.5d0 * sin(real(c, c_double))
    q(3 * k - 1) = 0.3d0 * cos(real(c, c_double))
    q(3 * k) = 0.2d0
    mu(k) = 0.3d0
  end do
  r = 0
  settings = fc3d_settings_new(500_c_int)
  if (fc3d_settings_set_tolerance(settings, 1d-10) /= 0) stop 1
  if (fc3d_settings_set_max_iter(settings, 500_c_int64_t) /= 0) stop 1
  info = fc3d_mpi_solve_blocks_f(MPI_COMM_WORLD, n_local, ids, n_blocks, row_ptr, cols, blocks, &
      q, mu, r, u, settings, res)
  if (info < 0) then
    print *, 'fc3d_mpi_solve_blocks_f: ', fc3d_last_error_message()
    call MPI_Abort(MPI_COMM_WORLD, 1, ierr)
  end if
  ! The same with a solver kept for time stepping: the same bits.
  solver = fc3d_mpi_solver_new_f(MPI_COMM_WORLD, FC3D_MPI_REPRODUCIBLE)
  if (.not. c_associated(solver)) call MPI_Abort(MPI_COMM_WORLD, 1, ierr)
  r2 = 0
  info = fc3d_mpi_solver_solve(solver, n_local, ids, n_blocks, row_ptr, cols, blocks, q, mu, &
      r2, u, settings, res2)
  if (info < 0 .or. any(r2 /= r) .or. res2%iterations /= res%iterations &
      .or. res2%error /= res%error) then
    print *, 'the solver handle gave another result'
    call MPI_Abort(MPI_COMM_WORLD, 1, ierr)
  end if
  if (fc3d_mpi_solver_stats(solver, stats) /= 0 .or. stats%total_contacts /= nc) then
    call MPI_Abort(MPI_COMM_WORLD, 1, ierr)
  end if
  call fc3d_mpi_solver_free(solver)
  call fc3d_settings_free(settings)
  if (rank == 0) print '(a, i0, a, i0, a, z16.16, a, es10.3)', 'info ', res%info, ' sweeps ', &
      res%iterations, ' error bits ', transfer(res%error, 0_c_int64_t), ' error ', res%error
  call MPI_Finalize(ierr)
end program mpi_example

! Fortran bindings of fc3d's distributed solve (fc3d_mpi.h, libfc3d_mpi) for MPI hosts: the
! communicator is the INTEGER handle of `use mpi` (MPI_COMM_WORLD, or comm%MPI_VAL of `use
! mpi_f08`), passed by value to the C entries ending in _f, which convert it with MPI_Comm_f2c.
! Needs the module fc3d (fc3d.f90) for fc3d_result and the settings functions. Installed as
! source to PREFIX/share/fc3d/fortran/fc3d_mpi.f90:
!
!   mpifort -c PREFIX/share/fc3d/fortran/fc3d.f90 PREFIX/share/fc3d/fortran/fc3d_mpi.f90
!   mpifort my_program.f90 fc3d.o fc3d_mpi.o $(pkg-config --libs fc3d-mpi) -o my_program
!
! Every call is collective over the communicator (fc3d_mpi_solver_stats excepted). Arguments as
! in fc3d_mpi.h: this rank's n_local contacts with their global ids (integer(c_int64_t), any
! order), its block rows (block_row_ptr 0-based, n_local + 1 entries; block_col_ids the GLOBAL
! id of each block's column; 9 values per block, column-major), q, mu, r (warm start, receives
! the result) and u; the result is the same on every rank; a negative return is the same code
! and message on every rank, nothing written.
module fc3d_mpi
  use, intrinsic :: iso_c_binding
  use fc3d, only: fc3d_result
  implicit none
  private

  integer(c_int), parameter, public :: FC3D_MPI_ERR_COMMUNICATION = -20
  integer(c_int), parameter, public :: FC3D_MPI_REPRODUCIBLE = 0
  integer(c_int), parameter, public :: FC3D_MPI_FAST = 1

  ! What fc3d_mpi_solver_stats reports for the calling rank (Fc3dMpiStats).
  type, bind(C), public :: fc3d_mpi_stats
    integer(c_int) :: ranks = 0
    integer(c_int) :: mode = 0
    integer(c_int64_t) :: colours = 0, colouring_rounds = 0, contacts = 0, total_contacts = 0
    integer(c_int64_t) :: ghosts = 0, boundary = 0, neighbours = 0
    integer(c_int64_t) :: messages_per_sweep = 0, bytes_per_sweep = 0
    integer(c_int64_t) :: setups = 0, solves = 0, sweeps = 0
    real(c_double) :: seconds_setup = 0, seconds_compute = 0, seconds_wait = 0
    real(c_double) :: cpu_seconds_compute = 0
  end type fc3d_mpi_stats

  public :: fc3d_mpi_solve_blocks_f, fc3d_mpi_solver_new_f, fc3d_mpi_solver_solve
  public :: fc3d_mpi_solver_stats, fc3d_mpi_solver_free

  interface
    function fc3d_mpi_solve_blocks_f(comm, n_local, contact_ids, n_blocks, block_row_ptr, &
        block_col_ids, blocks, q, mu, r, u, settings, result) &
        bind(C, name="fc3d_mpi_solve_blocks_f") result(info)
      import :: c_int, c_int64_t, c_double, c_ptr, fc3d_result
      integer(c_int), value :: comm
      integer(c_int64_t), value :: n_local, n_blocks
      integer(c_int64_t), intent(in) :: contact_ids(*), block_row_ptr(*), block_col_ids(*)
      real(c_double), intent(in) :: blocks(*), q(*), mu(*)
      real(c_double), intent(inout) :: r(*), u(*)
      type(c_ptr), value :: settings
      type(fc3d_result), intent(out) :: result
      integer(c_int) :: info
    end function fc3d_mpi_solve_blocks_f

    function fc3d_mpi_solver_new_f(comm, mode) bind(C, name="fc3d_mpi_solver_new_f") &
        result(solver)
      import :: c_int, c_ptr
      integer(c_int), value :: comm, mode
      type(c_ptr) :: solver
    end function fc3d_mpi_solver_new_f

    function fc3d_mpi_solver_solve(solver, n_local, contact_ids, n_blocks, block_row_ptr, &
        block_col_ids, blocks, q, mu, r, u, settings, result) &
        bind(C, name="fc3d_mpi_solver_solve") result(info)
      import :: c_int, c_int64_t, c_double, c_ptr, fc3d_result
      type(c_ptr), value :: solver
      integer(c_int64_t), value :: n_local, n_blocks
      integer(c_int64_t), intent(in) :: contact_ids(*), block_row_ptr(*), block_col_ids(*)
      real(c_double), intent(in) :: blocks(*), q(*), mu(*)
      real(c_double), intent(inout) :: r(*), u(*)
      type(c_ptr), value :: settings
      type(fc3d_result), intent(out) :: result
      integer(c_int) :: info
    end function fc3d_mpi_solver_solve

    function fc3d_mpi_solver_stats(solver, stats) bind(C, name="fc3d_mpi_solver_stats") &
        result(info)
      import :: c_int, c_ptr, fc3d_mpi_stats
      type(c_ptr), value :: solver
      type(fc3d_mpi_stats), intent(out) :: stats
      integer(c_int) :: info
    end function fc3d_mpi_solver_stats

    subroutine fc3d_mpi_solver_free(solver) bind(C, name="fc3d_mpi_solver_free")
      import :: c_ptr
      type(c_ptr), value :: solver
    end subroutine fc3d_mpi_solver_free
  end interface
end module fc3d_mpi

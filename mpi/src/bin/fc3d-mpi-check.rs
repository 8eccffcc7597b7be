//! The check program of fc3d-mpi's tests (tests/mpirun.rs runs it under `mpirun -np 1..4`): it
//! splits problems over the ranks as a host would and solves them through the C entries, then
//! writes each rank's results (bits of r and u by global id, info, sweeps, error) to files the
//! test compares across process counts and partitions.
//!
//!   fc3d-mpi-check OUT_DIR solve NAME PROBLEM TOL MAX_ITER   every partition, reproducible mode
//!   fc3d-mpi-check OUT_DIR errors PROBLEM                    rejected inputs, then a good solve
//!   fc3d-mpi-check OUT_DIR handle PROBLEM                    a reused solver, the fast mode
//!
//! PROBLEM is a `.dat` path or `gen:contacts=N,piles=P,seed=S`; several commands may follow one
//! another, separated by `--`.

#[cfg(fc3d_no_mpi)]
fn main() {
    eprintln!("fc3d-mpi-check: built without MPI");
    std::process::exit(2);
}

#[cfg(not(fc3d_no_mpi))]
fn main() {
    check::main()
}

#[cfg(not(fc3d_no_mpi))]
mod check {
    use std::ffi::{c_char, c_int, CStr};
    use std::fmt::Write as _;
    use std::path::{Path, PathBuf};

    use fc3d::{Fc3dResult, Fc3dSettings};
    use fc3d_mpi::comm::Comm;
    use fc3d_mpi::ffi::{self, MpiComm};
    use fc3d_mpi::problems::{Partition, RankRows, WholeProblem};
    use fc3d_mpi::*;

    // The native entry, declared as a C host declares it (Fc3dSettings is opaque).
    #[allow(improper_ctypes)]
    extern "C" {
        fn fc3d_settings_new(id: c_int) -> *mut Fc3dSettings;
        fn fc3d_settings_free(s: *mut Fc3dSettings);
        fn fc3d_settings_set_tolerance(s: *mut Fc3dSettings, tol: f64) -> c_int;
        fn fc3d_settings_set_max_iter(s: *mut Fc3dSettings, n: i64) -> c_int;
        fn fc3d_last_error_message() -> *const c_char;
    }

    struct World {
        comm: MpiComm,
        rank: usize,
        size: usize,
        out: PathBuf,
    }

    pub fn main() {
        let args: Vec<String> = std::env::args().skip(1).collect();
        assert!(args.len() >= 2, "usage: fc3d-mpi-check OUT_DIR COMMAND ...");
        // SAFETY: plain MPI set-up of this program.
        let comm = unsafe {
            assert_eq!(ffi::fc3d_mpi_shim_init(), 0, "MPI_Init");
            let mut comm: MpiComm = std::mem::zeroed();
            ffi::fc3d_mpi_shim_world(&mut comm);
            comm
        };
        let (rank, size) = {
            let c = unsafe { Comm::duplicate(&comm) }.expect("a communicator");
            (c.rank(), c.size())
        };
        let world = World {
            comm,
            rank,
            size,
            out: PathBuf::from(&args[0]),
        };
        std::fs::create_dir_all(&world.out).expect("output folder");
        for command in args[1..].split(|a| a == "--") {
            match command {
                [c, name, problem, tol, max_iter] if c == "solve" => solve_all(
                    &world,
                    name,
                    &WholeProblem::load(problem).expect("a problem"),
                    tol.parse().expect("a tolerance"),
                    max_iter.parse().expect("an iteration limit"),
                ),
                [c, problem] if c == "errors" => {
                    errors(&world, &WholeProblem::load(problem).expect("a problem"))
                }
                [c, problem] if c == "handle" => {
                    handle(&world, &WholeProblem::load(problem).expect("a problem"))
                }
                other => panic!("unknown command {other:?}"),
            }
        }
        // SAFETY: every fc3d communicator was released.
        unsafe { ffi::fc3d_mpi_shim_finalize() };
    }

    fn settings(tol: f64, max_iter: i64) -> *mut Fc3dSettings {
        // SAFETY: fc3d's settings API.
        unsafe {
            let s = fc3d_settings_new(500);
            assert!(!s.is_null());
            fc3d_settings_set_tolerance(s, tol);
            fc3d_settings_set_max_iter(s, max_iter);
            s
        }
    }

    fn last_error() -> String {
        // SAFETY: a static NUL-terminated string of this thread.
        unsafe { CStr::from_ptr(fc3d_last_error_message()) }
            .to_string_lossy()
            .into_owned()
    }

    /// One rank's solution and report.
    struct Solved {
        code: c_int,
        result: Fc3dResult,
        r: Vec<f64>,
        u: Vec<f64>,
    }

    /// Calls `fc3d_mpi_solve_blocks` (or the solver's entry when given) on `rows`.
    fn call(
        world: &World,
        rows: &RankRows,
        s: *const Fc3dSettings,
        solver: Option<*mut Fc3dMpiSolver>,
    ) -> Solved {
        let n = rows.n_local();
        let mut r = vec![0.0; 3 * n];
        let mut u = vec![f64::NAN; 3 * n];
        let mut result = Fc3dResult {
            info: -1000,
            ..Default::default()
        };
        // An empty array goes as NULL, as a C host with no contact would pass it.
        fn or_null<T>(v: &[T]) -> *const T {
            if v.is_empty() {
                std::ptr::null()
            } else {
                v.as_ptr()
            }
        }
        fn or_null_mut<T>(v: &mut [T]) -> *mut T {
            if v.is_empty() {
                std::ptr::null_mut()
            } else {
                v.as_mut_ptr()
            }
        }
        // SAFETY: arrays of the sizes given.
        let code = unsafe {
            match solver {
                None => fc3d_mpi_solve_blocks(
                    world.comm,
                    n as i64,
                    or_null(&rows.ids),
                    rows.cols.len() as i64,
                    rows.row_ptr.as_ptr(),
                    or_null(&rows.cols),
                    or_null(&rows.blocks),
                    or_null(&rows.q),
                    or_null(&rows.mu),
                    or_null_mut(&mut r),
                    or_null_mut(&mut u),
                    s,
                    &mut result,
                ),
                Some(solver) => fc3d_mpi_solver_solve(
                    solver,
                    n as i64,
                    or_null(&rows.ids),
                    rows.cols.len() as i64,
                    rows.row_ptr.as_ptr(),
                    or_null(&rows.cols),
                    or_null(&rows.blocks),
                    or_null(&rows.q),
                    or_null(&rows.mu),
                    or_null_mut(&mut r),
                    or_null_mut(&mut u),
                    s,
                    &mut result,
                ),
            }
        };
        Solved { code, result, r, u }
    }

    /// `code info iterations error_bits`, then `id r_bits(3) u_bits(3)` per contact.
    fn write_solution(path: &Path, rows: &RankRows, s: &Solved) {
        let mut text = format!(
            "{} {} {} {:016x}\n",
            s.code,
            s.result.info,
            s.result.iterations,
            s.result.error.to_bits()
        );
        for (k, id) in rows.ids.iter().enumerate() {
            write!(text, "{id}").unwrap();
            for v in s.r[3 * k..3 * k + 3].iter().chain(&s.u[3 * k..3 * k + 3]) {
                write!(text, " {:016x}", v.to_bits()).unwrap();
            }
            text.push('\n');
        }
        std::fs::write(path, text).expect("write a result");
    }

    fn file(world: &World, what: &str) -> PathBuf {
        world
            .out
            .join(format!("{what}.np{}.rank{}", world.size, world.rank))
    }

    fn solve_all(world: &World, name: &str, p: &WholeProblem, tol: f64, max_iter: i64) {
        let s = settings(tol, max_iter);
        for partition in Partition::ALL {
            let contacts = partition.contacts_of(p.n_contacts(), world.rank, world.size);
            let rows = RankRows::of(p, &contacts);
            let solved = call(world, &rows, s, None);
            assert!(solved.code >= 0, "{name}: {}", last_error());
            write_solution(
                &file(world, &format!("{name}.{}", partition.name())),
                &rows,
                &solved,
            );
        }
        // SAFETY: made above.
        unsafe { fc3d_settings_free(s) };
    }

    /// Rejected inputs, each on one rank only (the last, or rank 0): every rank must return the
    /// same code and message and leave r and u untouched; then a good solve must go through.
    fn errors(world: &World, p: &WholeProblem) {
        let good = settings(1e-8, 30);
        let last = world.size - 1;
        let contacts = Partition::Ranges.contacts_of(p.n_contacts(), world.rank, world.size);
        let base = RankRows::of(p, &contacts);
        let mut report = String::new();
        type Spoil = Box<dyn Fn(&mut RankRows, usize)>;
        let cases: Vec<(&str, Spoil)> = vec![
            (
                "nan-in-q",
                Box::new(move |r, rank| {
                    if rank == last {
                        r.q[1] = f64::NAN
                    }
                }),
            ),
            (
                "unowned-column",
                Box::new(|r, rank| {
                    if rank == 0 {
                        r.cols[0] = 3
                    }
                }),
            ),
            (
                "duplicate-id",
                Box::new(move |r, rank| {
                    // The last rank claims rank 0's first contact (or its own, twice).
                    if rank == last {
                        let first = fc3d_mpi::problems::global_id(0);
                        let k = r.n_local() - 1;
                        let old = r.ids[k];
                        r.ids[k] = first;
                        for c in &mut r.cols {
                            if *c == old {
                                *c = first;
                            }
                        }
                    }
                }),
            ),
            (
                "negative-mu",
                Box::new(|r, rank| {
                    if rank == 0 {
                        r.mu[0] = -0.5
                    }
                }),
            ),
            (
                "no-diagonal",
                Box::new(move |r, rank| {
                    if rank == last {
                        let id = r.ids[0];
                        let row = r.row_ptr[0] as usize..r.row_ptr[1] as usize;
                        for k in row {
                            if r.cols[k] == id {
                                r.cols[k] = r.ids[1];
                            }
                        }
                    }
                }),
            ),
            (
                "bad-row-ptr",
                Box::new(move |r, rank| {
                    if rank == last {
                        let n = r.n_local();
                        r.row_ptr[n] += 1;
                    }
                }),
            ),
        ];
        for (name, spoil) in &cases {
            let mut rows = RankRows::of(p, &contacts);
            spoil(&mut rows, world.rank);
            let solved = call(world, &rows, good, None);
            let untouched = solved.r.iter().all(|&v| v == 0.0)
                && solved.u.iter().all(|v| v.is_nan())
                && solved.result.info == -1000;
            writeln!(
                report,
                "{name}\t{}\t{untouched}\t{}",
                solved.code,
                last_error()
            )
            .unwrap();
        }
        // Settings that differ between ranks, and a solver that is not distributed.
        let other = settings(if world.rank == last { 1e-6 } else { 1e-8 }, 30);
        let solved = call(world, &base, other, None);
        writeln!(
            report,
            "settings-differ\t{}\t-\t{}",
            solved.code,
            last_error()
        )
        .unwrap();
        // SAFETY: fc3d's settings API.
        let nsn = unsafe { fc3d_settings_new(504) };
        let solved = call(world, &base, nsn, None);
        writeln!(report, "solver-504\t{}\t-\t{}", solved.code, last_error()).unwrap();
        // A negative size on one rank.
        let mut result = Fc3dResult::default();
        let (mut r, mut u) = (vec![0.0; 3 * base.n_local()], vec![0.0; 3 * base.n_local()]);
        let n = if world.rank == last {
            -1
        } else {
            base.n_local() as i64
        };
        // SAFETY: the arrays hold what the valid sizes say; -1 is rejected before any read.
        let code = unsafe {
            fc3d_mpi_solve_blocks(
                world.comm,
                n,
                base.ids.as_ptr(),
                base.cols.len() as i64,
                base.row_ptr.as_ptr(),
                base.cols.as_ptr(),
                base.blocks.as_ptr(),
                base.q.as_ptr(),
                base.mu.as_ptr(),
                r.as_mut_ptr(),
                u.as_mut_ptr(),
                good,
                &mut result,
            )
        };
        writeln!(report, "negative-size\t{code}\t-\t{}", last_error()).unwrap();
        // Nobody was left waiting: a good solve goes through.
        let solved = call(world, &base, good, None);
        writeln!(
            report,
            "good-after\t{}\t-\t{}",
            solved.code, solved.result.iterations
        )
        .unwrap();
        std::fs::write(file(world, "errors"), report).expect("write the report");
        // SAFETY: made above.
        unsafe {
            fc3d_settings_free(good);
            fc3d_settings_free(other);
            fc3d_settings_free(nsn);
        }
    }

    /// A solver kept across two solves of the same pattern (the second with another q: the
    /// set-up is reused), its results equal to the one-shot entry's; then the fast mode.
    fn handle(world: &World, p: &WholeProblem) {
        let s = settings(1e-3, 1000);
        let contacts = Partition::Random.contacts_of(p.n_contacts(), world.rank, world.size);
        let mut rows = RankRows::of(p, &contacts);
        let mut report = String::new();
        // SAFETY: the solver API.
        let solver = unsafe { fc3d_mpi_solver_new(world.comm, FC3D_MPI_REPRODUCIBLE) };
        assert!(!solver.is_null(), "{}", last_error());
        for step in 0..2 {
            if step == 1 {
                rows.q.iter_mut().for_each(|v| *v *= 1.5);
            }
            let kept = call(world, &rows, s, Some(solver));
            let once = call(world, &rows, s, None);
            let same = kept.code == once.code
                && kept.result.iterations == once.result.iterations
                && kept.result.error.to_bits() == once.result.error.to_bits()
                && kept
                    .r
                    .iter()
                    .zip(&once.r)
                    .all(|(a, b)| a.to_bits() == b.to_bits())
                && kept
                    .u
                    .iter()
                    .zip(&once.u)
                    .all(|(a, b)| a.to_bits() == b.to_bits());
            writeln!(
                report,
                "kept-{step}\t{}\t{}\t{:e}\t{same}",
                kept.code, kept.result.iterations, kept.result.error
            )
            .unwrap();
        }
        let mut stats = Fc3dMpiStats::default();
        // SAFETY: the solver API.
        unsafe { fc3d_mpi_solver_stats(solver, &mut stats) };
        writeln!(
            report,
            "stats\t{}\t{}\t{}\t{}\t{}\t{}\t{}\t{}\t{}",
            stats.ranks,
            stats.setups,
            stats.solves,
            stats.colours,
            stats.contacts,
            stats.total_contacts,
            stats.ghosts,
            stats.messages_per_sweep,
            stats.bytes_per_sweep
        )
        .unwrap();
        // SAFETY: the solver API.
        unsafe { fc3d_mpi_solver_free(solver) };
        let fast = unsafe { fc3d_mpi_solver_new(world.comm, FC3D_MPI_FAST) };
        assert!(!fast.is_null(), "{}", last_error());
        // The fast mode is Jacobi across ranks: it is meant for subdomains (contiguous ranges),
        // not for a random scatter, where most couplings cross ranks.
        let rows = RankRows::of(
            p,
            &Partition::Ranges.contacts_of(p.n_contacts(), world.rank, world.size),
        );
        let solved = call(world, &rows, s, Some(fast));
        writeln!(
            report,
            "fast\t{}\t{}\t{:e}",
            solved.code, solved.result.iterations, solved.result.error
        )
        .unwrap();
        write_solution(&file(world, "fast"), &rows, &solved);
        // SAFETY: the solver and settings APIs.
        unsafe {
            fc3d_mpi_solver_free(fast);
            fc3d_settings_free(s);
        }
        // A mode no one knows, refused on every rank.
        let bad = unsafe { fc3d_mpi_solver_new(world.comm, 7) };
        writeln!(report, "bad-mode\t{}\t{}", bad.is_null(), last_error()).unwrap();
        std::fs::write(file(world, "handle"), report).expect("write the report");
    }
}

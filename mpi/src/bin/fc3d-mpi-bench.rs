//! fc3d-mpi's scaling benchmark (docs/mpi.md): one generated pile split over the ranks in
//! contiguous ranges, solved by the distributed NSGS. Rank 0 prints one CSV line:
//!
//!   mpirun -np P fc3d-mpi-bench gen:contacts=N,piles=4,seed=1 [--sweeps K] [--tols 1e-3,1e-4]
//!                               [--limit SECONDS] [--mode reproducible|fast] [--header]
//!
//! Per sweep: wall time (a run of K + 1 sweeps minus a run of 1, over K, the set-up kept), this
//! rank's compute and MPI wait over the same difference (the slowest rank's), messages and bytes
//! sent by all ranks; the set-up (directory, colouring, halo) of the first call; the halo
//! (largest ghost and boundary counts of a rank) and the colours' load balance (the sum over
//! colours of the busiest rank's contacts over the contacts per rank: 1 is perfect). Then, from
//! r = 0, the time and sweeps to each tolerance under a time budget of `--limit` seconds.

#[cfg(fc3d_no_mpi)]
fn main() {
    eprintln!("fc3d-mpi-bench: built without MPI");
    std::process::exit(2);
}

#[cfg(not(fc3d_no_mpi))]
fn main() {
    bench::main()
}

#[cfg(not(fc3d_no_mpi))]
mod bench {
    use std::ffi::c_int;
    use std::time::Instant;

    use fc3d::Fc3dSettings;
    use fc3d_core::{Delassus, FrictionProblem, Method, SolverConfig};
    use fc3d_mpi::comm::{thread_cpu_seconds, Comm, Op};
    use fc3d_mpi::ffi::{self, MpiComm};
    use fc3d_mpi::input::{run_settings, LocalRows, RunSettings};
    use fc3d_mpi::layout::Mode;
    use fc3d_mpi::problems::{Partition, RankRows, WholeProblem};
    use fc3d_mpi::solver::{DistributedSolver, Outcome, Statistics};

    #[allow(improper_ctypes)]
    extern "C" {
        fn fc3d_settings_new(id: c_int) -> *mut Fc3dSettings;
        fn fc3d_settings_free(s: *mut Fc3dSettings);
        fn fc3d_settings_set_tolerance(s: *mut Fc3dSettings, tol: f64) -> c_int;
        fn fc3d_settings_set_max_iter(s: *mut Fc3dSettings, n: i64) -> c_int;
        fn fc3d_settings_set_time_budget(s: *mut Fc3dSettings, seconds: f64) -> c_int;
    }

    /// NSGS settings (Siconos' defaults otherwise) as the distributed run reads them.
    fn settings(tolerance: f64, max_iter: i64, budget: Option<f64>) -> RunSettings {
        // SAFETY: fc3d's settings API; the settings are freed once read.
        unsafe {
            let s = fc3d_settings_new(500);
            assert!(!s.is_null());
            assert_eq!(fc3d_settings_set_tolerance(s, tolerance), 0);
            assert_eq!(fc3d_settings_set_max_iter(s, max_iter), 0);
            if let Some(b) = budget {
                assert_eq!(fc3d_settings_set_time_budget(s, b), 0);
            }
            let run = run_settings(s).expect("NSGS settings");
            fc3d_settings_free(s);
            run
        }
    }

    struct Args {
        problem: String,
        sweeps: i64,
        tolerances: Vec<f64>,
        limit: f64,
        mode: Mode,
        header: bool,
        core: bool,
    }

    fn parse() -> Args {
        let mut args = Args {
            problem: String::new(),
            sweeps: 10,
            tolerances: vec![1e-3, 1e-4],
            limit: 60.0,
            mode: Mode::Reproducible,
            header: false,
            core: false,
        };
        let mut it = std::env::args().skip(1);
        while let Some(a) = it.next() {
            let mut value = || it.next().unwrap_or_else(|| panic!("{a} takes a value"));
            match a.as_str() {
                "--sweeps" => args.sweeps = value().parse().expect("a sweep count"),
                "--tols" => {
                    let v = value();
                    args.tolerances = if v.is_empty() {
                        Vec::new()
                    } else {
                        v.split(',')
                            .map(|t| t.parse().expect("a tolerance"))
                            .collect()
                    };
                }
                "--limit" => args.limit = value().parse().expect("seconds"),
                "--mode" => {
                    args.mode = match value().as_str() {
                        "reproducible" => Mode::Reproducible,
                        "fast" => Mode::Fast,
                        m => panic!("unknown mode {m}"),
                    }
                }
                "--header" => args.header = true,
                "--core" => args.core = true,
                _ if args.problem.is_empty() => args.problem = a,
                _ => panic!("unknown argument {a}"),
            }
        }
        assert!(
            !args.problem.is_empty(),
            "usage: fc3d-mpi-bench PROBLEM [options]"
        );
        args
    }

    pub fn main() {
        let args = parse();
        // SAFETY: plain MPI set-up of this program.
        let world = unsafe {
            assert_eq!(ffi::fc3d_mpi_shim_init(), 0, "MPI_Init");
            let mut comm: MpiComm = std::mem::zeroed();
            ffi::fc3d_mpi_shim_world(&mut comm);
            comm
        };
        run(&args, &world);
        // SAFETY: every fc3d communicator was released.
        unsafe { ffi::fc3d_mpi_shim_finalize() };
    }

    fn run(args: &Args, world: &MpiComm) {
        // SAFETY: MPI_COMM_WORLD of an initialised MPI.
        let comm = unsafe { Comm::duplicate(world) }.expect("a communicator");
        let (rank, size) = (comm.rank(), comm.size());
        let start = Instant::now();
        let whole = WholeProblem::load(&args.problem).expect("a problem");
        let n = whole.n_contacts();
        let rows = RankRows::of(&whole, &Partition::Ranges.contacts_of(n, rank, size));
        let core = (args.core && size == 1).then(|| core_sweep(whole, args.sweeps));
        let generated = comm.max_f64(start.elapsed().as_secs_f64()).unwrap();
        let zero = vec![0.0; 3 * rows.n_local()];
        let local = LocalRows {
            ids: &rows.ids,
            row_ptr: &rows.row_ptr,
            cols: &rows.cols,
            blocks: &rows.blocks,
            q: &rows.q,
            mu: &rows.mu,
            r: &zero,
        };
        // SAFETY: as above.
        let own = unsafe { Comm::duplicate(world) }.expect("a communicator");
        let mut solver = DistributedSolver::new(own, args.mode);
        let (mut r, mut u) = (zero.clone(), zero.clone());
        let mut solve =
            |s: &RunSettings, solver: &mut DistributedSolver| -> (Outcome, Statistics) {
                let outcome = solver.solve(&local, s, &mut r, &mut u).expect("a solve");
                (outcome, solver.statistics)
            };
        // Sweeps only: a tolerance these few sweeps do not reach.
        let (_, set_up) = solve(&settings(1e-16, 1, None), &mut solver);
        let (once, one) = solve(&settings(1e-16, 1, None), &mut solver);
        let (many, more) = solve(&settings(1e-16, args.sweeps + 1, None), &mut solver);
        let k = args.sweeps as f64;
        let max = |v: f64| comm.max_f64(v).unwrap();
        let sweep_ms = 1e3 * (many.seconds - once.seconds) / k;
        let compute_ms = 1e3 * max((more.seconds_compute - one.seconds_compute) / k);
        let wait_ms = 1e3 * max((more.seconds_wait - one.seconds_wait) / k);
        let cpu_ms = 1e3 * max((more.cpu_seconds_compute - one.cpu_seconds_compute) / k);
        let stats = fc3d_mpi::statistics_of(&solver);
        let mut sums = [stats.messages_per_sweep, stats.bytes_per_sweep];
        comm.allreduce(&mut sums, Op::Sum).unwrap();
        let mut maxima = [stats.ghosts, stats.boundary, stats.neighbours];
        comm.allreduce(&mut maxima, Op::Max).unwrap();
        let balance = colour_balance(&comm, &solver, n);
        let setup_s = max(set_up.seconds_setup);

        let mut to_tolerance = Vec::new();
        for &t in &args.tolerances {
            let (o, _) = solve(&settings(t, 1_000_000_000, Some(args.limit)), &mut solver);
            to_tolerance.push(if o.info == 0 {
                format!("{:.2},{}", o.seconds, o.iterations)
            } else {
                format!(">{:.0},{} (error {:.1e})", o.seconds, o.iterations, o.error)
            });
        }
        if rank == 0 {
            if args.header {
                let mut h = "contacts,ranks,mode,colours,generate_s,setup_s,sweep_ms,compute_ms,compute_cpu_ms,wait_ms,messages_per_sweep,bytes_per_sweep,max_ghosts,max_boundary,max_neighbours,colour_balance".to_string();
                for t in &args.tolerances {
                    h.push_str(&format!(",to_{t:e}_s,to_{t:e}_sweeps"));
                }
                println!("{h}");
            }
            let mode = if args.mode == Mode::Fast {
                "fast"
            } else {
                "reproducible"
            };
            let mut line = format!(
                "{n},{size},{mode},{},{generated:.2},{setup_s:.3},{sweep_ms:.2},{compute_ms:.2},{cpu_ms:.2},{wait_ms:.2},{},{},{},{},{},{balance:.4}",
                stats.colours, sums[0], sums[1], maxima[0], maxima[1], maxima[2]
            );
            for t in &to_tolerance {
                line.push(',');
                line.push_str(t);
            }
            if let Some((wall, cpu)) = core {
                line.push_str(&format!(",core {wall:.2} ms ({cpu:.2} ms CPU)"));
            }
            println!("{line}");
        }
    }

    /// The core's one-process NSGS (natural order, the same settings) on the whole problem:
    /// wall and CPU milliseconds per sweep, as (K + 1 sweeps - 1 sweep) / K.
    fn core_sweep(whole: WholeProblem, sweeps: i64) -> (f64, f64) {
        let nsgs = settings(1e-16, 1, None).nsgs;
        let problem = FrictionProblem::new(Delassus::SparseBlock(whole.w), whole.q, whole.mu)
            .expect("a problem");
        let n3 = 3 * problem.n_contacts();
        let time = |k: i64| {
            let config = SolverConfig::new(Method::Nsgs(nsgs))
                .with_tolerance(1e-16)
                .with_max_iter(k as usize);
            let (mut r, mut u) = (vec![0.0; n3], vec![0.0; n3]);
            let (t, cpu) = (Instant::now(), thread_cpu_seconds());
            fc3d_core::solve(&problem, &config, &mut r, &mut u).expect("a core solve");
            (t.elapsed().as_secs_f64(), thread_cpu_seconds() - cpu)
        };
        let (one, one_cpu) = time(1);
        let (many, many_cpu) = time(sweeps + 1);
        let k = sweeps as f64;
        (1e3 * (many - one) / k, 1e3 * (many_cpu - one_cpu) / k)
    }

    /// Sum over colours of the busiest rank's contacts of that colour, over `n / ranks`.
    fn colour_balance(comm: &Comm, solver: &DistributedSolver, n: usize) -> f64 {
        let Some((layout, _)) = solver.layout() else {
            return f64::NAN;
        };
        let mut per_colour: Vec<i64> = layout
            .steps
            .iter()
            .map(|s| (s.boundary.len() + s.interior.len()) as i64)
            .collect();
        comm.allreduce(&mut per_colour, Op::Max).unwrap();
        per_colour.iter().sum::<i64>() as f64 * comm.size() as f64 / n as f64
    }
}

//! FCLIB `.hdf5` problems: the two shared Siconos files load with the right sizes, the reduction
//! of the global one agrees with the solution stored in the file, NSGS reaches 1e-8 on both (with
//! iterations and errors printed next to Siconos 4.4's from `siconos-reference-1e-8.csv`), and
//! damaged files give typed errors naming the file, never a panic.
//!
//! Everything that needs libhdf5 is behind the `fclib` feature
//! (`cargo test --workspace --features fc3d/fclib`); without it only the check that
//! `read_problem_file` refuses `.hdf5` files with a clear message runs.

use std::path::{Path, PathBuf};

use fc3d_core::io::read_problem_file;
use fc3d_core::Fc3dError;

const DATA_DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/data/siconos");

fn data(name: &str) -> PathBuf {
    Path::new(DATA_DIR).join(name)
}

#[test]
fn read_problem_file_dispatches_on_the_extension() {
    let dat = read_problem_file(&data("FC3D_Example1.dat")).expect("a .dat problem");
    assert_eq!(dat.n_contacts(), 3);
    // "x.hdf5.dat" is a .dat file.
    let dat = read_problem_file(&data("BoxesStack1-i100000-32.hdf5.dat")).expect("a .dat problem");
    assert_eq!(dat.n_contacts(), 52);
    match read_problem_file(Path::new("problem.txt")) {
        Err(Fc3dError::Unsupported(m)) => assert!(m.contains("problem.txt"), "{m}"),
        other => panic!("expected Unsupported, got {other:?}"),
    }
}

#[cfg(not(feature = "fclib"))]
#[test]
fn hdf5_files_need_the_fclib_feature() {
    for name in ["Box_Stacks-i0122-82-5.hdf5", "missing.H5"] {
        match read_problem_file(&data(name)) {
            Err(Fc3dError::Unsupported(m)) => {
                assert!(m.contains(name), "{m}");
                assert!(m.contains("built without the `fclib` feature"), "{m}");
            }
            other => panic!("expected Unsupported, got {other:?}"),
        }
    }
}

#[cfg(feature = "fclib")]
mod with_hdf5 {
    use super::*;

    use fc3d_core::io::read_fclib_file;
    use fc3d_core::{Delassus, FrictionProblem, NsgsOptions, SolverConfig};
    use hdf5_metno as hdf5;

    const BOX_STACKS: &str = "Box_Stacks-i0122-82-5.hdf5";
    const PERIO_BOX: &str = "LMGC_100_PR_PerioBox-i00361-60-03000.hdf5";

    fn read_vec(file: &hdf5::File, path: &str) -> Vec<f64> {
        file.dataset(path)
            .and_then(|d| d.read_raw::<f64>())
            .unwrap_or_else(|e| panic!("{path}: {e}"))
    }

    fn read_ints(file: &hdf5::File, path: &str) -> Vec<i64> {
        file.dataset(path)
            .and_then(|d| d.read_raw::<i64>())
            .unwrap_or_else(|e| panic!("{path}: {e}"))
    }

    /// Siconos 4.4's NSGS row of the reference CSV: (nc, info, iterations, error).
    fn siconos_nsgs(file: &str) -> (usize, i32, usize, f64) {
        let csv =
            std::fs::read_to_string(Path::new(DATA_DIR).join("../siconos-reference-1e-8.csv"))
                .expect("the shared reference CSV");
        let line = csv
            .lines()
            .find(|l| l.starts_with(&format!("{file},")) && l.contains(",FC3D_NSGS,"))
            .unwrap_or_else(|| panic!("no NSGS row for {file}"));
        // file,dim,nc,solver,tol,info,iter,error,seconds
        let f: Vec<&str> = line.split(',').collect();
        (
            f[2].parse().unwrap(),
            f[5].parse().unwrap(),
            f[6].parse().unwrap(),
            f[7].parse().unwrap(),
        )
    }

    fn load(name: &str) -> FrictionProblem<'static> {
        read_fclib_file(&data(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
    }

    #[test]
    fn shared_files_load_with_their_sizes() {
        for (name, nc) in [(BOX_STACKS, 82), (PERIO_BOX, 60)] {
            let p = load(name);
            assert_eq!(p.n_contacts(), nc, "{name}");
            assert_eq!(p.n_contacts(), siconos_nsgs(name).0, "{name}: the CSV's nc");
            assert_eq!(p.size(), 3 * nc);
            assert!(matches!(p.w(), Delassus::SparseBlock(_)), "{name}");
            // The dispatcher gives the same problem.
            assert_eq!(read_problem_file(&data(name)).unwrap(), p, "{name}");
            let Delassus::SparseBlock(b) = p.w() else {
                unreachable!()
            };
            println!(
                "{name}: nc = {nc}, {} of {} 3x3 blocks stored, asymmetry {:.1e}",
                b.n_blocks(),
                nc * nc,
                p.w().relative_asymmetry()
            );
        }
    }

    #[test]
    fn local_file_is_read_as_stored() {
        // W is stored in compressed rows (nz = -2): compare every stored entry.
        let file = hdf5::File::open(data(PERIO_BOX)).unwrap();
        assert_eq!(read_ints(&file, "/fclib_local/W/nz"), [-2]);
        let ptr = read_ints(&file, "/fclib_local/W/p");
        let col = read_ints(&file, "/fclib_local/W/i");
        let x = read_vec(&file, "/fclib_local/W/x");
        let p = load(PERIO_BOX);
        assert_eq!(ptr.len(), p.size() + 1);
        let mut stored = 0;
        for row in 0..p.size() {
            for k in ptr[row] as usize..ptr[row + 1] as usize {
                assert_eq!(
                    p.w().get(row, col[k] as usize),
                    x[k],
                    "W[{row}, {}]",
                    col[k]
                );
                stored += 1;
            }
        }
        assert_eq!(stored, x.len());
        assert_eq!(p.q(), read_vec(&file, "/fclib_local/vectors/q").as_slice());
        assert_eq!(
            p.mu(),
            read_vec(&file, "/fclib_local/vectors/mu").as_slice()
        );
    }

    #[test]
    fn reduced_global_problem_matches_a_direct_computation() {
        // Box_Stacks is global only, with a diagonal M: W = H^T M^-1 H and q = H^T M^-1 f + w can
        // be formed directly, entry by entry, without any factorization. (Its /solution group
        // holds r = v = 0, which solves nothing, so it cannot serve as a check.)
        let file = hdf5::File::open(data(BOX_STACKS)).unwrap();
        assert!(!file.link_exists("fclib_local"));
        assert_eq!(read_ints(&file, "/fclib_global/M/nz"), [450]);
        assert_eq!(read_ints(&file, "/fclib_global/H/nz"), [1284]);
        let (mi, mj) = (
            read_ints(&file, "/fclib_global/M/i"),
            read_ints(&file, "/fclib_global/M/p"),
        );
        let mx = read_vec(&file, "/fclib_global/M/x");
        assert!(mi == mj, "M is diagonal");
        let mut m_diag = vec![0.0; 450];
        for (k, &i) in mi.iter().enumerate() {
            m_diag[i as usize] += mx[k];
        }
        let (hi, hj) = (
            read_ints(&file, "/fclib_global/H/i"),
            read_ints(&file, "/fclib_global/H/p"),
        );
        let hx = read_vec(&file, "/fclib_global/H/x");
        let n = 246;
        let mut h = vec![vec![0.0; n]; 450]; // h[dof][column]
        for k in 0..hx.len() {
            h[hi[k] as usize][hj[k] as usize] += hx[k];
        }
        let f = read_vec(&file, "/fclib_global/vectors/f");
        let w = read_vec(&file, "/fclib_global/vectors/w");
        let p = load(BOX_STACKS);
        let mut w_max = 0.0_f64;
        let mut w_diff = 0.0_f64;
        for i in 0..n {
            for j in 0..n {
                let direct: f64 = (0..450).map(|k| h[k][i] * h[k][j] / m_diag[k]).sum();
                w_max = w_max.max(direct.abs());
                w_diff = w_diff.max((p.w().get(i, j) - direct).abs());
            }
        }
        let mut q_diff = 0.0_f64;
        for i in 0..n {
            let direct = w[i] + (0..450).map(|k| h[k][i] * f[k] / m_diag[k]).sum::<f64>();
            q_diff = q_diff.max((p.q()[i] - direct).abs() / (1.0 + direct.abs()));
        }
        println!("{BOX_STACKS}: max |W - H^T M^-1 H| = {w_diff:.1e} (max |W| {w_max:.2}), q relative {q_diff:.1e}");
        assert!(w_diff <= 1e-14 * w_max, "{w_diff}");
        assert!(q_diff <= 1e-14, "{q_diff}");
        assert_eq!(
            p.mu(),
            read_vec(&file, "/fclib_global/vectors/mu").as_slice()
        );
        // M is diagonal, so W is symmetric up to rounding.
        assert!(p.w().relative_asymmetry() < 1e-12);
    }

    #[test]
    fn nsgs_reaches_1e8_on_both_files() {
        for name in [BOX_STACKS, PERIO_BOX] {
            let p = load(name);
            let config = SolverConfig::new(NsgsOptions::default())
                .with_tolerance(1e-8)
                .with_max_iter(100000);
            let mut r = vec![0.0; p.size()];
            let mut u = vec![0.0; p.size()];
            let report = fc3d_core::solve(&p, &config, &mut r, &mut u).expect("a solve");
            let (_, info, iter, error) = siconos_nsgs(name);
            println!(
                "{name}: fc3d NSGS {} sweeps, error {:.3e} (converged: {}); Siconos 4.4: info {info}, {iter} sweeps, error {error:.3e}",
                report.iterations,
                report.error,
                report.converged()
            );
            assert!(report.converged(), "{name}: {report:?}");
            assert!(report.error <= 1e-8, "{name}: {report:?}");
            // Same algorithm and defaults as Siconos: the sweep counts agree (33 and 766 when
            // this was written); allow 10% for rounding differences in W.
            let (ours, theirs) = (report.iterations as f64, iter as f64);
            assert!(
                (ours - theirs).abs() <= 0.1 * theirs,
                "{name}: {ours} vs Siconos {theirs}"
            );
        }
    }

    // ---- damaged files, written with hdf5-metno into a scratch directory ----

    struct Scratch(PathBuf);

    impl Scratch {
        fn new(tag: &str) -> Self {
            let dir = std::env::temp_dir().join(format!("fc3d-fclib-{tag}-{}", std::process::id()));
            std::fs::create_dir_all(&dir).unwrap();
            Scratch(dir)
        }
        fn path(&self, name: &str) -> PathBuf {
            self.0.join(name)
        }
    }

    impl Drop for Scratch {
        fn drop(&mut self) {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }

    /// A CSparse matrix group as FCLIB stores it.
    #[derive(Clone)]
    struct Sparse {
        m: i32,
        n: i32,
        nz: i32,
        p: Vec<i32>,
        i: Vec<i32>,
        x: Vec<f64>,
    }

    impl Sparse {
        /// The n x n identity scaled by `s`, in compressed columns.
        fn diagonal(n: i32, s: f64) -> Self {
            Sparse {
                m: n,
                n,
                nz: -1,
                p: (0..=n).collect(),
                i: (0..n).collect(),
                x: vec![s; n as usize],
            }
        }

        fn write(&self, g: &hdf5::Group, name: &str) {
            let mg = g.create_group(name).unwrap();
            let int = |field: &str, v: &[i32]| {
                mg.new_dataset_builder().with_data(v).create(field).unwrap();
            };
            int("nzmax", &[self.x.len() as i32]);
            int("m", &[self.m]);
            int("n", &[self.n]);
            int("nz", &[self.nz]);
            int("p", &self.p);
            int("i", &self.i);
            mg.new_dataset_builder()
                .with_data(self.x.as_slice())
                .create("x")
                .unwrap();
        }
    }

    fn write_vec(g: &hdf5::Group, name: &str, v: &[f64]) {
        g.new_dataset_builder().with_data(v).create(name).unwrap();
    }

    /// A small valid local problem (2 contacts, W = 2 I), to be damaged one field at a time.
    #[derive(Clone)]
    struct Local {
        spacedim: i32,
        w: Sparse,
        q: Vec<f64>,
        mu: Vec<f64>,
    }

    impl Local {
        fn valid() -> Self {
            Local {
                spacedim: 3,
                w: Sparse::diagonal(6, 2.0),
                q: vec![-1.0, 0.5, 0.0, 1.0, 0.0, 0.0],
                mu: vec![0.5, 0.3],
            }
        }

        fn write(&self, path: &Path) {
            let f = hdf5::File::create(path).unwrap();
            let g = f.create_group("fclib_local").unwrap();
            g.new_dataset_builder()
                .with_data(&[self.spacedim])
                .create("spacedim")
                .unwrap();
            self.w.write(&g, "W");
            let v = g.create_group("vectors").unwrap();
            write_vec(&v, "q", &self.q);
            write_vec(&v, "mu", &self.mu);
        }
    }

    /// A small global problem: 2 contacts on 2 bodies with 3 dofs each, H = I.
    #[derive(Clone)]
    struct Global {
        m: Sparse,
        h: Sparse,
        f: Vec<f64>,
        w: Vec<f64>,
        mu: Vec<f64>,
    }

    impl Global {
        fn valid() -> Self {
            Global {
                m: Sparse::diagonal(6, 4.0),
                h: Sparse {
                    m: 6,
                    n: 6,
                    nz: 6,
                    p: (0..6).collect(),
                    i: (0..6).collect(),
                    x: vec![1.0; 6],
                },
                f: vec![-4.0, 0.0, 0.0, 8.0, 0.0, 0.0],
                w: vec![0.0, 1.0, 0.0, 0.0, 0.0, 0.0],
                mu: vec![0.5, 0.3],
            }
        }

        fn write(&self, path: &Path) {
            let f = hdf5::File::create(path).unwrap();
            let g = f.create_group("fclib_global").unwrap();
            g.new_dataset_builder()
                .with_data(&[3i32])
                .create("spacedim")
                .unwrap();
            self.m.write(&g, "M");
            self.h.write(&g, "H");
            let v = g.create_group("vectors").unwrap();
            write_vec(&v, "f", &self.f);
            write_vec(&v, "w", &self.w);
            write_vec(&v, "mu", &self.mu);
        }
    }

    fn invalid_structure(path: &Path, needle: &str) {
        match read_fclib_file(path) {
            Err(Fc3dError::InvalidStructure(m)) => {
                assert!(m.contains(&path.display().to_string()), "{m}");
                assert!(m.contains(needle), "'{needle}' not in: {m}");
            }
            other => panic!(
                "{}: expected InvalidStructure, got {other:?}",
                path.display()
            ),
        }
    }

    #[test]
    fn small_written_files_read_back() {
        let s = Scratch::new("ok");
        let local = s.path("local.hdf5");
        Local::valid().write(&local);
        let p = read_fclib_file(&local).unwrap();
        assert_eq!(p.n_contacts(), 2);
        assert_eq!(p.w().get(4, 4), 2.0);
        assert_eq!(p.w().get(4, 3), 0.0);
        assert_eq!(p.mu(), [0.5, 0.3]);

        // Compressed rows and triplets give the same W.
        for nz in [-2, 6] {
            let mut l = Local::valid();
            l.w.nz = nz;
            if nz >= 0 {
                l.w.p = (0..6).collect();
            }
            l.write(&local);
            assert_eq!(read_fclib_file(&local).unwrap(), p, "nz = {nz}");
        }

        // Global: W = H^T M^-1 H = I / 4, q = H^T M^-1 f + w = (-1, 1, 0, 2, 0, 0).
        let global = s.path("global.h5");
        Global::valid().write(&global);
        let g = read_problem_file(&global).unwrap();
        assert_eq!(g.n_contacts(), 2);
        for i in 0..6 {
            for j in 0..6 {
                assert_eq!(g.w().get(i, j), if i == j { 0.25 } else { 0.0 });
            }
        }
        assert_eq!(g.q(), [-1.0, 1.0, 0.0, 2.0, 0.0, 0.0]);
        // No coupling between the two bodies: only the two diagonal blocks are stored.
        let Delassus::SparseBlock(b) = g.w() else {
            panic!("sparse-block W expected")
        };
        assert_eq!(b.n_blocks(), 2);
    }

    #[test]
    fn unreadable_files_are_io_errors_naming_the_file() {
        let s = Scratch::new("io");
        let missing = s.path("missing.hdf5");
        let not_hdf5 = s.path("text.hdf5");
        std::fs::write(&not_hdf5, "3 1\n0 3 3\n").unwrap();
        for path in [missing, not_hdf5, s.0.clone()] {
            match read_fclib_file(&path) {
                Err(Fc3dError::Io { file, .. }) => assert_eq!(file, path.display().to_string()),
                other => panic!("{}: expected Io, got {other:?}", path.display()),
            }
        }
    }

    #[test]
    fn two_dimensional_problems_are_unsupported() {
        let s = Scratch::new("2d");
        let path = s.path("fc2d.hdf5");
        let mut l = Local::valid();
        l.spacedim = 2;
        l.write(&path);
        match read_fclib_file(&path) {
            Err(Fc3dError::Unsupported(m)) => {
                assert!(m.contains("spacedim = 2") && m.contains("fc2d.hdf5"), "{m}")
            }
            other => panic!("expected Unsupported, got {other:?}"),
        }
    }

    #[test]
    fn damaged_local_files_are_typed_errors() {
        let s = Scratch::new("local");
        let path = s.path("bad.hdf5");
        type Damage = (&'static str, fn(&mut Local));
        let cases: [Damage; 10] = [
            ("nz = -3", |l| l.w.nz = -3),
            ("index out of range", |l| l.w.i[4] = 6),
            ("index out of range", |l| l.w.i[0] = -1),
            ("decreases", |l| l.w.p[3] = 1),
            ("p has 6 entries, expected 7", |l| {
                l.w.p.pop().map(|_| ()).unwrap()
            }),
            ("p[0] = 1", |l| l.w.p[0] = 1),
            ("fewer than nz = 7", |l| l.w.nz = 7),
            ("expected a square matrix", |l| {
                l.w.n = 3;
                l.w.p.truncate(4);
            }),
            ("/fclib_local/vectors/q has 5 entries", |l| {
                l.q.pop();
            }),
            ("/fclib_local/vectors/mu has 3 entries", |l| l.mu.push(0.1)),
        ];
        for (needle, damage) in cases {
            let mut l = Local::valid();
            damage(&mut l);
            l.write(&path);
            invalid_structure(&path, needle);
        }

        let mut l = Local::valid();
        l.w.x[2] = f64::NAN;
        l.write(&path);
        match read_fclib_file(&path) {
            Err(Fc3dError::NonFinite { what, index: 2 }) => {
                assert!(what.contains("/fclib_local/W/x"), "{what}")
            }
            other => panic!("expected NonFinite, got {other:?}"),
        }

        // Missing pieces and a mistyped dataset.
        {
            let f = hdf5::File::create(&path).unwrap();
            f.create_group("something_else").unwrap();
        }
        invalid_structure(&path, "neither /fclib_local nor /fclib_global");
        {
            let f = hdf5::File::create(&path).unwrap();
            let g = f.create_group("fclib_local").unwrap();
            g.new_dataset_builder()
                .with_data(&[3i32])
                .create("spacedim")
                .unwrap();
        }
        invalid_structure(&path, "/fclib_local/W is missing");
        {
            let f = hdf5::File::create(&path).unwrap();
            let g = f.create_group("fclib_local").unwrap();
            g.new_dataset_builder()
                .with_data(&[3.0f64])
                .create("spacedim")
                .unwrap();
        }
        invalid_structure(&path, "/fclib_local/spacedim holds float");
    }

    #[test]
    fn damaged_global_files_are_typed_errors() {
        let s = Scratch::new("global");
        let path = s.path("bad.hdf5");
        type Damage = (&'static str, fn(&mut Global));
        let cases: [Damage; 5] = [
            // A zero pivot: M singular, reported as such rather than NaNs in W.
            ("singular", |g| g.m.x[4] = 0.0),
            // M = [[1, 1], [1, 1]] in the first two dofs: numerically singular.
            ("singular", |g| {
                g.m = Sparse {
                    m: 6,
                    n: 6,
                    nz: 8,
                    p: vec![0, 1, 0, 1, 2, 3, 4, 5],
                    i: vec![0, 0, 1, 1, 2, 3, 4, 5],
                    x: vec![1.0; 8],
                }
            }),
            ("H has 7 rows but M has 6", |g| g.h.m = 7),
            ("/fclib_global/vectors/f has 5 entries", |g| {
                g.f.pop();
            }),
            ("not a multiple of the space dimension", |g| {
                g.h.n = 5;
                g.h.nz = 5;
                g.w.pop();
            }),
        ];
        for (needle, damage) in cases {
            let mut g = Global::valid();
            damage(&mut g);
            g.write(&path);
            invalid_structure(&path, needle);
        }
    }
}

//! FCLIB `.hdf5` problems: the two shared Siconos files load with the right sizes, the reduction
//! of the global one agrees with the solution stored in the file, NSGS reaches 1e-8 on both (with
//! iterations and errors printed next to Siconos 4.4's from `siconos-reference-1e-8.csv`), and
//! damaged files give typed errors naming the file, never a panic. The writer: every shared 3D
//! `.dat` problem goes `.dat` -> `.hdf5` -> `.dat` without changing a bit (W in the same storage,
//! q, mu, and the `.dat` text itself), in FCLIB's layout, in all three storages.
//!
//! Everything that needs libhdf5 is behind the `fclib` feature
//! (`cargo test -p fc3d-core --features fclib --test fclib`); without it only the checks that
//! `.hdf5` files are refused with a clear message run.

use std::path::{Path, PathBuf};

use fc3d_core::io::read_problem_file;
use fc3d_core::Fc3dError;

const DATA_DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/data/siconos");

fn data(name: &str) -> PathBuf {
    Path::new(DATA_DIR).join(name)
}

/// The 3D local problems of the shared collection: the `.dat` files except the global ones
/// (`GFC3D_`, `gfc2d_`), the 2D ones (`fc2d_`, `FC2D_`, `FrictionContactProblem*`) and
/// `ACinputs.dat` (not a problem).
fn shared_3d_dat_files() -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(DATA_DIR)
        .expect("the shared Siconos data directory")
        .map(|e| e.expect("a directory entry").path())
        .filter(|p| {
            let name = p.file_name().and_then(|n| n.to_str()).unwrap_or("");
            name.ends_with(".dat")
                && ![
                    "GFC3D_",
                    "gfc2d_",
                    "fc2d_",
                    "FC2D_",
                    "FrictionContactProblem",
                ]
                .iter()
                .any(|prefix| name.starts_with(prefix))
                && name != "ACinputs.dat"
        })
        .collect();
    files.sort();
    files
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
    use fc3d_core::io::{read_fclib_file, read_fclib_info, FCLIB_AVAILABLE};
    assert!(!FCLIB_AVAILABLE);
    for name in ["Box_Stacks-i0122-82-5.hdf5", "missing.H5"] {
        for result in [
            read_problem_file(&data(name)).map(drop),
            read_fclib_file(&data(name)).map(drop),
            read_fclib_info(&data(name)).map(drop),
        ] {
            match result {
                Err(Fc3dError::Unsupported(m)) => {
                    assert!(m.contains(name), "{m}");
                    assert!(m.contains("built without the `fclib` feature"), "{m}");
                }
                other => panic!("expected Unsupported, got {other:?}"),
            }
        }
    }
}

#[cfg(not(feature = "fclib"))]
#[test]
fn writing_hdf5_needs_the_fclib_feature_and_writes_nothing() {
    use fc3d_core::io::{write_fclib_file, write_problem_file, FclibInfo};
    let p = read_problem_file(&data("FC3D_Example1.dat")).expect("a .dat problem");
    let dir = std::env::temp_dir().join(format!("fc3d-fclib-nofeature-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("out.hdf5");
    for result in [
        write_problem_file(&p, &out, &FclibInfo::default()),
        write_fclib_file(&p, &out, &FclibInfo::default()),
    ] {
        match result {
            Err(Fc3dError::Unsupported(m)) => {
                assert!(m.contains("out.hdf5"), "{m}");
                assert!(m.contains("cannot be written"), "{m}");
                assert!(m.contains("built without the `fclib` feature"), "{m}");
            }
            other => panic!("expected Unsupported, got {other:?}"),
        }
    }
    assert_eq!(
        std::fs::read_dir(&dir).unwrap().count(),
        0,
        "nothing written"
    );
    // .dat files are written as before.
    write_problem_file(&p, &dir.join("out.dat"), &FclibInfo::default()).unwrap();
    assert_eq!(read_problem_file(&dir.join("out.dat")).unwrap(), p);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_shared_collection_has_its_3d_problems() {
    assert_eq!(shared_3d_dat_files().len(), 30);
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

    // ---- the writer ----

    use fc3d_core::io::{
        parse_dat, read_fclib_info, write_dat, write_fclib_file, write_problem_file, FclibInfo,
    };
    use fc3d_core::matrix::{BlockSparseMatrix, CsrMatrix, DenseMatrix};

    /// Every stored value of W in storage order, with the storage's structure: equal lists mean
    /// equal matrices bit for bit (signed zeros included), in the same storage.
    fn w_bits(w: &Delassus<'_>) -> (String, Vec<usize>, Vec<u64>) {
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<u64>>();
        match w {
            Delassus::Dense(d) => (
                format!("dense {}x{}", d.nrows(), d.ncols()),
                Vec::new(),
                bits(d.values()),
            ),
            Delassus::SparseBlock(b) => (
                format!("sparse-block {}x{}", b.n_block_rows(), b.n_block_cols()),
                b.row_ptr().iter().chain(b.col_idx()).copied().collect(),
                bits(&b.blocks().flatten().copied().collect::<Vec<f64>>()),
            ),
            Delassus::Sparse(c) => (
                format!("csr {}x{}", c.nrows(), c.ncols()),
                c.row_ptr().iter().chain(c.col_idx()).copied().collect(),
                bits(c.values()),
            ),
        }
    }

    fn assert_identical(a: &FrictionProblem<'_>, b: &FrictionProblem<'_>, what: &str) {
        assert_eq!(a, b, "{what}");
        assert_eq!(w_bits(a.w()), w_bits(b.w()), "{what}: W");
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<u64>>();
        assert_eq!(bits(a.q()), bits(b.q()), "{what}: q");
        assert_eq!(bits(a.mu()), bits(b.mu()), "{what}: mu");
    }

    fn dat_text(p: &FrictionProblem<'_>) -> String {
        let mut bytes = Vec::new();
        write_dat(p, &mut bytes).unwrap();
        String::from_utf8(bytes).unwrap()
    }

    fn info_of(name: &str) -> FclibInfo {
        FclibInfo {
            title: Some(name.to_string()),
            description: Some(format!("{name} rewritten by fc3d's FCLIB writer")),
            math_info: Some("unknown".to_string()),
            number_of_degrees_of_freedom: Some(-1),
        }
    }

    #[test]
    fn every_shared_3d_problem_round_trips_dat_hdf5_dat_bit_for_bit() {
        let s = Scratch::new("roundtrip");
        let files = shared_3d_dat_files();
        assert_eq!(files.len(), 30);
        for path in files {
            let name = path.file_name().unwrap().to_str().unwrap();
            let original = read_problem_file(&path).unwrap_or_else(|e| panic!("{name}: {e}"));
            let hdf5 = s.path(&format!("{name}.hdf5"));
            let info = info_of(name);
            write_problem_file(&original, &hdf5, &info).unwrap_or_else(|e| panic!("{name}: {e}"));
            let back = read_problem_file(&hdf5).unwrap_or_else(|e| panic!("{name}: {e}"));
            assert_identical(&original, &back, name);
            assert_eq!(read_fclib_info(&hdf5).unwrap(), info, "{name}");
            // And back to .dat: the same text as the original problem writes, which reads back
            // to the original.
            let dat = s.path(&format!("{name}.dat"));
            write_problem_file(&back, &dat, &FclibInfo::default()).unwrap();
            let text = std::fs::read_to_string(&dat).unwrap();
            assert_eq!(text, dat_text(&original), "{name}");
            assert_identical(&parse_dat(&text, name).unwrap(), &original, name);
            let file = hdf5::File::open(&hdf5).unwrap();
            println!(
                "{name}: {} contacts, W {} with {} stored entries, {} bytes of FCLIB",
                original.n_contacts(),
                original.w().storage_name(),
                read_ints(&file, "/fclib_local/W/nzmax")[0],
                std::fs::metadata(&hdf5).unwrap().len()
            );
        }
    }

    /// A problem with the awkward values: signed zeros, an explicit zero entry, an all-zero
    /// off-diagonal block, and a denormal.
    fn awkward() -> FrictionProblem<'static> {
        let mut blocks = vec![[0.0; 9]; 3];
        blocks[0] = [2.0, -0.0, 0.5, 0.0, 3.0, 1e-310, -1.25, 0.0, 4.0];
        blocks[1] = [-0.0; 9]; // block (0, 1): stored, all (negative) zeros
        blocks[2] = [5.0, 0.0, 0.0, 0.0, 5.0, 0.0, 0.0, 0.0, 5.0];
        let w = BlockSparseMatrix::new(2, 2, vec![0, 2, 3], vec![0, 1, 1], blocks).unwrap();
        FrictionProblem::new(
            Delassus::SparseBlock(w),
            vec![-1.0, -0.0, 0.0, 2.5, 1e-300, -7.0],
            vec![0.3, -0.0],
        )
        .unwrap()
    }

    #[test]
    fn all_three_storages_round_trip_exactly() {
        let s = Scratch::new("storages");
        let base = awkward();
        let dense = {
            // Column-major 6x6 with a negative zero and a denormal.
            let mut v = vec![0.0; 36];
            base.w().for_each_entry(|i, j, x| v[i + 6 * j] = x);
            v[1 + 6 * 4] = -0.0;
            v[5] = f64::MIN_POSITIVE / 8.0;
            Delassus::Dense(DenseMatrix::new(6, 6, v).unwrap())
        };
        let csr = Delassus::Sparse(
            CsrMatrix::from_triplets(
                6,
                6,
                &[
                    (0, 0, 2.0),
                    (0, 3, -0.0), // explicit entries that are zero
                    (1, 1, 0.0),
                    (1, 1, 3.0), // a duplicate, summed by the constructor
                    (2, 0, 0.5),
                    (3, 3, 5.0),
                    (4, 4, 5.0),
                    (5, 5, 5.0),
                    (5, 0, -1e-310),
                ],
            )
            .unwrap(),
        );
        for (label, w) in [
            ("sparse-block", base.w().clone()),
            ("dense", dense),
            ("csr", csr),
        ] {
            let p = base.with_w(w).unwrap();
            let path = s.path(&format!("{label}.h5"));
            write_fclib_file(&p, &path, &FclibInfo::default()).unwrap();
            let back = read_fclib_file(&path).unwrap();
            assert_eq!(back.w().storage_name(), p.w().storage_name(), "{label}");
            assert_identical(&p, &back, label);
            assert_eq!(read_fclib_info(&path).unwrap(), FclibInfo::default());
        }
    }

    #[test]
    fn written_files_have_fclibs_layout() {
        let s = Scratch::new("layout");
        let p = read_problem_file(&data("Confeti-ex13-4contact-Fc3D-SBM.dat")).unwrap();
        let Delassus::SparseBlock(b) = p.w() else {
            panic!("Confeti-ex13-4contact is a sparse-block problem")
        };
        let path = s.path("confeti.hdf5");
        let info = info_of("Confeti-ex13-4contact");
        write_fclib_file(&p, &path, &info).unwrap();
        let file = hdf5::File::open(&path).unwrap();
        let n = p.size() as i64;
        let nnz = 9 * b.n_blocks() as i64;
        // Every integer is a C int, every real a double, every array one-dimensional.
        for (ds, len) in [
            ("/fclib_local/spacedim", 1),
            ("/fclib_local/W/nzmax", 1),
            ("/fclib_local/W/m", 1),
            ("/fclib_local/W/n", 1),
            ("/fclib_local/W/nz", 1),
            ("/fclib_local/W/p", n + 1),
            ("/fclib_local/W/i", nnz),
        ] {
            let d = file.dataset(ds).unwrap();
            assert_eq!(d.shape(), [len as usize], "{ds}");
            assert_eq!(
                d.dtype().unwrap().to_descriptor().unwrap(),
                hdf5::types::TypeDescriptor::Integer(hdf5::types::IntSize::U4),
                "{ds}"
            );
        }
        for (ds, len) in [
            ("/fclib_local/W/x", nnz),
            ("/fclib_local/vectors/q", n),
            ("/fclib_local/vectors/mu", n / 3),
        ] {
            let d = file.dataset(ds).unwrap();
            assert_eq!(d.shape(), [len as usize], "{ds}");
            assert_eq!(
                d.dtype().unwrap().to_descriptor().unwrap(),
                hdf5::types::TypeDescriptor::Float(hdf5::types::FloatSize::U8),
                "{ds}"
            );
        }
        assert_eq!(read_ints(&file, "/fclib_local/spacedim"), [3]);
        assert_eq!(read_ints(&file, "/fclib_local/W/nz"), [-2]);
        assert_eq!(read_ints(&file, "/fclib_local/W/m"), [n]);
        assert_eq!(read_ints(&file, "/fclib_local/W/n"), [n]);
        assert_eq!(read_ints(&file, "/fclib_local/W/nzmax"), [nnz]);
        // Compressed rows: every row lists its entries, W[row, col] = x.
        let (ptr, col, x) = (
            read_ints(&file, "/fclib_local/W/p"),
            read_ints(&file, "/fclib_local/W/i"),
            read_vec(&file, "/fclib_local/W/x"),
        );
        for row in 0..n as usize {
            for k in ptr[row] as usize..ptr[row + 1] as usize {
                assert_eq!(p.w().get(row, col[k] as usize).to_bits(), x[k].to_bits());
            }
        }
        assert_eq!(ptr[n as usize], nnz);
        assert_eq!(read_vec(&file, "/fclib_local/vectors/q"), p.q());
        // The info strings are scalar fixed-length C strings of their length plus the NUL, as
        // H5LTmake_dataset_string writes them; numberOfDegreeOfFreedom is an int attribute.
        for (name, value) in [
            ("title", info.title.as_deref().unwrap()),
            ("description", info.description.as_deref().unwrap()),
            ("math_info", info.math_info.as_deref().unwrap()),
        ] {
            let d = file.dataset(&format!("/fclib_local/info/{name}")).unwrap();
            assert!(d.shape().is_empty(), "{name} is a scalar");
            assert_eq!(
                d.dtype().unwrap().to_descriptor().unwrap(),
                hdf5::types::TypeDescriptor::FixedAscii(value.len() + 1),
                "{name}"
            );
            let text: hdf5::types::FixedAscii<256> = d.read_scalar().unwrap();
            assert_eq!(text.as_str(), value);
        }
        let ndof = file
            .group("/fclib_local/info")
            .unwrap()
            .attr("numberOfDegreeOfFreedom")
            .unwrap();
        assert_eq!(ndof.read_raw::<i32>().unwrap(), [-1]);
        let storage = file
            .group("/fclib_local/W")
            .unwrap()
            .attr("fc3d_storage")
            .unwrap();
        assert_eq!(storage.read_raw::<i32>().unwrap(), [1]);
    }

    #[test]
    fn readers_that_ignore_the_storage_attribute_get_the_same_values() {
        // Without fc3d_storage (FCLIB's and Siconos' readers do not know it), the rule for
        // foreign files applies: 3x3 blocks with a non-zero entry plus the diagonal ones. The
        // values are the same; only exact zeros may lose their blocks or their sign.
        let s = Scratch::new("nohint");
        for name in [
            "FC3D_Example1.dat",
            "Capsules-i101-404.dat",
            "NESpheres_10_1.dat",
        ] {
            let p = read_problem_file(&data(name)).unwrap();
            let path = s.path("plain.hdf5");
            write_fclib_file(&p, &path, &FclibInfo::default()).unwrap();
            {
                let file = hdf5::File::open_rw(&path).unwrap();
                file.group("/fclib_local/W")
                    .unwrap()
                    .delete_attr("fc3d_storage")
                    .unwrap();
            }
            let back = read_fclib_file(&path).unwrap();
            assert!(matches!(back.w(), Delassus::SparseBlock(_)), "{name}");
            p.w()
                .for_each_entry(|i, j, v| assert_eq!(back.w().get(i, j), v, "{name} W[{i},{j}]"));
            back.w()
                .for_each_entry(|i, j, v| assert_eq!(p.w().get(i, j), v, "{name} W[{i},{j}]"));
            assert_eq!(back.q(), p.q());
            assert_eq!(back.mu(), p.mu());
        }
    }

    #[test]
    fn writing_replaces_the_file_and_leaves_nothing_on_failure() {
        let s = Scratch::new("replace");
        let path = s.path("p.hdf5");
        let a = read_problem_file(&data("FC3D_Example1.dat")).unwrap();
        let b = read_problem_file(&data("Rover4396.dat")).unwrap();
        write_fclib_file(&a, &path, &info_of("a")).unwrap();
        write_fclib_file(&b, &path, &FclibInfo::default()).unwrap();
        assert_identical(&read_fclib_file(&path).unwrap(), &b, "replaced");
        assert_eq!(read_fclib_info(&path).unwrap(), FclibInfo::default());
        let before = std::fs::read(&path).unwrap();

        // A NUL in a string is refused before anything is written; the old file stays.
        let bad = FclibInfo {
            description: Some("a\0b".into()),
            ..FclibInfo::default()
        };
        match write_fclib_file(&a, &path, &bad) {
            Err(Fc3dError::Unsupported(m)) => {
                assert!(
                    m.contains("p.hdf5") && m.contains("description") && m.contains("NUL"),
                    "{m}"
                )
            }
            other => panic!("expected Unsupported, got {other:?}"),
        }
        assert_eq!(std::fs::read(&path).unwrap(), before);

        // Unwritable places are Io errors naming the path.
        for target in [s.0.clone(), s.path("no/such/dir/p.hdf5")] {
            match write_fclib_file(&a, &target, &FclibInfo::default()) {
                Err(Fc3dError::Io { file, .. }) => assert_eq!(file, target.display().to_string()),
                other => panic!("{}: expected Io, got {other:?}", target.display()),
            }
        }
        // No temporary file is left behind.
        let names: Vec<String> = std::fs::read_dir(&s.0)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        assert_eq!(names, ["p.hdf5"]);
    }

    #[test]
    fn a_problem_without_contacts_round_trips() {
        let s = Scratch::new("empty");
        let p = FrictionProblem::new(
            Delassus::Dense(DenseMatrix::new(0, 0, Vec::new()).unwrap()),
            Vec::new(),
            Vec::new(),
        )
        .unwrap();
        let path = s.path("empty.hdf5");
        write_fclib_file(&p, &path, &FclibInfo::default()).unwrap();
        assert_identical(&read_fclib_file(&path).unwrap(), &p, "no contacts");
    }

    #[test]
    fn info_of_the_shared_files_and_of_foreign_strings() {
        for name in [BOX_STACKS, PERIO_BOX] {
            let info = read_fclib_info(&data(name)).unwrap();
            println!("{name}: {info:?}");
        }
        // h5py writes variable-length strings; a file without an info group has an empty one.
        let s = Scratch::new("info");
        let path = s.path("vlen.hdf5");
        Local::valid().write(&path);
        assert_eq!(read_fclib_info(&path).unwrap(), FclibInfo::default());
        {
            let f = hdf5::File::open_rw(&path).unwrap();
            let g = f.create_group("fclib_local/info").unwrap();
            let title: hdf5::types::VarLenUnicode = "Pile de cubes é".parse().unwrap();
            g.new_dataset::<hdf5::types::VarLenUnicode>()
                .create("title")
                .unwrap()
                .write_scalar(&title)
                .unwrap();
            g.new_attr::<i64>()
                .shape(1)
                .create("numberOfDegreeOfFreedom")
                .unwrap()
                .write_raw(&[450i64])
                .unwrap();
        }
        let info = read_fclib_info(&path).unwrap();
        assert_eq!(info.title.as_deref(), Some("Pile de cubes é"));
        assert_eq!(info.description, None);
        assert_eq!(info.number_of_degrees_of_freedom, Some(450));
    }

    /// The global problem of Box_Stacks read, written as Siconos writes it (triplets) and read
    /// again: the same problem, bit for bit, with its info; its reduction is the local problem
    /// `read_fclib_file` gives, and the file holds what Siconos' reader expects.
    #[test]
    fn global_problems_round_trip_and_reduce() {
        use fc3d_core::io::{read_fclib_global_file, write_fclib_global_file};
        let path = data(BOX_STACKS);
        let g = read_fclib_global_file(&path).unwrap();
        assert_eq!((g.ndof(), g.n_contacts()), (450, 82));
        assert_eq!(g.m().nnz(), 450);
        let s = Scratch::new("global-write");
        let out = s.path("box.hdf5");
        let info = FclibInfo {
            title: Some("Box stacks".into()),
            description: Some("written by fc3d".into()),
            math_info: None,
            number_of_degrees_of_freedom: None,
        };
        write_fclib_global_file(&g, &out, &info).unwrap();
        let again = read_fclib_global_file(&out).unwrap();
        assert_eq!(again, g);
        assert_eq!(
            fc3d_core::io::read_fclib_info(&out).unwrap().title,
            info.title
        );
        // Siconos' layout: triplets (nz = number of entries), f, w, mu.
        let file = hdf5::File::open(&out).unwrap();
        assert_eq!(read_ints(&file, "/fclib_global/H/nz"), [g.h().nnz() as i64]);
        assert_eq!(read_ints(&file, "/fclib_global/spacedim"), [3]);
        assert_eq!(read_vec(&file, "/fclib_global/vectors/w"), g.b());
        // The local reading of a global file is the problem's reduction.
        let mut operator = g.operator().unwrap();
        let reduced = g.reduce(&mut operator).unwrap();
        assert_eq!(read_fclib_file(&out).unwrap(), reduced);
        assert_eq!(read_fclib_file(&path).unwrap(), reduced);
        // A local file has no global problem.
        match read_fclib_global_file(&data(PERIO_BOX)) {
            Err(Fc3dError::InvalidStructure(m)) => assert!(m.contains("/fclib_global"), "{m}"),
            other => panic!("{other:?}"),
        }
    }
}

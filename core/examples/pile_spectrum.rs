//! Extreme eigenvalues of W on range(W) for the generated piles, and how the condition number
//! grows with size and pile height (docs/convergence.md):
//!
//! `cargo run --release -p fc3d-core --example pile_spectrum -- [--shape spheres|boxes]
//! [--piles P] [--min-steps N] [--max-steps N] [--budget SECONDS] [--csv FILE] CONTACTS...`
//!
//! W = H^T M^-1 H (3 nc x 3 nc) is singular on a hyperstatic pile; its nonzero spectrum is that
//! of the body-space operator `A = M^-1 H H^T` (6 a body), self-adjoint in the M inner product,
//! which is nonsingular when every body is held (H of full row rank). Lanczos on A in the M inner
//! product (`fc3d_core::math::spectrum`) gives the largest eigenvalue in a few dozen steps and
//! the smallest one, the smallest nonzero eigenvalue of W, once the smallest Ritz value has
//! settled (about `sqrt(condition)` steps: it decreases monotonically towards it). The largest
//! is checked against Lanczos on W itself (its block-sparse product). When A is singular (a
//! body with a motion no contact sees) the condition column says `singular`.

use std::io::Write;
use std::time::Instant;

use fc3d_core::math::spectrum::{euclidean, Lanczos};
use fc3d_core::matrix::CsrMatrix;
use fc3d_core::scenes::{GeneratedScene, PileShape, PileSpec};

struct Args {
    shape: PileShape,
    piles: usize,
    max_steps: usize,
    min_steps: usize,
    budget: f64,
    csv: Option<String>,
    sizes: Vec<usize>,
}

fn parse_args() -> Args {
    let mut a = Args {
        shape: PileShape::Spheres,
        piles: 4,
        max_steps: 40_000,
        min_steps: 1000,
        budget: 600.0,
        csv: None,
        sizes: Vec::new(),
    };
    let mut it = std::env::args().skip(1);
    while let Some(arg) = it.next() {
        let mut value = || it.next().expect("a value after the option");
        match arg.as_str() {
            "--shape" => a.shape = PileShape::from_name(&value()).expect("shape"),
            "--piles" => a.piles = value().parse().expect("piles"),
            "--max-steps" => a.max_steps = value().parse().expect("steps"),
            "--min-steps" => a.min_steps = value().parse().expect("steps"),
            "--budget" => a.budget = value().parse().expect("seconds"),
            "--csv" => a.csv = Some(value()),
            size => a.sizes.push(size.parse().expect("a contact count")),
        }
    }
    a
}

/// `x^T M y` for M in compressed rows.
fn m_inner(m: &CsrMatrix, x: &[f64], y: &[f64]) -> f64 {
    let (ptr, col, val) = (m.row_ptr(), m.col_idx(), m.values());
    let mut sum = 0.0;
    for (i, xi) in x.iter().enumerate() {
        let mut row = 0.0;
        for p in ptr[i]..ptr[i + 1] {
            row += val[p] * y[col[p]];
        }
        sum += xi * row;
    }
    sum
}

/// Smallest and largest eigenvalues of the body-space operator, the Lanczos steps taken and
/// whether the smallest settled (relative change below 1e-3 over the last fifth of the steps,
/// after at least `min_steps`).
fn body_space_extremes(
    scene: &GeneratedScene,
    (min_steps, max_steps): (usize, usize),
    budget: f64,
) -> (f64, f64, usize, bool, usize) {
    let global = scene.generate_global().expect("scene");
    let m = global.m().clone();
    let mut op = global.operator().expect("M factored");
    let ndof = op.ndof();
    let mut contact_work = vec![0.0; op.size()];
    let mut start = vec![0.0; ndof];
    Lanczos::default_start(&mut start);
    let inner = |x: &[f64], y: &[f64]| m_inner(&m, x, y);
    let mut lanczos = Lanczos::new(ndof, max_steps).expect("the Lanczos vectors");
    lanczos.start(&start, inner);
    let t = Instant::now();
    let mut history: Vec<(usize, f64)> = Vec::new();
    let mut next_check = 200;
    let mut settled = false;
    while lanczos.steps() < max_steps && t.elapsed().as_secs_f64() < budget {
        let more = lanczos.step(
            |x, y| {
                // y = M^-1 H H^T x.
                contact_work.iter_mut().for_each(|v| *v = 0.0);
                op.ht_mul_add(x, &mut contact_work);
                y.iter_mut().for_each(|v| *v = 0.0);
                op.h_mul_add(&contact_work, y);
                op.solve_mass(y);
            },
            inner,
        );
        if !more {
            settled = true;
            break;
        }
        if lanczos.steps() >= next_check {
            let (lo, _) = lanczos.extremes().expect("steps done");
            history.push((lanczos.steps(), lo));
            let k = lanczos.steps();
            if let Some(&(_, earlier)) = history.iter().rev().find(|(s, _)| *s <= k * 4 / 5) {
                if (earlier - lo).abs() <= 1e-3 * lo && k >= min_steps {
                    settled = true;
                    break;
                }
            }
            next_check = k + (k / 10).max(200);
        }
    }
    let (lo, hi) = lanczos.extremes().expect("steps done");
    (lo, hi, lanczos.steps(), settled, ndof)
}

/// The largest eigenvalue of W by Lanczos on its block-sparse product (`steps` steps).
fn w_largest(scene: &GeneratedScene, steps: usize) -> (f64, usize) {
    let p = scene.generate().expect("scene");
    let n = p.size();
    let mut start = vec![0.0; n];
    Lanczos::default_start(&mut start);
    let mut lanczos = Lanczos::new(n, steps).expect("the Lanczos vectors");
    lanczos.start(&start, euclidean);
    for _ in 0..steps {
        let more = lanczos.step(
            |x, y| {
                y.iter_mut().for_each(|v| *v = 0.0);
                p.w().mul_add(x, y);
            },
            euclidean,
        );
        if !more {
            break;
        }
    }
    (lanczos.extremes().expect("steps done").1, p.n_contacts())
}

fn main() {
    let args = parse_args();
    let header = "shape,contacts,piles,layers,ndof,lambda_max_w,lambda_max,lambda_min,condition,lanczos_steps,settled,seconds";
    println!("{header}");
    let mut csv = args
        .csv
        .as_ref()
        .map(|f| std::fs::File::create(f).expect("csv file"));
    if let Some(f) = csv.as_mut() {
        writeln!(f, "{header}").unwrap();
    }
    for &contacts in &args.sizes {
        let scene = GeneratedScene {
            pile: PileSpec {
                contacts,
                piles: args.piles,
                seed: 1,
            },
            shape: args.shape,
        };
        let t = Instant::now();
        let layers = scene.pile_layers().into_iter().max().unwrap_or(0);
        let (lambda_max_w, _) = w_largest(&scene, 60);
        let (lo, hi, steps, settled, ndof) =
            body_space_extremes(&scene, (args.min_steps, args.max_steps), args.budget);
        // A zero eigenvalue of the body-space operator is a motion no contact sees (H H^T
        // singular, e.g. a sphere on a single contact spinning about its normal): the smallest
        // eigenvalue of W on range(W) is then not this one, and the condition is not reported.
        let condition = if lo > 1e-9 * hi {
            format!("{:.6e}", hi / lo)
        } else {
            "singular".to_string()
        };
        let line = format!(
            "{},{contacts},{},{layers},{ndof},{lambda_max_w:.6e},{hi:.6e},{lo:.6e},{condition},{steps},{settled},{:.1}",
            args.shape.label(),
            args.piles,
            t.elapsed().as_secs_f64()
        );
        println!("{line}");
        if let Some(f) = csv.as_mut() {
            writeln!(f, "{line}").unwrap();
        }
    }
}

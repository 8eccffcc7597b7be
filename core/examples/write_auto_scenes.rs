//! Writes the generated problems of docs/auto.md's "AUTO against the best fixed solver" table
//! as Siconos `.dat` files: a tall tower of boxes (`scenes::box_towers`, one tower of 142 boxes,
//! 568 contacts, at rest and settling) and regular FCC sphere packings standing on the ground
//! (built here from H and M, see [`fcc_packing`]):
//! `cargo run --release -p fc3d-core --example write_auto_scenes -- DIR [CELLS...]`
//! (CELLS: the packings' sizes in lattice cells a side, default `4 8`: 1.6k and 11.6k contacts).

use std::path::Path;

use fc3d_core::io::write_dat_file;
use fc3d_core::problem::GlobalProblem;
use fc3d_core::scenes::{box_towers, TowerMotion, TowerSpec};
use fc3d_core::{CsrMatrix, FrictionProblem};

/// Sphere radius (m), mass (kg), time step (s), gravity (m/s^2) and friction of the packings.
const RADIUS: f64 = 0.05;
const MASS: f64 = 1.0;
const STEP: f64 = 0.01;
const GRAVITY: f64 = 9.81;
const MU: f64 = 0.5;

type Vec3 = [f64; 3];

fn cross(a: &Vec3, b: &Vec3) -> Vec3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn normalize(a: Vec3) -> Vec3 {
    let n = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    [a[0] / n, a[1] / n, a[2] / n]
}

/// The contact frame (normal first) of normal `n`.
fn frame(n: Vec3) -> [Vec3; 3] {
    let helper = if n[0].abs() < 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let t1 = normalize(cross(&n, &helper));
    let t2 = cross(&n, &t1);
    [n, t1, t2]
}

/// A regular FCC packing of equal spheres, `cells` cubic cells a side (4 spheres a cell, the
/// (001) planes horizontal), standing on the ground after one step of gravity: every pair of
/// spheres at distance 2R touches (12 neighbours inside), the bottom plane touches the ground.
/// Deterministic: no random number.
fn fcc_packing(cells: usize) -> FrictionProblem<'static> {
    let a = 2.0 * 2f64.sqrt() * RADIUS;
    let mut centres: Vec<Vec3> = Vec::new();
    // Half-cell lattice coordinates with an even sum: the FCC sites.
    let n = 2 * cells;
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                if (i + j + k) % 2 == 0 {
                    let h = a / 2.0;
                    centres.push([h * i as f64, h * j as f64, RADIUS + h * k as f64]);
                }
            }
        }
    }
    let index = |i: usize, j: usize, k: usize| -> Option<usize> {
        // Sites of layer k, row j: those with i of the parity of j + k, in order.
        (i < n && j < n && k < n && (i + j + k) % 2 == 0).then(|| {
            let per_row = |jj: usize, kk: usize| (n + 1 - (jj + kk) % 2) / 2;
            let rows_before: usize = (0..j).map(|jj| per_row(jj, k)).sum();
            let layers_before: usize = (0..k)
                .map(|kk| (0..n).map(|jj| per_row(jj, kk)).sum::<usize>())
                .sum();
            layers_before + rows_before + i / 2
        })
    };
    // (body a or the ground, body b, normal from a to b).
    let mut contacts: Vec<(Option<usize>, usize, Vec3)> = Vec::new();
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                let Some(b) = index(i, j, k) else { continue };
                if k == 0 {
                    contacts.push((None, b, [0.0, 0.0, 1.0]));
                }
                // The neighbours before this site (lower layer, or same layer earlier).
                let offsets: [(isize, isize, isize); 6] = [
                    (-1, 0, -1),
                    (1, 0, -1),
                    (0, -1, -1),
                    (0, 1, -1),
                    (-1, -1, 0),
                    (1, -1, 0),
                ];
                for (di, dj, dk) in offsets {
                    let (ii, jj, kk) = (i as isize + di, j as isize + dj, k as isize + dk);
                    if ii < 0 || jj < 0 || kk < 0 {
                        continue;
                    }
                    if let Some(a) = index(ii as usize, jj as usize, kk as usize) {
                        let (xa, xb) = (centres[a], centres[b]);
                        let normal = normalize([xb[0] - xa[0], xb[1] - xa[1], xb[2] - xa[2]]);
                        contacts.push((Some(a), b, normal));
                    }
                }
            }
        }
    }
    let nb = centres.len();
    let inertia = 0.4 * MASS * RADIUS * RADIUS;
    let mut m = Vec::with_capacity(6 * nb);
    let mut q = vec![0.0; 6 * nb];
    for body in 0..nb {
        for d in 0..3 {
            m.push((6 * body + d, 6 * body + d, MASS));
            m.push((6 * body + 3 + d, 6 * body + 3 + d, inertia));
        }
        q[6 * body + 2] = -MASS * GRAVITY * STEP;
    }
    let mut h = Vec::new();
    for (c, &(a, b, normal)) in contacts.iter().enumerate() {
        let f = frame(normal);
        // u = F^T (velocity of b's point - velocity of a's point); the point is R from each
        // centre along the normal, the velocity of a point at arm r is v + omega x r.
        let arms = [(Some(b), -1.0, 1.0), (a, 1.0, -1.0)];
        for (body, arm_sign, sign) in arms {
            let Some(body) = body else { continue };
            let r = normal.map(|x| arm_sign * RADIUS * x);
            for (i, t) in f.iter().enumerate() {
                // t . (omega x r) = omega . (r x t).
                let rt = cross(&r, t);
                for d in 0..3 {
                    h.push((6 * body + d, 3 * c + i, sign * t[d]));
                    h.push((6 * body + 3 + d, 3 * c + i, sign * rt[d]));
                }
            }
        }
    }
    let nc = contacts.len();
    let global = GlobalProblem::<3>::new(
        CsrMatrix::from_triplets(6 * nb, 6 * nb, &m).expect("M"),
        CsrMatrix::from_triplets(6 * nb, 3 * nc, &h).expect("H"),
        q,
        vec![0.0; 3 * nc],
        vec![MU; nc],
    )
    .expect("global problem");
    let mut operator = global.operator().expect("M factors");
    global.reduce(&mut operator).expect("W")
}

fn main() {
    let mut args = std::env::args().skip(1);
    let dir = args
        .next()
        .expect("usage: write_auto_scenes DIR [CELLS...]");
    let mut sizes: Vec<usize> = args.map(|a| a.parse().expect("cells a side")).collect();
    if sizes.is_empty() {
        sizes = vec![4, 8];
    }
    std::fs::create_dir_all(&dir).expect("output directory");
    for motion in [TowerMotion::Rest, TowerMotion::Settling] {
        let spec = TowerSpec {
            towers: 1,
            height: 142,
            motion,
            seed: 1,
        };
        let problem = box_towers(&spec).expect("tower scene");
        let path = Path::new(&dir).join(format!("{}.dat", spec.name()));
        write_dat_file(&problem, &path).expect("write the problem");
        println!("{} ({} contacts)", path.display(), problem.n_contacts());
    }
    for cells in sizes {
        let problem = fcc_packing(cells);
        let path = Path::new(&dir).join(format!("fcc-c{cells}.dat"));
        write_dat_file(&problem, &path).expect("write the problem");
        println!("{} ({} contacts)", path.display(), problem.n_contacts());
    }
}

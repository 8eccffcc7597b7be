//! A seeded generator of extreme frictional contact problems (issue 6): the scenes a host may hand
//! us on a bad day. Point masses in contact with each other and with the ground, each contact with
//! its own (random) orthonormal frame, `W = J M^-1 J^T` assembled exactly, `q = J v_free` with the
//! free velocity pushing everything down. The same seed gives the same problems bit for bit.

use fc3d_core::{Delassus, DenseMatrix, FrictionProblem};

/// SplitMix64: tiny, portable, reproducible.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Rng(seed)
    }
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1).
    pub fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    pub fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.uniform()
    }
}

/// A contact between body `a` and body `b` (`None`: the ground), with its frame (rows: normal,
/// tangent 1, tangent 2; the normal points from b to a).
#[derive(Clone, Copy)]
struct Contact {
    a: usize,
    b: Option<usize>,
    frame: [[f64; 3]; 3],
}

/// An orthonormal frame whose normal is within `tilt` radians of the vertical.
fn frame(rng: &mut Rng, tilt: f64) -> [[f64; 3]; 3] {
    let th = rng.range(0.0, tilt);
    let ph = rng.range(0.0, std::f64::consts::TAU);
    let n = [th.sin() * ph.cos(), th.sin() * ph.sin(), th.cos()];
    // Any vector not parallel to n, orthogonalised.
    let e = if n[0].abs() < 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let d = n[0] * e[0] + n[1] * e[1] + n[2] * e[2];
    let t1 = [e[0] - d * n[0], e[1] - d * n[1], e[2] - d * n[2]];
    let l = (t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]).sqrt();
    let t1 = [t1[0] / l, t1[1] / l, t1[2] / l];
    let t2 = [
        n[1] * t1[2] - n[2] * t1[1],
        n[2] * t1[0] - n[0] * t1[2],
        n[0] * t1[1] - n[1] * t1[0],
    ];
    [n, t1, t2]
}

/// Dense column-major `W = J M^-1 J^T` and `q = J v_free` for point masses.
fn assemble(masses: &[f64], contacts: &[Contact], v_free: &[[f64; 3]]) -> (Vec<f64>, Vec<f64>) {
    let n = 3 * contacts.len();
    // J as a dense (n x 3 nb) row-major matrix.
    let nb = masses.len();
    let mut j = vec![0.0; n * 3 * nb];
    for (c, ct) in contacts.iter().enumerate() {
        for row in 0..3 {
            for k in 0..3 {
                j[(3 * c + row) * 3 * nb + 3 * ct.a + k] += ct.frame[row][k];
                if let Some(b) = ct.b {
                    j[(3 * c + row) * 3 * nb + 3 * b + k] -= ct.frame[row][k];
                }
            }
        }
    }
    let mut w = vec![0.0; n * n];
    for i in 0..n {
        for jj in 0..n {
            let mut s = 0.0;
            for d in 0..3 * nb {
                s += j[i * 3 * nb + d] * j[jj * 3 * nb + d] / masses[d / 3];
            }
            w[i + jj * n] = s;
        }
    }
    let mut q = vec![0.0; n];
    for (i, qi) in q.iter_mut().enumerate() {
        for d in 0..3 * nb {
            *qi += j[i * 3 * nb + d] * v_free[d / 3][d % 3];
        }
    }
    (w, q)
}

/// A stack of `nb` point masses, each touching the one below at `per_body` points (the lowest
/// one touches the ground), everything falling at `v` (with a random horizontal drift so that
/// some contacts slide).
fn stack(rng: &mut Rng, masses: &[f64], per_body: usize) -> (Vec<Contact>, Vec<[f64; 3]>) {
    let mut contacts = Vec::new();
    for a in 0..masses.len() {
        for _ in 0..per_body {
            contacts.push(Contact {
                a,
                b: a.checked_sub(1),
                frame: frame(rng, 0.3),
            });
        }
    }
    let v_free = masses
        .iter()
        .enumerate()
        .map(|(k, _)| {
            [
                rng.range(-0.5, 0.5),
                rng.range(-0.5, 0.5),
                -0.1 * (1.0 + k as f64),
            ]
        })
        .collect();
    (contacts, v_free)
}

fn dense(n: usize, w: Vec<f64>, q: Vec<f64>, mu: Vec<f64>) -> FrictionProblem<'static> {
    let m = DenseMatrix::new(n, n, w).expect("square");
    FrictionProblem::new(Delassus::Dense(m), q, mu).expect("valid extreme problem")
}

/// The extreme problems, by name. All are valid inputs (finite, diagonal blocks present): each
/// must be solved or failed honestly, never crash or return NaN.
pub fn extreme_problems(seed: u64) -> Vec<(String, FrictionProblem<'static>)> {
    let mut rng = Rng::new(seed);
    let mut out = Vec::new();
    let base_masses = [1.0, 2.0, 0.5, 1.5];

    // Friction coefficients from frictionless to absurd.
    for mu in [0.0, 1e-6, 0.3, 1.0, 8.0, 1e3] {
        let (contacts, v) = stack(&mut rng, &base_masses, 2);
        let (w, q) = assemble(&base_masses, &contacts, &v);
        let n = w.len().isqrt();
        out.push((
            format!("mu={mu:e}"),
            dense(n, w, q, vec![mu; contacts.len()]),
        ));
    }
    // W scaled by 1e-8 and 1e8 (units of a host in grams and kilometres).
    for scale in [1e-8, 1e8] {
        let (contacts, v) = stack(&mut rng, &base_masses, 2);
        let (w, q) = assemble(&base_masses, &contacts, &v);
        let n = w.len().isqrt();
        let w = w.iter().map(|x| x * scale).collect();
        out.push((
            format!("W*{scale:e}"),
            dense(n, w, q, vec![0.3; contacts.len()]),
        ));
    }
    // Masses over twelve decades: cond(W) ~ 1e12.
    {
        let masses = [1e-6, 1e-2, 1e2, 1e6];
        let (contacts, v) = stack(&mut rng, &masses, 2);
        let (w, q) = assemble(&masses, &contacts, &v);
        let n = w.len().isqrt();
        out.push((
            "cond~1e12".into(),
            dense(n, w, q, vec![0.5; contacts.len()]),
        ));
    }
    // Contact density 3: three contacts per body, 9 unknowns per 3 degrees of freedom.
    {
        let (contacts, v) = stack(&mut rng, &base_masses[..3], 3);
        let (w, q) = assemble(&base_masses[..3], &contacts, &v);
        let n = w.len().isqrt();
        out.push((
            "rank-deficient (density 3)".into(),
            dense(n, w, q, vec![0.6; contacts.len()]),
        ));
    }
    // q = 0: nothing pushes, r = 0.
    {
        let (contacts, v) = stack(&mut rng, &base_masses, 1);
        let (w, _) = assemble(&base_masses, &contacts, &v);
        let n = w.len().isqrt();
        out.push((
            "q=0".into(),
            dense(n, w, vec![0.0; n], vec![0.3; contacts.len()]),
        ));
    }
    // The same contact twice (a duplicated collision pair).
    {
        let (mut contacts, v) = stack(&mut rng, &base_masses, 1);
        contacts.push(contacts[1]);
        let (w, q) = assemble(&base_masses, &contacts, &v);
        let n = w.len().isqrt();
        out.push((
            "duplicated contact".into(),
            dense(n, w, q, vec![0.4; contacts.len()]),
        ));
    }
    // Slightly non-symmetric W (Coriolis-like): a skew part of 1e-3 max|W| (x^T W x unchanged).
    {
        let (contacts, v) = stack(&mut rng, &base_masses, 2);
        let (mut w, q) = assemble(&base_masses, &contacts, &v);
        let n = w.len().isqrt();
        let wmax = w.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for i in 0..n {
            for j in 0..i {
                let s = 1e-3 * wmax * rng.range(-1.0, 1.0);
                w[i + j * n] += s;
                w[j + i * n] -= s;
            }
        }
        out.push((
            "non-symmetric 1e-3".into(),
            dense(n, w, q, vec![0.3; contacts.len()]),
        ));
    }
    // No contact at all.
    out.push(("zero contacts".into(), dense(0, vec![], vec![], vec![])));
    // One contact at the cone apex: q_N just below zero, r = O(1e-15).
    {
        let w = vec![1.0, 0.1, 0.0, 0.1, 2.0, 0.2, 0.0, 0.2, 1.5];
        out.push((
            "apex".into(),
            dense(3, w, vec![-1e-15, 1.0, 0.0], vec![0.3]),
        ));
    }
    // One contact sticking exactly: q = -W r* with r* inside the cone, so u = 0 and u_T = 0.
    {
        let w = vec![1.0, 0.1, 0.0, 0.1, 2.0, 0.2, 0.0, 0.2, 1.5];
        let r_star = [1.0, 0.1, -0.05];
        let mut q = vec![0.0; 3];
        for i in 0..3 {
            for j in 0..3 {
                q[i] -= w[i + 3 * j] * r_star[j];
            }
        }
        out.push(("stick u_T=0".into(), dense(3, w, q, vec![0.5])));
    }
    out
}

//! The generated scenes in the global form (Siconos' `GlobalFrictionContactProblem`): unknowns
//! the bodies' velocities `v = (linear, angular)`, 6 a body; `M` block diagonal, one 6x6 block
//! `diag(m I, J)` a body (J the angular iteration matrix, non-symmetric for a gyroscopic body);
//! `H^T` the contact Jacobians (`u_c = G_c v`, so column `3c + i` of H holds row i of contact c's
//! Jacobian on each of its bodies); `q = M v_free` (so `v = M^-1 (q + H r) = v_free + M^-1 H r`);
//! `b = 0`. Reduced, they give exactly the W and q of [`GeneratedScene::generate`] (up to
//! round-off).

use super::world::{inverse, World};
use super::{GeneratedScene, PileShape};
use crate::error::Fc3dError;
use crate::matrix::CsrMatrix;
use crate::problem::GlobalProblem;

impl World {
    fn global_problem(&self) -> Result<GlobalProblem<'static>, Fc3dError> {
        self.global_problem_with_b(vec![0.0; 3 * self.contacts.len()])
    }

    /// The global problem with the given `b` (3 entries per contact: `u = H^T v + b`), as a
    /// stepper shifts the normal rows of open contacts by `gap / dt`.
    pub(super) fn global_problem_with_b(
        &self,
        b: Vec<f64>,
    ) -> Result<GlobalProblem<'static>, Fc3dError> {
        let n = 6 * self.bodies.len();
        let mut m = Vec::with_capacity(12 * self.bodies.len());
        let mut q = vec![0.0; n];
        for (k, body) in self.bodies.iter().enumerate() {
            let o = 6 * k;
            let j = inverse(&body.inv_inertia);
            for i in 0..3 {
                m.push((o + i, o + i, body.mass));
                q[o + i] = body.mass * body.v_free[i];
                for c in 0..3 {
                    if j[i][c] != 0.0 {
                        m.push((o + 3 + i, o + 3 + c, j[i][c]));
                    }
                    q[o + 3 + i] += j[i][c] * body.v_free[3 + c];
                }
            }
        }
        let mut h = Vec::new();
        for c in 0..self.contacts.len() {
            for k in self.bodies_of(c) {
                let (lin, ang) = self.jacobian(c, k).expect("body of the contact");
                for i in 0..3 {
                    for d in 0..3 {
                        h.push((6 * k + d, 3 * c + i, lin[i][d]));
                        h.push((6 * k + 3 + d, 3 * c + i, ang[i][d]));
                    }
                }
            }
        }
        let mu: Vec<f64> = self.contacts.iter().map(|c| c.mu).collect();
        let nc = mu.len();
        GlobalProblem::new(
            CsrMatrix::from_triplets(n, n, &m)?,
            CsrMatrix::from_triplets(n, 3 * nc, &h)?,
            q,
            b,
            mu,
        )
    }
}

impl GeneratedScene {
    /// The scene in the global form (see the module's documentation).
    pub fn generate_global(&self) -> Result<GlobalProblem<'static>, Fc3dError> {
        let world = match self.shape {
            PileShape::Spheres => super::granular::pile_world(&self.pile)?,
            PileShape::Boxes => super::boxes::box_world(&self.pile)?,
            PileShape::Fcc => super::fcc::fcc_world(&self.pile)?,
        };
        world.global_problem()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenes::PileSpec;

    #[test]
    fn reduced_global_scenes_equal_the_local_ones() {
        for shape in [PileShape::Spheres, PileShape::Boxes, PileShape::Fcc] {
            let scene = GeneratedScene {
                pile: PileSpec {
                    contacts: 300,
                    piles: 1,
                    seed: 3,
                },
                shape,
            };
            let local = scene.generate().unwrap();
            let global = scene.generate_global().unwrap();
            let mut operator = global.operator().unwrap();
            assert!(operator.mass().is_block_diagonal());
            let reduced = global.reduce(&mut operator).unwrap();
            assert_eq!(reduced.n_contacts(), local.n_contacts());
            let scale = local.q().iter().fold(0.0_f64, |a, v| a.max(v.abs()));
            for (a, b) in reduced.q().iter().zip(local.q()) {
                assert!((a - b).abs() <= 1e-12 * scale, "{a} {b}");
            }
            let n = local.size();
            let mut wmax = 0.0_f64;
            local.w().for_each_entry(|_, _, v| wmax = wmax.max(v.abs()));
            let mut worst = 0.0_f64;
            local
                .w()
                .for_each_entry(|i, j, v| worst = worst.max((v - reduced.w().get(i, j)).abs()));
            reduced
                .w()
                .for_each_entry(|i, j, v| worst = worst.max((v - local.w().get(i, j)).abs()));
            assert!(
                worst <= 1e-12 * wmax,
                "{shape:?}: {worst} of {wmax} ({n} rows)"
            );
        }
    }
}

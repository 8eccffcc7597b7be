//! Generated towers of boxes: boxes stacked straight on one another, each face contact modelled
//! with 4 points (the corners of the overlap of the two faces), as LMGC90-style engines and
//! Siconos' box-stack examples (`BoxesStack1` of the shared problems: one tower of 13 boxes)
//! do. Every face gives 12 contact rows for the 6 degrees of freedom of the box above it: W is
//! rank-deficient (rank 6 per box), the scene is hyperstatic, and the Jacobian of a nonsmooth
//! Newton method is singular as soon as a box's contacts stick.
//!
//! Towers stand in a row along x with a gap between them (they share no body: separate islands
//! of W). A tower of height `h` has `4 h` contacts: its bottom box on the ground, each other box
//! on the one below. Horizontal half-widths vary by +-2 % and centres by +-1 % of the mean
//! half-width (so the overlaps, and therefore the contact points and arms, differ from face to
//! face), masses by +-20 %; the friction coefficient is one per tower in [0.3, 0.7]. With
//! [`TowerMotion::Rest`] the boxes only fall under one step of gravity (every contact sticks at
//! the solution: the most singular Newton systems); with [`TowerMotion::Settling`] each box also
//! has a small random horizontal velocity and spin (sticking, sliding and separating contacts).
//! Same spec, same bits: see [`super::granular`].

use super::granular::Random;
use super::world::{yaw, Body, Storage, World, E_Z};
use crate::error::Fc3dError;
use crate::problem::FrictionProblem;

/// Mean horizontal half-width of a box (m).
pub const TOWER_HALF_WIDTH: f64 = 0.1;
/// Half-height of every box (m).
pub const TOWER_HALF_HEIGHT: f64 = 0.05;
/// Mean mass of a box (kg).
const MASS: f64 = 1.0;

/// How the boxes of a tower move before the step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TowerMotion {
    /// At rest: gravity only.
    Rest,
    /// A small random horizontal velocity (up to 0.05 m/s) and spin (up to 0.5 rad/s) per box.
    Settling,
}

/// What to generate: `towers` towers of `height` boxes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TowerSpec {
    /// Number of towers (>= 1).
    pub towers: usize,
    /// Boxes per tower (>= 1).
    pub height: usize,
    pub motion: TowerMotion,
    /// Seed of the pseudo-random sequence.
    pub seed: u64,
}

impl TowerSpec {
    /// The number of contacts: 4 per box.
    pub fn contacts(&self) -> usize {
        4 * self.towers * self.height
    }

    /// A short name for tables and files: `towers-t1-h2-rest-s1`.
    pub fn name(&self) -> String {
        let motion = match self.motion {
            TowerMotion::Rest => "rest",
            TowerMotion::Settling => "settling",
        };
        format!(
            "towers-t{}-h{}-{motion}-s{}",
            self.towers, self.height, self.seed
        )
    }
}

/// Generates the towers of `spec` (sparse-block W).
pub fn box_towers(spec: &TowerSpec) -> Result<FrictionProblem<'static>, Fc3dError> {
    Ok(tower_world(spec)?.problem(Storage::SparseBlock))
}

fn tower_world(spec: &TowerSpec) -> Result<World, Fc3dError> {
    if spec.towers == 0 || spec.height == 0 {
        return Err(Fc3dError::InvalidOption(format!(
            "a tower scene needs at least one tower of one box, got {} towers of {} boxes",
            spec.towers, spec.height
        )));
    }
    let mut world = World::new();
    let mut random = Random(spec.seed);
    // Two box widths of empty ground between towers.
    let pitch = 6.0 * TOWER_HALF_WIDTH;
    for tower in 0..spec.towers {
        let mu = 0.5 + 0.2 * random.symmetric();
        let mut below: Option<(usize, [f64; 3], [f64; 2])> = None;
        for level in 0..spec.height {
            let jitter = 0.01 * TOWER_HALF_WIDTH;
            let x = [
                pitch * tower as f64 + jitter * random.symmetric(),
                jitter * random.symmetric(),
                TOWER_HALF_HEIGHT * (1 + 2 * level) as f64,
            ];
            let half = [
                TOWER_HALF_WIDTH * (1.0 + 0.02 * random.symmetric()),
                TOWER_HALF_WIDTH * (1.0 + 0.02 * random.symmetric()),
            ];
            let mass = MASS * (1.0 + 0.2 * random.symmetric());
            let (v, omega) = match spec.motion {
                TowerMotion::Rest => ([0.0; 3], [0.0; 3]),
                TowerMotion::Settling => (
                    [0.05 * random.symmetric(), 0.05 * random.symmetric(), 0.0],
                    [0.0, 0.0, 0.5 * random.symmetric()],
                ),
            };
            let h = [half[0], half[1], TOWER_HALF_HEIGHT];
            let body = world.add_body(Body::cuboid(x, mass, h, yaw(0.0), v, omega, false));
            // The corners of the overlap of this box's bottom face with the top face below.
            let (mut lo, mut hi) = (
                [x[0] - half[0], x[1] - half[1]],
                [x[0] + half[0], x[1] + half[1]],
            );
            if let Some((_, xb, hb)) = below {
                for k in 0..2 {
                    lo[k] = lo[k].max(xb[k] - hb[k]);
                    hi[k] = hi[k].min(xb[k] + hb[k]);
                }
            }
            let z = x[2] - TOWER_HALF_HEIGHT;
            for point in [
                [lo[0], lo[1], z],
                [hi[0], lo[1], z],
                [hi[0], hi[1], z],
                [lo[0], hi[1], z],
            ] {
                world.add_contact(body, below.map(|b| b.0), point, E_Z, mu);
            }
            below = Some((body, x, half));
        }
    }
    Ok(world)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenes::granular::tests::{bits, positive_semidefinite};
    use crate::scenes::{DT, GRAVITY};

    fn spec(towers: usize, height: usize, motion: TowerMotion) -> TowerSpec {
        TowerSpec {
            towers,
            height,
            motion,
            seed: 1,
        }
    }

    /// The numerical rank of a dense symmetric matrix by elimination with complete pivoting.
    fn rank(mut a: Vec<Vec<f64>>) -> usize {
        let n = a.len();
        let scale = a.iter().flatten().fold(0.0_f64, |m, v| m.max(v.abs()));
        for k in 0..n {
            let (mut p, mut q, mut best) = (k, k, 0.0);
            for (i, row) in a.iter().enumerate().skip(k) {
                for (j, v) in row.iter().enumerate().skip(k) {
                    if v.abs() > best {
                        (p, q, best) = (i, j, v.abs());
                    }
                }
            }
            if best <= 1e-12 * scale {
                return k;
            }
            a.swap(k, p);
            for row in a.iter_mut() {
                row.swap(k, q);
            }
            let pivot_row = a[k].clone();
            for row in a.iter_mut().skip(k + 1) {
                let l = row[k] / pivot_row[k];
                for (v, pv) in row.iter_mut().zip(&pivot_row).skip(k) {
                    *v -= l * pv;
                }
            }
        }
        n
    }

    #[test]
    fn four_contacts_per_box_and_rank_six_per_box() {
        let s = spec(2, 3, TowerMotion::Rest);
        let p = box_towers(&s).unwrap();
        assert_eq!(p.n_contacts(), 24);
        assert_eq!(s.contacts(), 24);
        // A face's 4 contacts are coupled with those of the faces below and above it (the
        // bodies they share); the two towers share nothing: per tower 16 (2 + 3 + 2) blocks.
        let w = p.w().to_block_sparse().unwrap();
        assert_eq!(w.n_blocks(), 2 * 16 * (2 + 3 + 2));
        assert_eq!(p.w().relative_asymmetry(), 0.0);
        positive_semidefinite(&p);
        // 72 contact rows for 6 boxes of 6 degrees of freedom.
        let dense = p.w().to_dense();
        let rows: Vec<Vec<f64>> = (0..72)
            .map(|i| (0..72).map(|j| dense.get(i, j)).collect())
            .collect();
        assert_eq!(rank(rows), 36);
        // At rest every box falls by the same velocity: q_N = -g dt on the ground, 0 between
        // boxes.
        for c in 0..24 {
            let on_ground = c % 12 < 4;
            let expected = if on_ground { -DT * GRAVITY } else { 0.0 };
            assert!((p.q()[3 * c] - expected).abs() < 1e-15, "contact {c}");
        }
    }

    #[test]
    fn same_seed_same_bits() {
        let s = spec(3, 4, TowerMotion::Settling);
        assert_eq!(
            bits(&box_towers(&s).unwrap()),
            bits(&box_towers(&s).unwrap())
        );
        let other = TowerSpec { seed: 2, ..s };
        assert_ne!(
            bits(&box_towers(&s).unwrap()),
            bits(&box_towers(&other).unwrap())
        );
        assert!(box_towers(&spec(0, 3, TowerMotion::Rest)).is_err());
        assert_eq!(s.name(), "towers-t3-h4-settling-s1");
    }
}

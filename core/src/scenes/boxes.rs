//! Generated piles of boxes: the box counterpart of [`super::sphere_piles`], assembled with the
//! same rigid-body code (one Moreau-Jean step, `W = G M^-1 G^T` in 3x3 blocks, `q = G v_free`)
//! and driven by the same [`PileSpec`] (total contacts, separate piles, seed).
//!
//! A pile is a stepped pyramid of bricks laid in stack bond shifted by half a brick per layer:
//! layer `L` holds `(n - L) x (n - L)` boxes on a square grid of pitch `2 H + G` (half-width
//! [`HALF_WIDTH`] `H`, gap `G` = [`GAP`] between neighbours, so boxes of a layer never touch),
//! and each box above layer 0 rests on the 4 boxes below it, centred over their common corner.
//! Every face contact is modelled as hosts do (LMGC90-style engines, Siconos' box stacks): 4
//! contact points at the corners of the overlap of the two faces, normal `+z`. A box of layer 0
//! has 4 contacts with the ground (its bottom corners), a box above has 16 (4 supports, 4 points
//! each): W is rank-deficient (12 or 48 rows for 6 degrees of freedom), as in every box stack.
//!
//! Horizontal half-widths vary by +-2 %, centres by +-0.1 % of `H` (so overlaps, and therefore
//! contact points and arms, differ from contact to contact), masses by +-20 %; each box has a
//! small random velocity and spin (a settling pile): sticking, sliding and separating contacts.
//!
//! Piles stand side by side with a gap: contacts of different piles share no body (separate
//! islands of W). The contact budget is split evenly between piles; each pile is built bottom-up,
//! box by box, contact by contact, until its share is reached (the last box may keep only part of
//! its contacts), so the count is exact. Same seed, same bits: see [`super::granular`].

use super::granular::{pile_shape, piles_side_by_side, random_motion, walk_pyramid, Pile, Random};
use super::world::{yaw, Body, Storage, World, E_Z};
use crate::error::Fc3dError;
use crate::problem::FrictionProblem;

use super::PileSpec;

/// Mean horizontal half-width of a box (m).
pub const HALF_WIDTH: f64 = 0.05;
/// Half-height of every box (m): flat bricks.
pub const HALF_HEIGHT: f64 = 0.03;
/// Horizontal gap between neighbouring boxes of a layer (m).
pub const GAP: f64 = 0.1 * HALF_WIDTH;
/// Mean mass of a box (kg).
pub const MASS: f64 = 1.0;

/// Contacts of a full layer of `m x m` boxes: 4 per box on the ground, 16 per box above.
pub(super) fn layer_contacts(m: usize, on_ground: bool) -> usize {
    if on_ground {
        4 * m * m
    } else {
        16 * m * m
    }
}

#[cfg(test)]
fn pyramid_contacts(n: usize) -> usize {
    (0..n)
        .map(|layer| layer_contacts(n - layer, layer == 0))
        .sum()
}

/// Generates the box scene of `spec` (sparse-block W).
pub fn box_piles(spec: &PileSpec) -> Result<FrictionProblem<'static>, Fc3dError> {
    Ok(box_world(spec)?.problem(Storage::SparseBlock))
}

pub(super) fn box_world(spec: &PileSpec) -> Result<World, Fc3dError> {
    let pitch = 2.0 * HALF_WIDTH + GAP;
    // Three box widths of empty ground between piles.
    piles_side_by_side(
        spec,
        |c| pile_shape(c, layer_contacts).0,
        pitch,
        6.0 * HALF_WIDTH,
        build_pile,
    )
}

/// A box as placed: centre and horizontal half-widths.
#[derive(Clone, Copy)]
struct Placed {
    body: usize,
    x: [f64; 3],
    half: [f64; 2],
}

/// Adds one stepped pyramid of boxes with its left front corner at `x = x_origin, y = 0`.
fn build_pile(world: &mut World, random: &mut Random, pile: &Pile) {
    let pitch = 2.0 * HALF_WIDTH + GAP;
    let jitter = 1e-3 * HALF_WIDTH;
    walk_pyramid(pile.base, pile.contacts, |budget, cell| {
        let (layer, i, j) = (cell.layer, cell.i, cell.j);
        let offset = 0.5 * pitch * layer as f64;
        let x = [
            pile.x_origin + 0.5 * pitch + offset + pitch * i as f64 + jitter * random.symmetric(),
            0.5 * pitch + offset + pitch * j as f64 + jitter * random.symmetric(),
            HALF_HEIGHT * (1 + 2 * layer) as f64,
        ];
        let half = [
            HALF_WIDTH * (1.0 + 0.02 * random.symmetric()),
            HALF_WIDTH * (1.0 + 0.02 * random.symmetric()),
        ];
        let mass = MASS * (1.0 + 0.2 * random.symmetric());
        let (v, omega) = random_motion(random);
        let h = [half[0], half[1], HALF_HEIGHT];
        let body = world.add_body(Body::cuboid(x, mass, h, yaw(0.0), v, omega, false));
        let placed = Placed { body, x, half };
        // The footprints this box rests on: the ground, or the 4 boxes below; boxes of a layer
        // never touch each other.
        'supports: for support in cell.supports {
            for point in face_contact_points(&placed, support.as_ref()) {
                if !budget.take() {
                    break 'supports;
                }
                world.add_contact(body, support.map(|s| s.body), point, E_Z, pile.mu);
            }
        }
        placed
    });
}

/// The 4 corners of the overlap of box `a`'s bottom face with `b`'s top face (the ground when
/// `b` is `None`: `a`'s bottom corners), at the height of the bottom face.
fn face_contact_points(a: &Placed, b: Option<&Placed>) -> [[f64; 3]; 4] {
    let z = a.x[2] - HALF_HEIGHT;
    let (mut lo, mut hi) = (
        [a.x[0] - a.half[0], a.x[1] - a.half[1]],
        [a.x[0] + a.half[0], a.x[1] + a.half[1]],
    );
    if let Some(b) = b {
        for k in 0..2 {
            lo[k] = lo[k].max(b.x[k] - b.half[k]);
            hi[k] = hi[k].min(b.x[k] + b.half[k]);
        }
    }
    [
        [lo[0], lo[1], z],
        [hi[0], lo[1], z],
        [hi[0], hi[1], z],
        [lo[0], hi[1], z],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenes::granular::tests::{
        bits, blocks_are_exactly_the_shared_bodies, positive_semidefinite,
    };

    fn spec(contacts: usize, piles: usize, seed: u64) -> PileSpec {
        PileSpec {
            contacts,
            piles,
            seed,
        }
    }

    #[test]
    fn same_seed_same_bits_other_seed_other_problem() {
        let a = box_piles(&spec(2000, 3, 7)).unwrap();
        let b = box_piles(&spec(2000, 3, 7)).unwrap();
        let c = box_piles(&spec(2000, 3, 8)).unwrap();
        assert_eq!(bits(&a), bits(&b));
        assert_ne!(bits(&a), bits(&c));
        let sum: f64 = a.q().iter().sum();
        assert!(sum.is_finite() && sum < 0.0, "gravity pulls down: {sum}");
    }

    #[test]
    fn contact_count_is_exact() {
        for (contacts, piles) in [(1, 1), (2, 2), (7, 1), (100, 3), (1000, 4), (12345, 5)] {
            let p = box_piles(&spec(contacts, piles, 1)).unwrap();
            assert_eq!(p.n_contacts(), contacts, "{contacts} in {piles} piles");
        }
        // A full pyramid of base 3: 9 boxes on the ground, 4 + 1 above.
        assert_eq!(pyramid_contacts(3), 4 * 9 + 16 * 5);
        assert!(box_piles(&spec(3, 4, 1)).is_err());
    }

    #[test]
    fn every_face_contact_has_4_points_on_both_faces() {
        let world = box_world(&spec(pyramid_contacts(3), 1, 2)).unwrap();
        assert_eq!(world.bodies.len(), 14);
        // Per box: its contacts as the upper body, grouped by support.
        for (k, body) in world.bodies.iter().enumerate() {
            let mine: Vec<_> = world.contacts.iter().filter(|c| c.a == k).collect();
            let on_ground = body.x[2] < 2.0 * HALF_HEIGHT;
            assert_eq!(mine.len(), if on_ground { 4 } else { 16 }, "box {k}");
            for c in &mine {
                // At the bottom face, inside the box's footprint, normal up.
                assert!((c.point[2] - (body.x[2] - HALF_HEIGHT)).abs() < 1e-15);
                assert!((c.point[0] - body.x[0]).abs() <= 1.03 * HALF_WIDTH);
                assert!((c.point[1] - body.x[1]).abs() <= 1.03 * HALF_WIDTH);
                assert_eq!(c.frame[0], E_Z);
                if let Some(b) = c.b {
                    let below = &world.bodies[b];
                    assert!((below.x[2] + HALF_HEIGHT - c.point[2]).abs() < 1e-15);
                    assert!((c.point[0] - below.x[0]).abs() <= 1.03 * HALF_WIDTH);
                    assert!((c.point[1] - below.x[1]).abs() <= 1.03 * HALF_WIDTH);
                }
            }
            if !on_ground {
                let mut supports: Vec<_> = mine.iter().map(|c| c.b.unwrap()).collect();
                supports.dedup();
                assert_eq!(supports.len(), 4, "box {k} rests on 4 boxes");
            }
        }
    }

    #[test]
    fn blocks_are_exactly_the_pairs_sharing_a_body() {
        let world = box_world(&spec(600, 2, 3)).unwrap();
        blocks_are_exactly_the_shared_bodies(&world, 300);
    }

    #[test]
    fn w_is_symmetric_positive_semidefinite() {
        let p = box_piles(&spec(400, 2, 5)).unwrap();
        assert_eq!(p.w().relative_asymmetry(), 0.0);
        positive_semidefinite(&p);
    }
}

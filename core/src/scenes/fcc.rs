//! Regular packings: boxes of equal spheres in a face-centred cubic (FCC) lattice on the ground,
//! the packing of crystallised granular beds, with every interior sphere touching 12 others.
//!
//! The lattice is stacked in square layers: even layers hold `m x m` spheres on a grid of spacing
//! `2 R`, odd layers the `(m - 1) x (m - 1)` spheres in the pockets between them (shifted by `R`
//! in x and y), `R sqrt 2` higher. A sphere touches its grid neighbours in its layer and the (up
//! to 4) spheres below it; layer 0 stands on the ground. Spheres on the sides of even layers
//! rest on 2 spheres, corners on 1 (there are no walls). A box of base `m` has `m` layers, the
//! smallest base holding the pile's share of the contacts is taken, and the box is built bottom-up
//! until the share is spent (the last sphere may keep only part of its contacts), so the count is
//! exact, as for [`super::sphere_piles`].
//!
//! Positions and masses are exact lattice values (no jitter); the seed draws each pile's friction
//! coefficient and each sphere's small velocity and spin, so the same spec gives the same problem,
//! bit for bit.

use super::granular::{add_sphere, piles_side_by_side, random_motion, walk_layers, Pile, MASS};
use super::granular::{PileSpec, RADIUS};
use super::world::{Storage, World};
use crate::error::Fc3dError;
use crate::problem::FrictionProblem;

/// Cells of layer `layer` of a box of base `m`, and the shift of its supports in the layer below
/// (see [`walk_layers`]): even layers `m x m` on pockets at `(i - 1, i)`, odd layers
/// `(m - 1) x (m - 1)` on the spheres at `(i, i + 1)`.
fn layer_of(m: usize, layer: usize) -> (usize, isize) {
    if layer.is_multiple_of(2) {
        (m, -1)
    } else {
        (m - 1, 0)
    }
}

/// Contacts of full layer `layer` of a box of base `m`.
fn layer_contacts(m: usize, layer: usize) -> usize {
    let (n, _) = layer_of(m, layer);
    let in_layer = 2 * n * n.saturating_sub(1);
    let vertical = if layer == 0 {
        m * m
    } else {
        // Each sphere of an odd layer rests on 4; each odd sphere carries 4 of the next layer.
        4 * (m - 1) * (m - 1)
    };
    vertical + in_layer
}

/// The smallest base `m` whose box (`m` layers) holds `contacts`, and the layers built on it
/// before they are spent.
pub(super) fn box_shape(contacts: usize) -> (usize, usize) {
    let full = |m: usize| -> usize { (0..m).map(|l| layer_contacts(m, l)).sum() };
    let mut m = 1;
    while full(m) < contacts {
        m += 1;
    }
    let (mut built, mut layers) = (0, 0);
    while built < contacts && layers < m {
        built += layer_contacts(m, layers);
        layers += 1;
    }
    (m, layers)
}

/// Generates FCC boxes for `spec` (sparse-block W).
pub fn fcc_piles(spec: &PileSpec) -> Result<FrictionProblem<'static>, Fc3dError> {
    Ok(fcc_world(spec)?.problem(Storage::SparseBlock))
}

pub(super) fn fcc_world(spec: &PileSpec) -> Result<World, Fc3dError> {
    // Three radii of empty ground between boxes.
    piles_side_by_side(
        spec,
        |c| box_shape(c).0,
        2.0 * RADIUS,
        6.0 * RADIUS,
        build_box,
    )
}

/// Adds one box with its left front corner at `x = x_origin, y = 0`.
fn build_box(world: &mut World, random: &mut super::granular::Random, pile: &Pile) {
    let m = pile.base;
    let spacing = 2.0 * RADIUS;
    let layer_height = RADIUS * 2f64.sqrt();
    walk_layers::<usize>(
        m,
        |l| layer_of(m, l),
        pile.contacts,
        |budget, cell| {
            let shift = if cell.layer % 2 == 1 { RADIUS } else { 0.0 };
            let x = [
                pile.x_origin + RADIUS + shift + spacing * cell.i as f64,
                RADIUS + shift + spacing * cell.j as f64,
                RADIUS + layer_height * cell.layer as f64,
            ];
            add_sphere(world, budget, cell, x, MASS, random_motion(random), pile.mu)
        },
    );
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenes::granular::tests::{
        bits, blocks_are_exactly_the_shared_bodies, positive_semidefinite, spec,
    };

    #[test]
    fn full_layers_count_their_contacts() {
        // Base 3: layer 0 has 9 ground and 12 in-layer contacts, layer 1 (2 x 2) 16 supports
        // and 4 in-layer, layer 2 (3 x 3) 16 supports (4 on each sphere of layer 1) and 12.
        assert_eq!(layer_contacts(3, 0), 21);
        assert_eq!(layer_contacts(3, 1), 20);
        assert_eq!(layer_contacts(3, 2), 28);
        assert_eq!(box_shape(69), (3, 3));
        assert_eq!(box_shape(70), (4, 2));
        assert_eq!(box_shape(1), (1, 1));
        let p = fcc_piles(&spec(69, 1, 1)).unwrap();
        assert_eq!(p.n_contacts(), 69);
    }

    #[test]
    fn contact_count_is_exact_and_the_seed_decides_the_bits() {
        for (contacts, piles) in [(1, 1), (2, 2), (7, 1), (100, 3), (1000, 4), (12345, 5)] {
            let p = fcc_piles(&spec(contacts, piles, 1)).unwrap();
            assert_eq!(p.n_contacts(), contacts, "{contacts} in {piles}");
        }
        let a = fcc_piles(&spec(2000, 2, 7)).unwrap();
        let b = fcc_piles(&spec(2000, 2, 7)).unwrap();
        let c = fcc_piles(&spec(2000, 2, 8)).unwrap();
        assert_eq!(bits(&a), bits(&b));
        assert_ne!(bits(&a), bits(&c));
    }

    /// Interior spheres touch 12 others: in a box of base 8, the stored blocks of a contact
    /// between two interior spheres are the contacts of both spheres (11 + 11 others and
    /// itself).
    #[test]
    fn an_interior_contact_couples_the_contacts_of_two_twelve_neighbour_spheres() {
        let world = fcc_world(&spec(box_shape_full(8), 1, 1)).unwrap();
        let p = world.problem(Storage::SparseBlock);
        let crate::matrix::Delassus::SparseBlock(w) = p.w() else {
            panic!("sparse-block W expected");
        };
        let per_row = (0..p.n_contacts()).map(|c| w.row_ptr()[c + 1] - w.row_ptr()[c]);
        assert_eq!(per_row.max(), Some(23));
        blocks_are_exactly_the_shared_bodies(&world, p.n_contacts());
    }

    fn box_shape_full(m: usize) -> usize {
        (0..m).map(|l| layer_contacts(m, l)).sum()
    }

    #[test]
    fn w_is_symmetric_positive_semidefinite() {
        let p = fcc_piles(&spec(400, 2, 5)).unwrap();
        assert_eq!(p.w().relative_asymmetry(), 0.0);
        positive_semidefinite(&p);
    }
}

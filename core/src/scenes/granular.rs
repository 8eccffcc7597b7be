//! Generated granular scenes at scale: piles of spheres on the ground, from a handful to
//! hundreds of thousands of contacts, assembled with the same rigid-body code as the built-in
//! scenes (one time step of Moreau-Jean, `W = G M^-1 G^T` in 3x3 blocks, `q = G v_free`).
//!
//! A pile is a square pyramid of equal spheres (radius [`RADIUS`]): layer `L` holds
//! `(n - L) x (n - L)` spheres on a square grid of spacing `2 R`, each sphere above layer 0
//! resting in the pocket of the 4 spheres below it. Every sphere touches its grid neighbours in
//! its layer and the 4 below it; layer 0 also touches the ground. Centers are jittered by a small
//! seeded amount (so the normals and arms are not all aligned, as in a real packing), masses vary
//! by +-20 %, and each sphere has a small random velocity and spin (a settling pile), so the
//! problem has sticking, sliding and separating contacts.
//!
//! Piles stand side by side with a gap between them: contacts of different piles share no body,
//! so W is block diagonal by pile (the islands of the contact graph). The total contact budget is
//! split evenly between the piles; each pile is built bottom-up, layer by layer, until its share is
//! reached (the last sphere may keep only part of its contacts), so the count is exact.
//!
//! Everything derives from the seed through a fixed pseudo-random sequence (SplitMix64) and
//! fixed-order floating-point arithmetic: the same spec gives the same problem, bit for bit, on
//! every machine. Memory and time are O(contacts): nothing dense is ever built.

use super::world::{normalize, Body, Storage, World, E_Z};
use crate::error::Fc3dError;
use crate::problem::FrictionProblem;

/// Radius of every sphere (m).
pub const RADIUS: f64 = 0.05;
/// Mean mass of a sphere (kg).
pub const MASS: f64 = 1.0;

/// What to generate: see the module documentation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PileSpec {
    /// Total number of contacts (>= `piles`).
    pub contacts: usize,
    /// Number of separate piles (>= 1).
    pub piles: usize,
    /// Seed of the pseudo-random sequence.
    pub seed: u64,
}

impl PileSpec {
    /// The contacts of pile `pile`: the count shared out, the first piles taking the remainder.
    pub(super) fn pile_contacts(&self, pile: usize) -> usize {
        self.contacts / self.piles + usize::from(pile < self.contacts % self.piles)
    }

    /// Parses `contacts=N,piles=P,seed=S` (any order; `piles` defaults to 1, `seed` to 1).
    pub fn parse(text: &str) -> Result<PileSpec, Fc3dError> {
        super::parse_spec(text, false).map(|scene| scene.pile)
    }

    pub(super) fn check(&self) -> Result<(), Fc3dError> {
        if self.piles == 0 || self.contacts < self.piles {
            return Err(Fc3dError::InvalidOption(format!(
                "a pile scene needs at least one pile and one contact per pile, got {} contacts \
                 in {} piles",
                self.contacts, self.piles
            )));
        }
        Ok(())
    }

    /// A short name for tables and files: `piles-c100000-p4-s1`.
    pub fn name(&self) -> String {
        format!("piles-c{}-p{}-s{}", self.contacts, self.piles, self.seed)
    }
}

/// SplitMix64: a tiny, well-mixed generator whose sequence is fixed by its definition.
pub(super) struct Random(pub(super) u64);

impl Random {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [-1, 1).
    pub(super) fn symmetric(&mut self) -> f64 {
        // 53 random bits to [0, 1), exactly representable.
        let unit = (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        2.0 * unit - 1.0
    }
}

/// Contacts of a full layer of `m x m` spheres: per sphere, the ground (`on_ground`) or the 4
/// spheres below, and its left and back neighbours in its layer.
pub(super) fn layer_contacts(m: usize, on_ground: bool) -> usize {
    let vertical = if on_ground { m * m } else { 4 * m * m };
    vertical + 2 * m * (m - 1)
}

/// The base of the smallest pyramid holding `contacts` (layer `L` of a pyramid of base `n` has
/// `(n - L) x (n - L)` cells of `layer_contacts` contacts), and the layers [`walk_pyramid`]
/// builds on that base before the contacts are spent: the height of the pile.
pub(super) fn pile_shape(
    contacts: usize,
    layer_contacts: fn(usize, bool) -> usize,
) -> (usize, usize) {
    let pyramid = |n: usize| -> usize { (0..n).map(|l| layer_contacts(n - l, l == 0)).sum() };
    let mut base = 1;
    while pyramid(base) < contacts {
        base += 1;
    }
    let mut built = 0;
    let mut layers = 0;
    while built < contacts && layers < base {
        built += layer_contacts(base - layers, layers == 0);
        layers += 1;
    }
    (base, layers)
}

/// One pile as [`piles_side_by_side`] lays it out: the base of its pyramid, its share of the
/// contacts, where it starts along x and its friction coefficient.
pub(super) struct Pile {
    pub(super) base: usize,
    pub(super) contacts: usize,
    pub(super) x_origin: f64,
    pub(super) mu: f64,
}

/// Lays out the piles of `spec` along x, for a shape whose smallest base holding `c` contacts is
/// `base_of(c)` cells and whose cells are `pitch` apart: per pile that base for its share of the
/// contacts, one friction coefficient in [0.3, 0.5], and `gap` of empty ground before the next
/// pile (so that piles never touch). `build` adds one pile to the world.
pub(super) fn piles_side_by_side(
    spec: &PileSpec,
    base_of: fn(usize) -> usize,
    pitch: f64,
    gap: f64,
    mut build: impl FnMut(&mut World, &mut Random, &Pile),
) -> Result<World, Fc3dError> {
    spec.check()?;
    let mut world = World::new();
    let mut random = Random(spec.seed);
    let mut x_origin = 0.0;
    for pile in 0..spec.piles {
        let contacts = spec.pile_contacts(pile);
        let base = base_of(contacts);
        let mu = 0.4 + 0.1 * random.symmetric();
        build(
            &mut world,
            &mut random,
            &Pile {
                base,
                contacts,
                x_origin,
                mu,
            },
        );
        x_origin += base as f64 * pitch + gap;
    }
    Ok(world)
}

/// The contacts a pile may still add: [`walk_pyramid`] stops at the first cell after it is spent,
/// and a cell stops adding contacts when `take` says no, so the count is exact.
pub(super) struct ContactBudget(usize);

impl ContactBudget {
    /// Takes one contact; false when none is left.
    pub(super) fn take(&mut self) -> bool {
        let left = self.0 > 0;
        self.0 = self.0.saturating_sub(1);
        left
    }
}

/// A cell of a stepped pyramid as [`walk_pyramid`] hands it over: its layer and grid position
/// (layer `L` has `(n - L) x (n - L)` cells), what it rests on (`None` is the ground: layer 0
/// only; above, the cells of the layer below that were built, of the 4 under it) and its left and
/// back neighbours in its layer, when built.
pub(super) struct Cell<'a, T> {
    pub(super) layer: usize,
    pub(super) i: usize,
    pub(super) j: usize,
    pub(super) supports: &'a [Option<T>],
    pub(super) left: Option<T>,
    pub(super) back: Option<T>,
}

/// Builds a stepped pyramid of base `n` bottom-up, layer by layer, row by row: `place` puts one
/// body in a cell, adds its contacts while `budget` allows, and returns what later cells need of
/// it. Stops at the first cell after the budget of `contacts` is spent.
pub(super) fn walk_pyramid<T: Copy>(
    n: usize,
    contacts: usize,
    place: impl FnMut(&mut ContactBudget, &Cell<'_, T>) -> T,
) {
    walk_layers(n, |layer| (n - layer, 0), contacts, place)
}

/// [`walk_pyramid`] for any stack of square layers: layer `L` has `m x m` cells and cell
/// `(i, j)` rests on the cells `(i + s + di, j + s + dj)`, `di, dj` in {0, 1}, of the layer
/// below that exist, where `(m, s) = layer_of(L)` (a pyramid: `m = n - L`, `s = 0`).
pub(super) fn walk_layers<T: Copy>(
    layers: usize,
    layer_of: impl Fn(usize) -> (usize, isize),
    contacts: usize,
    mut place: impl FnMut(&mut ContactBudget, &Cell<'_, T>) -> T,
) {
    let mut budget = ContactBudget(contacts);
    let mut supports: Vec<Option<T>> = Vec::with_capacity(4);
    let mut below: Vec<Option<T>> = Vec::new();
    let mut mb = 0;
    for layer in 0..layers {
        let (m, shift) = layer_of(layer);
        let mut current: Vec<Option<T>> = vec![None; m * m];
        for j in 0..m {
            for i in 0..m {
                if budget.0 == 0 {
                    return;
                }
                supports.clear();
                if layer == 0 {
                    supports.push(None);
                } else {
                    for (di, dj) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                        let (ib, jb) = (i as isize + shift + di, j as isize + shift + dj);
                        if (0..mb as isize).contains(&ib) && (0..mb as isize).contains(&jb) {
                            supports.extend(below[ib as usize + mb * jb as usize].map(Some));
                        }
                    }
                }
                let cell = Cell {
                    layer,
                    i,
                    j,
                    supports: &supports,
                    left: if i > 0 {
                        current[(i - 1) + m * j]
                    } else {
                        None
                    },
                    back: if j > 0 {
                        current[i + m * (j - 1)]
                    } else {
                        None
                    },
                };
                current[i + m * j] = Some(place(&mut budget, &cell));
            }
        }
        below = current;
        mb = m;
    }
}

/// A small random velocity and spin (a settling pile), drawn in a fixed order.
pub(super) fn random_motion(random: &mut Random) -> ([f64; 3], [f64; 3]) {
    let v = [
        0.05 * random.symmetric(),
        0.05 * random.symmetric(),
        0.05 * random.symmetric() - 0.05,
    ];
    let omega = [
        0.5 * random.symmetric(),
        0.5 * random.symmetric(),
        0.5 * random.symmetric(),
    ];
    (v, omega)
}

/// Generates the scene of `spec` (sparse-block W).
pub fn sphere_piles(spec: &PileSpec) -> Result<FrictionProblem<'static>, Fc3dError> {
    Ok(pile_world(spec)?.problem(Storage::SparseBlock))
}

pub(super) fn pile_world(spec: &PileSpec) -> Result<World, Fc3dError> {
    // Three radii of empty ground between piles.
    piles_side_by_side(
        spec,
        |c| pile_shape(c, layer_contacts).0,
        2.0 * RADIUS,
        6.0 * RADIUS,
        build_pile,
    )
}

/// Adds one pyramid of spheres with its left front corner at `x = x_origin, y = 0`.
fn build_pile(world: &mut World, random: &mut Random, pile: &Pile) {
    let spacing = 2.0 * RADIUS;
    let layer_height = spacing / 2f64.sqrt();
    let jitter = 1e-3 * RADIUS;
    walk_pyramid::<usize>(pile.base, pile.contacts, |budget, cell| {
        let (layer, i, j) = (cell.layer, cell.i, cell.j);
        let mut jitter3 = || jitter * random.symmetric();
        let x = [
            pile.x_origin + RADIUS + 0.5 * spacing * layer as f64 + spacing * i as f64 + jitter3(),
            RADIUS + 0.5 * spacing * layer as f64 + spacing * j as f64 + jitter3(),
            RADIUS + layer_height * layer as f64 + if layer == 0 { 0.0 } else { jitter3() },
        ];
        let mass = MASS * (1.0 + 0.2 * random.symmetric());
        add_sphere(world, budget, cell, x, mass, random_motion(random), pile.mu)
    });
}

/// Adds a sphere of radius [`RADIUS`] centred at `x` in `cell`, with its contacts while `budget`
/// allows: its supports first (the ground or the spheres below), then its left and back
/// neighbours. Returns the body.
pub(super) fn add_sphere(
    world: &mut World,
    budget: &mut ContactBudget,
    cell: &Cell<'_, usize>,
    x: [f64; 3],
    mass: f64,
    (v, omega): ([f64; 3], [f64; 3]),
    mu: f64,
) -> usize {
    let body = world.add_body(Body::sphere(x, mass, RADIUS, v, omega));
    let neighbours = [cell.left, cell.back].into_iter().flatten().map(Some);
    for other in cell.supports.iter().copied().chain(neighbours) {
        if !budget.take() {
            break;
        }
        match other {
            None => world.add_contact(body, None, [x[0], x[1], 0.0], E_Z, mu),
            Some(b) => {
                let xb = world.bodies[b].x;
                let normal = normalize(&[x[0] - xb[0], x[1] - xb[1], x[2] - xb[2]]);
                // Midway between the two surfaces.
                let gap =
                    ((x[0] - xb[0]).powi(2) + (x[1] - xb[1]).powi(2) + (x[2] - xb[2]).powi(2))
                        .sqrt()
                        - 2.0 * RADIUS;
                let reach = RADIUS + 0.5 * gap;
                let point = [
                    xb[0] + reach * normal[0],
                    xb[1] + reach * normal[1],
                    xb[2] + reach * normal[2],
                ];
                world.add_contact(body, Some(b), point, normal, mu);
            }
        }
    }
    body
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::matrix::Delassus;

    pub(crate) fn spec(contacts: usize, piles: usize, seed: u64) -> PileSpec {
        PileSpec {
            contacts,
            piles,
            seed,
        }
    }

    /// Every bit of W (structure and values), q and mu.
    pub(crate) fn bits(p: &FrictionProblem<'_>) -> Vec<u64> {
        let Delassus::SparseBlock(w) = p.w() else {
            panic!("sparse-block W expected");
        };
        let mut out: Vec<u64> = w.row_ptr().iter().map(|&k| k as u64).collect();
        out.extend(w.col_idx().iter().map(|&k| k as u64));
        out.extend(w.blocks().flatten().map(|v| v.to_bits()));
        out.extend(p.q().iter().map(|v| v.to_bits()));
        out.extend(p.mu().iter().map(|v| v.to_bits()));
        out
    }

    #[test]
    fn same_seed_same_bits_other_seed_other_problem() {
        let a = sphere_piles(&spec(2000, 3, 7)).unwrap();
        let b = sphere_piles(&spec(2000, 3, 7)).unwrap();
        let c = sphere_piles(&spec(2000, 3, 8)).unwrap();
        assert_eq!(bits(&a), bits(&b));
        assert_ne!(bits(&a), bits(&c));
        // Pinned: a change of the sequence or of the assembly shows here.
        let sum: f64 = a.q().iter().sum();
        assert!(
            sum.is_finite() && sum < 0.0,
            "gravity pulls down: sum(q) = {sum}"
        );
    }

    #[test]
    fn contact_count_is_exact() {
        for (contacts, piles) in [(1, 1), (2, 2), (7, 1), (100, 3), (1000, 4), (12345, 5)] {
            let p = sphere_piles(&spec(contacts, piles, 1)).unwrap();
            assert_eq!(
                p.n_contacts(),
                contacts,
                "{contacts} contacts in {piles} piles"
            );
        }
        assert!(sphere_piles(&spec(3, 4, 1)).is_err());
        assert!(sphere_piles(&spec(10, 0, 1)).is_err());
    }

    #[test]
    fn spec_parses() {
        let s = PileSpec::parse("contacts=100_000,piles=4,seed=9").unwrap();
        assert_eq!(s, spec(100_000, 4, 9));
        assert_eq!(PileSpec::parse("contacts=50").unwrap(), spec(50, 1, 1));
        assert!(PileSpec::parse("contacts=5,colour=2").is_err());
        assert!(PileSpec::parse("contacts=x").is_err());
        assert!(PileSpec::parse("piles=2").is_err());
    }

    #[test]
    fn blocks_are_exactly_the_pairs_sharing_a_body() {
        let world = pile_world(&spec(600, 2, 3)).unwrap();
        blocks_are_exactly_the_shared_bodies(&world, 300);
    }

    /// W's stored blocks are exactly the pairs of contacts sharing a body, each stored once, and
    /// no contact before `split` shares a body with one after it (separate piles).
    pub(crate) fn blocks_are_exactly_the_shared_bodies(world: &World, split: usize) {
        let p = world.problem(Storage::SparseBlock);
        let Delassus::SparseBlock(w) = p.w() else {
            panic!("sparse-block W expected");
        };
        let nc = p.n_contacts();
        let mut stored = vec![false; nc * nc];
        for (c, d, _) in w.iter_blocks() {
            assert!(!stored[c * nc + d], "block ({c}, {d}) stored twice");
            stored[c * nc + d] = true;
        }
        let mut coupled_piles = 0;
        for c in 0..nc {
            for d in 0..nc {
                let shared = world
                    .bodies_of(c)
                    .any(|k| world.bodies_of(d).any(|l| l == k));
                assert_eq!(stored[c * nc + d], shared, "block ({c}, {d})");
                coupled_piles += usize::from(shared && (c < split) != (d < split));
            }
        }
        assert_eq!(coupled_piles, 0, "separate piles share no body");
    }

    #[test]
    fn w_is_symmetric_positive_semidefinite() {
        let p = sphere_piles(&spec(400, 2, 5)).unwrap();
        assert_eq!(p.w().relative_asymmetry(), 0.0);
        positive_semidefinite(&p);
    }

    /// Cholesky of W + shift I succeeds for a shift far below W's scale only if W has no
    /// eigenvalue below -shift.
    pub(crate) fn positive_semidefinite(p: &FrictionProblem<'_>) {
        let dense = p.w().to_dense();
        let n = dense.nrows();
        let scale = (0..n).map(|i| dense.get(i, i)).fold(0.0, f64::max);
        let shift = 1e-9 * scale;
        let mut l = vec![0.0; n * n];
        for j in 0..n {
            let mut d = dense.get(j, j) + shift;
            for k in 0..j {
                d -= l[j * n + k] * l[j * n + k];
            }
            assert!(d > 0.0, "pivot {j} = {d}: W not positive semi-definite");
            let djj = d.sqrt();
            l[j * n + j] = djj;
            for i in j + 1..n {
                let mut v = dense.get(i, j);
                for k in 0..j {
                    v -= l[i * n + k] * l[j * n + k];
                }
                l[i * n + j] = v / djj;
            }
        }
    }
}

//! Time-stepping sequences: the problems a Moreau-Jean stepper solves at every step of a short
//! simulation (a pile of spheres settling, a box carrying a box sliding to rest), with the
//! host-side contact ids that name the same contact from one step to the next.
//!
//! Each step assembles FC(W, q, mu) with the [`World`] of the built-in scenes (`W = G M^-1 G^T`,
//! `q = G v_free`), hands it to the caller's solver, applies the impulses
//! (`v+ = v_free + M^-1 G^T r`) and moves the bodies explicitly (`x += dt v+`, orientation
//! rotated by `dt omega+`). Contacts are detected from the positions at the start of the step:
//! a pair whose gap `g` is below [`MARGIN`] plus what the free motion closes in one step is
//! active, and its normal row is shifted by `g / dt` when `g > 0` (`u_N + g / dt >= 0`: the bodies
//! may close the gap in this step but not pass through). The generator takes the solver as a
//! closure (this module sits below the solvers).

use super::world::{bottom_corners, cross, yaw, Body, Storage, World, E_Z};
use super::DT;
use crate::math::linalg::{mat3_mul, mat3_vec, Mat3, Vec3};
use crate::problem::{FrictionProblem, GlobalProblem};

/// Gap below which two shapes are in contact even without approaching (m).
pub const MARGIN: f64 = 1e-3;

/// One step of a sequence.
#[derive(Debug, Clone)]
pub struct Step {
    pub problem: FrictionProblem<'static>,
    /// The host's name of each contact, stable while the contact persists.
    pub ids: Vec<i64>,
}

/// A named sequence of steps.
#[derive(Debug, Clone)]
pub struct Sequence {
    pub name: &'static str,
    pub description: &'static str,
    pub steps: Vec<Step>,
}

/// The reaction `r` of a step's problem (3 entries per contact), as the stepper's solver returns
/// it.
pub type StepSolver<'a> = dyn FnMut(&FrictionProblem<'_>) -> Vec<f64> + 'a;

#[derive(Debug, Clone, Copy)]
enum Shape {
    Sphere { radius: f64 },
    Cuboid { h: Vec3 },
}

#[derive(Debug, Clone)]
struct SimBody {
    shape: Shape,
    mass: f64,
    x: Vec3,
    rot: Mat3,
    v: Vec3,
    omega: Vec3,
}

impl SimBody {
    fn body(&self) -> Body {
        match self.shape {
            Shape::Sphere { radius } => Body::sphere(self.x, self.mass, radius, self.v, self.omega),
            Shape::Cuboid { h } => {
                Body::cuboid(self.x, self.mass, h, self.rot, self.v, self.omega, false)
            }
        }
    }
}

/// A contact candidate found by the detection: bodies, point, normal (into `a`), gap, mu, id.
struct Candidate {
    a: usize,
    b: Option<usize>,
    point: Vec3,
    normal: Vec3,
    gap: f64,
    mu: f64,
    id: i64,
}

/// Ids: kind in the high bits, then the bodies (and the corner).
fn contact_id(kind: i64, i: usize, j: usize) -> i64 {
    (kind << 48) | ((i as i64) << 24) | j as i64
}

/// One step of a sequence in the global form (M block diagonal, one 6x6 block a body; H the
/// contacts' Jacobians; `q = M v_free`; `b` the normal rows' shift `gap / dt` of the contacts
/// still open): reduced, it is the [`Step`] the local form hands over.
#[derive(Debug, Clone)]
pub struct GlobalStep {
    pub problem: GlobalProblem<'static>,
    /// The host's name of each contact, stable while the contact persists.
    pub ids: Vec<i64>,
}

/// A solver that also sees the step's contact ids (to warm-start by id), for sequences whose
/// steps are not kept ([`pile_settling_in_bin`]).
pub type StepSolverWithIds<'a> = dyn FnMut(&Step) -> Vec<f64> + 'a;

/// Runs `steps` steps of `bodies` under `detect`, solving each step's problem with `solve`.
fn simulate(
    name: &'static str,
    description: &'static str,
    bodies: Vec<SimBody>,
    steps: usize,
    detect: &dyn Fn(&[SimBody]) -> Vec<Candidate>,
    solve: &mut StepSolver<'_>,
) -> Sequence {
    let mut out = Vec::with_capacity(steps);
    run_steps(bodies, steps, detect, &mut |world, candidates| {
        let step = local_step(world, candidates);
        let r = solve(&step.problem);
        out.push(step);
        r
    });
    Sequence {
        name,
        description,
        steps: out,
    }
}

/// The stepper: per step with contacts, `solve` gets the step's world (bodies with their free
/// velocities, contacts added) and its candidates, and returns r. Returns the number of steps
/// that had contacts.
fn run_steps(
    mut bodies: Vec<SimBody>,
    steps: usize,
    detect: &dyn Fn(&[SimBody]) -> Vec<Candidate>,
    solve: &mut dyn FnMut(&World, &[Candidate]) -> Vec<f64>,
) -> usize {
    let mut solved = 0;
    for _ in 0..steps {
        let mut world = World::new();
        for b in &bodies {
            world.add_body(b.body());
        }
        // Keep the contacts the free motion can close within the step.
        let candidates: Vec<Candidate> = detect(&bodies)
            .into_iter()
            .filter(|c| {
                let va = &world.bodies[c.a].v_free;
                let mut vn = approach(va, &world.bodies[c.a].x, &c.point, &c.normal);
                if let Some(b) = c.b {
                    let vb = &world.bodies[b].v_free;
                    vn -= approach(vb, &world.bodies[b].x, &c.point, &c.normal);
                }
                c.gap + DT * vn.min(0.0) < MARGIN
            })
            .collect();
        if candidates.is_empty() {
            // Free flight: no problem to solve this step.
            for (s, b) in bodies.iter_mut().zip(&world.bodies) {
                advance(s, &b.v_free);
            }
            continue;
        }
        for c in &candidates {
            world.add_contact(c.a, c.b, c.point, c.normal, c.mu);
        }
        let r = solve(&world, &candidates);
        solved += 1;
        let dv = world.impulse_response(&r);
        for ((s, b), d) in bodies.iter_mut().zip(&world.bodies).zip(&dv) {
            let v: [f64; 6] = std::array::from_fn(|i| b.v_free[i] + d[i]);
            advance(s, &v);
        }
    }
    solved
}

/// The normal rows' shift `gap / dt` of the open candidates (`u_N + g / dt >= 0`), 3 entries a
/// contact.
fn gap_shift(candidates: &[Candidate]) -> Vec<f64> {
    let mut shift = vec![0.0; 3 * candidates.len()];
    for (k, c) in candidates.iter().enumerate() {
        if c.gap > 0.0 {
            shift[3 * k] = c.gap / DT;
        }
    }
    shift
}

/// The local form of a step: `FC(W, q + shift, mu)` with W stored sparse by blocks.
fn local_step(world: &World, candidates: &[Candidate]) -> Step {
    let ids: Vec<i64> = candidates.iter().map(|c| c.id).collect();
    let problem = world.problem(Storage::SparseBlock);
    let mut q = problem.q().to_vec();
    for (qi, s) in q.iter_mut().zip(gap_shift(candidates)) {
        if s != 0.0 {
            *qi += s;
        }
    }
    let problem = FrictionProblem::new(problem.w().clone(), q, problem.mu().to_vec())
        .expect("consistent step");
    Step { problem, ids }
}

/// The global form of a step (`b` the shift).
fn global_step(world: &World, candidates: &[Candidate]) -> GlobalStep {
    let ids: Vec<i64> = candidates.iter().map(|c| c.id).collect();
    let problem = world
        .global_problem_with_b(gap_shift(candidates))
        .expect("consistent step");
    GlobalStep { problem, ids }
}

/// Normal velocity of the material point of a body at `p` along `n`.
fn approach(v: &[f64; 6], x: &Vec3, p: &Vec3, n: &Vec3) -> f64 {
    let arm = [p[0] - x[0], p[1] - x[1], p[2] - x[2]];
    let w = cross(&[v[3], v[4], v[5]], &arm);
    (v[0] + w[0]) * n[0] + (v[1] + w[1]) * n[1] + (v[2] + w[2]) * n[2]
}

/// Explicit position update with the end-of-step velocity `v`.
fn advance(s: &mut SimBody, v: &[f64; 6]) {
    s.v = [v[0], v[1], v[2]];
    s.omega = [v[3], v[4], v[5]];
    for i in 0..3 {
        s.x[i] += DT * s.v[i];
    }
    s.rot = mat3_mul(&rotation(&s.omega, DT), &s.rot);
}

/// Rotation by the angle `|omega| dt` about `omega` (Rodrigues).
fn rotation(omega: &Vec3, dt: f64) -> Mat3 {
    let theta = (omega[0] * omega[0] + omega[1] * omega[1] + omega[2] * omega[2]).sqrt() * dt;
    let mut r = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    if theta < 1e-14 {
        return r;
    }
    let k: Vec3 = std::array::from_fn(|i| omega[i] * dt / theta);
    let kx = [[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]];
    let kx2 = mat3_mul(&kx, &kx);
    let (s, c) = theta.sin_cos();
    for i in 0..3 {
        for j in 0..3 {
            r[i][j] += s * kx[i][j] + (1.0 - c) * kx2[i][j];
        }
    }
    r
}

/// Width of the pile's bin relative to its 4 x 4 bottom layer.
const BIN_ROOM: f64 = 1.1;

/// A small deterministic generator (the positions of the pile, identical on every platform).
fn jitter(seed: &mut u64) -> f64 {
    *seed = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    ((*seed >> 11) as f64 / (1u64 << 53) as f64) - 0.5
}

/// `n` spheres (radius 0.1, mass 1) dropped in layers into a square bin (frictionless walls),
/// settling on the ground for `steps` steps: contacts appear as the spheres land and touch,
/// vanish when they bounce apart or roll away, and the set stabilises as the pile comes to rest.
/// Friction 0.5 on the ground, 0.3 between spheres.
pub fn pile_settling(n: usize, steps: usize, solve: &mut StepSolver<'_>) -> Sequence {
    let (bodies, detect) = settling_pile(n, 4);
    simulate(
        "pile_settling",
        "spheres dropped in layers into a bin, settling on the ground",
        bodies,
        steps,
        &detect,
        solve,
    )
}

/// [`pile_settling`] in a bin whose layers hold `per_side` x `per_side` spheres (4 there), at a
/// host's scale: a wider bin settles a larger pile in the same number of steps. The steps are
/// handed to `solve` (with their contact ids, to warm-start by id) and not kept (hundreds of
/// W of 10^4 contacts would not fit); returns the number of steps that had contacts. The
/// contact detection sorts the spheres into a uniform grid (O(n log n) a step) and lists the
/// same pairs, in the same order, as testing every pair would.
pub fn pile_settling_in_bin(
    n: usize,
    per_side: usize,
    steps: usize,
    solve: &mut StepSolverWithIds<'_>,
) -> usize {
    let (bodies, detect) = settling_pile(n, per_side);
    run_steps(bodies, steps, &detect, &mut |world, candidates| {
        solve(&local_step(world, candidates))
    })
}

/// A solver of a step in the global form, from its contact ids (to warm-start by id).
pub type GlobalStepSolver<'a> = dyn FnMut(&GlobalStep) -> Vec<f64> + 'a;

/// [`pile_settling_in_bin`] with each step handed over in the global form ([`GlobalStep`]: M,
/// H, `q = M v_free`, `b` the gap shift) for a solver that takes M and H (the H-form sweep)
/// rather than W. The bodies move by the same rule from the returned r
/// (`v+ = v_free + M^-1 H r`); with the same r at every step the sequence is
/// [`pile_settling_in_bin`]'s. Returns the number of steps that had contacts.
pub fn pile_settling_in_bin_global(
    n: usize,
    per_side: usize,
    steps: usize,
    solve: &mut GlobalStepSolver<'_>,
) -> usize {
    let (bodies, detect) = settling_pile(n, per_side);
    run_steps(bodies, steps, &detect, &mut |world, candidates| {
        solve(&global_step(world, candidates))
    })
}

/// The spheres of [`pile_settling_in_bin`] and their contact detection.
fn settling_pile(
    n: usize,
    per_side: usize,
) -> (Vec<SimBody>, impl Fn(&[SimBody]) -> Vec<Candidate>) {
    let radius = 0.1;
    let per_side = per_side.max(1);
    // Room for the bottom layer to spread: a jammed packing wall to wall is a much harder
    // (and less typical) problem than a pile.
    let half_bin = 0.5 * per_side as f64 * 2.2 * radius * BIN_ROOM;
    let mut seed = 0x5EED_u64;
    let bodies: Vec<SimBody> = (0..n)
        .map(|k| {
            let layer = k / (per_side * per_side);
            let (i, j) = ((k % (per_side * per_side)) / per_side, k % per_side);
            let off = if layer % 2 == 1 { 0.5 } else { 0.0 };
            let x = -half_bin
                + (i as f64 + 0.5 + 0.5 * off) * 2.2 * radius * 0.97
                + 0.02 * jitter(&mut seed);
            let y = -half_bin
                + (j as f64 + 0.5 + 0.5 * off) * 2.2 * radius * 0.97
                + 0.02 * jitter(&mut seed);
            SimBody {
                shape: Shape::Sphere { radius },
                mass: 1.0,
                x: [x, y, radius + 0.01 + layer as f64 * 2.1 * radius],
                rot: yaw(0.0),
                v: [0.05 * jitter(&mut seed), 0.05 * jitter(&mut seed), 0.0],
                omega: [0.0; 3],
            }
        })
        .collect();
    let detect =
        move |bodies: &[SimBody]| sphere_candidates(bodies, radius, half_bin, PairSearch::Grid);
    (bodies, detect)
}

/// How [`sphere_candidates`] finds the pairs of spheres within reach.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum PairSearch {
    /// Every pair `i < j` (O(n^2)): the reference.
    #[cfg_attr(not(test), allow(dead_code))]
    AllPairs,
    /// A uniform grid of cells wider than the reach (O(n log n)): the same pairs in the same order.
    Grid,
}

/// The contacts of the settling pile's spheres (radius `radius`, bin walls at `+-half_bin`):
/// for each sphere `i` in order, the ground, the 4 walls, then the spheres `j > i` in
/// increasing `j` whose gap is below the reach. The order and the ids define the problem; both
/// searches give the same list.
fn sphere_candidates(
    bodies: &[SimBody],
    radius: f64,
    half_bin: f64,
    search: PairSearch,
) -> Vec<Candidate> {
    let mut found = Vec::new();
    let reach = MARGIN + 0.1;
    let grid = (search == PairSearch::Grid).then(|| SphereGrid::new(bodies, 2.0 * radius + reach));
    let mut near: Vec<usize> = Vec::new();
    for (i, s) in bodies.iter().enumerate() {
        let x = s.x;
        if x[2] - radius < reach {
            found.push(Candidate {
                a: i,
                b: None,
                point: [x[0], x[1], 0.0],
                normal: E_Z,
                gap: x[2] - radius,
                mu: 0.5,
                id: contact_id(1, i, 0),
            });
        }
        for (w, (axis, sign)) in [(0, 1.0), (0, -1.0), (1, 1.0), (1, -1.0)]
            .iter()
            .enumerate()
        {
            // Wall at coordinate `sign * half_bin` on `axis`, normal pointing inwards.
            let gap = half_bin - sign * x[*axis] - radius;
            if gap < reach {
                let mut normal = [0.0; 3];
                normal[*axis] = -sign;
                let mut point = x;
                point[*axis] = sign * half_bin;
                found.push(Candidate {
                    a: i,
                    b: None,
                    point,
                    normal,
                    gap,
                    mu: 0.0,
                    id: contact_id(2, i, w),
                });
            }
        }
        near.clear();
        match &grid {
            Some(g) => g.later_neighbours(i, &mut near),
            None => near.extend(i + 1..bodies.len()),
        }
        for &j in &near {
            let t = &bodies[j];
            let d = [x[0] - t.x[0], x[1] - t.x[1], x[2] - t.x[2]];
            let dist = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            let gap = dist - 2.0 * radius;
            if gap < reach {
                let n = [d[0] / dist, d[1] / dist, d[2] / dist];
                let p = [
                    t.x[0] + radius * n[0],
                    t.x[1] + radius * n[1],
                    t.x[2] + radius * n[2],
                ];
                found.push(Candidate {
                    a: i,
                    b: Some(j),
                    point: p,
                    normal: n,
                    gap,
                    mu: 0.3,
                    id: contact_id(3, i, j),
                });
            }
        }
    }
    found
}

/// The spheres sorted by the cell of a uniform grid that holds their centre. Cells are 1% wider
/// than the largest centre distance of a contact, so that (round-off included) two spheres
/// within reach lie in the same or adjacent cells on every axis.
struct SphereGrid {
    /// `(cell x, cell y, cell z, sphere)`, sorted.
    cells: Vec<(i64, i64, i64, usize)>,
    /// The cell of each sphere.
    of: Vec<(i64, i64, i64)>,
}

impl SphereGrid {
    fn new(bodies: &[SimBody], reach: f64) -> SphereGrid {
        let size = 1.01 * reach;
        // A NaN coordinate casts to cell 0 and an infinite one saturates: such a sphere is
        // still tested (and its NaN gap rejects it) as the all-pairs search would.
        let cell = |v: f64| (v / size).floor() as i64;
        let of: Vec<(i64, i64, i64)> = bodies
            .iter()
            .map(|b| (cell(b.x[0]), cell(b.x[1]), cell(b.x[2])))
            .collect();
        let mut cells: Vec<(i64, i64, i64, usize)> = of
            .iter()
            .enumerate()
            .map(|(k, c)| (c.0, c.1, c.2, k))
            .collect();
        cells.sort_unstable();
        SphereGrid { cells, of }
    }

    /// Appends to `out` the spheres `j > i` in the 27 cells around sphere `i`'s, in increasing
    /// `j`.
    fn later_neighbours(&self, i: usize, out: &mut Vec<usize>) {
        let (cx, cy, cz) = self.of[i];
        for dx in [-1i64, 0, 1] {
            for dy in [-1i64, 0, 1] {
                let (x, y) = (cx.saturating_add(dx), cy.saturating_add(dy));
                // Sorted by (x, y, z, sphere): the cells z - 1 ..= z + 1 of column (x, y) are
                // one run.
                let lo = (x, y, cz.saturating_sub(1));
                let hi = (x, y, cz.saturating_add(1));
                let start = self.cells.partition_point(|e| (e.0, e.1, e.2) < lo);
                let end = self.cells.partition_point(|e| (e.0, e.1, e.2) <= hi);
                out.extend(
                    self.cells[start..end]
                        .iter()
                        .map(|e| e.3)
                        .filter(|&j| j > i),
                );
            }
        }
        out.sort_unstable();
        out.dedup();
    }
}

/// A box (0.8 x 0.6 x 0.2, mass 4) carrying a smaller yawed box (mass 1) slides on the ground at
/// 1.5 m/s with a slight spin, until friction (0.3 on the ground, 0.5 between the boxes) stops
/// it: 8 corner contacts, sliding then sticking; a corner that lifts is dropped.
pub fn box_slide(steps: usize, solve: &mut StepSolver<'_>) -> Sequence {
    let h0 = [0.4, 0.3, 0.1];
    let h1 = [0.2, 0.15, 0.1];
    let r1 = yaw(0.3);
    let bodies = vec![
        SimBody {
            shape: Shape::Cuboid { h: h0 },
            mass: 4.0,
            x: [0.0, 0.0, h0[2]],
            rot: yaw(0.0),
            v: [1.5, 0.2, 0.0],
            omega: [0.0, 0.0, 0.4],
        },
        SimBody {
            shape: Shape::Cuboid { h: h1 },
            mass: 1.0,
            x: [0.0, 0.0, 2.0 * h0[2] + h1[2]],
            rot: r1,
            v: [1.5, 0.2, 0.0],
            omega: [0.0, 0.0, 0.4],
        },
    ];
    let detect = move |bodies: &[SimBody]| {
        let mut found = Vec::new();
        let reach = MARGIN + 0.05;
        let (lower, upper) = (&bodies[0], &bodies[1]);
        for (k, p) in bottom_corners(&lower.x, &h0, &lower.rot)
            .into_iter()
            .enumerate()
        {
            if p[2] < reach {
                found.push(Candidate {
                    a: 0,
                    b: None,
                    point: [p[0], p[1], 0.0],
                    normal: E_Z,
                    gap: p[2],
                    mu: 0.3,
                    id: contact_id(1, 0, k),
                });
            }
        }
        // The upper box's corners against the lower box's top face.
        let n = mat3_vec(&lower.rot, &E_Z);
        let top = mat3_vec(&lower.rot, &[0.0, 0.0, h0[2]]);
        let face = [
            lower.x[0] + top[0],
            lower.x[1] + top[1],
            lower.x[2] + top[2],
        ];
        for (k, p) in bottom_corners(&upper.x, &h1, &upper.rot)
            .into_iter()
            .enumerate()
        {
            let d = [p[0] - face[0], p[1] - face[1], p[2] - face[2]];
            let gap = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
            if gap < reach {
                let point = [p[0] - gap * n[0], p[1] - gap * n[1], p[2] - gap * n[2]];
                found.push(Candidate {
                    a: 1,
                    b: Some(0),
                    point,
                    normal: n,
                    gap,
                    mu: 0.5,
                    id: contact_id(4, 1, k),
                });
            }
        }
        found
    };
    simulate(
        "box_slide",
        "a box carrying a smaller box slides on the ground until friction stops it",
        bodies,
        steps,
        &detect,
        solve,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{solve, NsgsOptions, SolverConfig};

    fn same(a: &[Candidate], b: &[Candidate]) -> bool {
        a.len() == b.len()
            && a.iter().zip(b).all(|(x, y)| {
                x.a == y.a
                    && x.b == y.b
                    && x.id == y.id
                    && x.gap.to_bits() == y.gap.to_bits()
                    && x.mu.to_bits() == y.mu.to_bits()
                    && (0..3).all(|k| {
                        x.point[k].to_bits() == y.point[k].to_bits()
                            && x.normal[k].to_bits() == y.normal[k].to_bits()
                    })
            })
    }

    /// At every step of settling piles (small and medium, dropped, landing, at rest), the grid
    /// lists exactly the candidates of the all-pairs search, in the same order.
    #[test]
    fn grid_and_all_pairs_find_the_same_candidates() {
        let config = SolverConfig::new(NsgsOptions::default())
            .with_tolerance(1e-4)
            .with_max_iter(200);
        for (n, per_side, steps) in [(40, 4, 60), (300, 8, 40), (1000, 12, 25)] {
            let (bodies, _) = settling_pile(n, per_side);
            let radius = 0.1;
            let half_bin = 0.5 * per_side as f64 * 2.2 * radius * BIN_ROOM;
            let checked = std::cell::Cell::new(0usize);
            let pairs = std::cell::Cell::new(0usize);
            let detect = |b: &[SimBody]| {
                let grid = sphere_candidates(b, radius, half_bin, PairSearch::Grid);
                let all = sphere_candidates(b, radius, half_bin, PairSearch::AllPairs);
                assert!(same(&grid, &all), "{n} spheres, step {}", checked.get());
                checked.set(checked.get() + 1);
                pairs.set(pairs.get() + grid.iter().filter(|c| c.b.is_some()).count());
                grid
            };
            let solved = run_steps(bodies, steps, &detect, &mut |world, candidates| {
                let step = local_step(world, candidates);
                let p = &step.problem;
                let (mut r, mut u) = (vec![0.0; p.size()], vec![0.0; p.size()]);
                solve(p, &config, &mut r, &mut u).expect("solve");
                r
            });
            assert_eq!(checked.get(), steps);
            assert!(solved > 0 && pairs.get() > n, "{n}: {} pairs", pairs.get());
        }
    }

    /// The grid keeps a sphere with a non-finite coordinate (as the all-pairs search does: its
    /// NaN gap rejects it) and finds the same list.
    #[test]
    fn grid_handles_non_finite_positions() {
        let (mut bodies, _) = settling_pile(64, 4);
        bodies[3].x[0] = f64::NAN;
        bodies[10].x[2] = f64::INFINITY;
        bodies[11].x[1] = f64::NEG_INFINITY;
        let half_bin = 0.5 * 4.0 * 2.2 * 0.1 * BIN_ROOM;
        let grid = sphere_candidates(&bodies, 0.1, half_bin, PairSearch::Grid);
        let all = sphere_candidates(&bodies, 0.1, half_bin, PairSearch::AllPairs);
        assert!(same(&grid, &all));
    }

    /// At every step of a settling pile, the global form (M, H, q, b) reduces to the local
    /// form's W and q (gap shift included) up to round-off, with the same ids.
    #[test]
    fn global_steps_reduce_to_the_local_steps() {
        let config = SolverConfig::new(NsgsOptions::default())
            .with_tolerance(1e-6)
            .with_max_iter(500);
        let (bodies, detect) = settling_pile(120, 5);
        let mut shifted = 0usize;
        let solved = run_steps(bodies, 60, &detect, &mut |world, candidates| {
            let local = local_step(world, candidates);
            let global = global_step(world, candidates);
            assert_eq!(local.ids, global.ids);
            shifted += global.problem.b().iter().filter(|b| **b > 0.0).count();
            let mut operator = global.problem.operator().unwrap();
            assert!(operator.mass().is_block_diagonal());
            let reduced = global.problem.reduce(&mut operator).unwrap();
            let p = &local.problem;
            let scale = p.q().iter().fold(1e-3_f64, |a, v| a.max(v.abs()));
            for (a, b) in reduced.q().iter().zip(p.q()) {
                assert!((a - b).abs() <= 1e-12 * scale, "q: {a} {b}");
            }
            let mut wmax = 0.0_f64;
            p.w().for_each_entry(|_, _, v| wmax = wmax.max(v.abs()));
            let mut worst = 0.0_f64;
            p.w()
                .for_each_entry(|i, j, v| worst = worst.max((v - reduced.w().get(i, j)).abs()));
            reduced
                .w()
                .for_each_entry(|i, j, v| worst = worst.max((v - p.w().get(i, j)).abs()));
            assert!(worst <= 1e-12 * wmax, "W: {worst} of {wmax}");
            let (mut r, mut u) = (vec![0.0; p.size()], vec![0.0; p.size()]);
            solve(p, &config, &mut r, &mut u).expect("solve");
            r
        });
        assert!(
            solved > 20 && shifted > 0,
            "{solved} steps, {shifted} shifted rows"
        );
    }
}

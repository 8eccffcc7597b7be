//! Siconos' `GFC3D IPM` (id 615): a primal-dual interior-point method (Mehrotra's
//! predictor-corrector) on the global problem written as a second-order cone program.
//!
//! With `P = diag(1/mu, 1, 1)` per contact, the scaled velocity `u_s = P u` and reaction
//! `r_s = P^-1 r` live in the second-order cone `L = { x_0 >= ||x̄|| }` exactly when `u ∈ K*`
//! and `r ∈ K` (Coulomb's cone and its dual), and the problem becomes: find `(v, u_s, r_s)` with
//!
//! * `M v - q - H P r_s = 0` (the balance, "dual" residual),
//! * `u_s - P H^T v - w = 0`, `w = P b` (the kinematics, "primal" residual),
//! * `L ∋ u_s ⟂ r_s ∈ L`, linearised as `u_s ∘ r_s = 2 sigma mu e` in the cone's Jordan algebra
//!   ([`crate::math::jordan`]).
//!
//! This is the associated (convex) law, `u ∈ K* ⟂ r ∈ K`, not Coulomb's: by default
//! (Siconos' `UPDATE_S = NO`) the method solves that convex relaxation. With
//! [`IpmOptions::update_s`] the normal part of `w` carries De Saxcé's term, `w_N = b_N / mu +
//! ||u_T||` at the current velocity, updated every iteration (a fixed point on that term inside
//! the interior-point iteration), and the solution sought is Coulomb's.
//!
//! Each iteration (as Siconos 4.4's `gfc3d_IPM`): the Nesterov-Todd scaling point `p` of each
//! contact (or, without it, the arrow matrices of `u_s` and `r_s`), then two Newton systems with
//! the same matrix: the affine (predictor) direction, its step lengths to the cones' boundaries,
//! the centering `sigma = min(1, (mu_aff / mu)^e)`, and the corrected direction; both iterates
//! move by their step length times a safety factor, and `mu = u_s · r_s / m`. Siconos starts
//! from a fixed point whatever the inputs (`v = 0.01`, `u_s = (0.1, 0.01, 0.01)`, `r_s =
//! (0.2056, 0.0351, 0.0351)`): so does fc3d, and the reaction given is not read.
//!
//! The Newton system `[[M, 0, -P̃^T], [0, A, B], [-P̃, I, 0]] (dv, du, dr) = -(res_d, res_c,
//! res_p)` (`P̃ = P H^T`; `A`, `B` the 3x3 blocks of the linearised complementarity: `Q_p^2` and
//! `I` with Nesterov-Todd scaling, `L_r` and `L_u` without) is solved through its reduction to
//! v: `du = P̃ dv - res_p`, `dr = B^-1 (A res_p - res_c) - S P̃ dv` with `S = B^-1 A` per contact,
//! and `(M + P̃^T S P̃) dv = -res_d + P̃^T B^-1 (A res_p - res_c)`. That is the direction of
//! Siconos' unreduced system (the iterates agree with Siconos' to the printed digits while its
//! run is sound), from a matrix of the size of M with the pattern of `M + H H^T`, fixed for the
//! run: faer's sparse LU, symbolic analysis once, one numeric factorization and two solves per
//! iteration. No matrix beyond the 3x3 blocks of a contact is dense. The functions of the
//! Jordan algebra are exact where Siconos 4.4 regularises the spectral decomposition by 1e-12,
//! which breaks its runs (a failed assertion, or no convergence) once the iterates near the
//! cones' boundaries.
//!
//! A contact with `mu = 0` (where Siconos' `P` divides by zero and its iteration returns NaN) is
//! frictionless: `u_N >= 0 ⟂ r_N >= 0`, `u_T` free, `r_T = 0`. Its normal components form a
//! one-dimensional cone (the same steps with the algebra of the reals), its tangential reaction
//! stays zero and its tangential velocity is left to the kinematics.
//!
//! Stopping: after every step the reaction is mapped back (`r = P r_s`), the triple the solve
//! returns is formed (`v = M^-1 (q + H r)`, `u = H^T v + b`), and its error is measured (the
//! convex error by default, Siconos' `gfc3d_compute_error_convex`; the global Coulomb error with
//! `update_s`); the run stops when it is at most the tolerance. Siconos measures the iterate's
//! own `v` instead, and also stops, reporting success, when its scaled residuals
//! (`||res_primal||_∞ / (1 + ||w||)`, `||res_dual||_∞ / (1 + ||q||)`, `||u_s ∘ r_s|| / nc`,
//! `mu`) are all below the tolerance; fc3d does not stop there, as the relative error of the
//! returned triple may still be above the tolerance. A Newton matrix that cannot be factored,
//! a non-finite direction or a step of length zero ends the run with the last iterate.

use std::time::{Duration, Instant};

use crate::contract::{IterationEvent, Limits, Observer, SolverOutcome};
use crate::error::{require_setting, try_vec, Fc3dError};
use crate::math::jordan;
use crate::math::linalg::{axpy3, contact_of, dot, mat3_mul, mat3_vec, norm2, Mat3, Vec3};
use crate::math::sparse_lu::SparseLu;
use crate::matrix::{transpose, CsrMatrix, HForm};
use crate::measure::{global_error_with, ContactLaw, ErrorWork};
use crate::problem::GlobalProblem;

/// Settings of the interior-point method (615), Siconos 4.4's defaults (`gfc3d_ipm_set_default`;
/// its iteration limit 200 and tolerance 1e-8 are [`super::GlobalMethod::default_limits`]).
///
/// By default the method solves the convex relaxation (`update_s = false`, as Siconos): where
/// some contact slides, its solution is not Coulomb's and the solve reports
/// [`crate::SolveStatus::RelaxationNotCoulomb`] (Siconos reports success). Set `update_s` for
/// Coulomb's law.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IpmOptions {
    /// Nesterov-Todd scaling of the complementarity (Siconos `iparam[11] = 1`, the default);
    /// without it the Newton system linearises `u_s ∘ r_s` with the arrow matrices.
    pub nesterov_todd: bool,
    /// De Saxcé's term in `w`, updated every iteration (Siconos `iparam[15] = 0`,
    /// `UPDATE_S_YES`): Coulomb's law. Default `false` (`iparam[15] = 1`): the convex relaxation.
    pub update_s: bool,
    /// Below this barrier parameter `mu`, the centering exponent is
    /// [`final_centering_exponent`](Self::final_centering_exponent) (Siconos `dparam[7]`,
    /// 1e-5; >= 0).
    pub centering_threshold: f64,
    /// Above the threshold the centering exponent is `max(1, this x min(alpha_p, alpha_d))`
    /// of the affine step lengths (Siconos `dparam[8]`, 3; > 0).
    pub centering_exponent_factor: f64,
    /// The centering exponent below the threshold (Siconos `dparam[9]`, 1; > 0).
    pub final_centering_exponent: f64,
    /// The corrected step goes this fraction of the way to the cones' boundary, plus
    /// [`step_safety_slope`](Self::step_safety_slope) times the smaller affine step length
    /// (Siconos `dparam[10]`, 0.8; > 0).
    pub step_safety: f64,
    /// See [`step_safety`](Self::step_safety) (Siconos `dparam[11]`, 0.09; >= 0,
    /// `step_safety + step_safety_slope < 1` so that iterates stay interior).
    pub step_safety_slope: f64,
}

impl Default for IpmOptions {
    fn default() -> Self {
        IpmOptions {
            nesterov_todd: true,
            update_s: false,
            centering_threshold: 1e-5,
            centering_exponent_factor: 3.0,
            final_centering_exponent: 1.0,
            step_safety: 0.8,
            step_safety_slope: 0.09,
        }
    }
}

impl IpmOptions {
    pub fn validate(&self) -> Result<(), Fc3dError> {
        require_setting(
            self.centering_threshold >= 0.0 && self.centering_threshold.is_finite(),
            "global_ipm.centering_threshold",
            self.centering_threshold,
            "finite and >= 0",
        )?;
        for (name, value) in [
            (
                "global_ipm.centering_exponent_factor",
                self.centering_exponent_factor,
            ),
            (
                "global_ipm.final_centering_exponent",
                self.final_centering_exponent,
            ),
        ] {
            require_setting(
                value > 0.0 && value.is_finite(),
                name,
                value,
                "finite and > 0",
            )?;
        }
        require_setting(
            self.step_safety > 0.0 && self.step_safety < 1.0,
            "global_ipm.step_safety",
            self.step_safety,
            "in (0, 1)",
        )?;
        require_setting(
            self.step_safety_slope >= 0.0 && self.step_safety + self.step_safety_slope < 1.0,
            "global_ipm.step_safety_slope",
            self.step_safety_slope,
            ">= 0 and below 1 - step_safety",
        )
    }

    /// The law the run measures its iterate against.
    pub fn law(&self) -> ContactLaw {
        if self.update_s {
            ContactLaw::Coulomb
        } else {
            ContactLaw::Convex
        }
    }
}

/// The cone of one contact's scaled pair `(u_s, r_s)`.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Cone {
    /// `mu > 0`: both in the second-order cone `L`.
    Lorentz,
    /// `mu = 0`: `u_N >= 0 ⟂ r_N >= 0`, `u_T` free, `r_T = 0`.
    Ray,
}

impl Cone {
    fn is_interior(self, x: &Vec3) -> bool {
        match self {
            Cone::Lorentz => jordan::is_interior(x),
            Cone::Ray => x[0] > 0.0,
        }
    }

    /// The longest step `x + alpha dx` stays in the cone.
    fn max_step(self, x: &Vec3, dx: &Vec3) -> f64 {
        match self {
            Cone::Lorentz => jordan::max_step(x, dx),
            Cone::Ray if dx[0] < 0.0 => -x[0] / dx[0],
            Cone::Ray => f64::INFINITY,
        }
    }

    /// The blocks `A` and `B^-1` of the linearised complementarity `A du + B dr = -res` at
    /// `(u, r)`, and the Nesterov-Todd point (`e` without scaling).
    fn linearize(self, scaled: bool, u: &Vec3, r: &Vec3) -> (Mat3, Mat3, Vec3) {
        const I: Mat3 = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        match (self, scaled) {
            (Cone::Lorentz, true) => {
                let p = jordan::nesterov_todd_point(u, r);
                (jordan::quadratic(&jordan::product(&p, &p)), I, p)
            }
            (Cone::Lorentz, false) => {
                (jordan::arrow(r), jordan::arrow_inverse(u), jordan::IDENTITY)
            }
            // The reals' algebra on the normal components; the tangential rows keep dr_T = -r_T.
            (Cone::Ray, true) => (diagonal(r[0] / u[0], 0.0), I, jordan::IDENTITY),
            (Cone::Ray, false) => (
                diagonal(r[0], 0.0),
                diagonal(1.0 / u[0], 1.0),
                jordan::IDENTITY,
            ),
        }
    }

    /// The complementarity residual of the Newton system: the affine one (`target = 0`, no
    /// `(du, dr)`), or Mehrotra's corrected one with the affine direction and the centering
    /// target `2 sigma mu`. Scaled: `r - target u^-1 + (Q_p du) ∘ (Q_p^-1 dr)` (Siconos'
    /// `Q_p (Q_p u)^-1`, which equals `u^-1`); unscaled: `u ∘ r - target e + du ∘ dr`.
    fn residual(
        self,
        scaled: bool,
        (u, r, p): (&Vec3, &Vec3, &Vec3),
        affine: Option<(&Vec3, &Vec3)>,
        target: f64,
    ) -> Vec3 {
        match (self, scaled) {
            (Cone::Lorentz, true) => {
                let Some((du, dr)) = affine else {
                    return *r;
                };
                let u_inv = jordan::inverse(u);
                let du_t = mat3_vec(&jordan::quadratic(p), du);
                let dr_t = mat3_vec(&jordan::quadratic(&jordan::inverse(p)), dr);
                let cross = jordan::product(&du_t, &dr_t);
                [
                    r[0] - target * u_inv[0] + cross[0],
                    r[1] - target * u_inv[1] + cross[1],
                    r[2] - target * u_inv[2] + cross[2],
                ]
            }
            (Cone::Lorentz, false) => {
                let ur = jordan::product(u, r);
                let Some((du, dr)) = affine else {
                    return ur;
                };
                let cross = jordan::product(du, dr);
                [
                    ur[0] - target + cross[0],
                    ur[1] + cross[1],
                    ur[2] + cross[2],
                ]
            }
            (Cone::Ray, _) => {
                let base = if scaled { r[0] } else { u[0] * r[0] };
                let normal = match affine {
                    None => base,
                    Some((du, dr)) if scaled => base - target / u[0] + du[0] * dr[0],
                    Some((du, dr)) => base - target + du[0] * dr[0],
                };
                [normal, r[1], r[2]]
            }
        }
    }
}

fn diagonal(normal: f64, tangential: f64) -> Mat3 {
    [
        [normal, 0.0, 0.0],
        [0.0, tangential, 0.0],
        [0.0, 0.0, tangential],
    ]
}

/// The Newton matrix reduced to v, `M + P̃^T S P̃` (`P̃ = P H^T`, `S = B^-1 A` block diagonal),
/// on its fixed pattern: M's and, per contact, the square of the columns its rows touch.
struct NewtonSystem {
    lu: SparseLu,
    /// M's values in the pattern's slots (each factorization starts from them).
    m_values: Vec<f64>,
    /// Per contact, its range of the columns of v its three rows of `H^T` touch (ascending).
    column_ptr: Vec<usize>,
    /// `P H^T` on those columns, three values (the contact's rows) per column.
    scaled_ht: Vec<f64>,
    /// Per contact, the value slots of its `k x k` square of columns, row by row, from
    /// `square_ptr[c]`.
    square_ptr: Vec<usize>,
    square_slots: Vec<usize>,
    /// `S P̃` on a contact's columns (work space of the widest contact).
    sg: Vec<f64>,
}

impl NewtonSystem {
    fn new(problem: &GlobalProblem<'_>, ht: &CsrMatrix, scale: &[f64]) -> Result<Self, Fc3dError> {
        let (n, nc) = (problem.ndof(), problem.n_contacts());
        let what = "the IPM Newton matrix";
        let mut column_ptr = try_vec(nc + 1, 0usize, what)?;
        let mut columns = Vec::new();
        let mut marker = try_vec(n, usize::MAX, what)?;
        for c in 0..nc {
            for k in 3 * c..3 * c + 3 {
                for &j in &ht.col_idx()[ht.row_ptr()[k]..ht.row_ptr()[k + 1]] {
                    if marker[j] != c {
                        marker[j] = c;
                        columns.push(j);
                    }
                }
            }
            columns[column_ptr[c]..].sort_unstable();
            column_ptr[c + 1] = columns.len();
        }
        let mut scaled_ht = try_vec(3 * columns.len(), 0.0, what)?;
        let mut widest = 0;
        for c in 0..nc {
            let range = column_ptr[c]..column_ptr[c + 1];
            widest = widest.max(range.len());
            for i in 0..3 {
                let k = 3 * c + i;
                let entries = ht.row_ptr()[k]..ht.row_ptr()[k + 1];
                for (&j, &x) in ht.col_idx()[entries.clone()]
                    .iter()
                    .zip(&ht.values()[entries])
                {
                    let at = range.start + columns[range.clone()].partition_point(|&y| y < j);
                    scaled_ht[3 * at + i] += scale[k] * x;
                }
            }
        }
        let mut positions = Vec::new();
        let mut m_entries = Vec::new();
        problem.m().for_each_entry(|i, j, x| {
            positions.push((i, j));
            m_entries.push(x);
        });
        let fixed = positions.len();
        let mut square_ptr = try_vec(nc + 1, 0usize, what)?;
        for c in 0..nc {
            let cols = &columns[column_ptr[c]..column_ptr[c + 1]];
            for &i in cols {
                for &j in cols {
                    positions.push((i, j));
                }
            }
            square_ptr[c + 1] = positions.len() - fixed;
        }
        let (lu, slots) = SparseLu::from_positions(n, &positions, what)?;
        let mut m_values = try_vec(lu.nnz(), 0.0, what)?;
        for (&s, &x) in slots[..fixed].iter().zip(&m_entries) {
            m_values[s] += x;
        }
        Ok(NewtonSystem {
            lu,
            m_values,
            column_ptr,
            scaled_ht,
            square_ptr,
            square_slots: slots[fixed..].to_vec(),
            sg: try_vec(3 * widest, 0.0, what)?,
        })
    }

    /// Assembles `M + P̃^T S P̃` for the contact blocks `s` and factors it.
    fn factor(&mut self, s: &[Mat3]) -> bool {
        let vals = self.lu.values_mut();
        vals.copy_from_slice(&self.m_values);
        for (c, sc) in s.iter().enumerate() {
            let (start, end) = (self.column_ptr[c], self.column_ptr[c + 1]);
            let g = &self.scaled_ht[3 * start..3 * end];
            let width = end - start;
            for k in 0..width {
                let gk = [g[3 * k], g[3 * k + 1], g[3 * k + 2]];
                let t = mat3_vec(sc, &gk);
                self.sg[3 * k..3 * k + 3].copy_from_slice(&t);
            }
            let slots = &self.square_slots[self.square_ptr[c]..self.square_ptr[c + 1]];
            for a in 0..width {
                let ga = &g[3 * a..3 * a + 3];
                for b in 0..width {
                    let t = &self.sg[3 * b..3 * b + 3];
                    vals[slots[a * width + b]] += ga[0] * t[0] + ga[1] * t[1] + ga[2] * t[2];
                }
            }
        }
        self.lu.factor().is_ok()
    }
}

/// The scaled problem and the work space of a run (allocated before the loop).
struct Ipm<'p, 'a> {
    problem: &'p GlobalProblem<'a>,
    options: IpmOptions,
    cones: Vec<Cone>,
    /// `P`'s diagonal: `1/mu` at the normal component of a contact with friction, else 1.
    scale: Vec<f64>,
    ht: CsrMatrix,
    system: NewtonSystem,
    /// The iterate `(v, u_s, r_s)` and `w`.
    v: Vec<f64>,
    u: Vec<f64>,
    r: Vec<f64>,
    w: Vec<f64>,
    /// `u_s - P H^T v - w` and `M v - q - H P r_s`.
    primal: Vec<f64>,
    dual: Vec<f64>,
    /// Per contact: the linearisation's `A`, `B^-1`, `S = B^-1 A` and Nesterov-Todd point.
    a: Vec<Mat3>,
    b_inv: Vec<Mat3>,
    s: Vec<Mat3>,
    p: Vec<Vec3>,
    /// The affine and the corrected direction.
    affine: Direction,
    step: Direction,
    /// A work vector of the size of r.
    work_m: Vec<f64>,
}

/// A Newton direction `(dv, du, dr)`.
struct Direction {
    dv: Vec<f64>,
    du: Vec<f64>,
    dr: Vec<f64>,
}

impl Direction {
    fn new(n: usize, m: usize) -> Result<Self, Fc3dError> {
        Ok(Direction {
            dv: try_vec(n, 0.0, "the IPM direction")?,
            du: try_vec(m, 0.0, "the IPM direction")?,
            dr: try_vec(m, 0.0, "the IPM direction")?,
        })
    }
}

/// The step lengths `(alpha_p, alpha_d)` of a direction.
type Steps = (f64, f64);

impl<'p, 'a> Ipm<'p, 'a> {
    fn new(problem: &'p GlobalProblem<'a>, options: IpmOptions) -> Result<Self, Fc3dError> {
        let (n, m, nc) = (problem.ndof(), problem.size(), problem.n_contacts());
        let cones: Vec<Cone> = problem
            .mu()
            .iter()
            .map(|&mu| if mu > 0.0 { Cone::Lorentz } else { Cone::Ray })
            .collect();
        let mut scale = try_vec(m, 1.0, "the IPM scaling")?;
        for (c, &mu) in problem.mu().iter().enumerate() {
            if mu > 0.0 {
                scale[3 * c] = 1.0 / mu;
            }
        }
        let ht = transpose(problem.h())?;
        let system = NewtonSystem::new(problem, &ht, &scale)?;
        let blocks = || try_vec(nc, [[0.0; 3]; 3], "the IPM blocks");
        Ok(Ipm {
            problem,
            options,
            cones,
            scale,
            ht,
            system,
            v: try_vec(n, 0.0, "the IPM iterate")?,
            u: try_vec(m, 0.0, "the IPM iterate")?,
            r: try_vec(m, 0.0, "the IPM iterate")?,
            w: try_vec(m, 0.0, "the IPM iterate")?,
            primal: try_vec(m, 0.0, "the IPM residuals")?,
            dual: try_vec(n, 0.0, "the IPM residuals")?,
            a: blocks()?,
            b_inv: blocks()?,
            s: blocks()?,
            p: try_vec(nc, [0.0; 3], "the IPM blocks")?,
            affine: Direction::new(n, m)?,
            step: Direction::new(n, m)?,
            work_m: try_vec(m, 0.0, "the IPM work space")?,
        })
    }

    /// Siconos' starting point and `w = P b`.
    fn start(&mut self) {
        self.v.iter_mut().for_each(|x| *x = 0.01);
        for (c, cone) in self.cones.iter().enumerate() {
            self.u[3 * c..3 * c + 3].copy_from_slice(&[0.1, 0.01, 0.01]);
            let r = match cone {
                Cone::Lorentz => [0.2056, 0.0351, 0.0351],
                Cone::Ray => [0.2056, 0.0, 0.0],
            };
            self.r[3 * c..3 * c + 3].copy_from_slice(&r);
        }
        for ((w, b), s) in self.w.iter_mut().zip(self.problem.b()).zip(&self.scale) {
            *w = b * s;
        }
    }

    /// De Saxcé's term at the current velocity: `w_N = b_N / mu + ||u_T||`.
    fn update_w(&mut self) {
        for (c, cone) in self.cones.iter().enumerate() {
            if *cone == Cone::Lorentz {
                let k = 3 * c;
                self.w[k] =
                    self.problem.b()[k] * self.scale[k] + norm2(self.u[k + 1], self.u[k + 2]);
            }
        }
    }

    /// The primal and dual residuals of the iterate.
    fn residuals(&mut self) {
        let mut t = std::mem::take(&mut self.work_m);
        scaled_ht_mul(&self.ht, &self.scale, &self.v, &mut t);
        for (((res, x), u), w) in self.primal.iter_mut().zip(&t).zip(&self.u).zip(&self.w) {
            *res = u - x - w;
        }
        // dual = M v - q - H (P r), with t = -P r.
        for ((x, s), r) in t.iter_mut().zip(&self.scale).zip(&self.r) {
            *x = -s * r;
        }
        let p = self.problem;
        for (d, q) in self.dual.iter_mut().zip(p.q()) {
            *d = -q;
        }
        p.m().mul_add(&self.v, &mut self.dual);
        p.h().mul_add(&t, &mut self.dual);
        self.work_m = t;
    }

    /// The blocks of every contact at the iterate.
    fn linearize(&mut self) {
        for (c, cone) in self.cones.iter().enumerate() {
            let (a, b_inv, p) = cone.linearize(
                self.options.nesterov_todd,
                &contact_of(&self.u, c),
                &contact_of(&self.r, c),
            );
            self.a[c] = a;
            self.b_inv[c] = b_inv;
            self.s[c] = mat3_mul(&b_inv, &a);
            self.p[c] = p;
        }
    }

    /// Solves the Newton system (factored) for the direction into `step` when `corrected`
    /// (else `affine`): the complementarity residual is the affine one, or the corrected one
    /// with the affine direction and `target`. With `du = P̃ dv - res_p` and
    /// `dr = B^-1 (A res_p - res_c) - S P̃ dv`, the balance row gives
    /// `(M + P̃^T S P̃) dv = -res_d + P̃^T B^-1 (A res_p - res_c)`. False when the direction is
    /// not finite.
    fn solve(&mut self, corrected: bool, target: f64) -> bool {
        let Ipm {
            problem,
            options,
            cones,
            scale,
            ht,
            system,
            u,
            r,
            primal,
            dual,
            a,
            b_inv,
            s,
            p,
            affine,
            step,
            work_m,
            ..
        } = self;
        let (direction, previous) = if corrected {
            (step, Some(&*affine))
        } else {
            (affine, None)
        };
        let Direction { dv, du, dr } = direction;
        for (c, cone) in cones.iter().enumerate() {
            let (uc, rc) = (contact_of(u, c), contact_of(r, c));
            let da = previous.map(|d| (contact_of(&d.du, c), contact_of(&d.dr, c)));
            let res = cone.residual(
                options.nesterov_todd,
                (&uc, &rc, &p[c]),
                da.as_ref().map(|(du, dr)| (du, dr)),
                target,
            );
            let a_primal = mat3_vec(&a[c], &contact_of(primal, c));
            let rhs = mat3_vec(
                &b_inv[c],
                &[
                    a_primal[0] - res[0],
                    a_primal[1] - res[1],
                    a_primal[2] - res[2],
                ],
            );
            dr[3 * c..3 * c + 3].copy_from_slice(&rhs);
        }
        for ((t, x), sc) in work_m.iter_mut().zip(dr.iter()).zip(scale.iter()) {
            *t = sc * x;
        }
        for (x, d) in dv.iter_mut().zip(dual.iter()) {
            *x = -d;
        }
        problem.h().mul_add(work_m, dv);
        system.lu.solve_in_place(dv);
        if !dv.iter().all(|x| x.is_finite()) {
            return false;
        }
        scaled_ht_mul(ht, scale, dv, du);
        for (c, sc) in s.iter().enumerate() {
            let correction = mat3_vec(sc, &contact_of(du, c));
            for i in 0..3 {
                dr[3 * c + i] -= correction[i];
            }
        }
        for (x, res) in du.iter_mut().zip(primal.iter()) {
            *x -= res;
        }
        dr.iter().all(|x| x.is_finite())
    }

    /// The step lengths of a direction to the cones' boundaries, capped at 1, times `safety`.
    fn step_lengths(&self, direction: &Direction, safety: f64) -> Steps {
        let (mut primal, mut dual) = (1.0_f64, 1.0_f64);
        for (c, cone) in self.cones.iter().enumerate() {
            let (u, r) = (contact_of(&self.u, c), contact_of(&self.r, c));
            primal = primal.min(cone.max_step(&u, &contact_of(&direction.du, c)));
            dual = dual.min(cone.max_step(&r, &contact_of(&direction.dr, c)));
        }
        (safety * primal, safety * dual)
    }

    /// `(u + alpha_p du) · (r + alpha_d dr) / m` for the affine direction.
    fn affine_barrier(&self, (alpha_p, alpha_d): Steps) -> f64 {
        let d = &self.affine;
        let mut s = 0.0;
        for k in 0..self.u.len() {
            s += (self.u[k] + alpha_p * d.du[k]) * (self.r[k] + alpha_d * d.dr[k]);
        }
        s / self.u.len() as f64
    }

    /// Whether `(u + alpha_p du, r + alpha_d dr)` is interior for every contact.
    fn stays_interior(&self, (alpha_p, alpha_d): Steps) -> bool {
        let d = &self.step;
        self.cones.iter().enumerate().all(|(c, cone)| {
            let (u, r) = (contact_of(&self.u, c), contact_of(&self.r, c));
            let (du, dr) = (contact_of(&d.du, c), contact_of(&d.dr, c));
            cone.is_interior(&axpy3(alpha_p, &du, &u)) && cone.is_interior(&axpy3(alpha_d, &dr, &r))
        })
    }

    /// Moves the iterate along the corrected direction; halves the steps while a contact would
    /// leave the interior of its cone (rounding at a boundary). False when no step is left.
    fn advance(&mut self, mut steps: Steps) -> bool {
        let mut halvings = 0;
        while !self.stays_interior(steps) {
            halvings += 1;
            if halvings > 60 {
                return false;
            }
            steps = (0.5 * steps.0, 0.5 * steps.1);
        }
        if !(steps.0 > 0.0 || steps.1 > 0.0) {
            return false;
        }
        let d = &self.step;
        for (x, dx) in self.v.iter_mut().zip(&d.dv) {
            *x += steps.0 * dx;
        }
        for (x, dx) in self.u.iter_mut().zip(&d.du) {
            *x += steps.0 * dx;
        }
        for (x, dx) in self.r.iter_mut().zip(&d.dr) {
            *x += steps.1 * dx;
        }
        true
    }

    /// The reaction of the problem, `r = P r_s`.
    fn reaction(&self, out: &mut [f64]) {
        for ((o, r), s) in out.iter_mut().zip(&self.r).zip(&self.scale) {
            *o = r * s;
        }
    }
}

/// `P H^T x` into `out`.
fn scaled_ht_mul(ht: &CsrMatrix, scale: &[f64], x: &[f64], out: &mut [f64]) {
    out.iter_mut().for_each(|y| *y = 0.0);
    ht.mul_add(x, out);
    for (y, s) in out.iter_mut().zip(scale) {
        *y *= s;
    }
}

/// Runs the interior-point method (the reaction given is not read: Siconos' fixed start).
#[allow(clippy::too_many_arguments)]
pub(super) fn run(
    problem: &GlobalProblem<'_>,
    operator: &mut HForm,
    options: &IpmOptions,
    limits: &Limits,
    r: &mut [f64],
    u: &mut [f64],
    v: &mut [f64],
    observer: &mut Observer<'_>,
) -> Result<SolverOutcome, Fc3dError> {
    let run = limits.start();
    // The set-up (the Newton matrix: M's entries and each contact's square of the k unknowns
    // its rows touch) and the first factorization are not started when predicted to end past
    // the deadline: r as it came, 0 iterations.
    let entries = super::set_up_entries(problem, |k| k * k, 0);
    if !crate::math::lu_cost::assembly_ends_by(entries, run.deadline()) {
        return Ok(SolverOutcome::stopped(0, true));
    }
    let mut ipm = Ipm::new(problem, *options)?;
    let what = "the IPM Newton matrix";
    if !ipm.system.lu.factor_ends_by(run.deadline(), what)? {
        return Ok(SolverOutcome::stopped(0, true));
    }
    let mut work = ErrorWork::new(problem.ndof());
    let law = options.law();
    let m = problem.size() as f64;
    ipm.start();
    ipm.reaction(r);
    // Siconos' first barrier parameter (not the starting point's).
    let mut barrier = 1.0;
    let mut last_iteration = Duration::ZERO;
    let mut last_error = None;
    let stopped = |iterations, error: Option<f64>| {
        let converged = error.is_some_and(|e| e <= run.tolerance);
        SolverOutcome {
            relaxation_converged: converged && !options.update_s,
            // The solve measures Coulomb's error unless that is what was measured.
            ..SolverOutcome::stopped(iterations, false)
                .with_final_error(error.filter(|_| options.update_s))
        }
    };
    for iteration in 1..=run.max_iter {
        // The set-up (M's and the Newton matrix's analyses) may have spent the budget; a
        // factorization is not started when the last iteration says it would overrun.
        if run.out_of_time()
            || (iteration > 1 && run.cannot_afford(last_iteration))
            || !ipm.system.lu.factor_ends_by(run.deadline(), what)?
        {
            return Ok(SolverOutcome::stopped(iteration - 1, true));
        }
        let started = Instant::now();
        ipm.linearize();
        if options.update_s {
            ipm.update_w();
        }
        ipm.residuals();
        if !ipm.system.factor(&ipm.s) || !ipm.solve(false, 0.0) {
            return Ok(stopped(iteration - 1, last_error));
        }
        let affine_steps = ipm.step_lengths(&ipm.affine, 1.0);
        let smallest = affine_steps.0.min(affine_steps.1);
        let safety = options.step_safety + options.step_safety_slope * smallest;
        let exponent = if barrier > options.centering_threshold {
            (options.centering_exponent_factor * smallest).max(1.0)
        } else {
            options.final_centering_exponent
        };
        let sigma = (ipm.affine_barrier(affine_steps) / barrier)
            .powf(exponent)
            .min(1.0);
        if !ipm.solve(true, 2.0 * barrier * sigma) {
            return Ok(stopped(iteration - 1, last_error));
        }
        let steps = ipm.step_lengths(&ipm.step, safety);
        if !ipm.advance(steps) {
            return Ok(stopped(iteration - 1, last_error));
        }
        barrier = dot(&ipm.u, &ipm.r) / m;
        // The triple the solve returns, and its error in the law solved.
        ipm.reaction(r);
        operator.global_velocity(problem.q(), r, v);
        let error = global_error_with(problem, law, r, u, v, None, &mut work);
        last_error = Some(error);
        observer(&IterationEvent {
            iteration,
            reaction: r,
            error,
        });
        if error <= run.tolerance {
            return Ok(stopped(iteration, last_error));
        }
        last_iteration = started.elapsed();
        if let Some(outcome) = run.end_of_iteration(iteration, false) {
            return Ok(outcome);
        }
    }
    Ok(run.exhausted())
}

//! Siconos' `GFC3D_NSN_AC` (id 607): semismooth Newton on `z = (v, u, r)` for
//!
//! `psi(z) = [ -M v + H r + q ;  H^T v - u + b ;  F(r, u) ] = 0`,
//!
//! F the Alart-Curnier or Jean-Moreau function of each contact (the local Newton's, in
//! `solvers::nsn::jacobian`), with the Jacobian `[[-M, 0, H], [H^T, -I, 0], [0, B, A]]`
//! (`A = dF/dr`, `B = dF/du`, 3x3 a contact) factored by faer's sparse LU on a pattern fixed
//! for the run (symbolic analysis once), and Siconos' Goldstein-Price search on `|psi|^2 / 2`.
//! No W is formed: the system has the size of M plus twice the contact unknowns, and its
//! fill is that of M and H.
//!
//! The error is measured on the consistent triple of the current reaction (`v = M^-1 (q + H r)`,
//! `u = H^T v + b`), which is what the solve returns.

use crate::contract::{IterationEvent, Limits, Observer, SolverOutcome};
use crate::error::{require_setting, try_vec, Fc3dError};
use crate::math::linalg::Mat3;
use crate::math::sparse_lu::SparseLu;
use crate::matrix::{transpose_mul_add, HForm};
use crate::measure::{global_error_with, ContactLaw, ErrorWork};
use crate::problem::GlobalProblem;

use super::rescaling::GlobalRescaling;
use crate::solvers::nsn::jacobian::{residual, ContactData};
use crate::solvers::nsn::linesearch::siconos_goldstein_price;
use crate::solvers::nsn::NsnFormulation;

/// Shifts of the contact blocks `dF/dr` (entries of order 1) tried in turn when the Newton
/// matrix cannot be factored or gives a non-finite step; 0 first (Siconos' matrix).
const REGULARIZATION_SHIFTS: [f64; 5] = [0.0, 1e-10, 1e-7, 1e-4, 1e-1];

/// Settings of the global Newton (607), Siconos 4.4's defaults.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GlobalNewtonOptions {
    /// Alart-Curnier or Jean-Moreau (Siconos 607's default: Jean-Moreau, `iparam[10] = 1`).
    pub formulation: NsnFormulation,
    /// `rho_N = rho_T` of every contact (Siconos: `dparam[3] = 1`; > 0).
    pub rho: f64,
    /// Goldstein-Price search (Siconos: yes, `iparam[11] = 0`) or full steps (-1).
    pub line_search: bool,
    /// Trial steps per search (Siconos 607: `iparam[12] = 1000`; >= 1).
    pub line_search_max_iter: usize,
    /// The global error is measured every this many iterations (`iparam[8]`, 1 = every one).
    pub error_frequency: usize,
    /// The rescaling of the problem before the run (Siconos' `iparam[3]`; default none).
    pub rescaling: GlobalRescaling,
}

impl Default for GlobalNewtonOptions {
    fn default() -> Self {
        GlobalNewtonOptions {
            formulation: NsnFormulation::JeanMoreau,
            rho: 1.0,
            line_search: true,
            line_search_max_iter: 1000,
            error_frequency: 1,
            rescaling: GlobalRescaling::None,
        }
    }
}

impl GlobalNewtonOptions {
    pub fn validate(&self) -> Result<(), Fc3dError> {
        require_setting(
            matches!(
                self.formulation,
                NsnFormulation::AlartCurnier | NsnFormulation::JeanMoreau
            ),
            "global_newton.formulation",
            self.formulation.short_name(),
            "Alart-Curnier or Jean-Moreau",
        )?;
        require_setting(
            self.rho > 0.0 && self.rho.is_finite(),
            "global_newton.rho",
            self.rho,
            "finite and > 0",
        )?;
        require_setting(
            self.line_search_max_iter >= 1,
            "global_newton.line_search_max_iter",
            self.line_search_max_iter,
            ">= 1",
        )?;
        require_setting(
            self.error_frequency >= 1,
            "global_newton.error_frequency",
            self.error_frequency,
            ">= 1",
        )
    }
}

/// The Newton matrix on its fixed pattern, with the value slots of the contact blocks.
struct NewtonSystem {
    lu: SparseLu,
    /// Value slots of `A_c[i][j]` at `9 c + 3 i + j` (rows `n + m + 3c + i`, columns of r).
    a_slots: Vec<usize>,
    /// Value slots of `B_c[i][j]` (columns of u).
    b_slots: Vec<usize>,
}

impl NewtonSystem {
    fn new(problem: &GlobalProblem<'_>) -> Result<Self, Fc3dError> {
        let (n, m) = (problem.ndof(), problem.size());
        let size = n + 2 * m;
        let mut positions = Vec::new();
        let mut values = Vec::new();
        problem.m().for_each_entry(|i, j, x| {
            positions.push((i, j));
            values.push(-x);
        });
        problem.h().for_each_entry(|i, j, x| {
            // H in the first block row (columns of r), H^T in the second (columns of v).
            positions.push((i, n + m + j));
            values.push(x);
            positions.push((n + j, i));
            values.push(x);
        });
        for k in 0..m {
            positions.push((n + k, n + k));
            values.push(-1.0);
        }
        let fixed = positions.len();
        for c in 0..problem.n_contacts() {
            for i in 0..3 {
                for j in 0..3 {
                    positions.push((n + m + 3 * c + i, n + m + 3 * c + j));
                }
            }
        }
        for c in 0..problem.n_contacts() {
            for i in 0..3 {
                for j in 0..3 {
                    positions.push((n + m + 3 * c + i, n + 3 * c + j));
                }
            }
        }
        let (mut lu, slots) =
            SparseLu::from_positions(size, &positions, "the global Newton matrix")?;
        // The fixed part is set once; the contact blocks are written every iteration.
        let vals = lu.values_mut();
        for (&s, &x) in slots[..fixed].iter().zip(&values) {
            vals[s] += x;
        }
        let contact = slots.len() - fixed;
        Ok(NewtonSystem {
            lu,
            a_slots: slots[fixed..fixed + contact / 2].to_vec(),
            b_slots: slots[fixed + contact / 2..].to_vec(),
        })
    }

    /// Writes the contact blocks, `A + shift I` in place of A.
    fn set_contact_blocks(&mut self, a: &[Mat3], b: &[Mat3], shift: f64) {
        let vals = self.lu.values_mut();
        for (c, (ac, bc)) in a.iter().zip(b).enumerate() {
            for i in 0..3 {
                for j in 0..3 {
                    let diagonal = if i == j { shift } else { 0.0 };
                    vals[self.a_slots[9 * c + 3 * i + j]] = ac[i][j] + diagonal;
                    vals[self.b_slots[9 * c + 3 * i + j]] = bc[i][j];
                }
            }
        }
    }

    /// Factors the matrix with the contact blocks `a`, `b` and solves `J d = rhs` in place.
    /// A Jacobian that cannot be factored (a hyperstatic contact set: more contact rows than
    /// the bodies' unknowns make the rows of the sticking contacts dependent) is retried with
    /// a growing shift of the law's dependence on r, the step of a proximal regularisation of
    /// F; the line search still measures the true residual.
    fn solve(&mut self, a: &[Mat3], b: &[Mat3], rhs: &mut [f64], copy: &mut [f64]) -> bool {
        copy.copy_from_slice(rhs);
        for shift in REGULARIZATION_SHIFTS {
            self.set_contact_blocks(a, b, shift);
            if self.lu.factor().is_ok() {
                rhs.copy_from_slice(copy);
                self.lu.solve_in_place(rhs);
                if rhs.iter().all(|x| x.is_finite()) {
                    return true;
                }
            }
        }
        false
    }
}

/// `psi(z)` into `psi` and `|psi|^2 / 2`; with `blocks`, also the contact blocks A and B.
#[allow(clippy::too_many_arguments)]
fn evaluate(
    problem: &GlobalProblem<'_>,
    data: &[ContactData],
    formulation: NsnFormulation,
    z: &[f64],
    psi: &mut [f64],
    mut blocks: Option<(&mut [Mat3], &mut [Mat3])>,
) -> f64 {
    let (n, m) = (problem.ndof(), problem.size());
    let (v, rest) = z.split_at(n);
    let (u, r) = rest.split_at(m);
    let (p_balance, rest) = psi.split_at_mut(n);
    let (p_kinematics, p_law) = rest.split_at_mut(m);
    p_balance.copy_from_slice(problem.q());
    problem.h().mul_add(r, p_balance);
    problem
        .m()
        .for_each_entry(|i, j, x| p_balance[i] -= x * v[j]);
    for ((p, bk), uk) in p_kinematics.iter_mut().zip(problem.b()).zip(u) {
        *p = bk - uk;
    }
    transpose_mul_add(problem.h(), v, p_kinematics);
    for (c, d) in data.iter().enumerate() {
        let rc = [r[3 * c], r[3 * c + 1], r[3 * c + 2]];
        let uc = [u[3 * c], u[3 * c + 1], u[3 * c + 2]];
        let (f, a, b) = residual(formulation, &rc, &uc, d);
        p_law[3 * c..3 * c + 3].copy_from_slice(&f);
        if let Some((aa, bb)) = blocks.as_mut() {
            aa[c] = a;
            bb[c] = b;
        }
    }
    0.5 * psi.iter().map(|x| x * x).sum::<f64>()
}

/// Runs Newton from the reaction in `r` (`v` and `u` start from it).
#[allow(clippy::too_many_arguments)]
pub(super) fn run(
    problem: &GlobalProblem<'_>,
    operator: &mut HForm,
    options: &GlobalNewtonOptions,
    limits: &Limits,
    r: &mut [f64],
    u: &mut [f64],
    v: &mut [f64],
    observer: &mut Observer<'_>,
) -> Result<SolverOutcome, Fc3dError> {
    let run = limits.start();
    let (n, m) = (problem.ndof(), problem.size());
    let size = n + 2 * m;
    let nc = problem.n_contacts();
    let data: Vec<ContactData> = problem
        .mu()
        .iter()
        .map(|&mu| ContactData {
            mu,
            rho_n: options.rho,
            rho_t: options.rho,
        })
        .collect();
    // The set-up (the Newton matrix: M, H twice, the diagonal of u and two 3x3 blocks a
    // contact) and the first factorization are not started when predicted to end past the
    // deadline: r as it came, 0 iterations.
    let entries = problem.m().nnz() + 2 * problem.h().nnz() + m + 18 * nc;
    if !crate::math::lu_cost::assembly_ends_by(entries, run.deadline()) {
        return Ok(SolverOutcome::stopped(0, true));
    }
    let mut system = NewtonSystem::new(problem)?;
    let mut z = try_vec(size, 0.0, "the global Newton iterate")?;
    let mut psi = try_vec(size, 0.0, "the global Newton residual")?;
    let mut dz = try_vec(size, 0.0, "the global Newton step")?;
    let mut trial = try_vec(size, 0.0, "the global Newton trial")?;
    let mut trial_psi = try_vec(size, 0.0, "the global Newton trial")?;
    let mut a = vec![[[0.0; 3]; 3]; nc];
    let mut b = vec![[[0.0; 3]; 3]; nc];
    let mut work = ErrorWork::new(n);

    // z = (v(r), u(v), r): the balance and kinematic rows start at zero.
    operator.global_velocity(problem.q(), r, v);
    u.copy_from_slice(problem.b());
    operator.ht_mul_add(v, u);
    z[..n].copy_from_slice(v);
    z[n..n + m].copy_from_slice(u);
    z[n + m..].copy_from_slice(r);

    for iteration in 1..=run.max_iter {
        let merit = evaluate(
            problem,
            &data,
            options.formulation,
            &z,
            &mut psi,
            Some((&mut a, &mut b)),
        );
        for (d, p) in dz.iter_mut().zip(&psi) {
            *d = -p;
        }
        if !system
            .lu
            .factor_ends_by(run.deadline(), "the global Newton matrix")?
        {
            // r is the last iterate (as it came before the first).
            return Ok(SolverOutcome::stopped(iteration - 1, true));
        }
        if !system.solve(&a, &b, &mut dz, &mut trial) {
            // Siconos stops on a failed linear solve: so does fc3d after its shifts.
            r.copy_from_slice(&z[n + m..]);
            return Ok(SolverOutcome::stopped(iteration, false));
        }
        // The Newton direction's slope on |psi|^2 / 2 is -|psi|^2.
        let step = if options.line_search {
            siconos_goldstein_price(
                merit,
                -2.0 * merit,
                options.line_search_max_iter,
                run.deadline(),
                &mut |t| {
                    for ((x, z0), d) in trial.iter_mut().zip(&z).zip(&dz) {
                        *x = z0 + t * d;
                    }
                    evaluate(
                        problem,
                        &data,
                        options.formulation,
                        &trial,
                        &mut trial_psi,
                        None,
                    )
                },
            )
            .map_or(1.0, |s| s.t)
        } else {
            1.0
        };
        for (x, d) in z.iter_mut().zip(&dz) {
            *x += step * d;
        }
        r.copy_from_slice(&z[n + m..]);
        if iteration % options.error_frequency == 0 {
            operator.global_velocity(problem.q(), r, v);
            let error = global_error_with(problem, ContactLaw::Coulomb, r, u, v, None, &mut work);
            observer(&IterationEvent {
                iteration,
                reaction: r,
                error,
            });
            if error <= run.tolerance {
                return Ok(SolverOutcome::stopped(iteration, false).with_final_error(Some(error)));
            }
        }
        if let Some(outcome) = run.end_of_iteration(iteration, false) {
            return Ok(outcome);
        }
    }
    Ok(run.exhausted())
}

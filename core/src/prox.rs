//! Proximal point method (PROX, Siconos id 502; Algorithm 8 of Acary-Brémond-Huber with
//! omega = 1): from `r_k`, solve the regularized problem FC(W + a_k I, q - a_k r_k, mu) with an
//! internal solver (NSN-AC: PPA-NSN-AC, or NSGS: PPA-NSGS-AC) to the internal tolerance
//! `error_k / 10` (section 6.3), take its solution as `r_{k+1}`, and update the shift by
//! Siconos' variable rule `a_k = sigma error_k^nu` (read off Siconos 4.4's trace: its first shift
//! is `sigma` times the error of the initial guess), capped by `alpha`.

use std::time::Instant;

use crate::error::Fc3dError;
use crate::matrix::{BlockSparseMatrix, CsrMatrix, Delassus, DenseMatrix};
use crate::measure::natural_map_error;
use crate::nsn::{NewtonSolver, NsnFormulation, NsnOptions};
use crate::options::NsgsOptions;
use crate::problem::FrictionProblem;
use crate::solver::{IterationEvent, SolverOutcome};

/// The solver of the regularized problems.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ProxInternal {
    /// Alart-Curnier nonsmooth Newton (Siconos' default, 504). Its tolerance is replaced by the
    /// internal tolerance; its other options (iterations, rho, line search) are used as given.
    NsnAc(NsnOptions),
    /// Nonsmooth Gauss-Seidel (500), tolerance replaced likewise.
    Nsgs(NsgsOptions),
}

/// Options of the proximal point method. Defaults are Siconos 4.4's.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProxOptions {
    /// Maximum proximal iterations (1000).
    pub max_iter: usize,
    /// Tolerance on the natural-map error (1e-4).
    pub tolerance: f64,
    /// Largest diagonal shift `a_k` (Siconos' alpha, dparam[3], 1e4).
    pub alpha: f64,
    /// Factor of the shift rule `a_k = sigma error_k^nu` (dparam[4], 5).
    pub sigma: f64,
    /// Exponent of the shift rule (dparam[5], 1).
    pub nu: f64,
    /// Internal solver (NSN-AC with Siconos' 504 defaults).
    pub internal: ProxInternal,
    /// Wall-clock budget (default none).
    pub time_budget: Option<std::time::Duration>,
}

impl Default for ProxOptions {
    fn default() -> Self {
        ProxOptions {
            max_iter: 1000,
            tolerance: 1e-4,
            alpha: 1e4,
            sigma: 5.0,
            nu: 1.0,
            internal: ProxInternal::NsnAc(NsnOptions::new(NsnFormulation::AlartCurnier)),
            time_budget: None,
        }
    }
}

impl ProxOptions {
    /// Short label: `PROX/NSN-AC` or `PROX/NSGS`.
    pub fn label(&self) -> String {
        match self.internal {
            ProxInternal::NsnAc(_) => "PROX/NSN-AC".into(),
            ProxInternal::Nsgs(_) => "PROX/NSGS".into(),
        }
    }
}

pub(crate) fn validate(o: &ProxOptions) -> Result<(), Fc3dError> {
    for (name, v) in [("alpha", o.alpha), ("sigma", o.sigma), ("nu", o.nu)] {
        if !(v > 0.0 && v.is_finite()) {
            return Err(Fc3dError::InvalidOption(format!(
                "proximal {name} must be finite and > 0, got {v}"
            )));
        }
    }
    match &o.internal {
        ProxInternal::NsnAc(n) => {
            if !matches!(
                n.formulation,
                NsnFormulation::AlartCurnier | NsnFormulation::JeanMoreau
            ) {
                return Err(Fc3dError::InvalidOption(
                    "the proximal method's Newton solver must use the Alart-Curnier or \
                     Jean-Moreau formulation"
                        .into(),
                ));
            }
            crate::nsn::validate(n)
        }
        ProxInternal::Nsgs(_) => Ok(()),
    }
}

/// `W + shift I` in W's own storage.
fn shifted(w: &Delassus<'_>, shift: f64) -> Result<Delassus<'static>, Fc3dError> {
    let n = w.nrows();
    Ok(match w {
        Delassus::Dense(d) => {
            let mut data = d.values().to_vec();
            for i in 0..n {
                data[i + i * n] += shift;
            }
            Delassus::Dense(DenseMatrix::new(n, n, data)?)
        }
        Delassus::SparseBlock(s) => {
            let mut blocks = s.blocks().to_vec();
            for bi in 0..s.n_block_rows() {
                let (start, end) = (s.row_ptr()[bi], s.row_ptr()[bi + 1]);
                // Column-major 3x3: the diagonal is entries 0, 4, 8. Added to the first
                // diagonal block only, should a host store it twice.
                if let Some(k) = (start..end).find(|&k| s.col_idx()[k] == bi) {
                    for e in [0, 4, 8] {
                        blocks[k][e] += shift;
                    }
                }
            }
            Delassus::SparseBlock(BlockSparseMatrix::new(
                s.n_block_rows(),
                s.n_block_cols(),
                s.row_ptr().to_vec(),
                s.col_idx().to_vec(),
                blocks,
            )?)
        }
        Delassus::Sparse(s) => {
            let mut triplets = Vec::with_capacity(s.nnz() + n);
            s.for_each_entry(|i, j, v| triplets.push((i, j, v)));
            triplets.extend((0..n).map(|i| (i, i, shift)));
            Delassus::Sparse(CsrMatrix::from_triplets(n, n, &triplets)?)
        }
    })
}

/// Runs the proximal point method from the reaction in `r`.
pub(crate) fn prox(
    problem: &FrictionProblem<'_>,
    options: &ProxOptions,
    r: &mut [f64],
    u: &mut [f64],
    observer: &mut dyn FnMut(&IterationEvent<'_>),
) -> Result<SolverOutcome, Fc3dError> {
    validate(options)?;
    let mut newton = match &options.internal {
        ProxInternal::NsnAc(n) => Some(NewtonSolver::new(problem, n)?),
        ProxInternal::Nsgs(_) => None,
    };
    let deadline = options.time_budget.map(|b| Instant::now() + b);
    let n = problem.size();
    let mut shifted_q = vec![0.0; n];
    let mut best_r = r.to_vec();
    let mut error = natural_map_error(problem, r, u);
    let mut best_error = error;
    if error <= options.tolerance {
        return Ok(SolverOutcome {
            iterations: 0,
            out_of_time: false,
            final_error: Some(error),
        });
    }
    let mut iterations = 0;
    let mut out_of_time = false;
    for iteration in 1..=options.max_iter {
        iterations = iteration;
        let shift = (options.sigma * error.powf(options.nu)).min(options.alpha);
        for ((sq, q), ri) in shifted_q.iter_mut().zip(problem.q()).zip(r.iter()) {
            *sq = q - shift * ri;
        }
        let internal_tol = error / 10.0;
        match &options.internal {
            ProxInternal::NsnAc(n) => {
                let solver = newton.as_mut().expect("built for NSN-AC");
                solver.run(
                    &shifted_q,
                    problem.mu(),
                    shift,
                    internal_tol,
                    n.max_iter,
                    deadline,
                    r,
                    u,
                    &mut |_| {},
                );
            }
            ProxInternal::Nsgs(g) => {
                let inner = FrictionProblem::new(
                    shifted(problem.w(), shift)?,
                    shifted_q.clone(),
                    problem.mu().to_vec(),
                )?;
                let mut o = *g;
                o.tolerance = internal_tol;
                o.time_budget = deadline.map(|d| d.saturating_duration_since(Instant::now()));
                if o.time_budget.is_some_and(|b| b.is_zero()) {
                    o.time_budget = Some(std::time::Duration::from_nanos(1));
                }
                crate::nsgs::nsgs(&inner, &o, r, u, &mut |_| {})?;
            }
        }
        error = natural_map_error(problem, r, u);
        if error < best_error {
            best_error = error;
            best_r.copy_from_slice(r);
        }
        observer(&IterationEvent {
            iteration,
            reaction: r,
            error,
        });
        if error <= options.tolerance {
            return Ok(SolverOutcome {
                iterations,
                out_of_time: false,
                final_error: Some(error),
            });
        }
        if !error.is_finite() {
            break;
        }
        if deadline.is_some_and(|d| Instant::now() >= d) {
            out_of_time = true;
            break;
        }
    }
    if best_error < error || !error.is_finite() {
        r.copy_from_slice(&best_r);
    }
    Ok(SolverOutcome {
        iterations,
        out_of_time,
        final_error: None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shifted_keeps_the_storage_and_adds_to_the_diagonal() {
        let d = DenseMatrix::new(3, 3, vec![1.0, 2.0, 0.0, 0.0, 3.0, 0.0, 0.5, 0.0, 4.0]).unwrap();
        let w = Delassus::Dense(d);
        let csr = Delassus::Sparse(w.to_csr());
        let sbm = Delassus::SparseBlock(w.to_block_sparse().unwrap());
        for m in [&w, &csr, &sbm] {
            let s = shifted(m, 0.25).unwrap();
            assert_eq!(s.storage_name(), m.storage_name());
            for i in 0..3 {
                for j in 0..3 {
                    let extra = if i == j { 0.25 } else { 0.0 };
                    assert_eq!(s.get(i, j), w.get(i, j) + extra);
                }
            }
        }
    }
}

//! FP-VI-UPK of Table 3 (fixed-point projection (95) with the self-adaptive rule (98),
//! Algorithm 3: `L = 0.9`, `L_min = 0.3`, `nu = 2/3`) on one contact.
//!
//! The iteration is exactly the one of 553 (ProjectionOnConeWithLocalIteration), whose code it
//! shares; the difference is the starting rho, taken from the rho rule (by default (110),
//! `1 / lambda_max(W_cc)`, the paper's default for the natural map) instead of `1 / W_NN`.

use super::{
    local_rho, LocalOutcome, LocalProblem, LocalSolver, ProjectionOnConeWithLocalIteration,
};
use crate::local::{AlgorithmVariant, LocalSolverOptions, RhoRule};
use crate::math::linalg::{Mat3, Vec3};

pub struct FpViUpk {
    rule: RhoRule,
    iteration: ProjectionOnConeWithLocalIteration,
}

impl FpViUpk {
    pub fn new(options: &LocalSolverOptions) -> Self {
        FpViUpk {
            rule: options.rho_rule,
            // 570 is fc3d's: its iteration starts from the rule's rho at every solve.
            iteration: ProjectionOnConeWithLocalIteration::new(&LocalSolverOptions {
                variant: AlgorithmVariant::Fc3d,
                ..*options
            }),
        }
    }
}

impl LocalSolver for FpViUpk {
    fn rho(&self, w: &Mat3) -> (f64, f64) {
        // The cone projection takes one scalar rho: the smaller of the two is the safe one.
        let (rn, rt) = local_rho(w, self.rule);
        let rho = rn.min(rt);
        (rho, rho)
    }

    #[inline]
    fn solve_with_rho(
        &mut self,
        p: &LocalProblem<'_>,
        rho: (f64, f64),
        r: &mut Vec3,
    ) -> LocalOutcome {
        self.iteration.solve_with_rho(p, rho, r)
    }

    fn set_deadline(&mut self, deadline: Option<std::time::Instant>) {
        self.iteration.set_deadline(deadline);
    }
}

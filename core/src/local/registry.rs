//! The one table of the one-contact solvers: each row gives a solver's kind, Siconos id and name,
//! the names `fc3d bench` accepts, its default tolerance, iteration limit and rho rule, and the
//! type that implements it. The macro turns the table into [`LocalSolverKind`] (ids, names,
//! defaults) and [`AnyLocalSolver`] (static dispatch in the sweep). Adding a local solver: a
//! module with a type implementing [`LocalSolver`] (constructed by `new(&LocalSolverOptions)`),
//! its `mod` line in `local/mod.rs`, and a row here.

use super::settings::{LocalSolverOptions, RhoRule};
use super::{
    AlartCurnierNewton, EnhancedBipotential, FischerBurmeisterNewton, FpViUpk, LocalOutcome,
    LocalProblem, LocalSolver, ProjectionOnCone, ProjectionOnConeVelocity,
    ProjectionOnConeWithDiagonalization, ProjectionOnConeWithLocalIteration,
    ProjectionOnConeWithRegularization, ProjectionOnCylinder,
    ProjectionOnCylinderWithLocalIteration, Quartic,
};
use crate::math::linalg::{Mat3, Vec3};

macro_rules! local_solvers {
    ($(
        $(#[$doc:meta])*
        $kind:ident = $id:literal, $siconos_name:literal, [$($alias:literal),+],
            ($tolerance:expr, $max_iter:expr, $rho:expr), $solver:ty;
    )+) => {
        /// The one-contact solvers NSGS can use. Siconos ids in brackets; fc3d's own ids are in
        /// 568..=599, a range Siconos 4.4 leaves free (its one-contact solvers use 550..=567).
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub enum LocalSolverKind {
            $( $(#[$doc])* $kind, )+
        }

        impl LocalSolverKind {
            /// Every local solver, in the table's order.
            pub const ALL: [LocalSolverKind; [$(stringify!($kind)),+].len()] =
                [$(LocalSolverKind::$kind),+];

            /// Siconos id of this local solver.
            pub fn siconos_id(self) -> i32 {
                match self { $(LocalSolverKind::$kind => $id,)+ }
            }

            /// The local solver with Siconos id `id`, if implemented.
            pub fn from_siconos_id(id: i32) -> Option<Self> {
                match id { $($id => Some(LocalSolverKind::$kind),)+ _ => None }
            }

            /// Siconos' name of the id (`solver_options_id_to_name`).
            pub fn siconos_name(self) -> &'static str {
                match self { $(LocalSolverKind::$kind => $siconos_name,)+ }
            }

            /// Names `fc3d bench` accepts; the first is the short name used in legends.
            pub fn names(self) -> &'static [&'static str] {
                match self { $(LocalSolverKind::$kind => &[$($alias),+],)+ }
            }

            /// Default (tolerance, iteration limit, rho rule) of the solver.
            pub(crate) fn default_tolerance_iterations_rho(self) -> (f64, usize, RhoRule) {
                match self { $(LocalSolverKind::$kind => ($tolerance, $max_iter, $rho),)+ }
            }
        }

        /// Any of the local solvers, chosen at run time (static dispatch in the sweep).
        #[allow(clippy::large_enum_variant)]
        pub enum AnyLocalSolver {
            $( $kind($solver), )+
        }

        impl AnyLocalSolver {
            pub fn new(options: &LocalSolverOptions) -> Self {
                match options.kind {
                    $(LocalSolverKind::$kind => AnyLocalSolver::$kind(<$solver>::new(options)),)+
                }
            }
        }

        impl LocalSolver for AnyLocalSolver {
            fn rho(&self, w: &Mat3) -> (f64, f64) {
                match self { $(AnyLocalSolver::$kind(s) => s.rho(w),)+ }
            }

            fn set_deadline(&mut self, deadline: Option<std::time::Instant>) {
                match self { $(AnyLocalSolver::$kind(s) => s.set_deadline(deadline),)+ }
            }

            #[inline]
            fn solve_with_rho(
                &mut self,
                p: &LocalProblem<'_>,
                rho: (f64, f64),
                r: &mut Vec3,
            ) -> LocalOutcome {
                match self { $(AnyLocalSolver::$kind(s) => s.solve_with_rho(p, rho, r),)+ }
            }

            #[inline(always)]
            fn solve_in_sweep(
                &mut self,
                p: &LocalProblem<'_>,
                rho: (f64, f64),
                memory: &mut f64,
                r: &mut Vec3,
            ) -> LocalOutcome {
                match self { $(AnyLocalSolver::$kind(s) => s.solve_in_sweep(p, rho, memory, r),)+ }
            }
        }
    };
}

local_solvers! {
    /// Alart-Curnier nonsmooth Newton, full steps [550 ONECONTACT_NSN].
    NewtonAlartCurnier = 550, "FC3D_ONECONTACT_NSN", ["NSN", "NSN-AC"],
        (1e-14, 10, RhoRule::SplitSpectralNormCond), AlartCurnierNewton;
    /// Alart-Curnier Newton with Goldstein-Price line search [551 ONECONTACT_NSN_GP].
    NewtonAlartCurnierGp = 551, "FC3D_ONECONTACT_NSN_GP", ["NSN-GP", "NSN-AC-GP"],
        (1e-14, 10, RhoRule::SplitSpectralNorm), AlartCurnierNewton;
    /// Newton-GP, falling back to projection with local iterations and Newton again
    /// when Newton does not converge [565 ONECONTACT_NSN_GP_HYBRID, Siconos' default].
    NewtonHybrid = 565, "FC3D_ONECONTACT_NSN_GP_HYBRID", ["HYBRID", "NSN-GP-HYBRID"],
        (1e-14, 10, RhoRule::SplitSpectralNorm), AlartCurnierNewton;
    /// One projection step on the Coulomb cone along the De Saxcé direction: the "FP-DS-One"
    /// local solver of Acary-Brémond-Huber and Dumont's SBP [552 ProjectionOnCone].
    ProjectionOnCone = 552, "FC3D_ProjectionOnCone", ["PROJ", "SBP", "FP-DS-ONE"],
        (1e-14, 1000, RhoRule::SplitSpectralNorm), ProjectionOnCone;
    /// Projection steps on the cone with a self-adaptive rho until the local residual is below
    /// the local tolerance [553 ProjectionOnConeWithLocalIteration].
    ProjectionOnConeWithLocalIteration = 553, "FC3D_ProjectionOnConeWithLocalIteration",
        ["PROJ-ITER"], (1e-14, 1000, RhoRule::SplitSpectralNorm),
        ProjectionOnConeWithLocalIteration;
    /// One augmented-Lagrangian projection on the cylinder `R+ x B(0, mu r_N)` with the radius
    /// taken from the new normal reaction: Dumont's SAL [557 ProjectionOnCylinder].
    ProjectionOnCylinder = 557, "FC3D_projectionOnCylinder", ["CYL", "SAL"],
        (1e-14, 1000, RhoRule::SplitSpectralNorm), ProjectionOnCylinder;
    /// One projection step on the cone for the proximally regularized contact
    /// (`w + eps I`, `q - eps r`): a step `rho = 1 / (W_NN + eps)` along the De Saxcé direction;
    /// with Siconos' default `eps = 0` it is the step of 552
    /// [554 ProjectionOnConeWithRegularization].
    ProjectionOnConeWithRegularization = 554, "FC3D_projectionOnConeWithRegularization",
        ["PROJ-REG"], (1e-14, 1000, RhoRule::SplitSpectralNorm),
        ProjectionOnConeWithRegularization;
    /// One separated step with the diagonal of `w` as metric:
    /// `r_N <- (r_N - u_N / W_NN)_+`, `r_T <- P_{B(0, mu r_N)}(r_T - u_T ./ diag(W_TT))`
    /// [555 ProjectionOnConeWithDiagonalization]; checked against Siconos on one step. Its
    /// tangential fixed point is the Coulomb law only when `W_T1T1 = W_T2T2`.
    ProjectionOnConeWithDiagonalization = 555, "FC3D_ProjectionOnConeWithDiagonalization",
        ["PROJ-DIAG"], (1e-14, 1000, RhoRule::SplitSpectralNorm),
        ProjectionOnConeWithDiagonalization;
    /// The step of 552 computed in velocity space through Moreau's decomposition,
    /// `r <- r - rho ũ + P_{K*}(rho ũ - r)` [558 ProjectionOnCone_velocity].
    ProjectionOnConeVelocity = 558, "FC3D_ProjectionOnCone_velocity", ["PROJ-VEL"],
        (1e-14, 1000, RhoRule::SplitSpectralNorm), ProjectionOnConeVelocity;
    /// Newton on the Fischer-Burmeister function of the second-order cone (Jordan algebra) in
    /// the variables `(mu r_N, r_T)`, `(ũ_N, mu ũ_T)`, with an Armijo line search
    /// [561 NCPGlockerFBNewton].
    FischerBurmeisterNewton = 561, "FC3D_NCPGlockerFBNewton", ["FB", "NSN-FB"],
        (1e-12, 1000, RhoRule::SplitSpectralNorm), FischerBurmeisterNewton;
    /// The exact solution by enumeration of take-off, stick and slide; the slide direction is a
    /// root of a quartic (Bonnefon-Daviet) [562 QUARTIC].
    Quartic = 562, "FC3D_QUARTIC", ["QUARTIC"],
        (1e-12, 1000, RhoRule::SplitSpectralNorm), Quartic;
    /// The same exact solution by enumeration [563 QUARTIC_NU]. Siconos 4.4 parametrizes the
    /// slide by the multiplier nu of the tangential block instead of the slide angle; both
    /// solve the same equations, and fc3d computes them with the slide-angle quartic of 562.
    QuarticNu = 563, "FC3D_QUARTIC_NU", ["QUARTIC-NU"],
        (1e-12, 1000, RhoRule::SplitSpectralNorm), Quartic;
    /// Augmented-Lagrangian steps on the cylinder (557) with a self-adaptive rho until the local
    /// residual is below the local tolerance [564 ProjectionOnCylinderWithLocalIteration].
    ProjectionOnCylinderWithLocalIteration = 564, "FC3D_projectionOnCylinderWithLocalIteration",
        ["CYL-ITER"], (1e-14, 1000, RhoRule::SplitSpectralNorm),
        ProjectionOnCylinderWithLocalIteration;
    /// FP-VI-UPK of Table 3 applied to one contact: projection steps (95) with the
    /// self-adaptive rule (98), started from rho of the rho rule (default (110)); the algorithm of
    /// 553 with another initial rho [fc3d 570].
    FpViUpk = 570, "FC3D_ONECONTACT_FP_VI_UPK", ["FP-VI-UPK"],
        (1e-14, 1000, RhoRule::SpectralNorm), FpViUpk;
    /// Dumont's EBP: Newton on the bipotential fixed point `r = P_K(r - rho ũ)` with the
    /// condensed 3x3 system (32) [fc3d 571]. Dumont uses up to 100 Newton iterations with a loose
    /// 1e-5; a tight local tolerance lets NSGS reach 1e-8 and Newton rarely needs more than a
    /// few iterations.
    EnhancedBipotential = 571, "FC3D_ONECONTACT_EBP", ["EBP"],
        (1e-14, 20, RhoRule::Dumont(1.0)), EnhancedBipotential;
    /// Dumont's EAL: Newton on the augmented-Lagrangian fixed point (36). Its function is the
    /// Alart-Curnier function (60) with `rho_N = rho_T`, so this is 550 (plain Newton) with
    /// Dumont's rho rule by default [fc3d 572].
    EnhancedAugmentedLagrangian = 572, "FC3D_ONECONTACT_EAL", ["EAL"],
        (1e-14, 20, RhoRule::Dumont(1.0)), AlartCurnierNewton;
}

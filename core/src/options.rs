//! Typed solver options with Siconos' defaults. Integer/real parameter arrays exist only at the C
//! boundary (`capi::options`), which converts them to these types and back.

/// Local (one-contact) solvers usable inside NSGS. Siconos ids in brackets.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum LocalSolverKind {
    /// Alart-Curnier nonsmooth Newton, full steps [550 ONECONTACT_NSN].
    NewtonAlartCurnier,
    /// Alart-Curnier Newton with Goldstein-Price line search [551 ONECONTACT_NSN_GP].
    NewtonAlartCurnierGp,
    /// Newton-GP, falling back to projection with local iterations and Newton again
    /// when Newton does not converge [565 ONECONTACT_NSN_GP_HYBRID, Siconos' default].
    NewtonHybrid,
    /// One projection step on the Coulomb cone along the De Saxcé direction: the "FP-DS-One"
    /// local solver of Acary-Brémond-Huber and Dumont's SBP [552 ProjectionOnCone].
    ProjectionOnCone,
    /// Projection steps on the cone with a self-adaptive rho until the local residual is below
    /// the local tolerance [553 ProjectionOnConeWithLocalIteration].
    ProjectionOnConeWithLocalIteration,
    /// One augmented-Lagrangian projection on the cylinder `R+ x B(0, mu r_N)` with the radius
    /// taken from the new normal reaction: Dumont's SAL [557 ProjectionOnCylinder].
    ProjectionOnCylinder,
    /// One projection step on the cone for the proximally regularized contact
    /// (`w + eps I`, `q - eps r`): a step `rho = 1 / (W_NN + eps)` along the De Saxcé direction;
    /// with Siconos' default `eps = 0` it is the step of 552
    /// [554 ProjectionOnConeWithRegularization].
    ProjectionOnConeWithRegularization,
    /// One separated step with the diagonal of `w` as metric:
    /// `r_N <- (r_N - u_N / W_NN)_+`, `r_T <- P_{B(0, mu r_N)}(r_T - u_T ./ diag(W_TT))`
    /// [555 ProjectionOnConeWithDiagonalization]; checked against Siconos on one step. Its
    /// tangential fixed point is the Coulomb law only when `W_T1T1 = W_T2T2`.
    ProjectionOnConeWithDiagonalization,
    /// The step of 552 computed in velocity space through Moreau's decomposition,
    /// `r <- r - rho ũ + P_{K*}(rho ũ - r)` [558 ProjectionOnCone_velocity].
    ProjectionOnConeVelocity,
    /// Newton on the Fischer-Burmeister function of the second-order cone (Jordan algebra) in
    /// the variables `(mu r_N, r_T)`, `(ũ_N, mu ũ_T)`, with an Armijo line search
    /// [561 NCPGlockerFBNewton].
    FischerBurmeisterNewton,
    /// The exact solution by enumeration of take-off, stick and slide; the slide direction is a
    /// root of a quartic (Bonnefon-Daviet) [562 QUARTIC].
    Quartic,
    /// Augmented-Lagrangian steps on the cylinder (557) with a self-adaptive rho until the local
    /// residual is below the local tolerance [564 ProjectionOnCylinderWithLocalIteration].
    ProjectionOnCylinderWithLocalIteration,
    /// FP-VI-UPK of Table 3 applied to one contact: projection steps (95) with the
    /// self-adaptive rule (98), started from rho of the rho rule (default (110)); the algorithm of
    /// 553 with another initial rho [fc3d 570].
    FpViUpk,
    /// Dumont's EBP: Newton on the bipotential fixed point `r = P_K(r - rho ũ)` with the
    /// condensed 3x3 system (32) [fc3d 571].
    EnhancedBipotential,
    /// Dumont's EAL: Newton on the augmented-Lagrangian fixed point (36). Its function is the
    /// Alart-Curnier function (60) with `rho_N = rho_T`, so this is 550 (plain Newton) with
    /// Dumont's rho rule by default [fc3d 572].
    EnhancedAugmentedLagrangian,
}

impl LocalSolverKind {
    /// Siconos id of this local solver.
    pub fn siconos_id(self) -> i32 {
        match self {
            LocalSolverKind::NewtonAlartCurnier => 550,
            LocalSolverKind::NewtonAlartCurnierGp => 551,
            LocalSolverKind::NewtonHybrid => 565,
            LocalSolverKind::ProjectionOnCone => 552,
            LocalSolverKind::ProjectionOnConeWithLocalIteration => 553,
            LocalSolverKind::ProjectionOnCylinder => 557,
            LocalSolverKind::ProjectionOnConeWithRegularization => 554,
            LocalSolverKind::ProjectionOnConeWithDiagonalization => 555,
            LocalSolverKind::ProjectionOnConeVelocity => 558,
            LocalSolverKind::FischerBurmeisterNewton => 561,
            LocalSolverKind::Quartic => 562,
            LocalSolverKind::ProjectionOnCylinderWithLocalIteration => 564,
            LocalSolverKind::FpViUpk => FC3D_ONECONTACT_FP_VI_UPK,
            LocalSolverKind::EnhancedBipotential => FC3D_ONECONTACT_EBP,
            LocalSolverKind::EnhancedAugmentedLagrangian => FC3D_ONECONTACT_EAL,
        }
    }

    /// The local solver with Siconos id `id`, if implemented.
    pub fn from_siconos_id(id: i32) -> Option<Self> {
        Some(match id {
            550 => LocalSolverKind::NewtonAlartCurnier,
            551 => LocalSolverKind::NewtonAlartCurnierGp,
            565 => LocalSolverKind::NewtonHybrid,
            552 => LocalSolverKind::ProjectionOnCone,
            553 => LocalSolverKind::ProjectionOnConeWithLocalIteration,
            557 => LocalSolverKind::ProjectionOnCylinder,
            554 => LocalSolverKind::ProjectionOnConeWithRegularization,
            555 => LocalSolverKind::ProjectionOnConeWithDiagonalization,
            558 => LocalSolverKind::ProjectionOnConeVelocity,
            561 => LocalSolverKind::FischerBurmeisterNewton,
            562 => LocalSolverKind::Quartic,
            564 => LocalSolverKind::ProjectionOnCylinderWithLocalIteration,
            FC3D_ONECONTACT_FP_VI_UPK => LocalSolverKind::FpViUpk,
            FC3D_ONECONTACT_EBP => LocalSolverKind::EnhancedBipotential,
            FC3D_ONECONTACT_EAL => LocalSolverKind::EnhancedAugmentedLagrangian,
            _ => return None,
        })
    }

    pub const ALL: [LocalSolverKind; 15] = [
        LocalSolverKind::NewtonAlartCurnier,
        LocalSolverKind::NewtonAlartCurnierGp,
        LocalSolverKind::NewtonHybrid,
        LocalSolverKind::ProjectionOnCone,
        LocalSolverKind::ProjectionOnConeWithLocalIteration,
        LocalSolverKind::ProjectionOnCylinder,
        LocalSolverKind::ProjectionOnConeWithRegularization,
        LocalSolverKind::ProjectionOnConeWithDiagonalization,
        LocalSolverKind::ProjectionOnConeVelocity,
        LocalSolverKind::FischerBurmeisterNewton,
        LocalSolverKind::Quartic,
        LocalSolverKind::ProjectionOnCylinderWithLocalIteration,
        LocalSolverKind::FpViUpk,
        LocalSolverKind::EnhancedBipotential,
        LocalSolverKind::EnhancedAugmentedLagrangian,
    ];
}

/// fc3d's one-contact solver ids are in 568..=599, a range Siconos 4.4 leaves free (its
/// one-contact solvers use 550..=567). FP-VI-UPK of Acary-Brémond-Huber's Table 3 on one contact:
/// projection steps with the self-adaptive rho rule (98), started from rho strategy iparam[9]
/// (default 1, spectral norm). Use it as NSGS's internal solver.
pub const FC3D_ONECONTACT_FP_VI_UPK: i32 = 570;
/// Dumont's EBP (2021): Newton on the bipotential fixed point `r = P_K(r - rho ũ)` with the
/// condensed 3x3 system (32); rho by iparam[9] (default `FC3D_RHO_STRATEGY_DUMONT`, alpha =
/// dparam[3] = 1). Use it as NSGS's internal solver.
pub const FC3D_ONECONTACT_EBP: i32 = 571;
/// Dumont's EAL (2021): Newton on the augmented-Lagrangian fixed point; the same function as
/// the Alart-Curnier Newton 550, with Dumont's rho (`FC3D_RHO_STRATEGY_DUMONT`) by default.
pub const FC3D_ONECONTACT_EAL: i32 = 572;

/// The nonsmooth function a local Newton solver (550, 551, 565) zeroes (Siconos iparam[10]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum NewtonFormulation {
    /// Alart-Curnier (61): disk radius `mu (r_N - rho_N u_N)_+` (Siconos' default, 0).
    #[default]
    AlartCurnier,
    /// Jean-Moreau (59), "NSN-JM" of Table 3: disk radius `mu (r_N)_+` (Siconos 1).
    JeanMoreau,
}

/// How the penalty parameters rho (rho_N, rho_T) of a local solver are taken from the diagonal
/// block `W_cc` of the contact (section 5.4 of Acary-Brémond-Huber).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RhoRule {
    /// A fixed value for both.
    Constant(f64),
    /// (110): `rho_N = rho_T = 1 / lambda_max(W_cc)`.
    SpectralNorm,
    /// (111): `rho_N = 1 / W_NN`, `rho_T = 1 / lambda_max(W_TT)`.
    SplitSpectralNorm,
    /// (112), corrected: `rho_N = 1 / W_NN`, `rho_T = lambda_min(W_TT) / lambda_max(W_TT)^2`
    /// (the paper prints `lambda_min(W_NN)`, a scalar, which cannot measure the conditioning of W_TT).
    SplitSpectralNormCond,
    /// Dumont's rule: `rho_N = rho_T = alpha * rho_bar` with `rho_bar = 1 / W_NN`, the reduced
    /// mass `m_i m_j / (m_i + m_j)` of the two bodies at the contact when `W = H^T M^-1 H` (Dumont
    /// writes `rho_bar = m_i m_j / (m_i + m_j) / dt` for forces; impulses drop the `dt`).
    /// Dumont finds alpha in [1, 2] best for EBP.
    Dumont(f64),
}

/// Options of a local solver. Defaults per kind are Siconos 4.4's (`solver_options_create(id)`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LocalSolverOptions {
    pub kind: LocalSolverKind,
    /// Local tolerance on the local residual, relative to the local scale.
    pub tolerance: f64,
    /// Maximum local iterations.
    pub max_iter: usize,
    /// Rule for rho (Newton solvers; projection solvers use `1 / W_NN`).
    pub rho_rule: RhoRule,
    /// Maximum trial steps of the Goldstein-Price line search.
    pub line_search_max_iter: usize,
    /// Hybrid solver: number of (projection, Newton) rounds after the first Newton.
    pub hybrid_max_loop: usize,
    /// Hybrid solver: maximum projection iterations per round.
    pub hybrid_max_iter: usize,
    /// Newton solvers 550/551/565: which function Newton zeroes (default Alart-Curnier).
    pub formulation: NewtonFormulation,
    /// 554: the proximal regularization `eps` added to W_NN in the step (default 0, Siconos'
    /// dparam[3]).
    pub regularization: f64,
}

impl LocalSolverOptions {
    /// Siconos' defaults for the given local solver.
    pub fn new(kind: LocalSolverKind) -> Self {
        use LocalSolverKind::*;
        let (tolerance, max_iter, rho_rule) = match kind {
            NewtonAlartCurnier => (1e-14, 10, RhoRule::SplitSpectralNormCond),
            NewtonAlartCurnierGp | NewtonHybrid => (1e-14, 10, RhoRule::SplitSpectralNorm),
            ProjectionOnCone
            | ProjectionOnConeWithLocalIteration
            | ProjectionOnCylinder
            | ProjectionOnConeWithRegularization
            | ProjectionOnConeWithDiagonalization
            | ProjectionOnConeVelocity
            | ProjectionOnCylinderWithLocalIteration => (1e-14, 1000, RhoRule::SplitSpectralNorm),
            FischerBurmeisterNewton | Quartic => (1e-12, 1000, RhoRule::SplitSpectralNorm),
            FpViUpk => (1e-14, 1000, RhoRule::SpectralNorm),
            // Dumont uses up to 100 Newton iterations with a loose 1e-5; a tight local tolerance
            // lets NSGS reach 1e-8 and Newton rarely needs more than a few iterations.
            EnhancedBipotential | EnhancedAugmentedLagrangian => (1e-14, 20, RhoRule::Dumont(1.0)),
        };
        LocalSolverOptions {
            kind,
            tolerance,
            max_iter,
            rho_rule,
            line_search_max_iter: 10,
            hybrid_max_loop: 1,
            hybrid_max_iter: 100,
            formulation: NewtonFormulation::AlartCurnier,
            regularization: 0.0,
        }
    }
}

impl Default for LocalSolverOptions {
    fn default() -> Self {
        LocalSolverOptions::new(LocalSolverKind::NewtonHybrid)
    }
}

/// When NSGS evaluates the error it tests for convergence (Siconos iparam[7]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ErrorEvaluation {
    /// The full natural-map error after every sweep (one extra W r product per sweep).
    Full,
    /// Only the cheap increment error (134); the returned error is still the full one.
    Light,
    /// Cheap error each sweep; when it passes, confirm with the full error and tighten the cheap
    /// tolerance if the full one does not pass (Siconos' default).
    LightWithFullFinal,
    /// Dumont's global criterion (37): the mean over contacts of the motion error (how far the
    /// velocity a contact was solved with is from `W r + q` after the sweep), the distance of
    /// `r_c` to its cone, the bi-potential `|u·r + mu r_N ||u_T|||` and the penetration
    /// `max(0, -u_N)`. It is absolute (in the units of `r·u`), so its tolerance is the solver's
    /// tolerance taken in those units. The reported error stays the natural-map error; the
    /// criterion is reported beside it ([`SolveReport::dumont_criterion`](crate::SolveReport)).
    DumontCriterion,
}

/// How the local solver's tolerance is set during NSGS (Siconos iparam[2], ratio in dparam[2]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LocalTolerance {
    /// The local solver's own tolerance, fixed (Siconos' default, "given value").
    Given,
    /// After each measured sweep: `max(error / ratio, tolerance / n_contacts)` ("adaptive").
    Adaptive { ratio: f64 },
    /// After each measured sweep: `error / (ratio * n_contacts)` ("adaptive per contact").
    AdaptivePerContact { ratio: f64 },
}

/// Order in which a sweep visits the contacts (Siconos iparam[5], seed iparam[6]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ContactOrder {
    /// Contacts in index order (default).
    Natural,
    /// One random permutation drawn from `seed` before the first sweep.
    ShuffledOnce { seed: u64 },
    /// A new random permutation before every sweep, drawn from a generator seeded with `seed`.
    ShuffledEachSweep { seed: u64 },
}

/// Options of the nonsmooth Gauss-Seidel solver (NSGS, Siconos id 500).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NsgsOptions {
    /// Maximum number of sweeps (default 1000).
    pub max_iter: usize,
    /// Tolerance on the natural-map error (default 1e-4).
    pub tolerance: f64,
    /// Error evaluation strategy (default [`ErrorEvaluation::LightWithFullFinal`]).
    pub error_evaluation: ErrorEvaluation,
    /// The stopping test runs every `evaluation_frequency` sweeps (default 1; Siconos iparam[8],
    /// where 0 also means every sweep). The last allowed sweep is always tested.
    pub evaluation_frequency: usize,
    /// The one-contact solver and its options (default [`LocalSolverKind::NewtonHybrid`]).
    pub local: LocalSolverOptions,
    /// How the local tolerance evolves (default [`LocalTolerance::Given`]).
    pub local_tolerance: LocalTolerance,
    /// Over-relaxation (PSOR): each contact takes `omega r_new + (1 - omega) r_old`, projected on
    /// its cone when `omega > 1` would leave it. `None` (default) is plain Gauss-Seidel. `omega`
    /// must lie in (0, 2).
    pub relaxation: Option<f64>,
    /// Contact visiting order (default [`ContactOrder::Natural`]).
    pub order: ContactOrder,
    /// Freezing: a contact whose reaction moved by less than `tolerance * ||r_c||` in a sweep is
    /// skipped for this many following sweeps (default `None`: never frozen). Convergence is
    /// always confirmed on all contacts.
    pub freezing: Option<usize>,
    /// Wall-clock budget (default none). When it is spent, NSGS stops after the current sweep
    /// and returns the best iterate it measured, with
    /// [`SolveStatus::TimeBudgetExhausted`](crate::SolveStatus::TimeBudgetExhausted).
    pub time_budget: Option<std::time::Duration>,
}

impl Default for NsgsOptions {
    fn default() -> Self {
        NsgsOptions {
            max_iter: 1000,
            tolerance: 1e-4,
            error_evaluation: ErrorEvaluation::LightWithFullFinal,
            evaluation_frequency: 1,
            local: LocalSolverOptions::default(),
            local_tolerance: LocalTolerance::Given,
            relaxation: None,
            order: ContactOrder::Natural,
            freezing: None,
            time_budget: None,
        }
    }
}

impl NsgsOptions {
    /// Default options with another local solver.
    pub fn with_local(kind: LocalSolverKind) -> Self {
        NsgsOptions {
            local: LocalSolverOptions::new(kind),
            ..Default::default()
        }
    }
}

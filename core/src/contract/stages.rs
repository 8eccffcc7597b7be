//! The stages a composite solver (AUTO) took: which method ran, how many iterations it did, the
//! error it left and why it handed over. Fixed size and `Copy`, so that a [`SolveReport`]
//! (crate::SolveReport) stays a plain value.

/// The method of one stage.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StageKind {
    /// Gauss-Seidel sweeps (NSGS with the local solver 551, Newton with Goldstein-Price).
    Nsgs,
    /// Alart-Curnier nonsmooth Newton with Goldstein-Price line search (NSN-AC, 504).
    Newton,
    /// The proximal point method around NSN-AC (PROX, 502): the fallback for a singular W.
    Prox,
    /// ADMM on the local formulation (523): fast to loose tolerances on strongly coupled
    /// problems.
    Admm,
    /// Tresca fixed point with Gauss-Seidel sub-problems (TFP, 503): the fastest to every
    /// tolerance on most small and weakly coupled shared problems.
    Tresca,
    /// Siconos' extragradient with a self-adaptive step (EG, 512): the fastest to 1e-4 on the
    /// large strongly coupled shared problems.
    ExtraGradient,
    /// Tresca fixed point with APGD sub-problems (TFP-APGD, 503): its first step from r = 0 is
    /// a frictionless solve, a fraction of a millisecond on the small shared problems, which
    /// is nearly the solution on some (LMGC_100_PR_PerioBox).
    TrescaApgd,
}

impl StageKind {
    /// Every kind, in the order of their codes.
    pub const ALL: [StageKind; 7] = [
        StageKind::Nsgs,
        StageKind::Newton,
        StageKind::Prox,
        StageKind::Admm,
        StageKind::Tresca,
        StageKind::ExtraGradient,
        StageKind::TrescaApgd,
    ];

    /// The digit of this kind in the C output (`FC3D_IPARAM_AUTO_STAGES`): 1 to 7.
    pub fn code(self) -> u8 {
        match self {
            StageKind::Nsgs => 1,
            StageKind::Newton => 2,
            StageKind::Prox => 3,
            StageKind::Admm => 4,
            StageKind::Tresca => 5,
            StageKind::ExtraGradient => 6,
            StageKind::TrescaApgd => 7,
        }
    }

    /// The kind of a code (the inverse of [`StageKind::code`]).
    pub fn from_code(code: u8) -> Option<StageKind> {
        StageKind::ALL.into_iter().find(|k| k.code() == code)
    }

    /// Short name for prints and tables.
    pub fn name(self) -> &'static str {
        match self {
            StageKind::Nsgs => "NSGS",
            StageKind::Newton => "NSN-AC",
            StageKind::Prox => "PROX",
            StageKind::Admm => "ADMM",
            StageKind::Tresca => "TFP",
            StageKind::ExtraGradient => "EG",
            StageKind::TrescaApgd => "TFP-APGD",
        }
    }
}

/// Why a stage ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StageEnd {
    /// The error reached the tolerance.
    Converged,
    /// The error stopped decreasing fast enough: the next stage takes over.
    Stalled,
    /// The stage used the iterations its rule gave it.
    Allowance,
    /// The solve's iteration limit or time budget ran out.
    Limits,
    /// The stage could not start (e.g. a Newton matrix that cannot be built).
    Failed,
}

impl StageEnd {
    pub fn name(self) -> &'static str {
        match self {
            StageEnd::Converged => "converged",
            StageEnd::Stalled => "stalled",
            StageEnd::Allowance => "allowance used",
            StageEnd::Limits => "limits reached",
            StageEnd::Failed => "could not start",
        }
    }
}

/// One stage taken.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stage {
    pub kind: StageKind,
    /// Iterations the stage did (sweeps, Newton steps, proximal steps).
    pub iterations: usize,
    /// Natural-map error of the iterate the stage handed over.
    pub error: f64,
    pub end: StageEnd,
}

/// At most this many stages are recorded (the C output packs one decimal digit per stage in an
/// `int`).
pub const MAX_STAGES: usize = 9;

/// The stages taken, in order, and the rule of the table that chose the first plan.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StageLog {
    stages: [Option<Stage>; MAX_STAGES],
    len: usize,
    /// Index of the rule that chose the plan in AUTO's rule table.
    pub rule: usize,
}

impl StageLog {
    pub fn new(rule: usize) -> Self {
        StageLog {
            stages: [None; MAX_STAGES],
            len: 0,
            rule,
        }
    }

    /// Records a stage; returns false (and records nothing) when the log is full.
    pub fn push(&mut self, stage: Stage) -> bool {
        if self.len == MAX_STAGES {
            return false;
        }
        self.stages[self.len] = Some(stage);
        self.len += 1;
        true
    }

    pub fn len(&self) -> usize {
        self.len
    }

    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    pub fn is_full(&self) -> bool {
        self.len == MAX_STAGES
    }

    /// The stages, in the order they ran.
    pub fn stages(&self) -> impl Iterator<Item = &Stage> + '_ {
        self.stages[..self.len].iter().flatten()
    }

    /// The kinds as a string, e.g. `NSGS>NSN-AC>PROX`.
    pub fn path(&self) -> String {
        self.stages()
            .map(|s| s.kind.name())
            .collect::<Vec<_>>()
            .join(">")
    }

    /// The kinds packed one decimal digit each, first stage most significant (`NSGS` then
    /// `NSN-AC` is 12); 0 for no stage.
    pub fn packed_codes(&self) -> u32 {
        self.stages()
            .fold(0u32, |acc, s| acc * 10 + u32::from(s.kind.code()))
    }

    /// The kinds of a packed code (the inverse of [`StageLog::packed_codes`]); `None` when a
    /// digit is not a kind.
    pub fn unpack_codes(mut packed: u32) -> Option<Vec<StageKind>> {
        let mut kinds = Vec::new();
        while packed > 0 {
            kinds.push(StageKind::from_code((packed % 10) as u8)?);
            packed /= 10;
        }
        kinds.reverse();
        Some(kinds)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_pack_and_unpack() {
        let mut log = StageLog::new(0);
        assert_eq!(log.packed_codes(), 0);
        for kind in [StageKind::Nsgs, StageKind::Newton, StageKind::Prox] {
            assert!(log.push(Stage {
                kind,
                iterations: 1,
                error: 1.0,
                end: StageEnd::Stalled,
            }));
        }
        assert_eq!(log.packed_codes(), 123);
        assert_eq!(log.path(), "NSGS>NSN-AC>PROX");
        assert_eq!(
            StageLog::unpack_codes(123),
            Some(vec![StageKind::Nsgs, StageKind::Newton, StageKind::Prox])
        );
        assert_eq!(StageLog::unpack_codes(0), Some(vec![]));
        assert_eq!(StageLog::unpack_codes(18), None);
        // A full log packs into 9 digits, below i32::MAX.
        let mut full = StageLog::new(0);
        while full.push(Stage {
            kind: StageKind::Prox,
            iterations: 0,
            error: 0.0,
            end: StageEnd::Limits,
        }) {}
        assert!(full.is_full());
        assert!(full.packed_codes() <= i32::MAX as u32);
    }
}

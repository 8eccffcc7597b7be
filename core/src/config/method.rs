//! [`Method`]: which solver family runs, with the settings specific to it. The list below is the
//! one place that names every family: the macro makes the enum, the one dispatch to the family's
//! [`Family`] implementation, the `From` conversions and the catalogue of presets (`fc3d bench`
//! names, Siconos ids). Adding a family: its module under `solvers/` with settings implementing
//! [`Family`], its `pub mod` line in `solvers/mod.rs`, a line here, and its iparam/dparam mapping
//! in the C layer (`capi/src/params/`).

use crate::contract::Family;
use crate::solvers::aclm::AclmOptions;
use crate::solvers::admm::AdmmOptions;
use crate::solvers::auto::AutoOptions;
use crate::solvers::nsgs::NsgsOptions;
use crate::solvers::nsn::NsnOptions;
use crate::solvers::pfp::PfpOptions;
use crate::solvers::prox::ProxOptions;
use crate::solvers::soclcp::SoclcpOptions;
use crate::solvers::tresca::TrescaOptions;
use crate::solvers::vi::ViOptions;

macro_rules! methods {
    ($( $(#[$doc:meta])* $variant:ident($settings:ty), )+) => {
        /// Which solver family runs, with the settings specific to it (the common limits are in
        /// [`crate::SolverConfig`]).
        #[derive(Debug, Clone, Copy, PartialEq)]
        pub enum Method {
            $( $(#[$doc])* $variant($settings), )+
        }

        impl Method {
            /// The family's side of the solver contract: the one dispatch on the family.
            pub(crate) fn family(&self) -> &dyn Family {
                match self { $(Method::$variant(s) => s,)+ }
            }

            /// Every named configuration of every family with its defaults, in the order of
            /// this list: what `fc3d bench` and the C layer look names and ids up in.
            pub fn presets() -> Vec<Method> {
                let mut all = Vec::new();
                $( all.extend(<$settings as Family>::presets().into_iter().map(Method::$variant)); )+
                all
            }
        }

        $(
            impl From<$settings> for Method {
                fn from(settings: $settings) -> Self {
                    Method::$variant(settings)
                }
            }
        )+
    };
}

methods! {
    /// Nonsmooth Gauss-Seidel (Siconos id 500).
    Nsgs(NsgsOptions),
    /// Projection / extragradient / hyperplane methods on the VI form (Siconos ids 505, 506, 507, 508, 511, 512).
    Vi(ViOptions),
    /// Nonsmooth Newton: Alart-Curnier / Jean-Moreau (504), Fischer-Burmeister (513), natural
    /// map (520).
    Nsn(NsnOptions),
    /// Proximal point method with an NSN-AC or NSGS internal solver (502).
    Prox(ProxOptions),
    /// Tresca successive approximation (Siconos id 503).
    Tresca(TrescaOptions),
    /// Panagiotopoulos alternating fixed point (Siconos id 522).
    Pfp(PfpOptions),
    /// ACLM fixed point on the SOCLCP relaxation (Siconos id 516).
    Aclm(AclmOptions),
    /// The SOCLCP relaxation solved on its own (Siconos id 517).
    Soclcp(SoclcpOptions),
    /// ADMM on the local formulation (Siconos id 523).
    Admm(AdmmOptions),
    /// AUTO: chooses and switches between NSGS, NSN-AC and PROX (fc3d id 590, `FC3D_AUTO`).
    Auto(AutoOptions),
}

impl Method {
    /// Short name (`NSGS`, `VI-FPP`, `NSN-AC`, `PROX-NSGS`, ...): the family's name for this
    /// configuration, as `fc3d bench` accepts it.
    pub fn name(&self) -> &'static str {
        self.family().name()
    }

    /// Label in tables and legends, e.g. `NSGS/565`, `NSN-AC/GP`, `TFP/500`.
    pub fn label(&self) -> String {
        self.family().label()
    }

    /// The Siconos solver id this configuration runs as.
    pub fn siconos_id(&self) -> i32 {
        self.family().siconos_id()
    }

    /// Siconos' default `(tolerance, max_iter)` of the family.
    pub fn default_limits(&self) -> (f64, usize) {
        self.family().default_limits()
    }

    /// Whether a run of this method, on a W without NaN or infinite entries, can fail only
    /// before it touches `r`: what lets a caller solve in its own arrays (the C
    /// `fc3d_driver_in_place`) and still leave them untouched on every failure. NSGS prepares
    /// everything it allocates (local states, colouring, islands, the best-iterate copy under a
    /// time budget) before its first sweep. A factorizing method may run out of memory in a
    /// factorization mid-run, and the other families call inner solvers whose allocations
    /// happen mid-run: they answer `false`.
    pub fn fails_only_before_start(&self) -> bool {
        matches!(self, Method::Nsgs(_))
    }

    /// The preset named `name` (case-insensitive) or numbered `name` (a Siconos id; the first
    /// preset with that id).
    pub fn preset(name: &str) -> Option<Method> {
        let presets = Method::presets();
        match name.trim().parse::<i32>() {
            Ok(id) => presets.into_iter().find(|m| m.siconos_id() == id),
            Err(_) => presets
                .into_iter()
                .find(|m| m.name().eq_ignore_ascii_case(name.trim())),
        }
    }
}

impl Default for Method {
    /// NSGS with Siconos' defaults.
    fn default() -> Self {
        Method::Nsgs(NsgsOptions::default())
    }
}

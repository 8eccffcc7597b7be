//! AUTO's candidate plans on a generated pile under wall-clock budgets: the error each plan
//! reaches, next to the stages it took. Evidence for AUTO's large-problem rule (docs/scale.md).
//! `cargo run --release -p fc3d-core --example auto_scale -- CONTACTS PILES BUDGET_MS...`

use std::time::Duration;

use fc3d_core::scenes::{sphere_piles, PileSpec};
use fc3d_core::solvers::auto::stage;
use fc3d_core::{solve, AutoOptions, PlannedStage, SolverConfig, StageKind};

fn main() {
    let args: Vec<usize> = std::env::args()
        .skip(1)
        .map(|a| a.parse().unwrap())
        .collect();
    let (contacts, piles) = (args[0], args[1]);
    let p = sphere_piles(&PileSpec {
        contacts,
        piles,
        seed: 1,
    })
    .unwrap();
    let n = 3 * p.n_contacts();
    use StageKind::{ExtraGradient, Nsgs, Tresca};
    let s = |kind| stage(kind, None);
    let patient = |kind| stage(kind, fc3d_core::solvers::auto::TO_THE_LIMITS);
    let plans: Vec<(&str, Vec<PlannedStage>)> = vec![
        ("rule table", vec![]),
        (
            "NSGS, EG to the limits",
            vec![s(Nsgs), patient(ExtraGradient)],
        ),
        ("EG to the limits", vec![patient(ExtraGradient)]),
        ("NSGS to the limits", vec![patient(Nsgs)]),
        ("NSGS, TFP to the limits", vec![s(Nsgs), patient(Tresca)]),
        ("TFP to the limits", vec![patient(Tresca)]),
    ];
    let only = std::env::var("ONLY").ok();
    for &ms in &args[2..] {
        for (name, plan) in &plans {
            if only.as_ref().is_some_and(|o| !name.contains(o.as_str())) {
                continue;
            }
            let plan: Option<&'static [PlannedStage]> =
                (!plan.is_empty()).then(|| &*Box::leak(plan.clone().into_boxed_slice()));
            let mut config = SolverConfig::new(AutoOptions { plan });
            config.tolerance = 1e-4;
            config.max_iter = usize::MAX / 2;
            config.time_budget = Some(Duration::from_millis(ms as u64));
            let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
            let t = std::time::Instant::now();
            let report = solve(&p, &config, &mut r, &mut u).unwrap();
            println!(
                "{contacts} contacts, budget {ms} ms, {name:<22}: error {:.2e} in {:.2} s, stages {:?}",
                report.error,
                t.elapsed().as_secs_f64(),
                report
                    .stages
                    .as_ref()
                    .map(|l| l
                        .stages()
                        .map(|st| format!("{:?} {} it. {:.1e} {:?}", st.kind, st.iterations, st.error, st.end))
                        .collect::<Vec<_>>())
                    .unwrap_or_default()
            );
        }
    }
}

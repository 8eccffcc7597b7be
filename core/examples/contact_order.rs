//! Sweeps NSGS (Siconos' defaults, local solver 565, one thread) needs to bring the error (133)
//! below 1e-3, 1e-4 and 1e-6 when it visits the contacts in another order (issue 27 item 5,
//! docs/convergence.md "Contact order along the load path"):
//!
//! `cargo run --release -p fc3d-core --example contact_order -- [--max-sweeps N]
//! [--budget SECONDS] [--symmetric] [--seed S] [--extra-tol X] [--only LABEL,LABEL] SCENE...`
//!
//! A SCENE is a generated pile (`contacts=1000,piles=4,seed=1,shape=spheres`) or a `.dat` file.
//! Each order is measured on a permuted copy of the problem (contact `k` of the copy is contact
//! `order[k]` of the original), swept in index order: the iterates of NSGS visiting the original
//! in that order. The orders:
//!
//! - `natural`: the problem's own order (for a generated pile: pile after pile, each built
//!   bottom-up, layer after layer);
//! - `up` / `down`: by graph level from the supports (breadth-first through W's off-diagonal
//!   blocks, i.e. through shared bodies), bottom-up (supports first) or top-down, ties by index;
//! - `shuffled`: one random permutation (seed `--seed`, default 1; as NSGS' `ShuffledOnce`),
//!   the control;
//! - `shuffled+up` / `shuffled+down`: the levels recomputed on the shuffled copy, ties by its
//!   (random) indices: what a host whose contacts come in arbitrary order would get;
//! - `bfs`: breadth-first visiting order from the supports (levels bottom-up, each level in
//!   the order its contacts were reached), and `shuffled+bfs` the same on the shuffled copy;
//! - `shuffled+bfs-rev`: that order reversed (top-down, neighbours still close);
//! - `shuffled+cm`: Cuthill-McKee on the shuffled copy (per island, breadth-first from one
//!   support, neighbours by increasing degree): an order that keeps neighbours close without
//!   any notion of bottom;
//! - with `--symmetric`, `up-down`: sweeps alternately bottom-up and top-down, one solver call a
//!   sweep, and `up-up` the same calls always bottom-up (the control of the one-call-a-sweep
//!   scheme).
//!
//! `--only` keeps the named orders.
//!
//! Supports are found from W alone: a contact whose neighbours (the contacts it is coupled to)
//! are all coupled to each other touches one body (its only body's contacts), which is what a
//! ground or wall contact is. For a generated pile the contacts whose column of H touches one
//! body are counted too, and the two sets compared. An island without a support is levelled from
//! its first contact.

use std::time::{Duration, Instant};

use fc3d_core::io::read_dat_file;
use fc3d_core::scenes::GeneratedScene;
use fc3d_core::{
    solve, solve_with_observer, BlockSparseMatrix, Delassus, ErrorEvaluation, FrictionProblem,
    NsgsOptions, SolverConfig,
};

/// The tolerances reported, and one more (`--extra-tol`, default 1e-2) for runs that stop
/// before 1e-3.
const TOLERANCES: [f64; 3] = [1e-3, 1e-4, 1e-6];

static EXTRA_TOLERANCE: std::sync::OnceLock<f64> = std::sync::OnceLock::new();

fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .ok()
        .and_then(|s| s.split_whitespace().next().map(str::to_string))
        .unwrap_or_else(|| "?".into())
}

/// The contacts each contact is coupled to through a non-zero off-diagonal block of W (either
/// direction: W need not be symmetric), sorted.
fn contact_graph(p: &FrictionProblem<'_>) -> Vec<Vec<usize>> {
    let nc = p.n_contacts();
    let mut adj = vec![Vec::new(); nc];
    p.w().for_each_entry(|i, j, v| {
        let (a, b) = (i / 3, j / 3);
        if a != b && v != 0.0 {
            adj[a].push(b);
            adj[b].push(a);
        }
    });
    for list in &mut adj {
        list.sort_unstable();
        list.dedup();
    }
    adj
}

/// Contacts whose neighbours are pairwise coupled (one body's contacts): the supports W shows.
fn supports_from_w(adj: &[Vec<usize>]) -> Vec<bool> {
    adj.iter()
        .map(|nb| {
            nb.iter()
                .enumerate()
                .all(|(k, &a)| nb[k + 1..].iter().all(|b| adj[a].binary_search(b).is_ok()))
        })
        .collect()
}

/// Breadth-first levels from the supports; an island without one starts from its first contact.
fn levels(adj: &[Vec<usize>], supports: &[bool]) -> Vec<usize> {
    let nc = adj.len();
    let mut level = vec![usize::MAX; nc];
    let mut queue = std::collections::VecDeque::new();
    for c in (0..nc).filter(|&c| supports[c]) {
        level[c] = 0;
        queue.push_back(c);
    }
    let mut next_seed = 0;
    loop {
        while let Some(c) = queue.pop_front() {
            for &d in &adj[c] {
                if level[d] == usize::MAX {
                    level[d] = level[c] + 1;
                    queue.push_back(d);
                }
            }
        }
        while next_seed < nc && level[next_seed] != usize::MAX {
            next_seed += 1;
        }
        if next_seed == nc {
            return level;
        }
        level[next_seed] = 0;
        queue.push_back(next_seed);
    }
}

/// Breadth-first visiting order from the supports (in index order), each contact's
/// neighbours taken in index order: the levels of [`levels`], each level in the order its
/// contacts were reached (so neighbours stay close in the order).
fn bfs_order(adj: &[Vec<usize>], supports: &[bool]) -> Vec<usize> {
    let nc = adj.len();
    let mut seen = vec![false; nc];
    let mut order: Vec<usize> = (0..nc).filter(|&c| supports[c]).collect();
    order.iter().for_each(|&c| seen[c] = true);
    let mut head = 0;
    let mut next_seed = 0;
    while order.len() < nc {
        if head == order.len() {
            while seen[next_seed] {
                next_seed += 1;
            }
            seen[next_seed] = true;
            order.push(next_seed);
        }
        let c = order[head];
        head += 1;
        for &d in &adj[c] {
            if !seen[d] {
                seen[d] = true;
                order.push(d);
            }
        }
    }
    order
}

/// Cuthill-McKee: per island, breadth-first from its first support (else its first contact),
/// neighbours by increasing degree, ties by index.
fn cuthill_mckee(adj: &[Vec<usize>], supports: &[bool]) -> Vec<usize> {
    let nc = adj.len();
    let mut seen = vec![false; nc];
    let mut order = Vec::with_capacity(nc);
    let seeds: Vec<usize> = (0..nc).filter(|&c| supports[c]).chain(0..nc).collect();
    let mut head = 0;
    for seed in seeds {
        if seen[seed] {
            continue;
        }
        seen[seed] = true;
        order.push(seed);
        while head < order.len() {
            let c = order[head];
            head += 1;
            let mut next: Vec<usize> = adj[c].iter().copied().filter(|&d| !seen[d]).collect();
            next.sort_by_key(|&d| (adj[d].len(), d));
            for d in next {
                seen[d] = true;
                order.push(d);
            }
        }
    }
    order
}

fn by_level(level: &[usize], bottom_up: bool) -> Vec<usize> {
    let mut order: Vec<usize> = (0..level.len()).collect();
    if bottom_up {
        order.sort_by_key(|&c| (level[c], c));
    } else {
        order.sort_by_key(|&c| (std::cmp::Reverse(level[c]), c));
    }
    order
}

fn shuffled(nc: usize, seed: u64) -> Vec<usize> {
    let mut state = seed;
    let mut next = || {
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    };
    let mut order: Vec<usize> = (0..nc).collect();
    for i in (1..nc).rev() {
        order.swap(i, (next() % (i as u64 + 1)) as usize);
    }
    order
}

/// The problem whose contact `k` is contact `order[k]` of `p`, W in sparse-block storage.
fn permuted(p: &FrictionProblem<'_>, order: &[usize]) -> FrictionProblem<'static> {
    let nc = p.n_contacts();
    let mut position = vec![0; nc];
    for (k, &c) in order.iter().enumerate() {
        position[c] = k;
    }
    let mut rows: Vec<std::collections::BTreeMap<usize, [f64; 9]>> = vec![Default::default(); nc];
    for c in 0..nc {
        rows[position[c]].insert(position[c], [0.0; 9]);
    }
    p.w().for_each_entry(|i, j, v| {
        let (a, b) = (position[i / 3], position[j / 3]);
        rows[a].entry(b).or_insert([0.0; 9])[i % 3 + 3 * (j % 3)] += v;
    });
    let mut row_ptr = vec![0];
    let (mut col_idx, mut blocks) = (Vec::new(), Vec::new());
    for row in rows {
        for (b, block) in row {
            col_idx.push(b);
            blocks.push(block);
        }
        row_ptr.push(col_idx.len());
    }
    let w = BlockSparseMatrix::new(nc, nc, row_ptr, col_idx, blocks).expect("permuted W");
    let q: Vec<f64> = order
        .iter()
        .flat_map(|&c| p.q()[3 * c..3 * c + 3].to_vec())
        .collect();
    let mu: Vec<f64> = order.iter().map(|&c| p.mu()[c]).collect();
    FrictionProblem::new(Delassus::SparseBlock(w), q, mu).expect("permuted problem")
}

struct Run {
    first: [Option<usize>; 4],
    last: (usize, f64),
    seconds: f64,
}

fn measured(tolerance: f64, max_sweeps: usize, budget: f64) -> SolverConfig {
    SolverConfig::new(NsgsOptions {
        error_evaluation: ErrorEvaluation::Full,
        ..Default::default()
    })
    .with_tolerance(tolerance)
    .with_max_iter(max_sweeps)
    .with_time_budget(Some(Duration::from_secs_f64(budget)))
}

fn record(run: &mut Run, sweep: usize, error: f64) {
    let extra = *EXTRA_TOLERANCE.get().unwrap_or(&1e-2);
    for (k, tol) in TOLERANCES.into_iter().chain([extra]).enumerate() {
        if run.first[k].is_none() && error <= tol {
            run.first[k] = Some(sweep);
        }
    }
    run.last = (sweep, error);
}

/// One NSGS run in index order on `p`, the error measured after every sweep.
fn run_in_order(p: &FrictionProblem<'_>, max_sweeps: usize, budget: f64) -> Run {
    let n = p.size();
    let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
    let mut run = Run {
        first: [None; 4],
        last: (0, f64::NAN),
        seconds: 0.0,
    };
    let t = Instant::now();
    solve_with_observer(
        p,
        &measured(1e-6, max_sweeps, budget),
        &mut r,
        &mut u,
        &mut |e| record(&mut run, e.iteration, e.error),
    )
    .expect("solve");
    run.seconds = t.elapsed().as_secs_f64();
    run
}

/// Sweeps alternately through `forward` and `backward` (permuted copies of one problem, by
/// `forward_order` and `backward_order`), one sweep a call, the reaction carried over.
fn run_alternating(
    forward: (&FrictionProblem<'_>, &[usize]),
    backward: (&FrictionProblem<'_>, &[usize]),
    max_sweeps: usize,
    budget: f64,
) -> Run {
    let nc = forward.0.n_contacts();
    let mut original = vec![0.0; 3 * nc];
    let (mut r, mut u) = (vec![0.0; 3 * nc], vec![0.0; 3 * nc]);
    let mut run = Run {
        first: [None; 4],
        last: (0, f64::NAN),
        seconds: 0.0,
    };
    let t = Instant::now();
    for sweep in 1..=max_sweeps {
        let (p, order) = if sweep % 2 == 1 { forward } else { backward };
        for (k, &c) in order.iter().enumerate() {
            r[3 * k..3 * k + 3].copy_from_slice(&original[3 * c..3 * c + 3]);
        }
        let mut error = f64::NAN;
        solve_with_observer(p, &measured(0.0, 1, budget), &mut r, &mut u, &mut |e| {
            error = e.error
        })
        .expect("solve");
        for (k, &c) in order.iter().enumerate() {
            original[3 * c..3 * c + 3].copy_from_slice(&r[3 * k..3 * k + 3]);
        }
        record(&mut run, sweep, error);
        if error <= 1e-6 || t.elapsed().as_secs_f64() > budget {
            break;
        }
    }
    run.seconds = t.elapsed().as_secs_f64();
    run
}

fn main() {
    let mut max_sweeps = 30_000;
    let mut budget = 120.0;
    let mut symmetric = false;
    let mut shuffle_seed = 1;
    let mut only: Option<Vec<String>> = None;
    let mut scenes = Vec::new();
    let mut it = std::env::args().skip(1);
    while let Some(arg) = it.next() {
        match arg.as_str() {
            "--max-sweeps" => max_sweeps = it.next().expect("N").parse().expect("N"),
            "--budget" => budget = it.next().expect("s").parse().expect("seconds"),
            "--symmetric" => symmetric = true,
            "--extra-tol" => {
                let tol = it.next().expect("tolerance").parse().expect("tolerance");
                EXTRA_TOLERANCE.set(tol).expect("one --extra-tol");
            }
            "--seed" => shuffle_seed = it.next().expect("seed").parse().expect("seed"),
            "--only" => {
                only = Some(
                    it.next()
                        .expect("labels")
                        .split(',')
                        .map(str::to_string)
                        .collect(),
                )
            }
            scene => scenes.push(scene.to_string()),
        }
    }
    println!(
        "scene,contacts,order,levels,supports,sweeps_1e-3,sweeps_1e-4,sweeps_1e-6,sweeps_extra,\
         last_sweep,last_error,run_s,sweep_ms,load"
    );
    for spec in scenes {
        let (name, problem, h_supports) = if spec.ends_with(".dat") {
            let p = read_dat_file(std::path::Path::new(&spec)).expect("dat file");
            let name = std::path::Path::new(&spec)
                .file_stem()
                .unwrap()
                .to_string_lossy()
                .into_owned();
            (name, p, None)
        } else {
            let scene = GeneratedScene::parse(&spec).expect("scene spec");
            let global = scene.generate_global().expect("global scene");
            let nc = global.n_contacts();
            let mut bodies: Vec<Vec<usize>> = vec![Vec::new(); nc];
            global.h().for_each_entry(|i, j, v| {
                if v != 0.0 {
                    bodies[j / 3].push(i / 6);
                }
            });
            let one_body: Vec<bool> = bodies
                .into_iter()
                .map(|mut b| {
                    b.sort_unstable();
                    b.dedup();
                    b.len() == 1
                })
                .collect();
            (
                scene.name(),
                scene.generate().expect("scene"),
                Some(one_body),
            )
        };
        let nc = problem.n_contacts();
        let adj = contact_graph(&problem);
        let supports = supports_from_w(&adj);
        if let Some(h) = &h_supports {
            let differ = (0..nc).filter(|&c| h[c] != supports[c]).count();
            eprintln!(
                "{name}: {} supports from W, {} contacts touching one body (H), {differ} differ",
                supports.iter().filter(|&&s| s).count(),
                h.iter().filter(|&&s| s).count()
            );
        }
        let level = levels(&adj, &supports);
        let depth = level.iter().max().map_or(0, |l| l + 1);
        // How far the natural order is from bottom-up as Gauss-Seidel sees it: coupled pairs
        // visited higher level first (none: the sweep is the bottom-up one, iterate for
        // iterate, since uncoupled contacts commute).
        let (pairs, reversed) = (0..nc).fold((0, 0), |(n, r), c| {
            let later = adj[c].iter().filter(|&&d| d > c);
            let rev = later.clone().filter(|&&d| level[d] < level[c]).count();
            (n + later.count(), r + rev)
        });
        eprintln!(
            "{name}: {nc} contacts, {depth} levels, natural order: {reversed} of {pairs} coupled \
             pairs visited higher level first"
        );
        let shuffle = shuffled(nc, shuffle_seed);
        let shuffled_problem = permuted(&problem, &shuffle);
        let shuffled_adj = contact_graph(&shuffled_problem);
        let shuffled_level = levels(&shuffled_adj, &supports_from_w(&shuffled_adj));
        let identity: Vec<usize> = (0..nc).collect();
        let up = by_level(&level, true);
        let down = by_level(&level, false);
        let mut cases: Vec<(&str, FrictionProblem<'static>, Vec<usize>)> = vec![
            ("natural", permuted(&problem, &identity), identity.clone()),
            ("up", permuted(&problem, &up), up.clone()),
            ("down", permuted(&problem, &down), down.clone()),
            ("shuffled", permuted(&problem, &shuffle), shuffle.clone()),
        ];
        let shuffled_supports = supports_from_w(&shuffled_adj);
        let bfs = bfs_order(&adj, &supports);
        cases.push(("bfs", permuted(&problem, &bfs), bfs.clone()));
        let orders_of_shuffled = [
            ("shuffled+up", by_level(&shuffled_level, true)),
            ("shuffled+down", by_level(&shuffled_level, false)),
            ("shuffled+bfs", bfs_order(&shuffled_adj, &shuffled_supports)),
            ("shuffled+bfs-rev", {
                let mut o = bfs_order(&shuffled_adj, &shuffled_supports);
                o.reverse();
                o
            }),
            (
                "shuffled+cm",
                cuthill_mckee(&shuffled_adj, &shuffled_supports),
            ),
        ];
        for (label, order) in orders_of_shuffled {
            let in_original: Vec<usize> = order.iter().map(|&k| shuffle[k]).collect();
            cases.push((
                label,
                permuted(&shuffled_problem, &order),
                in_original.clone(),
            ));
        }
        let supports_count = supports.iter().filter(|&&s| s).count();
        for (label, p, _) in &cases {
            if only.as_ref().is_some_and(|o| !o.iter().any(|l| l == label)) {
                continue;
            }
            // One sweep's time: 20 sweeps with the default options, no error measured.
            let n = p.size();
            let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
            let t = Instant::now();
            let timing = SolverConfig::new(NsgsOptions::default())
                .with_tolerance(0.0)
                .with_max_iter(20);
            solve(p, &timing, &mut r, &mut u).expect("solve");
            let sweep_ms = t.elapsed().as_secs_f64() * 1e3 / 20.0;
            let run = run_in_order(p, max_sweeps, budget);
            print_row(&name, nc, label, depth, supports_count, &run, sweep_ms);
        }
        if symmetric {
            let (_, up_p, up_o) = &cases[1];
            let (_, down_p, down_o) = &cases[2];
            let run = run_alternating((up_p, up_o), (down_p, down_o), max_sweeps, budget);
            print_row(&name, nc, "up-down", depth, supports_count, &run, f64::NAN);
            // The same one-sweep calls through one order: how far restarting the solver every
            // sweep (its local solvers' carried state reset) moves the counts from `up`'s.
            let run = run_alternating((up_p, up_o), (up_p, up_o), max_sweeps, budget);
            print_row(&name, nc, "up-up", depth, supports_count, &run, f64::NAN);
        }
    }
}

fn print_row(
    name: &str,
    nc: usize,
    label: &str,
    depth: usize,
    supports: usize,
    run: &Run,
    sweep_ms: f64,
) {
    let s = |k: usize| run.first[k].map_or("-".to_string(), |s| s.to_string());
    println!(
        "{name},{nc},{label},{depth},{supports},{},{},{},{},{},{:.3e},{:.1},{sweep_ms:.3},{}",
        s(0),
        s(1),
        s(2),
        s(3),
        run.last.0,
        run.last.1,
        run.seconds,
        load_average()
    );
}

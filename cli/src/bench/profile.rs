//! Dolan–Moré performance profiles (section 8.2 of Acary-Brémond-Huber):
//!
//! `r_{p,s} = t_{p,s} / min_s t_{p,s}` and `rho_s(tau) = |{p : r_{p,s} <= tau}| / n_p`,
//!
//! where `t_{p,s}` is the time solver `s` needs to solve problem `p`. A problem `s` does not solve
//! has an infinite ratio (it never counts); a problem no solver solves still counts in `n_p`.

/// Times are floored here (seconds) so that a measured 0 cannot make a ratio 0/0.
const TIME_FLOOR: f64 = 1e-12;

/// The ratios of every solver, ready to be evaluated at any `tau`.
#[derive(Debug, Clone, PartialEq)]
pub struct PerformanceProfile {
    n_problems: usize,
    /// Per solver: its finite ratios `r_{p,s}`, sorted increasingly.
    finite_ratios: Vec<Vec<f64>>,
}

impl PerformanceProfile {
    /// `times[p][s]`: the time of solver `s` on problem `p`, `None` when it did not solve it.
    /// Every row must have `n_solvers` entries.
    pub fn new(times: &[Vec<Option<f64>>], n_solvers: usize) -> Self {
        let mut finite_ratios = vec![Vec::new(); n_solvers];
        for row in times {
            assert_eq!(row.len(), n_solvers, "one time per solver");
            let best = row
                .iter()
                .flatten()
                .map(|t| t.max(TIME_FLOOR))
                .fold(f64::INFINITY, f64::min);
            if !best.is_finite() {
                continue; // nobody solved p: infinite ratio for all
            }
            for (s, t) in row.iter().enumerate() {
                if let Some(t) = t {
                    finite_ratios[s].push(t.max(TIME_FLOOR) / best);
                }
            }
        }
        for r in &mut finite_ratios {
            r.sort_by(f64::total_cmp);
        }
        PerformanceProfile {
            n_problems: times.len(),
            finite_ratios,
        }
    }

    pub fn n_problems(&self) -> usize {
        self.n_problems
    }

    pub fn n_solvers(&self) -> usize {
        self.finite_ratios.len()
    }

    /// `rho_s(tau)`; 0 when there is no problem.
    pub fn rho(&self, s: usize, tau: f64) -> f64 {
        if self.n_problems == 0 {
            return 0.0;
        }
        let count = self.finite_ratios[s].partition_point(|&r| r <= tau);
        count as f64 / self.n_problems as f64
    }

    /// `rho_s(infinity)`: the share of problems `s` solves.
    pub fn robustness(&self, s: usize) -> f64 {
        self.rho(s, f64::INFINITY)
    }

    /// The largest finite ratio over all solvers (1 when there is none).
    pub fn max_ratio(&self) -> f64 {
        self.finite_ratios
            .iter()
            .filter_map(|r| r.last().copied())
            .fold(1.0, f64::max)
    }

    /// The step function `rho_s` on `[1, tau_max]` as a polyline `(tau, rho)`: it starts at
    /// `(1, rho_s(1))`, goes up vertically at every ratio, and ends at `(tau_max, rho_s(tau_max))`.
    pub fn steps(&self, s: usize, tau_max: f64) -> Vec<(f64, f64)> {
        let mut points = vec![(1.0, self.rho(s, 1.0))];
        for &r in &self.finite_ratios[s] {
            if r <= 1.0 || r > tau_max {
                continue;
            }
            let before = points.last().unwrap().1;
            let after = self.rho(s, r);
            if after > before {
                points.push((r, before));
                points.push((r, after));
            }
        }
        points.push((tau_max, self.rho(s, tau_max)));
        points
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Three solvers on four problems:
    ///
    /// | p | A | B | C |
    /// | --- | --- | --- | --- |
    /// | 0 | 1 | 2 | 4 |
    /// | 1 | 3 | 1 | - |
    /// | 2 | - | 5 | 10 |
    /// | 3 | - | - | - |
    ///
    /// ratios: A = {1, 3, inf, inf}, B = {2, 1, 1, inf}, C = {4, inf, 2, inf}.
    fn example() -> PerformanceProfile {
        let times = vec![
            vec![Some(1.0), Some(2.0), Some(4.0)],
            vec![Some(3.0), Some(1.0), None],
            vec![None, Some(5.0), Some(10.0)],
            vec![None, None, None],
        ];
        PerformanceProfile::new(&times, 3)
    }

    #[test]
    fn rho_on_a_hand_made_table() {
        let p = example();
        assert_eq!(p.n_problems(), 4);
        assert_eq!(p.n_solvers(), 3);
        let (a, b, c) = (0, 1, 2);
        // tau = 1: share of problems where the solver is (one of) the fastest.
        assert_eq!(p.rho(a, 1.0), 0.25);
        assert_eq!(p.rho(b, 1.0), 0.5);
        assert_eq!(p.rho(c, 1.0), 0.0);
        assert_eq!(p.rho(a, 2.9), 0.25);
        assert_eq!(p.rho(a, 3.0), 0.5);
        assert_eq!(p.rho(b, 2.0), 0.75);
        assert_eq!(p.rho(c, 2.0), 0.25);
        assert_eq!(p.rho(c, 4.0), 0.5);
        // Robustness: problems solved; p3 (nobody) still counts in n_p.
        assert_eq!(p.robustness(a), 0.5);
        assert_eq!(p.robustness(b), 0.75);
        assert_eq!(p.robustness(c), 0.5);
        assert_eq!(p.rho(b, 1e300), 0.75);
        assert_eq!(p.max_ratio(), 4.0);
        // Below 1 nothing counts.
        assert_eq!(p.rho(b, 0.99), 0.0);
    }

    #[test]
    fn ties_count_for_every_tied_solver() {
        let p = PerformanceProfile::new(&[vec![Some(2.0), Some(2.0)]], 2);
        assert_eq!(p.rho(0, 1.0), 1.0);
        assert_eq!(p.rho(1, 1.0), 1.0);
    }

    #[test]
    fn zero_times_and_empty_sets() {
        let p = PerformanceProfile::new(&[vec![Some(0.0), Some(0.0), Some(1e-9)]], 3);
        assert_eq!(p.rho(0, 1.0), 1.0);
        assert_eq!(p.rho(1, 1.0), 1.0);
        assert_eq!(p.rho(2, 1.0), 0.0);
        assert_eq!(p.rho(2, 1e4), 1.0);
        let p = PerformanceProfile::new(&[], 2);
        assert_eq!(p.rho(0, 10.0), 0.0);
        assert_eq!(p.max_ratio(), 1.0);
    }

    #[test]
    fn step_polyline() {
        let p = example();
        assert_eq!(
            p.steps(0, 8.0),
            vec![(1.0, 0.25), (3.0, 0.25), (3.0, 0.5), (8.0, 0.5)]
        );
        assert_eq!(
            p.steps(2, 3.0),
            vec![(1.0, 0.0), (2.0, 0.0), (2.0, 0.25), (3.0, 0.25)]
        );
        assert_eq!(
            p.steps(1, 8.0),
            vec![(1.0, 0.5), (2.0, 0.5), (2.0, 0.75), (8.0, 0.75)]
        );
    }
}

//! Problems and partitions for fc3d's own MPI programs (the check program run by the tests and
//! the scaling benchmark): a problem split over ranks as a host would split it, each rank
//! holding the block rows of its contacts with columns by global id.

use fc3d_core::scenes::GeneratedScene;
use fc3d_core::{BlockSparseMatrix, FrictionProblem};

/// A whole problem in 3x3 block rows (every rank of a test reads or generates the same one).
pub struct WholeProblem {
    pub w: BlockSparseMatrix<'static>,
    pub q: Vec<f64>,
    pub mu: Vec<f64>,
}

impl WholeProblem {
    /// `gen:contacts=N,piles=P,seed=S` (a generated pile) or the path of a `.dat` file.
    pub fn load(spec: &str) -> Result<WholeProblem, String> {
        let problem: FrictionProblem<'static> = match spec.strip_prefix("gen:") {
            Some(scene) => GeneratedScene::parse(scene)
                .and_then(|s| s.generate())
                .map_err(|e| e.to_string())?,
            None => fc3d_core::io::read_problem_file(std::path::Path::new(spec))
                .map_err(|e| e.to_string())?,
        };
        let w = problem.w().to_block_sparse().map_err(|e| e.to_string())?;
        Ok(WholeProblem {
            w,
            q: problem.q().to_vec(),
            mu: problem.mu().to_vec(),
        })
    }

    pub fn n_contacts(&self) -> usize {
        self.mu.len()
    }
}

/// The host's global id of contact `c` (not its index: ids need not be contiguous).
pub fn global_id(c: usize) -> i64 {
    5 * c as i64 + 11
}

/// How contacts are dealt to ranks.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Partition {
    /// Contiguous ranges of indices.
    Ranges,
    /// Contact c to rank c mod size.
    RoundRobin,
    /// Each contact to a rank drawn from a seeded generator; each rank lists its contacts in a
    /// shuffled order.
    Random,
    /// Contiguous ranges over all ranks but the last, which owns nothing.
    EmptyLast,
}

impl Partition {
    pub const ALL: [Partition; 4] = [
        Partition::Ranges,
        Partition::RoundRobin,
        Partition::Random,
        Partition::EmptyLast,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Partition::Ranges => "ranges",
            Partition::RoundRobin => "round-robin",
            Partition::Random => "random",
            Partition::EmptyLast => "empty-last",
        }
    }

    pub fn parse(s: &str) -> Option<Partition> {
        Partition::ALL.into_iter().find(|p| p.name() == s)
    }

    /// This rank's contacts (indices of the whole problem), in the order the host lists them.
    pub fn contacts_of(self, n: usize, rank: usize, size: usize) -> Vec<usize> {
        let range = |parts: usize, k: usize| (k * n / parts)..((k + 1) * n / parts);
        match self {
            Partition::Ranges => range(size, rank).collect(),
            Partition::RoundRobin => (rank..n).step_by(size).collect(),
            Partition::EmptyLast if size > 1 => {
                if rank + 1 == size {
                    Vec::new()
                } else {
                    range(size - 1, rank).collect()
                }
            }
            Partition::EmptyLast => range(1, 0).collect(),
            Partition::Random => {
                let mut mine: Vec<usize> = (0..n)
                    .filter(|&c| crate::layout::mix(c as u64 ^ 0xfeed) % size as u64 == rank as u64)
                    .collect();
                mine.sort_by_key(|&c| crate::layout::mix(c as u64 ^ 0xbeef));
                mine
            }
        }
    }
}

/// One rank's arguments of `fc3d_mpi_solve_blocks`.
pub struct RankRows {
    pub ids: Vec<i64>,
    pub row_ptr: Vec<i64>,
    pub cols: Vec<i64>,
    pub blocks: Vec<f64>,
    pub q: Vec<f64>,
    pub mu: Vec<f64>,
}

impl RankRows {
    /// The rows of `contacts` of `p`, each row's blocks in reverse storage order (a host's
    /// order need not be the column order).
    pub fn of(p: &WholeProblem, contacts: &[usize]) -> RankRows {
        let (row_ptr_w, col_w) = (p.w.row_ptr(), p.w.col_idx());
        let mut rows = RankRows {
            ids: Vec::with_capacity(contacts.len()),
            row_ptr: vec![0],
            cols: Vec::new(),
            blocks: Vec::new(),
            q: Vec::with_capacity(3 * contacts.len()),
            mu: Vec::with_capacity(contacts.len()),
        };
        for &c in contacts {
            rows.ids.push(global_id(c));
            for k in (row_ptr_w[c]..row_ptr_w[c + 1]).rev() {
                rows.cols.push(global_id(col_w[k]));
                rows.blocks.extend_from_slice(p.w.block(k));
            }
            rows.row_ptr.push(rows.cols.len() as i64);
            rows.q.extend_from_slice(&p.q[3 * c..3 * c + 3]);
            rows.mu.push(p.mu[c]);
        }
        rows
    }

    pub fn n_local(&self) -> usize {
        self.ids.len()
    }
}

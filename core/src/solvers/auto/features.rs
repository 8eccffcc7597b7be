//! The features AUTO's rules read: one pass over W's normal rows and diagonal blocks.

use crate::alloc::reserve;
use crate::error::Fc3dError;
use crate::matrix::Delassus;
use crate::problem::FrictionProblem;

/// Cheap features of a problem, computed in one pass over W's stored entries (O(nnz)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProblemFeatures {
    pub n_contacts: usize,
    /// Stored 3x3 blocks of W (nonzero entries / 9 for an entry-wise storage) over `nc^2`: 1 for
    /// a fully coupled W.
    pub block_density: f64,
    pub mu_min: f64,
    pub mu_max: f64,
    /// Contacts with mu = 0 (frictionless).
    pub frictionless: usize,
    /// min over contacts of `W_NN / sum |W_Nj|` over the entries j of the normal row outside
    /// the contact's block (infinite for an uncoupled contact): > 1 is a diagonally dominant
    /// normal row, the case where Gauss-Seidel converges fast.
    pub diagonal_dominance: f64,
    /// max over the diagonal blocks of `max |B - B^T| / max |B|`.
    pub block_asymmetry: f64,
    /// Conditioning estimate: `max W_NN / min W_NN` over the contacts (infinite when some
    /// `W_NN <= 0`).
    pub diagonal_spread: f64,
    /// Contacts whose normal diagonal entry is not positive relative to the largest one
    /// (`W_NN <= 1e-12 max W_NN`): their one-contact problems are singular.
    pub singular_contacts: usize,
}

/// `mu_max` from which friction couples the contacts strongly (see [`Condition`]).
pub const STRONG_MU: f64 = 0.25;
/// Normal-row diagonal dominance below which a coupled problem is hard for Gauss-Seidel.
pub const WEAK_DOMINANCE: f64 = 0.16;
impl ProblemFeatures {
    /// Strong frictional coupling (see [`Condition::strongly_coupled`]).
    pub fn strongly_coupled(&self) -> bool {
        self.mu_max >= STRONG_MU && self.diagonal_dominance < WEAK_DOMINANCE
    }

    /// The features of `problem`; panics when the diagonal of W cannot be held (see
    /// [`ProblemFeatures::try_of`]).
    pub fn of(problem: &FrictionProblem<'_>) -> ProblemFeatures {
        Self::try_of(problem).expect("room for the diagonal of W")
    }

    /// The features of `problem`, reading W once (its diagonal held, allocated fallibly).
    pub fn try_of(problem: &FrictionProblem<'_>) -> Result<ProblemFeatures, Fc3dError> {
        let nc = problem.n_contacts();
        let mu = problem.mu();
        let mut rows = NormalRows::new(nc)?;
        let stored_blocks = rows.read(problem.w(), nc);
        let NormalRows {
            w_nn,
            largest,
            smallest,
            diagonal_dominance,
            block_asymmetry,
        } = rows;
        let singular_contacts = w_nn.iter().filter(|&&v| v <= 1e-12 * largest).count();
        let diagonal_spread = if smallest > 0.0 {
            largest / smallest
        } else {
            f64::INFINITY
        };
        let (mut mu_min, mut mu_max, mut frictionless) = (f64::INFINITY, 0.0_f64, 0);
        for &m in mu {
            mu_min = mu_min.min(m);
            mu_max = mu_max.max(m);
            frictionless += usize::from(m == 0.0);
        }
        Ok(ProblemFeatures {
            n_contacts: nc,
            block_density: if nc > 0 {
                stored_blocks / (nc as f64 * nc as f64)
            } else {
                0.0
            },
            mu_min,
            mu_max,
            frictionless,
            diagonal_dominance,
            block_asymmetry,
            diagonal_spread,
            singular_contacts,
        })
    }
}

/// What one pass over W's normal rows (and the diagonal blocks they cross) gathers: each
/// contact's `W_NN` (kept for the singular count, which needs the largest first) and running
/// extremes, so that nothing else of size `nc` is allocated.
struct NormalRows {
    w_nn: Vec<f64>,
    largest: f64,
    smallest: f64,
    diagonal_dominance: f64,
    block_asymmetry: f64,
}

impl NormalRows {
    fn new(nc: usize) -> Result<Self, Fc3dError> {
        let mut w_nn = Vec::new();
        reserve(&mut w_nn, nc, "the diagonal of W")?;
        Ok(NormalRows {
            w_nn,
            largest: 0.0,
            smallest: f64::INFINITY,
            diagonal_dominance: f64::INFINITY,
            block_asymmetry: 0.0,
        })
    }

    /// Contact `c`'s normal row: its diagonal block (row-major) and the sum of `|W_Nj|` outside
    /// that block.
    fn push(&mut self, block: &[[f64; 3]; 3], off: f64) {
        let d = block[0][0];
        self.w_nn.push(d);
        self.largest = self.largest.max(d);
        self.smallest = self.smallest.min(d);
        if off > 0.0 {
            self.diagonal_dominance = self.diagonal_dominance.min(d / off);
        }
        let scale = block.iter().flatten().fold(0.0_f64, |m, v| m.max(v.abs()));
        let mut skew = 0.0_f64;
        for i in 0..3 {
            for j in 0..i {
                skew = skew.max((block[i][j] - block[j][i]).abs());
            }
        }
        if scale > 0.0 {
            self.block_asymmetry = self.block_asymmetry.max(skew / scale);
        }
    }

    /// Reads every contact's normal row and diagonal block, in contact order; returns the
    /// number of stored 3x3 blocks (a third of a dense W is read).
    fn read(&mut self, w: &Delassus<'_>, nc: usize) -> f64 {
        match w {
            Delassus::Dense(d) => {
                let n = 3 * nc;
                let values = d.values();
                for c in 0..nc {
                    let i = 3 * c;
                    let mut off = 0.0;
                    for j in (0..i).chain(i + 3..n) {
                        off += values[i + j * n].abs();
                    }
                    let block = std::array::from_fn(|a| {
                        std::array::from_fn(|b| values[(i + a) + (i + b) * n])
                    });
                    self.push(&block, off);
                }
                (nc * nc) as f64
            }
            Delassus::SparseBlock(b) => {
                let (row_ptr, cols) = (b.row_ptr(), b.col_idx());
                for c in 0..nc {
                    let mut diag = [[0.0; 3]; 3];
                    let mut off = 0.0;
                    for k in row_ptr[c]..row_ptr[c + 1] {
                        // Column-major: the normal row is entries 0, 3, 6.
                        let block = b.block(k);
                        if cols[k] == c {
                            for (a, row) in diag.iter_mut().enumerate() {
                                for (b, v) in row.iter_mut().enumerate() {
                                    *v += block[a + 3 * b];
                                }
                            }
                        } else {
                            off += block[0].abs() + block[3].abs() + block[6].abs();
                        }
                    }
                    self.push(&diag, off);
                }
                b.n_blocks() as f64
            }
            Delassus::Sparse(m) => {
                let (ptr, cols, values) = (m.row_ptr(), m.col_idx(), m.values());
                for c in 0..nc {
                    let i = 3 * c;
                    let mut off = 0.0;
                    for k in ptr[i]..ptr[i + 1] {
                        if cols[k] / 3 != c {
                            off += values[k].abs();
                        }
                    }
                    let block = w.diagonal_block(c).unwrap_or([[0.0; 3]; 3]);
                    self.push(&block, off);
                }
                m.nnz() as f64 / 9.0
            }
        }
    }
}

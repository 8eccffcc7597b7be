//! NSGS in the velocity form ("product Gauss-Seidel", as LMGC90, So-bogus, Chrono sweep) for
//! a global problem with a block-diagonal M: instead of W's block rows, the sweep keeps the
//! global velocity `v = M^-1 (q + H r)` up to date contact by contact. Contact c reads its
//! local velocity `u_c = H_c^T v + b_c` on the unknowns of the blocks of M it touches (its
//! bodies), solves FC(W_cc, u_c - W_cc r_c, mu_c) with the NSGS local step, and adds
//! `M^-1 H_c (r_c^new - r_c^old)` to the same unknowns. `W_cc = H_c^T M^-1 H_c` and
//! `M^-1 H_c` are computed once; W itself is never formed.
//!
//! In exact arithmetic the iterates are NSGS's on `W = H^T M^-1 H` in the same contact order.
//! Two contacts are coupled when they touch a common block of M; the coloured sweep colours
//! units of contacts by that coupling (the NSGS colouring and schedule), so the result is the
//! same for any number of threads.

use super::coloured::ColouredPlan;
use super::parallel::{Coupling, SharedSlice};
use super::step::{solve_contact, LocalStep};
use super::{Decomposition, NsgsOptions};
use crate::contract::deadline_passed;
use crate::error::{try_vec, Fc3dError};
use crate::local::AnyLocalSolver;
use crate::math::linalg::{distance_sq_d, Block};
use crate::matrix::{sort_and_dedup_from, HForm};

/// What the velocity-form sweep reads a contact by: its unknowns of M (whole blocks of M),
/// `H_c^T` and `M^-1 H_c` on them, and `W_cc`.
pub(crate) struct HFormContacts {
    /// Contact c's entries are `ptr[c]..ptr[c + 1]`.
    ptr: Vec<usize>,
    /// The unknown of M (index of v) of each entry.
    dofs: Vec<u32>,
    /// Per entry, `(H_{dof, 3c + j})_j`: the row of `H_c` on that unknown.
    h: Vec<[f64; 3]>,
    /// Per entry, the row of `M^-1 H_c` on that unknown.
    g: Vec<[f64; 3]>,
    diagonal: Vec<Block<3>>,
    /// The blocks of M each contact touches (`contact_blocks[contact_block_ptr[c]..]`) and the
    /// contacts touching each block: the coupling a colouring separates.
    contact_block_ptr: Vec<usize>,
    contact_blocks: Vec<usize>,
    block_contact_ptr: Vec<usize>,
    block_contacts: Vec<usize>,
}

/// Contacts between two clock reads of the H-form set-up (a contact's data costs about a
/// microsecond: the budget holds to about a millisecond).
const SET_UP_CLOCK_PERIOD: usize = 1024;

impl HFormContacts {
    /// The contacts of `operator` (3 columns of H each). Needs a block-diagonal M. `None` when
    /// `deadline` passes first (the clock is read every [`SET_UP_CLOCK_PERIOD`] contacts).
    pub(crate) fn new(
        operator: &HForm,
        deadline: Option<std::time::Instant>,
    ) -> Result<Option<Self>, Fc3dError> {
        let Some((block_dofs, offsets)) = operator.mass().blocks() else {
            return Err(Fc3dError::Unsupported(
                "the H-form sweep needs a block-diagonal M (connected blocks of at most 96 \
                 unknowns); this M is factored as a whole"
                    .into(),
            ));
        };
        let ndof = operator.ndof();
        if u32::try_from(ndof).is_err() {
            return Err(Fc3dError::Unsupported(format!(
                "the H-form sweep indexes M's unknowns in 32 bits: {ndof} unknowns"
            )));
        }
        let m = operator.size();
        if !m.is_multiple_of(3) {
            return Err(Fc3dError::InvalidStructure(format!(
                "H has {m} columns, not a multiple of 3"
            )));
        }
        let nc = m / 3;
        let n_blocks = offsets.len() - 1;
        let mut block_of = try_vec(ndof, 0usize, "the H-form sweep")?;
        let mut local_index = try_vec(ndof, 0usize, "the H-form sweep")?;
        for k in 0..n_blocks {
            for (li, &i) in block_dofs[offsets[k]..offsets[k + 1]].iter().enumerate() {
                block_of[i] = k;
                local_index[i] = li;
            }
        }
        let ht = operator.ht();
        let (ht_ptr, ht_cols, ht_values) = (ht.row_ptr(), ht.col_idx(), ht.values());
        let mut ptr = try_vec(nc + 1, 0usize, "the H-form sweep")?;
        let mut contact_block_ptr = try_vec(nc + 1, 0usize, "the H-form sweep")?;
        let (mut dofs, mut h, mut g) = (Vec::new(), Vec::new(), Vec::new());
        let mut contact_blocks = Vec::new();
        let mut diagonal = try_vec(nc, [[0.0; 3]; 3], "the H-form sweep")?;
        let mut column = Vec::new();
        for c in 0..nc {
            if c % SET_UP_CLOCK_PERIOD == 0 && deadline_passed(deadline) {
                return Ok(None);
            }
            let first_block = contact_blocks.len();
            for row in 3 * c..3 * c + 3 {
                for &i in &ht_cols[ht_ptr[row]..ht_ptr[row + 1]] {
                    contact_blocks.push(block_of[i]);
                }
            }
            sort_and_dedup_from(&mut contact_blocks, first_block);
            contact_block_ptr[c + 1] = contact_blocks.len();
            let start = dofs.len();
            for &k in &contact_blocks[first_block..] {
                let block = &block_dofs[offsets[k]..offsets[k + 1]];
                let at = dofs.len();
                dofs.extend(block.iter().map(|&i| i as u32));
                h.resize(dofs.len(), [0.0; 3]);
                for (j, row) in (3 * c..3 * c + 3).enumerate() {
                    for p in ht_ptr[row]..ht_ptr[row + 1] {
                        let i = ht_cols[p];
                        if block_of[i] == k {
                            h[at + local_index[i]][j] += ht_values[p];
                        }
                    }
                }
                // M_k^-1 H_ck, column by column in the block's numbering.
                g.resize(dofs.len(), [0.0; 3]);
                for j in 0..3 {
                    column.clear();
                    column.extend(h[at..].iter().map(|e| e[j]));
                    operator.mass().solve_block_in_place(k, &mut column);
                    for (e, x) in g[at..].iter_mut().zip(&column) {
                        e[j] = *x;
                    }
                }
            }
            ptr[c + 1] = dofs.len();
            let w = &mut diagonal[c];
            for (he, ge) in h[start..].iter().zip(&g[start..]) {
                for (i, row) in w.iter_mut().enumerate() {
                    for (j, x) in row.iter_mut().enumerate() {
                        *x += he[i] * ge[j];
                    }
                }
            }
        }
        // The contacts of every block, in increasing order.
        let mut block_contact_ptr = try_vec(n_blocks + 1, 0usize, "the H-form sweep")?;
        for &k in &contact_blocks {
            block_contact_ptr[k + 1] += 1;
        }
        for k in 0..n_blocks {
            block_contact_ptr[k + 1] += block_contact_ptr[k];
        }
        let mut fill = block_contact_ptr.clone();
        let mut block_contacts = try_vec(contact_blocks.len(), 0usize, "the H-form sweep")?;
        for c in 0..nc {
            for &k in &contact_blocks[contact_block_ptr[c]..contact_block_ptr[c + 1]] {
                block_contacts[fill[k]] = c;
                fill[k] += 1;
            }
        }
        Ok(Some(HFormContacts {
            ptr,
            dofs,
            h,
            g,
            diagonal,
            contact_block_ptr,
            contact_blocks,
            block_contact_ptr,
            block_contacts,
        }))
    }

    pub(crate) fn n_contacts(&self) -> usize {
        self.ptr.len() - 1
    }

    /// Contact c's diagonal block `W_cc = H_c^T M^-1 H_c`.
    pub(crate) fn diagonal(&self, c: usize) -> &Block<3> {
        &self.diagonal[c]
    }

    /// Bytes a sweep reads for the contacts' own data (indices, `H_c^T`, `M^-1 H_c`, `W_cc`),
    /// and the entries of v it reads and writes: what a sweep moves besides r, b and mu.
    pub(crate) fn bytes_per_sweep(&self) -> (usize, usize) {
        let entries = self.dofs.len();
        let own = std::mem::size_of_val(self.ptr.as_slice())
            + entries * (std::mem::size_of::<u32>() + 2 * std::mem::size_of::<[f64; 3]>())
            + std::mem::size_of_val(self.diagonal.as_slice());
        (own, 2 * entries * std::mem::size_of::<f64>())
    }

    /// Contact c's new reaction against the velocity `v` (its squared increment and squared
    /// norm returned), written into `r`, with `M^-1 H_c` times the increment added to `v`.
    #[allow(clippy::too_many_arguments)]
    #[inline]
    fn update(
        &self,
        step: &LocalStep,
        worker: &mut AnyLocalSolver,
        relaxation: Option<f64>,
        c: usize,
        b: &[f64],
        mu: &[f64],
        r: &SharedSlice<'_>,
        v: &SharedSlice<'_>,
        memory: &SharedSlice<'_>,
    ) -> (f64, f64) {
        let entries = self.ptr[c]..self.ptr[c + 1];
        let (dofs, h, g) = (
            &self.dofs[entries.clone()],
            &self.h[entries.clone()],
            &self.g[entries],
        );
        let w = &self.diagonal[c];
        let old: [f64; 3] = r.contact(c);
        // q_c + sum_{b != c} W_cb r_b = H_c^T v + b_c - W_cc r_c.
        let local_q = || {
            let mut u = [b[3 * c], b[3 * c + 1], b[3 * c + 2]];
            for (&i, he) in dofs.iter().zip(h) {
                let x = v.get(i as usize);
                u[0] += he[0] * x;
                u[1] += he[1] * x;
                u[2] += he[2] * x;
            }
            for (ui, wi) in u.iter_mut().zip(w) {
                *ui -= wi[0] * old[0] + wi[1] * old[1] + wi[2] * old[2];
            }
            u
        };
        let mut m = memory.get(c);
        let (rc, _) = solve_contact(
            step,
            worker,
            relaxation,
            c,
            w,
            mu[c],
            &old,
            local_q,
            || local_q()[0],
            &mut m,
            false,
        );
        let dr = [rc[0] - old[0], rc[1] - old[1], rc[2] - old[2]];
        if dr != [0.0; 3] {
            for (&i, ge) in dofs.iter().zip(g) {
                let i = i as usize;
                // SAFETY: entry i belongs to a block of M that contact c touches: updated by
                // the thread sweeping c only (no contact of another unit of c's colour touches
                // the block), ordered before the next colour by the barrier.
                unsafe { v.set(i, v.get(i) + ge[0] * dr[0] + ge[1] * dr[1] + ge[2] * dr[2]) };
            }
        }
        // SAFETY: contact c is updated by this thread only (as above).
        unsafe {
            r.set_contact(c, &rc);
            memory.set(c, m);
        }
        (distance_sq_d(&rc, &old), distance_sq_d(&rc, &[0.0; 3]))
    }
}

impl Coupling for HFormContacts {
    fn n_contacts(&self) -> usize {
        HFormContacts::n_contacts(self)
    }

    fn for_each_coupled(&self, c: usize, mut f: impl FnMut(usize)) {
        for &k in &self.contact_blocks[self.contact_block_ptr[c]..self.contact_block_ptr[c + 1]] {
            for &b in &self.block_contacts[self.block_contact_ptr[k]..self.block_contact_ptr[k + 1]]
            {
                if b != c {
                    f(b);
                }
            }
        }
    }
}

/// The velocity-form sweep prepared once per problem: the contacts' data, the NSGS local step,
/// and for [`Decomposition::Coloured`] the colouring and threads. A sweep allocates nothing.
pub(crate) struct HFormSweeper {
    contacts: HFormContacts,
    step: LocalStep,
    worker: AnyLocalSolver,
    memory: Vec<f64>,
    relaxation: Option<f64>,
    coloured: Option<ColouredPlan>,
}

impl HFormSweeper {
    /// The sweeper of `options` (validated by the caller: natural order, no freezing, the
    /// sequential or coloured decomposition); `None` when `deadline` passes during the set-up
    /// (a pass over H: seconds at 10^5 contacts on a loaded machine).
    pub(crate) fn new(
        operator: &HForm,
        options: &NsgsOptions,
        deadline: Option<std::time::Instant>,
    ) -> Result<Option<Self>, Fc3dError> {
        let Some(contacts) = HFormContacts::new(operator, deadline)? else {
            return Ok(None);
        };
        let nc = contacts.n_contacts();
        let step = LocalStep::for_contacts(nc, &options.local)?;
        let coloured = match options.decomposition {
            Decomposition::Coloured => Some(ColouredPlan::new(
                &contacts,
                super::resolve_threads(options.threads),
                None,
            )?),
            _ => None,
        };
        Ok(Some(HFormSweeper {
            worker: super::ContactStep::worker(&step),
            memory: try_vec(nc, 1.0, "local solver states")?,
            contacts,
            step,
            relaxation: options.relaxation,
            coloured,
        }))
    }

    pub(crate) fn contacts(&self) -> &HFormContacts {
        &self.contacts
    }

    /// The instant after which the local solves stop iterating.
    pub(crate) fn set_deadline(&mut self, deadline: Option<std::time::Instant>) {
        super::ContactStep::set_deadline(&mut self.step, deadline);
        self.worker = super::ContactStep::worker(&self.step);
    }

    /// Colours and units of a coloured sweep (`None` for the sequential one).
    pub(crate) fn colouring_size(&self) -> Option<(usize, usize)> {
        self.coloured
            .as_ref()
            .map(|c| (c.colouring.n_colours(), c.colouring.n_units()))
    }

    /// One sweep over the contacts, updating `r` and `v = M^-1 (q + H r)` in place; returns
    /// `sum_c ||r_c^new - r_c^old||^2`.
    pub(crate) fn sweep(&mut self, b: &[f64], mu: &[f64], r: &mut [f64], v: &mut [f64]) -> f64 {
        let HFormSweeper {
            contacts,
            step,
            worker,
            memory,
            relaxation,
            coloured,
        } = self;
        let (r, v, memory) = (
            SharedSlice::new(r),
            SharedSlice::new(v),
            SharedSlice::new(memory),
        );
        let relaxation = *relaxation;
        let Some(plan) = coloured.as_mut() else {
            let mut increment_sq = 0.0;
            for c in 0..contacts.n_contacts() {
                increment_sq += contacts
                    .update(step, worker, relaxation, c, b, mu, &r, &v, &memory)
                    .0;
            }
            return increment_sq;
        };
        let (units, unit_sums) = plan.units();
        let contacts = &*contacts;
        let step = &*step;
        units
            .run(
                contacts.n_contacts(),
                || super::ContactStep::worker(step),
                |worker, c| contacts.update(step, worker, relaxation, c, b, mu, &r, &v, &memory),
                unit_sums,
            )
            .0
    }
}

//! What the multithreaded sweeps need beyond the sequential one: the contact graph of W (its
//! colouring and its connected components), a small persistent pool of helper threads, a spin
//! barrier, and a view of the reaction vector through which threads write disjoint contacts.
//!
//! No dependency is added for this: the pool is one broadcast call (every thread runs the same
//! job with its index) over threads kept for the life of the process, one pool per thread count.
//! A coloured sweep is one broadcast with a barrier between colours, so a sweep costs two
//! wake-ups and `colours` barriers whatever the problem size, and nothing is allocated per sweep.

use std::marker::PhantomData;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Condvar, Mutex, OnceLock};

use crate::alloc::{try_collect, try_push};
use crate::error::{try_copy, try_vec, Fc3dError};
use crate::matrix::{BlockRows, SweepRows};

/// Environment variable a host may set to choose the threads of parallel sweeps.
pub const NUM_THREADS_ENV: &str = "FC3D_NUM_THREADS";

/// The number of threads for `requested` (0: `FC3D_NUM_THREADS` when it holds a positive
/// integer, else the available parallelism, else 1).
pub fn resolve_threads(requested: usize) -> usize {
    if requested > 0 {
        return requested;
    }
    if let Some(n) = std::env::var(NUM_THREADS_ENV)
        .ok()
        .and_then(|v| v.trim().parse::<usize>().ok())
        .filter(|&n| n > 0)
    {
        return n;
    }
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// A slice of `f64` shared by threads that each write their own entries. Reads are plain loads;
/// [`SharedSlice::set`] is `unsafe` because the caller must guarantee that no other thread reads
/// or writes the same entry until the next synchronisation point (a barrier, or the end of a
/// broadcast). The colouring and the islands give that guarantee: within a colour no contact
/// reads another of the same colour, and islands share no contact.
pub(crate) struct SharedSlice<'a> {
    ptr: *mut f64,
    len: usize,
    _borrow: PhantomData<&'a mut [f64]>,
}

// SAFETY: access rules above; the slice is borrowed mutably for 'a, so nothing else touches it.
unsafe impl Send for SharedSlice<'_> {}
unsafe impl Sync for SharedSlice<'_> {}

impl<'a> SharedSlice<'a> {
    pub fn new(v: &'a mut [f64]) -> Self {
        SharedSlice {
            ptr: v.as_mut_ptr(),
            len: v.len(),
            _borrow: PhantomData,
        }
    }

    pub fn len(&self) -> usize {
        self.len
    }

    #[inline]
    pub fn get(&self, i: usize) -> f64 {
        assert!(i < self.len);
        // SAFETY: in bounds; no concurrent writer of entry i (type-level contract of `set`).
        unsafe { self.ptr.add(i).read() }
    }

    /// # Safety
    /// No other thread accesses entry `i` until the next synchronisation point.
    #[inline]
    pub unsafe fn set(&self, i: usize, v: f64) {
        assert!(i < self.len);
        unsafe { self.ptr.add(i).write(v) }
    }

    /// Entries `range` as a slice of their own.
    ///
    /// # Safety
    /// No other thread accesses these entries until the next synchronisation point, and no other
    /// slice of them is alive.
    #[inline]
    pub unsafe fn range_mut(&self, range: std::ops::Range<usize>) -> &mut [f64] {
        assert!(range.start <= range.end && range.end <= self.len);
        unsafe { std::slice::from_raw_parts_mut(self.ptr.add(range.start), range.len()) }
    }

    /// Contact `c`'s `D` entries.
    #[inline]
    pub fn contact<const D: usize>(&self, c: usize) -> [f64; D] {
        std::array::from_fn(|j| self.get(D * c + j))
    }

    /// # Safety
    /// As [`SharedSlice::set`], for contact `c`'s `D` entries.
    #[inline]
    pub unsafe fn set_contact<const D: usize>(&self, c: usize, v: &[f64; D]) {
        for (j, x) in v.iter().enumerate() {
            unsafe { self.set(D * c + j, *x) }
        }
    }
}

/// Where a contact update reads the other contacts' reactions: the plain vector (the sequential
/// sweep, through [`BlockRows`]' own products) or a [`SharedSlice`] (threads; the same
/// operations in the same order).
pub(crate) trait Reactions<const D: usize> {
    fn contact(&self, c: usize) -> [f64; D];
    fn local_q<P: SweepRows<D>>(&self, rows: &P, c: usize, q: &[f64]) -> [f64; D];
    fn local_q_normal<P: SweepRows<D>>(&self, rows: &P, c: usize, q: &[f64]) -> f64;
}

impl<const D: usize> Reactions<D> for [f64] {
    #[inline]
    fn contact(&self, c: usize) -> [f64; D] {
        crate::math::linalg::contact_of(self, c)
    }
    #[inline]
    fn local_q<P: SweepRows<D>>(&self, rows: &P, c: usize, q: &[f64]) -> [f64; D] {
        rows.local_q(c, q, self)
    }
    #[inline]
    fn local_q_normal<P: SweepRows<D>>(&self, rows: &P, c: usize, q: &[f64]) -> f64 {
        rows.local_q_normal(c, q, self)
    }
}

impl<const D: usize> Reactions<D> for SharedSlice<'_> {
    #[inline]
    fn contact(&self, c: usize) -> [f64; D] {
        SharedSlice::contact(self, c)
    }
    #[inline]
    fn local_q<P: SweepRows<D>>(&self, rows: &P, c: usize, q: &[f64]) -> [f64; D] {
        rows.local_q_by(c, q, |b| SharedSlice::contact(self, b))
    }
    #[inline]
    fn local_q_normal<P: SweepRows<D>>(&self, rows: &P, c: usize, q: &[f64]) -> f64 {
        rows.local_q_normal_by(c, q, |i| self.get(i))
    }
}

/// Which contacts a contact's update reads or writes besides its own: the coupling a colouring
/// must separate. Through W, the contacts of its stored off-diagonal blocks; in the H form, the
/// contacts sharing a block of M (a body) with it.
pub(crate) trait Coupling {
    fn n_contacts(&self) -> usize;
    /// Calls `f` with every contact coupled to `c` (`c` itself left out; repeats allowed).
    fn for_each_coupled(&self, c: usize, f: impl FnMut(usize));
}

impl<const D: usize> Coupling for BlockRows<'_, D> {
    fn n_contacts(&self) -> usize {
        BlockRows::n_contacts(self)
    }
    #[inline]
    fn for_each_coupled(&self, c: usize, f: impl FnMut(usize)) {
        self.coupled(c).for_each(f)
    }
}

/// The undirected graph of units of contacts: contacts `unit * size .. (unit + 1) * size`
/// form one unit, and two units are adjacent when a contact of one is coupled ([`Coupling`]) to
/// a contact of the other (through W: `W_bc` or `W_cb` stored). With units of one contact it is
/// the contact graph.
pub(crate) struct ContactGraph {
    ptr: Vec<usize>,
    adjacent: Vec<usize>,
}

impl ContactGraph {
    pub fn new(rows: &impl Coupling, size: usize) -> Result<Self, Fc3dError> {
        Self::over(rows, None, size)
    }

    /// The graph of units of `size` consecutive positions of `island = (contacts, position)`
    /// (contacts closed under coupling, `position[c]`: contact c's position in `contacts`);
    /// without an island, of all contacts in index order.
    pub fn over(
        rows: &impl Coupling,
        island: Option<(&[usize], &[usize])>,
        size: usize,
    ) -> Result<Self, Fc3dError> {
        let n_positions = island.map_or(rows.n_contacts(), |(contacts, _)| contacts.len());
        let contact = |p: usize| island.map_or(p, |(contacts, _)| contacts[p]);
        // A shift for the units' power-of-two sizes: a division per stored block was a fifth
        // of a 2-thread sweep at 10^5 contacts.
        let shift = size.trailing_zeros();
        let power_of_two = size.is_power_of_two();
        let unit_of = |c: usize| {
            let p = island.map_or(c, |(_, position)| position[c]);
            if power_of_two {
                p >> shift
            } else {
                p / size
            }
        };
        let n = n_positions.div_ceil(size);
        // The units each unit's rows reach (without repeats, in the order first reached), then
        // both directions. `reached_by[v] == unit` marks v as listed for unit already: one pass
        // over W's column indices, no sort (the colouring and the islands do not depend on the
        // order of a unit's neighbours).
        let mut forward_ptr = try_vec(n + 1, 0usize, "contact graph")?;
        let mut forward = Vec::new();
        let mut reached_by = try_vec(n, usize::MAX, "contact graph")?;
        for unit in 0..n {
            for p in unit * size..((unit + 1) * size).min(n_positions) {
                let mut pushed = Ok(());
                rows.for_each_coupled(contact(p), |b| {
                    let v = unit_of(b);
                    if v != unit && reached_by[v] != unit && pushed.is_ok() {
                        reached_by[v] = unit;
                        pushed = try_push(&mut forward, v, "contact graph");
                    }
                });
                pushed?;
            }
            forward_ptr[unit + 1] = forward.len();
        }
        let mut ptr = try_vec(n + 1, 0usize, "contact graph")?;
        for unit in 0..n {
            for &v in &forward[forward_ptr[unit]..forward_ptr[unit + 1]] {
                ptr[unit + 1] += 1;
                ptr[v + 1] += 1;
            }
        }
        for unit in 0..n {
            ptr[unit + 1] += ptr[unit];
        }
        let mut adjacent = try_vec(ptr[n], 0usize, "contact graph")?;
        let mut fill = try_copy(&ptr, "contact graph")?;
        for unit in 0..n {
            for &v in &forward[forward_ptr[unit]..forward_ptr[unit + 1]] {
                adjacent[fill[unit]] = v;
                fill[unit] += 1;
                adjacent[fill[v]] = unit;
                fill[v] += 1;
            }
        }
        // A structurally symmetric W lists each neighbour twice, which only costs a little time
        // in the colouring and the island search.
        Ok(ContactGraph { ptr, adjacent })
    }

    fn n(&self) -> usize {
        self.ptr.len() - 1
    }

    fn neighbours(&self, c: usize) -> &[usize] {
        &self.adjacent[self.ptr[c]..self.ptr[c + 1]]
    }

    /// Greedy colouring in index order (smallest colour no neighbour has): the units grouped
    /// by colour, each group in index order, and where each colour starts.
    pub fn colour(&self) -> Result<(Vec<usize>, Vec<usize>), Fc3dError> {
        let nc = self.n();
        const NONE: usize = usize::MAX;
        let mut colour = try_vec(nc, NONE, "contact colouring")?;
        // taken[k] == c: colour k is used by a neighbour of c.
        let mut taken: Vec<usize> = Vec::new();
        let mut n_colours = 0;
        for c in 0..nc {
            for &b in self.neighbours(c) {
                let k = colour[b];
                if k != NONE {
                    taken[k] = c;
                }
            }
            let k = match (0..n_colours).find(|&k| taken[k] != c) {
                Some(k) => k,
                None => {
                    try_push(&mut taken, NONE, "contact colouring")?;
                    n_colours += 1;
                    n_colours - 1
                }
            };
            colour[c] = k;
        }
        let mut start = try_vec(n_colours + 1, 0usize, "contact colouring")?;
        for &k in &colour {
            start[k + 1] += 1;
        }
        for k in 0..n_colours {
            start[k + 1] += start[k];
        }
        let mut order = try_vec(nc, 0usize, "contact colouring")?;
        let mut fill = try_copy(&start, "contact colouring")?;
        for (c, &k) in colour.iter().enumerate() {
            order[fill[k]] = c;
            fill[k] += 1;
        }
        Ok((order, start))
    }

    /// Connected components: the units grouped by island, each island in index order, the
    /// islands ordered by decreasing size (ties by smallest contact), and where each starts.
    pub fn islands(&self) -> Result<(Vec<usize>, Vec<usize>), Fc3dError> {
        let nc = self.n();
        const NONE: usize = usize::MAX;
        let mut island = try_vec(nc, NONE, "contact islands")?;
        let mut sizes: Vec<(usize, usize)> = Vec::new(); // (size, first contact)
        let mut stack = Vec::new();
        for start in 0..nc {
            if island[start] != NONE {
                continue;
            }
            let id = sizes.len();
            island[start] = id;
            try_push(&mut stack, start, "contact islands")?;
            let mut size = 0;
            while let Some(c) = stack.pop() {
                size += 1;
                for &b in self.neighbours(c) {
                    if island[b] == NONE {
                        island[b] = id;
                        try_push(&mut stack, b, "contact islands")?;
                    }
                }
            }
            try_push(&mut sizes, (size, start), "contact islands")?;
        }
        let mut by_size = try_collect(0..sizes.len(), "contact islands")?;
        // First contacts differ: the keys are distinct, so an unstable sort gives one order.
        by_size.sort_unstable_by_key(|&i| (std::cmp::Reverse(sizes[i].0), sizes[i].1));
        let mut rank = try_vec(sizes.len(), 0usize, "contact islands")?;
        for (k, &i) in by_size.iter().enumerate() {
            rank[i] = k;
        }
        let mut start = try_vec(sizes.len() + 1, 0usize, "contact islands")?;
        for (k, &i) in by_size.iter().enumerate() {
            start[k + 1] = start[k] + sizes[i].0;
        }
        let mut order = try_vec(nc, 0usize, "contact islands")?;
        let mut fill = try_copy(&start, "contact islands")?;
        for c in 0..nc {
            let k = rank[island[c]];
            order[fill[k]] = c;
            fill[k] += 1;
        }
        Ok((order, start))
    }
}

/// A barrier for the threads of one broadcast: spins briefly, then yields (the machine may have
/// fewer free cores than threads, and a thread waiting in the kernel would cost a wake-up).
pub(crate) struct SpinBarrier {
    arrived: AtomicUsize,
    generation: AtomicUsize,
    n: usize,
    /// Set when a thread of the broadcast panicked: the others stop waiting (and panic in
    /// turn) instead of waiting forever for it.
    poisoned: std::sync::atomic::AtomicBool,
}

/// Poisons its barrier if the thread holding it unwinds.
pub(crate) struct PoisonOnPanic<'a>(pub &'a SpinBarrier);

impl Drop for PoisonOnPanic<'_> {
    fn drop(&mut self) {
        if std::thread::panicking() {
            self.0.poisoned.store(true, Ordering::Release);
        }
    }
}

impl SpinBarrier {
    pub fn new(n: usize) -> Self {
        SpinBarrier {
            arrived: AtomicUsize::new(0),
            generation: AtomicUsize::new(0),
            n,
            poisoned: std::sync::atomic::AtomicBool::new(false),
        }
    }

    pub fn wait(&self) {
        if self.n <= 1 {
            return;
        }
        let generation = self.generation.load(Ordering::Acquire);
        if self.arrived.fetch_add(1, Ordering::AcqRel) + 1 == self.n {
            self.arrived.store(0, Ordering::Relaxed);
            self.generation.fetch_add(1, Ordering::AcqRel);
            return;
        }
        let mut spins = 0u32;
        while self.generation.load(Ordering::Acquire) == generation {
            if self.poisoned.load(Ordering::Acquire) {
                panic!("another sweep thread panicked");
            }
            if spins < 2000 {
                std::hint::spin_loop();
                spins += 1;
            } else {
                std::thread::yield_now();
            }
        }
    }
}

type Job = dyn Fn(usize) + Sync;

/// The job of the current broadcast, its lifetime erased: valid until every helper has reported
/// back, which [`Pool::broadcast`] waits for before returning.
#[derive(Clone, Copy)]
struct JobPtr(*const Job);
// SAFETY: the job is Sync and outlives its use (see above).
unsafe impl Send for JobPtr {}

struct PoolState {
    generation: u64,
    job: Option<JobPtr>,
    pending: usize,
    panicked: bool,
}

struct PoolShared {
    state: Mutex<PoolState>,
    wake: Condvar,
    done: Condvar,
}

/// `threads - 1` helper threads kept for the life of the process; the calling thread is the
/// first worker of every broadcast.
pub(crate) struct Pool {
    threads: usize,
    shared: Arc<PoolShared>,
    /// One broadcast at a time (two host threads may solve at once with the same pool).
    running: Mutex<()>,
}

impl Pool {
    /// The process-wide pool of `threads` threads (created on first use); `None` for one thread.
    pub fn shared(threads: usize) -> Result<Option<Arc<Pool>>, Fc3dError> {
        if threads <= 1 {
            return Ok(None);
        }
        static POOLS: OnceLock<Mutex<Vec<Arc<Pool>>>> = OnceLock::new();
        let pools = POOLS.get_or_init(|| Mutex::new(Vec::new()));
        let mut pools = pools.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(p) = pools.iter().find(|p| p.threads == threads) {
            return Ok(Some(p.clone()));
        }
        let pool = Arc::new(Pool::spawn(threads)?);
        pools.push(pool.clone());
        Ok(Some(pool))
    }

    fn spawn(threads: usize) -> Result<Pool, Fc3dError> {
        let shared = Arc::new(PoolShared {
            state: Mutex::new(PoolState {
                generation: 0,
                job: None,
                pending: 0,
                panicked: false,
            }),
            wake: Condvar::new(),
            done: Condvar::new(),
        });
        for index in 1..threads {
            let shared = shared.clone();
            std::thread::Builder::new()
                .name(format!("fc3d-sweep-{index}"))
                .spawn(move || helper(&shared, index))
                .map_err(|e| {
                    Fc3dError::InvalidStructure(format!("cannot start sweep thread {index}: {e}"))
                })?;
        }
        Ok(Pool {
            threads,
            shared,
            running: Mutex::new(()),
        })
    }

    pub fn threads(&self) -> usize {
        self.threads
    }

    /// Runs `job(i)` on every thread `i` in `0..threads` (0 is the caller) and returns when all
    /// are done. A panic in a helper is raised again here.
    pub fn broadcast(&self, job: &(dyn Fn(usize) + Sync)) {
        let _running = self.running.lock().unwrap_or_else(|e| e.into_inner());
        // SAFETY: only the lifetime is erased; `job` outlives this call, and this call returns
        // only after every helper has finished with it (pending reaches 0).
        let short: *const (dyn Fn(usize) + Sync + '_) = job;
        let erased: *const Job = unsafe { std::mem::transmute(short) };
        {
            let mut s = self.shared.state.lock().unwrap_or_else(|e| e.into_inner());
            s.generation += 1;
            s.job = Some(JobPtr(erased));
            s.pending = self.threads - 1;
            s.panicked = false;
        }
        self.shared.wake.notify_all();
        let mine = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| job(0)));
        let mut s = self.shared.state.lock().unwrap_or_else(|e| e.into_inner());
        while s.pending > 0 {
            s = self.shared.done.wait(s).unwrap_or_else(|e| e.into_inner());
        }
        s.job = None;
        let helper_panicked = s.panicked;
        drop(s);
        if let Err(p) = mine {
            std::panic::resume_unwind(p);
        }
        if helper_panicked {
            panic!("a sweep thread panicked");
        }
    }
}

fn helper(shared: &PoolShared, index: usize) {
    let mut seen = 0u64;
    loop {
        let job = {
            let mut s = shared.state.lock().unwrap_or_else(|e| e.into_inner());
            while s.generation == seen {
                s = shared.wake.wait(s).unwrap_or_else(|e| e.into_inner());
            }
            seen = s.generation;
            s.job
        };
        let Some(JobPtr(job)) = job else { continue };
        // SAFETY: the broadcaster keeps the job alive until `pending` reaches 0.
        let ok =
            std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| unsafe { (*job)(index) }))
                .is_ok();
        let mut s = shared.state.lock().unwrap_or_else(|e| e.into_inner());
        s.panicked |= !ok;
        s.pending -= 1;
        if s.pending == 0 {
            shared.done.notify_all();
        }
    }
}

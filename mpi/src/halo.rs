//! The reactions a sweep exchanges: per colour, one message to and from each neighbour rank
//! that shares contacts of that colour, into buffers and requests allocated once per layout.

use std::time::Instant;

use crate::comm::{thread_cpu_seconds, Comm, Requests};
use crate::layout::Layout;
use fc3d::CResult;
use fc3d_core::error::try_vec;

/// One message: its peer, its colour (the tag), where its values sit in the buffer, and the
/// known indices of the contacts it carries.
struct Slot {
    rank: usize,
    colour: usize,
    offset: usize,
    contacts: Vec<usize>,
}

pub struct Halo {
    receives: Vec<Slot>,
    sends: Vec<Slot>,
    /// Message indices of each colour: `receive_first[k]..receive_first[k + 1]`.
    receive_first: Vec<usize>,
    send_first: Vec<usize>,
    receive_buffer: Vec<f64>,
    send_buffer: Vec<f64>,
    requests: Requests,
    /// Wall and CPU seconds spent waiting for messages since the last [`Halo::take_wait`] (MPI
    /// polls while it waits: CPU time too).
    waited: (f64, f64),
}

impl Halo {
    pub fn new(layout: &Layout) -> CResult<Halo> {
        let slots = |pick: &dyn Fn(&crate::layout::ColourStep) -> &Vec<crate::layout::Message>| {
            let mut slots = Vec::new();
            let mut first = vec![0];
            let mut offset = 0;
            for (colour, step) in layout.steps.iter().enumerate() {
                for m in pick(step) {
                    slots.push(Slot {
                        rank: m.rank,
                        colour,
                        offset,
                        contacts: m.contacts.clone(),
                    });
                    offset += 3 * m.contacts.len();
                }
                first.push(slots.len());
            }
            (slots, first, offset)
        };
        let (receives, receive_first, receive_len) = slots(&|s| &s.receives);
        let (sends, send_first, send_len) = slots(&|s| &s.sends);
        let requests = Requests::new(receives.len() + sends.len())?;
        Ok(Halo {
            receives,
            sends,
            receive_first,
            send_first,
            receive_buffer: try_vec(receive_len, 0.0, "the ghosts' reactions")?,
            send_buffer: try_vec(send_len, 0.0, "the boundary reactions")?,
            requests,
            waited: (0.0, 0.0),
        })
    }

    /// Messages and bytes this rank sends per sweep.
    pub fn sent_per_sweep(&self) -> (usize, usize) {
        (self.sends.len(), 8 * self.send_buffer.len())
    }

    /// Neighbour ranks (sent to or received from).
    pub fn neighbours(&self) -> usize {
        let mut ranks: Vec<usize> = self
            .sends
            .iter()
            .chain(&self.receives)
            .map(|s| s.rank)
            .collect();
        ranks.sort_unstable();
        ranks.dedup();
        ranks.len()
    }

    /// Contacts received per sweep.
    pub fn ghosts_received(&self) -> usize {
        self.receive_buffer.len() / 3
    }

    /// Wall and CPU seconds waited since the last call.
    pub fn take_wait(&mut self) -> (f64, f64) {
        std::mem::take(&mut self.waited)
    }

    /// Posts the receives of every colour of one sweep.
    pub fn post_receives(&mut self, comm: &Comm) -> CResult<()> {
        let base = self.receive_buffer.as_mut_ptr();
        for (k, s) in self.receives.iter().enumerate() {
            // SAFETY: the slots are disjoint ranges of the buffer, which is neither read nor
            // moved until request k is waited for (`wait_colour`).
            let buffer =
                unsafe { std::slice::from_raw_parts_mut(base.add(s.offset), 3 * s.contacts.len()) };
            unsafe { self.requests.receive(comm, buffer, s.rank, s.colour, k)? };
        }
        Ok(())
    }

    /// Packs the reactions of colour `colour`'s boundary contacts and posts their sends.
    pub fn send_colour(&mut self, comm: &Comm, colour: usize, r: &[f64]) -> CResult<()> {
        let n_receives = self.receives.len();
        for k in self.send_first[colour]..self.send_first[colour + 1] {
            let s = &self.sends[k];
            let out = &mut self.send_buffer[s.offset..s.offset + 3 * s.contacts.len()];
            for (o, &c) in out.chunks_exact_mut(3).zip(&s.contacts) {
                o.copy_from_slice(&r[3 * c..3 * c + 3]);
            }
            // SAFETY: this slot of the send buffer is not written again before `wait_sends`.
            let buffer = unsafe {
                std::slice::from_raw_parts(self.send_buffer.as_ptr().add(s.offset), out_len(s))
            };
            unsafe {
                self.requests
                    .send(comm, buffer, s.rank, s.colour, n_receives + k)?
            };
        }
        Ok(())
    }

    /// Waits for colour `colour`'s receives and writes the ghosts' reactions into `r`.
    pub fn wait_colour(&mut self, colour: usize, r: &mut [f64]) -> CResult<()> {
        let range = self.receive_first[colour]..self.receive_first[colour + 1];
        let (start, cpu) = (Instant::now(), thread_cpu_seconds());
        self.requests.wait(range.clone())?;
        self.waited.0 += start.elapsed().as_secs_f64();
        self.waited.1 += thread_cpu_seconds() - cpu;
        for s in &self.receives[range] {
            let values = &self.receive_buffer[s.offset..s.offset + 3 * s.contacts.len()];
            for (v, &c) in values.chunks_exact(3).zip(&s.contacts) {
                r[3 * c..3 * c + 3].copy_from_slice(v);
            }
        }
        Ok(())
    }

    /// Waits until every send of the sweep has left its buffer.
    pub fn wait_sends(&mut self) -> CResult<()> {
        let n = self.receives.len();
        let (start, cpu) = (Instant::now(), thread_cpu_seconds());
        self.requests.wait(n..n + self.sends.len())?;
        self.waited.0 += start.elapsed().as_secs_f64();
        self.waited.1 += thread_cpu_seconds() - cpu;
        Ok(())
    }

    /// Every ghost's reaction from its owner (before the first sweep).
    pub fn exchange_all(&mut self, comm: &Comm, colours: usize, r: &mut [f64]) -> CResult<()> {
        self.post_receives(comm)?;
        for k in 0..colours {
            self.send_colour(comm, k, r)?;
        }
        for k in 0..colours {
            self.wait_colour(k, r)?;
        }
        self.wait_sends()
    }
}

fn out_len(s: &Slot) -> usize {
    3 * s.contacts.len()
}

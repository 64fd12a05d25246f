//! The interface of a subdomain: which of its bodies have copies on other processes.
//!
//! Every process holds the bodies it owns and copies of the bodies of others that its contacts
//! touch. A body held by `m` processes is an interface body of multiplicity `m`: each copy
//! carries `1/m` of its mass (its inverse mass is multiplied by `m`), so that the average of
//! the copies' velocities is the velocity the whole body gets from the impulses of all its
//! contacts (Visseq et al., Comput. Mech. 49 (2012) 709, section 3).

use crate::comm::{exchange_by_rank, Communicator};

/// The shared bodies of one process and the processes it shares them with.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct InterfaceMap {
    /// Number of processes holding each local body (1: not shared).
    pub multiplicity: Vec<u32>,
    /// For each neighbour rank, in increasing order, the local indices of the bodies shared
    /// with it, in increasing global id (the order both sides use).
    pub neighbours: Vec<(usize, Vec<u32>)>,
}

impl InterfaceMap {
    /// Builds the map collectively (every rank calls it): `global_ids[b]` and `owners[b]` of
    /// each local body `b`, and `shared[b]`, false for bodies every process has identically
    /// (walls and other bodies whose velocity is imposed), which are never exchanged. Every
    /// rank must hold the bodies it owns; ids are below 2^53. With `among`, the messages go to
    /// those ranks only: they must include every owner of a copy held here and every holder of
    /// a copy of a body owned here (the partition's neighbours, see
    /// [`crate::comm::exchange_by_rank`]); else to every rank.
    pub fn build<C: Communicator + ?Sized>(
        comm: &C,
        global_ids: &[u64],
        owners: &[u32],
        shared: &[bool],
        among: Option<&[usize]>,
    ) -> Self {
        let (me, size) = (comm.rank(), comm.size());
        // Round 1: tell each owner which of its bodies this rank holds a copy of.
        let mut asks = vec![Vec::new(); size];
        for b in 0..global_ids.len() {
            if shared[b] && owners[b] as usize != me {
                asks[owners[b] as usize].push(global_ids[b] as f64);
            }
        }
        let asked = exchange_by_rank(comm, asks, among);
        // The owner lists the holders of each of its asked-for bodies: itself and the askers.
        let mut holders: std::collections::BTreeMap<u64, Vec<usize>> = Default::default();
        for (rank, ids) in asked.iter().enumerate() {
            if rank == me {
                continue;
            }
            for &id in ids {
                holders
                    .entry(id as u64)
                    .or_insert_with(|| vec![me])
                    .push(rank);
            }
        }
        // Round 2: the owner sends each holder `[id, m, rank_1..rank_m]` for the bodies it holds.
        let mut replies = vec![Vec::new(); size];
        for (id, ranks) in &holders {
            for &r in ranks {
                replies[r].push(*id as f64);
                replies[r].push(ranks.len() as f64);
                replies[r].extend(ranks.iter().map(|&x| x as f64));
            }
        }
        let answers = exchange_by_rank(comm, replies, among);
        // The holders of each interface body, by id: few next to the local bodies, so every
        // local body is looked up in this sorted list rather than hashed.
        let mut ranks_of: Vec<(u64, &[f64])> = Vec::new();
        for message in &answers {
            let mut k = 0;
            while k < message.len() {
                let (id, m) = (message[k] as u64, message[k + 1] as usize);
                ranks_of.push((id, &message[k + 2..k + 2 + m]));
                k += 2 + m;
            }
        }
        ranks_of.sort_unstable_by_key(|r| r.0);
        let mut multiplicity = vec![1u32; global_ids.len()];
        let mut by_rank: std::collections::BTreeMap<usize, Vec<(u64, u32)>> = Default::default();
        if !ranks_of.is_empty() {
            for (b, id) in global_ids.iter().enumerate().filter(|&(b, _)| shared[b]) {
                let Ok(k) = ranks_of.binary_search_by_key(id, |r| r.0) else {
                    continue;
                };
                let ranks = ranks_of[k].1;
                multiplicity[b] = ranks.len() as u32;
                for r in ranks.iter().map(|&x| x as usize).filter(|&r| r != me) {
                    by_rank.entry(r).or_default().push((*id, b as u32));
                }
            }
        }
        let neighbours = by_rank
            .into_iter()
            .map(|(r, mut list)| {
                list.sort_unstable();
                (r, list.into_iter().map(|(_, b)| b).collect())
            })
            .collect();
        InterfaceMap {
            multiplicity,
            neighbours,
        }
    }

    /// Whether local body `body` is shared with other processes.
    pub fn is_shared(&self, body: u32) -> bool {
        self.multiplicity.get(body as usize).is_some_and(|&m| m > 1)
    }

    /// Number of local bodies shared with other processes.
    pub fn shared_count(&self) -> usize {
        self.multiplicity.iter().filter(|&&m| m > 1).count()
    }
}

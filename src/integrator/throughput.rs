//! A pass's table of distinct camera throughputs. Gather records point into it instead of
//! carrying a spectrum each: paths that reach a medium or a diffuse surface with the same
//! throughput (every camera path entering fog directly has W = 1) share one entry.

use std::collections::HashMap;

/// Spectra of `n` bins, deduplicated by exact bit pattern. Lookups never allocate; a new entry
/// appends `n` floats (and a map slot).
#[derive(Default)]
pub struct ThroughputTable {
    n: usize,
    data: Vec<f32>,
    /// Bit hash -> first entry with that hash. A second spectrum with the same hash (a true
    /// collision) gets its own entry without a map slot: it just is not shared.
    index: HashMap<u64, u32>,
}

fn bit_hash(w: &[f32]) -> u64 {
    // FNV-1a over the 32-bit patterns: cheap, and exact-equality is all that matters.
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for x in w {
        h ^= x.to_bits() as u64;
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}

fn same_bits(a: &[f32], b: &[f32]) -> bool {
    a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())
}

impl ThroughputTable {
    pub fn new(n: usize) -> Self {
        Self {
            n,
            ..Self::default()
        }
    }

    /// Bins per entry.
    pub fn bins(&self) -> usize {
        self.n
    }

    /// Number of distinct entries.
    pub fn len(&self) -> usize {
        self.data.len().checked_div(self.n).unwrap_or(0)
    }

    pub fn is_empty(&self) -> bool {
        self.data.is_empty()
    }

    /// Index of `w` (its first `n` lanes), adding it if no entry has the same bits.
    pub fn insert(&mut self, w: &[f32]) -> u32 {
        let n = self.n;
        let w = &w[..n];
        let h = bit_hash(w);
        let at = self.len() as u32;
        match self.index.get(&h) {
            Some(&i) if same_bits(self.get(i), w) => return i,
            Some(_) => {}
            None => {
                self.index.insert(h, at);
            }
        }
        self.data.extend_from_slice(w);
        at
    }

    /// Entry `i` (`n` floats).
    #[inline]
    pub fn get(&self, i: u32) -> &[f32] {
        let a = i as usize * self.n;
        &self.data[a..a + self.n]
    }

    /// Adds every entry of `other` (same bin count), returning where each one went: merging
    /// batches in a fixed order keeps indices independent of the thread count.
    pub fn merge(&mut self, other: &ThroughputTable) -> Vec<u32> {
        if self.n == 0 {
            self.n = other.n;
        }
        (0..other.len() as u32)
            .map(|i| self.insert(other.get(i)))
            .collect()
    }

    /// The spectra alone (the lookup map is dropped).
    pub fn into_data(self) -> Vec<f32> {
        self.data
    }

    /// Bytes of the spectra (what a gather keeps).
    pub fn data_bytes(&self) -> usize {
        self.data.len() * 4
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equal_spectra_share_an_entry_and_merge_remaps() {
        let mut a = ThroughputTable::new(3);
        assert_eq!(a.insert(&[1.0, 1.0, 1.0]), 0);
        assert_eq!(a.insert(&[1.0, 0.5, 1.0]), 1);
        assert_eq!(a.insert(&[1.0, 1.0, 1.0]), 0);
        // -0.0 and 0.0 are different bits: kept apart (exactness over sharing).
        assert_eq!(a.insert(&[0.0, 0.0, 0.0]), 2);
        assert_eq!(a.insert(&[-0.0, 0.0, 0.0]), 3);
        assert_eq!(a.len(), 4);
        let mut b = ThroughputTable::new(3);
        b.insert(&[2.0, 2.0, 2.0]);
        b.insert(&[1.0, 0.5, 1.0]);
        let map = a.merge(&b);
        assert_eq!(map, vec![4, 1]);
        assert_eq!(a.get(4), &[2.0, 2.0, 2.0]);
        assert_eq!(a.data_bytes(), 5 * 3 * 4);
    }
}

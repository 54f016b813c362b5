//! Records as columns, the layout the lanes load from: rays, and whatever else a wave
//! keeps per ray for its lanes.

use super::{Lanes, RayOf, V3};
use crate::math::{Ray, Vec3};

/// The most lanes any width has.
const MAX_LANES: usize = 16;

/// Records of `K` numbers kept as columns, one per number, in blocks of `MAX_LANES` (16), so
/// that `N` records' first (or second, ...) numbers load as one row of lanes and adding a
/// record checks for room once a block.
#[derive(Clone, Debug)]
pub struct Columns<const K: usize> {
    blocks: Vec<[[f32; MAX_LANES]; K]>,
    len: usize,
}

impl<const K: usize> Default for Columns<K> {
    fn default() -> Self {
        Columns {
            blocks: Vec::new(),
            len: 0,
        }
    }
}

impl<const K: usize> Columns<K> {
    /// No records.
    pub fn clear(&mut self) {
        self.blocks.clear();
        self.len = 0;
    }

    /// The number of records.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Adds `record` at the end.
    #[inline]
    pub fn push(&mut self, record: [f32; K]) {
        let j = self.len % MAX_LANES;
        if j == 0 {
            // The lanes past the last record are zeros: for a ray, one of no direction,
            // hitting nothing.
            self.blocks.push([[0.0; MAX_LANES]; K]);
        }
        if let Some(block) = self.blocks.last_mut() {
            for (c, v) in block.iter_mut().zip(record) {
                c[j] = v;
            }
        }
        self.len += 1;
    }

    /// Adds `N` records at the end, given number by number (`N` divides `MAX_LANES` (16)):
    /// row by row where the records so far fill whole rows of `N`, else one by one.
    #[inline(always)]
    pub fn push_lanes<const N: usize>(&mut self, numbers: [Lanes<N>; K]) {
        let j = self.len % MAX_LANES;
        if !j.is_multiple_of(N) {
            for i in 0..N {
                self.push(numbers.map(|n| n.0[i]));
            }
            return;
        }
        if j == 0 {
            self.blocks.push([[0.0; MAX_LANES]; K]);
        }
        if let Some(block) = self.blocks.last_mut() {
            for (c, n) in block.iter_mut().zip(numbers) {
                c[j..j + N].copy_from_slice(&n.0);
            }
        }
        self.len += N;
    }

    /// Number `k` of record `i`.
    #[inline]
    pub fn get(&self, i: usize, k: usize) -> f32 {
        self.blocks[i / MAX_LANES][k][i % MAX_LANES]
    }

    /// Number `k` of records `i..i + N` (`i` a multiple of `N`, which divides
    /// `MAX_LANES` (16)); lanes past the last record hold zeros.
    #[inline(always)]
    pub fn lane<const N: usize>(&self, i: usize, k: usize) -> Lanes<N> {
        let j = i % MAX_LANES;
        let mut a = [0.0; N];
        a.copy_from_slice(&self.blocks[i / MAX_LANES][k][j..j + N]);
        Lanes(a)
    }

    /// Numbers `k..k + 3` of records `i..i + N` as vectors, as [`Columns::lane`].
    #[inline(always)]
    pub fn lanes3<const N: usize>(&self, i: usize, k: usize) -> V3<Lanes<N>> {
        V3 {
            x: self.lane(i, k),
            y: self.lane(i, k + 1),
            z: self.lane(i, k + 2),
        }
    }
}

/// Rays as columns: origin x, y, z, direction x, y, z, time.
#[derive(Clone, Debug, Default)]
pub struct RayColumns(Columns<7>);

impl RayColumns {
    /// No rays.
    pub fn clear(&mut self) {
        self.0.clear();
    }

    /// The number of rays.
    pub fn len(&self) -> usize {
        self.0.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// Adds `ray` at the end.
    #[inline]
    pub fn push(&mut self, ray: &Ray) {
        let (o, d) = (ray.origin, ray.dir);
        self.0.push([o.x, o.y, o.z, d.x, d.y, d.z, ray.time]);
    }

    /// Adds `N` rays at the end.
    #[inline(always)]
    pub fn push_lanes<const N: usize>(&mut self, rays: RayOf<Lanes<N>>) {
        let (o, d) = (rays.origin, rays.dir);
        self.0.push_lanes([o.x, o.y, o.z, d.x, d.y, d.z, rays.time]);
    }

    /// Ray `i`.
    #[inline]
    pub fn get(&self, i: usize) -> Ray {
        let c = |k: usize| self.0.get(i, k);
        Ray {
            origin: Vec3::new(c(0), c(1), c(2)),
            dir: Vec3::new(c(3), c(4), c(5)),
            time: c(6),
        }
    }

    /// Rays `i..i + N` (`i` a multiple of `N`, which divides `MAX_LANES` (16)). Lanes past
    /// the last ray hold zeros.
    #[inline(always)]
    pub fn lanes<const N: usize>(&self, i: usize) -> RayOf<Lanes<N>> {
        RayOf {
            origin: self.0.lanes3(i, 0),
            dir: self.0.lanes3(i, 3),
            time: self.0.lane(i, 6),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `N` records pushed as lanes are the records pushed one by one, wherever the list
    /// stands: at a row of `N`, or part way through one.
    fn push_lanes_is_push_n_times<const N: usize>() {
        for before in [0, 1, N - 1, N, 2 * N + 1, MAX_LANES - N, MAX_LANES] {
            let record = |i: usize| std::array::from_fn::<f32, 3, _>(|k| (i * 3 + k) as f32);
            let (mut one_by_one, mut in_lanes) = (Columns::<3>::default(), Columns::<3>::default());
            for i in 0..before {
                one_by_one.push(record(i));
                in_lanes.push(record(i));
            }
            for i in before..before + N {
                one_by_one.push(record(i));
            }
            in_lanes.push_lanes::<N>(std::array::from_fn(|k| {
                Lanes::from_fn(|i| record(before + i)[k])
            }));
            assert_eq!(in_lanes.len(), before + N);
            assert_eq!(
                in_lanes.blocks, one_by_one.blocks,
                "{N} lanes after {before}"
            );
        }
    }

    #[test]
    fn records_pushed_in_lanes_are_the_records_pushed_one_by_one() {
        push_lanes_is_push_n_times::<1>();
        push_lanes_is_push_n_times::<4>();
        push_lanes_is_push_n_times::<8>();
        push_lanes_is_push_n_times::<16>();
    }
}

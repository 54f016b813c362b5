//! Rays as columns, the layout the lanes load from.

use super::{Lanes, V3};
use crate::math::{Ray, Vec3};

/// The most lanes any width has.
const MAX_LANES: usize = 16;

/// Rays kept as columns, one per coordinate, in blocks of [`MAX_LANES`], so that `N` rays'
/// x (or y, ...) load as one row of lanes and adding a ray checks for room once a block.
#[derive(Clone, Debug, Default)]
pub struct RayColumns {
    // Origin x, y, z, direction x, y, z, time.
    blocks: Vec<[[f32; MAX_LANES]; 7]>,
    len: usize,
}

impl RayColumns {
    /// No rays.
    pub fn clear(&mut self) {
        self.blocks.clear();
        self.len = 0;
    }

    /// The number of rays.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Adds `ray` at the end.
    #[inline]
    pub fn push(&mut self, ray: &Ray) {
        let j = self.len % MAX_LANES;
        if j == 0 {
            // The lanes past the last ray are zeros: a ray of no direction, hitting nothing.
            self.blocks.push([[0.0; MAX_LANES]; 7]);
        }
        if let Some(block) = self.blocks.last_mut() {
            let values = [
                ray.origin.x,
                ray.origin.y,
                ray.origin.z,
                ray.dir.x,
                ray.dir.y,
                ray.dir.z,
                ray.time,
            ];
            for (c, v) in block.iter_mut().zip(values) {
                c[j] = v;
            }
        }
        self.len += 1;
    }

    /// Ray `i`.
    #[inline]
    pub fn get(&self, i: usize) -> Ray {
        let block = &self.blocks[i / MAX_LANES];
        let c = |k: usize| block[k][i % MAX_LANES];
        Ray {
            origin: Vec3::new(c(0), c(1), c(2)),
            dir: Vec3::new(c(3), c(4), c(5)),
            time: c(6),
        }
    }

    /// Rays `i..i + N` (`i` a multiple of `N`, which divides [`MAX_LANES`]), coordinate by
    /// coordinate: (origin, direction, time). Lanes past the last ray hold zeros.
    #[inline(always)]
    pub fn lanes<const N: usize>(&self, i: usize) -> (V3<Lanes<N>>, V3<Lanes<N>>, Lanes<N>) {
        let block = &self.blocks[i / MAX_LANES];
        let j = i % MAX_LANES;
        let load = |k: usize| {
            let mut a = [0.0; N];
            a.copy_from_slice(&block[k][j..j + N]);
            Lanes(a)
        };
        (
            V3 {
                x: load(0),
                y: load(1),
                z: load(2),
            },
            V3 {
                x: load(3),
                y: load(4),
                z: load(5),
            },
            load(6),
        )
    }
}

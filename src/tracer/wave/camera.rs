//! Level 0 of a wave: each sample's camera ray, its random numbers, its slot and its root.

use super::types::{Node, Rays, Root, Slot};
use crate::camera::CameraSample;
use crate::math::lanes::{LaneKernel, Lanes, Real, V3, is_finite};
use crate::math::rng::SobolLanes;
use crate::math::{Pattern, Ray, SampleStream};
use crate::optics::dispersion;
use crate::tracer::spectral::Wavelengths;
use crate::tracer::{Met, Stats, Tracer};

/// The camera rays of a wave, with each sample's random numbers after the camera's, into
/// its slots, roots and level 0: with the Sobol pattern, `N` at a time in lanes, the draws
/// and the rays; with the others (the sampling lecture's patterns), ray by ray.
pub(super) struct CameraRays<'a, 't> {
    pub(super) tracer: &'a Tracer<'t>,
    pub(super) samples: &'a [(u32, u32, u32)],
    pub(super) stats: &'a mut Stats,
    pub(super) slots: &'a mut Vec<Slot>,
    pub(super) roots: &'a mut Vec<Root>,
    pub(super) level: &'a mut Rays,
}

impl CameraRays<'_, '_> {
    /// A sample's slot (its stream `rng`, its camera ray's `weight`), and its root: its
    /// camera ray's node, if the ray can be traced (`ray` finite; `None`: not).
    #[inline(always)]
    fn push(&mut self, rng: SampleStream, ray: Option<&Ray>, weight: f32) {
        let node = ray.map(|ray| {
            let node = Node::new(self.slots.len() as u32, 0, 1.0, None);
            self.level.push(ray, node)
        });
        self.push_slot(rng, node, weight);
    }

    #[inline(always)]
    fn push_slot(&mut self, rng: SampleStream, root: Option<u32>, weight: f32) {
        self.stats.samples += 1;
        self.stats.camera_rays += root.is_some() as u64;
        self.roots.push(Root::One(root));
        self.slots.push(Slot {
            rng,
            weight,
            tree_rays: 0,
            rays: root.is_some() as u32,
            met: Met::default(),
        });
    }

    /// Sample `s` of pixel (x, y) through a lens whose glass disperses: its wavelengths
    /// drawn at the camera as the recursion draws them
    /// (`Tracer::sample_through_dispersive_lens`), and a camera ray traced out through the
    /// glass at each, a root carrying its wavelength.
    fn push_dispersed(&mut self, (x, y, s): (u32, u32, u32)) {
        let t = self.tracer;
        let (mut rng, cs) = t.camera_draw(x, y, s);
        let film = t.film_at(x, y, &cs);
        let slot = self.slots.len() as u32;
        let mut traced = 0;
        let mut root = |lambda: f32| {
            let (ray, weight) = t.frame.weighed_ray_at(film, cs.lens, cs.time, Some(lambda));
            let node = (weight > 0.0 && ray.origin.is_finite() && ray.dir.is_finite()).then(|| {
                traced += 1;
                self.level.push(&ray, Node::new(slot, 0, 1.0, Some(lambda)))
            });
            (node, weight)
        };
        let roots = match t.wavelengths(&mut rng) {
            Wavelengths::One(lambda) => {
                Root::Spectrum(root(lambda), dispersion::channel_weight(lambda))
            }
            Wavelengths::PerChannel(lambdas) => Root::PerChannel(lambdas.map(root)),
        };
        self.stats.samples += 1;
        self.stats.camera_rays += traced as u64;
        self.roots.push(roots);
        self.slots.push(Slot {
            rng,
            weight: 1.0,
            tree_rays: 0,
            rays: traced,
            met: Met::default(),
        });
    }
}

impl LaneKernel for CameraRays<'_, '_> {
    type Output = ();
    #[inline(always)]
    fn run<const N: usize>(mut self) {
        self.slots.clear();
        self.roots.clear();
        self.level.clear();
        let t = self.tracer;
        if t.frame.disperses() {
            // Each sample is three camera rays (or one at a wavelength of its own): made
            // one sample at a time.
            for &sample in self.samples {
                self.push_dispersed(sample);
            }
            return;
        }
        let sobol = t.params.pattern == Pattern::Sobol;
        let in_lanes = if sobol { self.samples.len() / N * N } else { 0 };
        let (chunks, rest) = self.samples.split_at(in_lanes);
        for chunk in chunks.chunks_exact(N) {
            let pixels = std::array::from_fn(|i| chunk[i].1 * t.width + chunk[i].0);
            let numbers = std::array::from_fn(|i| chunk[i].2);
            let mut lanes = SobolLanes::<N>::new(t.params.spp, t.seed_key, pixels, numbers);
            let cs = t.frame.draw_samples(&mut lanes);
            if let Some(real) = t.frame.real_lens() {
                // Through a real lens: its glass traced in lanes, the rays pushed one by
                // one (some are blocked).
                let film: [_; N] =
                    std::array::from_fn(|i| t.film_at(chunk[i].0, chunk[i].1, &cs[i]));
                let lens: [_; N] = std::array::from_fn(|i| cs[i].lens);
                let time: [_; N] = std::array::from_fn(|i| cs[i].time);
                for (i, (ray, weight)) in t
                    .frame
                    .weighed_rays(real, film, lens, time)
                    .iter()
                    .enumerate()
                {
                    let traced = *weight > 0.0 && ray.origin.is_finite() && ray.dir.is_finite();
                    self.push(lanes.stream(i), traced.then_some(ray), *weight);
                }
                continue;
            }
            let lane = |f: fn(&CameraSample) -> f32| Lanes::<N>::from_fn(|i| f(&cs[i]));
            let xy = (
                Lanes::from_fn(|i| chunk[i].0 as f32),
                Lanes::from_fn(|i| chunk[i].1 as f32),
            );
            let pixel = (lane(|c| c.pixel.x), lane(|c| c.pixel.y));
            let lens = (lane(|c| c.lens.x), lane(|c| c.lens.y));
            let rays = t.camera_ray_of(xy, pixel, lens, lane(|c| c.time));
            let finite = |v: V3<Lanes<N>>| is_finite(v.x) & is_finite(v.y) & is_finite(v.z);
            // Each stream is made where it is stored: an array of them built first and
            // copied out stalls on store-to-load forwarding.
            if Lanes::all(finite(rays.origin) & finite(rays.dir)) {
                // The usual case: the rays go to the level as they are, `N` at a time.
                let first = self.level.nodes.len() as u32;
                let slot = self.slots.len() as u32;
                self.level.rays.push_lanes(rays);
                let node = |i| Node::new(slot + i, 0, 1.0, None);
                self.level.nodes.extend((0..N as u32).map(node));
                // (Counted once for the `N`: an add to memory per sample waited on the last.)
                self.stats.samples += N as u64;
                self.stats.camera_rays += N as u64;
                self.roots
                    .extend((first..first + N as u32).map(|r| Root::One(Some(r))));
                self.slots.extend((0..N).map(|i| Slot {
                    rng: lanes.stream(i),
                    weight: 1.0,
                    tree_rays: 0,
                    rays: 1,
                    met: Met::default(),
                }));
            } else {
                for i in 0..N {
                    let ray = rays.get(i);
                    let traced = ray.origin.is_finite() && ray.dir.is_finite();
                    self.push(lanes.stream(i), traced.then_some(&ray), 1.0);
                }
            }
        }
        for &(x, y, s) in rest {
            let (rng, cs) = t.camera_draw(x, y, s);
            let (ray, weight) = t.camera_ray(x, y, &cs);
            let traced = weight > 0.0 && ray.origin.is_finite() && ray.dir.is_finite();
            self.push(rng, traced.then_some(&ray), weight);
        }
    }
}

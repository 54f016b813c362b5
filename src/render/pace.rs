//! How fast a generation refines now, for the status bar's time left. The cumulative
//! average it replaces ran up to 2x off: it left out the engine's time between passes
//! (sending each frame, estimating its noise), counted the first passes' overhead for
//! ever, and did not notice a neighbour finishing (an A/B view's other side) or the
//! machine's load changing.

use std::time::{Duration, Instant};

/// The pace of the newest passes: wall time per sample per pixel, the time between passes
/// included.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Pace {
    // When the last pass ended: the next pass's time runs from here (none after a pause
    // or at a generation's start, when it runs from the pass's own start).
    since: Option<Instant>,
    // Seconds per sample per pixel, each pass's weighing half (an exponential average:
    // the latest conditions count most, one pass's jitter is halved).
    per_spp: Option<f64>,
}

impl Pace {
    /// The next pass is timed from its own start (after a pause: the time paused is not
    /// refining).
    pub(super) fn pause(&mut self) {
        self.since = None;
    }

    /// A pass that began at `start` added `spp` samples per pixel and ended at `end`.
    pub(super) fn pass(&mut self, start: Instant, end: Instant, spp: u32) {
        let from = self.since.unwrap_or(start);
        let latest = end.duration_since(from).as_secs_f64() / spp.max(1) as f64;
        self.per_spp = Some(self.per_spp.map_or(latest, |old| 0.5 * (old + latest)));
        self.since = Some(end);
    }

    /// The time `remaining` samples per pixel take at the newest pace; none before a pass.
    pub(super) fn time_left(&self, remaining: u32) -> Option<Duration> {
        self.per_spp
            .map(|s| Duration::from_secs_f64(s * remaining as f64))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(t0: Instant, seconds: f64) -> Instant {
        t0 + Duration::from_secs_f64(seconds)
    }

    #[test]
    fn the_time_left_follows_the_newest_passes_and_counts_the_time_between_them() {
        let t0 = Instant::now();
        let mut pace = Pace::default();
        assert_eq!(pace.time_left(10), None, "nothing measured yet");
        // 4 spp in 0.8 s (0.2 s each), then 0.2 s sending the frame and 4 spp in 0.8 s
        // (0.25 s each, the frame counted): 0.225 s each on average, 1.8 s for 8.
        pace.pass(t0, at(t0, 0.8), 4);
        pace.pass(at(t0, 1.0), at(t0, 1.8), 4);
        let left = pace.time_left(8).unwrap().as_secs_f64();
        assert!((left - 1.8).abs() < 1e-9, "{left}");
        // Twice as fast from now (a neighbour finished): the estimate follows within passes.
        for i in 0..6 {
            let start = at(t0, 1.8 + i as f64 * 0.5);
            pace.pass(start, start + Duration::from_millis(500), 4);
        }
        let left = pace.time_left(8).unwrap().as_secs_f64();
        assert!((left - 1.0).abs() < 0.03, "{left}");
        // A pause is not refining.
        pace.pause();
        let resumed = at(t0, 60.0);
        pace.pass(resumed, resumed + Duration::from_millis(500), 4);
        let left = pace.time_left(8).unwrap().as_secs_f64();
        assert!((left - 1.0).abs() < 0.03, "{left}");
    }
}

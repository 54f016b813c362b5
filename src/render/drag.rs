//! A slider dragged at 60 Hz, simulated against the engine: what the window would show.

use super::{Engine, Frame};
use crate::params::Params;
use crossbeam_channel::RecvTimeoutError;
use std::time::{Duration, Instant};

/// What a drag showed, one entry per display frame.
#[derive(Clone, Debug, Default)]
pub struct DragReport {
    /// The time between changes.
    pub tick: Duration,
    /// Time from each change to the first frame of its generation; `None` where none came
    /// before the next change.
    pub first_frame: Vec<Option<Duration>>,
    /// The block side of the frame shown at each display frame (1: a full pass), as shown
    /// (a calmed picture's cells).
    pub block_shown: Vec<u32>,
    /// How many generations behind the newest the frame shown was.
    pub generations_behind: Vec<u64>,
    /// Whether the frame shown was calmed ([`Frame::calm`]).
    pub calmed: Vec<bool>,
    /// The share of the image's pixels each change started again, from the change's
    /// first frame ([`super::Progress::reached`]); `None` where none came.
    pub reached: Vec<Option<f32>>,
}

impl DragReport {
    /// One line: first-frame latency (median, worst, changes without a frame), the level
    /// shown (median, coarsest) and how many generations behind the shown frame was.
    pub fn summary(&self) -> String {
        let mut ms: Vec<f64> = self
            .first_frame
            .iter()
            .flatten()
            .map(|d| d.as_secs_f64() * 1e3)
            .collect();
        ms.sort_by(f64::total_cmp);
        let mut reached: Vec<f32> = self.reached.iter().flatten().copied().collect();
        reached.sort_by(f32::total_cmp);
        let mut blocks = self.block_shown.clone();
        blocks.sort_unstable();
        let (Some(median_ms), Some(median_block)) =
            (ms.get(ms.len() / 2), blocks.get(blocks.len() / 2))
        else {
            return "drag: no frames".into();
        };
        format!(
            "drag ({} changes, one every {} ms): first frame median {median_ms:.2} ms, worst \
             {:.2} ms, {} without one; level shown median {median_block}x{median_block}, \
             coarsest {b}x{b}; at most {} generation(s) behind; {:.0}% of them calmed; \
             {reached} of the pixels re-rendered per change (median)",
            self.first_frame.len(),
            self.tick.as_millis(),
            ms.last().copied().unwrap_or_default(),
            self.first_frame.len() - ms.len(),
            self.generations_behind.iter().max().copied().unwrap_or(0),
            100.0 * self.calmed.iter().filter(|&&c| c).count() as f64
                / self.calmed.len().max(1) as f64,
            b = blocks.last().copied().unwrap_or(0),
            reached = match reached.get(reached.len() / 2) {
                Some(r) => format!("{:.1}%", 100.0 * r),
                None => "none".into(),
            },
        )
    }
}

/// Changes `engine`'s parameters every `tick` for `duration` (`change(i)` gives the i-th
/// parameters), and records at the end of each tick the newest frame the engine sent, as
/// the window would show it.
pub fn simulate_drag(
    engine: &mut Engine,
    tick: Duration,
    duration: Duration,
    change: impl Fn(u32) -> Params,
) -> DragReport {
    let mut report = DragReport {
        tick,
        ..DragReport::default()
    };
    let mut shown: Option<Frame> = None;
    let start = Instant::now();
    let mut i = 0;
    while start.elapsed() < duration {
        let changed = Instant::now();
        engine.set_params(change(i));
        let generation = engine.generation();
        let (mut first, mut reached) = (None, None);
        let end = changed + tick;
        loop {
            let left = end.saturating_duration_since(Instant::now());
            match engine.frames().recv_timeout(left) {
                Ok(f) => {
                    if f.generation == generation && first.is_none() {
                        first = Some(changed.elapsed());
                        reached = Some(f.progress.reached);
                    }
                    shown = Some(f);
                }
                Err(RecvTimeoutError::Timeout) => break,
                Err(RecvTimeoutError::Disconnected) => return report,
            }
        }
        report.first_frame.push(first);
        report.reached.push(reached);
        if let Some(f) = &shown {
            report.block_shown.push(f.coarsest);
            report.generations_behind.push(generation - f.generation);
            report.calmed.push(f.calm.is_some());
        }
        i += 1;
    }
    report
}

//! How a generation refines after a change: a pyramid of previews, then full passes of a
//! bounded number of samples, each kept short so that frames keep coming. What the engine,
//! its controller and the slides rendered ahead share.

use std::time::Duration;

/// The resolution pyramid that opens every generation: previews with one sample per block
/// of these sides, each upsampled smoothly, before the full passes. The first costs 1/64
/// of a pass, so it shows within a frame; a change cancels the rest.
pub const PREVIEW_LEVELS: [u32; 3] = [8, 4, 2];
/// The most samples per pixel one pass adds.
pub const MAX_PASS_SPP: u32 = 16;
/// Passes are kept about this long, so that frames keep coming.
pub const PASS_BUDGET: Duration = Duration::from_millis(250);

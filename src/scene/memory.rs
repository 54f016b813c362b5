//! How much memory a scene may take, said before it is built: a scene that would pass the
//! limit is refused in one line rather than ending in an out-of-memory abort.
//!
//! The limit is the smaller of three quarters of the memory the machine (or its container)
//! has and half the address space a `ulimit -v` allows (threads reserve address space they
//! never touch), or `RAYLAB_MEMORY_LIMIT` (`512M`, `4G`, or bytes) where it is set.

use std::sync::OnceLock;

/// The variable that sets the limit.
const ENV: &str = "RAYLAB_MEMORY_LIMIT";

/// Peak bytes per triangle placed in a scene: the mesh (positions, normals, indices, the
/// edges intersection reads) and its share of the BVH and its build. Measured: a model of
/// 1,002,528 triangles placed 1, 2 and 4 times peaked at 368, 684 and 1,368 MB
/// (`/usr/bin/time -v raylab render`), 315 MB a placement; with margin.
pub const BYTES_PER_TRIANGLE: u64 = 340;

/// Peak bytes per pixel of a render: the film's sums (64 bytes a pixel), the pixels
/// handed to the encoder and the encoded file. Measured: 4096 × 4096 at 1 spp peaked at
/// 1,377 MB as a PNG and 1,459 MB as an EXR (82 and 87 bytes a pixel, scene included).
pub const BYTES_PER_PIXEL: u64 = 90;

/// The memory a scene may take, and where that figure comes from.
#[derive(Clone, Debug, PartialEq)]
pub struct MemoryLimit {
    /// Bytes.
    pub bytes: u64,
    /// Where the figure comes from, for a message.
    pub source: String,
}

/// The limit for this process (read once).
pub fn limit() -> &'static MemoryLimit {
    static LIMIT: OnceLock<MemoryLimit> = OnceLock::new();
    LIMIT.get_or_init(|| {
        let set = std::env::var(ENV).ok();
        match set.as_deref().map(parse_bytes) {
            Some(Some(bytes)) => MemoryLimit {
                bytes,
                source: ENV.into(),
            },
            _ => machine_limit(),
        }
    })
}

/// `512M`, `4G`, `1.5G`, `300K` or plain bytes.
pub fn parse_bytes(text: &str) -> Option<u64> {
    let text = text.trim();
    let (number, scale) = match text.char_indices().last()? {
        (i, 'k' | 'K') => (&text[..i], 1u64 << 10),
        (i, 'm' | 'M') => (&text[..i], 1 << 20),
        (i, 'g' | 'G') => (&text[..i], 1 << 30),
        (i, 't' | 'T') => (&text[..i], 1 << 40),
        _ => (text, 1),
    };
    let x: f64 = number.trim().parse().ok()?;
    let bytes = x * scale as f64;
    (x.is_finite() && x > 0.0 && bytes < u64::MAX as f64).then_some(bytes as u64)
}

/// What the machine allows: Linux says it in /proc and /sys; elsewhere no limit is known
/// and the system's own (swap, then refusal) applies.
fn machine_limit() -> MemoryLimit {
    let read = |path: &str| std::fs::read_to_string(path).ok();
    let physical = read("/proc/meminfo").and_then(|t| {
        let line = t.lines().find(|l| l.starts_with("MemTotal:"))?;
        let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
        Some(kb * 1024)
    });
    let container = read("/sys/fs/cgroup/memory.max").and_then(|t| t.trim().parse::<u64>().ok());
    let address_space = read("/proc/self/limits").and_then(|t| {
        let line = t.lines().find(|l| l.starts_with("Max address space"))?;
        line.split_whitespace().nth(3)?.parse::<u64>().ok()
    });
    let candidates = [
        physical.map(|b| (b / 4 * 3, "three quarters of the machine's memory")),
        container.map(|b| (b / 4 * 3, "three quarters of the container's memory")),
        address_space.map(|b| (b / 2, "half the address space ulimit -v allows")),
    ];
    candidates
        .into_iter()
        .flatten()
        .min_by_key(|(bytes, _)| *bytes)
        .map_or(
            MemoryLimit {
                bytes: u64::MAX,
                source: "no limit known on this system".into(),
            },
            |(bytes, source)| MemoryLimit {
                bytes,
                source: source.into(),
            },
        )
}

/// `bytes` for a reader: `3.3 GB`, `512 MB`, `262 kB`, `812 bytes`.
pub fn shown(bytes: u64) -> String {
    match bytes as f64 {
        b if b >= 1e9 => format!("{:.1} GB", b / 1e9),
        b if b >= 1e6 => format!("{:.0} MB", b / 1e6),
        b if b >= 1e3 => format!("{:.0} kB", b / 1e3),
        _ => format!("{bytes} bytes"),
    }
}

/// Refuses `bytes` (what `what` needs) beyond the limit, in one line that says how to
/// raise it.
pub fn check(bytes: u64, what: &str) -> Result<(), String> {
    let limit = limit();
    if bytes <= limit.bytes {
        return Ok(());
    }
    let advice = if limit.source == ENV {
        ""
    } else {
        "; set RAYLAB_MEMORY_LIMIT (e.g. 8G) to change it"
    };
    Err(format!(
        "{what} need about {}, more than raylab's limit of {} ({}){advice}",
        shown(bytes),
        shown(limit.bytes),
        limit.source
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_read_as_a_person_reads_them() {
        assert_eq!(shown(812), "812 bytes");
        assert_eq!(shown(262_144), "262 kB");
        assert_eq!(shown(512_000_000), "512 MB");
        assert_eq!(shown(3_300_000_000), "3.3 GB");
    }

    #[test]
    fn sizes_parse_with_their_units() {
        assert_eq!(parse_bytes("512M"), Some(512 << 20));
        assert_eq!(parse_bytes("1.5g"), Some(3 << 29));
        assert_eq!(parse_bytes(" 4096 "), Some(4096));
        for bad in ["", "G", "-1G", "0", "lots", "1e30T"] {
            assert_eq!(parse_bytes(bad), None, "{bad}");
        }
    }

    #[test]
    fn the_machine_limit_is_below_what_the_machine_has() {
        let limit = machine_limit();
        if cfg!(target_os = "linux") {
            assert!(limit.bytes < u64::MAX && limit.bytes > 0, "{limit:?}");
        }
        assert!(check(1, "one byte").is_ok());
        let e = check(u64::MAX, "everything").unwrap_err();
        assert!(e.starts_with("everything need about "), "{e}");
    }
}

//! Measured metals: the complex index of refraction η + iκ of real conductors, per RGB
//! channel, for `metal = "gold"` in scene files, `raylab fresnel --metal` and the Fresnel
//! plot.
//!
//! Source: the optical constants Mitsuba 3 ships (`mitsuba/data/ior/*.spd`, tabulated
//! from the luxpop.com database; nickel from Palik's Handbook of Optical Constants), as
//! Mitsuba 3.9.1 itself reduces them to RGB in its `scalar_rgb` variant. Reproduce with
//! `pip install mitsuba==3.9.1`, then in Python:
//!
//! ```text
//! import mitsuba as mi; mi.set_variant("scalar_rgb")
//! p = mi.traverse(mi.load_dict({"type": "conductor", "material": "Au"}))
//! print(p["eta.value"], p["k.value"])
//! ```

use crate::math::Color;

/// A metal's optical constants per RGB channel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Metal {
    /// The name used in scene files and on the command line.
    pub name: &'static str,
    /// Its chemical symbol (Mitsuba's preset name).
    pub symbol: &'static str,
    /// Real part of the index of refraction, R, G, B.
    pub eta: [f32; 3],
    /// Extinction coefficient, R, G, B.
    pub k: [f32; 3],
}

impl Metal {
    /// η as a colour.
    pub fn eta(&self) -> Color {
        Color::from_array(self.eta)
    }

    /// κ as a colour.
    pub fn k(&self) -> Color {
        Color::from_array(self.k)
    }
}

/// Every measured metal, gold first.
pub const METALS: [Metal; 7] = [
    Metal {
        name: "gold",
        symbol: "Au",
        eta: [0.143036, 0.375307, 1.44205],
        k: [3.983, 2.38556, 1.60336],
    },
    Metal {
        name: "silver",
        symbol: "Ag",
        eta: [0.155276, 0.116728, 0.138388],
        k: [4.82835, 3.12222, 2.1469],
    },
    Metal {
        name: "copper",
        symbol: "Cu",
        eta: [0.201005, 0.92375, 1.10222],
        k: [3.91326, 2.45305, 2.14209],
    },
    Metal {
        name: "aluminium",
        symbol: "Al",
        eta: [1.6575, 0.880405, 0.521244],
        k: [9.22381, 6.2695, 4.837],
    },
    Metal {
        name: "chromium",
        symbol: "Cr",
        eta: [4.36967, 2.91651, 1.6549],
        k: [5.20655, 4.23131, 3.7547],
    },
    Metal {
        name: "nickel",
        symbol: "Ni",
        eta: [2.3673, 1.66337, 1.46708],
        k: [4.49881, 3.05015, 2.34544],
    },
    Metal {
        name: "tungsten",
        symbol: "W",
        eta: [4.37082, 3.30025, 2.99841],
        k: [3.50064, 2.60487, 2.27323],
    },
];

/// The metal called `name` (or by its symbol; "aluminum" too), ignoring case.
pub fn metal(name: &str) -> Option<&'static Metal> {
    let name = name.trim();
    let name = if name.eq_ignore_ascii_case("aluminum") {
        "aluminium"
    } else {
        name
    };
    METALS
        .iter()
        .find(|m| m.name.eq_ignore_ascii_case(name) || m.symbol.eq_ignore_ascii_case(name))
}

/// The metals' names, comma separated, for messages.
pub fn metal_names() -> String {
    METALS.map(|m| m.name).join(", ")
}

/// The metal called `name`, or the message refusing it (naming the known metals), as
/// scene files and the command line give it.
pub fn find_metal(name: &str) -> Result<&'static Metal, String> {
    metal(name).ok_or_else(|| format!("unknown metal `{name}` (known: {})", metal_names()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optics::fresnel_conductor;

    #[test]
    fn names_and_symbols_find_their_metal() {
        for m in &METALS {
            assert_eq!(metal(m.name), Some(m));
            assert_eq!(metal(&m.symbol.to_uppercase()), Some(m));
        }
        assert_eq!(metal("Aluminum").map(|m| m.symbol), Some("Al"));
        assert_eq!(metal("brass"), None);
    }

    #[test]
    fn metals_look_like_themselves_head_on() {
        // Normal-incidence reflectance ((η−1)² + κ²)/((η+1)² + κ²) per channel: silver and
        // aluminium bright and nearly neutral, gold and copper red above blue.
        let r0 = |name: &str| {
            let m = metal(name).unwrap();
            std::array::from_fn::<f32, 3, _>(|c| fresnel_conductor(1.0, 1.0, m.eta[c], m.k[c]).2)
        };
        for name in ["silver", "aluminium"] {
            let r = r0(name);
            assert!(r.iter().all(|&v| v > 0.85), "{name}: {r:?}");
        }
        for name in ["gold", "copper"] {
            let r = r0(name);
            assert!(r[0] > 0.9 && r[2] < 0.65, "{name}: {r:?}");
        }
    }
}

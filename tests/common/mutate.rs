//! The fuzzer's mutations: splice, cut and insert lines, put a byte-order mark first, and
//! replace numbers with values that broke parsers before.

use crate::common::Rng;

/// Values that have broken parsers and renderers before.
const NUMBERS: &[&str] = &[
    "0",
    "-0",
    "-1",
    "1e20",
    "-1e20",
    "3e38",
    "1e-40",
    "nan",
    "inf",
    "-inf",
    "NaN",
    "16385",
    "4294967295",
    "18446744073709551616",
    "0.5",
    "180",
    "1e6",
    "999999",
    "65",
    "\"x\"",
    "",
    "[]",
    "[1, 2]",
    "{}",
    "true",
    // Beyond f32 (which once became infinity silently), beyond f64, below f32's least.
    "1e39",
    "-1e39",
    "3.5e38",
    "1e309",
    "1e-50",
];

/// Pieces of each format, spliced in as lines.
const LINES: &[&str] = &[
    "[[sphere]]",
    "[[quad]]",
    "[[plane]]",
    "[[box]]",
    "[[mesh]]",
    "[camera]",
    "[params]",
    "[image]",
    "radius = 1e30",
    "center = [0, 0, 0]",
    "file = \"models/prism.obj\"",
    // A second placement of a model: shared by both (an instance each).
    "[[mesh]]\nfile = \"models/bunny.obj\"\nscale = 0.1\nrotate = [10, 20, 30]",
    "file = \"/dev/zero\"",
    "scale = 1e30",
    "velocity = [3e38, 0, 0]",
    "width = 0",
    "max_depth = 64",
    "min_weight = 0",
    "aperture = 100",
    "focus_distance = 3e38",
    "v 1e20 0 0",
    "v nan 0 0",
    "f 1 2 99",
    "f -9 1 2",
    "vt 0",
    "vn 0 0",
    "mtllib m.mtl",
    "usemtl a",
    "newmtl a",
    "Kd 1",
    "Kd",
    "Ke 1 2",
    "Ns",
    "illum",
    "metal = \"gold\"",
    "abbe = 1e-40",
    "polarizer = 90",
    "transport = \"transmissive_shadows\"",
    "transport = \"path\"",
    "transport = \"photons\"",
    "Pm 1.0",
    "\"polarizer\": 45,",
    "\"samples\": 0,",
    "\"width\": 0,",
    "\"camera\": {\"position\": [0,0,0], \"look_at\": [0,0,0], \"up\": [0,1,0], \"fov_deg\": 0},",
];

/// UTF-8's byte-order mark, which Windows editors put first.
pub const BOM: &str = "\u{feff}";

pub fn mutate(text: &str, rng: &mut Rng) -> String {
    // One case in eight starts with a byte-order mark, as if saved by a Windows editor.
    let bom = if rng.below(8) == 0 { BOM } else { "" };
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    for _ in 0..1 + rng.below(4) {
        let i = rng.below(lines.len());
        match rng.below(7) {
            0 if !lines.is_empty() => {
                lines.remove(i);
            }
            1 if !lines.is_empty() => {
                let line = lines[i].clone();
                lines.insert(rng.below(lines.len()), line);
            }
            2 => lines.insert(i.min(lines.len()), rng.pick(LINES).to_string()),
            3 if !lines.is_empty() => lines[i] = replace_a_number(&lines[i], rng),
            4 if !lines.is_empty() => {
                // Cut a line short, or drop a character from it.
                let chars: Vec<char> = lines[i].chars().collect();
                let cut = rng.below(chars.len() + 1);
                lines[i] = chars[..cut].iter().collect();
            }
            5 => lines.truncate(i),
            _ if !lines.is_empty() => {
                let junk = *rng.pick(&['"', '[', ']', '{', '}', '=', ',', '\n', '\0', 'é', '#']);
                let at = rng.below(lines[i].chars().count() + 1);
                let mut chars: Vec<char> = lines[i].chars().collect();
                chars.insert(at, junk);
                lines[i] = chars.into_iter().collect();
            }
            _ => lines.push(rng.pick(LINES).to_string()),
        }
    }
    format!("{bom}{}", lines.join("\n"))
}

/// The line with one of its numbers replaced by an interesting value.
fn replace_a_number(line: &str, rng: &mut Rng) -> String {
    let spans: Vec<(usize, usize)> = {
        let b = line.as_bytes();
        let mut spans = Vec::new();
        let mut i = 0;
        while i < b.len() {
            if b[i].is_ascii_digit() || b[i] == b'-' {
                let start = i;
                while i < b.len() && (b[i].is_ascii_alphanumeric() || b"-+.".contains(&b[i])) {
                    i += 1;
                }
                spans.push((start, i));
            } else {
                i += 1;
            }
        }
        spans
    };
    if spans.is_empty() {
        return format!("{line} {}", rng.pick(NUMBERS));
    }
    let (s, e) = *rng.pick(&spans);
    format!("{}{}{}", &line[..s], rng.pick(NUMBERS), &line[e..])
}

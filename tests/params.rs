//! The parameter table: docs/parameters.md documents exactly it, every parameter changes the image (or,
//! for display-only ones, only the display), and its ranges are what `--set` enforces.
// Its helpers unwrap as its tests do: a failure there fails the test (clippy.toml allows
// unwrap in #[test] functions only).
#![allow(clippy::unwrap_used)]

mod common;

use raylab::math::Color;
use raylab::params::{Kind, Params, TABLE, markdown_table};
use raylab::render::{render, to_srgba8};
use raylab::scene::Scene;

#[test]
fn the_docs_hold_the_parameter_table_exactly() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/parameters.md");
    // A checkout may end lines with CR LF; the table is written with LF.
    let docs = std::fs::read_to_string(path)
        .expect("docs/parameters.md")
        .replace("\r\n", "\n");
    let table = markdown_table();
    assert!(
        docs.contains(&table),
        "docs/parameters.md's table differs from the table in src/params/table.rs; \
         paste the output of `raylab params --markdown`:\n{table}"
    );
}

/// Where each parameter shows: a built-in scene, parameters set first, and two values.
fn case(
    name: &str,
) -> (
    &'static str,
    &'static [(&'static str, &'static str)],
    &'static str,
    &'static str,
) {
    match name {
        "spp" => ("default", &[], "1", "4"),
        "pattern" => ("default", &[], "random", "sobol"),
        "seed" => ("soft-shadows", &[], "0", "1"),
        "noise_target" => ("soft-shadows", &[("spp", "32")], "off", "5"),
        "ior" => ("glass", &[], "1.2", "1.8"),
        "abbe" => ("dispersion", &[], "0", "20"),
        "roughness" => ("glass", &[], "0", "0.3"),
        "fresnel" => ("glazed", &[], "constant", "exact"),
        "constant_reflectance" => ("glazed", &[("fresnel", "constant")], "0.1", "0.5"),
        "absorption_scale" => ("glass", &[], "0", "3"),
        "tree" => ("glass", &[], "split", "stochastic"),
        "transport" => ("default", &[], "whitted", "transmissive_shadows"),
        "max_depth" => ("glass", &[], "1", "8"),
        "min_weight" => ("ray-tree", &[], "0", "0.5"),
        "light_size" => ("soft-shadows", &[], "0", "2"),
        "phong_exponent" => ("glossy", &[], "5", "5000"),
        "lens" => ("depth-of-field", &[], "thin", "double-gauss-50"),
        "lens_dispersion" => ("real-lens", &[("lens", "singlet-50")], "off", "on"),
        "aperture" => ("depth-of-field", &[], "0", "0.3"),
        "focus_distance" => ("depth-of-field", &[("aperture", "0.2")], "3", "9"),
        "shutter_open" => ("motion-blur", &[("shutter", "0")], "0", "0.8"),
        "shutter" => ("motion-blur", &[], "0", "0.5"),
        "polarizer" => ("glazed", &[], "none", "90"),
        "exposure" => ("default", &[], "0", "2"),
        other => panic!("no scene shows parameter `{other}`: add a case here"),
    }
}

fn image(scene: &Scene, params: &Params) -> Vec<Color> {
    render(scene, params, 96, 54, &())
        .unwrap()
        .0
        .pixels()
        .collect()
}

#[test]
fn every_parameter_changes_the_image_and_display_only_ones_only_the_display() {
    for spec in TABLE {
        let (scene_name, setup, a, b) = case(spec.name);
        let scene = Scene::load(scene_name).unwrap();
        let mut base = Params {
            spp: 2,
            ..scene.params.clone()
        };
        for (n, v) in setup {
            base.set(n, v).unwrap();
        }
        let with = |v: &str| {
            let mut p = base.clone();
            p.set(spec.name, v)
                .unwrap_or_else(|e| panic!("{}={v}: {e}", spec.name));
            p
        };
        let (pa, pb) = (with(a), with(b));
        let (ia, ib) = (image(&scene, &pa), image(&scene, &pb));
        if spec.display_only {
            assert!(pa.same_image(&pb), "{}: display-only", spec.name);
            assert!(ia == ib, "{} changes the render", spec.name);
            assert!(
                to_srgba8(&ia, pa.exposure) != to_srgba8(&ib, pb.exposure),
                "{} changes nothing shown",
                spec.name
            );
        } else {
            assert!(!pa.same_image(&pb), "{}", spec.name);
            assert!(
                ia != ib,
                "{}={a} and {b} render the same image on {scene_name}",
                spec.name
            );
        }
    }
}

#[test]
fn set_accepts_each_range_and_refuses_just_outside_it() {
    for spec in TABLE {
        let mut p = Params::default();
        match spec.kind {
            Kind::Count { min, max } => {
                p.set(spec.name, &min.to_string()).unwrap();
                if max < u64::MAX {
                    p.set(spec.name, &max.to_string()).unwrap();
                    assert!(
                        p.set(spec.name, &(max + 1).to_string()).is_err(),
                        "{}",
                        spec.name
                    );
                }
                if min > 0 {
                    assert!(
                        p.set(spec.name, &(min - 1).to_string()).is_err(),
                        "{}",
                        spec.name
                    );
                }
            }
            Kind::Number { min, max, open_min } => {
                let inside = if open_min { min + 0.5 } else { min };
                p.set(spec.name, &inside.to_string()).unwrap();
                if max.is_finite() {
                    p.set(spec.name, &max.to_string()).unwrap();
                    assert!(
                        p.set(spec.name, &(max * 1.01 + 0.01).to_string()).is_err(),
                        "{}",
                        spec.name
                    );
                }
                let below = if open_min { min } else { min - 0.01 };
                let err = p.set(spec.name, &below.to_string()).unwrap_err();
                assert!(err.to_string().contains(spec.name), "{err}");
                assert!(p.set(spec.name, "NaN").is_err(), "{}", spec.name);
            }
            Kind::Choice(choices) => {
                for c in choices {
                    let w = c.word;
                    p.set(spec.name, w)
                        .unwrap_or_else(|e| panic!("{}={w}: {e}", spec.name));
                    assert_eq!(p.value_text(spec.name).as_deref(), Some(w));
                }
                assert!(p.set(spec.name, "nonsense").is_err(), "{}", spec.name);
            }
            Kind::WordOrNumber { word, min, max } => {
                p.set(spec.name, &min.to_string()).unwrap();
                p.set(spec.name, &max.to_string()).unwrap();
                assert_eq!(p.value_text(spec.name), Some(max.to_string()));
                p.set(spec.name, word).unwrap();
                assert_eq!(p.value_text(spec.name).as_deref(), Some(word));
                for bad in [
                    &(max + 1.0).to_string(),
                    &(min - 1.0).to_string(),
                    "nonsense",
                ] {
                    let err = p.set(spec.name, bad).unwrap_err();
                    assert!(err.to_string().contains(spec.name), "{err}");
                }
            }
        }
    }
}

#[test]
fn the_shutter_must_close_within_the_frame() {
    let mut p = Params::default();
    p.set("shutter_open", "0.6").unwrap();
    let err = p.set("shutter", "0.5").unwrap_err().to_string();
    assert!(err.contains("1 − shutter_open"), "{err}");
    p.set("shutter", "0.4").unwrap();
}

#[test]
fn a_scene_files_params_refuse_nan_and_infinity_at_the_value() {
    let d = tempfile::tempdir().unwrap();
    let dir = d.path();
    let reals = raylab::params::TABLE
        .iter()
        .filter(|s| matches!(s.kind, Kind::Number { .. } | Kind::WordOrNumber { .. }));
    let mut checked = 0;
    for spec in reals {
        for value in ["nan", "inf", "-inf", "+nan"] {
            let (name, column) = (spec.name, spec.name.len() + 4);
            std::fs::write(
                dir.join("s.toml"),
                format!(
                    "[camera]\nposition = [0.0, 1.0, 5.0]\nlook_at = [0.0, 1.0, 0.0]\n[params]\n{name} = {value}\n"
                ),
            )
            .unwrap();
            common::fails(
                &["render", "s.toml", "-o", "x.png", "--size", "4x4"],
                dir,
                &format!("s.toml:5:{column}: in [params]: bad value for `{name}`: "),
            );
            checked += 1;
        }
    }
    // 15 real parameters (8 of them optional: on 10fbafe the 7 it had took NaN and
    // infinity as "unset").
    assert_eq!(checked, 15 * 4);
    assert!(!dir.join("x.png").exists(), "nothing rendered");
}

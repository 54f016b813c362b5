//! raylab among the tools its users bring: tev (`render --tev`), `RUST_LOG`, and the
//! build without the window (`--no-default-features`).
// Its helpers unwrap as its tests do: a failure there fails the test (clippy.toml allows
// unwrap in #[test] functions only).
#![allow(clippy::unwrap_used)]

mod common;

use common::{raylab, stderr};

/// `render --tev=HOST:PORT` streams each pass into tev: a listener standing in for tev
/// decodes its messages as tev does; the image they leave is the one written, bit for bit.
#[test]
fn render_streams_each_pass_into_tev_and_leaves_the_image_written() {
    use std::io::Read;
    let listener = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let address = listener.local_addr().unwrap();
    let tev = std::thread::spawn(move || {
        let (mut stream, _) = listener.accept().unwrap();
        let mut bytes = Vec::new();
        stream.read_to_end(&mut bytes).unwrap();
        bytes
    });
    let dir = tempfile::tempdir().unwrap();
    let o = raylab(
        &[
            "render",
            "glass",
            "--size",
            "40x30",
            "--spp",
            "8",
            &format!("--tev={address}"),
            "-o",
            "t.exr",
        ],
        dir.path(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let bytes = tev.join().unwrap();
    // Decoded as tev reads them: u32 length (itself included), u8 type, fields.
    let mut at = 0;
    let mut image: Vec<f32> = Vec::new();
    let (mut creates, mut rows_updated) = (0, 0);
    let take = |n: usize, at: &mut usize| {
        let s = &bytes[*at..*at + n];
        *at += n;
        s.to_vec()
    };
    let i32_at = |b: &[u8]| i32::from_le_bytes(b.try_into().unwrap());
    while at < bytes.len() {
        let start = at;
        let len = u32::from_le_bytes(take(4, &mut at).try_into().unwrap()) as usize;
        let kind = take(1, &mut at)[0];
        let _focus = take(1, &mut at)[0];
        let string = |at: &mut usize| {
            let end = bytes[*at..].iter().position(|&b| b == 0).unwrap();
            let s = String::from_utf8(bytes[*at..*at + end].to_vec()).unwrap();
            *at += end + 1;
            s
        };
        assert_eq!(string(&mut at), "t.exr", "the image is named as the file");
        match kind {
            4 => {
                creates += 1;
                let (w, h, n) = (
                    i32_at(&take(4, &mut at)),
                    i32_at(&take(4, &mut at)),
                    i32_at(&take(4, &mut at)),
                );
                assert_eq!((w, h, n), (40, 30, 3));
                let names: Vec<String> = (0..3).map(|_| string(&mut at)).collect();
                assert_eq!(names, ["R", "G", "B"]);
                image = vec![-1.0; 40 * 30 * 3];
            }
            6 => {
                assert_eq!(i32_at(&take(4, &mut at)), 3);
                let names: Vec<String> = (0..3).map(|_| string(&mut at)).collect();
                assert_eq!(names, ["R", "G", "B"]);
                let r: Vec<i32> = (0..4).map(|_| i32_at(&take(4, &mut at))).collect();
                let (x, y, w, h) = (r[0] as usize, r[1] as usize, r[2] as usize, r[3] as usize);
                let offsets_strides: Vec<i64> = (0..6)
                    .map(|_| i64::from_le_bytes(take(8, &mut at).try_into().unwrap()))
                    .collect();
                assert_eq!(offsets_strides, [0, 1, 2, 3, 3, 3]);
                for row in 0..h {
                    for col in 0..w {
                        for c in 0..3 {
                            let v = f32::from_le_bytes(take(4, &mut at).try_into().unwrap());
                            image[((y + row) * 40 + x + col) * 3 + c] = v;
                        }
                    }
                }
                rows_updated += h;
            }
            other => panic!("message type {other}"),
        }
        assert_eq!(at - start, len, "the length is the message's");
    }
    assert_eq!(creates, 1);
    // Passes of 1, 1, 2 and 4 samples: the whole image after each.
    assert_eq!(rows_updated, 4 * 30);
    let written = raylab::render::compare::LinearImage::read(&dir.path().join("t.exr")).unwrap();
    let streamed: Vec<f32> = written
        .pixels
        .iter()
        .flat_map(|p| [p.x, p.y, p.z])
        .collect();
    assert_eq!(
        image.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
        streamed.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
        "the last pass streamed is the image written"
    );
    // Nobody listening: one line naming the address, before any rendering.
    let closed = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let gone = closed.local_addr().unwrap();
    drop(closed);
    let o = raylab(
        &["render", "glass", &format!("--tev={gone}"), "-o", "u.png"],
        dir.path(),
    );
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.starts_with(&format!("error: tev at {gone}: ")), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(!dir.path().join("u.png").exists());
}

/// RUST_LOG turns on the log of what raylab does, on stderr with the time since start;
/// without it the commands say only what they say.
#[test]
fn rust_log_logs_what_raylab_does_and_nothing_without_it() {
    let dir = tempfile::tempdir().unwrap();
    let run = |log: Option<&str>| {
        let mut c = std::process::Command::new(env!("CARGO_BIN_EXE_raylab"));
        c.current_dir(dir.path()).args([
            "render", "glass", "--size", "16x9", "--spp", "1", "-q", "-o", "a.png",
        ]);
        match log {
            Some(filter) => c.env("RUST_LOG", filter),
            None => c.env_remove("RUST_LOG"),
        };
        let o = c.output().unwrap();
        assert!(o.status.success(), "{}", stderr(&o));
        stderr(&o)
    };
    let err = run(Some("debug"));
    let lines: Vec<&str> = err.lines().collect();
    assert!(
        lines
            .iter()
            .any(|l| l.contains("DEBUG raylab::scene: builtin:glass: loaded in")),
        "{err}"
    );
    assert!(
        lines
            .iter()
            .any(|l| l.contains("INFO  raylab::math::lanes::width: SIMD: ")),
        "{err}"
    );
    // Each line starts with the seconds since start.
    for l in &lines {
        let t: f64 = l.split_whitespace().next().unwrap().parse().unwrap();
        assert!((0.0..60.0).contains(&t), "{l}");
    }
    assert!(
        !run(Some("warn")).contains("SIMD"),
        "info is not logged at warn"
    );
    assert_eq!(run(None), "", "nothing is logged without RUST_LOG");
}

/// Built without the window (`--no-default-features`): `raylab` alone says so in one
/// line and what works instead; the commands work.
#[cfg(not(feature = "gui"))]
#[test]
fn without_the_window_raylab_says_so_and_its_commands_work() {
    let dir = tempfile::tempdir().unwrap();
    let o = raylab(&[], dir.path());
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(
        err.contains("without its window") && err.contains("raylab render"),
        "{err}"
    );
    let render = [
        "render", "default", "--size", "32x18", "--spp", "1", "-o", "a.png",
    ];
    let o = raylab(&render, dir.path());
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(dir.path().join("a.png").is_file());
}

/// The window streams its image into tev from the start with `raylab --tev`, and View >
/// Stream to tev turns it off: a listener standing in for tev receives the image made at
/// the render's size, then its pixels.
#[cfg(feature = "gui")]
#[test]
fn the_window_streams_its_image_into_tev_until_turned_off() {
    #[path = "common/window.rs"]
    mod window;
    use std::io::Read;
    let listener = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let address = listener.local_addr().unwrap().to_string();
    // Reads messages until the first update and says what came: the create's name, width
    // and height, and the update's name; then holds the connection until the window lets
    // it go (tev keeps listening), and closes (tev quits).
    let (said, heard) = std::sync::mpsc::channel();
    let tev = std::thread::spawn(move || {
        let (mut stream, _) = listener.accept().unwrap();
        let mut created = None;
        loop {
            let mut len = [0u8; 4];
            if stream.read_exact(&mut len).is_err() {
                return; // the window closed the stream
            }
            let mut m = vec![0u8; u32::from_le_bytes(len) as usize - 4];
            stream.read_exact(&mut m).unwrap();
            let name_end = 2 + m[2..].iter().position(|&b| b == 0).unwrap();
            let name = String::from_utf8(m[2..name_end].to_vec()).unwrap();
            let int = |at: usize| i32::from_le_bytes(m[at..at + 4].try_into().unwrap());
            match m[0] {
                4 => created = Some((name, int(name_end + 1), int(name_end + 5))),
                6 => {
                    let _ = said.send((created.clone(), name));
                }
                other => panic!("message type {other}"),
            }
        }
    });
    let dir = tempfile::tempdir().unwrap();
    let options = raylab::app::AppOptions {
        scene: Some("glass".into()),
        snapshot_dir: dir.path().to_path_buf(),
        threads: Some(1),
        persist: false,
        tev: Some(address),
        ..Default::default()
    };
    let mut h = egui_kittest::Harness::builder()
        .with_size(egui::vec2(1280.0, 800.0))
        .build_eframe(move |cc| raylab::app::RaylabApp::new(cc, options.clone()).unwrap());
    assert!(h.state().streams_to_tev());
    let first = std::cell::RefCell::new(None);
    window::step_until(&mut h, "an image streamed", |_| {
        let mut f = first.borrow_mut();
        if f.is_none() {
            *f = heard.try_recv().ok();
        }
        f.is_some()
    });
    let (created, updated) = first.into_inner().unwrap();
    let (w, h_) = h.state().latest_frame().unwrap().grid_size();
    assert_eq!(created, Some(("raylab".to_string(), w as i32, h_ as i32)));
    assert_eq!(updated, "raylab");
    window::choose_from_menu(&mut h, "View", "Stream to tev");
    assert!(!h.state().streams_to_tev(), "turned off");
    tev.join().unwrap();
    // On again with tev gone (the listener closed): it says so and turns itself off,
    // the finished image it had sent at once being refused.
    window::choose_from_menu(&mut h, "View", "Stream to tev");
    window::step_until(&mut h, "the stream turned off", |a| !a.streams_to_tev());
}

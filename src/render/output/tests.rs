//! The tests of writing: atomic replacement, pairs cut at every step, sweeps, links.

use super::pair::{Cut, write_pair_cut};
use super::*;

/// The steps of [`write_pair`].
const PAIR_STEPS: usize = 6;

#[test]
fn an_atomic_write_replaces_the_file_and_leaves_no_temporary() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("a.json");
    std::fs::write(&path, "old").unwrap();
    write_file(&path, b"new").unwrap();
    assert_eq!(std::fs::read_to_string(&path).unwrap(), "new");
    let names: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert_eq!(names.len(), 1, "{names:?}");
    // A folder in the way: an error, and the folder untouched.
    std::fs::create_dir(dir.path().join("d")).unwrap();
    assert!(write_file(&dir.path().join("d"), b"x").is_err());
    assert!(dir.path().join("d").is_dir());
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 2);
}

#[test]
fn a_pair_cut_at_any_step_is_never_mixed_and_the_next_write_sweeps() {
    for steps in 0..=PAIR_STEPS {
        let dir = tempfile::tempdir().unwrap();
        let (image, sidecar) = (dir.path().join("a.png"), dir.path().join("a.png.json"));
        std::fs::write(&image, "old image").unwrap();
        std::fs::write(&sidecar, "old sidecar").unwrap();
        write_pair_cut(
            &image,
            b"new image",
            &sidecar,
            b"new sidecar",
            Cut::Kill(steps),
        )
        .unwrap();
        let read = |p: &Path| std::fs::read_to_string(p).ok();
        let state = (read(&image), read(&sidecar));
        let allowed = [
            (Some("old image"), Some("old sidecar")),
            (Some("old image"), None),
            (Some("new image"), None),
            (Some("new image"), Some("new sidecar")),
        ];
        assert!(
            allowed
                .iter()
                .any(|(i, s)| state.0.as_deref() == *i && state.1.as_deref() == *s),
            "after {steps} steps: {state:?}"
        );
        if steps == PAIR_STEPS {
            assert_eq!(state.0.as_deref(), Some("new image"));
            assert_eq!(state.1.as_deref(), Some("new sidecar"));
        }
        // What a kill left is gone after the next write to the folder.
        write_file(&dir.path().join("b.txt"), b"b").unwrap();
        let temporary: Vec<_> = std::fs::read_dir(dir.path())
            .unwrap()
            .flatten()
            .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
            .collect();
        assert!(temporary.is_empty(), "after {steps} steps: {temporary:?}");
    }
}

#[test]
fn a_temporary_file_held_by_a_writer_is_not_swept() {
    let dir = tempfile::tempdir().unwrap();
    let held = TempFile::create(dir.path(), "a.png").unwrap();
    let old = dir.path().join(".b.png.12345-0.tmp");
    std::fs::write(&old, "left by raylab 0.1").unwrap();
    let mine = dir.path().join(".notes.tmp");
    std::fs::write(&mine, "not ours").unwrap();
    let theirs = dir.path().join(".notes.txt.12-3.tmp");
    std::fs::write(&theirs, "another program's").unwrap();
    sweep_stale(dir.path());
    assert!(held.path.exists(), "a live writer's file stays");
    assert!(!old.exists(), "an old version's leftover goes");
    assert!(mine.exists(), "a name raylab never writes stays");
    assert!(theirs.exists(), "another program's temporary file stays");
    assert!(is_temporary(".x.raylab-1-2.tmp") && !is_temporary(".x.1.tmp"));
}

#[test]
fn names_near_the_limit_get_a_temporary_name_that_fits() {
    let dir = tempfile::tempdir().unwrap();
    let name = format!("{}.png", "é".repeat(125));
    assert_eq!(name.len(), 254);
    let path = dir.path().join(&name);
    write_file(&path, b"x").unwrap();
    assert_eq!(std::fs::read(&path).unwrap(), b"x");
    assert!(check_writable(&path, 0, 1).is_ok());
    let e = check_writable(&path, ".json".len(), 1)
        .unwrap_err()
        .to_string();
    assert!(e.contains("259 bytes"), "{e}");
}

#[cfg(unix)]
#[test]
fn a_link_stays_a_link_and_its_target_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let (link, target) = (dir.path().join("link.png"), dir.path().join("real.png"));
    std::os::unix::fs::symlink("real.png", &link).unwrap();
    write_file(&link, b"first").unwrap();
    write_file(&link, b"second").unwrap();
    assert!(link.symlink_metadata().unwrap().file_type().is_symlink());
    assert_eq!(std::fs::read(&target).unwrap(), b"second");
}

#[test]
fn relative_paths_climb_to_the_common_folder() {
    let rel = |t: &str, b: &str| relative_path(Path::new(t), Path::new(b));
    assert_eq!(rel("/a/b/s.toml", "/a/b"), Some(PathBuf::from("s.toml")));
    assert_eq!(
        rel("/a/scenes/s.toml", "/a/renders/today"),
        Some(PathBuf::from("../../scenes/s.toml"))
    );
    assert_eq!(rel("/s.toml", "/a"), Some(PathBuf::from("../s.toml")));
    assert_eq!(rel("s.toml", "/a"), None);
}

#[test]
fn an_image_that_cannot_go_into_place_leaves_the_old_pair() {
    let dir = tempfile::tempdir().unwrap();
    let (image, sidecar) = (dir.path().join("a.png"), dir.path().join("a.png.json"));
    std::fs::write(&image, "old image").unwrap();
    std::fs::write(&sidecar, "old sidecar").unwrap();
    let e = write_pair_cut(&image, b"new", &sidecar, b"new", Cut::ImageFails);
    assert!(e.is_err());
    assert_eq!(std::fs::read_to_string(&image).unwrap(), "old image");
    assert_eq!(std::fs::read_to_string(&sidecar).unwrap(), "old sidecar");
    let names: Vec<_> = std::fs::read_dir(dir.path()).unwrap().flatten().collect();
    assert_eq!(names.len(), 2, "{names:?}");
}

#[cfg(unix)]
#[test]
fn a_pair_through_a_link_rewrites_its_file_and_leaves_the_link() {
    let dir = tempfile::tempdir().unwrap();
    let elsewhere = tempfile::tempdir().unwrap();
    let real = elsewhere.path().join("real.png");
    std::fs::write(&real, "old image, a longer one").unwrap();
    let link = dir.path().join("latest.png");
    std::os::unix::fs::symlink(&real, &link).unwrap();
    let sidecar = dir.path().join("latest.png.json");
    std::fs::write(&sidecar, "old sidecar").unwrap();
    write_pair(&link, b"new image", &sidecar, b"new sidecar").unwrap();
    assert!(link.symlink_metadata().unwrap().file_type().is_symlink());
    assert_eq!(std::fs::read_to_string(&real).unwrap(), "new image");
    assert_eq!(std::fs::read_to_string(&sidecar).unwrap(), "new sidecar");
    // Nothing was made in the link's target's folder.
    let there: Vec<_> = std::fs::read_dir(elsewhere.path())
        .unwrap()
        .flatten()
        .collect();
    assert_eq!(there.len(), 1, "{there:?}");
}

#[cfg(unix)]
#[test]
fn a_fifo_gets_the_image_alone_and_devices_are_left_alone() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("pipe.png");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    assert!(made.unwrap().success());
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || std::fs::read(fifo).unwrap())
    };
    let sidecar = dir.path().join("pipe.png.json");
    write_pair(&fifo, b"streamed", &sidecar, b"{}").unwrap();
    assert_eq!(reader.join().unwrap(), b"streamed");
    assert!(!sidecar.exists(), "nothing beside a stream");
    // A link to /dev/null: refused, the link and the device as they were.
    let null = dir.path().join("null.png");
    std::os::unix::fs::symlink("/dev/null", &null).unwrap();
    let e = write_file(&null, b"x").unwrap_err().to_string();
    assert!(e.contains("character device"), "{e}");
    assert!(null.symlink_metadata().unwrap().file_type().is_symlink());
    use std::os::unix::fs::FileTypeExt;
    let dev = Path::new("/dev/null").metadata().unwrap();
    assert!(dev.file_type().is_char_device());
}

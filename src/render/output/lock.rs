//! One writer at a time in a folder: every raylab process replacing files in a folder
//! holds the folder's advisory lock from its sweep of stale temporary files to its last
//! rename, so that two renders to one output replace the image and its sidecar one pair
//! after the other, never interleaved, and no sweep takes another's file being made.

use std::fs::{File, TryLockError};
use std::io::{Error, ErrorKind, Result};
use std::path::Path;
use std::time::{Duration, Instant};

/// The longest a writer waits for another's writes to the same folder. Writes take
/// milliseconds; a lock held longer is a stuck program, and the writer says so.
const WAIT: Duration = Duration::from_secs(60);

/// The folder's lock, held until dropped.
pub(super) struct FolderLock {
    _file: Option<File>,
}

impl FolderLock {
    /// Takes `dir`'s lock, waiting (bounded) while another writer holds it. On a file
    /// system without locks it goes on unlocked, as writing did before locks.
    pub(super) fn take(dir: &Path) -> Result<FolderLock> {
        let Some(file) = lock_file(dir) else {
            return Ok(FolderLock { _file: None });
        };
        let deadline = Instant::now() + WAIT;
        let mut pause = Duration::from_millis(1);
        loop {
            match file.try_lock() {
                Ok(()) => return Ok(FolderLock { _file: Some(file) }),
                Err(TryLockError::WouldBlock) if Instant::now() < deadline => {
                    std::thread::sleep(pause);
                    pause = (pause * 2).min(Duration::from_millis(20));
                }
                Err(TryLockError::WouldBlock) => {
                    return Err(Error::new(
                        ErrorKind::TimedOut,
                        format!(
                            "another program has been writing in {} for over {} s",
                            dir.display(),
                            WAIT.as_secs()
                        ),
                    ));
                }
                // No locks here (some network file systems): unlocked, as before.
                Err(TryLockError::Error(_)) => return Ok(FolderLock { _file: None }),
            }
        }
    }
}

/// What is locked for `dir`: the folder itself on Unix (nothing is made in it); on other
/// systems, which cannot open a folder as a file, a hidden `.raylab.lock` in it, kept.
fn lock_file(dir: &Path) -> Option<File> {
    #[cfg(unix)]
    {
        File::open(dir).ok()
    }
    #[cfg(not(unix))]
    {
        File::options()
            .create(true)
            .truncate(false)
            .write(true)
            .open(dir.join(".raylab.lock"))
            .ok()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_second_writer_waits_for_the_first() {
        let dir = tempfile::tempdir().unwrap();
        let first = FolderLock::take(dir.path()).unwrap();
        let path = dir.path().to_path_buf();
        let (tx, rx) = std::sync::mpsc::channel();
        let second = std::thread::spawn(move || {
            let lock = FolderLock::take(&path).unwrap();
            tx.send(()).unwrap();
            drop(lock);
        });
        // Not before the first lets go.
        assert!(rx.recv_timeout(Duration::from_millis(200)).is_err());
        drop(first);
        rx.recv_timeout(Duration::from_secs(10)).unwrap();
        second.join().unwrap();
    }
}

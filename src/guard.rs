//! The last line of defence: a panic (a bug in raylab or a dependency, never an expected
//! outcome of bad input, which is checked before) turned into an error message, so that a
//! load or a render that fails this way leaves the window working and the command saying why.

use std::panic::{AssertUnwindSafe, catch_unwind};

/// Runs `f`; a panic inside becomes `Err` with its message.
pub fn caught<T>(f: impl FnOnce() -> T) -> Result<T, String> {
    catch_unwind(AssertUnwindSafe(f)).map_err(|payload| {
        let message = payload
            .downcast_ref::<String>()
            .cloned()
            .or_else(|| payload.downcast_ref::<&str>().map(|s| s.to_string()))
            .unwrap_or_else(|| "no message".to_string());
        format!("an internal error (a bug in raylab): {message}")
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_panic_becomes_its_message() {
        assert_eq!(caught(|| 7), Ok(7));
        let e = caught(|| -> u32 { panic!("out of {}", "range") }).unwrap_err();
        assert!(e.ends_with("out of range"), "{e}");
    }
}

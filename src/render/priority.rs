//! The window's render workers yield to the window's own thread.
//!
//! The window renders on every core, so a 2-core laptop renders on both cores, not one;
//! its workers run a little below normal priority, so a frame of the
//! interface seldom waits for a pass. Measured on this 2-core machine with two busy
//! threads beside a thread doing 6 ms of work per 16 ms frame, that frame ran late by
//! (median, 95th percentile, two runs each): 4.0 and 8.0 ms with the busy threads at
//! normal priority, 0.1–1.8 and 4.1 ms at nice 5, 0.04–0.06 and 4.0 ms at nice 10.

/// Below normal priority for the calling thread, where the platform has it per thread.
///
/// Linux keeps a nice value per thread (`setpriority(PRIO_PROCESS, 0, …)` names the
/// calling thread there, see setpriority(2), NOTES). macOS already runs threads it did not
/// start below its main thread's QoS class, and Windows raises the thread that takes the
/// window's input; elsewhere this does nothing. A failure leaves the thread as it was:
/// it then renders at normal priority, as it did before.
pub(super) fn below_window() {
    #[cfg(any(target_os = "linux", target_os = "android"))]
    {
        /// 5 of 19: the window's thread gets three quarters of a core it shares with a
        /// worker (the kernel's weights: 1024 at nice 0, 335 at nice 5), and a worker
        /// keeps a quarter of a core against another program's busy thread (a screen
        /// recorder's, a build's). At nice 10 it kept a tenth: a slide rendered ahead
        /// beside a build reached 6 of its 128 samples in 30 s.
        const NICE: libc::c_int = 5;
        // Safety: `setpriority` reads only its three integer arguments.
        #[allow(unsafe_code)]
        let failed = unsafe { libc::setpriority(libc::PRIO_PROCESS, 0, NICE) } != 0;
        if failed {
            log::debug!(
                "a render worker stays at normal priority: {}",
                std::io::Error::last_os_error()
            );
        }
    }
}

#[cfg(all(test, any(target_os = "linux", target_os = "android")))]
mod tests {
    #[test]
    fn lowers_the_calling_thread_and_no_other() {
        let nice_of_this_thread = || {
            // Safety: `getpriority` reads only its two integer arguments.
            #[allow(unsafe_code)]
            unsafe {
                libc::getpriority(libc::PRIO_PROCESS, 0)
            }
        };
        let before = nice_of_this_thread();
        let lowered = std::thread::spawn(move || {
            super::below_window();
            nice_of_this_thread()
        })
        .join()
        .expect("the thread runs");
        assert_eq!(lowered, 5.max(before));
        assert_eq!(
            nice_of_this_thread(),
            before,
            "the caller's thread is untouched"
        );
    }
}

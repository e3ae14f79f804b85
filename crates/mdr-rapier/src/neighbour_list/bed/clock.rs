//! The process clocks the benchmark reads: CPU time and peak memory.

/// Peak resident set size of this process so far (MB), from `VmHWM` in `/proc/self/status`; 0
/// where unavailable (systems without `/proc`).
pub fn peak_rss_mb() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1))
                .and_then(|kb| kb.parse::<f64>().ok())
        })
        .map_or(0.0, |kb| kb / 1024.0)
}

/// CPU time (user + system, all threads) of this process so far (s), from
/// `clock_gettime(CLOCK_PROCESS_CPUTIME_ID)` (nanosecond resolution, up to date for running
/// threads too); `None` where the clock is unavailable (systems other than Unix).
pub fn process_cpu_seconds() -> Option<f64> {
    #[cfg(unix)]
    {
        let mut time = libc::timespec {
            tv_sec: 0,
            tv_nsec: 0,
        };
        // SAFETY: clock_gettime writes one `timespec` through the valid pointer it is given and
        // reads nothing else.
        let status = unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut time) };
        (status == 0).then_some(time.tv_sec as f64 + time.tv_nsec as f64 * 1e-9)
    }
    #[cfg(not(unix))]
    {
        None
    }
}

//! Process memory figures for reports: the peak resident set (`VmHWM` of `/proc/self/status`)
//! and the current one (`VmRSS`). Linux only; `None` elsewhere or when the file cannot be read.

/// A `/proc/self/status` field in bytes (the file gives kB).
fn status_bytes(field: &str) -> Option<u64> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    parse_status(&s, field)
}

fn parse_status(s: &str, field: &str) -> Option<u64> {
    s.lines()
        .find_map(|l| l.strip_prefix(field)?.strip_prefix(':'))
        .and_then(|v| v.split_whitespace().next())
        .and_then(|kb| kb.parse::<u64>().ok())
        .map(|kb| kb * 1024)
}

/// Peak resident memory of this process so far (bytes): what `build --json` reports as
/// `peak_memory_mb`.
pub fn peak_resident_bytes() -> Option<u64> {
    status_bytes("VmHWM")
}

/// Resident memory of this process now (bytes).
pub fn resident_bytes() -> Option<u64> {
    status_bytes("VmRSS")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_the_status_fields() {
        let s = "Name:\tflexbody\nVmPeak:\t  200 kB\nVmHWM:\t    1234 kB\nVmRSS:\t 1000 kB\n";
        assert_eq!(parse_status(s, "VmHWM"), Some(1234 * 1024));
        assert_eq!(parse_status(s, "VmRSS"), Some(1000 * 1024));
        assert_eq!(parse_status(s, "VmSwap"), None);
    }

    #[test]
    fn the_peak_grows_with_a_touched_allocation() {
        let Some(before) = peak_resident_bytes() else {
            return; // not Linux
        };
        // 64 MB touched page by page is resident, so the high-water mark covers it
        let mut v = vec![0u8; 64 << 20];
        for i in (0..v.len()).step_by(4096) {
            v[i] = 1;
        }
        std::hint::black_box(&v);
        let after = peak_resident_bytes().unwrap();
        assert!(after >= before);
        assert!(
            after >= 64 << 20,
            "peak {after} below a 64 MB resident buffer"
        );
        assert!(resident_bytes().unwrap() > 0);
    }
}

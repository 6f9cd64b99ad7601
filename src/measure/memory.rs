//! The process's memory use, as the operating system reports it.

/// The peak resident memory of this process so far, bytes (`VmHWM` of `/proc/self/status`);
/// `None` where the system does not report it.
pub fn peak_resident_bytes() -> Option<u64> {
    status_kib("VmHWM:").map(|kib| kib * 1024)
}

/// The resident memory of this process now, bytes (`VmRSS` of `/proc/self/status`); `None`
/// where the system does not report it.
pub fn resident_bytes() -> Option<u64> {
    status_kib("VmRSS:").map(|kib| kib * 1024)
}

/// The memory this process may have, bytes: the machine's physical memory (`MemTotal` of
/// `/proc/meminfo`), or the container's bound (`/sys/fs/cgroup/memory.max`) when that is
/// smaller; `None` where the system reports neither.
pub fn usable_memory_bytes() -> Option<u64> {
    let total = std::fs::read_to_string("/proc/meminfo")
        .ok()
        .and_then(|info| {
            let line = info.lines().find(|l| l.starts_with("MemTotal:"))?;
            let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
            Some(kib * 1024)
        });
    let container = std::fs::read_to_string("/sys/fs/cgroup/memory.max")
        .ok()
        .and_then(|text| text.trim().parse::<u64>().ok());
    match (total, container) {
        (Some(t), Some(c)) => Some(t.min(c)),
        (t, c) => t.or(c),
    }
}

/// The value in KiB of the `/proc/self/status` line starting with `key`.
fn status_kib(key: &str) -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with(key))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn peak_memory_grows_with_a_large_allocation() {
        let Some(before) = peak_resident_bytes() else {
            return; // Not reported on this system.
        };
        let block = vec![1u8; 64 << 20];
        let after = peak_resident_bytes().unwrap();
        assert!(after >= before.max(64 << 20), "{before} then {after}");
        assert!(resident_bytes().unwrap() >= 64 << 20);
        assert!(usable_memory_bytes().unwrap() >= 64 << 20);
        assert_eq!(block.iter().map(|&b| u64::from(b)).sum::<u64>(), 64 << 20);
    }
}

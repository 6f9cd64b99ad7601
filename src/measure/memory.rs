//! The process's memory use, as the operating system reports it.

/// The peak resident memory of this process so far, bytes (`VmHWM` of `/proc/self/status`);
/// `None` where the system does not report it.
pub fn peak_resident_bytes() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
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
        assert_eq!(block.iter().map(|&b| u64::from(b)).sum::<u64>(), 64 << 20);
    }
}

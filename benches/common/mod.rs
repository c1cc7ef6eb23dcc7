//! What the solver bench (`benches/solver.rs`) and the speed table
//! (`examples/speed_table.rs`) share.

/// Peak resident memory of this process (`VmHWM`, kB), if `/proc` has it.
pub fn peak_memory_kb() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

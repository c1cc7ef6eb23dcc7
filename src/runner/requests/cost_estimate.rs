//! What a solve will need, before it runs: its peak memory and wall time on its mesh, by a model
//! of the element count measured at meshes 256–2048 (memory) and 48–256 (time), and the refusal
//! of a solve whose memory is above what the machine has available or above the caller's
//! `--max-memory`. The models, their constants and how close they are: docs/performance.md,
//! "Large meshes".

use crate::fe::MeshLevel;
use crate::runner::requests::request_error::RequestError;

/// Peak memory per displacement unknown, in bytes, at `log2(nx) = 0`: the factor of the sparse
/// tangent grows like `n log n` with nested dissection (fitted, docs/performance.md).
const BYTES_PER_UNKNOWN_AT_ONE: f64 = 1455.0;
/// Its growth per doubling of the elements along the face, in bytes per unknown.
const BYTES_PER_UNKNOWN_PER_DOUBLING: f64 = 88.3;
/// Wall time of one load step, in seconds, per `unknowns^TIME_EXPONENT` (fitted on complete
/// curves, frictionless, one thread).
const SECONDS_PER_STEP_FACTOR: f64 = 1.37e-5;
/// The exponent of the unknowns in the time of one load step.
const TIME_EXPONENT: f64 = 1.04;
/// Load steps of a complete curve (to a/λ = 0.45) per element along the face.
const STEPS_PER_ELEMENT: f64 = 0.95;
/// Peak address space over peak resident memory (measured 1.20–1.25 at meshes 256–2048): what
/// an address-space limit (`ulimit -v`) must leave room for.
const ADDRESS_SPACE_PER_RESIDENT: f64 = 1.25;

/// From this many elements along the face on, a solve is told its estimate (a note).
pub const TOLD_FROM_ELEMENTS: usize = 256;

/// The estimated peak memory and wall time of a solve on one mesh.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CostEstimate {
    /// The mesh estimated.
    pub mesh: MeshLevel,
    /// Peak resident memory, in bytes.
    pub bytes: u64,
    /// Wall time of a complete frictionless curve to a/λ = 0.45 on one core, in seconds.
    pub seconds: f64,
}

impl CostEstimate {
    /// The estimate for `mesh` with every column to the bonded face.
    pub fn of(mesh: MeshLevel) -> Self {
        Self::with_unknowns(mesh, mesh.unknowns())
    }

    /// The estimate for `mesh` with `unknowns` displacement unknowns: fewer than
    /// [`MeshLevel::unknowns`] where the grading coarsens its columns with depth (the memory
    /// model holds there too: docs/performance.md, "Large meshes").
    pub fn with_unknowns(mesh: MeshLevel, unknowns: usize) -> Self {
        let (nx, _) = mesh.counts();
        let unknowns = unknowns as f64;
        let per_unknown =
            BYTES_PER_UNKNOWN_AT_ONE + BYTES_PER_UNKNOWN_PER_DOUBLING * (nx as f64).log2();
        let steps = STEPS_PER_ELEMENT * nx as f64;
        CostEstimate {
            mesh,
            bytes: (unknowns * per_unknown).round() as u64,
            seconds: steps * SECONDS_PER_STEP_FACTOR * unknowns.powf(TIME_EXPONENT),
        }
    }

    /// "mesh 2048×1024 needs about 10.2 GB of memory and 58 h …", for messages and notes.
    pub fn describe(&self) -> String {
        let (nx, ny) = self.mesh.counts();
        format!(
            "mesh {nx}×{ny} needs about {} of memory and {} for a complete curve (estimated, docs/performance.md)",
            gigabytes(self.bytes),
            duration(self.seconds)
        )
    }

    /// `Ok` when the memory the solve needs is at most `max_memory` (the caller's cap, in
    /// bytes) and at most what the machine has available now; else the refusal that names the
    /// estimate ([`RequestError::Memory`]). The available memory is the operating system's
    /// (`sysinfo`); an address space too small for it (a ulimit) is found by reserving the
    /// address space it takes once ([`ADDRESS_SPACE_PER_RESIDENT`] times the estimate), without
    /// touching it.
    pub fn check(&self, max_memory: Option<u64>) -> Result<(), RequestError> {
        if let Some(cap) = max_memory {
            if self.bytes > cap {
                return Err(RequestError::Memory(format!(
                    "{}, above --max-memory = {cap} bytes ({}): choose a coarser --mesh or raise --max-memory",
                    self.describe(),
                    gigabytes(cap)
                )));
            }
        }
        let available = available_memory();
        if self.bytes > available {
            return Err(RequestError::Memory(format!(
                "{}, above the {} this machine has available: choose a coarser --mesh",
                self.describe(),
                gigabytes(available)
            )));
        }
        let address_space = (ADDRESS_SPACE_PER_RESIDENT * self.bytes as f64) as u64;
        let mut probe: Vec<u8> = Vec::new();
        if probe.try_reserve_exact(address_space as usize).is_err() {
            return Err(RequestError::Memory(format!(
                "{}, and this process cannot reserve the {} of address space that takes (an address-space limit, ulimit -v?): choose a coarser --mesh",
                self.describe(),
                gigabytes(address_space)
            )));
        }
        Ok(())
    }
}

/// The memory the operating system says is available to a new allocation, in bytes.
pub fn available_memory() -> u64 {
    let mut system = sysinfo::System::new();
    system.refresh_memory();
    system.available_memory()
}

/// An amount of memory in GB, or in MB below 1 GB.
fn gigabytes(bytes: u64) -> String {
    match bytes as f64 {
        b if b < 1e9 => format!("{:.0} MB", b / 1e6),
        b => format!("{:.1} GB", b / 1e9),
    }
}

fn duration(seconds: f64) -> String {
    match seconds {
        s if s < 90.0 => format!("{s:.0} s"),
        s if s < 5400.0 => format!("{:.0} min", s / 60.0),
        s => format!("{:.0} h", s / 3600.0),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_estimate_grows_with_the_mesh_and_is_refused_above_a_cap() {
        let small = CostEstimate::of(MeshLevel::Default);
        let big = CostEstimate::of(MeshLevel::along_face(2048));
        assert!(
            small.bytes < 20_000_000 && small.seconds < 10.0,
            "{small:?}"
        );
        assert!(big.bytes > 9_000_000_000 && big.seconds > 3600.0, "{big:?}");
        assert!(small.check(None).is_ok());
        let e = small.check(Some(1000)).unwrap_err().to_string();
        assert!(e.starts_with("mesh 48×24 needs about 5 MB"), "{e}");
        assert!(e.contains("above --max-memory = 1000 bytes"), "{e}");
        assert!(CostEstimate::of(MeshLevel::along_face(1 << 14))
            .check(None)
            .is_err());
    }
}

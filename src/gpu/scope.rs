//! Named synchronization scopes (pipeline stages with their accesses) for the barriers that
//! the passes record, so each is defined once.

use ash::vk::{AccessFlags2 as A, PipelineStageFlags2 as S};

/// A barrier's source or destination: stages and accesses.
pub type Scope = (S, A);

const fn s(a: S, b: S) -> S {
    S::from_raw(a.as_raw() | b.as_raw())
}
const fn a(x: A, y: A) -> A {
    A::from_raw(x.as_raw() | y.as_raw())
}

pub const NONE: Scope = (S::NONE, A::NONE);
/// Anything, read or written (coarse, for rare transitions).
pub const ANY: Scope = (S::ALL_COMMANDS, a(A::MEMORY_READ, A::MEMORY_WRITE));
pub const TRANSFER_READ: Scope = (S::ALL_TRANSFER, A::TRANSFER_READ);
pub const TRANSFER_WRITE: Scope = (S::ALL_TRANSFER, A::TRANSFER_WRITE);
pub const HOST_READ: Scope = (S::HOST, A::HOST_READ);
pub const COMPUTE_SAMPLED: Scope = (S::COMPUTE_SHADER, A::SHADER_SAMPLED_READ);
pub const CLEAR_WRITE: Scope = (S::CLEAR, A::TRANSFER_WRITE);
pub const DEPTH_RW: Scope = (
    s(S::EARLY_FRAGMENT_TESTS, S::LATE_FRAGMENT_TESTS),
    a(A::DEPTH_STENCIL_ATTACHMENT_READ, A::DEPTH_STENCIL_ATTACHMENT_WRITE),
);
pub const COLOR_WRITE: Scope = (S::COLOR_ATTACHMENT_OUTPUT, A::COLOR_ATTACHMENT_WRITE);
pub const COMPUTE_WRITE: Scope = (S::COMPUTE_SHADER, A::SHADER_STORAGE_WRITE);
pub const COMPUTE_READ: Scope = (S::COMPUTE_SHADER, A::SHADER_STORAGE_READ);
pub const COMPUTE_RW: Scope = (S::COMPUTE_SHADER, a(A::SHADER_STORAGE_READ, A::SHADER_STORAGE_WRITE));

//! CPU ground truth, kept apart from the GPU code it judges (it shares no code path with it):
//! exact triangle/box voxel coverage, the voxels a camera sees, a model of the cone tracer, a
//! path tracer, and the image metrics that compare renders with it.

pub mod bvh;
pub mod cone;
pub mod coverage;
pub mod metrics;
pub mod pathtrace;
pub mod visible;

//! CPU ground truth, kept apart from the GPU code it judges (it shares no code path with it):
//! exact triangle/box voxel coverage and the accuracy figures computed against it.

pub mod cone;
pub mod coverage;

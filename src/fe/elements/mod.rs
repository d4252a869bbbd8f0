//! Element formulations.

pub mod planar_frame;

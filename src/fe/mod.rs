//! Element matrices and sparse assembly of stiffness K and mass M.

pub mod elements;

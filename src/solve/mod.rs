//! Sparse factorizations (METIS-ordered Cholesky) and the block shift-invert eigensolver.

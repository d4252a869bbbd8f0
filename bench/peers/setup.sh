#!/bin/sh
# One-time setup of the benchmark peers (Debian bookworm + pyenv Python 3.11, as root).
# scikit-sparse 0.5 needs SuiteSparse 7 (bookworm ships 5.12): pin 0.4.12 and build it against
# the installed numpy 2 (no build isolation), else its import fails with "numpy.dtype size
# changed". OpenBLAS replaces the reference BLAS that CHOLMOD would otherwise call.
set -e
apt-get install -y calculix-ccx libsuitesparse-dev libopenblas0-pthread
pip install scipy numpy exudyn cython wheel
pip install --no-build-isolation --no-binary scikit-sparse --no-deps "scikit-sparse==0.4.12"

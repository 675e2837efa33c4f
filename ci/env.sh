#!/usr/bin/env bash
# Environment for running MPI jobs here and in CI (sourced by the other scripts).
# mpirun refuses root without these; -n 3 on 2 cores needs oversubscription; tests running side
# by side must not bind to cores (stack.md §8).
export OMPI_ALLOW_RUN_AS_ROOT=1
export OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
export OMPI_MCA_hwloc_base_binding_policy=none
export OMPI_MCA_btl_vader_single_copy_mechanism=none
export MPIEXEC_TIMEOUT=${MPIEXEC_TIMEOUT:-600}
# OpenBLAS picks its kernels by CPU (AVX-512 "SkylakeX" on recent Intel, "Zen" on AMD, generic
# SSE3 "Prescott" on a virtual CPU it does not recognise), their sums round differently, and the
# GP rockfill's loading path carries those last bits to 1e-3 of the coarse seed dam's slab
# stresses (cfrd::verification, "Rank-count independence"). One kernel family on every machine
# makes results, goldens (tests/goldens.rs) and the tests' bit-for-bit checks the same across
# machines: the AVX2 kernels ("Haswell", which "Zen" gives alike, measured), which every x86-64
# CPU with AVX2 and FMA runs. A CPU without them keeps OpenBLAS's own choice.
if grep -qw avx2 /proc/cpuinfo 2>/dev/null && grep -qw fma /proc/cpuinfo 2>/dev/null; then
    export OPENBLAS_CORETYPE=${OPENBLAS_CORETYPE:-Haswell}
fi

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

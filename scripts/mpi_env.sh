# shellcheck shell=bash
# Sourced by scripts/bootstrap.sh and scripts/run_tests.sh (and usable by hand:
# `source scripts/mpi_env.sh`). Sets the environment that lets Open MPI's
# mpirun work as root, inside containers, and with more ranks than cores.
#
# Debian 12 ships Open MPI 4.1.4. With it, these are what matter:
#   OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1   mpirun as root
#   OMPI_MCA_rmaps_base_oversubscribe=1                          -n 3 on 2 cores
#   OMPI_MCA_btl_vader_single_copy_mechanism=none                no CMA/ptrace in containers
#   OMPI_MCA_hwloc_base_binding_policy=none                      no binding: by default every
#       mpirun binds its rank r to core r, so two runs at once (two validation runs, a run beside
#       the tests) share core 0 at half speed each while core 1 idles
# Open MPI 5 (Debian 13) moved the mapper into PRRTE and renamed vader to sm,
# so those get their own names below.

export OMPI_ALLOW_RUN_AS_ROOT=1
export OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

_mpisph_ompi_version="$(mpirun --version 2>/dev/null | sed -n 's/.*(Open MPI) \([0-9][0-9.]*\).*/\1/p' | head -n 1 || true)"
case "${_mpisph_ompi_version}" in
    5.*)
        export PRTE_MCA_rmaps_default_mapping_policy=:oversubscribe
        export OMPI_MCA_rmaps_base_oversubscribe=1
        export OMPI_MCA_smsc=^cma
        export PRTE_MCA_hwloc_default_binding_policy=none
        ;;
    *)
        export OMPI_MCA_rmaps_base_oversubscribe=1
        export OMPI_MCA_btl_vader_single_copy_mechanism=none
        export OMPI_MCA_hwloc_base_binding_policy=none
        # no mpirun banner after a rank exits non-zero: mpisph's own one-line error stands alone
        export OMPI_MCA_orte_execute_quiet=1
        # ranks waiting in MPI give their core away: runs with more ranks than cores stay fast
        export OMPI_MCA_mpi_yield_when_idle=1
        ;;
esac
unset _mpisph_ompi_version

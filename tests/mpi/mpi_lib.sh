# Helpers of the MPI tests (POSIX sh), on top of the pipeline tests' lib.sh.
# mpi NP CMD...: CMD under mpirun on NP ranks, as CI runs it (root, two
# cores: --allow-run-as-root --oversubscribe); the CPU path of every rank.
. "$here/../pipeline/lib.sh"
# Containers often forbid the cross-memory attach of Open MPI's shared
# memory transport; copying through the segment works everywhere.
OMPI_MCA_btl_vader_single_copy_mechanism=none
export OMPI_MCA_btl_vader_single_copy_mechanism
mpi() {
    np=$1
    shift
    "$mpiexec" --allow-run-as-root --oversubscribe -np "$np" "$@"
}

# same_bytes WHAT A B: A and B must be identical files.
same_bytes() {
    cmp -s "$2" "$3" || { diff "$2" "$3" | head -10 >&2; fail "$1: $3 differs from $2 (one process)"; }
}

#!/bin/sh
# Every command of README.md runs as written, from the directory the README
# says (the repository root, the built command on the path). The code blocks
# of the README (lines indented by four spaces) are read, not copied here:
#   - a block of `vorball ...` lines is examples: each line runs and must exit 0,
#     and each file it names after -o, --centerlines or --pymol must be written;
#   - `mpirun ...` blocks run in mode mpi only (an MPI build), as written, with
#     Open MPI told that root and oversubscription are fine (CI runs as root on
#     2 cores);
#   - `bash .ci/build && build/cli/vorball ...`: the part after && runs (the
#     set-up before it is what CI itself ran);
#   - the set-up blocks (bash .ci/..., cmake, ctest, python3 -m venv, .venv/bin/)
#     are what CI runs; the Python block is run by python/tests/test_readme.py;
#     a line of a vertex file shown as it is written starts with '#'.
# Any other block fails the test, so a new example cannot be left out.
# usage: readme_examples.sh VORBALL SOURCE_DIR WORK_DIR [mpi]
vorball=$1 src=$2 mode=${4:-single}
work=$3/readme_$mode
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
readme=$src/README.md
[ -s "$readme" ] || fail "no $readme"
# The stand-in for the repository root: the corpus and the built command
# where the README says they are; outputs stay in the work folder.
fresh_dir "$work"
ln -s "$src/corpus" corpus || fail "cannot link corpus"
mkdir -p build/cli && ln -s "$vorball" build/cli/vorball || fail "cannot link vorball"
PATH=$work/build/cli:$PATH
export PATH
if [ "$mode" = mpi ]; then
    OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
    OMPI_MCA_btl_vader_single_copy_mechanism=none
    export OMPI_ALLOW_RUN_AS_ROOT OMPI_ALLOW_RUN_AS_ROOT_CONFIRM OMPI_MCA_rmaps_base_oversubscribe \
        OMPI_MCA_btl_vader_single_copy_mechanism
fi
# blocks.txt: "N<TAB>line" for each code line, N the block's number.
awk '/^    / { if (!inb) { n++; inb = 1 } sub(/^    /, ""); print n "\t" $0; next }
     /^[[:space:]]*$/ { next }
     { inb = 0 }' "$readme" > blocks.txt
[ -s blocks.txt ] || fail "no code block in $readme"
ran=0 mpi_lines=0 k=0
# outputs CMD: the files CMD writes by its options.
outputs() {
    echo "$1" | awk '{ for (i = 1; i < NF; i++)
        if ($i == "-o" || $i == "--centerlines" || $i == "--pymol" || $i == "--stats-file") print $(i + 1) }'
}
example() { # CMD
    k=$((k + 1))
    for f in $(outputs "$1"); do rm -f "$f"; done
    sh -c "$1" < /dev/null > "example.$k.out" 2> "example.$k.err"
    rc=$?
    [ $rc -eq 0 ] || { cat "example.$k.err" >&2; fail "README example exited $rc: $1"; }
    for f in $(outputs "$1"); do
        [ -s "$f" ] || fail "README example wrote no $f: $1"
    done
    ran=$((ran + 1))
    echo "ran: $1"
}
nblocks=$(tail -1 blocks.txt | cut -f1)
b=1
while [ "$b" -le "$nblocks" ]; do
    grep "^$b	" blocks.txt | cut -f2- > block.txt
    first=$(head -1 block.txt)
    case $first in
    "vorball "*)
        [ "$mode" = mpi ] || while IFS= read -r line; do
            case $line in
            "vorball "*) example "$line" ;;
            *) fail "README block $b mixes an example with '$line'" ;;
            esac
        done < block.txt ;;
    "mpirun "*)
        while IFS= read -r line; do
            case $line in
            "mpirun "*) mpi_lines=$((mpi_lines + 1)); [ "$mode" = mpi ] && example "$line" ;;
            *) fail "README block $b mixes mpirun with '$line'" ;;
            esac
        done < block.txt ;;
    "bash .ci/build && "*)
        [ "$mode" = mpi ] || example "${first#bash .ci/build && }" ;;
    "bash .ci/"* | "bash python/wheel.sh"* | "cmake "* | "python3 -m venv "* | ".venv/bin/"* | "import vorball" | "#"*) ;;
    *) fail "README block $b is neither an example nor a known set-up: '$first'" ;;
    esac
    b=$((b + 1))
done
# What the examples computed, as the README says.
if [ "$mode" = mpi ]; then
    [ "$ran" -eq "$mpi_lines" ] && [ "$ran" -ge 2 ] || fail "ran $ran of $mpi_lines mpirun examples"
    expect_line capsid.tsv "^# complete: 180006 certified vertices"
    [ "$(grep -c '^0,' channels.csv)" -ge 1 ] || fail "no frame 0 in channels.csv"
else
    [ "$ran" -ge 8 ] || fail "only $ran README examples found"
    expect_line 1crn.vertices.tsv "^# complete: 1996 certified vertices"
    expect_line 1crn.tsv "^# complete: [0-9]+ certified vertices"
    # the cover's set and the sampled one checked by arc closure: the same vertices
    [ "$(grep -vc '^#' 1crn.tsv)" -eq "$(grep -vc '^#' 1crn.sampled.tsv)" ] ||
        fail "the sampled crambin differs from the cover's"
    grep -q '"channels"' pore.json || fail "no channel table in pore.json"
    expect_line pore.pdb "^(ATOM|HETATM)"
fi
echo "ok: $ran README example(s) ran as written ($mode)"

#!/bin/sh
# Regenerates the golden answers corpus/golden/CASE.tsv with `vorball reference`.
#
# The goldens are what the pipeline tests hold every later change to, byte for
# byte. Run this ONLY deliberately: after adding a case, or after a change that
# is meant to change the reference output (the file layout, the canonical
# order). Then read `git diff corpus/golden` line by line and say in the commit
# why each difference is right. Regenerating to make a failing test pass hides
# the bug the test found.
#
# usage: corpus/regenerate.sh --deliberately VORBALL [CASE...]
#   VORBALL  path of the vorball executable; CASE defaults to every input.
set -u
if [ "${1:-}" != "--deliberately" ] || [ $# -lt 2 ]; then
    sed -n '2,12p' "$0" | sed 's/^# \{0,1\}//' >&2
    exit 2
fi
vorball=$(cd "$(dirname "$2")" && pwd)/$(basename "$2")
shift 2
cd "$(dirname "$0")/inputs" || exit 3
mkdir -p ../golden
[ $# -gt 0 ] || set -- $(ls *.xyzr | sed 's/\.xyzr$//')
status=0
for case in "$@"; do
    # The input is named relative to corpus/inputs, as tests/pipeline/golden.sh
    # names it, so any file name the header carries matches.
    # The provenance lines (# tool: names the commit) are left out: the tests
    # compare without them (tests/pipeline/lib.sh sans_provenance).
    if "$vorball" reference "$case.xyzr" > "../golden/$case.tsv.raw" &&
        grep -Ev '^# (tool|input|options): ' "../golden/$case.tsv.raw" > "../golden/$case.tsv.new"; then
        rm -f "../golden/$case.tsv.raw"
        mv "../golden/$case.tsv.new" "../golden/$case.tsv"
        echo "$case: $(grep -c -v '^#' "../golden/$case.tsv") vertices"
    else
        echo "$case: vorball reference failed; golden left as it was" >&2
        rm -f "../golden/$case.tsv.new" "../golden/$case.tsv.raw"
        status=1
    fi
done
exit $status

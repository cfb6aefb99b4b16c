# Helpers sourced by the pipeline tests (POSIX sh).

fail() {
    echo "FAIL: $*" >&2
    exit 1
}

# fresh_dir DIR: DIR emptied (made if absent) and made the current folder.
fresh_dir() {
    rm -rf "$1"
    mkdir -p "$1" || fail "cannot create $1"
    cd "$1" || fail "no $1"
}

# run EXPECTED_EXIT OUTFILE CMD...: runs CMD with stdout+stderr to OUTFILE and
# fails unless it exits with EXPECTED_EXIT.
run() {
    expected=$1 out=$2
    shift 2
    "$@" > "$out" 2>&1
    got=$?
    if [ "$got" -ne "$expected" ]; then
        cat "$out" >&2
        fail "'$*' exited $got, expected $expected"
    fi
}

# expect_line FILE PATTERN: FILE must hold a line matching the grep -E PATTERN.
expect_line() {
    grep -Eq "$2" "$1" || { cat "$1" >&2; fail "no line matching '$2' in $1"; }
}

# vertex_lines FILE: the vertex lines of a tsv file (comments dropped).
vertex_lines() {
    grep -v '^#' "$1"
}

# stat NAME ERR: the value of the --stats line NAME in ERR (the command's
# stderr), empty when there is none.
stat() {
    awk -v k="$1" '$1 == k { print $2 }' "$2"
}

# sans_provenance FILE: FILE without the provenance lines of its header
# ("# tool: ...", "# input: ...", "# options: ..."), for comparisons with a
# stored file (a golden: the tool line names the commit) or with a run that
# differs in input or options; every other line, header too, stays.
sans_provenance() {
    grep -Ev '^# (tool|input|options): ' "$1"
}

# pdb_y_to_z PDB: the ATOM/HETATM records of PDB turned so that y becomes z
# ((x, y, z) -> (x, -z, y), a proper rotation), other records kept, END dropped.
pdb_y_to_z() {
    awk '/^(ATOM|HETATM)/ { x = substr($0, 31, 8); y = substr($0, 39, 8); z = substr($0, 47, 8)
      printf "%s%8.3f%8.3f%8.3f%s\n", substr($0, 1, 30), x, -z, y, substr($0, 55); next }
      /^END/ { next } { print }' "$1"
}

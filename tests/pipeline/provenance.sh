#!/bin/sh
# Provenance in output headers (issue 35): a vertex file names the tool
# version and commit, the input and its sphere count, and the options, before
# the certificate (tsv '#' lines, json keys, periodic tsv, the channels JSON);
# what changes no byte (threads, device, --stats, where the outputs go) is
# not in the options line, so those runs still write the same bytes; `vorball
# verify` reads the files back.
# usage: provenance.sh VORBALL CORPUS_DIR WORK_DIR
vorball=$1 corpus=$2 work=$3/provenance
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
fresh_dir "$work"
out=$work/out.txt
cp "$corpus/inputs/cubic_lattice.xyzr" in.xyzr
cp "$corpus/inputs/cubic_lattice.xyzr" "my in.xyzr"
version=$("$vorball" --version | sed -n '1s/^vorball \([0-9][0-9.]*\).*/\1/p')
[ -n "$version" ] || fail "no version from vorball --version"

# tsv: the three lines after the title, the certificate after them.
run 0 "$out" "$vorball" vertices --device ref --threads 1 --arcs in.xyzr -o a.tsv \
    --topology a.top --atoms a.atoms
sed -n 2,5p a.tsv > head.txt
sed -n 1p head.txt | grep -Eq "^# tool: vorball $version \(commit [^)]+\)$" || fail "tool line: $(cat head.txt)"
sed -n 2p head.txt | grep -qx "# input: in.xyzr, 27 spheres" || fail "input line: $(cat head.txt)"
sed -n 3p head.txt | grep -qx "# options: vertices --arcs in.xyzr --topology FILE --atoms FILE" ||
    fail "options line: $(cat head.txt)"
sed -n 4p head.txt | grep -q "^# complete: 8 certified vertices" || fail "certificate line: $(cat head.txt)"
# Other threads, --stats, other places for the outputs: the same bytes.
run 0 "$out" "$vorball" vertices --arcs --threads 3 --stats --device ref in.xyzr -o b.tsv \
    --topology b.top --atoms b.atoms
cmp -s a.tsv b.tsv || fail "threads, --stats or output paths changed the file"
run 0 "$out" "$vorball" verify in.xyzr a.tsv --complete
expect_line "$out" "^verify: 8 lines \(tsv\): 8 certified, .* 0 missed$"

# An argument a shell would split is quoted as a shell reads it.
run 0 "$out" "$vorball" reference "my in.xyzr" --force -o q.tsv
grep -qx "# options: reference 'my in.xyzr' --force" q.tsv || fail "quoting: $(sed -n 4p q.tsv)"
grep -qx "# input: my in.xyzr, 27 spheres" q.tsv || fail "input with a blank: $(sed -n 3p q.tsv)"

# json: keys before the comment; verify reads it.
run 0 "$out" "$vorball" vertices --device ref --output-format json in.xyzr -o v.json
python3 - "$version" <<'PY' || fail "json provenance"
import json, sys
d = json.load(open("v.json"))
assert list(d)[:6] == ["tool", "input", "spheres", "options", "comment", "vertices"], list(d)
assert d["tool"].startswith("vorball %s (commit " % sys.argv[1]), d["tool"]
assert (d["input"], d["spheres"]) == ("in.xyzr", 27), d
assert d["options"] == "vertices --output-format json in.xyzr", d["options"]
assert d["comment"].startswith("complete: 8 certified vertices") and len(d["vertices"]) == 8
PY
run 0 "$out" "$vorball" verify in.xyzr v.json --complete
expect_line "$out" "^verify: 8 lines \(json\): 8 certified, .* 0 missed$"

# Periodic vertex files: the same lines after their title.
run 0 "$out" "$vorball" vertices --periodic --box 3 3 3 --device ref in.xyzr -o p.tsv
sed -n 3,4p p.tsv > phead.txt
grep -qx "# input: in.xyzr, 27 spheres" phead.txt || fail "periodic input line: $(cat phead.txt)"
grep -qx "# options: vertices --periodic --box 3 3 3 in.xyzr" phead.txt ||
    fail "periodic options line: $(cat phead.txt)"
sed -n 2p p.tsv | grep -q "^# tool: vorball $version " || fail "periodic tool line"

# channels: JSON keys; the CSV keeps its column line first (no comment line).
pdb=$corpus/data/1grm_single_hole2.pdb
run 0 "$out" "$vorball" channels --device ref --grid 32 --json "$pdb" -o c.json --centerlines c.pdb
python3 - "$version" "$pdb" <<'PY' || fail "channels json provenance"
import json, sys
d = json.load(open("c.json"))
assert list(d)[:3] == ["tool", "options", "input"], list(d)
assert d["tool"].startswith("vorball %s (commit " % sys.argv[1]), d["tool"]
assert d["options"] == "channels --grid 32 --json %s --centerlines FILE" % sys.argv[2], d["options"]
assert d["frames"][0]["atoms"] > 0
PY
run 0 "$out" "$vorball" channels --device ref --grid 32 "$pdb" -o c.csv
sed -n 1p c.csv | grep -q "^frame,model,channel," || fail "the CSV's first line is not its columns"
echo "ok: provenance in vertex, periodic and channels headers"

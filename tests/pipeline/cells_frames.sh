#!/bin/sh
# `vorball cells` over frames and as JSON: --frames on a multi-model PDB is
# one table with a frame column first, whose frame 0 is the run on
# `--model 1`; --json holds the TSV's rows and per-residue and per-chain sums
# that enclose the sums of the TSV's rows (within the outward rounding).
# usage: cells_frames.sh VORBALL CORPUS WORKDIR
vorball=$1 corpus=$2 work=$3
. "$(dirname "$0")/lib.sh"
fresh_dir "$work/cells_frames"
fast="--tolerance 1e-2 --max-patches 96 --threads 2"

# Each table starts with its provenance (issue 35: tool, input and sphere
# count, options): checked, then left out, so the checks below read the
# column names and the rows.
strip_provenance() {
    for t in "$@"; do
        [ "$(head -n 3 "$t" | grep -c '^# \(tool: vorball \|input: .*, [0-9]* spheres$\|options: cells \)')" -eq 3 ] ||
            fail "$t: no provenance lines first"
        grep -v '^#' "$t" > "$t.rows" && mv "$t.rows" "$t"
    done
}

# Frames 0 and 2 of the 51 models (183 atoms each), contacts too.
# shellcheck disable=SC2086 # $fast are words
run 0 log "$vorball" cells "$corpus/data/ngl_md_ascii_trj.pdb" --frames 0:3:2 $fast \
    -o frames.tsv --contacts frames_c.tsv
strip_provenance frames.tsv frames_c.tsv
expect_line frames.tsv '^frame	id	chain	resname	resseq	atom	volume	volume_lo	volume_hi	sas	sas_lo	sas_hi$'
expect_line frames_c.tsv '^frame	id1	id2	area	area_lo	area_hi$'
[ "$(cut -f1 frames.tsv | tail -n +2 | sort -u | tr '\n' ' ')" = "0 2 " ] ||
    fail "frames.tsv: frames $(cut -f1 frames.tsv | tail -n +2 | sort -u | tr '\n' ' '), expected 0 2"
[ "$(wc -l < frames.tsv)" -eq 367 ] || fail "frames.tsv: $(wc -l < frames.tsv) lines, expected 1 + 2 x 183"
# shellcheck disable=SC2086
run 0 log1 "$vorball" cells "$corpus/data/ngl_md_ascii_trj.pdb" --model 1 $fast \
    -o model1.tsv --contacts model1_c.tsv
strip_provenance model1.tsv model1_c.tsv
awk -F'\t' 'NR > 1 && $1 == 0' frames.tsv | cut -f2- > frame0.tsv
tail -n +2 model1.tsv | cmp -s - frame0.tsv || fail "frame 0's rows differ from --model 1's"
awk -F'\t' 'NR > 1 && $1 == 0' frames_c.tsv | cut -f2- > frame0_c.tsv
tail -n +2 model1_c.tsv | cmp -s - frame0_c.tsv || fail "frame 0's contacts differ from --model 1's"
# frame 2 is another structure: other volumes
awk -F'\t' 'NR > 1 && $1 == 2' frames.tsv | cut -f2- | cmp -s - frame0.tsv &&
    fail "frame 2's rows equal frame 0's"
# every row: lo <= value <= hi
awk -F'\t' 'NR > 1 && !($8 <= $7 && $7 <= $9 && $11 <= $10 && $10 <= $12) { exit 1 }' frames.tsv ||
    fail "a value outside its enclosure"
# --traj: the XTC of the same 183 atoms over that PDB as topology; its
# frames carry no decimals (the decimals of their doubles are measured).
# shellcheck disable=SC2086
run 0 log "$vorball" cells "$corpus/data/ngl_md_ascii_trj.pdb" --traj "$corpus/data/ngl_md_10frames.xtc" \
    --frames 0:2 $fast -o traj.tsv
strip_provenance traj.tsv
[ "$(cut -f1 traj.tsv | tail -n +2 | uniq -c | awk '{printf "%s:%s ", $2, $1}')" = "0:183 1:183 " ] ||
    fail "traj.tsv: not frames 0 and 1 of 183 atoms each"
awk -F'\t' 'NR > 1 && !($8 <= $7 && $7 <= $9 && $8 > 0 && $11 <= $10 && $10 <= $12) { exit 1 }' traj.tsv ||
    fail "traj.tsv: a value outside its enclosure, or an empty volume"
run 2 log "$vorball" cells "$corpus/data/ngl_md_ascii_trj.pdb" --frames 5:3 -o bad.tsv
expect_line log 'E7'
run 21 log "$vorball" cells "$corpus/data/ngl_md_ascii_trj.pdb" --frames 60: -o none.tsv
expect_line log 'E111'

# JSON over frames: an array whose every object starts with the provenance.
# shellcheck disable=SC2086
run 0 log "$vorball" cells "$corpus/data/ngl_md_ascii_trj.pdb" --frames 0:3:2 $fast --json -o frames.json \
    --contacts frames_jc.tsv
strip_provenance frames_jc.tsv
cmp -s frames_jc.tsv frames_c.tsv || fail "--json changed the contacts table of the frames"
python3 - frames.json <<'PY' || fail "frames.json: not one object per frame, each with its provenance"
import json, sys
doc = json.load(open(sys.argv[1]))
assert [f["frame"] for f in doc] == [0, 2], [f["frame"] for f in doc]
for f in doc:
    assert list(f)[:6] == ["tool", "input", "spheres", "options", "frame", "model"], list(f)
    assert f["spheres"] == 183 and f["options"].endswith("--frames 0:3:2 --tolerance 1e-2 "
                                                         "--max-patches 96 --json --contacts FILE"), f["options"]
PY

# JSON: residues 1-3 of crambin, residue 3 moved to chain B.
awk '/^ATOM/ && substr($0, 23, 4) + 0 <= 3 {
        if (substr($0, 23, 4) + 0 == 3) $0 = substr($0, 1, 21) "B" substr($0, 23)
        print }' "$corpus/data/1crn.pdb" > three_res.pdb
# shellcheck disable=SC2086
run 0 log "$vorball" cells three_res.pdb $fast -o three.tsv
# shellcheck disable=SC2086
run 0 log "$vorball" cells three_res.pdb $fast --json -o three.json
strip_provenance three.tsv
python3 - three.tsv three.json <<'PY' || fail "JSON sums do not match the TSV"
import json, sys
rows = [l.rstrip("\n").split("\t") for l in open(sys.argv[1])][1:]
doc = json.load(open(sys.argv[2]))
# the provenance first, as in a vertex JSON file
assert list(doc)[:4] == ["tool", "input", "spheres", "options"], list(doc)
assert doc["spheres"] == 20 and doc["options"].startswith("cells three_res.pdb "), doc["options"]
assert len(doc["atoms"]) == len(rows) == 20, len(rows)
keys = ("volume", "volume_lo", "volume_hi", "sas", "sas_lo", "sas_hi")
for a, r in zip(doc["atoms"], rows):   # the TSV's digits
    assert [repr(float(a[k])) for k in keys] == [repr(float(v)) for v in r[5:11]], (a, r)
def check(groups, key, want):
    assert [(g[key], g["atoms"]) for g in groups] == want, [(g[key], g["atoms"]) for g in groups]
    for g in groups:
        mine = [r for r in rows if (r[1] if key == "chain" else int(r[3])) == g[key]]
        for q in ("volume", "sas"):
            lo, hi = g[q + "_lo"], g[q + "_hi"]
            assert lo <= g[q] <= hi, g
            slo = sum(float(r[keys.index(q + "_lo") + 5]) for r in mine)
            shi = sum(float(r[keys.index(q + "_hi") + 5]) for r in mine)
            # the group's sum of the enclosures, printed outward: within
            # 1e-10 relative of the TSV's rows summed, and enclosing them
            # but for that printing
            assert abs(lo - slo) <= 1e-10 * shi and abs(hi - shi) <= 1e-10 * shi, (g, slo, shi)
            assert lo <= slo * (1 + 1e-11) and hi >= shi * (1 - 1e-11), (g, slo, shi)
check(doc["residues"], "resseq", [(1, 7), (2, 7), (3, 6)])
check(doc["chains"], "chain", [("A", 14), ("B", 6)])
assert [g["resname"] for g in doc["residues"]] == ["THR", "THR", "CYS"]
PY
echo "ok: cells over frames (frame 0 = --model 1) and JSON sums"

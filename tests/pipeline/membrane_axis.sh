#!/bin/sh
# The membrane's normal as the pore axis (issue 32; vbc_pore.h, source 0):
# a synthetic lipid bilayer (POPE and POPG, each lipid a head-group P atom
# at z = +-19 A and two tail carbons at +-14 and +-9 A, on a 4 A lattice
# 80 A wide) around gramicidin A turned so that its pore runs along z. The
# bilayer is left out (W809), its normal z is the axis (W810 "membrane
# normal", axis_from membrane) and the bottleneck is gramicidin's alone
# along z; --axis-refit follows a tilted bilayer; without P atoms every
# lipid atom gives the normal; gramicidin
# lying in the membrane (its pore along y) has no pore across it (W808);
# cholera toxin B's C5 axis near the normal takes its place; crambin (soluble) in the bilayer
# gets no pore along the normal (W808) rather than along a principal axis;
# three lipid atoms in a line, nine lipids in a 12 A square make no
# membrane (W812).
# usage: membrane_axis.sh VORBALL CORPUS_DIR WORK_DIR
vorball=$1 corpus=$2 work=$3/membrane_axis
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
fresh_dir "$work"
out=$work/out.txt

# bilayer P_NAME [NX NY NZ]: the lipid records (serials from 6000), P_NAME
# the head atom's name, the bilayer normal to (NX, NY, NZ) (default z),
# centred at the origin.
bilayer() {
    awk -v pn="$1" -v nx="${2:-0}" -v ny="${3:-0}" -v nz="${4:-1}" 'BEGIN { n = 6000; r = 0
      # a = a unit normal to the normal, b = normal x a
      if (nx * nx < 0.5) { ax = 0; ay = nz; az = -ny } else { ax = -nz; ay = 0; az = nx }
      l = sqrt(ax * ax + ay * ay + az * az); ax /= l; ay /= l; az /= l
      bx = ny * az - nz * ay; by = nz * ax - nx * az; bz = nx * ay - ny * ax
      for (p = -1; p <= 1; p += 2) for (i = -10; i <= 10; i++) for (j = -10; j <= 10; j++) {
        res = (i + j + 20) % 2 ? "POPG" : "POPE"; r++
        split(pn " C21 C31", nm, " "); split("0 1 0", di, " "); split("0 0 1", dj, " "); split("19 14 9", h, " ")
        for (k = 1; k <= 3; k++) {
          u = 4 * i + di[k]; v = 4 * j + dj[k]; w = h[k] * p
          printf "ATOM  %5d  %-3s %-4sM%4d    %8.3f%8.3f%8.3f  1.00  0.00           %s\n", n++ % 100000, nm[k], res, r % 10000, u * ax + v * bx + w * nx, u * ay + v * by + w * ny, u * az + v * bz + w * nz, substr(nm[k], 1, 1) } } }'
}
# Gramicidin turned: (x, y, z) -> (x, -z, y), its pore along z.
pdb_y_to_z "$corpus/data/1grm_single_hole2.pdb" > grmz.pdb
{ cat grmz.pdb; bilayer P; echo END; } > slab.pdb
[ "$(grep -c ' P   POP' slab.pdb)" = 882 ] || fail "the bilayer has $(grep -c ' P   POP' slab.pdb) P atoms, not 882"

run 0 "$out" "$vorball" channels --device ref --grid 64 slab.pdb --json -o slab.json
expect_line "$out" "W809: slab.pdb: 2646 atoms left out: membrane \(--membrane none keeps it\): .*POPE 1326, POPG 1320"
expect_line "$out" "W810: slab.pdb: pore axis \(membrane\): membrane normal \(882 lipid P atoms"
grep -q '"axis_from": "membrane"' slab.json || fail "axis_from is not membrane"
grep -q '"axis": \[0.00000, 0.00000, 1.00000\]' slab.json || fail "the bilayer's normal is not z: $(grep -o '"axis": [^]]*' slab.json)"
run 0 "$out" "$vorball" channels --device ref --grid 64 slab.pdb -o slab.csv
run 0 "$out" "$vorball" channels --device ref --grid 64 --axis 0,0,1 grmz.pdb -o grmz.csv
cut -d, -f1-5,7 grmz.csv | sed -n 2p > want.txt
cut -d, -f1-5,7 slab.csv | sed -n 2p > got.txt
[ -s want.txt ] || fail "gramicidin along z has no pore row"
cmp -s want.txt got.txt || fail "gramicidin in the bilayer: $(cat got.txt), alone along z: $(cat want.txt)"

# --axis-refit over two models, the second's bilayer tilted 5 degrees
# about x: the second frame sweeps that bilayer's normal (the default,
# --axis fixed, keeps z).
grep -E '^(ATOM|HETATM)' grmz.pdb > grmz_atoms.pdb
{ echo "MODEL        1"; cat grmz_atoms.pdb; bilayer P; echo ENDMDL
  echo "MODEL        2"; cat grmz_atoms.pdb; bilayer P 0 0.0871557 0.9961947; echo ENDMDL; echo END; } > tilt.pdb
run 0 "$out" "$vorball" channels --device ref --grid 64 --axis-refit tilt.pdb --json -o tilt.json
grep -o '"axis": [^]]*' tilt.json > got.txt
printf '"axis": [0.00000, 0.00000, 1.00000\n"axis": [0.00000, 0.08716, 0.99619\n' > want.txt
cmp -s want.txt got.txt || fail "--axis-refit with a tilted bilayer: $(cat got.txt)"
run 0 "$out" "$vorball" channels --device ref --grid 64 tilt.pdb --json -o tiltfixed.json
[ "$(grep -c '"axis": \[0.00000, 0.00000, 1.00000\]' tiltfixed.json)" = 2 ] || fail "--axis fixed did not keep z"

# No head-group P: all the lipid atoms give the normal.
{ cat grmz.pdb; bilayer C1; echo END; } > slabc.pdb
run 0 "$out" "$vorball" channels --device ref --grid 64 slabc.pdb --json -o slabc.json
expect_line "$out" "W810: slabc.pdb: pore axis \(membrane\): membrane normal \(2646 membrane atoms"
grep -q '"axis": \[0.00000, 0.00000, 1.00000\]' slabc.json || fail "the bilayer's normal (no P) is not z"

# Gramicidin lying in the bilayer (its pore along y): no pore crosses the
# membrane (W808 along the normal), no principal or chains axis is taken
# instead; --axis 0,1,0 still sweeps its pore.
{ grep -v '^END' "$corpus/data/1grm_single_hole2.pdb"; bilayer P; echo END; } > lying.pdb
run 0 "$out" "$vorball" channels --device ref --grid 64 lying.pdb -o lying.csv
expect_line "$out" "W808: lying.pdb: no pore: the widest path along the membrane axis"
[ "$(grep -c ',pore,' lying.csv)" = 0 ] || fail "gramicidin lying in the membrane has a pore row"
run 0 "$out" "$vorball" channels --device ref --grid 64 --axis 0,1,0 lying.pdb -o lyingy.csv
[ "$(grep -c ',pore,' lyingy.csv)" = 1 ] || fail "--axis 0,1,0 lost gramicidin's pore in the membrane"

# Cholera toxin B (C5) in a bilayer normal to (0.5, 0, -0.866), about 4 degrees
# off its C5 axis: the symmetry axis takes the normal's place.
grep -v '^END' "$corpus/data/1chb_hole2.pdb" > chb.pdb
{ cat chb.pdb; bilayer P 0.5 0 -0.8660254; echo END; } > chbslab.pdb
run 0 "$out" "$vorball" channels --device ref --grid 64 chb.pdb --json -o chb.json
run 0 "$out" "$vorball" channels --device ref --grid 64 chbslab.pdb --json -o chbslab.json
expect_line "$out" "W810: chbslab.pdb: pore axis \(symmetry\): .*; 4 deg off the membrane normal"
grep -o '"axis": [^]]*' chb.json > want.txt
grep -o '"axis": [^]]*' chbslab.json > got.txt
cmp -s want.txt got.txt || fail "cholera toxin in the bilayer: $(cat got.txt), alone: $(cat want.txt)"

# Crambin in the bilayer: no pore along the normal.
{ grep -v '^END' "$corpus/data/1crn.pdb"; bilayer P; echo END; } > crn.pdb
run 0 "$out" "$vorball" channels --device ref --grid 64 crn.pdb -o crn.csv
expect_line "$out" "W808: crn.pdb: no pore: the widest path along the membrane axis"

# Three lipid atoms in a line are no membrane: W812, the usual order.
{ cat grmz.pdb
  for k in 0 1 2; do
    printf 'HETATM%5d  C%-2d POPCL   2    %8.3f%8.3f%8.3f  1.00  0.00           C\n' $((7000 + k)) $k $((25 + k)) 0 25
  done; echo END; } > line.pdb
run 0 "$out" "$vorball" channels --device ref --grid 64 line.pdb --json -o line.json
expect_line "$out" "W812: line.pdb: the membrane atoms left out make no flat, wide membrane"
grep -q '"axis_from": "membrane"' line.json && fail "three atoms in a line gave a membrane normal"
# Nine lipids on a 4 A lattice (flat, 3.3 A rms wide) are bound lipids, no
# membrane patch: W812.
{ cat grmz.pdb
  for i in 0 1 2; do for j in 0 1 2; do
    printf 'ATOM  %5d  P   POPCL%4d    %8.3f%8.3f%8.3f  1.00  0.00           P\n' $((7100 + 3 * i + j)) $((3 * i + j + 1)) $((30 + 4 * i)) $((4 * j)) 20
  done; done; echo END; } > few.pdb
run 0 "$out" "$vorball" channels --device ref --grid 64 few.pdb --json -o few.json
expect_line "$out" "W812: few.pdb"
grep -q '"axis_from": "membrane"' few.json && fail "nine bound lipids gave a membrane normal"
echo "membrane axis: ok"

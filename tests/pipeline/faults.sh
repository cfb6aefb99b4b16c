#!/bin/sh
# Planted faults: a golden vertex file is damaged in one way and
# `vorball verify` must name the damage with the right class and exit 1.
# usage: faults.sh VORBALL CORPUS_DIR WORK_DIR FAULT
vorball=$1 corpus=$2 fault=$4 work=$3/fault_$4
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
mkdir -p "$work" || fail "cannot create $work"
cd "$corpus/inputs" || fail "no $corpus/inputs"
cubic=../golden/cubic_lattice.tsv
bad=$work/bad.tsv
out=$work/report.txt
MISMATCH=1

# The golden's header is h comment lines; its first vertex, on line v1, is the
# cube centre (0.5 0.5 0.5) touching spheres 0,1,3,4,9,10,12,13 (checked here
# so that a change of the golden shows up as such); it has 8 vertices.
h=$(grep -c '^#' "$cubic")
v1=$((h + 1)) v3=$((h + 3)) v4=$((h + 4)) end=$((h + 8))
case $(sed -n "${v1}p" "$cubic") in
0,1,3,4,9,10,12,13*) ;;
*) fail "unexpected first vertex line of $cubic" ;;
esac
[ "$(wc -l < "$cubic")" -eq "$end" ] || fail "$cubic: 8 vertices expected"

case $fault in
moved)
    # x + 1e-7: certified at the default --tol 1e-6, wrong at --tol 1e-8
    awk -F '\t' -v l="$v1" 'BEGIN { OFS = "\t" } NR == l { $2 = sprintf("%.17g", $2 + 1e-7) } { print }' "$cubic" > "$bad"
    run 0 "$out" "$vorball" verify cubic_lattice.xyzr "$bad"
    run $MISMATCH "$out" "$vorball" verify cubic_lattice.xyzr "$bad" --tol 1e-8
    expect_line "$out" "^$bad:$v1: wrong coordinates: 1e-07 from the exact vertex"
    expect_line "$out" " 7 certified, 0 not a vertex, 1 wrong coordinates, 0 missing members, 0 duplicate$"
    run $MISMATCH "$out" "$vorball" verify cubic_lattice.xyzr "$bad" --tol 1e-8 --json
    expect_line "$out" '"counts":\{"certified":7,"not_a_vertex":0,"wrong_coordinates":1,"missing_members":0,"duplicate":0\}'
    expect_line "$out" '\{"line":'$v1',"class":"wrong_coordinates","distance":(9\.9|1\.0|1e-07)' ;;
missing_member)
    # sphere 13 dropped from the degree-8 vertex
    sed "${v1}s/^0,1,3,4,9,10,12,13\t/0,1,3,4,9,10,12\t/" "$cubic" > "$bad"
    run $MISMATCH "$out" "$vorball" verify cubic_lattice.xyzr "$bad"
    expect_line "$out" "^$bad:$v1: missing members: the exact vertex also touches 13$"
    expect_line "$out" " 7 certified, 0 not a vertex, 0 wrong coordinates, 1 missing members, 0 duplicate$" ;;
intruder)
    # corners 0 (0,0,0), 2 (0,0,2), 6 (0,2,0), 18 (2,0,0) are tangent to the
    # sphere around (1,1,1), which holds sphere 13
    { cat "$cubic"; printf '0,2,6,18\t1\t1\t1\t1.4820508075688772\tcandidate\n'; } > "$bad"
    run $MISMATCH "$out" "$vorball" verify cubic_lattice.xyzr "$bad"
    expect_line "$out" "^$bad:$((end + 1)): not a vertex: sphere 13 \(cubic_lattice.xyzr:14\) cuts the tangent sphere$"
    run $MISMATCH "$out" "$vorball" verify cubic_lattice.xyzr "$bad" --json
    expect_line "$out" '"line":'$((end + 1))',"class":"not_a_vertex","reason":"intruder","sphere":13' ;;
no_solution)
    # spheres 0..3 of bisectors_no_meet have no common tangent sphere
    { cat ../golden/bisectors_no_meet.tsv; printf '0,1,2,3\t1\t1\t-1\t1\tcandidate\n'; } > "$bad"
    run $MISMATCH "$out" "$vorball" verify bisectors_no_meet.xyzr "$bad"
    expect_line "$out" "^$bad:$(($(wc -l < ../golden/bisectors_no_meet.tsv) + 1)): not a vertex: the spheres have no common tangent sphere$" ;;
duplicate)
    { cat "$cubic"; sed -n "${v3}p" "$cubic"; } > "$bad"
    run $MISMATCH "$out" "$vorball" verify cubic_lattice.xyzr "$bad"
    expect_line "$out" "^$bad:$((end + 1)): duplicate: same vertex as line $v3$"
    expect_line "$out" " 8 certified, 0 not a vertex, 0 wrong coordinates, 0 missing members, 1 duplicate$" ;;
missed)
    # without --complete a file with a vertex left out is consistent
    sed "${v4}d" "$cubic" > "$bad"
    run 0 "$out" "$vorball" verify cubic_lattice.xyzr "$bad"
    run $MISMATCH "$out" "$vorball" verify cubic_lattice.xyzr "$bad" --complete
    expect_line "$out" "^$bad: missed vertex $(sed -n "${v4}p" "$cubic" | cut -f1) at "
    expect_line "$out" " 7 certified, .*, 1 missed$"
    run $MISMATCH "$out" "$vorball" verify cubic_lattice.xyzr "$bad" --complete --json
    expect_line "$out" '"missed":1\}' ;;
arcs)
    # exact arc closure (--arcs) restores what sampling would miss
    run 0 "$out" "$vorball" verify cubic_lattice.xyzr "$cubic" --arcs
    expect_line "$out" ": arcs: 8 vertices traced, 48 half arcs: 24 closed at a vertex, 24 to infinity, 0 closed loops, 0 undecided; 0 vertices added; 1 components$"
    # one vertex deleted: found again, exit 1
    sed "${v4}d" "$cubic" > "$bad"
    run $MISMATCH "$out" "$vorball" verify cubic_lattice.xyzr "$bad" --arcs
    expect_line "$out" "^$bad: missing vertex $(sed -n "${v4}p" "$cubic" | cut -f1) at .* \(found by arc closure\)$"
    expect_line "$out" " 0 undecided; 1 vertices added; 1 components$"
    # every vertex of the cell of sphere 20 of crambin_fragment (14) deleted
    g=../golden/crambin_fragment.tsv
    awk -F '\t' '/^#/ { print; next } { n = split($1, a, ","); for (i = 1; i <= n; i++) if (a[i] == 20) next; print }' "$g" > "$bad"
    [ $(($(grep -c -v '^#' "$g") - $(grep -c -v '^#' "$bad"))) -eq 14 ] || fail "expected to drop 14 vertices"
    run $MISMATCH "$out" "$vorball" verify crambin_fragment.xyzr "$bad" --arcs
    [ "$(grep -c ': missing vertex .*20.* (found by arc closure)$' "$out")" -eq 14 ] || fail "expected 14 missing vertices of cell 20"
    expect_line "$out" " 0 undecided; 14 vertices added; 1 components$"
    # Voronota's degree-8 vertices as tetrahedra: one vertex each
    run 0 "$out" "$vorball" verify cubic_lattice.xyzr "$here/data/cubic_lattice_kuhn.voronota" --arcs
    expect_line "$out" ": arcs: 8 vertices traced, 48 half arcs: .* 0 vertices added; 1 components$"
    # what it does not prove: a component with no vertex in the file (the
    # lens cell of sphere 8 of coplanar_centres) is not seen
    grep -v '^0,7,8,10	' ../golden/coplanar_centres.tsv > "$bad"
    run 0 "$out" "$vorball" verify coplanar_centres.xyzr "$bad" --arcs
    expect_line "$out" ": arcs: 24 vertices traced, .* 0 vertices added; 1 components$"
    run 0 "$out" "$vorball" verify coplanar_centres.xyzr ../golden/coplanar_centres.tsv --arcs
    expect_line "$out" ": arcs: 26 vertices traced, .* 0 vertices added; 2 components$"
    # the far hull vertices (the 3 of largest t) of crambin_fragment deleted:
    # all three found again
    awk -F '\t' '!/^#/ { print $5 "\t" NR }' "$g" | sort -g -r | head -3 | cut -f2 > "$work/far.txt"
    awk 'NR == FNR { far[$1] = 1; next } !(FNR in far)' "$work/far.txt" "$g" > "$bad"
    [ $(($(grep -c -v '^#' "$g") - $(grep -c -v '^#' "$bad"))) -eq 3 ] || fail "expected to drop 3 vertices"
    run $MISMATCH "$out" "$vorball" verify crambin_fragment.xyzr "$bad" --arcs
    [ "$(grep -c ': missing vertex .* (found by arc closure)$' "$out")" -eq 3 ] || fail "expected the 3 far hull vertices back"
    expect_line "$out" " 0 undecided; 3 vertices added; 1 components$"
    for l in $(cat "$work/far.txt"); do
        ids=$(sed -n "${l}p" "$g" | cut -f1)
        expect_line "$out" "^$bad: missing vertex $ids at "
    done
    # a real miss: sampling with 6 x 6 rays per face misses the far hull
    # vertex 0,1,2,8 of far_hull_vertex (t = 1892); --arcs certifies it and
    # writes the golden
    run 0 "$work/far_s.err" "$vorball" vertices --device ref --proposer sampling --samples 6 far_hull_vertex.xyzr -o "$work/far_s.tsv"
    grep -q '^0,1,2,8	' "$work/far_s.tsv" && fail "sampling at --samples 6 no longer misses 0,1,2,8: the case lost its point"
    run 0 "$work/far_a.err" "$vorball" vertices --device ref --proposer sampling --samples 6 --arcs far_hull_vertex.xyzr -o "$work/far_a.tsv"
    expect_line "$work/far_a.tsv" "^# arcs: every arc closed exactly: 17 vertices, 68 half arcs: .* 0 undecided; 1 vertices added by tracing; 1 connected components$"
    grep -v '^#' "$work/far_a.tsv" > "$work/far_a.lines"
    grep -v '^#' ../golden/far_hull_vertex.tsv | cmp - "$work/far_a.lines" || fail "sampling + arcs does not give the golden of far_hull_vertex"
    # the JSON form: counts and the missing vertex, "ok" false, exit 1
    sed "${v4}d" "$cubic" > "$bad"
    run $MISMATCH "$out" "$vorball" verify cubic_lattice.xyzr "$bad" --arcs --json
    expect_line "$out" '"arcs":\{"vertices":8,"half_arcs":48,"closed":24,"infinite":24,"loops":0,"undecided":0,"added":1,"components":1,"complete":false,"missing":\['
    expect_line "$out" "^\\{\"ids\":\\[$(sed -n "${v4}p" "$cubic" | cut -f1)\\],\"x\":"
    expect_line "$out" '"ok":false\}$'
    run 0 "$out" "$vorball" verify cubic_lattice.xyzr "$cubic" --arcs --json
    expect_line "$out" '"added":0,"components":1,"complete":true,"missing":\[\]\},"ok":true\}$' ;;
voronota_groups)
    # Voronota-style: each degree-8 vertex as the 6 tetrahedra of its cube
    # (2 comment lines, then 48 quadruple lines)
    kuhn=$here/data/cubic_lattice_kuhn.voronota
    run 0 "$out" "$vorball" verify cubic_lattice.xyzr "$kuhn" --complete
    expect_line "$out" "^verify: 48 lines \(voronota, 8 vertices\): 48 certified, 0 not a vertex"
    # without the tetrahedra through corner 1 (0,0,1) the first vertex misses it
    grep -v -E '^0 1 |^0 [0-9]+ 1 |^0 [0-9]+ [0-9]+ 1 ' "$kuhn" > "$bad"
    [ "$(grep -c -v '^#' "$bad")" -eq 46 ] || fail "expected to drop 2 tetrahedra"
    run $MISMATCH "$out" "$vorball" verify cubic_lattice.xyzr "$bad"
    expect_line "$out" "^$bad:3: missing members: the exact vertex also touches 1$"
    # a repeated quadruple is a duplicate, a second vertex of one quadruple is not
    { cat "$kuhn"; sed -n 4p "$kuhn"; } > "$bad"
    run $MISMATCH "$out" "$vorball" verify cubic_lattice.xyzr "$bad"
    expect_line "$out" "^$bad:51: duplicate: same vertex as line 4$" ;;
voronota_fan)
    # our goldens rewritten as Voronota lines {m0 m1 m2 mj}: groups rebuilt;
    # for the cube {0 1 3 4} is coplanar and does not determine the point
    for c in cubic_lattice two_vertices_one_quadruple degree5_vertex collinear_centres; do
        g=../golden/$c.tsv
        awk -F '\t' '!/^#/ { n = split($1, id, ","); for (j = 4; j <= n; j++)
                       print id[1], id[2], id[3], id[j], $2, $3, $4, $5 }' "$g" > "$bad"
        nv=$(grep -c -v '^#' "$g")
        run 0 "$out" "$vorball" verify "$c.xyzr" "$bad" --complete
        expect_line "$out" "^verify: [0-9]+ lines \(voronota, $nv vertices\): [0-9]+ certified, 0 not a vertex.* 0 missed$"
    done ;;
*)
    fail "unknown fault $fault" ;;
esac
echo "ok: $fault"

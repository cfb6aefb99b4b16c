#!/bin/sh
# The property each corpus case was built to exhibit, checked on its golden
# (columns: ids x y z t status). Exits 1 with a message when it does not hold.
# usage: properties.sh CASE GOLDEN WORK_DIR   (run from corpus/inputs)
case=$1 golden=$2 work=$3
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
v=$work/vertices.txt
vertex_lines "$golden" > "$v"
[ -s "$v" ] || fail "$case: golden has no vertices"

# awk_check PROGRAM: runs PROGRAM over the vertex lines (tab-separated, with
# n = number of ids and id[1..n]); PROGRAM's END block exits 1 on failure.
awk_check() {
    awk -F '\t' "{ n = split(\$1, id, \",\") } $1" "$v" || fail "$case: $2"
}

case $case in
cubic_lattice)
    # every vertex is a cube centre touching all 8 corners
    awk_check '{ c++; if (n != 8 || $2 - int($2) != 0.5) bad++ }
               END { exit !(c == 8 && bad == 0) }' "8 vertices of degree 8 expected" ;;
bcc_lattice)
    # interior vertices are simple (degree 4); the flat boundary adds degree 5
    awk_check '{ d[n]++ } END { exit !(d[4] == 48 && d[5] == 24 && NR == 72) }' \
        "48 vertices of degree 4 and 24 of degree 5 expected" ;;
hexagonal_ring)
    # the six ring bisectors share the axis: two degree-7 vertices on it
    awk_check '{ c++; if (n == 7 && $2 == 0 && $3 == 0 && ($4 == 3.75 || $4 == -3.75) && $5 == 4.75) ok++ }
               END { exit !(c == 2 && ok == 2) }' "two degree-7 vertices at z = +-3.75 expected" ;;
degree5_vertex)
    awk_check '$1 == "0,1,2,3,4" && $2 == 0 && $3 == 0 && $4 == 0 && $5 == 2 { ok++ } n > 5 { bad++ }
               END { exit !(ok == 1 && bad == 0) }' "the degree-5 vertex 0,1,2,3,4 at the origin expected" ;;
large_offset)
    # the same diagram as degree5_vertex, moved by 1e5 along each axis
    vertex_lines ../golden/degree5_vertex.tsv > "$work/base.txt"
    paste "$work/base.txt" "$v" | awk -F '\t' '
        { c++; if ($1 != $7 || $5 != $11) bad++
          for (k = 2; k <= 4; k++) { d = $(k + 6) - $k - 100000; if (d < -1e-9 || d > 1e-9) bad++ } }
        END { exit !(c == 14 && bad == 0) }' || fail "$case: degree5_vertex moved by 1e5 expected"
    [ "$(wc -l < "$work/base.txt")" -eq "$(wc -l < "$v")" ] || fail "$case: vertex counts differ" ;;
two_vertices_one_quadruple)
    awk_check '$1 == "0,1,2,3" { c++; z[c] = $4 } END { exit !(c == 2 && z[1] == -z[2] && z[1] != 0) }' \
        "two mirror vertices of the quadruple 0,1,2,3 expected" ;;
bisectors_no_meet)
    # spheres 0..3 have no common tangent sphere (checked by the fault test
    # verify_no_solution); here: no vertex uses all four
    awk_check '{ m = 0; for (k = 1; k <= n; k++) if (id[k] <= 3) m++; if (m == 4) bad++ }
               END { exit !(bad == 0 && NR == 16) }' "16 vertices, none with all of 0..3, expected" ;;
nearly_equal_radii)
    # radii 1.5, 1.5000001, 1.4999999 by id mod 3: vertices mix all three
    awk_check '{ delete cls; for (k = 1; k <= n; k++) cls[id[k] % 3] = 1; if (length(cls) == 3) mixed++ }
               END { exit !(NR == 34 && mixed > 0) }' "34 vertices, some touching all three radii, expected" ;;
intersecting_spheres)
    awk_check '$5 < 0 { neg++ } END { exit !(neg == 21 && NR == 46) }' \
        "46 vertices of which 21 with t < 0 expected" ;;
contained_sphere)
    # sphere 7 lies inside sphere 0: its cell is empty
    awk_check '{ for (k = 1; k <= n; k++) if (id[k] == 7) bad++ } END { exit !(bad == 0 && NR == 14) }' \
        "14 vertices, none touching the contained sphere 7, expected" ;;
coplanar_centres)
    # all centres in z = 0: vertices come in mirror pairs off the plane
    awk_check '{ k = $1 " " $2 " " $3 " " $5; if ($4 == 0) bad++; else if ($4 > 0) up[k]++; else down[k]++ }
               END { for (k in up) if (down[k] != up[k]) bad++; for (k in down) if (down[k] != up[k]) bad++
                     exit !(bad == 0 && NR == 26) }' "26 vertices in mirror pairs expected" ;;
collinear_centres)
    # spheres 0..5 on the x axis: tangent spheres of three of them form a
    # circle, which an off-axis sphere cuts in two points
    awk_check '{ m = 0; for (k = 1; k <= n; k++) if (id[k] <= 5) m++; if (m == 3) three[$1]++ }
               END { c = 0; for (k in three) { c++; if (three[k] != 2) bad++ } exit !(c == 4 && bad == 0) }' \
        "4 quadruples with 3 collinear members, two vertices each, expected" ;;
jittered_lattice)
    # the 1e-9 jitter splits each degree-8 vertex into nearby simple ones
    awk_check '{ d[n]++ } $5 < 0.7 { near++ } END { exit !(d[4] == 88 && d[5] == 2 && near > 8) }' \
        "88 vertices of degree 4, 2 of degree 5, more than 8 near the cube centres expected" ;;
lattice_subset)
    # 30 of the 64 points of a 4x4x4 lattice, equal radii: cospherical
    # subsets everywhere, vertices of degree 4 to 7 side by side
    awk_check '{ d[n]++ } END { exit !(d[4] == 29 && d[5] == 18 && d[6] == 2 && d[7] == 1 && NR == 50) }' \
        "29, 18, 2, 1 vertices of degree 4, 5, 6, 7 expected" ;;
crambin_fragment)
    awk_check '{ if (n < 4) bad++ } END { exit !(bad == 0 && NR > 100) }' "a real diagram expected" ;;
far_hull_vertex)
    # one far hull vertex, 0,1,2,8 at t = 1892 (the next largest t is 53)
    awk_check '$1 == "0,1,2,8" && $5 > 1800 { far++ } $5 > 100 { big++ } END { exit !(far == 1 && big == 1 && NR == 17) }' \
        "17 vertices, one far hull vertex 0,1,2,8 with t > 1800 expected" ;;
internally_tangent)
    # sphere 0 touches 1, 2 and 3 from inside: its cell is the origin, a vertex at t = -2
    awk_check '$1 == "0,1,2,3" && $2 == 0 && $3 == 0 && $4 == 0 && $5 == -2 { ok++ }
               END { exit !(ok == 1 && NR == 1) }' "the vertex 0,1,2,3 at the origin, t = -2, expected" ;;
nested_tangent_cluster)
    # sphere 0 touches six spheres from inside at the origin (degree 7, t = -2);
    # spheres 7 and 8 lie strictly inside others and touch nothing
    awk_check '$1 == "0,1,2,3,4,5,6" && $2 == 0 && $3 == 0 && $4 == 0 && $5 == -2 { ok++ }
               { for (k = 1; k <= n; k++) if (id[k] == 7 || id[k] == 8) bad++ }
               END { exit !(ok == 1 && bad == 0 && NR == 17) }' \
        "17 vertices, the degree-7 vertex at the origin, none touching 7 or 8, expected" ;;
cospherical_unequal)
    # nine spheres of nine radii tangent to the sphere of radius 2 at the origin
    awk_check '$1 == "0,1,2,3,4,5,6,7,8" && $2 == 0 && $3 == 0 && $4 == 0 && $5 == 2 { ok++ } n > 4 { big++ }
               END { exit !(ok == 1 && big == 1 && NR == 19) }' \
        "19 vertices, one of degree 9 (0..8) at the origin with t = 2, expected" ;;
fcc_hull_ties)
    # octahedral holes (degree 6) inside, ties of five on the flat hull
    awk_check '{ d[n]++ } END { exit !(d[4] == 39 && d[5] == 12 && d[6] == 4 && NR == 55) }' \
        "39 vertices of degree 4, 12 of degree 5, 4 of degree 6 expected" ;;
jittered_fcc)
    # every degree-6 octahedral hole (t = a/2 - r = 0.525) splits into four
    # simple vertices 1e-9 apart: where combination dominance acts
    awk_check 'n != 4 { bad++ } { k = sprintf("%.4f %.4f %.4f", $2, $3, $4); c[k]++; t[k] = $5 }
               END { for (k in c) if (c[k] == 4 && t[k] > 0.5249 && t[k] < 0.5251) four++
                     exit !(bad == 0 && four == 32 && NR == 518) }' \
        "518 vertices of degree 4, 32 octahedral holes split four ways, expected" ;;
near_cospherical)
    # twelve balls within 1e-6 of tangent to one sphere: simple vertices crowded at its centre
    awk_check 'n == 4 { dx = $2 - 1.5; dy = $3 + 2; dz = $4 - 0.5; dt = $5 - 8
                        if (dx * dx + dy * dy + dz * dz < 1e-8 && dt * dt < 1e-8) near++ }
               END { exit !(near == 17 && NR == 17) }' \
        "17 vertices of degree 4, all within 1e-4 of (1.5, -2, 0.5) with t = 8, expected" ;;
sc_jitter12)
    # every degree-8 cube centre splits into five or six simple vertices 1e-12 apart
    awk_check 'n != 4 { bad++ } { k = sprintf("%.6f %.6f %.6f", $2, $3, $4); c[k]++ }
               END { for (k in c) if (c[k] == 5 || c[k] == 6) split6++
                     exit !(bad == 0 && split6 == 27 && NR == 312) }' \
        "312 vertices of degree 4, 27 cube centres split five or six ways, expected" ;;
*)
    fail "no property known for case $case" ;;
esac

#!/bin/sh
# The exact topology (`vorball vertices --topology`, edges traced by arc
# closure) of one corpus case against the arc certificate of the same run:
# one line per finite edge (half arcs closed at a vertex / 2), one per half
# arc to infinity; each edge's triple among the members of its ends; a
# vertex of four spheres has exactly four edges (a finite edge counts at both
# ends) and all six of its pairs as faces; every face is a pair of a
# vertex's members. Then hand counts of some cases.
# usage: topology.sh CASE VERTICES_TSV TOPOLOGY
case=$1 tsv=$2 top=$3
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
grep -q '^# edges exact (from arc closure)' "$top" || fail "$top: header does not say the edges are exact"
cert=$(grep '^# arcs: ' "$tsv") || fail "$tsv: no arc certificate"
closed=$(echo "$cert" | sed -n 's/.* \([0-9]*\) closed at a vertex.*/\1/p')
inf=$(echo "$cert" | sed -n 's/.* \([0-9]*\) to infinity.*/\1/p')
loops=$(echo "$cert" | sed -n 's/.* \([0-9]*\) closed loops.*/\1/p')
comps=$(echo "$cert" | sed -n 's/.* \([0-9]*\) connected components$/\1/p')
fin=$(awk '$1 == "edge" && $3 != -1 && $3 != $2' "$top" | wc -l)
tinf=$(awk '$1 == "edge" && $3 == -1' "$top" | wc -l)
tloop=$(awk '$1 == "edge" && $3 == $2' "$top" | wc -l)
[ $((2 * fin)) -eq "$closed" ] || fail "$case: $fin finite edges for $closed closed half arcs"
[ "$tinf" -eq "$inf" ] || fail "$case: $tinf edges to infinity for $inf half arcs"
# no closed loop in the corpus: none written either
[ "$loops" -eq 0 ] && [ "$tloop" -eq 0 ] || fail "$case: $tloop loop lines for $loops loop half arcs"
vertex_lines "$tsv" | awk '{ print NR - 1, $1 }' > "$top.rows"
# A sphere that touches another from inside has a point or segment cell: no
# edge runs along a triple holding it, so its vertices have fewer edges.
four=4
[ "$case" != internally_tangent ] || four=2
bad=$(awk -v four=$four 'NR == FNR { m[$1] = "," $2 ","; deg[$1] = 0; n4[$1] = split($2, x, ",") == 4; next }
    $1 == "edge" { split($4, t, ","); ends = $3 == -1 ? $2 : $2 " " $3
        k = split(ends, e, " ")
        for (i = 1; i <= k; i++) { deg[e[i]]++
            for (j = 1; j <= 3; j++) if (index(m[e[i]], "," t[j] ",") == 0) print "triple " $0 }
        if ($3 == $2) deg[$2]++ }
    END { for (v in deg) if (n4[v] && deg[v] != four) print "degree " v " " deg[v] }' \
    "$top.rows" "$top")
[ -z "$bad" ] || fail "$case: $bad"
bad=$(awk 'NR == FNR { n = split($2, x, ",")
        for (i = 1; i <= n; i++) for (j = i + 1; j <= n; j++) { p[x[i] " " x[j]] = 1
            if (n == 4) need[x[i] " " x[j]] = 1 } next }
    $1 == "face" { k = $2 " " $3; if (!(k in p)) print "face " k; seen[k] = 1 }
    END { for (k in need) if (!(k in seen)) print "missing face " k }' "$top.rows" "$top")
[ -z "$bad" ] || fail "$case: $bad"
faces=$(grep -c '^face' "$top")
edges=$(grep -c '^edge' "$top")
case $case in
cubic_lattice)
    # topology_cli.sh's hand count, one line per edge: 12 finite edges
    # joining cube centres one step apart, 24 to infinity, 54 faces
    [ "$fin" -eq 12 ] && [ "$tinf" -eq 24 ] && [ "$faces" -eq 54 ] ||
        fail "$case: $fin finite, $tinf infinite edges, $faces faces (expected 12, 24, 54)"
    bad=$(vertex_lines "$tsv" | awk '{ print NR - 1, ($2 > 1) * 4 + ($3 > 1) * 2 + ($4 > 1) }' |
        awk 'NR == FNR { b[$1] = $2; next }
            $1 == "edge" && $3 != -1 { x = b[$2] - b[$3]; if (x < 0) x = -x
                if (x != 1 && x != 2 && x != 4) print $0 }' - "$top")
    [ -z "$bad" ] || fail "$case: edge between non-adjacent centres: $bad"
    [ "$(awk '$1 == "edge" && $3 != -1 { print $2, $3 }' "$top" | sort -u | wc -l)" -eq 12 ] ||
        fail "$case: finite edges do not join 12 distinct pairs" ;;
coplanar_centres)
    # the lens: the two vertices 0,7,8,10 (above and below the plane) are
    # joined by three edges and are a component of their own
    a=$(awk '$2 == "0,7,8,10" { print $1 }' "$top.rows" | head -1)
    b=$(awk '$2 == "0,7,8,10" { print $1 }' "$top.rows" | tail -1)
    [ "$a" != "$b" ] || fail "$case: the lens vertices are not two"
    [ "$(awk -v a="$a" -v b="$b" '$1 == "edge" && $2 == a && $3 == b' "$top" | wc -l)" -eq 3 ] ||
        fail "$case: the lens vertices are not joined by three edges"
    [ "$comps" -eq 2 ] || fail "$case: $comps components" ;;
jittered_lattice)
    # all 196 edges (the sampling topology wrote 187: nine join vertices
    # about 3e8 A away whose coordinates coincide in doubles)
    [ "$edges" -eq 196 ] || fail "$case: $edges edges, expected 196" ;;
internally_tangent)
    # the vertex at the origin lies on the edge of 1, 2, 3 (the line x = y = z),
    # which runs through it to infinity both ways
    [ "$(awk '$1 == "edge" && $2 == 0 && $3 == -1 && $4 == "1,2,3"' "$top" | wc -l)" -eq 2 ] &&
        [ "$edges" -eq 2 ] || fail "$case: $edges edges, expected the two halves of 1,2,3" ;;
bcc_lattice)
    [ "$edges" -eq 168 ] && [ "$faces" -eq 130 ] ||
        fail "$case: $edges edges, $faces faces (expected 168, 130)" ;;
esac
exit 0

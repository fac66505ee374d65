#!/usr/bin/env bash
# test_deform_cli.sh EXE — `subspectra deform` from the outside: the refusals
# (unknown pattern, displacement count, target topology, a point outside,
# --method exact where the evaluator does not reach), a translation moving
# every point by the translation, the formats (JSON statuses, VTK lines,
# checker labels, PNG).
set -u
exe=$1
SS_EXPECT_TIMEOUT=120
. "$(dirname "$0")/../ss_expect.sh"
data="$(dirname "$0")/../../data/meshes"
tets="$data/cube-6tets.mesh"
hexes="$data/hexstar-icosahedron.mesh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

expect 0 "--pattern P" "$exe" deform --help
expect 2 "unknown pattern 'waves': expected grid or checker" "$exe" deform --scheme tetoct "$tets" --pattern waves
expect 2 "exactly one of --points and --pattern" "$exe" deform --scheme tetoct "$tets"
# a mesh with fields (issue 36): named, and refused rather than dropped silently
awk '/^Dimension/ {print "Dimension 4"; next} /^Vertices/ {print; getline; print; n = $1; next}
  n > 0 {$NF = 2.5 " " $NF; n--} {print}' "$tets" >"$tmp/f4.mesh"
expect 2 "f4.mesh carries 1 field \\(w\\), which deform does not evaluate yet" "$exe" deform --scheme tetoct "$tmp/f4.mesh" --pattern grid
printf '0.1 0.2 0.3\n0.5 0.5 0.5\n' > "$tmp/p.txt"
printf '0 0 0\n0 0 1\n1 0 0\n' > "$tmp/d3.txt"
expect 2 "d3.txt has 3 displacements; .*cube-6tets.mesh has 8 control points" "$exe" deform --scheme tetoct "$tets" --points "$tmp/p.txt" --displace "$tmp/d3.txt"
expect 2 "target .* does not have the topology of .*: 63 vertices, not 8" "$exe" deform --scheme tetoct "$tets" --points "$tmp/p.txt" --target "$hexes"
# the same vertices, one tet with another vertex
sed 's/^1 2 4 8 0$/1 2 4 7 0/' "$tets" > "$tmp/other.mesh"
expect 2 "does not have the topology of .*: its tetrahedra have other vertices" "$exe" deform --scheme tetoct "$tets" --points "$tmp/p.txt" --target "$tmp/other.mesh"
printf '0.5 0.5 0.5\n2 0.5 0.5\n' > "$tmp/out.txt"
expect 2 "point 2 \(2 0.5 0.5\) of .*out.txt lies outside every cell" "$exe" deform --scheme tetoct "$tets" --points "$tmp/out.txt"
expect 2 "--method exact: point 1 is in a tetrahedron" "$exe" deform --scheme tetoct "$tets" --points "$tmp/p.txt" --method exact
printf '0.1 0.2 x\n' > "$tmp/bad.txt"
expect 2 "bad.txt:1: expected three finite numbers" "$exe" deform --scheme tetoct "$tets" --points "$tmp/bad.txt"

# a translation by (1, 2, 3) moves every image by (1, 2, 3) (rows sum to 1)
for i in 1 2 3 4 5 6 7 8; do echo "1 2 3"; done > "$tmp/t.txt"
"$exe" deform --scheme tetoct "$tets" --points "$tmp/p.txt" --displace "$tmp/t.txt" --levels 2 > "$tmp/t.out" 2>/dev/null
d=$(grep -v '^#' "$tmp/t.out" | awk '{for (a = 0; a < 3; a++) {e = $(13 + a) - $(10 + a) - (a + 1); if (e < 0) e = -e; if (e > m) m = e}} END {print (NR == 2 && m <= 1e-13) ? "ok" : NR " " m}')
checks=$((checks + 1)); [ "$d" = "ok" ] || fail "translation: $d"
# the same on the exact path (hexes, mlca)
"$exe" deform --scheme mlca "$hexes" --pattern grid --n 2 --samples 5 --displace <(for i in $(seq 63); do echo "1 2 3"; done) > "$tmp/h.out" 2>"$tmp/h.err"
d=$(grep -v '^#' "$tmp/h.out" | awk '$4 == "ok" {n++; for (a = 0; a < 3; a++) {e = $(13 + a) - $(10 + a) - (a + 1); if (e < 0) e = -e; if (e > m) m = e}} END {print (n > 0 && m <= 1e-12) ? "ok" : n " " m}')
checks=$((checks + 1)); [ "$d" = "ok" ] || fail "exact translation: $d"
checks=$((checks + 1)); grep -q "the exact limit" "$tmp/h.err" || fail "mlca on hexes did not take the exact path: $(cat "$tmp/h.err")"
# patterns: outside points reported, not dropped; JSON statuses
expect 0 '"status":"outside"' "$exe" deform --scheme mlca "$hexes" --pattern grid --n 4 --samples 5 --format json
expect 0 "240 points, [1-9][0-9]* outside the mesh" "$exe" deform --scheme mlca "$hexes" --pattern grid --n 4 --samples 5
expect 0 '"label":1' "$exe" deform --scheme tetoct "$tets" --pattern checker --n 2 --samples 4 --levels 1 --format json
expect 0 "" "$exe" deform --scheme tetoct "$tets" --pattern grid --n 2 --samples 6 --levels 1 -o "$tmp/g.vtk"
checks=$((checks + 1)); grep -q "^LINES 12 84$" "$tmp/g.vtk" || fail "vtk: not 12 lines of 6 points"
expect 0 "" "$exe" deform --scheme tetoct "$tets" --pattern checker --n 2 --samples 4 --levels 1 -o "$tmp/c.png"
checks=$((checks + 1)); [ "$(head -c 4 "$tmp/c.png" | tail -c 3)" = "PNG" ] || fail "no PNG written"
expect_done deform_cli

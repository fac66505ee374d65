#!/usr/bin/env bash
# test_limit_cli.sh EXE — `subspectra limit` from the outside: the JSON
# contract (cell, u, v, w, point, jacobian), counts of --samples and --gauss
# points, Gauss weights summing to 1 per cell, VTK and -o, the reference
# agreeing with the direct walk, and the exit statuses of bad input.
set -u
exe=$1
SS_EXPECT_TIMEOUT=120
. "$(dirname "$0")/../ss_expect.sh"
. "$(dirname "$0")/limit_grid.sh"
mesh="$(dirname "$0")/../../data/meshes/hexstar-icosahedron.mesh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

expect 0 "Gauss-Legendre" "$exe" limit --help
expect 0 '"cell":3,"u":0.25,"v":0.5,"w":0.125,"point":\[' "$exe" limit --scheme mlca "$mesh" --at "3 0.25 0.5 0.125" --format json
expect 0 '"jacobian":\[\[' "$exe" limit --scheme mlca "$mesh" --at "3 0.25 0.5 0.125" --format json --derivatives
# 20 cells x 2^3 samples; 20 x 3^3 Gauss points
n=$("$exe" limit --scheme mlca "$mesh" --samples 2 | wc -l)
checks=$((checks + 1)); [ "$n" -eq 160 ] || fail "--samples 2: $n lines, not 160"
"$exe" limit --scheme mlca "$mesh" --gauss 3 --format json > "$tmp/g.json"
n=$(wc -l < "$tmp/g.json")
checks=$((checks + 1)); [ "$n" -eq 540 ] || fail "--gauss 3: $n lines, not 540"
# the weights of one cell's Gauss points sum to 1 (the volume of [0,1]^3)
w=$(grep '"cell":1,' "$tmp/g.json" | sed 's/.*"weight":\([^,]*\),.*/\1/' | awk '{s += $1} END {e = s - 1; if (e < 0) e = -e; print (e <= 1e-14) ? "ok" : s}')
checks=$((checks + 1)); [ "$w" = "ok" ] || fail "Gauss weights of cell 1 sum to $w"
# direct and reference agree (text: 7 columns; compare the points to 1e-12)
a=$("$exe" limit --scheme mlca "$mesh" --at "5 0.01 0.3 0.002" --at "7 0.6 0.1 0.9")
b=$("$exe" limit --scheme mlca "$mesh" --at "5 0.01 0.3 0.002" --at "7 0.6 0.1 0.9" --reference)
d=$(paste <(echo "$a") <(echo "$b") | awk '{for (i = 5; i <= 7; i++) {e = $i - $(i + 7); if (e < 0) e = -e; if (e > m) m = e}} END {print (m <= 1e-12) ? "ok" : m}')
checks=$((checks + 1)); [ "$d" = "ok" ] || fail "direct vs reference differ by $d"
# the same for ccsolid, and for ccsolid-tensor on the star refined once (its
# spokes' midpoints are then interior vertices on extraordinary edges, where
# the variant's rule differs: the two limits differ there)
expect 0 "ccsolid-tensor level 1" "$exe" subdivide --scheme ccsolid-tensor "$mesh" -o "$tmp/t1.mesh"
for s in ccsolid ccsolid-tensor; do
  for m in "$mesh" "$tmp/t1.mesh"; do
    a=$("$exe" limit --scheme $s "$m" --at "5 0.01 0.3 0.002" --at "7 0.6 0.1 0.9")
    b=$("$exe" limit --scheme $s "$m" --at "5 0.01 0.3 0.002" --at "7 0.6 0.1 0.9" --reference)
    d=$(paste <(echo "$a") <(echo "$b") | awk '{for (i = 5; i <= 7; i++) {e = $i - $(i + 7); if (e < 0) e = -e; if (e > m) m = e}} END {print (m <= 1e-12) ? "ok" : m}')
    checks=$((checks + 1)); [ "$d" = "ok" ] || fail "$s, $m: direct vs reference differ by $d"
  done
done
a=$("$exe" limit --scheme ccsolid "$tmp/t1.mesh" --samples 3 | md5sum)
b=$("$exe" limit --scheme ccsolid-tensor "$tmp/t1.mesh" --samples 3 | md5sum)
checks=$((checks + 1)); [ "$a" != "$b" ] || fail "ccsolid-tensor's limit is ccsolid's on a mesh with vertices on extraordinary edges"
# VTK with -o: the sampled volume as hexahedra (20 cells x 2^3)
expect 0 "" "$exe" limit --scheme mlca "$mesh" --samples 3 --format vtk -o "$tmp/v.vtk"
checks=$((checks + 1)); grep -q "^CELLS 160 1440" "$tmp/v.vtk" || fail "vtk: no 160 hexahedra"
# Gauss points lie inside the cells, where the Jacobian is defined
expect 0 "" "$exe" limit --scheme mlca "$mesh" --gauss 2 --format vtk -d -o "$tmp/g.vtk"
checks=$((checks + 1)); grep -q "^SCALARS jacobian_det" "$tmp/g.vtk" || fail "vtk: no det J"
checks=$((checks + 1)); grep -q "^CELLS 160 320" "$tmp/g.vtk" || fail "vtk: no 160 points"
# a point refused (unknown cell, parameter outside [0,1]) is written with
# its status and the message, exit 1 (test_limit_batch.sh: batches)
expect 1 "cell 21 does not exist" "$exe" limit --scheme mlca "$mesh" --at "21 0.5 0.5 0.5"
expect 1 "parameter u = 1.5 is outside" "$exe" limit --scheme mlca "$mesh" --at "1 1.5 0.5 0.5"
# bad input: exit 2 with a message
expect 2 "expected \"CELL U V W\"" "$exe" limit --scheme mlca "$mesh" --at "1 0.5 0.5"
expect 2 "expected \"CELL U V W\"" "$exe" limit --scheme mlca "$mesh" --at "0 0.5 0.5 0.5"
expect 2 "exactly one of --at, --samples and --gauss" "$exe" limit --scheme mlca "$mesh"
expect 2 "exactly one of --at, --samples and --gauss" "$exe" limit --scheme mlca "$mesh" --samples 2 --gauss 2
expect 2 "--scheme is required" "$exe" limit "$mesh" --samples 2
expect 2 "tetoct is not one" "$exe" limit --scheme tetoct "$mesh" --samples 2
expect 2 "hexahedra only" "$exe" limit --scheme mlca "$(dirname "$0")/../../data/meshes/cube-6tets.mesh" --samples 2
# creases (issue 36): the cube with crease quadrilaterals on its faces is
# evaluated (every sample, with its Jacobian) as subdivide refines it; a
# crease that lies on no hexahedron (a segment across a face) is refused
cube="$(dirname "$0")/../../data/meshes/cube-creased.mesh"
for s in mlca ccsolid; do
  c=$("$exe" limit --scheme $s "$cube" --samples 4 -d | awk 'NF == 16' | wc -l)
  checks=$((checks + 1)); [ "$c" -eq 64 ] || fail "$s: cube-creased.mesh: $c full sample lines, not 64"
done
sed 's/^Quadrilaterals$/Edges\n1\n1 4 0\nQuadrilaterals/' "$cube" > "$tmp/diag.mesh"
# the refusal names the cell, its vertices and why; subdivide takes each of
# these meshes, as the message says
expect 2 "segment 1 \(vertices 1 4\) is not an edge of any hexahedron: its vertices are corners of hexahedron 1 but not the ends of one of its edges \(a diagonal\); subdivide refines it" "$exe" limit --scheme ccsolid "$tmp/diag.mesh" --samples 2
expect 0 "wrote" "$exe" subdivide --scheme ccsolid "$tmp/diag.mesh" -o "$tmp/diag.out.mesh"
sed 's/^Quadrilaterals$/Quadrilaterals\n7\n1 2 8 7 0/; 0,/^6$/{/^6$/d}' "$cube" > "$tmp/qdiag.mesh"
expect 2 "quadrilateral 1 \(vertices 1 2 8 7\) is not a face of any hexahedron: its vertices are corners of hexahedron 1 but not one of its faces" "$exe" limit --scheme mlca "$tmp/qdiag.mesh" --samples 2
expect 0 "wrote" "$exe" subdivide --scheme mlca "$tmp/qdiag.mesh" -o "$tmp/qdiag.out.mesh"
awk '/^Vertices/ {print; getline; print $1 + 1; v = 1; next} v && /^$/ && !done {print "5 5 5 0"; done = 1} {print} END {print "Corners\n1\n9"}' "$cube" | sed '$!{/^End$/d}' > "$tmp/vfar.mesh"
expect 2 "corner 1 \(vertices 9\) is not a corner of any hexahedron: its vertex 9 is on no hexahedron" "$exe" limit --scheme mlca "$tmp/vfar.mesh" --samples 2
expect 0 "wrote" "$exe" subdivide --scheme mlca "$tmp/vfar.mesh" -o "$tmp/vfar.out.mesh"
expect 2 "--gauss '0'" "$exe" limit --scheme mlca "$mesh" --gauss 0
expect 2 "--format: expected text, json, vtk or vtu" "$exe" limit --scheme mlca "$mesh" --gauss 1 --format xml
expect 2 "No such file" "$exe" limit --scheme mlca /nonexistent.mesh --gauss 1
# the Jacobian exactly at the extraordinary vertex is not defined: exit 1
expect 1 "Jacobian" "$exe" limit --scheme mlca "$mesh" --at "1 0 0 0" --derivatives
expect 0 "" "$exe" limit --scheme mlca "$mesh" --at "1 0 0 0"
# issue 35: deep points near the icosahedron vertex (a defective run) grow
# like d^(-1 - log2 lambda), lambda = 0.628884076988 (test_limit_depth):
# J(2^-158 x) = (2 lambda)^100 J(2^-58 x) (the old walk printed noise with
# its sign flipped), and agree with the reference at 2^-58 to 1e-11
j1=$("$exe" limit --scheme mlca "$mesh" --at "1 0x1p-58 0x1p-58 0x1p-58" -d | cut -d' ' -f8)
j2=$("$exe" limit --scheme mlca "$mesh" --at "1 0x1p-158 0x1p-158 0x1p-158" -d | cut -d' ' -f8)
r=$(awk -v a="$j1" -v b="$j2" 'BEGIN {g = b / a; e = exp(100 * log(2 * 0.628884076988)); print (a > 0 && g > (1 - 1e-6) * e && g < (1 + 1e-6) * e) ? "ok" : g / e}')
checks=$((checks + 1)); [ "$r" = "ok" ] || fail "J[0][0] at 2^-58, 2^-158: $j1, $j2 (ratio / (2 lambda)^100 = $r)"
d=3.4694469519536142e-18
a=$("$exe" limit --scheme mlca "$mesh" --at "1 $d $d $d" -d)
b=$("$exe" limit --scheme mlca "$mesh" --at "1 $d $d $d" -d --reference)
r=$(paste <(echo "$a") <(echo "$b") | awk '{for (i = 8; i <= 16; i++) {e = $i - $(i + 16); if (e < 0) e = -e; if (e > m) m = e; s = $(i + 16); if (s < 0) s = -s; if (s > n) n = s}} END {print (m <= 1e-11 * n) ? "ok" : m / n}')
checks=$((checks + 1)); [ "$r" = "ok" ] || fail "2^-58: direct vs reference Jacobian off by $r of |J|"
# subnormal parameters: finite numbers and valid JSON (no NaN, inf)
grid="$tmp/grid.mesh"
{
  printf 'MeshVersionFormatted 2\nDimension 3\nVertices\n64\n'
  for k in 0 1 2 3; do for j in 0 1 2 3; do for i in 0 1 2 3; do echo "$i $j $k 0"; done; done; done
  printf 'Hexahedra\n27\n'
  for k in 0 1 2; do for j in 0 1 2; do for i in 0 1 2; do
    v=$((i + 4 * j + 16 * k + 1))
    echo "$v $((v + 1)) $((v + 5)) $((v + 4)) $((v + 16)) $((v + 17)) $((v + 21)) $((v + 20)) 0"
  done; done; done
  printf 'End\n'
} > "$grid"
for s in mlca ccsolid; do
  out=$("$exe" limit --scheme $s "$grid" --at "1 1e-310 0.3 0.6" --at "1 4.9406564584124654e-324 1e-320 0.3" --at "14 1e-310 0.5 0.5" -d --format json)
  checks=$((checks + 1)); [ $? -eq 0 ] && ! echo "$out" | grep -qi 'nan\|inf' || fail "$s: subnormal parameters: $out"
  out=$("$exe" limit --scheme $s "$grid" --at "1 1e-310 0.3 0.6" -d --format vtk)
  checks=$((checks + 1)); ! echo "$out" | grep -qi 'nan\|inf' || fail "$s: subnormal parameters in VTK"
done
# ccsolid on grids of 1, 2, 3 cells a side: every sample (boundary edges and
# corners included) has a Jacobian
for n in 1 2 3; do
  limit_grid $n > "$tmp/g$n.mesh"
  n3=$(( 27 * n * n * n ))
  c=$("$exe" limit --scheme ccsolid "$tmp/g$n.mesh" --samples 3 -d | wc -l)
  checks=$((checks + 1)); [ "$c" -eq "$n3" ] || fail "ccsolid grid $n: $c sample lines, not $n3"
done
# 5 wedges x 3 layers around an edge of valence 5, straight along z (issue 35
# item 3): at (d, d, 1/2) of a middle-layer cell the along row is (0, 0, 1)
# (the mesh is its own mirror image in z = 3/2, and z = layer is reproduced)
# down to 1e-300 and below; on the bottom boundary there it is refused, exit 1
awk 'BEGIN { pi = atan2(0, -1)
  printf "MeshVersionFormatted 2\nDimension 3\nVertices\n44\n"
  for (k = 0; k <= 3; k++) {
    print 0, 0, k, 0
    for (s = 0; s < 5; s++) printf "%.17g %.17g %d 0\n", cos(2 * pi * s / 5), sin(2 * pi * s / 5), k
    for (s = 0; s < 5; s++) printf "%.17g %.17g %d 0\n", cos(2 * pi * s / 5) + cos(2 * pi * (s + 1) / 5), sin(2 * pi * s / 5) + sin(2 * pi * (s + 1) / 5), k }
  printf "Hexahedra\n15\n"
  for (k = 0; k < 3; k++) for (s = 0; s < 5; s++) {
    b = 11 * k + 1; t = b + 11
    print b, b + 1 + s, b + 6 + s, b + 1 + (s + 1) % 5, t, t + 1 + s, t + 6 + s, t + 1 + (s + 1) % 5, 0 }
  print "End" }' > "$tmp/ring5.mesh"
for s in mlca ccsolid; do
  for d in 1e-20 1e-150 1e-200 1e-300 4.9406564584124654e-324; do
    r=$("$exe" limit --scheme $s "$tmp/ring5.mesh" --at "6 $d $d 0.5" -d | awk '{e = $14; if (e < 0) e = -e; f = $15; if (f < 0) f = -f; g = $16 - 1; if (g < 0) g = -g
      m = e > f ? e : f; m = m > g ? m : g; print (NF == 16 && m <= 1e-14) ? "ok" : $14 " " $15 " " $16}')
    checks=$((checks + 1)); [ "$r" = "ok" ] || fail "$s: along row at ($d, $d, 1/2) of 5 wedges: $r"
  done
  expect 1 "the derivative d/dW cannot be trusted" "$exe" limit --scheme $s "$tmp/ring5.mesh" --at "1 1e-300 1e-300 0" -d
done
# flat, folded and inverted hexes are refused as subdivide refuses them
two() {
  printf 'MeshVersionFormatted 2\nDimension 3\nVertices\n16\n'
  for k in 0 1; do for j in 0 1; do for i in 0 1 2; do echo "$i $j $k 0"; done; done; done
  printf '1 0 0 0\n2 0 0 0\n2 1 0 0\n1 1 0 0\n'
  printf 'Hexahedra\n2\n1 2 5 4 7 8 11 10 0\n%s 0\nEnd\n' "$1"
}
two "2 3 6 5 8 9 12 11" > "$tmp/ok.mesh"
two "2 5 6 3 8 11 12 9" > "$tmp/mirrored.mesh"
two "2 3 6 5 8 12 9 11" > "$tmp/folded.mesh"
two "2 3 6 5 13 14 15 16" > "$tmp/flat.mesh"
expect 0 "" "$exe" limit --scheme mlca "$tmp/ok.mesh" --at "2 0.5 0.5 0.5" -d
expect 2 "hexahedron 2 is inverted" "$exe" limit --scheme mlca "$tmp/mirrored.mesh" --at "2 0.5 0.5 0.5" -d
expect 2 "hexahedron 2 is flat or folded" "$exe" limit --scheme mlca "$tmp/folded.mesh" --at "2 0.5 0.5 0.5" -d
expect 2 "hexahedron 2 is flat or folded" "$exe" limit --scheme ccsolid "$tmp/flat.mesh" --samples 2
# hostile parameters: the point refused naming the parameter, exit 1
expect 1 "parameter u = 1.0000000000000002 is outside" "$exe" limit --scheme mlca "$mesh" --at "1 1.0000000000000002 0.5 0.5"
expect 1 "parameter w = -4.9406564584124654e-324 is outside" "$exe" limit --scheme mlca "$mesh" --at "1 0.5 0.5 -4.9406564584124654e-324"
expect 1 "parameter v = nan is outside" "$exe" limit --scheme mlca "$mesh" --at "1 0.5 nan 0.5"
expect 1 "parameter u = inf is outside" "$exe" limit --scheme mlca "$mesh" --at "1 inf 0.5 0.5"
# fields (issue 36): a Medit 4th coordinate is the field w.  The 3x3x3 grid,
# jittered, with w = 2x - 3y + z/2 + 1 (an affine field reproduces itself:
# w = a.p + b at the limit point, its gradient J a) and inverted hexes' check
# done on the positions
awk 'BEGIN { srand(11)
  printf "MeshVersionFormatted 2\nDimension 4\nVertices\n64\n"
  for (k = 0; k < 4; k++) for (j = 0; j < 4; j++) for (i = 0; i < 4; i++) {
    x = i + 0.2 * (rand() - 0.5); y = j + 0.2 * (rand() - 0.5); z = k + 0.2 * (rand() - 0.5)
    printf "%.17g %.17g %.17g %.17g 0\n", x, y, z, 2 * x - 3 * y + z / 2 + 1 }
  printf "Hexahedra\n27\n"
  for (k = 0; k < 3; k++) for (j = 0; j < 3; j++) for (i = 0; i < 3; i++) {
    v = i + 4 * (j + 4 * k) + 1
    print v, v + 1, v + 5, v + 4, v + 16, v + 17, v + 21, v + 20, 0 }
  print "End" }' > "$tmp/w.mesh"
# the same positions without w
awk 'NR == 2 {print "Dimension 3"; next} NF == 5 {print $1, $2, $3, $5; next} {print}' "$tmp/w.mesh" > "$tmp/p.mesh"
for s in mlca ccsolid; do
  "$exe" limit --scheme $s "$tmp/w.mesh" --samples 3 -d > "$tmp/w.txt"
  "$exe" limit --scheme $s "$tmp/p.mesh" --samples 3 -d > "$tmp/p.txt"
  checks=$((checks + 1)); [ "$(wc -l < "$tmp/w.txt")" -eq 729 ] || fail "$s: fields: not 729 lines"
  r=$(awk '{w = 2 * $5 - 3 * $6 + $7 / 2 + 1; e = $17 - w; if (e < 0) e = -e; if (e > m) m = e
            for (a = 0; a < 3; a++) { g = 2 * $(8 + 3 * a) - 3 * $(9 + 3 * a) + $(10 + 3 * a) / 2
              e = $(18 + a) - g; if (e < 0) e = -e; if (e > n) n = e }
            if (NF != 20) bad = 1 }
          END {print (!bad && m <= 1e-12 && n <= 1e-12) ? "ok" : m " " n " " bad}' "$tmp/w.txt")
  checks=$((checks + 1)); [ "$r" = "ok" ] || fail "$s: affine field w off by $r (value, gradient)"
  # the positions and Jacobians are those of the mesh without w, bit for bit
  checks=$((checks + 1)); cmp -s <(cut -d' ' -f1-16 "$tmp/w.txt") "$tmp/p.txt" || fail "$s: positions change with a field"
  # the reference carries the field too
  a=$("$exe" limit --scheme $s "$tmp/w.mesh" --at "14 0.3 0.6 0.2" --at "1 0.01 0.5 0.7" -d)
  b=$("$exe" limit --scheme $s "$tmp/w.mesh" --at "14 0.3 0.6 0.2" --at "1 0.01 0.5 0.7" -d --reference)
  d=$(paste -d' ' <(echo "$a") <(echo "$b") | awk '{for (i = 17; i <= 20; i++) {e = $i - $(i + 20); if (e < 0) e = -e; if (e > m) m = e}} END {print (m <= 1e-12) ? "ok" : m}')
  checks=$((checks + 1)); [ "$d" = "ok" ] || fail "$s: field: direct vs reference differ by $d"
done
expect 0 '"point":\[.*"fields":{"w":.*"field_gradients":{"w":\[' "$exe" limit --scheme mlca "$tmp/w.mesh" --at "14 0.5 0.5 0.5" -d --format json
out=$("$exe" limit --scheme mlca "$tmp/w.mesh" --at "14 0.5 0.5 0.5" --format json)
checks=$((checks + 1)); echo "$out" | grep -q '"fields":{"w":' && ! echo "$out" | grep -q field_gradients || fail "fields without -d: $out"
"$exe" limit --scheme mlca "$tmp/w.mesh" --samples 2 -d --format vtk -o "$tmp/w.vtk"
checks=$((checks + 1)); grep -q "^SCALARS w double 1" "$tmp/w.vtk" && grep -q "^SCALARS w_gradient double 3" "$tmp/w.vtk" || fail "vtk: no w, w_gradient"
# fields from gmsh (issue 36): the same mesh as a .msh with w as $NodeData
# gives the same points, Jacobians, values and gradients, byte for byte, and
# subdivide keeps it as Medit's 4th coordinate, the same vertices
tomsh() { # tomsh MEDIT [NVAL]: the Medit file with w as $NodeData (its first NVAL values)
  awk -v nval="${2:-64}" '/^Vertices/ {sec = "V"} /^Hexahedra/ {sec = "H"}
    sec == "V" && NF == 5 {n++; X[n] = $1; Y[n] = $2; Z[n] = $3; W[n] = $4}
    sec == "H" && NF == 9 {e++; H[e] = $1 " " $2 " " $3 " " $4 " " $5 " " $6 " " $7 " " $8}
    END { printf "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n%d\n", n
      for (i = 1; i <= n; i++) print i, X[i], Y[i], Z[i]
      printf "$EndNodes\n$Elements\n%d\n", e
      for (i = 1; i <= e; i++) print i, 5, 2, 1, 1, H[i]
      printf "$EndElements\n$NodeData\n1\n\"density\"\n1\n0.0\n3\n0\n1\n%d\n", nval
      for (i = 1; i <= nval; i++) print i, W[i]
      printf "$EndNodeData\n" }' "$1"
}
tomsh "$tmp/w.mesh" > "$tmp/w.msh"
if "$exe" limit --scheme mlca "$tmp/w.msh" --at "1 0.5 0.5 0.5" 2>&1 | grep -q "built without gmsh"; then
  echo "gmsh \$NodeData: skipped (built without gmsh)"
else
  for s in mlca ccsolid; do
    "$exe" limit --scheme $s "$tmp/w.mesh" --samples 3 -d > "$tmp/w.txt"
    "$exe" limit --scheme $s "$tmp/w.msh" --samples 3 -d > "$tmp/wm.txt"
    checks=$((checks + 1)); [ "$(wc -l < "$tmp/wm.txt")" -eq 729 ] && cmp -s "$tmp/w.txt" "$tmp/wm.txt" || fail "$s: \$NodeData field differs from Medit's w"
  done
  expect 0 "" "$exe" subdivide --scheme mlca "$tmp/w.msh" -o "$tmp/sm.mesh"
  expect 0 "" "$exe" subdivide --scheme mlca "$tmp/w.mesh" -o "$tmp/s.mesh"
  checks=$((checks + 1)); cmp -s <(awk 'NF == 5' "$tmp/sm.mesh") <(awk 'NF == 5' "$tmp/s.mesh") || fail "subdivide: \$NodeData not kept as w"
  tomsh "$tmp/w.mesh" 63 > "$tmp/w63.msh"
  expect 2 "NodeData gives node 64 no value" "$exe" limit --scheme mlca "$tmp/w63.msh" --samples 2
  { tomsh "$tmp/w.mesh"; awk '/^\$NodeData/ {on = 1} on' "$tmp/w.msh" | sed 's/density/stiffness/'; } > "$tmp/w2.msh"
  # field names (issue 36): the view's name; two views are two fields, a
  # 3-component view (here the position) NAME_x, _y, _z
  expect 0 '"fields":\{"density":' "$exe" limit -s mlca "$tmp/w.msh" --at "14 0.5 0.5 0.5" -f json
  out=$("$exe" limit --scheme mlca "$tmp/w2.msh" --at "14 0.3 0.6 0.2" -f json)
  checks=$((checks + 1))
  echo "$out" | grep -Eq '"fields":\{"density":([-0-9.e]+),"stiffness":\1\}' ||
    fail "two \$NodeData views: not density and stiffness, equal: $out"
  { tomsh "$tmp/w.mesh"
    awk '/^Vertices/ {sec = "V"} /^Hexahedra/ {sec = ""} sec == "V" && NF == 5 {n++; L[n] = n " " $1 " " $2 " " $3}
      END { printf "$NodeData\n1\n\"pos\"\n1\n0.0\n3\n0\n3\n%d\n", n
        for (i = 1; i <= n; i++) print L[i]
        printf "$EndNodeData\n" }' "$tmp/w.mesh"; } > "$tmp/wv.msh"
  "$exe" limit --scheme mlca "$tmp/wv.msh" --samples 3 -d -f json > "$tmp/wv.json"
  checks=$((checks + 1))
  python3 - "$tmp/wv.json" <<'PY' || fail "a vector \$NodeData view: pos_x/_y/_z are not the limit point and its Jacobian"
import json, sys
n = 0
for line in open(sys.argv[1]):
    p = json.loads(line)
    f, g, x, J = p["fields"], p["field_gradients"], p["point"], p["jacobian"]
    assert sorted(f) == ["density", "pos_x", "pos_y", "pos_z"], sorted(f)
    for a, c in enumerate("xyz"):
        assert abs(f["pos_" + c] - x[a]) <= 1e-13 * max(1, abs(x[a])), (f, x)
        for r in range(3):
            assert abs(g["pos_" + c][r] - J[r][a]) <= 1e-13 * max(1, abs(J[r][a]))
    n += 1
assert n == 729
PY
fi
# a vertex without its w shifts the section: refused by the reader, exit 2
awk 'NR == 9 {print $1, $2, $3, $5; next} {print}' "$tmp/w.mesh" > "$tmp/short.mesh"
expect 2 "short.mesh:[0-9]*: vertex reference .* is not an integer" "$exe" limit --scheme mlca "$tmp/short.mesh" --samples 2
awk 'NR == 9 {print $1, $2, $3, "nan", $5; next} {print}' "$tmp/w.mesh" > "$tmp/nan.mesh"
expect 2 "coordinate 'nan' is not a finite number" "$exe" limit --scheme mlca "$tmp/nan.mesh" --samples 2
# subdivide keeps w: in Medit as the 4th coordinate, in VTK as point data w
expect 0 "" "$exe" subdivide --scheme mlca "$tmp/w.mesh" -o "$tmp/s.mesh"
checks=$((checks + 1)); grep -q "^Dimension 4" "$tmp/s.mesh" || fail "subdivide: w dropped in Medit"
expect 0 "" "$exe" subdivide --scheme mlca "$tmp/w.mesh" -o "$tmp/s.vtk"
checks=$((checks + 1)); grep -q "^SCALARS w double 1" "$tmp/s.vtk" || fail "subdivide: w dropped in VTK"
expect 2 "OBJ holds at most 3 coordinates, not 4" "$exe" subdivide --scheme mlca "$tmp/w.mesh" -o "$tmp/s.obj"
expect_done limit_cli

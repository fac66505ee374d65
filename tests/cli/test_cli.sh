#!/usr/bin/env bash
# test_cli.sh EXE SRCDIR — the command-line contract of `subspectra subdivide`:
# exit statuses (0 ok, 2 bad usage or input), messages that name the problem,
# JSON output, and every malformed sample file rejected with status 2.
set -u
exe=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
. "$(dirname "$0")/../ss_expect.sh"

m=$src/data/meshes
expect 0 "subdivide" "$exe" --help
expect 0 "tetoct" "$exe" subdivide --help
expect 2 "unknown command 'frobnicate'" "$exe" frobnicate
expect 2 "usage" "$exe"
expect 2 "unknown scheme 'butterfly'" "$exe" subdivide --scheme butterfly "$m/cube-6tets.mesh" -o "$tmp/o.mesh"
expect 2 "--scheme is required" "$exe" subdivide "$m/cube-6tets.mesh" -o "$tmp/o.mesh"
# box-spline solids: Algorithm 2 by default, the file's diagonals on request
expect 0 "major diagonals: bfs; [0-9]+ of 6 adjacent pairs improper" "$exe" subdivide --scheme boxspline --levels 2 "$m/cube-6tets.mesh" --octahedra-keyword -o "$tmp/b.mesh"
expect 0 "major diagonals: given; [0-9]+ of 240 adjacent pairs improper" "$exe" subdivide --scheme boxspline --diagonals given "$tmp/b.mesh" -o "$tmp/b2.mesh"
expect 0 "boxspline-avg level 2: 125 vertices, 144 tetrahedra, 60 octahedra" "$exe" subdivide --scheme boxspline-avg --levels 2 "$m/cube-6tets.mesh" -o "$tmp/a.mesh"
expect 0 "major diagonals: proper; 0 of 6 adjacent pairs improper" "$exe" subdivide --scheme boxspline --diagonals proper "$m/cube-6tets.mesh" -o "$tmp/p.mesh"
expect 2 "--diagonals: scheme tetoct reads no major diagonals" "$exe" subdivide --scheme tetoct --diagonals bfs "$m/cube-6tets.mesh" -o "$tmp/o.mesh"
expect 2 "--diagonals: expected bfs, proper or given, not 'x'" "$exe" subdivide --scheme boxspline --diagonals x "$m/cube-6tets.mesh" -o "$tmp/o.mesh"
expect 2 "-o OUT is required" "$exe" subdivide --scheme tetoct "$m/cube-6tets.mesh"
expect 2 "no input mesh" "$exe" subdivide --scheme tetoct -o "$tmp/o.mesh"
expect 2 "levels 'abc'" "$exe" subdivide --scheme tetoct --levels abc "$m/cube-6tets.mesh" -o "$tmp/o.mesh"
expect 2 "levels '13'" "$exe" subdivide --scheme tetoct --levels 13 "$m/cube-6tets.mesh" -o "$tmp/o.mesh"
expect 2 "unknown option '--bogus'" "$exe" subdivide --bogus
expect 2 "format of" "$exe" subdivide --scheme mlca "$m/cube-creased.mesh" -o "$tmp/o.xyz"
expect 2 "would make .* cells" "$exe" subdivide --scheme mlca --levels 12 "$m/hexstar-icosahedron.mesh" -o "$tmp/o.mesh"
expect 2 "does not take .*tetrahedra" "$exe" subdivide --scheme mlca "$m/cube-6tets.mesh" -o "$tmp/o.mesh"
expect 2 "does not take .*hexahedra" "$exe" subdivide --scheme loop "$m/cube-creased.mesh" -o "$tmp/o.mesh"
expect 2 "no-such-file" "$exe" subdivide --scheme mlca "$tmp/no-such-file.mesh" -o "$tmp/o.mesh"

# every scheme on a sample it takes, then the output read back
expect 0 "mlca level 2: " "$exe" subdivide --scheme mlca --levels 2 "$m/cube-creased.mesh" -o "$tmp/a.mesh"
expect 0 "read .*a.mesh: 125 vertices, 96 quadrilaterals, 64 hexahedra" "$exe" subdivide --scheme mlca --levels 0 "$tmp/a.mesh" -o "$tmp/a2.mesh"
expect 0 "tetoct level 1: .*24 tetrahedra, 6 octahedra" "$exe" subdivide --scheme tetoct "$m/cube-6tets.mesh" -o "$tmp/b.vtk"
# --hexify (MLCA paper, section 3.3): tets into hexes for the hexahedral schemes
expect 2 "scheme mlca does not take tetrahedra" "$exe" subdivide --scheme mlca "$m/cube-6tets.mesh" -o "$tmp/hx.mesh"
expect 0 "hexified \\(MLCA paper, section 3.3\\): 6 tetrahedra into 24 hexahedra" "$exe" subdivide --scheme mlca --hexify "$m/cube-6tets.mesh" -o "$tmp/hx.mesh"
# 8 corners + 19 edges (12 of the cube, 6 face diagonals, the main one) + 18
# triangles (12 on the boundary, 6 round the diagonal) + 6 tets = 51 points
expect 0 "read .*: 51 vertices, 24 hexahedra" "$exe" subdivide --scheme ccsolid --hexify "$m/cube-6tets.mesh" -o "$tmp/hx.mesh"
expect 2 "--hexify: scheme tetoct is not hexahedral" "$exe" subdivide --scheme tetoct --hexify "$m/cube-6tets.mesh" -o "$tmp/hx.mesh"
# --boundary-c (box-spline paper, figure 14(b)): 3/(8k) moves the boundary
# (test_boxspline_surface checks the weights); refused where Loop's beta is fixed
expect 0 "wrote" "$exe" subdivide --scheme boxspline "$m/cube-6tets.mesh" -o "$tmp/c1.mesh"
expect 0 "wrote" "$exe" subdivide --scheme boxspline --boundary-c 3/8k "$m/cube-6tets.mesh" -o "$tmp/c2.mesh"
expect 0 "wrote" "$exe" subdivide --scheme boxspline --boundary-c loop "$m/cube-6tets.mesh" -o "$tmp/c3.mesh"
expect 0 "^" cmp "$tmp/c1.mesh" "$tmp/c3.mesh"
expect 1 "differ" cmp "$tmp/c1.mesh" "$tmp/c2.mesh"
expect 2 "--boundary-c: expected loop or 3/8k, not 'beta'" "$exe" subdivide --scheme boxspline --boundary-c beta "$m/cube-6tets.mesh" -o "$tmp/c4.mesh"
expect 2 "--boundary-c: scheme tetoct has no choice" "$exe" subdivide --scheme tetoct --boundary-c 3/8k "$m/cube-6tets.mesh" -o "$tmp/c4.mesh"
# quasi48 adaptivity (test_quasi48_adapt checks conformity and confinement):
# a box holding the mesh is plain subdivision, a small one refines less
ico=$m/icosahedron.obj
expect 0 "quasi48 level 4: 135 vertices" "$exe" subdivide --scheme quasi48 --levels 4 "$ico" -o "$tmp/q1.obj"
expect 0 "quasi48 level 4: 135 vertices" "$exe" subdivide --scheme quasi48 --levels 4 --adapt-box -2,-2,-2,2,2,2 "$ico" -o "$tmp/q2.obj"
expect 0 "^" cmp "$tmp/q1.obj" "$tmp/q2.obj"
expect 0 "quasi48 level 4: [0-9]{2} vertices" "$exe" subdivide --scheme quasi48 --levels 4 --adapt-box 0,0,0,2,2,2 "$ico" -o "$tmp/q3.obj"
expect 0 "quasi48 level 4: [0-9]{2} vertices" "$exe" subdivide --scheme quasi48 --levels 4 --adapt-edge-length 0.6 "$ico" -o "$tmp/q3.obj"
expect 2 "--adapt-box: expected six numbers" "$exe" subdivide --scheme quasi48 --adapt-box 1,0,0,0,1,1 "$ico" -o "$tmp/q3.obj"
expect 2 "--adapt-box: expected six numbers" "$exe" subdivide --scheme quasi48 --adapt-box 0,0,0,1,1 "$ico" -o "$tmp/q3.obj"
expect 2 "--adapt-edge-length: expected a length > 0, not '-1'" "$exe" subdivide --scheme quasi48 --adapt-edge-length -1 "$ico" -o "$tmp/q3.obj"
expect 2 "scheme loop does not refine adaptively" "$exe" subdivide --scheme loop --adapt-edge-length 1 "$ico" -o "$tmp/q3.obj"
# --adapt-curvature: the icosahedron's dihedral angles are 41.8 degrees
expect 0 "quasi48 level 1: 12 vertices" "$exe" subdivide --scheme quasi48 --adapt-curvature 42 "$ico" -o "$tmp/q3.obj"
expect 0 "quasi48 level 1: 20 vertices" "$exe" subdivide --scheme quasi48 --adapt-curvature 41 "$ico" -o "$tmp/q3.obj"
expect 2 "--adapt-curvature: expected an angle in degrees, 0..180, not '181'" "$exe" subdivide --scheme quasi48 --adapt-curvature 181 "$ico" -o "$tmp/q3.obj"
expect 2 "--adapt-curvature: expected an angle in degrees, 0..180, not 'x'" "$exe" subdivide --scheme quasi48 --adapt-curvature x "$ico" -o "$tmp/q3.obj"
# --boundary (test_quasi48_boundary checks the rules): a closed surface is the
# same in every mode; bad values and other schemes exit 2
expect 0 "wrote" "$exe" subdivide --scheme quasi48 --levels 3 --boundary smooth "$ico" -o "$tmp/q4.obj"
expect 0 "wrote" "$exe" subdivide --scheme quasi48 --levels 3 --boundary fixed "$ico" -o "$tmp/q5.obj"
expect 0 "wrote" "$exe" subdivide --scheme quasi48 --levels 3 "$ico" -o "$tmp/q6.obj"
expect 0 "^" cmp "$tmp/q4.obj" "$tmp/q5.obj"
expect 0 "^" cmp "$tmp/q4.obj" "$tmp/q6.obj"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv -1 0 0\nv 0 -1 0\nf 1 2 3\nf 1 3 4\nf 1 4 5\nf 1 5 2\n' >"$tmp/sq.obj"
expect 0 "wrote" "$exe" subdivide --scheme quasi48 --levels 2 --boundary smooth "$tmp/sq.obj" -o "$tmp/q7.obj"
expect 0 "wrote" "$exe" subdivide --scheme quasi48 --levels 2 --boundary normal "$tmp/sq.obj" -o "$tmp/q8.obj"
expect 0 "wrote" "$exe" subdivide --scheme quasi48 --levels 2 --boundary fixed "$tmp/sq.obj" -o "$tmp/q9.obj"
expect 1 "differ" cmp "$tmp/q7.obj" "$tmp/q9.obj"
expect 0 "^" cmp "$tmp/q8.obj" "$tmp/q9.obj"
expect 2 "--boundary: expected normal, smooth or fixed, not 'free'" "$exe" subdivide --scheme quasi48 --boundary free "$ico" -o "$tmp/q3.obj"
expect 2 "--boundary: scheme loop has no choice of boundary rule" "$exe" subdivide --scheme loop --boundary smooth "$ico" -o "$tmp/q3.obj"
expect 0 "UNSTRUCTURED_GRID" cat "$tmp/b.vtk"
# Medit output: octahedra split into 4 tets each by default (said on stderr),
# kept under the Octahedra extension keyword only on request
expect 0 "split 6 octahedra into 24 tetrahedra" "$exe" subdivide --scheme tetoct "$m/cube-6tets.mesh" -o "$tmp/c.mesh"
expect 1 "^0$" grep -c Octahedra "$tmp/c.mesh"
expect 0 "read .*c.mesh: .* 48 tetrahedra" "$exe" subdivide --scheme tetoct --levels 0 "$tmp/c.mesh" -o "$tmp/c2.mesh"
expect 0 "wrote" "$exe" subdivide --scheme tetoct "$m/cube-6tets.mesh" --split-octahedra -o "$tmp/c3.mesh"
expect 0 "^" cmp "$tmp/c.mesh" "$tmp/c3.mesh"
expect 0 "^wrote [^ ]*k.mesh \\(medit\\)$" "$exe" subdivide --scheme tetoct "$m/cube-6tets.mesh" --octahedra-keyword -o "$tmp/k.mesh"
expect 0 "read .*k.mesh: .* 24 tetrahedra, 6 octahedra" "$exe" subdivide --scheme tetoct --levels 0 "$tmp/k.mesh" -o "$tmp/k2.mesh"
expect 2 "--split-octahedra and --octahedra-keyword contradict" "$exe" subdivide --scheme tetoct "$m/cube-6tets.mesh" --split-octahedra --octahedra-keyword -o "$tmp/c.mesh"
expect 2 "cannot write the read-only format of .*x.node' \\(write: .mesh \\(Medit\\), .vtk, .vtu, .msh \\(gmsh 4.1\\) or .obj\\)" "$exe" subdivide --scheme tetoct "$m/cube-6tets.mesh" -o "$tmp/x.node"
expect 2 "x.msh: gmsh has no octahedron element \\(6 octahedra\\)" "$exe" subdivide --scheme tetoct "$m/cube-6tets.mesh" -o "$tmp/x.msh"
expect 0 "catmull-clark level 3: 386 vertices, 384 quadrilaterals" "$exe" subdivide --scheme catmull-clark --levels 3 "$m/cube-surface.obj" -o "$tmp/d.obj"
expect 0 "loop level 2: 162 vertices, 320 triangles" "$exe" subdivide --scheme loop --levels 2 "$m/icosahedron.obj" -o "$tmp/e.obj"
# quasi 4-8 surfaces: triangles only; non-manifold edges refused by name
expect 0 "quasi48 level 2" "$exe" subdivide --scheme quasi48 --levels 2 "$m/icosahedron.obj" -o "$tmp/q.obj"
expect 2 "does not take quadrilaterals" "$exe" subdivide --scheme quasi48 "$m/cube-surface.obj" -o "$tmp/q.obj"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 0 -1 0\nf 1 2 3\nf 2 1 4\nf 1 2 5\n' > "$tmp/nm.obj"
expect 2 "non-manifold edge: the edge between vertices 1 and 2 is held by 3 triangles" "$exe" subdivide --scheme quasi48 "$tmp/nm.obj" -o "$tmp/q.obj"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 2 1 3\n' > "$tmp/pillow.obj"
expect 2 "doubled triangle: both triangles on the edge between vertices 1 and 2 have the third corner 3" "$exe" subdivide --scheme quasi48 "$tmp/pillow.obj" -o "$tmp/q.obj"
# the level cap counts at most 2 triangles per triangle and level for quasi48
# (a bisection), not 4 as for Loop: 320 * 2^12 cells are allowed (issue 35)
"$exe" subdivide --scheme loop --levels 2 "$m/icosahedron.obj" -o "$tmp/ico320.obj" >/dev/null 2>&1
expect 0 "quasi48 level 12: [0-9]+ vertices, [0-9]+ triangles" "$exe" subdivide --scheme quasi48 --levels 12 "$tmp/ico320.obj" -o "$tmp/q.vtk"
expect 2 "12 levels would make 5.37e\+09 cells" "$exe" subdivide --scheme loop --levels 12 "$tmp/ico320.obj" -o "$tmp/q.vtk"
# quasi48 analysis (issue 19): surface vertices of class 4 or 8 only
expect 0 "valence 8, 4-8 class 8" "$exe" analyze --scheme quasi48 --surface-vertex 8 --eigenvalues 4
expect 0 "valence 5, 4-8 class 4" "$exe" analyze --scheme quasi48 --surface-vertex 5 --class 4 --eigenvalues 4
expect 0 '"class":8' "$exe" analyze --scheme quasi48 --surface-vertex 6 --class 8 --format json
expect 0 "MatrixMarket" "$exe" matrix --scheme quasi48 --surface-vertex 3
expect 2 "class-8 vertex of a 4-8 mesh has an even valence of at least 6, not 7" "$exe" analyze --scheme quasi48 --surface-vertex 7 --class 8
expect 2 "class-8 vertex of a 4-8 mesh has an even valence of at least 6, not 4" "$exe" analyze --scheme quasi48 --surface-vertex 4 --class 8
expect 2 "class-8 vertex .* not 9" "$exe" matrix --scheme quasi48 --surface-vertex 9 --class 8
expect 2 "--class: expected 4 or 8, not '5'" "$exe" analyze --scheme quasi48 --surface-vertex 6 --class 5
expect 2 "--class: expected 4 or 8, not 'eight'" "$exe" analyze --scheme quasi48 --surface-vertex 6 --class eight
expect 2 "option --class needs a value" "$exe" analyze --scheme quasi48 --surface-vertex 6 --class
expect 2 "--class: scheme loop has no 4-8 vertex classes" "$exe" analyze --scheme loop --surface-vertex 6 --class 4
expect 2 "--class is the 4-8 class of a quasi48 --surface-vertex" "$exe" analyze --scheme quasi48 --vertex octahedron --class 4
expect 2 "scheme quasi48 does not support the vertex case" "$exe" analyze --scheme quasi48 --vertex octahedron
expect 2 "scheme quasi48 does not support the edge case" "$exe" analyze --scheme quasi48 --edge 5
expect 2 "only its surface vertices are analysed" "$exe" sweep --scheme quasi48 --vertices 4..5
expect 0 "mlca level 1" "$exe" subdivide --scheme mlca "$m/patch3x3.mesh" -o "$tmp/f.mesh"
expect 0 "tetoct level 1" "$exe" subdivide --scheme tetoct "$m/tetstar-icosahedron.mesh" -o "$tmp/g.mesh"
expect 0 "mlca level 1" "$exe" subdivide --scheme mlca "$m/hexstar-icosahedron.mesh" -o "$tmp/h.mesh"

# read-only formats (tests/mesh/test_mesh_formats.c checks them in full):
# gmsh .msh and TetGen .node/.ele in, a message and status 2 for bad files,
# and nothing from gmsh itself on the terminal
g=$src/tests/mesh/gmsh
expect 2 "mixed.v4b.msh: mixed mesh \\(6 tetrahedra and 1 hexahedra\\)" "$exe" enumerate mesh "$g/mixed.v4b.msh"
printf '$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 2 1 2\n' > "$tmp/cut.msh"
expect 2 "^subspectra subdivide: [^ ]*cut.msh:5: \\\$Nodes: the file ends where entity block 1 of 1 is expected$" "$exe" subdivide --scheme tetoct "$tmp/cut.msh" -o "$tmp/x.mesh"
checks=$((checks + 1))
lines=$("$exe" subdivide --scheme tetoct "$tmp/cut.msh" -o "$tmp/x.mesh" 2>&1 | wc -l)
[ "$lines" -eq 1 ] || fail "a bad .msh: $lines lines of output, want the one message"

# one message prefix (issue 40): a failure says "subspectra COMMAND: ...",
# the library's message after it, whichever path reports it (the command's
# own check, a failed library call, a file that cannot be read)
expect 2 "^subspectra subdivide: /nonexistent/x.mesh: No such file" "$exe" subdivide --scheme mlca /nonexistent/x.mesh -o "$tmp/x.mesh"
expect 2 "^subspectra limit: /nonexistent/x.mesh: No such file" "$exe" limit --scheme mlca --samples 2 /nonexistent/x.mesh
expect 2 "^subspectra enumerate mesh: /nonexistent/x.mesh: No such file" "$exe" enumerate mesh /nonexistent/x.mesh
expect_in 2 "^subspectra enumerate canonical: stdin:1: " "4 bcd" "$exe" enumerate canonical
expect 2 "^subspectra jsr: unknown scheme 'nope'" "$exe" jsr --scheme nope --face
expect 2 "^subspectra matrix: /nonexistent/x.mtx: cannot open" "$exe" matrix --scheme mlca --edge 4 -o /nonexistent/x.mtx
expect 2 "^subspectra draw: [^ ]*x.gif: unknown picture format" "$exe" draw --scheme mlca --edge 4 -o "$tmp/x.gif"
checks=$((checks + 1))
"$exe" draw --scheme mlca --edge 8 -o "$tmp/e8.png" 2>&1 | grep -q "no characteristic map to draw: no characteristic map" &&
  fail "draw says 'no characteristic map' twice"
printf 'System "touch %s";\n' "$tmp/MARK" > "$tmp/script.msh"
expect 2 "script.msh:1: not a gmsh mesh" "$exe" subdivide --scheme tetoct "$tmp/script.msh" -o "$tmp/x.mesh"
expect 1 "" test -e "$tmp/MARK"
printf '4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n' > "$tmp/t.node"
printf '1 4 0\n1 1 2 3 4\n' > "$tmp/t.ele"
expect 0 "tetoct level 1: 10 vertices, 4 tetrahedra, 1 octahedron" "$exe" subdivide --scheme tetoct "$tmp/t.ele" -o "$tmp/t.vtk"
printf '1 4 0\n1 1 2 3 9\n' > "$tmp/t.ele"
expect 2 "t.ele:2: tetrahedron 1: point number 9 is out of range 1..4" "$exe" subdivide --scheme tetoct "$tmp/t.node" -o "$tmp/t.vtk"
expect 2 "x.stl: cannot tell the mesh format \\(read: .mesh \\(Medit\\), .obj, .vtk, .vtu, .msh \\(gmsh\\) or .node/.ele \\(TetGen\\)\\)" "$exe" subdivide --scheme tetoct "$tmp/x.stl" -o "$tmp/x.mesh"

# machine-readable summary
checks=$((checks + 1))
json=$("$exe" subdivide --scheme mlca --levels 2 --format json "$m/cube-creased.mesh" -o "$tmp/j.mesh")
if ! python3 -c 'import json,sys; d=json.loads(sys.argv[1]); assert d["levels"][2]["cells"]["hexahedra"]==64 and d["levels"][2]["vertices"]==125, d' "$json"; then
  failed=$((failed + 1))
  echo "FAILED: json summary: $json" >&2
fi

# an inverted cell: the second of two tets listed the wrong way round
cat >"$tmp/inv.mesh" <<'MESH'
MeshVersionFormatted 2
Dimension 3
Vertices
5
0 0 0 0
1 0 0 0
0 1 0 0
0 0 1 0
0 0 -1 0
Tetrahedra
3
1 2 3 4 0
1 3 2 5 0
1 2 3 5 0
End
MESH
expect 2 "tetrahedron 3 is inverted" "$exe" subdivide --scheme tetoct "$tmp/inv.mesh" -o "$tmp/o.mesh"

# results are checked, not only input: a unit hex cube with one face pushed
# to 1.7e308 is finite, but its refinement overflows (exit 2, no output file,
# the input vertices named); cubes of side 1e-300 and 1e300 are accepted and
# refine to finite meshes, which read back (the reader refuses inf)
cube() { # cube SIDE OFFSET-OF-THE-TOP-FACE: a Medit hex cube
  local a=$1 z=$2
  printf 'MeshVersionFormatted 2\nDimension 3\nVertices\n8\n'
  printf '0 0 0 0\n%s 0 0 0\n%s %s 0 0\n0 %s 0 0\n' "$a" "$a" "$a" "$a"
  printf '0 0 %s 0\n%s 0 %s 0\n%s %s %s 0\n0 %s %s 0\n' "$z" "$a" "$z" "$a" "$a" "$z" "$a" "$z"
  printf 'Hexahedra\n1\n1 2 3 4 5 6 7 8 0\nEnd\n'
}
cube 1 1.7e308 >"$tmp/huge.mesh"
rm -f "$tmp/huge-out.mesh"
expect 2 "huge.mesh: level 1: refined vertex [0-9]+ has a non-finite coordinate; it derives from input vertices [0-9, ]+ and [0-9]+ \\(numbered as in the file\\); the largest input coordinate is 1.7e\\+308, at vertex 5.*DBL_MAX.*nothing written" "$exe" subdivide --scheme mlca "$tmp/huge.mesh" -o "$tmp/huge-out.mesh"
checks=$((checks + 1))
[ -e "$tmp/huge-out.mesh" ] && fail "subdivide wrote $tmp/huge-out.mesh despite the overflow"
for side in 1e-300 1e300; do
  cube "$side" "$side" >"$tmp/cube$side.mesh"
  expect 0 "mlca level 2: 125 vertices" "$exe" subdivide --scheme mlca --levels 2 "$tmp/cube$side.mesh" -o "$tmp/cube$side-2.mesh"
  expect 0 "read .*: 125 vertices, 64 hexahedra" "$exe" subdivide --scheme mlca --levels 0 "$tmp/cube$side-2.mesh" -o "$tmp/cube$side-3.mesh"
done
cube 1e-300 0 >"$tmp/flat.mesh"
expect 2 "hexahedron 1 is flat" "$exe" subdivide --scheme mlca "$tmp/flat.mesh" -o "$tmp/o.mesh"

# every malformed sample: status 2 and a message naming the file
for f in "$src"/tests/mesh/bad/*; do
  [ -f "$f" ] || continue
  name=$(basename "$f")
  case "$name" in *.obj) scheme=loop ;; *) scheme=mlca ;; esac
  expect 2 "$name" "$exe" subdivide --scheme "$scheme" "$f" -o "$tmp/o.mesh"
done

# enumerate random: K-vertex links, one per line, reproducible from the seed
expect 0 "seed S" "$exe" enumerate random --help
expect 2 "--vertices '3'" "$exe" enumerate random --vertices 3 --samples 1
expect 2 "--samples is required" "$exe" enumerate random --vertices 12
expect 2 "--format 'xml'" "$exe" enumerate random --vertices 12 --samples 1 --format xml
checks=$((checks + 1))
r1=$("$exe" enumerate random --vertices 12 --samples 3 --seed 7)
r2=$("$exe" enumerate random --vertices 12 --samples 3 --seed 7)
if [ "$(grep -c '^12 ' <<<"$r1")" -ne 3 ] || [ "$(wc -l <<<"$r1")" -ne 3 ] || [ "$r1" != "$r2" ]; then
  failed=$((failed + 1))
  echo "FAILED: enumerate random --vertices 12 --samples 3 --seed 7 (3 lines '12 ...', twice the same):" >&2
  echo "$r1" "$r2" | head -6 >&2
fi
expect 0 '^\{"vertices":12,"seed":7,"sample":2,"link":"12 ' "$exe" enumerate random --vertices 12 --samples 3 --seed 7 --format json

# Catmull-Clark solids: the shipped hex meshes; tets and non-manifold hex meshes refused
expect 0 "ccsolid level 2: 1809 vertices, 1280 hexahedra" "$exe" subdivide --scheme ccsolid --levels 2 "$m/hexstar-icosahedron.mesh" -o "$tmp/cs.mesh"
expect 0 "ccsolid level 1: 27 vertices, 24 quadrilaterals, 8 hexahedra" "$exe" subdivide --scheme ccsolid "$m/cube-creased.mesh" -o "$tmp/cs.vtk"
expect 2 "scheme ccsolid does not take tetrahedra" "$exe" subdivide --scheme ccsolid "$m/cube-6tets.mesh" -o "$tmp/cs.mesh"
{
  printf 'MeshVersionFormatted 2\nDimension 3\nVertices\n15\n'
  for z in 0 1; do for y in 0 1; do for x in 0 1; do echo "$x $y $z 0"; done; done; done
  for z in 1 2; do for y in 1 2; do for x in 1 2; do [ "$x$y$z" = 111 ] || echo "$x $y $z 0"; done; done; done
  printf 'Hexahedra\n2\n1 2 4 3 5 6 8 7 0\n8 9 11 10 12 13 15 14 0\nEnd\n'
} >"$tmp/pinch.mesh"
expect 0 "2 hexahedra" "$exe" subdivide --scheme mlca "$tmp/pinch.mesh" -o "$tmp/p.mesh"
expect 2 "the hexahedra at vertex 8 do not form one ball or half-ball .*non-manifold" "$exe" subdivide --scheme ccsolid "$tmp/pinch.mesh" -o "$tmp/p.mesh"

# the shared options (ss_cli_opt.c): one range and one message in every
# command that takes them; the bounds themselves are refused
for cmd in "analyze --scheme mlca --edge 4" "check --scheme mlca --edges 4..4" \
  "sweep --scheme mlca --edges 4..4 --db $tmp/opt.db"; do
  name=${cmd%% *}
  for t in 0 0.1 -1e-6 1e-6x ""; do
    expect 2 "subspectra $name: --tol '$t' is not a number in \(0, 0.1\)" "$exe" $cmd --tol "$t"
  done
  for d in -1 13 x; do
    expect 2 "subspectra $name: --depth '$d' is not an integer in 0..12" "$exe" $cmd --depth "$d"
  done
done
expect 0 "1 cases: 1 pass" "$exe" check --scheme mlca --edges 4..4 --tol 0.05 --depth 0
for cmd in analyze sweep; do
  expect 2 "subspectra $cmd: give exactly one of --scheme and --stencil" "$exe" $cmd --scheme mlca \
    --stencil "$src/data/stencils/mlca.ini" --edge 4
done

# plantri's binary planar_code (its default output) is refused with the hint to use -a
printf '>>planar_code<<\004\002\003\004\000\001\004\003\000' >"$tmp/pc.bin"
for cmd in "analyze --scheme mlca --vertex -" "enumerate canonical"; do
  checks=$((checks + 1))
  out=$("$exe" $cmd <"$tmp/pc.bin" 2>&1)
  rc=$?
  [ $rc = 2 ] && grep -q "stdin:1: this is plantri's binary planar_code .*run plantri with -a" <<<"$out" ||
    fail "$cmd on planar_code: status $rc, $out"
done

# --version on every command (and before any)
ver=$("$exe" --version)
for cmd in analyze matrix draw enumerate subdivide limit check sweep merge report reproduce jsr; do
  expect 0 "^$ver\$" "$exe" $cmd --version
done
expect 0 "^$ver\$" "$exe" analyze --scheme mlca --version

expect_done "cli"

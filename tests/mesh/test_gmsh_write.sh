#!/usr/bin/env bash
# test_gmsh_write.sh SUBSPECTRA [GMSH] — `-o FILE.msh`: gmsh .msh 4.1 written
# through gmsh's API (issue 40 "Meshes in and out"; ss_mesh_gmsh_write.c).
# SKIPPED (77) in a build without gmsh.
#  1. Round trips: subdivide IN -o A.msh, then subdivide -l 0 A.msh -o B.mesh
#     equals subdivide IN -o B.mesh byte for byte but for the vertex
#     references (gmsh nodes have none; read 0): mlca on a VTU grid with
#     references 1..5 and fields (hexahedra, quads, corners), boxspline -l 0
#     on tetrahedra of reference 3; loop's triangles of reference 0 come back with their
#     entity's tag (1), as documented (gmsh's physical groups are positive).
#  2. Fields: the VTU's density and velocity become the views "density" and
#     "velocity" (3 components), and read back as density, velocity_x/_y/_z.
#  3. gmsh itself reads the file (GMSH given: the program), and
#     --output-format gmsh -o /dev/stdout writes the same bytes.
#  4. Octahedra (tetoct) are refused, naming the file and why.
set -u
exe=$1
gmsh=${2:-}
. "$(dirname "$0")/../ss_expect.sh"
src=$(cd "$(dirname "$0")/../.." && pwd)
m=$src/data/meshes
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
out=$("$exe" subdivide -s loop -l 0 "$m/icosahedron.obj" -o "$tmp/probe.msh" 2>&1)
if grep -q "built without gmsh" <<<"$out"; then
  echo "SKIP: this build writes no .msh (gmsh missing)"
  exit 77
fi
python3 "$src/tests/mesh/vtk_make.py" "$tmp" || fail "vtk_make.py"
novref() { # the Medit file with every vertex reference 0
  awk '/^Vertices/ {v = 1; print; getline; print; n = $1; next}
    v && n > 0 {$NF = 0; n--; print; next} {print}' "$1"
}
trip() { # NAME SCHEME LEVELS IN
  local name=$1 scheme=$2 levels=$3 in=$4
  expect 0 "wrote .*$name.msh \(gmsh\)" "$exe" subdivide -s "$scheme" -l "$levels" "$in" \
    -o "$tmp/$name.msh"
  expect 0 "wrote" "$exe" subdivide -s "$scheme" -l "$levels" "$in" -o "$tmp/$name.direct.mesh"
  expect 0 "read .*$name.msh" "$exe" subdivide -s "$scheme" -l 0 "$tmp/$name.msh" \
    -o "$tmp/$name.back.mesh"
  checks=$((checks + 1))
  cmp -s <(novref "$tmp/$name.direct.mesh") <(novref "$tmp/$name.back.mesh") ||
    fail "$name: the .msh does not read back as the mesh written"
}
trip grid mlca 1 "$tmp/ascii.vtu"
awk '/^Tetrahedra/ {t = 1; print; getline; print; n = $1; next} t && n-- > 0 {$5 = 3} {print}' \
  "$m/cube-6tets.mesh" >"$tmp/tets3.mesh"
trip tets boxspline 0 "$tmp/tets3.mesh"
# references 0: the entity's tag
expect 0 "wrote" "$exe" subdivide -s loop -l 1 "$m/icosahedron.obj" -o "$tmp/ico.msh"
expect 0 "wrote" "$exe" subdivide -s loop -l 0 "$tmp/ico.msh" -o "$tmp/ico.mesh"
checks=$((checks + 1))
awk '/^Triangles/ {t = 1; getline; n = $1; next} t && n-- > 0 && $4 != 1 {bad++} END {exit bad > 0}' \
  "$tmp/ico.mesh" || fail "ico: triangles of reference 0 do not read back as entity 1"

# 2. fields as views, names back
checks=$((checks + 1))
grep -aq '"density"' "$tmp/grid.msh" && grep -aq '"velocity"' "$tmp/grid.msh" ||
  fail "grid.msh: no views density and velocity"
expect 0 '"fields":\{"density":[-0-9.e]+,"velocity_x":[-0-9.e]+,"velocity_y":[-0-9.e]+,"velocity_z"' \
  "$exe" limit -s mlca "$tmp/grid.msh" --at "100 0.5 0.5 0.5" -f json

# 3. gmsh reads it; standard output
if [ -n "$gmsh" ]; then
  expect 0 "Done reading" "$gmsh" "$tmp/grid.msh" -0 -o "$tmp/gmsh-again.msh"
  checks=$((checks + 1))
  ! "$gmsh" "$tmp/grid.msh" -0 -o "$tmp/gmsh-again.msh" 2>&1 | grep -q "Error" ||
    fail "gmsh reports an error reading grid.msh"
fi
checks=$((checks + 1))
"$exe" subdivide -s mlca -l 1 "$tmp/ascii.vtu" -o /dev/stdout --output-format gmsh \
  >"$tmp/stdout.msh" 2>/dev/null || fail "--output-format gmsh -o /dev/stdout"
cmp -s "$tmp/stdout.msh" "$tmp/grid.msh" || fail "/dev/stdout differs from grid.msh"

# 4. octahedra
expect 2 "to.msh: gmsh has no octahedron element \([0-9]+ octahedra\)" \
  "$exe" subdivide -s tetoct -l 1 "$m/cube-6tets.mesh" -o "$tmp/to.msh"
checks=$((checks + 1))
[ ! -e "$tmp/to.msh" ] || fail "to.msh written although refused"
expect_done gmsh_write

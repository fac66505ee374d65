#!/usr/bin/env bash
# test_drop.sh SUBSPECTRA TETGEN [GMSH] — `subdivide --drop-unsupported` (issue 40):
# TetGen's default output of a cube holds its boundary triangles (.face)
# beside the tetrahedra.  Every scheme that takes tetrahedra now takes
# triangles too (tetoct: crease surfaces; boxspline: its Loop boundary
# surface, which the .face triangles are part of — issue 38, figure 29;
# test_boxspline_surface shows they move nothing), so both keep them with or
# without the option, nothing said dropped.  A scheme that refuses the top
# cells (mlca on tets) is refused as before, nothing dropped.  What is left
# to drop beside tetrahedra are gmsh's geometry points and curves: with GMSH,
# a box meshed without physical groups is refused by boxspline for its
# corners and segments (the counts the refusal names), and with the option
# they are dropped, its triangles kept, and the tets refined.
# SKIPPED (77) without tetgen.
set -u
exe=$1
tetgen=${2:-}
gmsh=${3:-}
. "$(dirname "$0")/../ss_expect.sh"
[ -n "$tetgen" ] && [ -x "$tetgen" ] || { echo "SKIP: tetgen not installed"; exit 77; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cat >"$tmp/cube.poly" <<'POLY'
8 3 0 1
1 0 0 0 0
2 1 0 0 0
3 1 1 0 0
4 0 1 0 0
5 0 0 1 0
6 1 0 1 0
7 1 1 1 0
8 0 1 1 0
6 1
1 0 1
4 1 2 3 4
1 0 2
4 5 6 7 8
1 0 3
4 1 2 6 5
1 0 4
4 2 3 7 6
1 0 5
4 3 4 8 7
1 0 6
4 4 1 5 8
0
0
POLY
(cd "$tmp" && "$tetgen" -pqa0.02Q cube.poly >/dev/null 2>&1) || { fail "tetgen"; expect_done drop; exit; }
nface=$(awk 'NR == 1 {print $1}' "$tmp/cube.1.face")
checks=$((checks + 1))
[ "${nface:-0}" -gt 12 ] || fail "tetgen wrote ${nface:-no} boundary triangles"
ele=$tmp/cube.1.ele
# the triangles are taken, with or without the option: the same file
expect 0 "cube.1.ele: [0-9]* vertices, $nface triangles, [0-9]* tetrahedra" \
  "$exe" subdivide --scheme boxspline --levels 2 "$ele" -o "$tmp/kept.mesh"
out=$("$exe" subdivide --scheme boxspline --levels 2 --drop-unsupported "$ele" -o "$tmp/kept2.mesh" 2>&1)
checks=$((checks + 1))
! grep -q dropped <<<"$out" && cmp -s "$tmp/kept.mesh" "$tmp/kept2.mesh" || fail "boxspline: $out"
# refused top cells: refused as before, nothing said dropped
out=$("$exe" subdivide --scheme mlca --drop-unsupported "$ele" -o "$tmp/m.mesh" 2>&1)
rc=$?
checks=$((checks + 1))
[ $rc -eq 2 ] && grep -q "does not take triangles ($nface), tetrahedra" <<<"$out" && ! grep -q dropped <<<"$out" ||
  fail "mlca on tets: $out"
# a scheme that takes the triangles keeps them
expect 0 "wrote" "$exe" subdivide --scheme tetoct "$ele" -o "$tmp/t1.mesh"
out=$("$exe" subdivide --scheme tetoct --drop-unsupported "$ele" -o "$tmp/t2.mesh" 2>&1)
checks=$((checks + 1))
! grep -q dropped <<<"$out" && cmp -s "$tmp/t1.mesh" "$tmp/t2.mesh" || fail "tetoct: $out"
# gmsh without physical groups saves its geometry entities' points, curves and
# surfaces beside the volume: all dropped for boxspline, counted as read
if [ -n "$gmsh" ] && [ -x "$gmsh" ]; then
  printf 'SetFactory("OpenCASCADE");\nBox(1) = {0,0,0,1,1,1};\nMesh.CharacteristicLengthMax = 0.5;\n' >"$tmp/box.geo"
  "$gmsh" -3 "$tmp/box.geo" -o "$tmp/box.msh" -format msh41 >/dev/null 2>&1 || fail "gmsh"
  out=$("$exe" subdivide --scheme boxspline "$tmp/box.msh" -o "$tmp/box.vtu" 2>&1)
  read -r nc ns < <(sed -n 's/.*does not take corners (\([0-9]*\)), segments (\([0-9]*\)); .*/\1 \2/p' <<<"$out")
  out=$("$exe" subdivide --scheme boxspline --drop-unsupported "$tmp/box.msh" -o "$tmp/box.vtu" 2>&1)
  rc=$?
  checks=$((checks + 1))
  [ $rc -eq 0 ] && [ "${ns:-0}" -gt 0 ] &&
    grep -q "box.msh: dropped $nc corners, $ns segments that scheme boxspline" <<<"$out" &&
    grep -q "^boxspline level 1: [0-9]* vertices, [0-9]* triangles, [0-9]* tetrahedra, [0-9]* octahedra (" <<<"$out" ||
    fail "gmsh box: $out"
else
  echo "gmsh not given: its geometry entities are not tried"
fi
expect_done "drop"

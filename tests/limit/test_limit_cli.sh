#!/usr/bin/env bash
# test_limit_cli.sh EXE — `subspectra limit` from the outside: the JSON
# contract (cell, u, v, w, point, jacobian), counts of --samples and --gauss
# points, Gauss weights summing to 1 per cell, VTK and -o, the reference
# agreeing with the direct walk, and the exit statuses of bad input.
set -u
exe=$1
SS_EXPECT_TIMEOUT=120
. "$(dirname "$0")/../ss_expect.sh"
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
# the same for ccsolid
a=$("$exe" limit --scheme ccsolid "$mesh" --at "5 0.01 0.3 0.002" --at "7 0.6 0.1 0.9")
b=$("$exe" limit --scheme ccsolid "$mesh" --at "5 0.01 0.3 0.002" --at "7 0.6 0.1 0.9" --reference)
d=$(paste <(echo "$a") <(echo "$b") | awk '{for (i = 5; i <= 7; i++) {e = $i - $(i + 7); if (e < 0) e = -e; if (e > m) m = e}} END {print (m <= 1e-12) ? "ok" : m}')
checks=$((checks + 1)); [ "$d" = "ok" ] || fail "ccsolid: direct vs reference differ by $d"
# VTK with -o: the sampled volume as hexahedra (20 cells x 2^3)
expect 0 "" "$exe" limit --scheme mlca "$mesh" --samples 3 --format vtk -o "$tmp/v.vtk"
checks=$((checks + 1)); grep -q "^CELLS 160 1440" "$tmp/v.vtk" || fail "vtk: no 160 hexahedra"
# Gauss points lie inside the cells, where the Jacobian is defined
expect 0 "" "$exe" limit --scheme mlca "$mesh" --gauss 2 --format vtk -d -o "$tmp/g.vtk"
checks=$((checks + 1)); grep -q "^SCALARS jacobian_det" "$tmp/g.vtk" || fail "vtk: no det J"
checks=$((checks + 1)); grep -q "^CELLS 160 320" "$tmp/g.vtk" || fail "vtk: no 160 points"
# bad input: exit 2 with a message
expect 2 "cell 21 does not exist" "$exe" limit --scheme mlca "$mesh" --at "21 0.5 0.5 0.5"
expect 2 "parameter u = 1.5 is outside" "$exe" limit --scheme mlca "$mesh" --at "1 1.5 0.5 0.5"
expect 2 "expected \"CELL U V W\"" "$exe" limit --scheme mlca "$mesh" --at "1 0.5 0.5"
expect 2 "expected \"CELL U V W\"" "$exe" limit --scheme mlca "$mesh" --at "0 0.5 0.5 0.5"
expect 2 "exactly one of --at, --samples and --gauss" "$exe" limit --scheme mlca "$mesh"
expect 2 "exactly one of --at, --samples and --gauss" "$exe" limit --scheme mlca "$mesh" --samples 2 --gauss 2
expect 2 "--scheme is required" "$exe" limit "$mesh" --samples 2
expect 2 "tetoct is not one" "$exe" limit --scheme tetoct "$mesh" --samples 2
expect 2 "hexahedra only" "$exe" limit --scheme mlca "$(dirname "$0")/../../data/meshes/cube-6tets.mesh" --samples 2
expect 2 "--gauss '0'" "$exe" limit --scheme mlca "$mesh" --gauss 0
expect 2 "--format" "$exe" limit --scheme mlca "$mesh" --gauss 1 --format xml
expect 2 "No such file" "$exe" limit --scheme mlca /nonexistent.mesh --gauss 1
# the Jacobian exactly at the extraordinary vertex is not defined: exit 1
expect 1 "Jacobian" "$exe" limit --scheme mlca "$mesh" --at "1 0 0 0" --derivatives
expect 0 "" "$exe" limit --scheme mlca "$mesh" --at "1 0 0 0"
expect_done limit_cli

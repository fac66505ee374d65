#!/usr/bin/env bash
# test_deform_examples.sh EXE — the examples of data/deform/README.md at low
# resolution: cylinder.py writes the meshes (the axis of --sectors m an
# interior edge shared by m tets in every layer, counted here from the file),
# and deform renders each (exit 0, a PNG, every pattern point inside the
# cylinder either evaluated or reported outside).
set -u
exe=$1
SS_EXPECT_TIMEOUT=300
. "$(dirname "$0")/../ss_expect.sh"
gen="$(dirname "$0")/../../data/deform/cylinder.py"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

python3 "$gen" --crease --out "$tmp/cyl.mesh" --target "$tmp/cyl-twist.mesh" --rings 2 --layers 3
expect 0 "0 refused" "$exe" deform --scheme tetoct "$tmp/cyl.mesh" --target "$tmp/cyl-twist.mesh" --pattern grid --n 3 --samples 12 --levels 1 --embed-level 1 -o "$tmp/cyl.png"
checks=$((checks + 1)); [ "$(head -c 4 "$tmp/cyl.png" | tail -c 3)" = "PNG" ] || fail "cylinder: no PNG"
for m in 3 4; do
  python3 "$gen" --sectors $m --move push --out "$tmp/e$m.mesh" --target "$tmp/e$m-push.mesh" --rings 2 --layers 4
  # tets around the axis edge of the middle layer: vertices 1 + 2 npl and 1 + 3 npl
  npl=$((1 + m + 2 * m))
  a=$((1 + 2 * npl)) b=$((1 + 3 * npl))
  n=$(awk -v a=$a -v b=$b '/^Tetrahedra/ {t = 1; getline; next} t && NF >= 5 {x = 0; for (i = 1; i <= 4; i++) if ($i == a || $i == b) x++; if (x == 2) c++} END {print c + 0}' "$tmp/e$m.mesh")
  checks=$((checks + 1)); [ "$n" -eq "$m" ] || fail "sectors $m: the axis edge is in $n tets"
  expect 0 "0 refused" "$exe" deform --scheme tetoct "$tmp/e$m.mesh" --target "$tmp/e$m-push.mesh" --pattern grid --n 3 --samples 12 --levels 1 --embed-level 1 -o "$tmp/e$m.png"
done
expect_done deform_examples

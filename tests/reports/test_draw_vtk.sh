#!/usr/bin/env bash
# test_draw_vtk.sh EXE — `draw -o FILE.vtk` carries analyze's numbers (issue
# 21): for a few cases, among them maps whose cells are all negatively
# oriented (links tetrahedron and bipyramid:3), the VTK's field data
# (min_scaled_jacobian, orientation, ring_level) equals `analyze --format
# json`'s regularity, the minimum of the per-cell min_scaled_jacobian over the
# deciding ring level's cells (part 2) is that same number, and every cell of
# that level of a passing case has jacobian_sign +1 (the map's orientation).
set -u
exe=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
checks=0
failed=0
compare() {
  local name=$1
  shift
  checks=$((checks + 1))
  # analyze and draw exit 1 when a verdict fails: a case to compare too
  rm -f "$tmp/m.vtk"
  "$exe" analyze "$@" --format json > "$tmp/a.json" 2> "$tmp/err"
  local rc=$?
  "$exe" draw "$@" -o "$tmp/m.vtk" 2>> "$tmp/err"
  local rd=$?
  if [ "$rc" -gt 1 ] || [ "$rd" -ne "$rc" ] || [ ! -s "$tmp/m.vtk" ]; then
    failed=$((failed + 1))
    echo "FAILED: $name: analyze or draw failed: $(head -3 "$tmp/err")" >&2
    return
  fi
  if ! python3 - "$tmp/a.json" "$tmp/m.vtk" "$name" <<'PY'; then
import json, math, sys
reg = json.load(open(sys.argv[1]))["regularity"]
L = open(sys.argv[2]).read().split("\n")
name = sys.argv[3]
def field(key):
    return L[L.index(key) + 1]
def scalars(key, conv):
    i = L.index("SCALARS %s" % key) + 2
    out = []
    while i < len(L) and L[i] and not L[i].startswith(("SCALARS", "POINT_DATA")):
        out.append(conv(L[i]))
        i += 1
    return out
msj = float(field("min_scaled_jacobian 1 1 double"))
ori = int(field("orientation 1 1 int"))
lev = int(field("ring_level 1 1 int"))
sign = scalars("jacobian_sign int 1", int)
meas = scalars("min_scaled_jacobian double 1", float)
part = scalars("part int 1", int)
ring = [(s, m) for s, m, p in zip(sign, meas, part) if p == 2]
want = reg["min_scaled_jacobian"]
bad = []
def close(a, b):
    return abs(a - b) <= 1e-12 * max(1.0, abs(b))
if not close(msj, want): bad.append("field min_scaled_jacobian %r, analyze %r" % (msj, want))
if ori != reg["orientation"]: bad.append("orientation %d, analyze %d" % (ori, reg["orientation"]))
if lev != reg["ring_level"]: bad.append("ring_level %d, analyze %d" % (lev, reg["ring_level"]))
if not ring: bad.append("no cells of the deciding ring level")
elif not close(min(m for s, m in ring), want):
    bad.append("min over the ring level's cells %r, analyze %r" % (min(m for s, m in ring), want))
if reg["verdict"] == "pass" and any(s != 1 for s, m in ring):
    bad.append("a passing case with ring cells of sign %s" % sorted(set(s for s, m in ring)))
if reg["verdict"] == "pass" and not all(m > 0 for s, m in ring):
    bad.append("a passing case with a ring cell of measure <= 0")
if reg["verdict"] == "fail" and "psi o sigma" not in reg["reason"] and all(s == 1 for s, m in ring):
    bad.append("a failing ring level whose cells are all of the map's orientation")
if bad:
    print("FAILED: %s: %s" % (name, "; ".join(bad)), file=sys.stderr)
    sys.exit(1)
print("%s: %s, min scaled Jacobian %.6g, orientation %+d" % (name, reg["verdict"], want, ori))
PY
    failed=$((failed + 1))
  fi
}
compare "mlca tetrahedron" --scheme mlca --vertex tetrahedron
compare "mlca bipyramid:3" --scheme mlca --vertex bipyramid:3
compare "mlca octahedron" --scheme mlca --vertex octahedron
compare "tetoct tetrahedron" --scheme tetoct --vertex tetrahedron
compare "tetoct bipyramid:3" --scheme tetoct --vertex bipyramid:3
compare "tetoct 7 bgecdf" --scheme tetoct --vertex "7 bgecdf,afdceg,aebd,acbf,agbc,adb,abe"
# a failing map: folded and inverted ring cells, the minimum negative
compare "mlca k = 8 (fails)" --scheme mlca --vertex "8 bcdefgh,ahc,abhd,ache,adhf,aehg,afh,agfedcb"
compare "tetoct edge 5" --scheme tetoct --edge 5
compare "loop surface vertex 5" --scheme loop --surface-vertex 5
echo "draw_vtk: $checks checks, $failed failed"
[ "$checks" -gt 0 ] && [ "$failed" -eq 0 ]

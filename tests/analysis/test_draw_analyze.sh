#!/usr/bin/env bash
# test_draw_analyze.sh EXE — `draw` carries exactly `analyze`'s numbers
# (issue 33): both run one pipeline (ss_pipeline), so for every case below
#   - the VTK's field data (min_scaled_jacobian, orientation, ring_level)
#     equal analyze --format json's regularity object, to the last digit;
#   - the smallest per-cell min_scaled_jacobian over the cells marked part 2
#     (the ring level that decided) is that minimum, while the cells around p
#     (part 0) are marked apart: their folds decide nothing, and in the
#     tetrahedron's MLCA star they go lower (0.77 < 0.84), which a reader
#     taking the minimum over every cell would mistake for analyze's number;
#   - draw's verdict line names analyze's regularity verdict;
#   - the VTK's points and cells are those of a case in canonical form: the
#     link as given and a relabelled, mirrored copy draw the same file.
# Cases: vertices of MLCA, tet/oct and box-spline (whose BFS diagonals depend
# on the labelling), an MLCA edge point (the bipyramid over 5, judged as the
# edge), an edge and a surface vertex.
set -u
exe=$1
SS_EXPECT_TIMEOUT=120
. "$(dirname "$0")/../ss_expect.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# The VTK reader and the checks above in Python (stdlib only), once: `vtk.py
# compare JSON VTK` prints one line per failed property (nothing when all
# hold); `vtk.py centre VTK` says whether the cells around p go below the
# ring's minimum.
cat >"$tmp/vtk.py" <<'PY'
import json, sys
def read(path):
    lines = open(path).read().split("\n")
    field = {}
    for i, l in enumerate(lines):
        for name in ("min_scaled_jacobian", "orientation", "ring_level"):
            if l.startswith(name + " 1 1 "):
                field[name] = lines[i + 1]
    def block(head, stop):
        i = lines.index(head) + 2  # skip LOOKUP_TABLE
        out = []
        while i < len(lines) and lines[i] and not lines[i].startswith(stop):
            out.append(lines[i]); i += 1
        return out
    msj = [float(x) for x in block("SCALARS min_scaled_jacobian double 1", "SCALARS")]
    part = [int(x) for x in block("SCALARS part int 1", "POINT_DATA")]
    return field, msj, part
if sys.argv[1] == "centre":
    field, msj, part = read(sys.argv[2])
    c = [m for m, p in zip(msj, part) if p == 0]
    r = [m for m, p in zip(msj, part) if p == 2]
    print("yes" if c and r and min(c) < min(r) else "no")
    sys.exit(0)
j = json.load(open(sys.argv[2]))["regularity"]
field, msj, part = read(sys.argv[3])
bad = []
if float(field["min_scaled_jacobian"]) != j["min_scaled_jacobian"]:
    bad.append("field min_scaled_jacobian %s, analyze %r" % (field["min_scaled_jacobian"], j["min_scaled_jacobian"]))
if int(field["orientation"]) != j["orientation"]:
    bad.append("orientation %s, analyze %d" % (field["orientation"], j["orientation"]))
if int(field["ring_level"]) != j["ring_level"]:
    bad.append("ring_level %s, analyze %d" % (field["ring_level"], j["ring_level"]))
ring = [m for m, p in zip(msj, part) if p == 2]
if len(msj) != len(part) or not ring:
    bad.append("cell data: %d values, %d parts, %d ring cells" % (len(msj), len(part), len(ring)))
elif min(ring) != j["min_scaled_jacobian"]:
    bad.append("ring cells' minimum %r, analyze %r" % (min(ring), j["min_scaled_jacobian"]))
print("\n".join(bad))
PY

one() { # SCHEME CASE-OPTION [ARG]
  local name="$*" js="$tmp/a.json" vtk="$tmp/d.vtk"
  checks=$((checks + 1))
  "$exe" analyze --scheme "$@" --format json >"$js" 2>/dev/null
  local verdict
  verdict=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["regularity"]["verdict"])' "$js" 2>/dev/null)
  local line
  line=$("$exe" draw --scheme "$@" -o "$vtk" 2>&1)
  if [ -z "$verdict" ] || [ ! -s "$vtk" ]; then
    fail "$name: no analysis or no picture ($line)"
    return
  fi
  grep -q "(regularity $verdict" <<<"$line" || fail "$name: draw says '$line', analyze '$verdict'"
  local bad
  bad=$(python3 "$tmp/vtk.py" compare "$js" "$vtk")
  [ -z "$bad" ] || fail "$name: $bad"
}

one mlca --vertex tetrahedron
one mlca --vertex octahedron
one mlca --vertex icosahedron
one mlca --vertex bipyramid:5
one mlca --edge 5
one tetoct --vertex "5 bcde,aec,abed,ace,adcb"
one boxspline --vertex bipyramid:3
one catmull-clark --surface-vertex 5

# the tetrahedron's centre cells go below the ring's minimum: the VTK must
# keep them apart (part 0), or the test above would compare the wrong cells
"$exe" draw --scheme mlca --vertex tetrahedron -o "$tmp/t.vtk" 2>/dev/null
checks=$((checks + 1))
low=$(python3 "$tmp/vtk.py" centre "$tmp/t.vtk")
[ "$low" = yes ] || fail "mlca tetrahedron: the centre cells are not marked apart below the ring's minimum"

# relabelled and mirrored: the same picture data (canonical form)
"$exe" draw --scheme boxspline --vertex "5 bcde,aec,abed,ace,adcb" -o "$tmp/x.vtk" 2>/dev/null
"$exe" draw --scheme boxspline --vertex "5 edcb,ace,adeb,aec,abcd" -o "$tmp/y.vtk" 2>/dev/null
checks=$((checks + 1))
[ -s "$tmp/x.vtk" ] && cmp -s "$tmp/x.vtk" "$tmp/y.vtk" ||
  fail "boxspline k = 5: a mirrored link draws another file"

expect_done test_draw_analyze

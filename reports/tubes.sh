#!/usr/bin/env bash
# reports/tubes.sh — the MLCA vertex links the certified control net leaves
# undecided, judged on psi with its spoke tubes proven (issue 34 section 3;
# reports/README.md, finding 5).  Not part of ./run (about 6 s of CPU a link).
#
#   reports/tubes.sh [--max-k K] [--psi-depth N] [--exe PATH] [--list FILE]
#                    [--net-folds] [--data DIR] [--links-only]
#
# Reads the links from the exhaustive tables' not-passing list
# (DIR/exhaustive-vertices-k4-13-not-passing.csv.xz, DIR default
# reports/data: scheme mlca, eigenvalue condition pass, regularity undecided,
# k <= K, default 11), or with --net-folds the links whose control net's fold
# is certified there (regularity fail, certified) while the table judged on
# psi (DIR/exhaustive-vertices-psi-k4-13-not-passing.csv.xz) leaves psi's
# regularity undecided, or from FILE (one plantri link per line);
# --links-only prints the links chosen and stops.  It runs for each
#   subspectra analyze --scheme mlca --vertex LINK --certify --psi-depth N \
#       --psi-tubes --format json
# (N default 2) printing one JSON line per link (link, regularity and
# injectivity verdicts, certified, judged_on, the tubes proven, psi's
# injectivity from its boundary's winding number, the reason) and, on standard
# error, the counts per k.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
maxk=11
depth=2
exe=${SUBSPECTRA:-"$here/../build/cli/subspectra"}
list=""
data="$here/data"
select=undecided
only=0
while [ $# -gt 0 ]; do
  case "$1" in
  --max-k) maxk=$2; shift 2 ;;
  --psi-depth) depth=$2; shift 2 ;;
  --exe) exe=$2; shift 2 ;;
  --list) list=$2; shift 2 ;;
  --net-folds) select=net-folds; shift ;;
  --data) data=$2; shift 2 ;;
  --links-only) only=1; shift ;;
  -h | --help) sed -n '2,22p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
  *) echo "tubes.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
case "$maxk" in
'' | *[!0-9]*) echo "tubes.sh: --max-k expects an integer, not '$maxk'" >&2; exit 2 ;;
esac
case "$depth" in
[1-8]) ;;
*) echo "tubes.sh: --psi-depth expects an integer in 1..8, not '$depth'" >&2; exit 2 ;;
esac
[ -x "$exe" ] || { echo "tubes.sh: no subspectra at '$exe' (--exe PATH)" >&2; exit 2; }
links=$(mktemp)
trap 'rm -f "$links"' EXIT
if [ -n "$list" ]; then
  [ -r "$list" ] || { echo "tubes.sh: cannot read '$list'" >&2; exit 2; }
  cp "$list" "$links"
else
  for f in exhaustive-vertices-k4-13-not-passing.csv.xz exhaustive-vertices-psi-k4-13-not-passing.csv.xz; do
    [ -r "$data/$f" ] || { echo "tubes.sh: cannot read '$data/$f' (--data DIR)" >&2; exit 2; }
  done
  python3 - "$maxk" "$select" "$data/exhaustive-vertices-k4-13-not-passing.csv.xz" \
    "$data/exhaustive-vertices-psi-k4-13-not-passing.csv.xz" >"$links" <<'PY'
import csv, io, lzma, sys
maxk, select, net, psi = int(sys.argv[1]), sys.argv[2], sys.argv[3], sys.argv[4]
def rows(path):
    with lzma.open(path, "rt", newline="") as f:
        for r in csv.DictReader(f):
            if (r["scheme"] == "mlca" and r["case"] == "vertex"
                    and r["eigen_condition"] == "pass" and int(r["k"]) <= maxk):
                yield r
if select == "undecided":
    for r in rows(net):
        if r["regularity"] == "undecided":
            print(r["link"])
else:  # the net's certified folds that psi leaves undecided
    psi_undecided = {r["link"] for r in rows(psi) if r["regularity"] == "undecided"}
    for r in rows(net):
        if (r["regularity"] == "fail" and r["certified"] == "1"
                and r["link"] in psi_undecided):
            print(r["link"])
PY
fi
if [ "$only" = 1 ]; then
  cat "$links"
  exit 0
fi
while IFS= read -r link; do
  [ -z "$link" ] && continue
  # exit status 1 is a failing verdict, still a whole JSON object
  out=$("$exe" analyze --scheme mlca --vertex "$link" --certify --psi-depth "$depth" \
    --psi-tubes --format json) || [ $? -eq 1 ] ||
    { echo "tubes.sh: analyze failed on '$link'" >&2; exit 2; }
  printf '%s' "$out" | python3 -c '
import json, sys
o = json.load(sys.stdin)
r, i = o["regularity"], o["injectivity"]
t = (r.get("psi") or {}).get("tubes")
print(json.dumps({"link": sys.argv[1], "regularity": r["verdict"],
                  "certified": r["certified"], "judged_on": r.get("judged_on"),
                  "injectivity": i["verdict"], "injectivity_certified": i["certified"],
                  "injectivity_judged_on": i.get("judged_on"),
                  "psi_injectivity": (r.get("psi") or {}).get("injectivity"),
                  "tubes": t, "reason": r["reason"]}))
' "$link"
done <"$links" | tee "$links.out"
python3 -c '
import collections, json, sys
c = collections.Counter()
for line in open(sys.argv[1]):
    o = json.loads(line)
    k = o["link"].split()[0]
    c[(k, "regularity", o.get("regularity"), o.get("certified"), o.get("judged_on"))] += 1
    c[(k, "injectivity", o.get("injectivity"), o.get("injectivity_certified"),
       o.get("injectivity_judged_on"))] += 1
for (k, what, v, cert, on), n in sorted(c.items()):
    print("k = %s: %s %d %s%s (judged on %s)" % (k, what, n, v,
          ", certified" if cert else "", on), file=sys.stderr)
' "$links.out"
rm -f "$links.out"

#!/usr/bin/env bash
# test_sweep_psi.sh EXE SRCDIR — `sweep --psi-depth` and what the store keeps
# of psi (issue 34): a sweep of the MLCA vertex links with 6 and 7 vertices
# with --psi-depth 2 stores, case by case, what `analyze --psi-depth 2`
# decides — every verdict's judged_on, psi's verdict, covered and uncovered
# shares (bit for bit) and pieces — as `report --format json` shows it; the
# same sweep without psi keeps its old identity and no psi.  The exhaustive
# table gains the columns on psi only where psi was judged, with psi's
# verdicts counted as the report's cases say; the tables of a store without
# psi have none of them.  --psi-depth out of range is refused.
set -u
exe=$1
src=$2
SS_EXPECT_TIMEOUT=240
. "$src/tests/ss_expect.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

expect 2 "sweep: --psi-depth: expects an integer in 0..8, not '9'" \
  "$exe" sweep --scheme mlca --vertices 6..7 --psi-depth 9 --db "$tmp/bad.db"
expect 2 "sweep: --psi-depth: expects an integer in 0..8, not 'x'" \
  "$exe" sweep --scheme mlca --vertices 6..7 --psi-depth x --db "$tmp/bad.db"
checks=$((checks + 1))
[ ! -e "$tmp/bad.db" ] || fail "a refused --psi-depth created the store"
expect 0 "psi-depth" "$exe" sweep --help

# the same links with and without psi
expect 0 "7 cases of mlca tol=1e-06 depth=6 rings=3 psi-depth=2 " \
  "$exe" sweep --scheme mlca --vertices 6..7 --psi-depth 2 --db "$tmp/psi.db" --jobs 2
expect 0 "7 cases of mlca tol=1e-06 depth=6 rings=3 in " \
  "$exe" sweep --scheme mlca --vertices 6..7 --db "$tmp/net.db" --jobs 2
"$exe" report --db "$tmp/psi.db" --format json >"$tmp/psi.json"
"$exe" report --db "$tmp/net.db" --format json >"$tmp/net.json"
# analyze's own JSON of every stored link, with and without psi
python3 - "$tmp/psi.json" >"$tmp/links.txt" <<'PY'
import json, sys
for c in json.load(open(sys.argv[1]))["cases"]:
    print(c["link"])
PY
i=0
while read -r link; do
  "$exe" analyze --scheme mlca --vertex "$link" --psi-depth 2 --format json >"$tmp/a2.$i.json"
  "$exe" analyze --scheme mlca --vertex "$link" --psi-depth 0 --format json >"$tmp/a0.$i.json"
  i=$((i + 1))
done <"$tmp/links.txt"
checks=$((checks + 1))
python3 - "$tmp" "$i" <<'PY' || fail "report's judged_on and psi against analyze's"
import json, struct, sys
d, n = sys.argv[1], int(sys.argv[2])
bits = lambda x: struct.pack("<d", x)
links = open(d + "/links.txt").read().split("\n")[:n]
for store, tag in (("psi", "a2"), ("net", "a0")):
    cases = {c["link"]: c for c in json.load(open(d + "/" + store + ".json"))["cases"]}
    assert len(cases) == n == 7, (store, len(cases), n)
    on_psi = tubes = 0
    for i, link in enumerate(links):
        a = json.load(open("%s/%s.%d.json" % (d, tag, i)))
        c = cases[link]
        assert a["link"] == link
        for v in ("eigen_condition", "regularity", "injectivity"):
            assert c[v]["verdict"] == a[v]["verdict"], (store, link, v)
            assert c[v]["judged_on"] == a[v]["judged_on"], (store, link, v, c[v], a[v])
        g, ag = c["regularity"], a["regularity"]
        p, ap = g["psi"], ag["psi"]
        assert (p is None) == (ap is None), (store, link, p, ap)
        assert (g["covered"] is None) == (ag["covered"] is None), (store, link)
        if ap is not None:
            assert p["verdict"] == ap["verdict"] and p["judged_on"] == "psi", (link, p, ap)
            assert bits(p["covered"]) == bits(ap["covered"]), (link, p, ap)
            assert bits(g["covered"]) == bits(ag["covered"]), (link, g, ag)
            assert bits(p["uncovered"]) == bits(ap["uncovered"]), (link, p, ap)
            assert p["pieces"] == ap["pieces"], (link, p, ap)
            tubes += ap["uncovered"] > 0
        on_psi += g["judged_on"] == "psi"
    if store == "psi":
        # not vacuous: the octahedron is judged on psi, others have spoke tubes
        assert on_psi >= 1 and tubes >= 1, (on_psi, tubes)
        assert cases["6 bcde,aefc,abfd,acfe,adfb,bedc"]["regularity"]["judged_on"] == "psi"
    else:
        assert on_psi == 0 and all(c["regularity"]["psi"] is None for c in cases.values())
PY

# the exhaustive table: columns on psi only with psi, counted as the cases say
"$exe" report --db "$tmp/psi.db" --table exhaustive >"$tmp/psi.md"
"$exe" report --db "$tmp/psi.db" --table exhaustive --format csv >"$tmp/psi.csv"
"$exe" report --db "$tmp/psi.db" --table exhaustive --format json >"$tmp/psi-exh.json"
"$exe" report --db "$tmp/net.db" --table exhaustive >"$tmp/net.md"
"$exe" report --db "$tmp/net.db" --table exhaustive --format csv >"$tmp/net.csv"
"$exe" report --db "$tmp/net.db" --table exhaustive --format json >"$tmp/net-exh.json"
"$exe" report --db "$tmp/net.db" --format csv >"$tmp/net-cases.csv"
"$exe" report --db "$tmp/psi.db" --format csv >"$tmp/psi-cases.csv"
"$exe" merge "$tmp/both.db" "$tmp/psi.db" "$tmp/net.db" >/dev/null 2>&1
"$exe" report --db "$tmp/both.db" --table exhaustive >"$tmp/both.md"
"$exe" report --db "$tmp/both.db" --table exhaustive --format csv >"$tmp/both.csv"
checks=$((checks + 1))
python3 - "$tmp" <<'PY' || fail "exhaustive tables with and without psi"
import csv, json, sys
d = sys.argv[1]
cases = json.load(open(d + "/psi.json"))["cases"]
want = {}  # k -> [pass, fail, undecided] of the verdicts about psi, from the cases
for c in cases:
    p, g = c["regularity"]["psi"], c["regularity"]
    if c["case"] == "vertex" and p is not None:
        v = g["verdict"] if g["judged_on"] == "psi" else "undecided"
        want.setdefault(c["k"], [0, 0, 0])[["pass", "fail", "undecided"].index(v)] += 1
assert sorted(want) == [6, 7], want
head = ("identity,scheme,k,links,vertices,pass,fail_eigen_condition,fail_regularity,"
        "fail_injectivity_only,undecided,pass_with_centre_folds,edge_points,"
        "edge_point_valence,edge_point_verdict,certified_pass,certified_fail,not_certified")
# without psi: the header of the tables before psi, no psi anywhere
net = open(d + "/net.csv", newline="").read().split("\r\n")
assert net[0] == head, net[0]
assert "psi" not in open(d + "/net.md").read()
assert "psi" not in open(d + "/net-exh.json").read()
assert open(d + "/net-cases.csv", newline="").read().split("\r\n")[0].endswith(
    ",degree,injectivity_certified"), "cases CSV without psi keeps its columns"
# with psi: the columns, counted as the cases say
rows = list(csv.DictReader(open(d + "/psi.csv", newline="")))
assert open(d + "/psi.csv", newline="").read().split("\r\n")[0] == \
    head + ",psi_pass,psi_fail,psi_undecided"
got = {int(r["k"]): [int(r["psi_pass"]), int(r["psi_fail"]), int(r["psi_undecided"])]
       for r in rows}
assert got == want, (got, want)
exh = {o["k"]: [o["psi_pass"], o["psi_fail"], o["psi_undecided"]]
       for o in json.load(open(d + "/psi-exh.json"))["exhaustive"]}
assert exh == want, (exh, want)
md = open(d + "/psi.md").read()
assert "| on psi: pass | on psi: fail | on psi: undecided |" in md, md
for k, (p, f, u) in want.items():
    line = [l for l in md.split("\n") if l.startswith("| %d |" % k)]
    assert len(line) == 1 and line[0].endswith(" %d | %d | %d |" % (p, f, u)), (k, line)
# the cases CSV with psi: judged_on and psi's figures per case
crow = {r["link"]: r for r in csv.DictReader(open(d + "/psi-cases.csv", newline=""))}
for c in cases:
    r, p = crow[c["link"]], c["regularity"]["psi"]
    assert r["regularity_on"] == c["regularity"]["judged_on"], (r, c)
    assert r["eigen_on"] == c["eigen_condition"]["judged_on"]
    assert r["psi_verdict"] == (p["verdict"] if p else "")
    assert (float(r["psi_covered"]) == p["covered"]) if p else r["psi_covered"] == ""
# both stores in one: the psi columns in the psi identity's section only, and
# the CSV rows of the identity without psi leave them empty
both = open(d + "/both.md").read()
secs = both.split("## ")[1:]
assert len(secs) == 2, len(secs)
for s in secs:
    assert ("on psi: pass" in s) == s.startswith("mlca tol=1e-06 depth=6 rings=3 psi-depth=2"), s[:80]
for r in csv.DictReader(open(d + "/both.csv", newline="")):
    assert (r["psi_pass"] == "") == ("psi-depth" not in r["identity"]), r
PY

# --psi-tubes (with --certify and --psi-depth): the identity says so, and the
# store keeps, link by link, the verdicts `analyze --psi-tubes` gives (the
# regular vertex and the octahedron: injectivity judged on psi, proven)
expect 2 "sweep: --psi-tubes needs --certify and a --psi-depth of at least 1" \
  "$exe" sweep --scheme mlca --vertices 6..6 --psi-tubes --db "$tmp/bad.db"
expect 2 "sweep: --psi-tubes needs --certify and a --psi-depth of at least 1" \
  "$exe" sweep --scheme mlca --vertices 6..6 --certify --psi-tubes --db "$tmp/bad.db"
expect 0 "2 cases of mlca tol=1e-06 depth=6 rings=3 certified psi-depth=2 psi-tubes in " \
  "$exe" sweep --scheme mlca --vertices 6..6 --certify --psi-depth 2 --psi-tubes \
  --db "$tmp/tubes.db" --jobs 2
"$exe" report --db "$tmp/tubes.db" --format json >"$tmp/tubes.json"
checks=$((checks + 1))
python3 - "$tmp/tubes.json" "$exe" <<'PY' || fail "sweep --psi-tubes: the store against analyze"
import json, subprocess, sys
cases = json.load(open(sys.argv[1]))["cases"]
assert len(cases) == 2
for c in cases:
    assert c["identity"].endswith(" certified psi-depth=2 psi-tubes"), c["identity"]
    a = json.loads(subprocess.run([sys.argv[2], "analyze", "--scheme", "mlca", "--vertex",
                                   c["link"], "--certify", "--psi-depth", "2",
                                   "--psi-tubes", "--format", "json"],
                                  capture_output=True, text=True).stdout)
    for v in ("regularity", "injectivity"):
        assert c[v]["verdict"] == a[v]["verdict"], (v, c[v], a[v])
        assert c[v]["judged_on"] == a[v]["judged_on"] == "psi", (v, c[v], a[v])
        assert c[v]["certified"] and a[v]["certified"], v
PY

expect_done test_sweep_psi

#!/usr/bin/env python3
"""test_check_surface.py -- `subspectra check --surface-vertices A..B`: the
surface-vertex cases of a Loop-like stencil, in every format, with --certify,
--jobs and --baseline.

Known answers, from closed forms computed here (not from the program): a
Loop-like rule with the edge rule 3/8, 3/8, 1/8, 1/8 and the vertex rule
(1 - n b) P + b (sum of the neighbours) has on its one-ring the eigenvalues
1 and 5/8 - n b (Fourier mode 0) and 3/8 + cos(2 pi k / n) / 4 (mode k, each
twice for 0 < k < n/2), the outer ring's being at most 1/8.
  - data/stencils/loop.ini (Loop's b): lambda1 = lambda2 = 3/8 + cos(2 pi/n)/4
    above every other, so 3..12 pass, also under --certify (exit 0);
  - the mutation b = 1/(8n) (vertex = 3/4, edge = 1/4 in the points family):
    5/8 - n b = 1/2, which is at least 3/8 + cos(2 pi / n) / 4 exactly when
    cos(2 pi / n) <= 1/2, n <= 6: those valences fail the eigenvalue
    condition (n = 6 by an exact tie), 7..12 pass; exit 1 in text, JSON and
    JUnit, with --jobs 2, and certified (the weights are rational);
  - against loop.ini's JSON as a baseline the mutation's regressions are
    exactly the failing valences (exit 1); against itself none (exit 0);
  - --surface-vertices 2..5 and 5..3 are usage errors (exit 2).

usage: test_check_surface.py SUBSPECTRA SOURCE_ROOT"""
import json
import math
import os
import re
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

exe, root = sys.argv[1], sys.argv[2]
loop = os.path.join(root, "data", "stencils", "loop.ini")
failed = 0
checks = 0


def check(ok, what):
    global failed, checks
    checks += 1
    if not ok:
        failed += 1
        print("FAILED:", what, file=sys.stderr)


def run(*args):
    p = subprocess.run([exe, "check", *args], capture_output=True, text=True, timeout=600)
    return p.returncode, p.stdout, p.stderr


def outcomes(js):
    return {c["name"]: c["outcome"] for c in json.loads(js)["cases"]}


valences = range(3, 13)
names = ["surface-vertex %d" % n for n in valences]

# Loop itself: every valence passes, plain and certified
for extra in ([], ["--certify"]):
    rc, js, err = run(loop, "--surface-vertices", "3..12", "--format", "json", *extra)
    got = outcomes(js) if rc in (0, 1) else {}
    check(rc == 0 and list(got) == names and set(got.values()) == {"pass"},
          f"loop.ini {extra}: exit {rc}, {got} {err}")

# the mutation b = 1/(8n): its failing valences from the closed forms
want_fail = set()
for n in valences:
    lam_mode1 = 3 / 8 + math.cos(2 * math.pi / n) / 4
    if 5 / 8 - n * (1 / (8 * n)) >= lam_mode1 - 1e-12:
        want_fail.add("surface-vertex %d" % n)
check(want_fail == {"surface-vertex %d" % n for n in (3, 4, 5, 6)},
      f"closed forms: {sorted(want_fail)}")

with tempfile.TemporaryDirectory() as tmp:
    text = open(loop).read()
    mutated, k = re.subn(r"\[surface\.vertex\]\nvertex = [^\n]*\nedge = [^\n]*\n",
                         "[surface.vertex]\nvertex = 3/4\nedge = 1/4\n", text)
    check(k == 1, "loop.ini's [surface.vertex] not found to mutate")
    mut = os.path.join(tmp, "loop-b8.ini")
    open(mut, "w").write(mutated)
    case = [mut, "--surface-vertices", "3..12"]
    rc_t, txt, _ = run(*case)
    rc_j, js, err_j = run(*case, "--format", "json", "--jobs", "2")
    rc_c, jsc, _ = run(*case, "--format", "json", "--certify")
    rc_x, xml, _ = run(*case, "--format", "junit")
    check(rc_t == rc_j == rc_c == rc_x == 1, f"exit statuses {rc_t} {rc_j} {rc_c} {rc_x}, want 1")
    for label, doc in (("json --jobs 2", js), ("json --certify", jsc)):
        got = outcomes(doc) if doc else {}
        check(list(got) == names, f"{label}: cases {list(got)}")
        check({n for n, o in got.items() if o == "fail"} == want_fail
              and {n for n, o in got.items() if o == "pass"} == set(names) - want_fail,
              f"{label}: outcomes {got}")
    cert = {c["name"]: c for c in json.loads(jsc)["cases"]} if jsc else {}
    check(all(cert[n]["condition"] == "eigenvalue condition" and "not certified" not in
              cert[n]["reason"] for n in want_fail if n in cert),
          f"certified failures: {[cert.get(n) for n in sorted(want_fail)]}")
    check("exact tie" in cert.get("surface-vertex 6", {}).get("reason", ""),
          f"valence 6's tie: {cert.get('surface-vertex 6')}")
    for n in sorted(want_fail):
        check(re.search(r"^fail +%s: eigenvalue condition: " % n, txt, re.M),
              f"text lacks the failure of {n}: {txt}")
    check(re.search(r"10 cases: 6 pass, 4 fail, 0 undecided, 0 errors", txt), f"summary: {txt}")
    tcs = ET.fromstring(xml).findall("./testsuite/testcase") if xml else []
    check([t.get("classname") for t in tcs] == ["check.surface-vertex"] * 10
          and [t.get("name") for t in tcs] == names
          and {t.get("name") for t in tcs if t.find("failure") is not None} == want_fail,
          f"junit testcases {[(t.get('classname'), t.get('name')) for t in tcs]}")
    # --baseline: loop.ini passed everywhere, so the failures are regressions
    base = os.path.join(tmp, "loop.json")
    rc, bjs, _ = run(loop, "--surface-vertices", "3..12", "--format", "json")
    open(base, "w").write(bjs)
    rc_b, out_b, err_b = run(*case, "--baseline", base)
    regs = set(re.findall(r"^regression (surface-vertex \d+):", out_b + err_b, re.M))
    check(rc_b == 1 and "4 regressions against" in out_b + err_b and regs == want_fail,
          f"baseline: exit {rc_b}, regressions {sorted(regs)}")
    selfbase = os.path.join(tmp, "self.json")
    open(selfbase, "w").write(js)
    rc_s, out_s, err_s = run(*case, "--baseline", selfbase)
    check(rc_s == 0 and "0 regressions" in out_s + err_s, f"self baseline: exit {rc_s}")

for bad in ("2..5", "5..3", "3..257", "x"):
    rc, _, err = run(loop, "--surface-vertices", bad)
    check(rc == 2 and "--surface-vertices" in err, f"--surface-vertices {bad}: exit {rc} {err}")
rc, out, _ = run("--help")
check(rc == 0 and "--surface-vertices A..B" in out, "--help lacks --surface-vertices")

print(f"check_surface: {checks} checks, {failed} failed")
sys.exit(1 if failed else 0)

#!/usr/bin/env python3
"""test_check_report.py -- `subspectra check --format json|junit`, `--jobs`
and `--baseline`: the JUnit XML parses (xml.etree) and its counts equal the
JSON's, which equal the text summary's; --jobs 2 gives the same cases and
outcomes; a baseline in which a failing case passed makes it a regression
(listed, exit 1), the run against itself has none (exit 0 though cases fail).

usage: test_check_report.py SUBSPECTRA SOURCE_ROOT"""
import json
import os
import re
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

exe, root = sys.argv[1], sys.argv[2]
stencils = os.path.join(root, "data", "stencils")
failed = 0
checks = 0


def check(ok, what):
    global failed, checks
    checks += 1
    if not ok:
        failed += 1
        print("FAILED:", what, file=sys.stderr)


def run(*args):
    p = subprocess.run([exe, "check", *args], capture_output=True, text=True, timeout=300)
    return p.returncode, p.stdout, p.stderr


# mlca fails from edge valence 8 (lambda3 = |lambda4| = 1/2 there), passes below
case = [os.path.join(stencils, "mlca.ini"), "--vertices", "4..5", "--edges", "6..9"]
rc_t, text, _ = run(*case)
rc_j, js, err_j = run(*case, "--format", "json")
rc_x, xml, err_x = run(*case, "--format", "junit", "--jobs", "2")
check(rc_t == rc_j == rc_x == 1, f"exit statuses {rc_t} {rc_j} {rc_x}, want 1 (edges 8, 9 fail)")
doc = json.loads(js)
summ = doc["summary"]
names = [c["name"] for c in doc["cases"]]
check(summ["cases"] == len(doc["cases"]) and "edge 8" in names and "edge 6" in names,
      f"json cases {names}")
byname = {c["name"]: c for c in doc["cases"]}
check(byname["edge 8"]["outcome"] == "fail" and byname["edge 9"]["outcome"] == "fail"
      and byname["edge 6"]["outcome"] == "pass" and byname["edge 7"]["outcome"] == "pass",
      "edge outcomes")
check(byname["edge 8"]["condition"] == "eigenvalue condition"
      and "lambda3 = 0.5" in byname["edge 8"]["reason"], "edge 8's reason")
m = re.search(r"(\d+) cases: (\d+) pass, (\d+) fail, (\d+) undecided, (\d+) errors", text)
check(m and [int(g) for g in m.groups()] ==
      [summ["cases"], summ["pass"], summ["fail"], summ["undecided"], summ["error"]],
      "text summary equals the json counts")
check(m and m.group(0) in err_j and m.group(0) in err_x, "summary on stderr in json/junit")
top = ET.fromstring(xml)
suites = top.findall("testsuite")
tcs = top.findall("./testsuite/testcase")
fails = [t for t in tcs if t.find("failure") is not None]
errs = [t for t in tcs if t.find("error") is not None]
check(len(suites) == 1 and len(tcs) == summ["cases"], f"{len(tcs)} testcases")
check(int(top.get("tests")) == len(tcs) and int(suites[0].get("tests")) == len(tcs),
      "tests attributes")
check(len(fails) == summ["fail"] + summ["undecided"] == int(top.get("failures"))
      == int(suites[0].get("failures")), f"{len(fails)} failures")
check(len(errs) == summ["error"] == int(top.get("errors")), "errors")
check([t.get("name") for t in tcs] == names, "junit names and order equal json's (--jobs 2)")
for t in fails:
    want = byname[t.get("name")]
    check(t.find("failure").get("message") == want["condition"] + ": " + want["reason"],
          f"{t.get('name')}: failure message")

with tempfile.TemporaryDirectory() as d:
    base = os.path.join(d, "base.json")
    with open(base, "w") as f:
        f.write(js)
    rc, out, _ = run(*case, "--baseline", base)
    check(rc == 0 and "0 regressions" in out, f"against itself: {rc} {out[-200:]}")
    doc["cases"][names.index("edge 9")]["outcome"] = "pass"  # it passed "before"
    with open(base, "w") as f:
        json.dump(doc, f)
    rc, out, _ = run(*case, "--baseline", base)
    check(rc == 1 and "1 regressions" in out and "regression edge 9: eigenvalue condition"
          in out and "regression edge 8" not in out, f"one regression: {rc} {out[-300:]}")
    rc, js2, _ = run(*case, "--baseline", base, "--format", "json", "--jobs", "2")
    d2 = json.loads(js2)
    check(rc == 1 and d2["summary"]["regressions"] == 1 and
          [c["name"] for c in d2["cases"] if c["regression"]] == ["edge 9"], "json regressions")
    with open(base, "w") as f:
        f.write("{\"cases\": 3}")
    rc, _, err = run(*case, "--baseline", base)
    check(rc == 2 and "not the JSON of a" in err, f"malformed baseline: {rc} {err}")
    rc, _, err = run(*case, "--format", "xml")
    check(rc == 2, "--format xml refused")

# bad stencils: exit 2 naming the file, the first error's line and its key (a
# file with two errors named line 6 with line 10's complaint), and the
# valence where a sum is off
HEAD = "[scheme]\nname = bad\nfamily = averaging\nsplit = multilinear\n[mask.hex]\n"
with tempfile.TemporaryDirectory() as d:
    bad2 = os.path.join(d, "bad2.ini")
    with open(bad2, "w") as f:
        f.write(HEAD + "self = 1/x\nedge = 0\nface = 0\nopposite = 0\nfoo = 1\n")
    rc, out, err = run(bad2, "--edges", "4..4", "--format", "junit")
    check(rc == 2 and f"{bad2}:6: [mask.hex] self = '1/x'" in err and "foo" not in err
          and out == "", f"two errors: {rc} {err}")
    off = os.path.join(d, "off.ini")
    with open(off, "w") as f:  # 1/1000 too much at n = 5 only
        f.write(HEAD + "self = 1/8\nedge = 1/8\nface = 1/8\n"
                "opposite = 1/8 + (n-1)*(n-2)*(n-3)*(n-4)/24000\n")
    rc, out, err = run(off, "--edges", "4..4")
    if "libmatheval" in err:
        print("SKIP the valence check: built without libmatheval")
    else:
        check(rc == 2 and f"{off}:5: [mask.hex]: the weights sum to 1001/1000 at n = 5"
              in err, f"sum off at n = 5: {rc} {err}")

print(f"check_report: {checks} checks, {failed} failed")
sys.exit(1 if failed else 0)

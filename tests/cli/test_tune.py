#!/usr/bin/env python3
"""test_tune.py -- `subspectra tune` against a family whose passing interval
and margin are known in closed form, computed here independently.

The family: the tensor-product averaging rule with the 1D rule
a*self + (1-a)*other in every direction (hex mask self = a^3,
edge = a^2 (1-a), face = a (1-a)^2, opposite = (1-a)^3), which is the cubic
B-spline at a = 1/2.  At a regular point (edge valence 4) the scheme is the
tensor cube of the 1D scheme "split, then p_i <- a p_i + (1-a)(p_i-1 + p_i+1)/2",
whose local subdivision matrix on the five points p-2..p2 is built here
(its characteristic polynomial in exact rationals) with spectrum 1, 1/2, a/2, (1-a)/4, (1-a)/4 (at a = 1/2: 1, 1/2,
1/4, 1/8, 1/8, the cubic B-spline's published values).  The 3D spectrum is
the products of three of them: lambda1..3 = 1/2 and |lambda4| =
max(1/4, |a|/2, |1-a|/4), so the case passes exactly for -1 < a < 1 (the
characteristic map is linear: scaled Jacobian 1; for a > 1 the eigenvalue
a/2 of (x^2, y^2, z^2) leads, and that map folds) with margin
gap(a) = 1 - 2 max(1/4, |a|/2, |1-a|/4), largest (1/2) on [0, 1/2].

Checked: the matrix's characteristic polynomial against the closed form; tune over ?(-7/4, 5/4)
lands where gap >= 0.9 * 1/2 (its --keep) and reports the margin gap(a) of
the rational it writes; over ?(-7/4, -1/2), whose middle fails, it lands in
(-1, -1/2] near the optimum -1/2 (gap 1/4); over ?(-3, -3/2), where nothing
passes, it exits 1; the written files read again and pass `check --certify`;
bad input exits 2; a parameter given per valence (self@8 = a^3, ...) tunes
the same way where the case's vertices have that valence, and not where they
do not.  Exits 77 (skipped) without NLopt or libmatheval.

The shipped data/stencils/tensor-family.ini (the same family with segment
and quad masks) is tuned the same way.

usage: test_tune.py SUBSPECTRA SOURCE_ROOT"""
import os
import re
import subprocess
import sys
import tempfile
from fractions import Fraction


exe, root = sys.argv[1], sys.argv[2]
failed = 0
checks = 0


def check(ok, what):
    global failed, checks
    checks += 1
    if not ok:
        failed += 1
        print("FAILED:", what, file=sys.stderr)


def run(*args):
    p = subprocess.run([exe, *args], capture_output=True, text=True, timeout=600)
    return p.returncode, p.stdout, p.stderr


FAMILY = """; the 1D rule a*self + (1-a)*other in every direction
[scheme]
name = tensor-a
family = averaging
split = multilinear
[param]
a = ?({lo}, {hi})   ; the free parameter
[mask.hex]
self = a^3
edge = a^2*(1-a)
face = a*(1-a)^2
opposite = (1-a)^3
"""


def local_1d(a):
    """The 1D scheme's local subdivision matrix on p-2..p2 (Fractions)."""
    b = (1 - a) / 4  # vertex rule b, 1 - 2b, b; edge rule 1/2, 1/2
    h, z = Fraction(1, 2), Fraction(0)
    return [[b, 1 - 2 * b, b, z, z],
            [z, h, h, z, z],
            [z, b, 1 - 2 * b, b, z],
            [z, z, h, h, z],
            [z, z, b, 1 - 2 * b, b]]


def charpoly(m):
    """det(x I - m), coefficients from x^n down (Faddeev-LeVerrier, exact)."""
    n = len(m)
    c = [Fraction(1)]
    mk = [[Fraction(0)] * n for _ in range(n)]
    for k in range(1, n + 1):
        for i in range(n):  # M_k = m (M_{k-1} + c_{k-1} I)
            mk[i][i] += c[-1]
        mk = [[sum(m[i][l] * mk[l][j] for l in range(n)) for j in range(n)]
              for i in range(n)]
        c.append(-sum(mk[i][i] for i in range(n)) / k)
    return c


def poly_from_roots(roots):
    c = [Fraction(1)]
    for r in roots:
        c = [x - r * y for x, y in zip(c + [Fraction(0)], [Fraction(0)] + c)]
    return c


def spectrum_1d(a):
    """The closed form 1, 1/2, a/2, (1-a)/4, (1-a)/4."""
    return [Fraction(1), Fraction(1, 2), a / 2, (1 - a) / 4, (1 - a) / 4]


def gap_tensor(a):
    """(lambda3 - |lambda4|) / lambda3 of the tensor cube of the closed-form
    1D spectrum, or None when the eigenvalue condition fails."""
    e = spectrum_1d(a)
    cube = sorted((x * y * z for x in e for y in e for z in e), key=lambda v: -abs(v))
    if cube[1] != cube[3] or cube[1] <= 0 or abs(cube[1]) == 1 or abs(cube[4]) >= cube[3]:
        return None
    if cube[1] != Fraction(1, 2):  # a/2 > 1/2: a map like (x^2, y^2, z^2), folded
        return None
    return float((cube[3] - abs(cube[4])) / cube[3])


def gap_closed(a):
    return 1 - 2 * max(0.25, abs(a) / 2, abs(1 - a) / 4)


# the closed-form 1D spectrum proven exactly at rational a (the characteristic
# polynomial of the matrix built here); the cubic B-spline's at a = 1/2
grid = [Fraction(k, 200) for k in range(-350, 251)]
for a in grid[::20] + [Fraction(1, 2), Fraction(-1), Fraction(1)]:
    if charpoly(local_1d(a)) != poly_from_roots(spectrum_1d(a)):
        check(False, "1D spectrum at a = %s is not 1, 1/2, a/2, (1-a)/4 x2" % a)
check(sorted(spectrum_1d(Fraction(1, 2)), reverse=True) ==
      [1, Fraction(1, 2), Fraction(1, 4), Fraction(1, 8), Fraction(1, 8)],
      "cubic B-spline spectrum")
passing = [a for a in grid if gap_tensor(a) is not None]
check(min(passing) == Fraction(-199, 200) and max(passing) == Fraction(199, 200),
      "passing interval [%s, %s], not (-1, 1)" % (min(passing), max(passing)))
for a in passing:
    if abs(gap_tensor(a) - gap_closed(float(a))) > 1e-12:
        check(False, "gap at %s: tensor %g, closed form %g" % (a, gap_tensor(a),
                                                                gap_closed(float(a))))
        break

tmp = tempfile.mkdtemp(prefix="ss_tune_")


def tune(lo, hi, evals, *extra):
    path = os.path.join(tmp, "family.ini")
    with open(path, "w") as f:
        f.write(FAMILY.format(lo=lo, hi=hi))
    out = os.path.join(tmp, "tuned.ini")
    if os.path.exists(out):
        os.remove(out)
    rc, so, se = run("tune", path, "--edges", "4..4", "--evals", str(evals), "--jobs", "2",
                     "--output", out, *extra)
    return rc, so, se, out


rc, so, se, out = tune("-7/4", "5/4", 40, "--progress")
if rc == 2 and ("no NLopt" in se or "libmatheval" in se):
    print("SKIP:", se.strip())
    sys.exit(77)


def tuned_value(out):
    """The rational the written file gives a, and the margin it reports."""
    with open(out) as f:
        text = f.read()
    m = re.search(r"^a = (-?\d+)/(\d+)\s+; tuned by subspectra tune in \?\(.*\): "
                  r"smallest margin (\S+)$", text, re.M)
    return (Fraction(int(m.group(1)), int(m.group(2))), float(m.group(3))) if m else (None, None)


check(rc == 0, "tune ?(-7/4, 5/4): exit %d: %s %s" % (rc, so, se))
check("best margin" in se, "--progress prints nothing: %s" % se)
a, margin = tuned_value(out)
check(a is not None, "tuned file: %s" % so)
if a is not None:
    check(-1 < a < 1, "a = %s outside the passing interval (-1, 1)" % a)
    check(gap_closed(float(a)) >= 0.9 * 0.5 - 1e-9,
          "a = %s: gap %g below 0.9 of the optimum 1/2" % (a, gap_closed(float(a))))
    check(abs(margin - gap_closed(float(a))) < 1e-5,
          "reported margin %g, closed form %g at a = %s" % (margin, gap_closed(float(a)), a))
    rc, so2, se2 = run("check", out, "--edges", "4..4", "--certify")
    check(rc == 0, "the tuned file does not pass check --certify: %s %s" % (so2, se2))
    check("check --certify" in so and "1 pass" in so, "no verification said: %s" % so)

# the shipped example: the same family, the same answer
out = os.path.join(tmp, "shipped-tuned.ini")
rc, so, se = run("tune", os.path.join(root, "data", "stencils", "tensor-family.ini"),
                 "--edges", "4..4", "--evals", "30", "-o", out)
a, margin = tuned_value(out) if rc == 0 else (None, None)
check(a is not None and gap_closed(float(a)) >= 0.9 * 0.5 - 1e-9,
      "tensor-family.ini: exit %d, a = %s: %s %s" % (rc, a, so, se))

# the middle of the range fails: the search must find the passing end
rc, so, se, out = tune("-7/4", "-1/2", 40)
a, margin = tuned_value(out)
check(rc == 0 and a is not None, "tune ?(-7/4, -1/2): exit %d: %s %s" % (rc, so, se))
if a is not None:
    check(-1 < a <= Fraction(-1, 2), "a = %s outside (-1, -1/2]" % a)
    check(gap_closed(float(a)) >= 0.9 * 0.25 - 1e-9,
          "a = %s: gap %g below 0.9 of the optimum 1/4" % (a, gap_closed(float(a))))
    rc, _, _ = run("check", out, "--edges", "4..4")
    check(rc == 0, "the tuned file ?(-7/4, -1/2) does not pass check")

# a per-valence parameter (KEY@N): MLCA's hex mask (1/8 each) everywhere but
# at valence 8, where the family's weights read a.  Every fine vertex of the
# regular case lies in 8 hexes, so the closed form is the family's: tune
# lands in (-1, -1/2] with margin gap(a).  The same file with the weights
# given at valence 7 instead leaves the case MLCA's (margin 1/2 whatever a):
# the margin then differs from gap(a), which this check would see.
AT8 = FAMILY.replace("self = a^3\nedge = a^2*(1-a)\nface = a*(1-a)^2\nopposite = (1-a)^3",
                     "self = 1/8\nedge = 1/8\nface = 1/8\nopposite = 1/8\n"
                     "self@8 = a^3\nedge@8 = a^2*(1-a)\nface@8 = a*(1-a)^2\n"
                     "opposite@8 = (1-a)^3")
for valence, want_family in (("8", True), ("7", False)):
    path = os.path.join(tmp, "at%s.ini" % valence)
    with open(path, "w") as f:
        f.write(AT8.replace("@8", "@" + valence).format(lo="-7/4", hi="-1/2"))
    out = os.path.join(tmp, "at%s-tuned.ini" % valence)
    rc, so, se = run("tune", path, "--edges", "4..4", "--evals", "40", "-j", "2", "-o", out)
    a, margin = tuned_value(out) if rc == 0 else (None, None)
    check(rc == 0 and a is not None, "per-valence a@%s: exit %d: %s %s" % (valence, rc, so, se))
    if a is None:
        continue
    fits = abs(margin - gap_closed(float(a))) < 1e-5 and -1 < a <= Fraction(-1, 2)
    check(fits == want_family,
          "a@%s = %s: margin %g, gap(a) %g (the weights at valence %s %s the case)" %
          (valence, a, margin, gap_closed(float(a)), valence,
           "must decide" if want_family else "cannot change"))

# nothing passes: exit 1, the file written all the same
rc, so, se, out = tune("-3", "-3/2", 12)
check(rc == 1 and os.path.exists(out), "tune ?(-3, -3/2): exit %d (want 1): %s" % (rc, se))
m = re.search(r"best smallest margin (\S+)", so)
check(m and float(m.group(1)) < 0, "a failing case's margin is not below 0: %s" % so)

# bad input: exit 2 with a message
path = os.path.join(tmp, "bad.ini")
for text, want in [
        (FAMILY.format(lo="1", hi="0"), "neither p/q nor ?(LO, HI)"),
        (FAMILY.format(lo="0", hi="1/3").replace("self = a^3", "self = 1/8"),
         "the weights sum to"),
        (FAMILY.format(lo="0", hi="1").replace("[mask.hex]", "b = ?(0, 1)\n[mask.hex]"),
         "[param] b is used by no weight"),
        (FAMILY.format(lo="0", hi="1").replace("a = ?(0, 1)", "a = 1/2"),
         "no free parameter"),
        (FAMILY.format(lo="0", hi="1").replace("a = ?", "pi = ?"), "not a parameter's name")]:
    with open(path, "w") as f:
        f.write(text)
    rc, so, se = run("tune", path, "--edges", "4..4", "--evals", "4")
    check(rc == 2 and want in se, "bad file (want '%s'): exit %d: %s" % (want, rc, se))
    if "no free" not in want:
        rc, so, se = run("check", path, "--edges", "4..4")
        check(rc == 2, "check of a bad or free file: exit %d: %s" % (rc, se))
for args in (["--evals", "1"], ["--keep", "0"], ["--vertices", "3..5"], ["--face"]):
    rc, so, se = run("tune", os.path.join(tmp, "family.ini"), "--edges", "4..4", *args)
    check(rc == 2 and "subspectra tune" in se, "tune %s: exit %d: %s" % (args, rc, se))
rc, so, se = run("tune", "--help")
check(rc == 0 and "--vertices" in so and "?(LO, HI)" in so, "tune --help")
rc, so, se = run("tune", os.path.join(tmp, "absent.ini"))
check(rc == 2, "tune of a missing file: exit %d" % rc)

print("tune: %d checks, %d failed" % (checks, failed))
sys.exit(1 if failed else 0)

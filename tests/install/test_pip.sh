#!/usr/bin/env bash
# test_pip.sh SRC SUBSPECTRA SANITIZE
#
# `pip install .` as a Python user meets it (issue 40): a copy of the source
# tree SRC is installed by pip into a fresh virtual environment (made without
# --system-site-packages), the build going through pyproject.toml and
# meson-python (-Dpython_wheel=true: the library inside the package).  No
# network at test time, so pip runs with --no-build-isolation --no-index, and
# the environment is given exactly the packages the build and the package
# need (meson-python, cffi, NumPy, SciPy and what they import), taken from
# the system's python3 through a .pth file: nothing else of the system's
# site directory, so a subspectra installed there cannot be the one found.
# Then, from the environment's python, with no SUBSPECTRA_LIBRARY, PYTHONPATH
# or LD_LIBRARY_PATH:
#  - `import subspectra` is the environment's package and loads the library
#    inside it (subspectra.library_path);
#  - analyze() equals `SUBSPECTRA analyze --format json` (the program of this
#    build) for an edge and a surface vertex, numbers within a relative 1e-12;
#  - eigenvalues() gives the regular MLCA edge's tricubic spectrum 1, 1/2
#    (x3), 1/4 (x6), a closed form;
#  - pip knows the package (pip show) and uninstalls it completely.
# Skipped (exit 77, said why) when /usr/bin/python3 lacks venv/ensurepip or
# one of the packages above, and in a sanitizer build (the wheel is built by
# meson-python's own configuration, without the sanitizers: nothing of it is
# under test there).  The build reuses ccache's objects of the main build
# when ccache is there (the same flags and relative paths: build/ in the
# copy), so it takes seconds; without ccache, a full build of the library.
set -u
src=$1 exe=$(realpath "$2") sanitize=$3
here=$(dirname "$(realpath "$0")") # ss_json_same.py
py=/usr/bin/python3
skip() {
  echo "pip: SKIPPED ($*)"
  exit 77
}
[ "$sanitize" = true ] && skip "sanitizer build: the wheel is built without the sanitizers"
[ -x "$py" ] || skip "no $py"
"$py" -c 'import venv, ensurepip' 2>/dev/null || skip "$py has no venv/ensurepip (Debian: python3-venv)"
mods=(mesonpy pyproject_metadata packaging cffi _cffi_backend pycparser numpy scipy)
"$py" -c "import $(IFS=,; echo "${mods[*]}")" 2>/dev/null ||
  skip "$py lacks one of ${mods[*]} (Debian: python3-mesonpy python3-cffi python3-numpy python3-scipy)"
command -v meson >/dev/null && command -v ninja >/dev/null || skip "no meson or ninja on PATH"

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fails=0
fail() {
  echo "FAIL: $*" >&2
  fails=$((fails + 1))
}
ok() { echo "ok: $*"; }

# the source tree without its build folders
mkdir "$tmp/src"
(cd "$src" && tar -cf - --exclude=./build --exclude='./build-*' --exclude=./.git \
  --exclude='./.mesonpy*' .) | (cd "$tmp/src" && tar -xf -) || { echo "FAIL: copy $src" >&2; exit 1; }
[ -f "$tmp/src/pyproject.toml" ] || { echo "FAIL: no pyproject.toml in $src" >&2; exit 1; }

"$py" -m venv "$tmp/venv" >"$tmp/venv.log" 2>&1 || { cat "$tmp/venv.log" >&2; echo "FAIL: venv" >&2; exit 1; }
vpy=$tmp/venv/bin/python
site=$("$vpy" -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')
# the packages named above, each with its metadata (so that pip sees the
# requirements satisfied), and what they import (ply for Debian's pycparser)
mkdir "$tmp/deps"
"$py" - "$tmp/deps" "${mods[@]}" ply <<'EOF' || { echo "FAIL: dependency links" >&2; exit 1; }
import glob, importlib.util, os, sys
out = sys.argv[1]
for name in sys.argv[2:]:
    spec = importlib.util.find_spec(name)
    if spec is None:
        continue
    path = spec.submodule_search_locations[0] if spec.submodule_search_locations else spec.origin
    top = os.path.dirname(path)
    dist = name.replace("mesonpy", "meson_python")
    for p in [path] + glob.glob(os.path.join(top, dist + "-*.*-info")):
        os.symlink(p, os.path.join(out, os.path.basename(p)))
EOF
echo "$tmp/deps" >"$site/offline-deps.pth"
"$vpy" -c 'import sys; sys.exit(any("dist-packages" in p or "site-packages" in p and "venv" not in p for p in sys.path))' ||
  fail "the environment sees a system site directory"
"$vpy" -c 'import subspectra' 2>/dev/null && fail "subspectra importable before pip install"

# pip install . (builddir: beside the source as the main build, for ccache)
start=$(date +%s)
if (cd "$tmp/src" && env -u PIP_FIND_LINKS -u PIP_INDEX_URL PIP_CONFIG_FILE=/dev/null \
  PIP_DISABLE_PIP_VERSION_CHECK=1 "$vpy" -m pip install --no-build-isolation --no-index \
  --no-cache-dir --config-settings builddir=build . >"$tmp/pip.log" 2>&1); then
  ok "pip install . in a fresh venv ($(($(date +%s) - start)) s)"
else
  tail -30 "$tmp/pip.log" >&2
  echo "FAIL: pip install ." >&2
  exit 1
fi

# from the environment, elsewhere, nothing pointing at the build
mkdir "$tmp/elsewhere"
(cd "$tmp/elsewhere" && env -u SUBSPECTRA_LIBRARY -u PYTHONPATH -u LD_LIBRARY_PATH \
  "$vpy" - "$exe" "$site" "$here" <<'EOF') || fail "the installed package"
import json, os, subprocess, sys
import numpy as np
import subspectra
exe, site = sys.argv[1], sys.argv[2]
sys.path.insert(0, sys.argv[3])
from ss_json_same import same
fails = 0
def fail(msg):
    global fails
    fails += 1
    print("FAIL: " + msg, file=sys.stderr)
pkg = os.path.join(site, "subspectra")
if os.path.dirname(os.path.abspath(subspectra.__file__)) != pkg:
    fail("subspectra is %s, not the environment's %s" % (subspectra.__file__, pkg))
if subspectra.library_path != os.path.join(pkg, "libsubspectra.so"):
    fail("library %s, not the one inside the package" % subspectra.library_path)
print("ok: import subspectra: %s, library %s" % (subspectra.__file__, subspectra.library_path))

for scheme, case, args in (("mlca", {"edge": 5}, ["--edge", "5"]),
                           ("catmull-clark", {"surface_vertex": 5}, ["--surface-vertex", "5"])):
    want = json.loads(subprocess.run([exe, "analyze", "--scheme", scheme, *args, "--format",
                                      "json"], capture_output=True, text=True).stdout)
    same(subspectra.analyze(scheme, **case), want, "%s %s" % (scheme, case), fail)
    print("ok: analyze(%r, %s) == analyze --format json" % (scheme, case))
v, m = subspectra.eigenvalues("mlca", edge=4)
want = np.array([1] + [0.5] * 3 + [0.25] * 6)
if np.max(np.abs(v[:10] - want)) > 1e-12 or list(m[:10]) != [1] + [3] * 3 + [6] * 6:
    fail("mlca edge 4: %s (mult %s), want the tricubic 1, 1/2 x3, 1/4 x6" % (v[:10], m[:10]))
else:
    print("ok: eigenvalues: the tricubic spectrum")
sys.exit(1 if fails else 0)
EOF

show=$("$vpy" -m pip show subspectra 2>/dev/null)
echo "$show" | grep -q '^Version: 0\.1\.0$' && ok "pip show subspectra" || fail "pip show: $show"
"$vpy" -m pip uninstall -y subspectra >"$tmp/un.log" 2>&1 || fail "pip uninstall: $(tail -3 "$tmp/un.log")"
[ -e "$site/subspectra" ] && fail "pip uninstall left $site/subspectra"
"$vpy" -c 'import subspectra' 2>/dev/null && fail "subspectra importable after pip uninstall"
[ "$fails" -eq 0 ] && ok "uninstalled" && echo "pip: all checks passed"
[ "$fails" -eq 0 ]

#!/usr/bin/env bash
# test_install.sh BUILD SRC EXAMPLE PREFIX LIBDIR DATADIR BINDIR MANDIR INCLUDEDIR
#                 PYDIR PYTEST SANITIZE CXXPROG CHECKEXPORTS
#
# The installed library as a user meets it (issue 21): `meson install` into a
# staging folder (DESTDIR), then
#  - every public header compiles alone from #include <subspectra/NAME.h> with
#    the installed pkg-config file's --cflags (nothing includes a header that
#    is not installed), in C and in C++;
#  - the library boundary (issue 33): the C++ program CXXPROG
#    (tests/install/cxx_link.cpp) includes every installed header, is built
#    with g++ and `pkg-config --cflags --libs subspectra`, linked shared, and
#    run (closed forms of the MLCA edge 4, its own checks); ss_version() ==
#    SS_VERSION_STRING == pkg-config --modversion; `nm -D --defined-only` of
#    the installed libsubspectra.so is exactly the functions the installed
#    headers declare, all ss_ (CHECKEXPORTS, tests/install/check_exports.sh),
#    and the checker fails on doctored lists (an undeclared name, an
#    unprefixed one, a missing one, none at all);
#  - the C example examples/analyze_edge.c compiled with
#    `pkg-config --cflags --libs subspectra`, linked against the shared library
#    (and run with it: LD_LIBRARY_PATH, the binary must need libsubspectra.so)
#    and once against the static one (--static; it must not need it); both
#    print numbers checked against closed forms:
#      MLCA edge 4 (the regular grid): the tricubic B-spline's spectrum 1,
#        1/2 (x3), 1/4 (x6) and the two-ring 125, one-ring 27;
#      MLCA edge 5: the tensor product of the cubic B-spline curve and 2D MLCA
#        at valence 5, so lambda1 = lambda2 = Catmull-Clark's subdominant
#        (5 + cos(2pi/n) + cos(pi/n) sqrt(2 (9 + cos(2pi/n))))/16, lambda3 = 1/2
#        and lambda4 = the second Fourier mode's (the same with 4pi/n, 2pi/n);
#        two-ring 30n + 5, one-ring 6n + 3;
#  - the man pages (when help2man was found: MAN = true) are installed, one per
#    command of the overview and per sub-command of enumerate, each naming every
#    long option its --help names, and groff has no warning on any;
#  - `reproduce` run from outside the source tree finds the installed reference
#    values and its tables (reproduce/tables.json) beside the program, and
#    through SUBSPECTRA_DATADIR, and its --help names the compiled-in datadir;
#  - the Python package, installed under the platform's site directory (PYDIR,
#    empty when not built), through test_python.py (PYTEST) and, beside it,
#    test_python_limit.py (limit and the results store) and
#    test_python_mesh.py (mesh files; S's row labels against meshes).
set -u
build=$1 src=$2 example=$3 prefix=$4 libdir=$5 datadir=$6 bindir=$7 mandir=$8 incdir=$9
pydir=${10} pytest=${11} sanitize=${12} cxxprog=${13} checkexports=${14} man=${15}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fails=0
fail() {
  echo "FAIL: $*" >&2
  fails=$((fails + 1))
}
ok() { echo "ok: $*"; }

abs() { case $1 in /*) echo "$1" ;; *) echo "$prefix/$1" ;; esac; }
stage=$tmp/stage
L=$stage$(abs "$libdir")
D=$stage$(abs "$datadir")/subspectra
B=$stage$(abs "$bindir")
MAN=$stage$(abs "$mandir")
INC=$stage$(abs "$incdir")

if ! meson install -C "$build" --no-rebuild --destdir "$stage" >"$tmp/install.log" 2>&1; then
  cat "$tmp/install.log" >&2
  echo "FAIL: meson install" >&2
  exit 1
fi
ok "meson install --destdir"

for f in "$L/libsubspectra.a" "$L/libsubspectra.so" "$L/pkgconfig/subspectra.pc" \
  "$INC/subspectra/ss_local.h" "$B/subspectra"; do
  [ -e "$f" ] || fail "not installed: ${f#"$stage"}"
done
ls "$INC/subspectra" | grep -q '_impl\.h$' && fail "an *_impl.h header is installed"
for d in stencils reference reproduce meshes; do
  [ -n "$(ls "$D/$d" 2>/dev/null)" ] || fail "not installed: ${D#"$stage"}/$d/"
done

# pkg-config over the staged tree: the installed subspectra.pc with its prefix
# moved to the staging folder (PKG_CONFIG_SYSROOT_DIR would move the system
# packages' paths too, cairo's -I/usr/include/cairo among them)
mkdir -p "$tmp/pc"
sed "s|^prefix=.*|prefix=$stage$prefix|" "$L/pkgconfig/subspectra.pc" >"$tmp/pc/subspectra.pc"
grep -q "^prefix=$prefix\$" "$L/pkgconfig/subspectra.pc" || fail "subspectra.pc: prefix is not $prefix"
export PKG_CONFIG_PATH=$tmp/pc
pc_cflags=$(pkg-config --cflags subspectra) || fail "pkg-config --cflags subspectra"
pc_libs=$(pkg-config --libs subspectra) || fail "pkg-config --libs subspectra"
pc_static=$(pkg-config --static --libs subspectra) || fail "pkg-config --static --libs"
echo "cflags: $pc_cflags"
echo "libs: $pc_libs"
echo "static libs: $pc_static"
cc=${CC:-cc}
cxx=${CXX:-c++}
cflags=(-std=c11 -Wall -Wextra -Wpedantic -Werror)
cxxflags=(-std=c++17 -Wall -Wextra -Wpedantic -Werror)
# a sanitizer build's library needs its runtime in the programs that load it
pyenv=()
if [ "$sanitize" = true ]; then
  cflags+=(-fsanitize=address,undefined -fno-omit-frame-pointer)
  cxxflags+=(-fsanitize=address,undefined -fno-omit-frame-pointer)
  pyenv=(LD_PRELOAD="$("$cc" -print-file-name=libasan.so) $("$cc" -print-file-name=libubsan.so)"
    ASAN_OPTIONS=detect_leaks=0) # the interpreter's own allocations are not ours
fi

# every public header alone
nh=0
for h in "$INC"/subspectra/*.h; do
  printf '#include <subspectra/%s>\nint main(void) { return 0; }\n' "${h##*/}" >"$tmp/h.c"
  # shellcheck disable=SC2086 # pkg-config's output is a word list
  "$cc" "${cflags[@]}" -fsyntax-only $pc_cflags "$tmp/h.c" 2>"$tmp/h.log" ||
    fail "header ${h##*/} does not compile alone: $(head -3 "$tmp/h.log")"
  cp "$tmp/h.c" "$tmp/h.cpp"
  # shellcheck disable=SC2086
  "$cxx" "${cxxflags[@]}" -fsyntax-only $pc_cflags "$tmp/h.cpp" 2>"$tmp/h.log" ||
    fail "header ${h##*/} does not compile alone in C++: $(head -3 "$tmp/h.log")"
  printf '#include <subspectra/%s>\n' "${h##*/}" >>"$tmp/ss_all_headers.h"
  nh=$((nh + 1))
done
[ "$nh" -ge 10 ] && ok "$nh public headers compile alone (C and C++)" || fail "only $nh headers"

# C++: every installed header in one program, linked shared, run
# shellcheck disable=SC2086
if "$cxx" "${cxxflags[@]}" -I"$tmp" -o "$tmp/cxx_link" "$cxxprog" $pc_cflags $pc_libs \
  2>"$tmp/cxx.log"; then
  ok "C++ program compiled and linked against the shared library"
  readelf -d "$tmp/cxx_link" 2>/dev/null | grep -q 'NEEDED.*libsubspectra\.so' ||
    fail "the C++ program does not need libsubspectra.so"
  out=$(cd "$tmp" && LD_LIBRARY_PATH=$L "$tmp/cxx_link" 2>&1) || fail "cxx_link: exit $?"
  echo "$out" | sed 's|^|  cxx_link: |'
  echo "$out" | grep -q '^FAIL' && fail "cxx_link: a check failed"
  [ "$(echo "$out" | grep -c '^ok: ')" -ge 8 ] || fail "cxx_link: too few checks ran"
  modversion=$(pkg-config --modversion subspectra)
  libversion=$(echo "$out" | awk '$1 == "version" { print $2 }')
  if [ -n "$modversion" ] && [ "$libversion" = "$modversion" ]; then
    ok "ss_version() $libversion == pkg-config --modversion $modversion"
  else
    fail "ss_version() '$libversion' != pkg-config --modversion '$modversion'"
  fi
else
  fail "C++ program does not compile or link: $(head -5 "$tmp/cxx.log")"
fi

# the export list: exactly the declared ss_ functions; the checker itself on
# doctored lists, so that it cannot pass vacuously
# shellcheck disable=SC2086
exports() { bash "$checkexports" "$1" "$INC" "$cc" $pc_cflags; }
nm -D --defined-only "$L/libsubspectra.so" >"$tmp/nm.txt" || fail "nm -D"
echo "exported: $(wc -l <"$tmp/nm.txt") symbols"
if exports "$tmp/nm.txt" >"$tmp/exports.log" 2>&1; then
  cat "$tmp/exports.log"
else
  fail "export list: $(grep -c FAIL "$tmp/exports.log") offenders:
$(head -20 "$tmp/exports.log")"
fi
# (doctored: NAME, the check that must fail, what it must say)
doctored() {
  if exports "$tmp/fake.txt" >"$tmp/fake.log" 2>&1; then
    fail "check_exports passed a list with $1"
  elif ! grep -qF "$2" "$tmp/fake.log"; then
    fail "check_exports on a list with $1 did not say '$2': $(head -3 "$tmp/fake.log")"
  else
    ok "check_exports fails on a list with $1"
  fi
}
{ cat "$tmp/nm.txt" && echo "0000000000001000 T ss_fake_undeclared"; } >"$tmp/fake.txt"
doctored "an undeclared ss_ name" "declared in no installed header: ss_fake_undeclared"
{ cat "$tmp/nm.txt" && echo "0000000000001000 T lim_step"; } >"$tmp/fake.txt"
doctored "an unprefixed name" "without the ss_ prefix: lim_step"
grep -v ' ss_version$' "$tmp/nm.txt" >"$tmp/fake.txt"
doctored "ss_version hidden" "not exported: ss_version"
: >"$tmp/fake.txt"
doctored "no symbol" "the export list is empty"

# the example, shared
# shellcheck disable=SC2086
if "$cc" "${cflags[@]}" -o "$tmp/ae" "$example" $pc_cflags $pc_libs 2>"$tmp/cc.log"; then
  ok "example compiled against the shared library"
else
  fail "example (shared) does not compile: $(head -5 "$tmp/cc.log")"
fi
readelf -d "$tmp/ae" 2>/dev/null | grep -q 'NEEDED.*libsubspectra\.so' ||
  fail "the shared example does not need libsubspectra.so"
# the example, static libsubspectra (the system libraries it needs stay shared)
# shellcheck disable=SC2086
if "$cc" "${cflags[@]}" -o "$tmp/aes" "$example" $pc_cflags \
  ${pc_static/-lsubspectra/$L/libsubspectra.a} 2>"$tmp/ccs.log"; then
  ok "example linked statically"
else
  fail "example (static) does not link: $(head -5 "$tmp/ccs.log")"
fi
readelf -d "$tmp/aes" 2>/dev/null | grep -q 'libsubspectra' &&
  fail "the static example still needs libsubspectra"

# check_edge BINARY N: the example's numbers against the closed forms above
check_edge() {
  local bin=$1 n=$2 out
  out=$(cd "$tmp" && LD_LIBRARY_PATH=$L "$bin" mlca "$n" 2>&1)
  local rc=$?
  echo "$out" | sed "s|^|  ${bin##*/} $n: |"
  [ "$rc" -eq 0 ] || fail "${bin##*/} mlca $n: exit $rc (expected 0: pass)"
  echo "$out" | awk -v n="$n" -v who="${bin##*/} mlca $n" '
    function near(a, b, what) {
      if (!(a - b <= 1e-9 * (b < 0 ? -b : b) + 1e-12 && b - a <= 1e-9 * (b < 0 ? -b : b) + 1e-12)) {
        printf "FAIL: %s: %s = %.15g, closed form %.15g\n", who, what, a, b > "/dev/stderr"; bad = 1
      }
    }
    BEGIN { pi = atan2(0, -1) }
    $1 == "matrix" { n2 = $2; n1 = $3 }
    $1 == "lambda" { re[$2] = $3; im[$2] = $4; mu[$2] = $5 }
    $1 == "verdict" { verdict = $2 }
    END {
      want[0] = 1
      if (n == 4) {
        for (i = 1; i <= 3; i++) want[i] = 0.5
        for (i = 4; i <= 7; i++) want[i] = 0.25
        if (mu[1] != 3 || mu[4] != 6) {
          printf "FAIL: %s: multiplicities %d, %d (tricubic: 3, 6)\n", who, mu[1], mu[4] > "/dev/stderr"; bad = 1
        }
        near(n2, 125, "two-ring"); near(n1, 27, "one-ring")
      } else {
        c2 = cos(2 * pi / n); c1 = cos(pi / n)
        c4 = cos(4 * pi / n)
        want[1] = want[2] = (5 + c2 + c1 * sqrt(2 * (9 + c2))) / 16
        want[3] = 0.5
        want[4] = (5 + c4 + c2 * sqrt(2 * (9 + c4))) / 16
        near(n2, 30 * n + 5, "two-ring"); near(n1, 6 * n + 3, "one-ring")
      }
      for (i = 0; i in want; i++) {
        near(re[i], want[i], "lambda" i)
        near(im[i], 0, "Im lambda" i)
      }
      if (verdict != "pass") { printf "FAIL: %s: verdict %s\n", who, verdict > "/dev/stderr"; bad = 1 }
      exit bad
    }' || fails=$((fails + 1))
}
[ -x "$tmp/ae" ] && check_edge "$tmp/ae" 4 && check_edge "$tmp/ae" 5
[ -x "$tmp/aes" ] && check_edge "$tmp/aes" 4

# the man pages: one per command of the overview and per sub-command of
# enumerate, each made from that command's --help (every long option of the
# help is in the page; help2man writes "\-\-name" as roff)
if [ "$man" = true ]; then
  man1=$MAN/man1
  pages=(subspectra)
  for c in $("$B/subspectra" --help | awk '/^commands:/ { on = 1; next } on && /^  [a-z]/ { print $1 } on && /^$/ { exit }'); do
    pages+=("subspectra-$c")
  done
  for w in $("$B/subspectra" enumerate --help | awk '/^  [a-z]+  / { print $1 }'); do
    pages+=("subspectra-enumerate-$w")
  done
  [ ${#pages[@]} -ge 15 ] || fail "man pages: the overview lists only ${#pages[@]} commands"
  for p in "${pages[@]}"; do
    f=$man1/$p.1
    if [ ! -f "$f" ]; then
      fail "man page $p(1) is not installed"
      continue
    fi
    args=${p#subspectra}
    args=${args//-/ }
    # shellcheck disable=SC2086 # the command's words
    for o in $("$B/subspectra" $args --help | grep -o -E -- '--[a-z][a-z0-9-]+' | sort -u); do
      grep -q -F -- "$(sed 's/-/\\-/g' <<<"$o")" "$f" || fail "man page $p(1) lacks $o of its --help"
    done
    want=".TH $(tr '[:lower:]' '[:upper:]' <<<"$p" | sed 's/-/\\-/g') "
    grep -q -F -- "$want" "$f" || fail "man page $p(1) is titled $(grep -m1 '^\.TH' "$f")"
    if command -v groff >/dev/null; then
      groff -k -man -Tutf8 -ww -z "$f" 2>"$tmp/groff.log"
      [ -s "$tmp/groff.log" ] && fail "groff warns on $p(1): $(head -3 "$tmp/groff.log")"
    fi
  done
  ok "man pages (${#pages[@]}, from --help by help2man)"
else
  echo "skip: man pages (built without help2man: the option man)"
fi

# reproduce from outside the source tree: the reference files and the tables
# are found (they are loaded before the output folder is made, so an output
# that cannot be made shows that loading got past them without running the
# whole reproduce)
mkdir -p "$tmp/elsewhere"
run_reproduce() { (cd "$tmp/elsewhere" && "$@" reproduce --out /dev/null/x 2>&1); }
out=$(run_reproduce env -u SUBSPECTRA_DATADIR "$B/subspectra")
case $out in
*"cannot create /dev/null/x"*) ok "reproduce finds the data beside the installed program" ;;
*) fail "installed reproduce: $out" ;;
esac
mv "$D/reproduce" "$tmp/tables"
out=$(run_reproduce env -u SUBSPECTRA_DATADIR "$B/subspectra")
case $out in
*"reproduce/tables.json: No such file or directory (the tables to make)"*) ok "without the tables: a clear message" ;;
*) fail "reproduce without its tables: $out" ;;
esac
mv "$tmp/tables" "$D/reproduce"
mv "$D" "$tmp/moved"
out=$(run_reproduce env -u SUBSPECTRA_DATADIR "$B/subspectra")
case $out in
*"no reference files"*) ok "without the data: a clear message" ;;
*) fail "reproduce without its data: $out" ;;
esac
out=$(run_reproduce env SUBSPECTRA_DATADIR="$tmp/moved" "$B/subspectra")
case $out in
*"cannot create /dev/null/x"*) ok "SUBSPECTRA_DATADIR" ;;
*) fail "reproduce with SUBSPECTRA_DATADIR: $out" ;;
esac
# the source tree keeps its behaviour: data/reference relative to the cwd
# (the installed data still moved away, so only the source tree can serve)
out=$(cd "$src" && env -u SUBSPECTRA_DATADIR "$B/subspectra" reproduce --out /dev/null/x 2>&1)
case $out in
*"cannot create /dev/null/x"*) ok "source tree" ;;
*) fail "reproduce in the source tree: $out" ;;
esac
mv "$tmp/moved" "$D"
"$B/subspectra" reproduce --help | tr -s ' \n' ' ' | grep -qF "$(abs "$datadir")/subspectra/reference" ||
  fail "reproduce --help does not name the installed datadir"

# the Python package (when meson found Debian's python3 with cffi): installed
# under the platform's site directory, run against the staged library
if [ -n "$pydir" ]; then
  P=$stage$(abs "$pydir")
  if [ -f "$P/subspectra/__init__.py" ] && [ -f "$P/subspectra/_config.py" ]; then
    grep -q "^LIBRARY = \"$(abs "$libdir")/libsubspectra.so.0\"" "$P/subspectra/_config.py" ||
      fail "python: _config.py does not name the installed library"
    # the layouts the package declares to cffi, as the C compiler sees them
    cat >"$tmp/layout.c" <<'EOC'
#include <stddef.h>
#include <stdio.h>
#include <subspectra/ss_eigvec.h>
#include <subspectra/ss_report_case.h>
#include <subspectra/ss_limit.h>
#include <subspectra/ss_report_table.h>
#define SZ(T) printf("sizeof %s %zu\n", #T, sizeof(T))
#define OFF(T, f) printf("offsetof %s %s %zu\n", #T, #f, offsetof(T, f))
int main(void) {
  SZ(ss_error), SZ(ss_case), SZ(ss_eigval), SZ(ss_eig_opts), SZ(ss_report_analyze_opts);
  OFF(ss_case, link), OFF(ss_case, n), OFF(ss_case, diag);
  OFF(ss_local, n2), OFF(ss_local, n1), OFF(ss_local, S), OFF(ss_local, nnz);
  OFF(ss_local, dim), OFF(ss_local, level), OFF(ss_eig, n), OFF(ss_eig, val);
  OFF(ss_eigval, mult), OFF(ss_eig_opts, tol), OFF(ss_eig_opts, progress);
  SZ(ss_eigvec), OFF(ss_eigvec, k), OFF(ss_eigvec, right_re), OFF(ss_eigvec, left_im);
  OFF(ss_eigvec, complex_any);
  SZ(ss_limit_point), OFF(ss_limit_point, jac), OFF(ss_limit_point, products);
  SZ(ss_result), OFF(ss_result, eig), OFF(ss_result, seconds), SZ(ss_report_row);
  SZ(ss_report_rows), OFF(ss_report_rows, n);
  return 0;
}
EOC
    # shellcheck disable=SC2086
    "$cc" "${cflags[@]}" -o "$tmp/layout" "$tmp/layout.c" $pc_cflags &&
      "$tmp/layout" >"$tmp/layout.txt" || fail "layout program"
    (cd "$tmp/elsewhere" && env "${pyenv[@]}" PYTHONPATH="$P" \
      SUBSPECTRA_LIBRARY="$L/libsubspectra.so.0" /usr/bin/python3 "$pytest" "$B/subspectra" "$tmp/layout.txt") || fail "python package"
    (cd "$tmp/elsewhere" && env "${pyenv[@]}" PYTHONPATH="$P" \
      SUBSPECTRA_LIBRARY="$L/libsubspectra.so.0" /usr/bin/python3 "$(dirname "$pytest")/test_python_limit.py" \
      "$B/subspectra" "$src") || fail "python package: limit, store_table"
    (cd "$tmp/elsewhere" && env "${pyenv[@]}" PYTHONPATH="$P" \
      SUBSPECTRA_LIBRARY="$L/libsubspectra.so.0" /usr/bin/python3 "$(dirname "$pytest")/test_python_mesh.py" \
      "$B/subspectra" "$src") || fail "python package: read_mesh, write_mesh, local_labels on meshes"
  else
    fail "python package not installed under ${P#"$stage"}"
  fi
else
  echo "python: SKIPPED (no /usr/bin/python3 with cffi at configure time)"
fi

[ "$fails" -eq 0 ] && echo "install: all checks passed"
[ "$fails" -eq 0 ]

#!/usr/bin/env bash
# check_exports.sh NMFILE INCDIR CC [CFLAG...]
#
# The shared library's export list against its installed headers (issue 33):
# NMFILE is `nm -D --defined-only` of libsubspectra.so (lines "ADDR TYPE
# NAME"), INCDIR the installed include folder (INCDIR/subspectra/*.h), CC a
# GCC and CFLAGs what the headers need (pkg-config --cflags subspectra).
#
# The declared functions are the compiler's own list, not a pattern over the
# text: a C file including every installed header is compiled with -aux-info,
# which writes one prototype per function declared, with the file it is
# declared in; kept are the declarations (NC, not the NF of static inline
# definitions) in INCDIR/subspectra.  Declared objects: `extern` lines of the
# headers.  Fails when
#  - the export list is empty, or the headers declare no function;
#  - an exported name does not start with ss_;
#  - an exported name is declared in no installed header;
#  - a function an installed header declares is not exported (a user would
#    link against a name the library hides).
# Prints every offender; exit 0 when none.  test_install.sh also runs it on
# doctored lists, so that it cannot pass vacuously.
set -u
nmfile=$1 inc=$2 cc=$3
shift 3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
bad=0

for h in "$inc"/subspectra/*.h; do
  printf '#include <subspectra/%s>\n' "${h##*/}"
done >"$tmp/all.c"
if ! "$cc" -std=c11 -fsyntax-only -aux-info "$tmp/aux.txt" "$@" "$tmp/all.c" 2>"$tmp/cc.log"; then
  echo "FAIL: the installed headers do not compile together: $(head -3 "$tmp/cc.log")"
  exit 1
fi
# "/* INCDIR/subspectra/ss_x.h:12:NC */ extern T *ss_name (args);": the name is
# the first identifier followed by " (" after the comment
awk -v dir="$inc/subspectra/" '
  $1 == "/*" && index($2, dir) == 1 && $2 ~ /:NC$/ {
    sub(/^\/\*[^*]*\*\/ /, "")
    if ($1 == "static") next
    if (match($0, /[A-Za-z_][A-Za-z0-9_]* \(/)) print substr($0, RSTART, RLENGTH - 2)
  }' "$tmp/aux.txt" | sort -u >"$tmp/functions"
# extern objects: "extern const T ss_name[...];" (no parenthesis: not a function)
cat "$inc"/subspectra/*.h | grep -E '^[[:space:]]*extern[^(]*;' |
  grep -oE 'ss_[A-Za-z0-9_]+[][0-9A-Z_]*;' | grep -oE '^ss_[A-Za-z0-9_]+' | sort -u >"$tmp/objects"
sort -u "$tmp/functions" "$tmp/objects" >"$tmp/declared"
awk 'NF == 3 { print $3 }' "$nmfile" | sort -u >"$tmp/exported"

nexp=$(wc -l <"$tmp/exported")
nfun=$(wc -l <"$tmp/functions")
[ "$nexp" -gt 0 ] || {
  echo "FAIL: the export list is empty"
  bad=1
}
[ "$nfun" -gt 0 ] || {
  echo "FAIL: the installed headers declare no function (-aux-info found none)"
  bad=1
}
while read -r s; do
  case $s in
  ss_*) ;;
  *)
    echo "FAIL: exported without the ss_ prefix: $s"
    bad=1
    continue
    ;;
  esac
  grep -qxF "$s" "$tmp/declared" || {
    echo "FAIL: exported but declared in no installed header: $s"
    bad=1
  }
done <"$tmp/exported"
while read -r f; do
  grep -qxF "$f" "$tmp/exported" || {
    echo "FAIL: declared in an installed header but not exported: $f"
    bad=1
  }
done <"$tmp/functions"
[ "$bad" -eq 0 ] &&
  echo "ok: $nexp exported symbols, each an ss_ name an installed header declares; all $nfun declared functions exported"
exit "$bad"

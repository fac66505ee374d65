#!/usr/bin/env bash
# ss_man.sh HELP2MAN SUBSPECTRA VERSION OUT [COMMAND [WHAT]] -- write the man
# page subspectra(1) (no COMMAND: the overview), subspectra-COMMAND(1) or
# subspectra-COMMAND-WHAT(1) with help2man from the program's own --help and
# --version, so that a page says exactly what --help says (help2man turns the
# "  -x, --long ARG   text" lines into the page's option lists).  The page's
# one-line NAME is the command's line of the overview (or of `enumerate
# --help` for its sub-commands); the title names the page, not the program
# help2man finds in --version.
set -euo pipefail
# help2man reads --help in the locale (LC_ALL and --locale: the overview has a dash)
h2m=$1 exe=$2 version=$3 out=$4
shift 4
cmd="$*"
page=subspectra${cmd:+-${cmd// /-}}
if [ -z "$cmd" ]; then
  name=$("$exe" --help | sed -n '1s/^[^—]*— *//p')
  see="The user guide: README.md and docs/ (a page per command) in the source distribution; the library: pkg\\-config subspectra."
else
  # the summary of the last word of COMMAND in its parent's list
  parent=()
  [ $# -gt 1 ] && parent=("$1")
  name=$("$exe" "${parent[@]}" --help |
    awk -v c="${!#}" '$1 == c { $1 = ""; sub(/^ +/, ""); print; exit }')
  [ -n "$name" ] || { echo "ss_man.sh: '$cmd' is not in its overview" >&2; exit 1; }
  see="\\fBsubspectra\\fR(1); docs/$1.md in the source distribution."
fi
inc=$(mktemp)
trap 'rm -f "$inc" "$out.tmp"' EXIT
{
  echo '[ENVIRONMENT]'
  echo '.TP'
  echo '.B SUBSPECTRA_DATADIR'
  echo "the folder of the installed data (stencils/, reference/, meshes/);"
  echo "\`reproduce' reads its reference values from its reference/ folder"
  echo '[SEE ALSO]'
  echo "$see"
} >"$inc"
LC_ALL=C.UTF-8 "$h2m" --no-info --no-discard-stderr --locale=C.UTF-8 --name="$name" --include="$inc" \
  --help-option="${cmd:+$cmd }--help" --version-option="${cmd:+$cmd }--version" \
  --source="subspectra $version" --manual="User Commands" -o "$out.tmp" "$exe"
# help2man titles the page after the program (SUBSPECTRA, "subspectra \-"):
# name it after the command
upper=$(tr '[:lower:]' '[:upper:]' <<<"$page")
sed -e "s/^\.TH SUBSPECTRA /.TH ${upper//-/\\\\-} /" \
  -e "/^\.SH NAME/{n;s/^subspectra \\\\-/${page//-/\\\\-} \\\\-/}" "$out.tmp" >"$out"

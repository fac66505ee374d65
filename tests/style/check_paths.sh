#!/usr/bin/env bash
# shellcheck disable=SC2016 # backquotes in single quotes are Markdown's
# check_paths.sh SRCDIR — the repository names only itself (issue 21).
#
# Fails when
#  1. a tracked text file names a path outside the repository: the shared
#     folder the project was planned in (an absolute path under the work
#     directory, or the folder "shared" beside the repository), or a paper text
#     under papers/ (the paper texts are not in the repository; cite them by
#     their key in docs/references.bib);
#  2. docs/DESIGN.md names, in backquotes, a repository path that does not exist
#     (a span that looks like a path: no spaces, and a '/' or a file extension;
#     globs must match something; placeholders in capitals such as DIR/NAME.md
#     or FILE.png are skipped);
#  2b. README.md or a page docs/*.md links (Markdown, relative to the file) to
#     a file that does not exist or to a heading a Markdown file does not have;
#  3. a file cites "DESIGN section N" for a section docs/DESIGN.md does not have.
#
# Before checking SRCDIR it checks itself on two small trees, one clean and one
# with one fault of each kind, so that a checker that finds nothing cannot pass.
set -u

# The patterns are assembled so that this file does not match them itself.
outside_re="/wo""rk/|\.\./sha""red|(^|[^A-Za-z0-9_./-])pa""pers/[A-Za-z0-9_.-]+"
path_ext='c|h|cpp|md|tsv|ini|sh|bib|build|mesh|obj|jsonl|png|svg|supp|txt|mtx'
placeholders='DIR|NAME|FILE|IN|OUT|STENCIL|MESH|LINKS'

# The files to check, one per line: git's tracked files when SRCDIR is a git
# checkout, else every file outside build directories.
list_files() {
  if git -C "$1" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
    git -C "$1" ls-files
  else
    (cd "$1" && find . -path ./.git -prune -o -path './build*' -prune -o -type f -print |
      sed 's|^\./||')
  fi
}

# in_files ROOT FILES COMMAND...: run COMMAND on those of FILES (one per line,
# relative to ROOT) that are regular files, from ROOT, as few times as xargs can.
in_files() {
  local root=$1 files=$2
  shift 2
  (cd "$root" && while IFS= read -r f; do
    [ -f "$f" ] && printf '%s\0' "$f"
  done <<<"$files" | xargs -0 -r "$@" 2>/dev/null)
}

# anchors FILE.md: the anchors of its headings as GitHub makes them (lower
# case; letters, digits, spaces, '-' and '_' kept, spaces turned into '-'; this
# drops non-ASCII letters too, which the project's headings do not use).
anchors() {
  grep -E '^#{1,6} ' "$1" | sed -E 's/^#+ +//' | tr '[:upper:]' '[:lower:]' |
    LC_ALL=C sed 's/[^a-z0-9 _-]//g; s/ /-/g'
}

# links FILE.md: the targets of its Markdown links and images, one per line,
# outside code (indented blocks and fences) and inline code spans.
links() {
  awk '/^ *```/ { fence = !fence; next } !fence && !/^    /' "$1" |
    sed 's/`[^`]*`//g' | grep -o '\]([^)]*)' | sed 's/^\](//; s/)$//; s/ .*//' | sort -u
}

# check_tree DIR: print one line per fault; return 1 if there was any.
check_tree() {
  local root=$1 bad=0 files f span p n line
  files=$(list_files "$root" | sort)

  # 1. paths outside the repository (one grep over all files: FILE:LINE:text)
  while IFS= read -r line; do
    echo "outside path: $line"
    bad=1
  done < <(in_files "$root" "$files" grep -I -n -H -E "$outside_re" | cut -c1-160)

  # 2. paths and links in docs/DESIGN.md
  local design="$root/docs/DESIGN.md"
  if [ ! -f "$design" ]; then
    echo "missing: docs/DESIGN.md"
    bad=1
  else
    while IFS= read -r span; do
      # a path: no spaces or other signs; a letter in its first component
      [[ "$span" =~ ^[A-Za-z0-9_.*-]+(/[A-Za-z0-9_.*-]*)*$ ]] || continue
      [[ "$span" =~ ^[0-9./]*$ ]] && continue
      [[ "$span" == */* || "$span" =~ \.($path_ext)$ ]] || continue
      [[ "$span" =~ (^|/)($placeholders)(\.[a-z]+)?(/|$) ]] && continue
      [[ "$span" =~ ^\.[a-z]+$ && ! -e "$root/$span" ]] && continue # an extension
      p=${span%/}
      if [[ "$span" == */ ]]; then
        # a folder
        [ -d "$root/$p" ] && continue
      elif [[ "$p" == */* ]]; then
        # a path from the root; globs match tracked files
        if [[ "$p" == *'*'* ]]; then
          n=$(grep -c -E "^$(sed 's/[.]/\\./g; s/[*]/[^\/]*/g' <<<"$p")$" <<<"$files")
          [ "$n" -gt 0 ] && continue
        elif [ -e "$root/$p" ]; then
          continue
        fi
      else
        # a bare file name: some file of that name
        grep -q -E "(^|/)${p//./\\.}$" <<<"$files" && continue
      fi
      echo "docs/DESIGN.md names \`$span\`, which is not in the repository"
      bad=1
    done < <(grep -o '`[^`]*`' "$design" | tr -d '`' | sort -u)
  fi

  # 2b. links in README.md and docs/*.md (relative to the file) to files and
  # headings that exist
  local md dir
  while IFS= read -r md; do
    dir=$(dirname "$md")
    while IFS= read -r span; do
      p=${span%%#*}
      [[ "$p" =~ ^[a-z]+: ]] && continue # http:, https:, mailto:
      if [ -z "$p" ]; then
        p=$(basename "$md")
      fi
      if [ ! -e "$root/$dir/$p" ]; then
        echo "$md links to $span, which does not exist"
        bad=1
      elif [[ "$span" == *'#'* && "$p" == *.md ]] &&
        ! anchors "$root/$dir/$p" | grep -q -x -F "${span#*#}"; then
        echo "$md links to $span: $p has no such heading"
        bad=1
      fi
    done < <(links "$root/$md")
  done < <(grep -E '^(README\.md|docs/[^/]*\.md)$' <<<"$files")

  # 3. "DESIGN section N" cited anywhere must exist
  if [ -f "$design" ]; then
    while IFS= read -r n; do
      if ! grep -q -E "^## $n\. " "$design"; then
        echo "DESIGN section $n is cited but docs/DESIGN.md has no section $n"
        bad=1
      fi
    done < <(in_files "$root" "$files" grep -I -o -h -E \
      'DESIGN sections? [0-9]+((, | and )[0-9]+)*' | grep -o -E '[0-9]+' | sort -un)
  fi
  return $bad
}

# A tree that passes and one with one fault of each kind.
self_test() {
  local t out status=0
  t=$(mktemp -d) || return 1
  mkdir -p "$t/good/docs" "$t/good/src" "$t/bad/docs" "$t/bad/src"
  printf '# D\n## 1. One\nSee `src/a.c`, `src/*.c`, `a.c`, `DIR/NAME.md`, `1/2`, [r](../README.md#the-x-y).\n' \
    >"$t/good/docs/DESIGN.md"
  printf '/* a.c (DESIGN section 1) */\n' >"$t/good/src/a.c"
  printf '# R\n## The `x` (y)\nSee [d](docs/DESIGN.md#1-one), [p](docs/p.md#a) and [s](#r).\n' >"$t/good/README.md"
  printf '# P\n## A\n[back](../README.md#the-x-y), [self](#p), `[no](x.md)`\n\n    [code](y.md)\n' >"$t/good/docs/p.md"
  cp -r "$t/good/." "$t/bad/"
  printf '/* b.c: see %s (DESIGN sections 1 and 7) */\n' "/wo""rk/shared/x" >"$t/bad/src/b.c"
  printf 'See `src/missing.c`, `data/*.tsv` and [m](../MISSING.md), [z](../README.md#zz).\n' >>"$t/bad/docs/DESIGN.md"
  printf '[q](docs/q.md) [b](#nowhere)\n' >>"$t/bad/README.md"
  printf '[i](../img.png)\n' >>"$t/bad/docs/p.md"
  if ! out=$(check_tree "$t/good"); then
    echo "self-test: a clean tree was refused:"
    echo "$out"
    status=1
  fi
  out=$(check_tree "$t/bad") && {
    echo "self-test: a tree with faults passed"
    status=1
  }
  for want in "outside path: src/b.c" "src/missing.c" "data/\*.tsv" "MISSING.md" "README.md#zz: ../README.md has no such heading" \
    "README.md links to docs/q.md, which" "README.md links to #nowhere: README.md has no such heading" \
    "docs/p.md links to ../img.png, which" "DESIGN section 7"; do
    if ! grep -q "$want" <<<"$out"; then
      echo "self-test: the fault '$want' was not found; the checker said:"
      echo "$out"
      status=1
    fi
  done
  rm -rf "$t"
  return $status
}

src=${1:?usage: check_paths.sh SRCDIR}
if ! self_test; then
  echo "paths: the checker's self-test failed"
  exit 1
fi
if out=$(check_tree "$src"); then
  echo "paths: $(list_files "$src" | wc -l) files name no path outside the repository;" \
    "docs/DESIGN.md's paths and cited sections and the links of README.md and docs/*.md exist"
  exit 0
fi
echo "$out"
echo "paths: fix the lines above (cite the papers by their key in docs/references.bib," \
  "name paths relative to the repository)"
exit 1

#!/usr/bin/env bash
# test_output.sh EXE SRCDIR — no output is lost silently (issue 16):
#  - every command whose standard output cannot be written (/dev/full) exits 2
#    with "error writing standard output: REASON";
#  - a reader closing the pipe early (`| head`) is not an error;
#  - output files (draw, matrix -o, subdivide, report --plot) are written whole
#    or not at all: a failed write (a file size limit) leaves no file, no
#    temporary file, and an existing target as it was.
set -u
exe=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
. "$(dirname "$0")/../ss_expect.sh"

m=$src/data/meshes
st=$src/data/stencils
full="error writing standard output: No space left on device"
# CMD > /dev/full (a program, for timeout in expect)
to_full=(bash -c '"$@" >/dev/full' _)
# CMD with a 1 KiB file size limit; SIGXFSZ ignored, so write() fails with EFBIG
limited=(bash -c 'trap "" XFSZ; ulimit -f 1; exec "$@"' _)
# no file but the ones named survives in $tmp/out
only() {
  checks=$((checks + 1))
  local have want
  have=$(cd "$tmp/out" && ls -A | sort | tr '\n' ' ')
  want=$(printf '%s\n' "$@" | sed '/^$/d' | sort | tr '\n' ' ')
  [ "$have" = "$want" ] || fail "files left in out/: '$have', want '$want'"
}
same() { # FILE TEXT: the file still holds TEXT
  checks=$((checks + 1))
  [ "$(cat "$1" 2>/dev/null)" = "$2" ] || fail "$1 changed: $(head -c 80 "$1" 2>/dev/null)"
}

# ---- standard output on a full device ----
expect 2 "$full" "${to_full[@]}" "$exe" --help
expect 2 "$full" "${to_full[@]}" "$exe" --version
expect 2 "$full" "${to_full[@]}" "$exe" analyze --help
# the message names the command, as every message does
expect 2 "^subspectra analyze: $full" "${to_full[@]}" "$exe" analyze --help
expect 2 "^subspectra: $full" "${to_full[@]}" "$exe" --version
for f in text json tsv; do
  expect 2 "$full" "${to_full[@]}" "$exe" analyze --scheme mlca --vertex octahedron --format $f
  expect_in 2 "$full" "octahedron" "${to_full[@]}" "$exe" analyze --scheme mlca --vertex - --format $f
done
expect 2 "$full" "${to_full[@]}" "$exe" matrix --scheme mlca --edge 4
expect 2 "$full" "${to_full[@]}" "$exe" enumerate links --vertices 4..9
expect_in 2 "$full" "$("$exe" enumerate links --vertices 4..9 2>/dev/null)" "${to_full[@]}" "$exe" enumerate canonical
expect_in 2 "$full" "octahedron" "${to_full[@]}" "$exe" enumerate canonical --format json
expect 2 "$full" "${to_full[@]}" "$exe" enumerate random --vertices 8 --samples 3 --seed 1
expect 2 "$full" "${to_full[@]}" "$exe" enumerate mesh "$m/cube-6tets.mesh"
expect 2 "$full" "${to_full[@]}" "$exe" check "$st/mlca.ini" --vertices 4 --edges 3
expect 2 "$full" "${to_full[@]}" "$exe" subdivide --scheme mlca "$m/cube-creased.mesh" -o "$tmp/s.mesh"
expect 2 "$full" "${to_full[@]}" "$exe" subdivide --scheme mlca --format json "$m/cube-creased.mesh" -o "$tmp/s.mesh"
expect 2 "$full" "${to_full[@]}" "$exe" sweep --scheme mlca --vertices 4..5 --db "$tmp/s.db" --format json
for f in md csv tex json; do
  expect 2 "$full" "${to_full[@]}" "$exe" report --db "$tmp/s.db" --format $f
done
# the table writer's failure is reported once, by the reason
checks=$((checks + 1))
n=$("$exe" report --db "$tmp/s.db" 2>&1 >/dev/full | wc -l)
[ "$n" -eq 1 ] || fail "report > /dev/full: $n lines of messages, want 1"
# standard output closed (>&-): lost output is an error; a command that writes
# none to it (draw) is not disturbed, and its file does not take fd 1's place
closed=(bash -c '"$@" >&-' _)
expect 2 "error writing standard output: Bad file descriptor" "${closed[@]}" "$exe" --help
expect 0 "wrote .*c.mtx" "${closed[@]}" bash -c '"$1" matrix --scheme mlca --edge 4 -o "$2" && echo "wrote $2" >&2' _ "$exe" "$tmp/c.mtx"
expect 0 "^%%MatrixMarket" head -1 "$tmp/c.mtx"
# a failing check still exits 2 when its report is lost; an error is not hidden
expect 2 "$full" "${to_full[@]}" "$exe" check "$st/mlca.ini" --edges 8
expect 2 "unknown scheme" "${to_full[@]}" "$exe" analyze --scheme nope --vertex octahedron

# ---- a reader that stops early is not an error ----
# SIGPIPE at its default (a shell's choice): the kernel ends the writer silently
checks=$((checks + 1))
err=$( { "$exe" enumerate links --vertices 4..11 | head -1 >/dev/null; } 2>&1)
[ -z "$err" ] || fail "| head: a message: $err"
# SIGPIPE ignored: write() fails with EPIPE; no message, the command's status
checks=$((checks + 1))
(trap '' PIPE; "$exe" enumerate links --vertices 4..11 2>"$tmp/epipe" | head -1 >/dev/null; exit "${PIPESTATUS[0]}")
rc=$?
[ "$rc" -eq 0 ] && [ ! -s "$tmp/epipe" ] || fail "EPIPE: status $rc, message '$(cat "$tmp/epipe")'"

# ---- output files: whole or not at all ----
mkdir "$tmp/out"
o=$tmp/out
for f in png svg vtk; do
  expect 2 "big.$f: cannot write: File too large" "${limited[@]}" "$exe" draw --scheme mlca --vertex octahedron -o "$o/big.$f"
done
expect 2 "big.mtx: cannot write: File too large" "${limited[@]}" "$exe" matrix --scheme mlca --vertex octahedron -o "$o/big.mtx"
expect 2 "big.mesh: cannot write: File too large" "${limited[@]}" "$exe" subdivide --scheme mlca --levels 2 "$m/cube-creased.mesh" -o "$o/big.mesh"
# (SQLite cannot read the store under a size limit: the plot goes to a full
# device through a symbolic link, which is written in place)
ln -s /dev/full "$tmp/full.png"
ln -s /dev/full "$tmp/full.svg"
expect 2 "full.png: cannot write: No space left on device" "$exe" report --db "$tmp/s.db" --plot "$tmp/full.png"
expect 2 "full.svg: cannot write: No space left on device" "$exe" draw --scheme mlca --vertex octahedron -o "$tmp/full.svg"
only
# an existing file is left as it was
for f in png svg vtk mtx mesh; do echo "old $f" >"$o/keep.$f"; done
for f in png svg vtk; do
  expect 2 "File too large" "${limited[@]}" "$exe" draw --scheme mlca --vertex octahedron -o "$o/keep.$f"
done
expect 2 "File too large" "${limited[@]}" "$exe" matrix --scheme mlca --vertex octahedron -o "$o/keep.mtx"
expect 2 "File too large" "${limited[@]}" "$exe" subdivide --scheme mlca --levels 2 "$m/cube-creased.mesh" -o "$o/keep.mesh"
# a format the mesh cannot take: the old file stays too
echo "old obj" >"$o/keep.obj"
expect 2 "surfaces only|does not take|cannot" "$exe" subdivide --scheme mlca "$m/cube-creased.mesh" -o "$o/keep.obj"
for f in png svg vtk mtx mesh obj; do same "$o/keep.$f" "old $f"; done
only keep.png keep.svg keep.vtk keep.mtx keep.mesh keep.obj
# reproduce: the first table cannot be written; no table, no temporary file
mkdir "$tmp/rep"
expect 2 "mlca-vertices-k4-8.md: cannot write: File too large" "${limited[@]}" "$exe" reproduce --reference "$src/data/reference" --out "$tmp/rep"
expect 0 "^$" find "$tmp/rep" -type f
# a missing folder: a message naming the file, nothing made
expect 2 "$o/no/such/x.png" "$exe" draw --scheme mlca --vertex octahedron -o "$o/no/such/x.png"
expect 2 "$o/no/such/x.mtx" "$exe" matrix --scheme mlca --edge 4 -o "$o/no/such/x.mtx"

# success: the file replaced whole, its mode kept; a new file gets 0666 less
# the umask; a symbolic link is followed, not replaced; a device written in place
expect 0 "wrote" "$exe" draw --scheme mlca --vertex octahedron -o "$o/keep.png"
expect 0 "PNG" head -c 4 "$o/keep.png"
chmod 600 "$o/keep.mtx"
expect 0 "" "$exe" matrix --scheme mlca --edge 4 -o "$o/keep.mtx"
expect 0 "^600$" stat -c %a "$o/keep.mtx"
expect 0 "MatrixMarket" head -1 "$o/keep.mtx"
expect 0 "^644$" bash -c 'umask 022; "$1" matrix --scheme mlca --edge 4 -o "$2" && stat -c %a "$2"' _ "$exe" "$o/new.mtx"
mkdir "$o/real"
ln -s real/target.mtx "$o/link.mtx"
expect 0 "" "$exe" matrix --scheme mlca --edge 4 -o "$o/link.mtx"
expect 0 "MatrixMarket" bash -c '[ -L "$1" ] && head -1 "$2"' _ "$o/link.mtx" "$o/real/target.mtx"
expect 0 "" "$exe" matrix --scheme mlca --edge 4 -o /dev/null
expect 0 "MatrixMarket" bash -c '"$1" matrix --scheme mlca --edge 4 -o /dev/stdout | head -1' _ "$exe"
only keep.png keep.svg keep.vtk keep.mtx keep.mesh keep.obj new.mtx link.mtx real

expect_done test_output

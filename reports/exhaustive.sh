#!/usr/bin/env bash
# reports/exhaustive.sh — the exhaustive tables of vertex one-rings (issue 20):
# every link with 4..K vertices under MLCA, tet/oct and box-spline solids,
# certified, counted per k by the condition that fails, and the links that do
# not pass.  Not part of ./run (k = 12 takes well over an hour of CPU, most of
# it MLCA at about 0.5 s a link); see
# reports/README.md, "Exhaustive tables".
#
#   reports/exhaustive.sh [--max-k K] [--db FILE] [--out DIR] [--jobs N]
#                         [--schemes "mlca tetoct boxspline"]
#                         [--psi-depth N | --psi-depth S=N,S=N...]
#                         [--no-sweep]
#
# It runs, for each scheme S,
#   subspectra sweep --scheme S --vertices 4..K --certify --db FILE --jobs N
# (resumable: an interrupted run, rerun with the same arguments, computes only
# what is missing; with --psi-depth N > 0 the schemes whose characteristic map
# is judged on psi (mlca and ccsolid on its polynomial pieces, tetoct and
# boxspline at the ring's regular vertices by tangent masks) are swept with
# --psi-depth N too, and the tables count their verdicts about psi;
# --psi-depth S=N,... sets the depth per scheme, 0 or absent: the net only),
# then
# writes from the store
#   DIR/exhaustive-vertices-k4-K.md        subspectra report --table exhaustive
#   DIR/exhaustive-vertices-k4-K.csv       the same counts, --format csv
#   DIR/data/exhaustive-vertices-k4-K-not-passing.csv.xz
#                                          --table not-passing --format csv, xz
# (exhaustive-vertices-psi-k4-K.* when some scheme is judged on psi, so the
# tables about psi sit beside those about the control net),
# restricted to the schemes and k asked for (a store may hold more).  A
# (scheme, k) whose links the store does not hold all of (a sweep that was
# interrupted) is left out of all three files and named in the Markdown's
# preamble with how many are stored.  --no-sweep writes the files from the
# store as it is, without sweeping.  The tables hold counts only, no timing:
# the same store gives the same bytes.
#
# The program: $SUBSPECTRA, else build/cli/subspectra beside this script's
# folder, else subspectra on PATH.  Exit status: 0 written, 1 a sweep ended
# with an error other than failing verdicts, 2 bad usage.
set -euo pipefail

usage() {
  sed -n '2,/^set -euo/p' "$0" | sed -e '$d' -e 's/^# \{0,1\}//'
}

kmax=12 db=exhaustive.db out=reports jobs=1 schemes="mlca tetoct boxspline" sweep=1 psi=0
declare -A psi_at=()
while (($#)); do
  case "$1" in
  --max-k) kmax=${2:?--max-k needs a value}; shift 2 ;;
  --db) db=${2:?--db needs a file}; shift 2 ;;
  --out) out=${2:?--out needs a folder}; shift 2 ;;
  --jobs) jobs=${2:?--jobs needs a number}; shift 2 ;;
  --schemes) schemes=${2:?--schemes needs names}; shift 2 ;;
  --psi-depth) psi=${2:?--psi-depth needs a value}; shift 2 ;;
  --no-sweep) sweep=0; shift ;;
  -h | --help) usage; exit 0 ;;
  *) echo "exhaustive.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
if ! [[ $kmax =~ ^[0-9]+$ ]] || ((kmax < 4 || kmax > 20)); then
  echo "exhaustive.sh: --max-k '$kmax' is not an integer 4..20" >&2
  exit 2
fi
# the schemes whose characteristic map the sweep judges on psi
psi_judged() { case "$1" in mlca | ccsolid | tetoct | boxspline) return 0 ;; *) return 1 ;; esac; }
if [[ $psi == *=* ]]; then
  IFS=, read -ra pairs <<< "$psi"
  for p in "${pairs[@]}"; do
    s=${p%%=*} d=${p#*=}
    if [[ $p != *=* ]] || ! psi_judged "$s" || ! [[ $d =~ ^[0-9]+$ ]] || ((d > 8)); then
      echo "exhaustive.sh: --psi-depth: '$p' is not SCHEME=N with SCHEME one of mlca ccsolid tetoct boxspline and N 0..8" >&2
      exit 2
    fi
    psi_at[$s]=$d
  done
  psi=0
elif ! [[ $psi =~ ^[0-9]+$ ]] || ((psi > 8)); then
  echo "exhaustive.sh: --psi-depth '$psi' is not an integer 0..8 or SCHEME=N,..." >&2
  exit 2
fi
# the sweep's --psi-depth for scheme $1
psi_of() {
  if [[ -n ${psi_at[$1]:-} ]]; then echo "${psi_at[$1]}"
  elif psi_judged "$1"; then echo "$psi"
  else echo 0; fi
}
for s in $schemes; do
  case "$s" in
  mlca | tetoct | boxspline | boxspline-avg | ccsolid) ;;
  *) echo "exhaustive.sh: --schemes: '$s' is not a solid scheme with vertex one-rings" >&2
     exit 2 ;;
  esac
done
source "$(dirname "$0")/find-program.sh" exhaustive.sh
command -v xz > /dev/null || { echo "exhaustive.sh: xz is needed" >&2; exit 2; }
mkdir -p "$out/data"

for s in $schemes; do
  ((sweep)) || break
  d=$(psi_of "$s")
  echo "exhaustive.sh: sweep --scheme $s --vertices 4..$kmax --certify --psi-depth $d (store $db)" >&2
  rc=0
  "$exe" sweep --scheme "$s" --vertices "4..$kmax" --certify --psi-depth "$d" --jobs "$jobs" --db "$db" || rc=$?
  # 1 = some case fails or is undecided: the tables are about exactly that
  if ((rc != 0 && rc != 1)); then
    echo "exhaustive.sh: the $s sweep ended with status $rc; rerun to resume" >&2
    exit 1
  fi
done

[[ -f $db ]] || { echo "exhaustive.sh: no store $db" >&2; exit 2; }
names=$(printf "'%s'," $schemes)
where="kind IN ('vertex','edge-point') AND k BETWEEN 4 AND $kmax AND scheme IN (${names%,})"
where+=" AND identity LIKE '% certified%'"
# one identity per scheme: with psi-depth=N where the sweep asked for it
for s in $schemes; do
  d=$(psi_of "$s")
  if ((d > 0)); then where+=" AND (scheme != '$s' OR identity LIKE '% psi-depth=$d')"
  else where+=" AND (scheme != '$s' OR identity NOT LIKE '% psi-depth=%')"; fi
done
# the (scheme, k) the store holds only in part: compared with the number of
# links with k vertices
declare -A want
while read -r k n; do want[$k]=$n; done < <("$exe" enumerate links --vertices "4..$kmax" --count 2> /dev/null | grep -v '^#')
missing=() partial=""
for s in $schemes; do
  declare -A have=()
  while IFS=, read -r _ sc k links _; do
    [[ $sc == "$s" ]] && have[$k]=$((${have[$k]:-0} + links))
  done < <("$exe" report --db "$db" --where "$where AND scheme = '$s'" --table exhaustive --format csv 2> /dev/null | tr -d '\r' | tail -n +2)
  for ((k = 4; k <= kmax; k++)); do
    if [[ ${have[$k]:-0} != "${want[$k]}" ]]; then
      missing+=("$s k = $k (${have[$k]:-0} of ${want[$k]} links stored)")
      partial+=" AND NOT (scheme = '$s' AND k = $k)"
    fi
  done
  unset have
done
where+=$partial
# the tables about psi are named apart from those about the control net
any_psi=0
for s in $schemes; do (($(psi_of "$s") > 0)) && any_psi=1; done
if ((any_psi)); then stem=$out/exhaustive-vertices-psi-k4-$kmax
else stem=$out/exhaustive-vertices-k4-$kmax; fi
{
  echo "# Exhaustive tables: every vertex one-ring with 4..$kmax vertices"
  echo
  echo "Written by \`reports/exhaustive.sh --max-k $kmax\` (the sweeps"
  on=""
  for s in $schemes; do
    d=$(psi_of "$s")
    ((d > 0)) && on+="\`$s\` with \`--psi-depth $d\`, "
  done
  echo "\`subspectra sweep --scheme S --vertices 4..$kmax --certify\` for S in"
  echo "$(printf '`%s` ' $schemes)into one store, then \`subspectra report --table exhaustive\`);"
  if [[ -n $on ]]; then
    echo "judged on the characteristic map psi, not only its control net: ${on%, } (their"
    echo "columns \"on psi\" count the verdicts proven about psi);"
  fi
  echo "not part of \`./run\`.  How long it takes, and what \"certified\" covers:"
  echo "reports/README.md, \"Exhaustive tables\".  The links that do not pass:"
  echo "\`data/$(basename "$stem")-not-passing.csv.xz\` (\`xz -dc\` it)."
  echo
  if ((${#missing[@]})); then
    echo "**Not complete:** the store holds only part of the links of these rows,"
    echo "which are left out below and in the CSV files; rerun the same command"
    echo "(the sweeps resume) to complete them:"
    echo
    printf -- '- %s\n' "${missing[@]}"
    echo
  fi
  "$exe" report --db "$db" --where "$where" --table exhaustive
} > "$stem.md.tmp"
"$exe" report --db "$db" --where "$where" --table exhaustive --format csv > "$stem.csv.tmp"
"$exe" report --db "$db" --where "$where" --table not-passing --format csv |
  xz -9 -T1 > "$out/data/$(basename "$stem")-not-passing.csv.xz.tmp"
mv "$stem.md.tmp" "$stem.md"
mv "$stem.csv.tmp" "$stem.csv"
mv "$out/data/$(basename "$stem")-not-passing.csv.xz.tmp" \
  "$out/data/$(basename "$stem")-not-passing.csv.xz"
echo "exhaustive.sh: wrote $stem.md, $stem.csv and $out/data/$(basename "$stem")-not-passing.csv.xz" >&2

#!/bin/sh
# Runs every benchmark program of the float and the double build, alternating
# the two builds program by program so that both see the same machine state,
# and prints each figure with the double/float ratio.
# Benchmark programs print lines "BENCH <name> <value> <unit>" (other lines
# pass through); for ns/call a ratio above 1 means double is slower.
# usage: run-bench.sh FLOAT_BENCH_DIR DOUBLE_BENCH_DIR
fdir=$1; ddir=$2
tmp=$(mktemp -d "${TMPDIR:-/tmp}/materia-bench.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT INT TERM
status=0
for f in "$fdir"/*; do
    [ -x "$f" ] || continue
    name=$(basename "$f")
    d="$ddir/$name"
    echo "== $name"
    "$f" >"$tmp/float" || status=1
    grep -v '^BENCH ' "$tmp/float"
    if [ -x "$d" ]; then "$d" >"$tmp/double" || status=1; else : >"$tmp/double"; fi
    awk 'FNR == NR { if ($1 == "BENCH") { d[$2] = $3 } next }
         $1 == "BENCH" {
             if ($2 in d && $3 > 0) printf "%-48s float %12.4g  double %12.4g %-8s double/float %.3f\n", $2, $3, d[$2], $4, d[$2] / $3
             else printf "%-48s float %12.4g %s\n", $2, $3, $4
         }' "$tmp/double" "$tmp/float"
done
exit $status

#!/bin/sh
# What each check costs: the suite run whole, then each check alone (its
# stages only: --check NAME), on the same configurations and options, one
# thread, materia's plugin in this process (--impl-lib).
#
#   sh bench/check-share.sh BUILD [OPTIONS...]   e.g. --compare none --quick --power 0.01
#
# One line per run: queries answered (from --report) and CPU seconds (user
# + system). Checks share stages (chi2, mean wi, pdf integral and furnace
# MC=quad count the same samples in the same cells), so the lines do not
# add up: a check's line is what running it alone costs. docs/BENCHMARKS.md
# has the results.
set -u
build=$1
shift
tmp=$(mktemp -d "${TMPDIR:-/tmp}/materia-share.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT INT TERM
conf="$build/bin/materia-conformance"
plugin="$build/plugins/materia_plugin.so"
for check in all identity chi2 "mean wi" "pdf integral" "chi2 materia" "furnace MC=quad" furnace "agree f" \
    "agree pdf" "agree delta" reciprocity helmholtz extremes; do
    if [ "$check" = all ]; then
        /usr/bin/time -f '%U %S' -o "$tmp/time" "$conf" --impl-lib "$plugin" "$@" --threads 1 \
            --report "$tmp/report.json" >/dev/null 2>&1
    else
        /usr/bin/time -f '%U %S' -o "$tmp/time" "$conf" --impl-lib "$plugin" "$@" --check "$check" --threads 1 \
            --report "$tmp/report.json" >/dev/null 2>&1
    fi
    q=$(sed -n 's/^ *"queries": \([0-9]*\),.*/\1/p' "$tmp/report.json")
    read -r u s < "$tmp/time"
    printf '%-16s %12s queries %9.2f cpu-s\n' "$check" "$q" "$(echo "$u + $s" | bc)"
done

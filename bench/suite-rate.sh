#!/bin/sh
# Queries per second of the suite through each path, side by side in one
# run: materia's plugin in this process (--impl-lib), the same plugin as
# text (--impl 'materia-plugin-host ...'), and materia-query (--impl), on
# the same configurations with the same options, one thread.
#
#   sh bench/suite-rate.sh BUILD [OPTIONS...]     e.g. --only '^plastic default$'
#
# One line per path: queries answered (from --report), CPU seconds of the
# suite and its children (user + system), wall seconds, and queries per
# CPU second (what a free core gives; wall time on a shared machine says
# little). docs/BENCHMARKS.md has the results.
set -u
build=$1
shift
tmp=$(mktemp -d "${TMPDIR:-/tmp}/materia-rate.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT INT TERM
conf="$build/bin/materia-conformance"
plugin="$build/plugins/materia_plugin.so"
for path in plugin host query; do
    case $path in
    plugin) set -- --impl-lib "$plugin" "$@" ;;
    host) set -- --impl "$build/bin/materia-plugin-host $plugin" "$@" ;;
    query) set -- --impl "$build/bin/materia-query" "$@" ;;
    esac
    /usr/bin/time -f '%U %S %e' -o "$tmp/time" "$conf" "$@" --threads 1 --report "$tmp/report.json" >/dev/null 2>&1
    shift 2 # the path's two words: the options remain
    q=$(sed -n 's/^ *"queries": \([0-9]*\),.*/\1/p' "$tmp/report.json")
    read -r u s e < "$tmp/time"
    printf '%-7s %12s queries %9.2f cpu-s %9.2f wall-s %12.0f queries/cpu-s\n' "$path" "$q" \
        "$(echo "$u + $s" | bc)" "$e" "$(echo "$q / ($u + $s)" | bc -l)"
done

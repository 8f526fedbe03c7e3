#!/bin/sh
# Queries per second of the suite through each path, side by side in one
# run: materia's plugin in this process (--impl-lib), the same plugin as
# text through materia-plugin-host (--impl), and materia-query (--impl),
# the text paths both with batched lines (protocol 3, their default) and
# one query a line (--plain), on the same configurations with the same
# options, one thread.
#
#   sh bench/suite-rate.sh BUILD [OPTIONS...]     e.g. --only '^plastic default$'
#
# (--samples 40000 unless the options set the samples: every path answers
# the same queries.)
# BEFORE=DIR (a build directory of an older materia, e.g. a worktree of an
# earlier commit built with make) adds its host and materia-query paths,
# run by its own materia-conformance, to the same run: before and after
# side by side.
#
# One line per path: queries answered (from --report), CPU seconds of the
# implementation's process (materia-query or the host; 0 in process), of
# the suite's, and of both, wall seconds, and queries per CPU second of
# both (what a free core gives; wall time on a shared machine says little).
# docs/BENCHMARKS.md has the results.
set -u
build=$1
shift
# the same samples on every path (the suite's default is 100000 for an
# implementation that speaks batched lines, 40000 one query a line)
case " $* " in *" --samples "*|*" --quick "*|*" --power "*) ;; *) set -- --samples 40000 "$@" ;; esac
tmp=$(mktemp -d "${TMPDIR:-/tmp}/materia-rate.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT INT TERM
paths="plugin host-plain host query-plain query"
[ -n "${BEFORE:-}" ] && paths="before-host before-query $paths"
printf '%-13s %10s %9s %9s %9s %9s %12s %12s\n' path queries impl-cpu suite-cpu cpu-s wall-s queries/cpu-s queries/wall-s
for path in $paths; do
    b=$build extra=
    case $path in before-*) b=$BEFORE ;; esac
    case $path in *-plain) extra=--plain ;; esac
    # the implementation's own CPU time, from a time(1) around it
    child="/usr/bin/time -a -f '%U %S' -o $tmp/child"
    rm -f "$tmp/child"
    case $path in
    plugin) impl="--impl-lib $b/plugins/materia_plugin.so" ;;
    *host*) impl="--impl \"$child $b/bin/materia-plugin-host $b/plugins/materia_plugin.so\"" ;;
    *query*) impl="--impl \"$child $b/bin/materia-query\"" ;;
    esac
    eval "/usr/bin/time -f '%U %S %e' -o \"$tmp/time\" \"$b/bin/materia-conformance\" $impl $extra \"\$@\" \
          --threads 1 --report \"$tmp/report.json\"" >/dev/null 2>&1
    q=$(sed -n 's/^ *"queries": \([0-9]*\),.*/\1/p' "$tmp/report.json")
    read -r u s e < "$tmp/time"
    # every child's (the probe's and one per configuration), summed
    implcpu=0
    [ -f "$tmp/child" ] && implcpu=$(awk '{ t += $1 + $2 } END { printf "%.2f", t }' "$tmp/child")
    total=$(echo "$u + $s" | bc)
    printf '%-13s %10s %9.2f %9.2f %9.2f %9.2f %12.0f %12.0f\n' "$path" "$q" "$implcpu" "$(echo "$total - $implcpu" | bc)" \
        "$total" "$e" "$(echo "$q / $total" | bc -l)" "$(echo "$q / $e" | bc -l)"
done

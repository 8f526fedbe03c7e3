#!/bin/sh
# The suite's power, measured: how often a plugin with one smooth error of
# relative size EPS planted (tests/plugin_planted.c: warp, pdf, f; none is
# materia itself) is failed by the physics checks alone, over seeded runs.
#
#   sh bench/power.sh BUILD PATH CONFIG KINDS EPSS SEEDS [OPTIONS...]
#
# BUILD   the build directory (build/float)
# PATH    lib: the plugin in this process (--impl-lib);
#         text: the same plugin through materia-plugin-host (--impl)
# CONFIG  a configuration's exact name (matte Kd=1)
# KINDS   "warp pdf f none"; EPSS "0.005 0.01 0.02"; SEEDS the number of seeds
# OPTIONS the suite's, e.g. --power 0.01 --quick, or --samples 40000
#
# One line per (kind, eps): "PATH CONFIG KIND EPS caught/runs seconds", the
# seconds the runs took (wall). docs/TRADEOFF.md, "Power", has the results.
set -u
build=$1 path=$2 config=$3 kinds=$4 epss=$5 seeds=$6
shift 6
conf="$build/bin/materia-conformance"
plugin="$build/tests/plugin_planted.so"
for kind in $kinds; do
    for eps in $epss; do
        caught=0 runs=0
        t0=$(date +%s.%N)
        s=1
        while [ "$s" -le "$seeds" ]; do
            if [ "$path" = lib ]; then
                out=$("$conf" --impl-lib "$plugin" --impl-arg "$kind $eps" --compare none --only "^$config\$" \
                      --seed "$s" --threads 2 "$@" 2>&1)
            else
                out=$("$conf" --impl "$build/bin/materia-plugin-host $plugin --arg '$kind $eps'" --compare none \
                      --only "^$config\$" --seed "$s" --threads 2 "$@" 2>&1)
            fi
            runs=$((runs + 1))
            if printf '%s\n' "$out" | grep -q '^FAIL '; then caught=$((caught + 1)); fi
            if printf '%s\n' "$out" | grep -q 'protocol  *physics'; then echo "protocol failure: $out" >&2; fi
            s=$((s + 1))
        done
        t1=$(date +%s.%N)
        printf '%s\t%s\t%s\t%s\t%d/%d\t%.1f\n' "$path" "$config" "$kind" "$eps" "$caught" "$runs" \
            "$(echo "$t1 - $t0" | bc)"
    done
done

#!/bin/sh
# Runs each libFuzzer target for SECONDS seconds (make fuzz): its seed corpus
# fuzz/corpus/TARGET read, new inputs written to BUILD/work/TARGET, crashes,
# leaks and timeouts to BUILD/artifacts/TARGET-*, the log to
# BUILD/logs/TARGET.log. One line per target with libFuzzer's final figures;
# exit status 1 when any target found a crash, leak, timeout or out-of-memory
# input.
# usage: run-fuzz.sh BUILD SECONDS TARGET...
build=$1; secs=$2; shift 2
# cpu: the user + system CPU seconds of this shell's finished children. The
# times builtin must run in this shell, not in a command substitution (whose
# subshell has no children), so it writes to a file.
child_cpu() {
    times >"$build/logs/.times"
    cpu=$(awk 'NR == 2 { n = 0; for (i = 1; i <= 2; ++i) { split($i, a, /[ms]/); n += a[1] * 60 + a[2] }
                         printf "%.2f", n }' "$build/logs/.times")
}
found=0
mkdir -p "$build/artifacts" "$build/logs" || exit 1
for t in "$@"; do
    bin=$build/libfuzzer/fuzz-$t
    mkdir -p "$build/work/$t" || exit 1
    dict=
    [ -f "fuzz/dict/$t.dict" ] && dict=-dict=fuzz/dict/$t.dict
    log=$build/logs/$t.log
    # shellcheck disable=SC2086
    "$bin" -max_total_time="$secs" -print_final_stats=1 -timeout=60 -rss_limit_mb=3072 \
        -malloc_limit_mb=2600 $dict -artifact_prefix="$build/artifacts/$t-" \
        ${FUZZ_FLAGS:-} "$build/work/$t" "fuzz/corpus/$t" >"$log" 2>&1
    rc=$?
    execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
    # under -fork=N the parent prints no final stats, only "#RUNS: cov: ..."
    # lines (its cov: is its own measure, not edges) and its corpus size
    # without the bytes
    [ -n "$execs" ] || execs=$(sed -n 's/^#\([0-9]*\): cov:.*/\1/p' "$log" | tail -1)
    cov=$(grep -o 'cov: [0-9]* ft: [0-9]*' "$log" | tail -1)
    corp=$(grep -oE 'corp: [0-9]+(/[0-9]+[a-zA-Z]*)?' "$log" | tail -1)
    # crash-, leak-, timeout- and oom- inputs are findings; slow-unit- ones
    # (over 10 s, e.g. rho of a glossy material under the sanitizers) are not
    arts=$(ls "$build/artifacts" | grep -v "^$t-slow-unit-" | grep -c "^$t-")
    slow=$(ls "$build/artifacts" | grep -c "^$t-slow-unit-")
    echo "fuzz $t: ${execs:-?} executions in ${secs} s, $cov, $corp, exit $rc, $arts findings, $slow slow inputs"
    # libFuzzer's timeout is wall time: on a busy machine (or at nice 19) a
    # slow but finite input can reach it. Each timeout input is run once more
    # alone, up to 10 minutes, with its wall and CPU time reported, so that a
    # hang (CPU time near the wall time, the limit reached again) can be told
    # from a starved run (seconds of CPU); it stays a finding either way.
    for a in "$build/artifacts/$t"-timeout-*; do
        [ -f "$a" ] || continue
        t0=$(date +%s)
        child_cpu
        c0=$cpu
        if "$bin" -timeout=600 -rss_limit_mb=3072 "$a" >/dev/null 2>&1; then
            how="ran alone in"
        else
            how="failed or hung again alone, after"
        fi
        child_cpu
        echo "fuzz $t: $(basename "$a") $how $(($(date +%s) - t0)) s of wall time," \
            "$(echo "$c0 $cpu" | awk '{ printf "%.1f", $2 - $1 }') s of CPU time"
    done
    if [ "$rc" -ne 0 ] || [ "$arts" -ne 0 ]; then found=1; fi
done
[ "$found" -eq 0 ]

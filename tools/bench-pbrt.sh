#!/bin/sh
# Times materia-render and pbrt-v2 side by side on the reference scenes, with
# the pbrt-v2 baseline's own script (../shared/baselines/pbrt-v2/side_by_side.sh:
# both renderers back to back on each scene, the order swapped on every repeat,
# medians of the repeats, wall clock and user+sys CPU, the ratio
# materia/pbrt-v2 per scene, the worst and the geometric mean).
#
# usage: bench-pbrt.sh BUILD [GROUP ...]
#   GROUP  material (the 11 path-traced material scenes), subsurface (subsurface,
#          kdsubsurface), real (real-killeroo-simple, real-bunny-measured,
#          real-metal-teapot, real-ss-envmap); default: all three
# environment:
#   BENCH_SPP      samples per pixel for both renderers (default: each scene's own)
#   BENCH_REPEAT   runs of each renderer per scene (default 3)
#   BENCH_THREADS  threads for both (default 2)
#   MATERIA_SHARED the shared data folder (default ../shared or ../../shared)
#
# Without the baseline it says so and exits 0: the side-by-side figures are
# then simply absent, never replaced by recorded times. A scene materia
# cannot render yet (checked with a 1-sample render first) is named and left
# out of its group.
build=${1:?usage: bench-pbrt.sh BUILD [GROUP ...]}
shift
root=$(pwd)
materia=$root/$build/bin/materia-render
shared=${MATERIA_SHARED:-}
if [ -z "$shared" ]; then
    for c in ../shared ../../shared; do
        if [ -d "$c" ]; then shared=$c; break; fi
    done
fi
sbs=${shared:+$shared/baselines/pbrt-v2/side_by_side.sh}
if [ -z "$shared" ] || [ ! -x "$sbs" ] || [ ! -x "$shared/baselines/pbrt-v2/pbrt" ]; then
    echo "bench-pbrt: no pbrt-v2 baseline (${sbs:-../shared/baselines/pbrt-v2/side_by_side.sh} and the pbrt binary beside it):"
    echo "bench-pbrt: no side-by-side figures; materia is not compared with any recorded time"
    exit 0
fi
scenes=$(cd "$shared/reference/scenes" && pwd)
[ -x "$materia" ] || { echo "bench-pbrt: $materia not built" >&2; exit 1; }
[ $# -gt 0 ] || set -- material subsurface real

tmp=$(mktemp -d "${TMPDIR:-/tmp}/materia-bench-pbrt.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT INT TERM
status=0
for group in "$@"; do
    case $group in
        material) list="matte plastic glass mirror metal shinymetal substrate translucent uber mix measured" ;;
        subsurface) list="subsurface kdsubsurface" ;;
        real) list="real-killeroo-simple real-bunny-measured real-metal-teapot real-ss-envmap" ;;
        *) echo "bench-pbrt: unknown group '$group' (material, subsurface, real)" >&2; exit 2 ;;
    esac
    ok=
    for s in $list; do
        if "$materia" "$scenes/$s.pbrt" --spp 1 --threads 1 --quiet -o "$tmp/probe.pfm" >"$tmp/probe.log" 2>&1; then
            ok="$ok $s"
        else
            echo "bench-pbrt: materia does not render $s yet, left out: $(head -n 1 "$tmp/probe.log")"
        fi
    done
    [ -n "$ok" ] || continue
    echo "== side by side with pbrt-v2: $group scenes, spp ${BENCH_SPP:-of each scene}, ${BENCH_REPEAT:-3} repeat(s), ${BENCH_THREADS:-2} threads, load average $(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null)"
    # shellcheck disable=SC2086
    MATERIA=$materia THREADS=${BENCH_THREADS:-2} bash "$sbs" ${BENCH_SPP:+--spp "$BENCH_SPP"} \
        --repeat "${BENCH_REPEAT:-3}" --out "$tmp/$group" $ok 2>"$tmp/$group.log" || status=1
    grep -i 'failed\|error' "$tmp/$group.log" | grep -v 'ioctl' || :
done
exit $status

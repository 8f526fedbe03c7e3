#!/bin/sh
# Times materia-render and pbrt-v2 side by side on the reference scenes, with
# the pbrt-v2 baseline's own script (../shared/baselines/pbrt-v2/side_by_side.sh:
# both renderers back to back on each scene, the order swapped on every repeat,
# medians of the repeats, wall clock and user+sys CPU, the ratio
# materia/pbrt-v2 per scene, the worst and the geometric mean).
#
# usage: bench-pbrt.sh BUILD [GROUP ...]
#   GROUP  material (the scenes of the material kinds without a BSSRDF, as
#          materia-query --list materials gives them), subsurface (those with
#          one: subsurface, kdsubsurface), real (real-killeroo-simple, real-bunny-measured,
#          real-metal-teapot, real-ss-envmap), bvh (pbrt-v2's BVH build of the
#          bunny beside materia's, from bench/embree's harness); default: all
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
[ $# -gt 0 ] || set -- material subsurface real bvh

tmp=$(mktemp -d "${TMPDIR:-/tmp}/materia-bench-pbrt.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT INT TERM
status=0
# bvh_build: pbrt-v2's BVH build (its refinement of the mesh into triangles
# and BVHAccel's construction) for the bunny, as the difference of the CPU time
# of two whole processes that parse the same mesh inside ObjectBegin/ObjectEnd,
# one of them instancing it (pbrt-v2 builds an instance's BVH at
# ObjectInstance), 1x1 pixel, 1 sample, one thread; medians of BENCH_REPEAT
# (at least 5) alternating pairs. materia's build of the same mesh is timed by
# bench/embree's harness (mt_geometry_commit, one thread) in the same minutes.
bvh_build() {
    if [ ! -x /usr/bin/time ]; then echo "bench-pbrt: bvh: /usr/bin/time is needed for CPU times; skipped"; return 0; fi
    for inst in 0 1; do
        {
            echo 'Film "image" "integer xresolution" [1] "integer yresolution" [1]'
            echo 'Sampler "lowdiscrepancy" "integer pixelsamples" [1]'
            echo 'SurfaceIntegrator "directlighting" Camera "perspective" WorldBegin'
            echo "ObjectBegin \"mesh\" Include \"$scenes/geometry/bunny.pbrt\" ObjectEnd"
            [ $inst = 0 ] || echo 'ObjectInstance "mesh"'
            echo 'WorldEnd'
        } > "$tmp/bvh$inst.pbrt"
    done
    n=${BENCH_REPEAT:-5}; [ "$n" -ge 5 ] || n=5
    echo "== BVH build of the bunny (69,451 triangles), one thread, CPU time, medians of $n, load average $(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null)"
    : > "$tmp/bvh.times"
    i=0
    while [ $i -lt $n ]; do
        for inst in 1 0; do
            /usr/bin/time -f "$inst %U %S" -o "$tmp/bvh.t" "$shared/baselines/pbrt-v2/pbrt" --ncores 1 --quiet \
                --outfile "$tmp/bvh.exr" "$tmp/bvh$inst.pbrt" >/dev/null 2>&1 || { echo "bench-pbrt: pbrt-v2 failed on $tmp/bvh$inst.pbrt"; return 1; }
            tail -n 1 "$tmp/bvh.t" >> "$tmp/bvh.times"
        done
        i=$((i + 1))
    done
    pbrt_ms=$(awk '{ t[$1, ++n[$1]] = $2 + $3 }
        function med(k,   i, j, x, a, m) { m = n[k]; for (i = 1; i <= m; i++) a[i] = t[k, i]
            for (i = 2; i <= m; i++) { x = a[i]; for (j = i - 1; j >= 1 && a[j] > x; j--) a[j + 1] = a[j]; a[j + 1] = x }
            return (m % 2) ? a[(m + 1) / 2] : (a[m / 2] + a[m / 2 + 1]) / 2 }
        END { printf "%.0f", 1000 * (med(1) - med(0)) }' "$tmp/bvh.times")
    echo "pbrt-v2 BVHAccel (refine + build): $pbrt_ms ms (CPU time with the instance minus without, 10 ms resolution)"
    harness=$root/$build/bench/bvh-embree
    if [ -x "$harness" ]; then
        mat_ms=$(MT_BENCH_PASSES=$n "$harness" --build bunny.pbrt | awk '$1 == "BENCH" && $2 ~ /build.materia/ { print $3 }')
        echo "materia mt_geometry_commit: $mat_ms ms; materia/pbrt-v2: $(awk -v a="$mat_ms" -v b="$pbrt_ms" 'BEGIN { if (b > 0) printf "%.2f", a / b; else print "-" }')"
    else
        echo "materia: no bench/embree harness in $build (built by make bench where Embree is found); its build time is bench/bvh's bvh.build"
    fi
}

for group in "$@"; do
    [ "$group" != bvh ] || { bvh_build || status=1; continue; }
    case $group in
        material) list=$("$root/$build/bin/materia-query" --list materials | awk '$2 != "bssrdf" { print $1 }') ;;
        subsurface) list=$("$root/$build/bin/materia-query" --list materials | awk '$2 == "bssrdf" { print $1 }') ;;
        real) list="real-killeroo-simple real-bunny-measured real-metal-teapot real-ss-envmap" ;;
        *) echo "bench-pbrt: unknown group '$group' (material, subsurface, real, bvh)" >&2; exit 2 ;;
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

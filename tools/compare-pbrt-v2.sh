#!/bin/sh
# compare-pbrt-v2.sh -- render scenes with pbrt-v2 and with materia and compare them with
# pbrt-v2's noise metric (docs/RENDERER.md, "Comparing images").
#
# usage: tools/compare-pbrt-v2.sh [--spp N] [--mode pbrt-v2|corrected] [--out DIR] [SCENE ...]
#
# Run from the project's root after `make`. SCENE is a .pbrt file (default: every scene of
# tools/pbrt-v2-mixed/). Each scene is rendered by ../shared/baselines/pbrt-v2/pbrt twice,
# with its own lowdiscrepancy sampler and with halton, and by build/float/bin/materia-render
# (MATERIA= names another binary) at the same sample count (the scene's, or --spp). Printed
# per scene: twice the noise between the two pbrt-v2 renders (the bound) and materia's
# against the lowdiscrepancy render -- block mean, 99th percentile and maximum of
# |a - b| / (b + 0.01) over 4x4 blocks, and the luminance ratio -- and PASS when materia's
# three figures are within the bound. Images and logs go to DIR (default: a new directory
# under ${TMPDIR:-/tmp}). Relative file names in a scene resolve against a copy of its folder
# in which `textures` is ../shared/reference/scenes/textures.
#
# The pbrt-v2 baseline is optional for materia: without it this tool says so and exits 1.
# Exit status: 0 when every scene passed, 1 when one failed or could not run, 2 on a wrong
# command line.
set -u

usage() {
    echo "usage: $0 [--spp N] [--mode pbrt-v2|corrected] [--out DIR] [SCENE ...]" >&2
    exit 2
}

spp= mode=pbrt-v2 out=
while [ $# -gt 0 ]; do
    case "$1" in
    --spp) [ $# -ge 2 ] || usage; spp=$2; shift 2 ;;
    --mode) [ $# -ge 2 ] || usage; mode=$2; shift 2 ;;
    --out) [ $# -ge 2 ] || usage; out=$2; shift 2 ;;
    --help|-h) sed -n '2,22p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    -*) usage ;;
    *) break ;;
    esac
done
case "$spp" in ''|*[!0-9]*) [ -z "$spp" ] || usage ;; esac
case "$mode" in pbrt-v2|corrected) ;; *) usage ;; esac

root=$(pwd)
pbrt=$root/../shared/baselines/pbrt-v2/pbrt
textures=$root/../shared/reference/scenes/textures
materia=${MATERIA:-$root/build/float/bin/materia-render}
imgdiff=$(dirname "$materia")/materia-imgdiff
if [ ! -x "$pbrt" ]; then
    echo "$0: no pbrt-v2 baseline at $pbrt: nothing compared" >&2
    exit 1
fi
for b in "$materia" "$imgdiff"; do
    [ -x "$b" ] || { echo "$0: $b not found (run make first)" >&2; exit 1; }
done
[ $# -gt 0 ] || set -- "$root"/tools/pbrt-v2-mixed/*.pbrt
if [ -z "$out" ]; then
    out=$(mktemp -d "${TMPDIR:-/tmp}/compare-pbrt-v2.XXXXXX") || exit 1
fi
mkdir -p "$out" || exit 1
case "$out" in /*) ;; *) out=$root/$out ;; esac

# The figures of `materia-imgdiff A B` as "mean p99 max lum".
figures() {
    "$imgdiff" "$1" "$2" | awk '/^noise-mean/{m=$2} /^noise-p99/{p=$2} /^noise-max/{x=$2}
        /^lum-ratio/{l=$2} END{print m, p, x, l}'
}

status=0
printf '%-24s %5s  %-26s  %-34s %s\n' scene spp "bound (mean p99 max)" "materia (mean p99 max lum-ratio)" ""
for scene in "$@"; do
    name=$(basename "$scene" .pbrt)
    src=$(cd "$(dirname "$scene")" && pwd) || { status=1; continue; }
    work=$out/$name
    rm -rf "$work" && mkdir -p "$work" || { status=1; continue; }
    # the scene's folder, with textures from ../shared and the Film's own file name removed
    # (pbrt-v2 ignores --outfile when the Film names a file)
    for f in "$src"/*; do
        [ "$(basename "$f")" = textures ] || ln -s "$f" "$work/$(basename "$f")"
    done
    [ -d "$textures" ] && ln -sfn "$textures" "$work/textures"
    rm -f "$work/$name.pbrt"
    if ! grep -q '^Film' "$scene"; then
        echo "$name: the Film statement must start a line" >&2
        status=1
        continue
    fi
    sed -e '/^Film/s/"string filename" "[^"]*"//' "$scene" > "$work/$name.pbrt"
    n=${spp:-$(sed -n 's/.*"integer pixelsamples" \[\([0-9]*\)\].*/\1/p' "$scene" | head -n 1)}
    [ -n "$n" ] || { echo "$name: no \"integer pixelsamples\" [N] in its Sampler" >&2; status=1; continue; }
    sed -e "s/\"integer pixelsamples\" \[[0-9]*\]/\"integer pixelsamples\" [$n]/" "$work/$name.pbrt" > "$work/ld.pbrt"
    sed -e 's/"lowdiscrepancy"/"halton"/' "$work/ld.pbrt" > "$work/halton.pbrt"
    ok=1
    (cd "$work" && "$pbrt" --ncores 2 --quiet --outfile "$work/pbrt-ld.exr" ld.pbrt &&
        "$pbrt" --ncores 2 --quiet --outfile "$work/pbrt-halton.exr" halton.pbrt) \
        > "$work/pbrt.log" 2>&1 || ok=0
    [ -f "$work/pbrt-ld.exr" ] && [ -f "$work/pbrt-halton.exr" ] || ok=0
    (cd "$work" && "$materia" ld.pbrt --spp "$n" --mode "$mode" --quiet -o "$work/materia.exr") \
        > "$work/materia.log" 2>&1 || ok=0
    if [ $ok = 0 ]; then
        echo "$name: a render failed (logs in $work)" >&2
        status=1
        continue
    fi
    read -r bm bp bx bl <<EOF
$(figures "$work/pbrt-halton.exr" "$work/pbrt-ld.exr")
EOF
    read -r mm mp mx ml <<EOF
$(figures "$work/materia.exr" "$work/pbrt-ld.exr")
EOF
    verdict=$(echo "$bm $bp $bx $mm $mp $mx" |
        awk '{print ($4 <= 2 * $1 && $5 <= 2 * $2 && $6 <= 2 * $3) ? "PASS" : "FAIL"}')
    [ "$verdict" = PASS ] || status=1
    printf '%-24s %5s  %-26s  %-34s %s\n' "$name" "$n" \
        "$(echo "$bm $bp $bx" | awk '{printf "%.4f %.4f %.4f", 2 * $1, 2 * $2, 2 * $3}')" \
        "$(echo "$mm $mp $mx $ml" | awk '{printf "%.4f %.4f %.4f %.4f", $1, $2, $3, $4}')" "$verdict"
done
echo "images and logs: $out"
exit $status

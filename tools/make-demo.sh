#!/bin/sh
# make demo: every material of golden/scenes/ rendered at 192 x 144 and laid
# out with its name in one contact sheet, demo.png.
# usage: tools/make-demo.sh BUILD_DIR [SPP] [OUT]
set -eu
build=${1:-build/float}
spp=${2:-128}
out=${3:-demo.png}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/materia-demo.XXXXXX")
trap 'rm -rf "$tmp"' EXIT INT TERM
for scene in golden/scenes/*.pbrt; do
    sed -e 's/"integer xresolution" \[64\]/"integer xresolution" [192]/' \
        -e 's/"integer yresolution" \[48\]/"integer yresolution" [144]/' "$scene" > "$tmp/$(basename "$scene")"
done
cp golden/scenes/*-points.txt "$tmp/"   # the dipole scenes' irradiance points
"$build/bin/materia-merl" --out "$tmp/plastic.merl" - < golden/plastic-merl.txt > /dev/null
set --
for scene in "$tmp"/*.pbrt; do
    name=$(basename "$scene" .pbrt)
    printf 'demo: %s\n' "$name"
    # the scenes' warnings (materia's own sampler) are expected; an error is shown
    # the dipole scenes' lights take 64 and 16 samples: 16 pixel samples do
    n=$spp
    if grep -q '"dipolesubsurface"' "$scene"; then n=16; fi
    if ! "$build/bin/materia-render" "$scene" --spp "$n" --quiet -o "$tmp/$name.exr" 2> "$tmp/log"; then
        cat "$tmp/log" >&2
        exit 1
    fi
    set -- "$@" "$name=$tmp/$name.exr"
done
"$build/bin/materia-sheet" -o "$out" --columns 4 "$@"
echo "demo: wrote $out"

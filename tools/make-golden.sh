#!/bin/sh
# Renders the golden images of golden/scenes/ at a high sample count: for each
# scene NAME, golden/NAME.exr (the mean) and golden/NAME.var.exr (the
# variance of each pixel's mean), in pbrt-v2 mode with seed 1. The measured
# scene reads a MERL table of the plastic in golden/plastic-merl.txt, made
# by materia-merl first (33 MB: made in a temporary directory, not kept).
# usage: tools/make-golden.sh BUILD_DIR [SPP]    (make golden)
set -eu
build=${1:-build/float}
spp=${2:-4096}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/materia-golden.XXXXXX")
trap 'rm -rf "$tmp"' EXIT INT TERM
cp golden/scenes/*.pbrt "$tmp/"
"$build/bin/materia-merl" --out "$tmp/plastic.merl" - < golden/plastic-merl.txt
for scene in golden/scenes/*.pbrt; do
    name=$(basename "$scene" .pbrt)
    echo "golden: $name at $spp samples per pixel"
    "$build/bin/materia-render" "$tmp/$name.pbrt" --spp "$spp" --seed 1 --mode pbrt-v2 --quiet \
        -o "golden/$name.exr" --variance "golden/$name.var.exr"
done

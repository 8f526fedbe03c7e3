#!/bin/sh
# Renders the golden images of golden/scenes/ at a high sample count: for each
# scene NAME, golden/NAME.exr (the mean) and golden/NAME.var.exr (the
# variance of each pixel's mean), in pbrt-v2 mode with seed 1. The dipole
# scenes (subsurface, kdsubsurface) get their irradiance points deposited
# with seed 1 into golden/scenes/NAME-points.txt, then RENDERS (32) renders
# with seeds 1..32 at DIPOLE_SPP (16) samples per pixel, the test's own
# count, with golden/NAME.stats.txt (tools/materia-golden.c). The measured
# scene reads a MERL table of the plastic in golden/plastic-merl.txt, made
# by materia-merl first (33 MB: made in a temporary directory, not kept).
# usage: tools/make-golden.sh BUILD_DIR [SPP]    (make golden)
# GOLDEN_ONLY="NAME ...": those scenes alone (a new material's, say).
set -eu
build=${1:-build/float}
spp=${2:-4096}
renders=${RENDERS:-32}
dipole_spp=${DIPOLE_SPP:-16}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/materia-golden.XXXXXX")
trap 'rm -rf "$tmp"' EXIT INT TERM
cp golden/scenes/*.pbrt "$tmp/"
"$build/bin/materia-merl" --out "$tmp/plastic.merl" - < golden/plastic-merl.txt
for scene in golden/scenes/*.pbrt; do
    name=$(basename "$scene" .pbrt)
    case " ${GOLDEN_ONLY:-$name} " in *" $name "*) ;; *) continue ;; esac
    if grep -q '"dipolesubsurface"' "$scene"; then
        # the dipole scenes: the points deposited once into the scene's points
        # file, then RENDERS renders with seeds 1..RENDERS at the test's sample
        # count, their mean, its variance and each render's statistics
        # (tests/test_golden.c)
        echo "golden: $name, its points (seed 1), $renders renders at $dipole_spp samples per pixel"
        grep -v '"string pointsfile"' "$scene" > "$tmp/$name-deposit.pbrt"
        "$build/bin/materia-golden" "$tmp/$name-deposit.pbrt" --points "golden/scenes/$name-points.txt" --seed 1 2> /dev/null
        cp "golden/scenes/$name-points.txt" "$tmp/"
        "$build/bin/materia-golden" "$tmp/$name.pbrt" --renders "$renders" --spp "$dipole_spp" --mode pbrt-v2 \
            -o "golden/$name.exr" --variance "golden/$name.var.exr" --stats "golden/$name.stats.txt" 2> /dev/null
        continue
    fi
    echo "golden: $name at $spp samples per pixel"
    "$build/bin/materia-render" "$tmp/$name.pbrt" --spp "$spp" --seed 1 --mode pbrt-v2 --quiet \
        -o "golden/$name.exr" --variance "golden/$name.var.exr"
done

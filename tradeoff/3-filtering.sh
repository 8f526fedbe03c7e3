#!/bin/sh
# Measurement 3: texture filtering. $MT_TRADEOFF/filtering
# (tradeoff/filtering.c) measures, over a sweep of footprint sizes and
# anisotropies, each filter's error against a brute-force box average over
# the sample's footprint and its time per lookup, for the image map (none,
# trilinear, EWA with maxanisotropy 1 to 64, supersampling) and the
# checkerboard (aamode none, closedform, supersampling). This script sums
# them up ($OUT/3-filtering-overall.csv, 3-filtering-series.csv), plots them
# (3-filtering-time, -aniso, -size: .gp, and .png with gnuplot) and writes the
# report section $OUT/3-filtering.md. Environment: MT_TRADEOFF, OUT, QUICK,
# GNUPLOT, TRADEOFF_DIR (tools/run-tradeoff.sh).
set -u
: "${MT_TRADEOFF:?}" "${OUT:?}"
QUICK=${QUICK:-0}
GNUPLOT=${GNUPLOT:-}
TRADEOFF_DIR=${TRADEOFF_DIR:-$(cd "$(dirname "$0")" && pwd)}
PROG=$MT_TRADEOFF/filtering
[ -x "$PROG" ] || { echo "3-filtering: $PROG not found (build it first)" >&2; exit 1; }
mkdir -p "$OUT"
START=$(date +%s)
if [ "${FILTERING_REPORT_ONLY:-0}" = 1 ] && [ -s "$OUT/3-filtering-checker.csv" ]; then :
elif [ "$QUICK" = 1 ]; then "$PROG" --out "$OUT" --quick; else "$PROG" --out "$OUT"; fi ||
    { echo "3-filtering: $PROG failed" >&2; exit 1; }
# FILTERING_REPORT_ONLY=1: the plots and section again from an earlier run's CSV
if [ "${FILTERING_REPORT_ONLY:-0}" = 1 ] && [ -s "$OUT/3-filtering.seconds" ]; then
    ELAPSED=$(cat "$OUT/3-filtering.seconds")
else
    ELAPSED=$(($(date +%s) - START))
    echo "$ELAPSED" > "$OUT/3-filtering.seconds"
fi
I=$OUT/3-filtering-imagemap.csv
C=$OUT/3-filtering-checker.csv
. "$TRADEOFF_DIR/lib.sh"
status=0

# Per texture, mode and parameter over the whole sweep: the RMS of the
# groups' RMS errors (cell and wide truth) and the mean time per lookup.
OV=$OUT/3-filtering-overall.csv
overall() {
    awk -F, -v tex="$2" 'NR > 1 { k = $1 "," $2; if (!(k in n)) o[++m] = k; n[k]++; e[k] += $5 * $5; w[k] += $6 * $6; t[k] += $7 }
        END { for (i = 1; i <= m; i++) { k = o[i]; printf "%s,%s,%.4g,%.4g,%.1f\n", tex, k, sqrt(e[k] / n[k]), sqrt(w[k] / n[k]), t[k] / n[k] } }' "$1"
}
{
    echo "texture,mode,param,rms_err,rms_err_wide,ns_per_lookup"
    overall "$I" imagemap
    overall "$C" checker
} > "$OV.tmp" && mv "$OV.tmp" "$OV"

# The error of a mode against one sweep variable, the RMS over the other:
# one run of rows per texture, mode, parameter and axis (size: column 3 of
# the data, aniso: column 4).
SE=$OUT/3-filtering-series.csv
series() {
    awk -F, -v tex="$2" -v m="$3" -v p="$4" -v axis="$5" -v xc="$6" 'NR > 1 && $1 == m && $2 == p {
        x = $xc; if (!(x in n)) o[++k] = x; n[x]++; e[x] += $5 * $5 }
        END { for (i = 1; i <= k; i++) printf "%s,%s,%s,%s,%s,%.5g\n", tex, m, p, axis, o[i], sqrt(e[o[i]] / n[o[i]]) }' "$1"
}
{
    echo "texture,mode,param,axis,x,rms_err"
    for a in "size 3" "aniso 4"; do
        set -- $a; axis=$1; xc=$2
        for m in "none 0" "trilinear 0" "trilinear-corrected 0" "ewa 8" "ewa 64" "supersampled 4"; do
            set -- $m; series "$I" imagemap "$1" "$2" "$axis" "$xc"
        done
        for m in "none 0" "closedform 0" "supersampled 4" "supersampled 16"; do
            set -- $m; series "$C" checker "$1" "$2" "$axis" "$xc"
        done
    done
} > "$SE.tmp" && mv "$SE.tmp" "$SE"

# gnuplot selections: pick TEX MODE [PARAM] is true on the rows of one
# texture and mode (and parameter)
pick() {
    if [ $# = 3 ]; then echo "strcol(1) eq '$1' && strcol(2) eq '$2' && column(3) == $3"
    else echo "strcol(1) eq '$1' && strcol(2) eq '$2'"; fi
}
HEAD="set grid; set logscale xy; set format y '10^{%L}'; set format x '%g'; set key below horizontal maxcols 2 width -4; set bmargin 9
set multiplot layout 1,2"
TERM="size 1100,560 enhanced font 'DejaVu Sans,10'"

# error against time: one point per mode, EWA and supersampling as lines
# (EWA labelled with maxanisotropy, the checkerboard's supersampling with
# its number of lookups)
cmds="$HEAD
set xlabel 'time per lookup (ns, one thread)'; set ylabel 'RMS error (texture values span [0, 1])'
set title 'Image map (512^2): error against cost, whole sweep'
plot '3-filtering-overall.csv' using ($(pick imagemap ewa) ? column(6) : NaN):(column(4)) with linespoints pt 7 lw 1.5 title 'EWA, maxanisotropy 1..64', \\
     '' using ($(pick imagemap ewa) ? column(6) : NaN):(column(4)):(sprintf('%d', column(3))) with labels offset 1.2,0.6 font ',8' notitle, \\
     '' using ($(pick imagemap supersampled) ? column(6) : NaN):(column(4)) with linespoints pt 5 lw 1.5 dt 2 title 'supersampled, 4..64 bilinear lookups', \\
     '' using ($(pick imagemap none) ? column(6) : NaN):(column(4)) with points pt 9 ps 1.6 title 'none (bilinear, level 0)', \\
     '' using ($(pick imagemap trilinear) ? column(6) : NaN):(column(4)) with points pt 11 ps 1.6 title 'trilinear (pbrt-v2 width)', \\
     '' using ($(pick imagemap trilinear-corrected) ? column(6) : NaN):(column(4)) with points pt 13 ps 1.6 title 'trilinear (corrected width)'
set title 'Checkerboard: error against cost, whole sweep'
plot '3-filtering-overall.csv' using ($(pick checker supersampled) ? column(6) : NaN):(column(4)) with linespoints pt 5 lw 1.5 dt 2 title 'supersampled, 4..256 lookups', \\
     '' using ($(pick checker supersampled) ? column(6) : NaN):(column(4)):(sprintf('%d', column(3) * column(3))) with labels offset 1.2,0.6 font ',8' notitle, \\
     '' using ($(pick checker none) ? column(6) : NaN):(column(4)) with points pt 9 ps 1.6 title 'aamode none', \\
     '' using ($(pick checker closedform) ? column(6) : NaN):(column(4)) with points pt 11 ps 1.6 title 'aamode closedform'
unset multiplot"
PLOTMD=$(tr_plot 3-filtering-time "Texture filters: error against time per lookup" \
    "3-filtering-overall.csv" "$cmds" "$TERM") || status=1

# error against the footprint's size and against its anisotropy: the same
# two panels, one plot per axis
for axis in aniso size; do
    # one curve: its selection, then its look and title
    curve() { echo "'3-filtering-series.csv' using ($(pick "$1" "$2" "$3") && strcol(4) eq '$axis' ? column(5) : NaN):(column(6)) with linespoints $4"; }
    if [ $axis = size ]; then
        ixl="footprint: major semi-axis |d0| (texels)"; cxl="footprint: major semi-axis |d0| (checks)"
        it="Image map: error against footprint size (all anisotropies)"
        ct="Checkerboard: error against footprint size (all anisotropies)"
        title="Texture filters: error against footprint size"
    else
        ixl="anisotropy |d0| / |d1|"; cxl=$ixl
        it="Image map: error against anisotropy (all sizes)"
        ct="Checkerboard: error against anisotropy (all sizes)"
        title="Texture filters: error against anisotropy"
    fi
    cmds="$HEAD
set ylabel 'RMS error (texture values span [0, 1])'
set xlabel '$ixl'; set title '$it'
plot $(curve imagemap none 0 "pt 9 lw 1.5 title 'none'"), \\
     $(curve imagemap trilinear 0 "pt 11 lw 1.5 title 'trilinear (pbrt-v2 width)'"), \\
     $(curve imagemap trilinear-corrected 0 "pt 13 lw 1.5 title 'trilinear (corrected width)'"), \\
     $(curve imagemap ewa 8 "pt 7 lw 1.5 title 'EWA, maxanisotropy 8 (default)'"), \\
     $(curve imagemap ewa 64 "pt 6 lw 1.5 title 'EWA, maxanisotropy 64'"), \\
     $(curve imagemap supersampled 4 "pt 5 lw 1.5 dt 2 title 'supersampled 4x4'")
set xlabel '$cxl'; set title '$ct'
plot $(curve checker none 0 "pt 9 lw 1.5 title 'aamode none'"), \\
     $(curve checker closedform 0 "pt 11 lw 1.5 title 'aamode closedform'"), \\
     $(curve checker supersampled 4 "pt 5 lw 1.5 dt 2 title 'supersampled 4x4'"), \\
     $(curve checker supersampled 16 "pt 4 lw 1.5 dt 2 title 'supersampled 16x16'")
unset multiplot"
    md=$(tr_plot "3-filtering-$axis" "$title" "3-filtering-series.csv" "$cmds" "$TERM") || status=1
    PLOTMD="$PLOTMD

$md"
done

MD=$OUT/3-filtering.md
{
    echo "## 3. Texture filtering"
    echo
    echo "What each texture filter costs and how close it comes to the ideal answer. A lookup gets a"
    echo "point and its screen-space differentials d0, d1, which pbrt-v2 scales to the spacing of the"
    echo "samples; the ideal answer is the average of the texture over the sample's own cell, the"
    echo "parallelogram p + a d0 + b d1 with a, b in [-1/2, 1/2] (what many unfiltered samples average"
    echo "to under a box pixel filter), computed by brute force in double on a fine grid, independently"
    echo "of materia's filters (\`tradeoff/filtering.c\`). pbrt-v2's filters span more than the cell"
    echo "(trilinear a square of side 2 max|d|, closedform a box of +-max|d|, EWA an ellipse with the"
    echo "differentials as semi-axes): their error against the box over a, b in [-1, 1] is the column"
    echo "\"wide\" below and in the CSV files."
    echo
    echo "- **Image map**: a 512 x 512 periodic pattern of eight plane waves, 2 to 205 cycles across"
    echo "  the image (up to 0.4 cycles per texel), amplitudes falling as 1/sqrt(frequency), values in"
    echo "  [0, 1]; the continuous texture is the bilinear interpolant of its texels. Modes through the"
    echo "  public MIP-map API as pbrt-v2's \`imagemap\` uses it: no filtering (bilinear at level 0),"
    echo "  \`\"bool trilinear\" \"true\"\` (pbrt-v2's width 2 max|d|, and the corrected width max|d|),"
    echo "  EWA (the default) with \`\"float maxanisotropy\"\` 1 to 64, and supersampling by the caller:"
    echo "  S x S unfiltered lookups over the cell."
    echo "- **Checkerboard**: pbrt-v2's float \`checkerboard\` (tex1 1, tex2 0) through the public"
    echo "  texture API, \`\"string aamode\"\` \`none\` and \`closedform\` (pbrt-v2 has no supersampling"
    echo "  aamode), and S x S lookups with aamode none over the cell."
    if [ "$QUICK" = 1 ]; then
        echo "- Sweep (reduced): footprint sizes |d0| 0.5, 2, 8, 32 texels (0.03, 0.3, 1 checks), anisotropies"
        echo "  1, 4, 16, 64, 40 (30) random footprints each."
    else
        echo "- Sweep: footprint sizes |d0| 0.25 to 64 texels in powers of 2 (0.01 to 3 checks),"
        echo "  anisotropies |d0|/|d1| 1 to 64 in powers of 2, 200 (150) random footprints each, at random"
        echo "  points and orientations."
    fi
    echo "- Error: RMS of lookup - truth; time: ns per lookup on one thread (CPU time, median of 3 runs"
    echo "  of 8 passes)."
    echo
    printf '%s\n\n' "$PLOTMD"
    echo "Over the whole sweep (RMS of the groups' errors, mean time per lookup):"
    echo
    echo "| texture | mode | parameter | RMS error (cell) | RMS error (wide) | ns per lookup |"
    echo "| --- | --- | --- | --- | --- | --- |"
    awk -F, 'NR > 1 { printf "| %s | %s | %s | %s | %s | %s |\n", ($1 == "imagemap" ? "image map" : "checkerboard"), $2,
                      ($2 == "ewa" ? "maxanisotropy " $3 : ($2 == "supersampled" ? $3 "x" $3 : "-")), $4, $5, $6 }' "$OV"
    echo
    # conclusions from the data: the cheapest supersampling that beats EWA 8
    # and closedform, and the relative costs
    awk -F, '$1 == "imagemap" { if ($2 == "ewa" && $3 == 8) { ee = $4; te = $6 } if ($2 == "none") { en = $4; tn = $6 }
                               if ($2 == "trilinear") { et = $4; tt = $6 } if ($2 == "ewa" && $3 == 64) { e64 = $4; t64 = $6 }
                               if ($2 == "supersampled") { se[++ns] = $4; st[ns] = $6; sp[ns] = $3 } }
        $1 == "checker" { if ($2 == "closedform") { ec = $4; tc = $6 } if ($2 == "none") { ecn = $4; tcn = $6 }
                               if ($2 == "supersampled") { cse[++ncs] = $4; cst[ncs] = $6; csp[ncs] = $3 } }
        END {
            printf "Image map: EWA at the default maxanisotropy 8 has %.2g of the error of no filtering (%.3g against %.3g) at %.1fx its cost; ", ee / en, ee, en, te / tn
            printf "trilinear %.3g at %.1fx; maxanisotropy 64 gives %.3g at %.1fx. ", et, tt / tn, e64, t64 / tn
            b = 0; for (i = 1; i <= ns; i++) if (!b && se[i] <= ee) b = i
            if (b) printf "Supersampling needs %dx%d lookups (%.0f ns, %.1fx EWA'\''s time) to match EWA'\''s error.\n", sp[b], sp[b], st[b], st[b] / te
            else printf "No supersampling rate measured (up to %dx%d, %.0f ns) matches EWA'\''s error.\n", sp[ns], sp[ns], st[ns]
            printf "Checkerboard: closedform has %.2g of the error of aamode none (%.3g against %.3g) at %.1fx its cost; ", ec / ecn, ec, ecn, tc / tcn
            b = 0; for (i = 1; i <= ncs; i++) if (!b && cse[i] <= ec) b = i
            if (b) printf "supersampling needs %dx%d lookups (%.0f ns, %.0fx closedform'\''s time) to match it.\n", csp[b], csp[b], cst[b], cst[b] / tc
            else printf "no supersampling rate measured matches it.\n"
        }' "$OV"
    echo
    echo "Measured by \`$(if [ "$QUICK" = 1 ]; then echo "make tradeoff QUICK=1"; else echo "make tradeoff"; fi)\` (\`tradeoff/3-filtering.sh\`) in ${ELAPSED} s of wall time."
} > "$MD.tmp" && mv "$MD.tmp" "$MD"
echo "3-filtering: wrote $I, $C, $OV, $SE, $MD" >&2
exit $status

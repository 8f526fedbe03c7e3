#!/bin/sh
# Measurement 2: samples per pixel. For each scene, materia-render and (when
# ../shared is present) pbrt-v2 render it at a sweep of sample counts on the
# same machine, alternating which goes first, with the same thread count.
# Each image's error is measured by $MT_TRADEOFF/imgerr against a reference of
# two materia renders with seeds of their own, each at twice the largest count
# (four times it in all), whose own noise, estimated from their difference,
# is taken out of the squared error (tradeoff/imgerr.c, tests/support/sqerr.h).
# Writes $OUT/2-spp.csv (one row per scene, renderer and count),
# $OUT/2-spp-reference.csv (the references: their time and how their
# variance images compare with their measured variance), the fitted slopes and
# times-to-error in $OUT/2-spp-summary.csv, $OUT/2-spp-relerr.csv, the plots
# $OUT/2-spp-rmse.png, 2-spp-time.png, 2-spp-cpu.png, 2-spp-relerr.png (with their .gp
# files) and the report section $OUT/2-spp.md.
#
# Environment (tools/run-tradeoff.sh sets the first ones): MT_BIN,
# MT_TRADEOFF, OUT, QUICK, SHARED, GNUPLOT, TRADEOFF_DIR; and to change the
# sweep: SPP_SCENES (path-traced golden scenes, "none" for none), SPP_LIST,
# SPP_DIPOLE (the golden dipole scenes, "none" for none), SPP_DIPOLE_LIST,
# SPP_REAL (scenes of ../shared/reference/scenes, "none" for none),
# SPP_REAL_LIST, SPP_REAL_SCALE (resolution divisor of the real scenes), the
# samples of each of the two reference renders SPP_REF, SPP_DIPOLE_REF,
# SPP_REAL_REF (default: twice the sweep's largest count), SPP_THREADS (2);
# SPP_REPORT_ONLY=1 rewrites the summary, plots and section from an earlier
# run's $OUT/2-spp.csv and 2-spp-reference.csv without rendering.
set -u
: "${MT_BIN:?}" "${MT_TRADEOFF:?}" "${OUT:?}"
QUICK=${QUICK:-0}
SHARED=${SHARED:-}
GNUPLOT=${GNUPLOT:-}
TRADEOFF_DIR=${TRADEOFF_DIR:-$(cd "$(dirname "$0")" && pwd)}
. "$TRADEOFF_DIR/lib.sh"
ROOT=$(cd "$TRADEOFF_DIR/.." && pwd)
# Absolute paths: the renderers run from the scene's folder.
abspath() { case $1 in /*) echo "$1" ;; *) echo "$PWD/$1" ;; esac; }
MT_BIN=$(abspath "$MT_BIN"); MT_TRADEOFF=$(abspath "$MT_TRADEOFF"); OUT=$(abspath "$OUT")
RENDER=$MT_BIN/materia-render
IMGERR=$MT_TRADEOFF/imgerr
THREADS=${SPP_THREADS:-2}
GOLDEN=$ROOT/golden/scenes

if [ "$QUICK" = 1 ]; then
    SCENES=${SPP_SCENES:-"matte glass measured"}
    SPPS=${SPP_LIST:-"1 4 16 64"}
    DIPOLE=${SPP_DIPOLE:-none}
    REAL=${SPP_REAL:-none}
else
    # the material kinds without a BSSRDF (the path-traced golden scenes)
    SCENES=${SPP_SCENES:-$("$MT_BIN/materia-query" --list materials | awk '$2 != "bssrdf" { printf "%s%s", sep, $1; sep = " " }')}
    SPPS=${SPP_LIST:-"1 4 16 64 256 1024 4096"}
    # The dipole scenes' lights take 64 and 16 samples per camera sample: to
    # 64 spp they cost what the others do to 4096.
    DIPOLE=${SPP_DIPOLE:-$("$MT_BIN/materia-query" --list materials | awk '$2 == "bssrdf" { printf "%s%s", sep, $1; sep = " " }')}
    REAL=${SPP_REAL:-"real-killeroo-simple real-metal-teapot real-bunny-measured"}
fi
DIPOLESPPS=${SPP_DIPOLE_LIST:-"1 4 16 64"}
REALSPPS=${SPP_REAL_LIST:-"1 4 16 64 256"}
REALSCALE=${SPP_REAL_SCALE:-4}
largest() { echo "$1" | awk '{ print $NF }'; }
REFSPP=${SPP_REF:-$((2 * $(largest "$SPPS")))}
DIPOLEREF=${SPP_DIPOLE_REF:-$((2 * $(largest "$DIPOLESPPS")))}
REALREF=${SPP_REAL_REF:-$((2 * $(largest "$REALSPPS")))}
# Slopes are fitted to the points from this count on: below it the process's
# fixed cost (parse, BVH, writing) dominates the wall time.
SLOPEMIN=16; [ "$QUICK" = 1 ] && SLOPEMIN=4
[ "$SCENES" = none ] && SCENES=
[ "$DIPOLE" = none ] && DIPOLE=
[ "$REAL" = none ] && REAL=

for f in "$RENDER" "$IMGERR"; do
    [ -x "$f" ] || { echo "2-spp: $f not found (build it first)" >&2; exit 1; }
done
PBRT=
if [ -n "$SHARED" ] && [ -x "$SHARED/baselines/pbrt-v2/pbrt" ]; then
    PBRT=$SHARED/baselines/pbrt-v2/pbrt
fi
[ -n "$SHARED" ] && [ -d "$SHARED/reference/scenes" ] || REAL=
TIMECMD=; [ -x /usr/bin/time ] && TIMECMD=/usr/bin/time

mkdir -p "$OUT"
TMP=$(mktemp -d "${TMPDIR:-/tmp}/mt-spp.XXXXXX") || exit 1
trap 'rm -rf "$TMP"' EXIT INT TERM
CSV=$OUT/2-spp.csv
REFCSV=$OUT/2-spp-reference.csv

# prep SRC DIR SCALE: DIR gets a copy of scene SRC without the Film's
# "string filename" (pbrt-v2 ignores --outfile when the Film names a file)
# and with the resolution divided by SCALE, beside symlinks to every other
# entry of SRC's folder (both renderers resolve relative names against the
# scene file's folder). The sample count is given on each run.
prep() {
    mkdir -p "$2"
    for e in "$(dirname "$1")"/*; do
        [ "$e" = "$1" ] || ln -s "$e" "$2/" 2>/dev/null
    done
    awk -v scale="$3" '
        /^[ \t]*[A-Z][A-Za-z]*/ { infilm = ($1 == "Film") }
        infilm {
            gsub(/"string filename"[ \t]*(\[[ \t]*"[^"]*"[ \t]*\]|"[^"]*")/, "")
            while (match($0, /"integer [xy]resolution"[ \t]*\[[ \t]*[0-9]+/)) {
                s = substr($0, RSTART, RLENGTH); n = s; sub(/.*[^0-9]/, "", n)
                sub(/[0-9]+$/, "", s); gsub(/"integer /, "\"integer_", s)
                $0 = substr($0, 1, RSTART - 1) s int(n / scale) substr($0, RSTART + RLENGTH)
            }
            gsub(/"integer_/, "\"integer ")
        }
        { print }' "$1" > "$2/scene.pbrt"
}

# pbrt_scene DIR SPP: DIR/scene.pbrt with the Sampler's pixelsamples set
# (pbrt-v2 has no --spp), as DIR/scene-SPP.pbrt.
pbrt_scene() {
    sed 's/"integer pixelsamples"[ \t]*\[[ \t]*[0-9]*[ \t]*\]/"integer pixelsamples" ['"$2"']/' \
        "$1/scene.pbrt" > "$1/scene-$2.pbrt"
    grep -q "\"integer pixelsamples\" \\[$2\\]" "$1/scene-$2.pbrt" ||
        { echo "2-spp: $1/scene.pbrt states no pixelsamples" >&2; return 1; }
}

# timed LOG CMD...: runs CMD in the current folder, prints "wall cpu".
timed() {
    log=$1; shift
    t0=$(date +%s.%N)
    if [ -n "$TIMECMD" ]; then
        "$TIMECMD" -f '%U %S' -o "$log.time" "$@" > "$log" 2>&1; rc=$?
    else
        "$@" > "$log" 2>&1; rc=$?
    fi
    t1=$(date +%s.%N)
    cpu=NA
    [ -f "$log.time" ] && cpu=$(awk 'NF == 2 && $1 ~ /^[0-9.]+$/ { c = $1 + $2 } END { if (c != "") printf "%.3f", c; else print "NA" }' "$log.time")
    [ $rc = 0 ] || { echo "2-spp: failed ($rc): $*; see below" >&2; tail -5 "$log" >&2; return 1; }
    awk -v a="$t0" -v b="$t1" -v c="$cpu" 'BEGIN { printf "%.3f %s\n", b - a, c }'
}

# run SCENE DIR RENDERER SPP: one render, one CSV row (its error against the
# two references DIR/ref1.exr, DIR/ref2.exr).
run() {
    s=$1 d=$2 r=$3 n=$4
    img=$d/$r-$n.exr
    if [ "$r" = pbrt-v2 ]; then
        pbrt_scene "$d" "$n" || return 1
        tw=$(cd "$d" && timed "$d/$r-$n.log" "$PBRT" --ncores "$THREADS" --quiet --outfile "$img" "$d/scene-$n.pbrt") || return 1
    else
        tw=$(cd "$d" && timed "$d/$r-$n.log" "$RENDER" "$d/scene.pbrt" -o "$img" --spp "$n" --threads "$THREADS" --quiet) || return 1
    fi
    e=$("$IMGERR" "$img" "$d/ref1.exr" "$d/ref2.exr") || return 1
    echo "$s $r $n $tw $e" | awk '{ $1 = $1; gsub(/ /, ","); print }' >> "$CSV.tmp"
    rm -f "$img"
    echo "  $s $r spp $n: wall/cpu s $tw, rmse relmse p50 p90 p99 noise rmse_raw ref_share $e" >&2
}

# sweep SCENE SRC SCALE REFSPP SPPS...
sweep() {
    s=$1 src=$2 scale=$3 rs=$4; shift 4
    d=$TMP/$s
    prep "$src" "$d" "$scale"
    # The golden measured scene reads a MERL table of a plastic, made here as
    # tools/make-golden.sh makes it (33 MB, not kept).
    if grep -q '"plastic.merl"' "$d/scene.pbrt" && [ -f "$ROOT/golden/plastic-merl.txt" ]; then
        rm -f "$d/plastic.merl"
        "$MT_BIN/materia-merl" --out "$d/plastic.merl" - < "$ROOT/golden/plastic-merl.txt" ||
            { echo "2-spp: materia-merl failed" >&2; return 1; }
    fi
    # Two references with seeds of their own (the sweep's materia renders use
    # seed 0): their mean is the reference, their difference measures its
    # noise. Their variance images are kept only to compare them with it.
    echo "2-spp: $s: two references at $rs spp each (materia, seeds 1 and 2)" >&2
    rw=0
    for k in 1 2; do
        t=$(cd "$d" && timed "$d/ref$k.log" "$RENDER" "$d/scene.pbrt" -o "$d/ref$k.exr" --variance "$d/var$k.exr" \
            --spp "$rs" --seed "$k" --threads "$THREADS" --quiet) ||
            { echo "2-spp: reference render of $s failed" >&2; return 1; }
        rw=$(echo "$rw $t" | awk '{ printf "%.3f", $1 + $2 }')
    done
    v=$("$IMGERR" --variance-check "$d/ref1.exr" "$d/var1.exr" "$d/ref2.exr" "$d/var2.exr") || return 1
    echo "$s $rs $rw $v" | awk '{ $1 = $1; gsub(/ /, ","); print }' >> "$REFCSV.tmp"
    k=0
    for n in "$@"; do
        # Alternate which renderer goes first, so that neither always meets
        # the machine in the same state.
        if [ -z "$PBRT" ]; then order=materia
        elif [ $((k % 2)) = 0 ]; then order="pbrt-v2 materia"
        else order="materia pbrt-v2"; fi
        for r in $order; do run "$s" "$d" "$r" "$n" || return 1; done
        k=$((k + 1))
    done
    rm -rf "$d"
}

START=$(date +%s)
if [ "${SPP_REPORT_ONLY:-0}" = 1 ] && [ -s "$CSV" ] && [ -s "$REFCSV" ]; then
    # Only the summary, plots and section again, from the CSV of an earlier
    # run (with the same sweep settings); its duration is kept beside it.
    ELAPSED=$(cat "$OUT/2-spp.seconds" 2>/dev/null || echo "?")
else
    LOADAVG() { cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo unknown; }
    LOAD0=$(LOADAVG)
    printf 'scene,renderer,spp,wall_s,cpu_s,rmse,relmse,rel_p50,rel_p90,rel_p99,noise_mean,rmse_raw,ref_share\n' > "$CSV.tmp"
    printf 'scene,ref_spp_each,wall_s_both,variance_measured,variance_claimed,claimed_over_measured\n' > "$REFCSV.tmp"
    for s in $SCENES $DIPOLE; do
        [ -f "$GOLDEN/$s.pbrt" ] || { echo "2-spp: no golden scene $s" >&2; exit 1; }
    done
    for s in $SCENES; do
        # shellcheck disable=SC2086
        sweep "$s" "$GOLDEN/$s.pbrt" 1 "$REFSPP" $SPPS || exit 1
    done
    for s in $DIPOLE; do
        # shellcheck disable=SC2086
        sweep "$s" "$GOLDEN/$s.pbrt" 1 "$DIPOLEREF" $DIPOLESPPS || exit 1
    done
    for s in $REAL; do
        # shellcheck disable=SC2086
        sweep "$s" "$SHARED/reference/scenes/$s.pbrt" "$REALSCALE" "$REALREF" $REALSPPS || exit 1
    done
    mv "$CSV.tmp" "$CSV"
    mv "$REFCSV.tmp" "$REFCSV"
    ELAPSED=$(($(date +%s) - START))
    echo "$ELAPSED" > "$OUT/2-spp.seconds"
    echo "$LOAD0 at the start, $(LOADAVG) at the end" > "$OUT/2-spp.load"
fi
# Rows grouped by scene (in the sweep's order), then renderer, then count:
# each curve is one run of rows, as the plots and the summary read them.
awk -F, 'NR == 1 { next } { if (!($1 in o)) o[$1] = ++k; print o[$1] "," $0 }' "$CSV" |
    sort -t, -k1,1n -k3,3 -k4,4n | cut -d, -f2- > "$TMP/rows"
{ head -1 "$CSV"; cat "$TMP/rows"; } > "$CSV.tmp" && mv "$CSV.tmp" "$CSV"
# Per scene and renderer: the least-squares slope of log RMSE against log spp
# and against log wall time; the error pbrt-v2 reaches at 1024 spp (or at its
# largest spp when the sweep stops below) and the wall time each renderer
# needs to reach it, interpolated log-log between the two measured points that
# bracket it (extrapolated along the last segment when materia's sweep does
# not reach it, flagged), and the ratio materia/pbrt-v2.
SUM=$OUT/2-spp-summary.csv
awk -F, '
NR == 1 { next }
{
    k = $1 SUBSEP $2; n[k]++; i = n[k]
    S[k, i] = $3; T[k, i] = $4; C[k, i] = ($5 == "NA" ? 0 : $5); E[k, i] = $6
    if (!($1 in seen)) { seen[$1] = 1; order[++ns] = $1 }
    have[$2] = 1
}
function slope(k, usetime,   i, x, y, sx, sy, sxx, sxy, m) {
    m = 0; sx = sy = sxx = sxy = 0
    for (i = 1; i <= n[k]; i++) {
        if (E[k, i] <= 0 || S[k, i] < smin) continue
        x = log(usetime ? T[k, i] : S[k, i]); y = log(E[k, i])
        sx += x; sy += y; sxx += x * x; sxy += x * y; m++
    }
    if (m < 2 || m * sxx - sx * sx == 0) return "NA"
    return sprintf("%.3f", (m * sxy - sx * sy) / (m * sxx - sx * sx))
}
# time (from the array X: wall T or cpu C) for renderer key k to reach error
# e (points in spp order)
function time_to(k, e, X,   i, a, b, f) {
    flag = ""
    for (i = 1; i < n[k]; i++)
        if (E[k, i] >= e && E[k, i + 1] <= e) break
    if (i >= n[k]) {
        if (E[k, 1] <= e) { i = 1 } else { i = n[k] - 1 }
        flag = "extrapolated"
    }
    if (X[k, i] <= 0 || X[k, i + 1] <= 0) return 0
    if (E[k, i] <= 0 || E[k, i + 1] <= 0 || E[k, i] == E[k, i + 1]) return X[k, i + 1]
    f = (log(e) - log(E[k, i])) / (log(E[k, i + 1]) - log(E[k, i]))
    return exp(log(X[k, i]) + f * (log(X[k, i + 1]) - log(X[k, i])))
}
END {
    print "scene,slope_spp_materia,slope_time_materia,slope_spp_pbrt,slope_time_pbrt,target_spp,target_rmse,time_pbrt_s,time_materia_s,ratio,cpu_pbrt_s,cpu_materia_s,ratio_cpu,note"
    for (j = 1; j <= ns; j++) {
        s = order[j]; km = s SUBSEP "materia"; kp = s SUBSEP "pbrt-v2"
        line = s "," slope(km, 0) "," slope(km, 1)
        if (!have["pbrt-v2"]) { print line ",NA,NA,NA,NA,NA,NA,NA,NA,NA,NA,no pbrt-v2"; continue }
        line = line "," slope(kp, 0) "," slope(kp, 1)
        ti = 0
        for (i = 1; i <= n[kp]; i++) if (S[kp, i] <= 1024) ti = i
        tp = T[kp, ti]; e = E[kp, ti]
        tm = time_to(km, e, T); fw = flag
        cp = C[kp, ti]; cm = time_to(km, e, C)
        printf "%s,%d,%.5g,%.4g,%.4g,%.3f,%.4g,%.4g,%s,%s\n", line, S[kp, ti], e, tp, tm, tm / tp, cp, cm,
               (cp > 0 && cm > 0) ? sprintf("%.3f", cm / cp) : "NA", fw
    }
}' smin="$SLOPEMIN" "$CSV" > "$SUM.tmp" && mv "$SUM.tmp" "$SUM"

# The relative-error percentiles, geometric means over the path-traced golden
# scenes, per renderer and count.
REL=$OUT/2-spp-relerr.csv
awk -F, -v scenes="$SCENES" 'BEGIN { split(scenes, a, " "); for (i in a) g[a[i]] = 1; print "renderer,spp,rel_p50,rel_p90,rel_p99,scenes" }
    NR > 1 && ($1 in g) && $8 > 0 && $10 > 0 {
        k = $2 "," $3; if (!(k in n)) o[++m] = k; n[k]++; p50[k] += log($8); p90[k] += log($9); p99[k] += log($10) }
    END { for (i = 1; i <= m; i++) { k = o[i]; printf "%s,%.5g,%.5g,%.5g,%d\n", k, exp(p50[k] / n[k]), exp(p90[k] / n[k]), exp(p99[k] / n[k]), n[k] } }' \
    "$CSV" > "$REL.tmp" && mv "$REL.tmp" "$REL"

# Plots: one panel per scene, RMSE against spp and against wall time, the
# two renderers' rows of 2-spp.csv selected in gnuplot; the percentiles.
status=0
PSCENES=$(awk -F, 'NR > 1 && !($1 in seen) { seen[$1] = 1; print $1 }' "$CSV")
np=$(echo $PSCENES | wc -w)
cols=4; [ "$np" -le 4 ] && cols=$np
rows=$(((np + cols - 1) / cols))
w=$((cols * 330)); [ $w -lt 660 ] && w=660
# series SCENE RENDERER XCOL: the plot clause of one curve
series() {
    sel="strcol(1) eq '$1' && strcol(2) eq '$2'"
    if [ "$2" = materia ]; then look="lc rgb '#1f77b4' pt 7 ps 0.6 lw 1.5"; else look="lc rgb '#d62728' pt 5 ps 0.6 lw 1.5 dt 2"; fi
    printf "'2-spp.csv' using (%s ? column(%s) : NaN):(column(6)) with linespoints %s title '%s'" "$sel" "$3" "$look" "$2"
}
PLOTMD=
for what in rmse time cpu; do
    if [ $what = rmse ]; then
        xl="samples per pixel"; title="RMSE against samples per pixel"; col=3
    elif [ $what = time ]; then
        xl="wall time per image (s)"; title="RMSE against wall time ($THREADS threads each)"; col=4
    else
        xl="CPU time per image, user + sys (s)"; title="RMSE against CPU time ($THREADS threads each)"; col=5
    fi
    cmds="set logscale xy; set format y '10^{%L}'; set format x '%g'; set grid
set key top right
set xlabel '$xl'
set ylabel 'RMSE (radiance)'
set multiplot layout $rows,$cols title \"$title\""
    for s in $PSCENES; do
        p="plot $(series "$s" materia $col)"
        grep -q "^$s,pbrt-v2," "$CSV" && p="$p, $(series "$s" pbrt-v2 $col)"
        cmds="$cmds
set title '$s'
$p"
    done
    cmds="$cmds
unset multiplot"
    md=$(tr_plot "2-spp-$what" "$title" "2-spp.csv" "$cmds" \
        "size $w,$((rows * 260 + 40)) enhanced font 'DejaVu Sans,9'") || status=1
    PLOTMD="$PLOTMD$md

"
done
cmds="set logscale xy; set format y '10^{%L}'; set format x '%g'; set grid; set key top right box opaque
set xlabel 'samples per pixel'; set ylabel 'relative error |a - b| / (b + 0.01)'
set title 'Relative error percentiles over pixels, geometric mean over the path-traced golden scenes'
plot '2-spp-relerr.csv' using (strcol(1) eq 'materia' ? column(2) : NaN):(column(3)) with linespoints lc rgb '#1f77b4' pt 7 lw 1.5 title 'materia, median', \\
     '' using (strcol(1) eq 'materia' ? column(2) : NaN):(column(5)) with linespoints lc rgb '#1f77b4' pt 9 lw 1.5 title 'materia, 99th percentile'"
if grep -q "^pbrt-v2," "$REL"; then
    cmds="$cmds, \\
     '' using (strcol(1) eq 'pbrt-v2' ? column(2) : NaN):(column(3)) with linespoints lc rgb '#d62728' pt 5 lw 1.5 dt 2 title 'pbrt-v2, median', \\
     '' using (strcol(1) eq 'pbrt-v2' ? column(2) : NaN):(column(5)) with linespoints lc rgb '#d62728' pt 11 lw 1.5 dt 2 title 'pbrt-v2, 99th percentile'"
fi
md=$(tr_plot 2-spp-relerr "Relative error percentiles against samples per pixel" "2-spp-relerr.csv" "$cmds") || status=1
PLOTMD="$PLOTMD$md
"
# The report section.
list() { echo $1 | sed 's/ /, /g'; }
# at the largest count of each path-traced golden scene: the median and the
# largest share of the reference's noise in the raw squared error (column 13)
refshare=$(awk -F, -v scenes="$SCENES" 'BEGIN { split(scenes, a, " "); for (i in a) g[a[i]] = 1 }
    NR > 1 && ($1 in g) && $13 != "NA" { k = $1 SUBSEP $2; if ($3 + 0 >= top[k] + 0) { top[k] = $3; v[k] = $13 } }
    END { n = 0; for (k in v) x[++n] = v[k] + 0
          for (i = 1; i <= n; i++) for (j = i + 1; j <= n; j++) if (x[j] < x[i]) { t = x[i]; x[i] = x[j]; x[j] = t }
          if (n) printf "%.0f%% %.0f%% %.0f%%\n", 100 * x[int((n + 1) / 2)], 100 * x[n], 100 * (1 / sqrt(1 - x[n]) - 1) }' "$CSV")
MD=$OUT/2-spp.md
{
    echo "## 2. Samples per pixel"
    echo
    echo "What a sample buys: the error of an image against a converged reference as a function of"
    echo "the samples per pixel and of the wall time, for materia-render and pbrt-v2 side by side."
    echo "Scenes: the golden scenes \`golden/scenes/\` at their own 64x48 pixels, the path-traced ones"
    echo "($(echo $SCENES | wc -w): $SCENES) at $(list "$SPPS") spp$( [ -n "$DIPOLE" ] && echo ", the dipole ones ($DIPOLE) at $(list "$DIPOLESPPS") spp (their lights take 64 and 16 samples per camera sample)")."
    if [ -n "$REAL" ]; then
        echo "Real scenes of \`../shared/reference/scenes\` ($REAL) at 1/$REALSCALE of their resolution,"
        echo "$(list "$REALSPPS") spp."
    fi
    echo
    echo "**The reference and its noise.** Each scene's reference is the mean b of two materia renders"
    echo "with seeds 1 and 2 (the sweep's materia renders use seed 0), each at twice the sweep's largest"
    echo "count ($REFSPP spp$( [ -n "$DIPOLE" ] && echo ", $DIPOLEREF for the dipole scenes")$( [ -n "$REAL" ] && echo ", $REALREF for the real ones")): four times it in all. The error"
    echo "of an image a is RMSE = sqrt(mean((a - b)^2 - vb)) over pixels and colour channels, with vb ="
    echo "(r1 - r2)^2 / 4 the reference's noise measured by its two halves: since E[(a - b)^2] ="
    echo "E[(a - mu)^2] + Var(b) for independent a and b (mu the converged image) and E[vb] = Var(b),"
    echo "this is a's error against mu without the reference's own, whatever the sampler"
    echo "(\`tradeoff/imgerr.c\`; \`tests/test_sqerr.c\` checks it against known answers, and that"
    echo "leaving vb out, or taking it from a low-discrepancy render's own variance image, misses)."
    if [ -n "$refshare" ]; then
        set -- $refshare
        echo "At the largest count the reference's noise was $1 of the raw squared error (the median"
        echo "over the path-traced scenes and renderers; at most $2), which the raw RMSE (\`rmse_raw\` in"
        echo "\`2-spp.csv\`) would have counted."
        echo "What remains: the square root of an unbiased mean square is low by about its relative"
        echo "variance / 8 (for Gaussian noise over the 9216 values of a 64x48 image, (2/9216) / 8 ="
        echo "3e-5); a difference between pbrt-v2's converged image and"
        echo "materia's counts as pbrt-v2's error, as it should. The relative-error percentiles and"
        echo "pbrt-v2's block metric keep the reference's noise: at the largest count it raises them by"
        echo "up to $3 (for Gaussian noise, 1/sqrt(1 - share))."
    fi
    if [ -s "$REFCSV" ]; then
        awk -F, 'NR > 1 && $6 != "NA" { x[++n] = $6 + 0; s[n] = $1 }
            END { if (!n) exit
                  for (i = 1; i <= n; i++) for (j = i + 1; j <= n; j++) if (x[j] < x[i]) { t = x[i]; x[i] = x[j]; x[j] = t; t = s[i]; s[i] = s[j]; s[j] = t }
                  printf "materia-render'\''s own variance image (`--variance`, the sample variance over the count)\n"
                  printf "claims %.2f times the variance measured between the two references (median over the\n", x[int((n + 1) / 2)]
                  printf "scenes; %.2f (%s) to %.2f (%s), `2-spp-reference.csv`): its low-discrepancy samples do\n", x[1], s[1], x[n], s[n]
                  printf "better than independent ones, so subtracting it would remove too much.\n" }' "$REFCSV"
    fi
    echo
    echo "Wall time is the whole process (parse, BVH, render, write), both renderers with $THREADS"
    echo "threads, run back to back on the same machine, alternating which goes first at each count;"
    echo "CPU time is user + sys, steadier on a loaded machine."
    if [ -n "$PBRT" ]; then
        echo "pbrt-v2: \`../shared/baselines/pbrt-v2/pbrt\`, its \`lowdiscrepancy\` sampler at the same sample"
        echo "count (the scene's \`pixelsamples\` rewritten in a copy); materia uses its own sampler."
        echo "pbrt-v2 writes half-float EXR (rounding adds about 1.4e-4 relative, far below these errors)."
    else
        echo
        echo "**pbrt-v2 not measured**: \`../shared\` is absent (or has no pbrt-v2 baseline), so only"
        echo "materia's curves are here and there are no ratios."
    fi
    echo
    printf '%s\n' "$PLOTMD"
    echo "Convergence slopes (least squares of log RMSE against log spp and log wall time over the"
    echo "counts from $SLOPEMIN spp on, where the fixed cost of a run no longer dominates; -0.5 is"
    echo "plain Monte Carlo), and the time each renderer needs to reach the RMSE pbrt-v2 reaches at"
    echo "1024 spp (or its largest count), interpolated log-log between materia's two bracketing"
    echo "counts: wall time, and user+sys CPU time (steadier on a shared machine), from"
    echo "\`2-spp-summary.csv\`:"
    echo
    awk -F, 'NR == 1 { next }
        NR == 2 { print "| scene | slope/spp materia | slope/spp pbrt-v2 | slope/wall materia | slope/wall pbrt-v2 | pbrt-v2 spp | its RMSE | pbrt-v2 wall s | materia wall s | ratio | pbrt-v2 cpu s | materia cpu s | ratio |"
                  print "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |" }
        { printf "| %s | %s | %s | %s | %s | %s | %s | %s | %s%s | %s | %s | %s | %s |\n", $1, $2, $4, $3, $5, $6, $7, $8, $9, ($14 == "extrapolated" ? " (extrap.)" : ""), $10, $11, $12, $13 }' "$SUM"
    echo
    awk -F, 'function gm(c, what,   n, s, w, b, ws, bs, i) {
            n = 0; s = 0; w = 0; b = ""
            for (i = 2; i <= nr; i++) { x = V[i, c]; if (x == "NA" || x <= 0) continue
                n++; s += log(x); if (x > w) { w = x; ws = V[i, 1] } if (b == "" || x < b) { b = x; bs = V[i, 1] } }
            if (n) printf "Time to pbrt-v2'\''s error, materia/pbrt-v2, %s: geometric mean %.2f over %d scenes, from %.2f (%s) to %.2f (%s). ", what, exp(s / n), n, b, bs, w, ws
        }
        { nr = NR; for (i = 1; i <= NF; i++) V[NR, i] = $i }
        NR > 1 { if ($2 != "NA") { nm++; sm += $2 } if ($4 != "NA") { np++; sp += $4 } }
        END {
            gm(10, "wall time"); gm(13, "CPU time")
            if (nm) printf "Mean slope against spp: materia %.2f", sm / nm
            if (np) printf ", pbrt-v2 %.2f", sp / np
            if (nm) printf ".\n"
        }' "$SUM"
    echo
    echo "Measured by \`$(if [ "$QUICK" = 1 ]; then echo "make tradeoff QUICK=1"; else echo "make tradeoff"; fi)\` (\`tradeoff/2-spp.sh\`) in ${ELAPSED} s of wall time$( [ -s "$OUT/2-spp.load" ] && echo "; load average (1, 5, 15 min) $(cat "$OUT/2-spp.load")")."
} > "$MD.tmp" && mv "$MD.tmp" "$MD"
echo "2-spp: wrote $CSV, $SUM, $MD" >&2
exit $status

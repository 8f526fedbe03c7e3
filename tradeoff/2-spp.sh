#!/bin/sh
# Measurement 2: samples per pixel. For each scene, materia-render and (when
# ../shared is present) pbrt-v2 render it at a sweep of sample counts on the
# same machine, alternating which goes first, with the same thread count;
# each image's error against a high-sample materia reference (another seed)
# is computed by $MT_TRADEOFF/imgerr. Writes $OUT/2-spp.csv, the fitted
# convergence slopes and times-to-error in $OUT/2-spp-summary.csv, plots
# $OUT/2-spp-rmse.png and $OUT/2-spp-time.png (with gnuplot), and the report
# section $OUT/2-spp.md.
#
# Environment (tools/run-tradeoff.sh sets the first ones): MT_BIN,
# MT_TRADEOFF, OUT, QUICK, SHARED, GNUPLOT, TRADEOFF_DIR; and to change the
# sweep: SPP_SCENES (golden scene names, "none" for none), SPP_LIST, SPP_REF, SPP_REAL (real
# scene names of ../shared/reference/scenes, "none" for none), SPP_REAL_LIST,
# SPP_REAL_REF, SPP_REAL_SCALE (resolution divisor of the real scenes),
# SPP_THREADS (2); SPP_REPORT_ONLY=1 rewrites the summary, plots and
# section from an earlier run's $OUT/2-spp.csv without rendering.
set -u
: "${MT_BIN:?}" "${MT_TRADEOFF:?}" "${OUT:?}"
QUICK=${QUICK:-0}
SHARED=${SHARED:-}
GNUPLOT=${GNUPLOT:-}
TRADEOFF_DIR=${TRADEOFF_DIR:-$(cd "$(dirname "$0")" && pwd)}
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
    REFSPP=${SPP_REF:-1024}
    REAL=${SPP_REAL:-none}
else
    SCENES=${SPP_SCENES:-"matte plastic glass mirror metal shinymetal substrate translucent uber mix measured subsurface kdsubsurface"}
    # Up to 1024 spp with the reference at 8x: within an hour on a shared
    # 2-core machine. SPP_LIST="1 4 16 64 256 1024 4096" SPP_REF=32768 goes
    # to 4096 (about four times as long).
    SPPS=${SPP_LIST:-"1 4 16 64 256 1024"}
    REFSPP=${SPP_REF:-8192}
    REAL=${SPP_REAL:-"real-killeroo-simple real-metal-teapot real-bunny-measured"}
fi
# Slopes are fitted to the points from this count on: below it the process's
# fixed cost (parse, BVH, writing) dominates the wall time.
SLOPEMIN=16; [ "$QUICK" = 1 ] && SLOPEMIN=4
REALSPPS=${SPP_REAL_LIST:-"1 4 16 64 256"}
REALREF=${SPP_REAL_REF:-2048}
REALSCALE=${SPP_REAL_SCALE:-4}
[ "$REAL" = none ] && REAL=
[ "$SCENES" = none ] && SCENES=

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
printf 'scene,renderer,spp,wall_s,cpu_s,rmse,relmse,rel_p50,rel_p90,rel_p99,noise_mean\n' > "$CSV.tmp"

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

# run SCENE DIR RENDERER SPP REF: one render, one CSV row.
run() {
    s=$1 d=$2 r=$3 n=$4 ref=$5
    img=$d/$r-$n.exr
    if [ "$r" = pbrt-v2 ]; then
        pbrt_scene "$d" "$n" || return 1
        tw=$(cd "$d" && timed "$d/$r-$n.log" "$PBRT" --ncores "$THREADS" --quiet --outfile "$img" "$d/scene-$n.pbrt") || return 1
    else
        tw=$(cd "$d" && timed "$d/$r-$n.log" "$RENDER" "$d/scene.pbrt" -o "$img" --spp "$n" --threads "$THREADS" --quiet) || return 1
    fi
    e=$("$IMGERR" "$img" "$ref") || return 1
    echo "$s $r $n $tw $e" | awk '{ $1 = $1; gsub(/ /, ","); print }' >> "$CSV.tmp"
    rm -f "$img"
    echo "  $s $r spp $n: wall/cpu s $tw, rmse relmse p50 p90 p99 noise $e" >&2
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
    echo "2-spp: $s: reference at $rs spp (materia, seed 1)" >&2
    (cd "$d" && "$RENDER" "$d/scene.pbrt" -o "$d/ref.exr" --spp "$rs" --seed 1 --threads "$THREADS" --quiet) ||
        { echo "2-spp: reference render of $s failed" >&2; return 1; }
    k=0
    for n in "$@"; do
        # Alternate which renderer goes first, so that neither always meets
        # the machine in the same state.
        if [ -z "$PBRT" ]; then order=materia
        elif [ $((k % 2)) = 0 ]; then order="pbrt-v2 materia"
        else order="materia pbrt-v2"; fi
        for r in $order; do run "$s" "$d" "$r" "$n" "$d/ref.exr" || return 1; done
        k=$((k + 1))
    done
    rm -rf "$d"
}

START=$(date +%s)
if [ "${SPP_REPORT_ONLY:-0}" = 1 ] && [ -s "$CSV" ]; then
    # Only the summary, plots and section again, from the CSV of an earlier
    # run (with the same sweep settings); its duration is kept beside it.
    rm -f "$CSV.tmp"
    ELAPSED=$(cat "$OUT/2-spp.seconds" 2>/dev/null || echo "?")
else
    for s in $SCENES; do
        [ -f "$GOLDEN/$s.pbrt" ] || { echo "2-spp: no golden scene $s" >&2; exit 1; }
        # shellcheck disable=SC2086
        sweep "$s" "$GOLDEN/$s.pbrt" 1 "$REFSPP" $SPPS || exit 1
    done
    for s in $REAL; do
        # shellcheck disable=SC2086
        sweep "$s" "$SHARED/reference/scenes/$s.pbrt" "$REALSCALE" "$REALREF" $REALSPPS || exit 1
    done
    mv "$CSV.tmp" "$CSV"
    ELAPSED=$(($(date +%s) - START))
    echo "$ELAPSED" > "$OUT/2-spp.seconds"
fi

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

# Plots: one panel per scene, RMSE against spp and against wall time.
PLOTS=
# the scenes of the CSV, in its order (in SPP_REPORT_ONLY runs too)
PSCENES=$(awk -F, 'NR > 1 && !($1 in seen) { seen[$1] = 1; print $1 }' "$CSV")
if [ -n "$GNUPLOT" ]; then
    for s in $PSCENES; do
        for r in materia pbrt-v2; do
            awk -F, -v s="$s" -v r="$r" '$1 == s && $2 == r { print $3, $4, $6 }' "$CSV" > "$TMP/$s.$r.dat"
        done
    done
    np=$(echo $PSCENES | wc -w)
    cols=4; [ "$np" -le 4 ] && cols=$np
    rows=$(((np + cols - 1) / cols))
    for what in rmse time; do
        gp=$TMP/$what.gp
        {
            if [ -f "$TRADEOFF_DIR/style.gp" ]; then
                echo "load '$TRADEOFF_DIR/style.gp'"
            fi
            w=$((cols * 330)); [ $w -lt 660 ] && w=660
            echo "set terminal pngcairo size $w,$((rows * 260 + 40)) enhanced font 'DejaVu Sans,9'"
            # the data files here are whitespace-separated (the shared style reads CSV)
            echo "set datafile separator whitespace"
            echo "set output '$OUT/2-spp-$what.png'"
            echo "set logscale xy; set format y '10^{%L}'; set grid"
            echo "set key top right"
            if [ $what = rmse ]; then
                echo "set xlabel 'samples per pixel'; set format x '%g'"
                title="RMSE against samples per pixel"
                col=1
            else
                echo "set xlabel 'wall time per image (s)'; set format x '%g'"
                title="RMSE against wall time ($THREADS threads each)"
                col=2
            fi
            echo "set ylabel 'RMSE (radiance)'"
            echo "set multiplot layout $rows,$cols title \"$title\""
            for s in $PSCENES; do
                echo "set title '$s'"
                p="plot '$TMP/$s.materia.dat' using $col:3 with linespoints lc rgb '#1f77b4' pt 7 ps 0.6 lw 1.5 title 'materia'"
                [ -s "$TMP/$s.pbrt-v2.dat" ] &&
                    p="$p, '$TMP/$s.pbrt-v2.dat' using $col:3 with linespoints lc rgb '#d62728' pt 5 ps 0.6 lw 1.5 dt 2 title 'pbrt-v2'"
                echo "$p"
            done
            echo "unset multiplot"
        } > "$gp"
        "$GNUPLOT" "$gp" || { echo "2-spp: gnuplot failed on $gp" >&2; exit 1; }
        PLOTS="$PLOTS 2-spp-$what.png"
    done
    # The relative-error percentiles, geometric mean over the golden scenes.
    for r in materia pbrt-v2; do
        awk -F, -v r="$r" -v scenes="$SCENES" 'BEGIN { split(scenes, a, " "); for (i in a) g[a[i]] = 1 }
            NR > 1 && $2 == r && ($1 in g) && $8 > 0 && $10 > 0 {
                if (!($3 in n)) o[++k] = $3; n[$3]++; p50[$3] += log($8); p90[$3] += log($9); p99[$3] += log($10) }
            END { for (i = 1; i <= k; i++) { x = o[i]; printf "%s %.5g %.5g %.5g\n", x, exp(p50[x] / n[x]), exp(p90[x] / n[x]), exp(p99[x] / n[x]) } }' \
            "$CSV" > "$TMP/rel.$r.dat"
    done
    {
        if [ -f "$TRADEOFF_DIR/style.gp" ]; then echo "load '$TRADEOFF_DIR/style.gp'"; fi
        echo "set terminal pngcairo size 760,500 enhanced font 'DejaVu Sans,10'"
        echo "set datafile separator whitespace"
        echo "set output '$OUT/2-spp-relerr.png'"
        echo "set logscale xy; set format y '10^{%L}'; set format x '%g'; set grid; set key top right box opaque"
        echo "set xlabel 'samples per pixel'; set ylabel 'relative error |a - b| / (b + 0.01)'"
        echo "set title 'Relative error percentiles over pixels, geometric mean over the golden scenes'"
        p="plot '$TMP/rel.materia.dat' using 1:2 with linespoints lc rgb '#1f77b4' pt 7 lw 1.5 title 'materia, median'"
        p="$p, '' using 1:4 with linespoints lc rgb '#1f77b4' pt 9 lw 1.5 title 'materia, 99th percentile'"
        if [ -s "$TMP/rel.pbrt-v2.dat" ]; then
            p="$p, '$TMP/rel.pbrt-v2.dat' using 1:2 with linespoints lc rgb '#d62728' pt 5 lw 1.5 dt 2 title 'pbrt-v2, median'"
            p="$p, '' using 1:4 with linespoints lc rgb '#d62728' pt 11 lw 1.5 dt 2 title 'pbrt-v2, 99th percentile'"
        fi
        echo "$p"
    } > "$TMP/rel.gp"
    "$GNUPLOT" "$TMP/rel.gp" || { echo "2-spp: gnuplot failed on $TMP/rel.gp" >&2; exit 1; }
    PLOTS="$PLOTS 2-spp-relerr.png"
fi

# The report section.
MD=$OUT/2-spp.md
{
    echo "## 2. Samples per pixel"
    echo
    echo "What a sample buys: the error of an image against a high-sample reference as a function"
    echo "of the samples per pixel and of the wall time, for materia-render and pbrt-v2 side by side."
    echo "Scenes: the golden scenes \`golden/scenes/\` ($(echo $SCENES | wc -w): $SCENES), at their own"
    echo "64x48 pixels, sample counts $(echo $SPPS | tr ' ' ','); reference: materia-render at $REFSPP spp with"
    echo "another seed (\`--seed 1\`)."
    if [ -n "$REAL" ]; then
        echo "Real scenes of \`../shared/reference/scenes\` ($REAL) at 1/$REALSCALE of their resolution,"
        echo "sample counts $(echo $REALSPPS | tr ' ' ','), reference at $REALREF spp."
    fi
    echo "Error: RMSE over pixels and channels, and percentiles of the relative error"
    echo "\`|a - b| / (b + 0.01)\` per pixel and channel (columns of \`2-spp.csv\`, computed by"
    echo "\`tradeoff/imgerr.c\`). Wall time is the whole process (parse, BVH, render, write), both"
    echo "renderers with $THREADS threads, run back to back on the same machine, alternating which goes"
    echo "first at each sample count. The reference's own noise adds to the error of the largest"
    echo "count ($(echo $SPPS | awk '{ print $NF }') spp, against $REFSPP): by $(awk -v a="$(echo $SPPS | awk '{ print $NF }')" -v b="$REFSPP" 'BEGIN { printf "%.0f%%", 100 * (sqrt(1 + a / b) - 1) }') if the error falls as 1/sqrt(spp)."
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
    if [ -n "$PLOTS" ]; then
        for p in $PLOTS; do echo "![$p]($p)"; echo; done
    else
        echo "gnuplot was not found: the data are in \`2-spp.csv\` (one row per scene, renderer and"
        echo "spp) and \`2-spp-summary.csv\`. To plot: \`set datafile separator ','; set logscale xy\`,"
        echo "then RMSE (column 6) against spp (column 3) or wall time (column 4) per scene and renderer."
        echo
    fi
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
    echo "Measured by \`$(if [ "$QUICK" = 1 ]; then echo "make tradeoff QUICK=1"; else echo "make tradeoff"; fi)\` (\`tradeoff/2-spp.sh\`) in ${ELAPSED} s of wall time."
} > "$MD.tmp" && mv "$MD.tmp" "$MD"
echo "2-spp: wrote $CSV, $SUM, $MD" >&2

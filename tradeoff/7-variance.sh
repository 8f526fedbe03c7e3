#!/bin/sh
# Measurement 7: noise per sample and where it comes from (the variance
# budget; docs/BENCHMARKS.md, Noise per sample). One render's error is
# measured without a reference, from two renders with different seeds:
# rmse = sqrt(mean over pixels and channels of (a - b)^2 / 2), since two
# independent draws of an unbiased estimator differ by twice its variance.
# Each configuration draws some values independently at random instead of
# from their low-discrepancy pair; what that costs is what the pair's
# stratification buys.
#   materia   tradeoff/variance (the configurations below, VAR_CONFIGS)
#   pbrt-v2   its own samplers (lowdiscrepancy, random, stratified, halton) in
#             the scene's Sampler; its two "seeds" are two task splits
#             (--ncores 2 and 8: every task seeds its RNG with its number)
#   Mitsuba 3 tradeoff/mitsuba_variance.py (its path integrator with switches),
#             when a Python with mitsuba and numpy is found (MITSUBA_PYTHON, or
#             python3) and ../shared/baselines/mitsuba3/render.py exists
# Writes $OUT/7-variance.csv and the report section $OUT/7-variance.md.
#
# Environment (tools/run-tradeoff.sh sets the first ones): MT_TRADEOFF, OUT,
# QUICK, SHARED, TRADEOFF_DIR; VAR_SCENES (reference scenes, default "matte
# plastic"), VAR_SPP (1024; QUICK 64), VAR_THREADS (2), MITSUBA_PYTHON.
set -u
: "${MT_TRADEOFF:?}" "${OUT:?}"
QUICK=${QUICK:-0}
SHARED=${SHARED:-}
TRADEOFF_DIR=${TRADEOFF_DIR:-$(cd "$(dirname "$0")" && pwd)}
. "$TRADEOFF_DIR/lib.sh"
abspath() { case $1 in /*) echo "$1" ;; *) echo "$PWD/$1" ;; esac; }
MT_TRADEOFF=$(abspath "$MT_TRADEOFF"); OUT=$(abspath "$OUT")
VARIANCE=$MT_TRADEOFF/variance
IMGERR=$MT_TRADEOFF/imgerr
tr_need "$VARIANCE" "$IMGERR"
SCENES=${VAR_SCENES:-"matte plastic"}
if [ "$QUICK" = 1 ]; then SPP=${VAR_SPP:-64}; else SPP=${VAR_SPP:-1024}; fi
THREADS=${VAR_THREADS:-2}
CSV=$OUT/7-variance.csv
MD=$OUT/7-variance.md
mkdir -p "$OUT"
TMP=$(mktemp -d "${TMPDIR:-/tmp}/mt-variance.XXXXXX") || exit 1
trap 'rm -rf "$TMP"' EXIT INT TERM

if [ -z "$SHARED" ] || [ ! -d "$SHARED/reference/scenes" ]; then
    printf '## 7. Noise per sample\n\nSkipped: the reference scenes (../shared/reference/scenes) are absent.\n' >"$MD"
    exit 0
fi
SCN=$SHARED/reference/scenes

# materia: the renderer as it is, then one dimension (or vertex) at a time
# drawn independently, then everything
VAR_CONFIGS=${VAR_CONFIGS:-"ld= image=image v0.light=v0.light v0.bsdf=v0.bsdf v0=v0 v1=v1 v2+=v2+ all=all own-choice=own-choice chosen-bsdf=chosen-bsdf pbrt-v2-both=own-choice,chosen-bsdf pbrt-v2-both-random=own-choice,chosen-bsdf,all"}
echo "renderer,scene,spp,config,rmse,mean,seconds,load" > "$CSV"
for s in $SCENES; do
    echo "7-variance: materia $s at $SPP spp" >&2
    # shellcheck disable=SC2086
    (cd "$SCN" && "$VARIANCE" --threads "$THREADS" "$s.pbrt" "$SPP" $VAR_CONFIGS) > "$TMP/m.txt" ||
        tr_die "materia's variance failed on $s"
    load=$(cut -d' ' -f1 /proc/loadavg 2>/dev/null || echo NA)
    awk -v s="$s" -v n="$SPP" -v l="$load" '{ printf "materia,%s,%s,%s,%s,%s,%s,%s\n", s, n, $1, $2, $3, $4, l }' \
        "$TMP/m.txt" >> "$CSV"
done

# pbrt-v2: its samplers, each with two task splits
PBRT=
[ -x "$SHARED/baselines/pbrt-v2/pbrt" ] && PBRT=$SHARED/baselines/pbrt-v2/pbrt
if [ -n "$PBRT" ]; then
    side=$(echo "$SPP" | awk '{ printf "%d", sqrt($1) + 0.5 }')
    for s in $SCENES; do
        for smp in lowdiscrepancy random stratified halton; do
            case $smp in
                stratified) line="Sampler \"stratified\" \"integer xsamples\" [$side] \"integer ysamples\" [$side]" ;;
                *) line="Sampler \"$smp\" \"integer pixelsamples\" [$SPP]" ;;
            esac
            echo "7-variance: pbrt-v2 $s $smp" >&2
            sed -e "s|^Sampler .*|$line|" -e 's|"string filename" "[^"]*"||' "$SCN/$s.pbrt" > "$TMP/$s-$smp.pbrt"
            t0=$(date +%s.%N)
            for c in 2 8; do
                (cd "$SCN" && "$PBRT" --ncores $c --quiet --outfile "$TMP/$s-$smp-$c.exr" "$TMP/$s-$smp.pbrt") \
                    > "$TMP/pbrt.log" 2>&1 || { echo "7-variance: pbrt-v2 failed on $s $smp" >&2; continue 2; }
            done
            t1=$(date +%s.%N)
            load=$(cut -d' ' -f1 /proc/loadavg 2>/dev/null || echo NA)
            # imgerr's rmse_raw is sqrt(mean (a - b)^2): one render's error is that over sqrt 2
            "$IMGERR" "$TMP/$s-$smp-2.exr" "$TMP/$s-$smp-8.exr" | awk -v s="$s" -v n="$SPP" -v m="$smp" \
                -v t="$(echo "$t0 $t1" | awk '{ printf "%.2f", $2 - $1 }')" -v l="$load" \
                '{ printf "pbrt-v2,%s,%s,%s,%.6g,NA,%s,%s\n", s, n, m, $7 / sqrt(2), t, l }' >> "$CSV"
        done
    done
fi

# Mitsuba 3
MPY=${MITSUBA_PYTHON:-python3}
RENDER_PY=$SHARED/baselines/mitsuba3/render.py
MITSUBA=0
if [ -f "$RENDER_PY" ] && "$MPY" -c 'import mitsuba, numpy' 2>/dev/null; then MITSUBA=1; fi
if [ $MITSUBA = 1 ]; then
    for s in $SCENES; do
        echo "7-variance: Mitsuba $s" >&2
        "$MPY" "$TRADEOFF_DIR/mitsuba_variance.py" --threads "$THREADS" "$RENDER_PY" "$s" "$SPP" \
            builtin=builtin independent=independent path= image=image emitter=emitter emitter@0=emitter@0 \
            bsdf=bsdf1,bsdf2 bsdf@0=bsdf1@0,bsdf2@0 rr=rr depth0=emitter@0,bsdf1@0,bsdf2@0,rr@0 \
            choice=choice rr-pbrt=rr=pbrt > "$TMP/mi.txt" 2>"$TMP/mi.log" ||
            { echo "7-variance: Mitsuba failed on $s:" >&2; tail -5 "$TMP/mi.log" >&2; continue; }
        load=$(cut -d' ' -f1 /proc/loadavg 2>/dev/null || echo NA)
        awk -v s="$s" -v n="$SPP" -v l="$load" '{ printf "mitsuba,%s,%s,%s,%s,%s,%s,%s\n", s, n, $1, $2, $3, $4, l }' \
            "$TMP/mi.txt" >> "$CSV"
    done
fi

# The report: per renderer and scene, each configuration's rmse and its
# variance over the renderer's own (ld / ldsampler / lowdiscrepancy) one.
{
    echo "## 7. Noise per sample: the variance budget"
    echo
    echo "One render's RMSE at $SPP samples per pixel, from two renders with different seeds"
    echo "(\`make tradeoff TRADEOFF_ONLY=7\`; data: \`7-variance.csv\`). \"variance x\" is the"
    echo "configuration's variance over the renderer's own: what the values it draws at random"
    echo "would cost. materia's configurations are tradeoff/variance's, Mitsuba's"
    echo "tradeoff/mitsuba_variance.py's, pbrt-v2's its samplers."
    [ -n "$PBRT" ] || echo "pbrt-v2 (../shared/baselines/pbrt-v2/pbrt) was not found: no pbrt-v2 rows."
    [ $MITSUBA = 1 ] || echo "Mitsuba 3 was not found (set MITSUBA_PYTHON to a Python with mitsuba and numpy): no Mitsuba rows."
    echo
    echo "| renderer | scene | configuration | RMSE | variance x |"
    echo "| --- | --- | --- | --- | --- |"
    awk -F, 'NR > 1 {
        key = $1 "," $2
        if (($1 == "materia" && $4 == "ld") || ($1 == "mitsuba" && $4 == "path") || ($1 == "pbrt-v2" && $4 == "lowdiscrepancy")) base[key] = $5
        row[NR] = $0
    }
    END {
        for (i = 2; i <= NR; ++i) {
            split(row[i], f, ",")
            b = base[f[1] "," f[2]]
            printf "| %s | %s | %s | %.3g | %s |\n", f[1], f[2], f[4], f[5], (b > 0) ? sprintf("%.2f", (f[5] / b) ^ 2) : "-"
        }
    }' "$CSV"
    echo
    echo "Load average at the end: $(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo unknown)."
} > "$MD"

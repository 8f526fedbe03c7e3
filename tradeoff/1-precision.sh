#!/bin/sh
# 1. Precision: the float build's f, pdf and sampled direction against the
# double build's, in float ULPs, beside the time per call of each build
# (tradeoff/precision.c), for every configuration of the --impl catalog.
. "$TRADEOFF_DIR/lib.sh"
tr_need "$MT_TRADEOFF/precision" "$MT_TRADEOFF_DOUBLE/precision"
if [ "$QUICK" = 1 ]; then nq=512; else nq=8192; fi
data=$OUT/1-precision-data
mkdir -p "$data" || exit 1
# the two builds one after the other, in one run
"$MT_TRADEOFF/precision" answers "$data" $nq >"$data/float.txt" || tr_die "float build's answers failed"
"$MT_TRADEOFF_DOUBLE/precision" answers "$data" $nq >"$data/double.txt" || tr_die "double build's answers failed"
"$MT_TRADEOFF_DOUBLE/precision" compare "$data/float.txt" "$data/double.txt" >"$OUT/1-precision.csv.tmp" ||
    tr_die "compare failed"
mv "$OUT/1-precision.csv.tmp" "$OUT/1-precision.csv"
rm -rf "$data"
csv=$OUT/1-precision.csv
nconf=$(awk 'END { print NR - 1 }' "$csv")
nmat=$(awk -F, 'NR > 1 { m[$2] = 1 } END { n = 0; for (k in m) n++; print n }' "$csv")
# the material kinds, in registry order, for the plot's legend
mats=$("$MT_BIN/materia-query" --list materials | awk '{ printf "%s%s", sep, $1; sep = " " }')
# columns: 2 material, 3 configuration, 13 the 99th percentile over all
# values, 14 double against long double, 21 the time ratio
stats=$(awk -F, 'NR > 1 {
        r = $21; x = $13; lm = $14
        n++; rs[n] = r; xs[n] = x
        if (x + 0 > wx) { wx = x + 0; wn = $2 }
        if (lm != "" && lm + 0 > ld) ld = lm + 0
        if (lm != "") nld++
        if (x + 0 <= 16) good++
        if (x + 0 == 0) exact++
    }
    function med(a, n,   i, j, t) { for (i = 1; i <= n; ++i) for (j = i + 1; j <= n; ++j) if (a[j] + 0 < a[i] + 0) { t = a[i]; a[i] = a[j]; a[j] = t } return a[int((n + 1) / 2)] }
    END { lo = rs[1]; hi = rs[1]; for (i = 1; i <= n; ++i) { if (rs[i] + 0 < lo + 0) lo = rs[i]; if (rs[i] + 0 > hi + 0) hi = rs[i] }
          printf "%s %s %s %s %s %d %d %s %d\n", med(rs, n), lo, hi, med(xs, n), wx, good, exact, ld, nld }' "$csv")
set -- $stats
rmed=$1; rlo=$2; rhi=$3; xmed=$4; xworst=$5; good=$6; exact=$7; ldmax=$8; nld=$9
worst=$(awk -F, -v w="$xworst" 'NR > 1 && $13 + 0 == w + 0 { print $3; exit }' "$csv")

plot=$(tr_plot 1-precision "Float against double: error and time, per configuration" "1-precision.csv" "
set title 'Float against double, per configuration of the --impl catalog ($nconf, $nmat materials)'
set xlabel 'float build: 99th percentile of |float - double| over f, pdf and sampled direction (float ULPs)'
set ylabel 'time per call, double / float (f + pdf + sample f)'
eval logx
set xrange [0.05:*]
set key outside right top font ',9'
set rmargin 16
set style data points
mats = '$mats'
xv(x) = x < 0.1 ? 0.1 : x
set label 'exact (0 ULPs)' at 0.1, graph 0.06 center font ',8'
plot for [i = 1:words(mats)] '1-precision.csv' using (strcol(2) eq word(mats, i) ? xv(column(13)) : NaN):(column(21)) \\
         every ::1 title word(mats, i) with points lc (i % 8 + 1) pt (4 + 2 * ((i - 1) / 8)) ps 1.3, \\
     1 with lines dt 2 lc rgb '#888888' title 'equal time'
") || status=1

cat >"$OUT/1-precision.md" <<EOF
## 1. Precision: float against double

Every configuration of the catalog that \`materia-conformance --impl\` runs
(conformance/impl_catalog.c: $nconf configurations covering all $nmat materials across their
parameters and extremes, built from pbrt-v2 statements as \`materia-query\` builds them; the
suite's own catalog, conformance/materials.c, has no \`measured\` material), in pbrt-v2 mode.
For $nq queries per configuration with inputs representable in float (the same in both
builds): f (RGB) and pdf of random (wo, wi), and the direction and pdf that sample_f returns
for random (wo, u). The float build's error is its difference from the double build's answer
in float ULPs at the larger magnitude (values below 1e-7 of the configuration's largest are
compared at that floor, as the suite's float-versus-double check does). Times: ns per call of
each build, CPU time of one thread, median of 5 repetitions, the two builds one after the
other in one run (\`tradeoff/precision.c\`, run by \`tradeoff/1-precision.sh\`; every figure per
configuration in \`1-precision.csv\`).

$plot

- The float build's 99th-percentile error (over f, pdf and direction together) is $xmed float
  ULPs for the median configuration; $good of $nconf configurations stay within 16 ULPs and
  $exact are exact (delta lobes only: the same directions and weights). The worst is
  "$worst" ($xworst ULPs): sharp lobes (roughness 0.001, exponent 1000) and bump maps
  amplify rounding, and a sampled direction that falls on the other side of a branch (which
  lobe, total internal reflection or not) counts as a large error; the maximum per
  configuration is in the CSV.
- The double build costs $rmed times the float build's time per call for the median
  configuration ($rlo to $rhi). The ratio of one configuration moves by some tens of
  percent between runs on a shared machine (below 1 is such noise); the median over the
  catalog is the figure to read. Double precision is cheap here: for a user who wants ground
  truth, the double build is worth its time.
- The double build against a higher precision: for the Lambertian configurations ($nld: matte
  with constant Kd, no Oren-Nayar, no texture, no tilt) f and pdf evaluated in long double from
  pbrt-v2's closed form (R/pi, |cos wi|/pi) differ from the double build's by at most $ldmax
  double ULPs. For the other BxDFs no higher-precision answer is cheap: materia has no long
  double build, and a long double reimplementation of Fresnel, the microfacet distributions,
  Oren-Nayar and the measured tables would be a second implementation to verify; the double
  build's error there is bounded only by these closed-form cases and by its agreement with
  float.

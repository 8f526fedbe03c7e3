#!/bin/sh
# 5. The conformance suite's power: sample and cell counts of the
# chi-square against the fraction of runs that catch a planted pdf error
# (tradeoff/power.c), and the time of one test.
. "$TRADEOFF_DIR/lib.sh"
tr_need "$MT_TRADEOFF/power"
if [ "$QUICK" = 1 ]; then runs=20; maxn=1000000; else runs=50; maxn=4000000; fi
"$MT_TRADEOFF/power" $runs $maxn >"$OUT/5-power.out" || tr_die "$MT_TRADEOFF/power failed"
grep -v '^#' "$OUT/5-power.out" >"$OUT/5-power.csv"
alpha=$(awk '$2 == "alpha_per_test" { print $3 }' "$OUT/5-power.out")
tests=$(awk '$2 == "tests" { print $3 }' "$OUT/5-power.out")
rm -f "$OUT/5-power.out"
pw() { awk -F, -v c="$1" -v n="$2" -v e="$3" '$1 == c && $2 == n && $3 + 0 == e + 0 { printf "%.2f\n", $6 }' "$OUT/5-power.csv"; }
# the fewest samples that catch eps in at least 90% of the runs, with cells c
least() {
    awk -F, -v c="$1" -v e="$2" 'NR > 1 && $1 == c && $3 + 0 == e + 0 && $6 >= 0.9 && (m == "" || $2 + 0 < m) { m = $2 + 0 }
        END { print (m == "" ? "more than any tried" : m) }' "$OUT/5-power.csv"
}
tsamp() { tr_g3 "$(awk -F, -v n="$1" '$2 == n { print $7; exit }' "$OUT/5-power.csv")"; }
tcub() { tr_g3 "$(awk -F, -v c="$1" '$1 == c { print $8; exit }' "$OUT/5-power.csv")"; }
fp=$(awk -F, 'NR > 1 && $3 + 0 == 0 { d += $5; r += $4 } END { printf "%d of %d", d, r }' "$OUT/5-power.csv")

# one wide table per cell count: samples, then the power for each eps
for c in 16x17 32x33 100x101; do
    awk -F, -v c="$c" 'NR > 1 && $1 == c { p[$2, $3 + 0] = $6; if (!($2 in seen)) { seen[$2] = 1; ns[++k] = $2 } }
        END { print "samples,power_0,power_0.005,power_0.01,power_0.02,power_0.05"
              for (i = 1; i <= k; ++i) printf "%s,%s,%s,%s,%s,%s\n", ns[i], p[ns[i], 0], p[ns[i], 0.005], p[ns[i], 0.01], p[ns[i], 0.02], p[ns[i], 0.05] }' \
        "$OUT/5-power.csv" >"$OUT/5-power-$c.csv"
done

plot=$(tr_plot 5-power "Chi-square power against the sample count" "5-power-32x33.csv, 5-power-100x101.csv" "
set title 'Conformance chi-square: power to detect a planted pdf error, $runs seeds per point'
set xlabel 'samples per test (per incoming direction)'
set ylabel 'fraction of runs that fail the test (power)'
eval logx
set xrange [8e3:5e6]
set yrange [-0.02:1.02]
set key top left
set arrow from 1e5, graph 0 to 1e5, graph 1 nohead dt 2 lc rgb '#444444'
set label 'make check: 1e5, 32x33 cells' at 1e5, graph 0.5 right offset -0.5,0 font ',9'
set arrow from 4e6, graph 0 to 4e6, graph 1 nohead dt 2 lc rgb '#444444'
set label 'check-full: 4e6, 100x101' at 4e6, graph 0.4 right offset -0.5,0 font ',9'
plot for [i = 1:4] '5-power-32x33.csv' using 1:(column(i + 2)) \\
         title sprintf('pdf error %s%%, 32x33 cells', word('0.5 1 2 5', i)) ls i, \\
     for [i = 1:4] '5-power-100x101.csv' using 1:(column(i + 2)) \\
         title sprintf('%s%%, 100x101 cells', word('0.5 1 2 5', i)) ls i dt 2 pt 6, \\
     '5-power-32x33.csv' using 1:2 title 'no error, 32x33 (false alarms)' ls 8
") || status=1

cat >"$OUT/5-power.md" <<EOF
## 5. The conformance suite's power

The suite's chi-square (conformance/sampling.c: equal-area cells in phi and z over the whole
sphere, expected counts by adaptive cubature in double, cells below 5 expected pooled) decides
at the per-test significance $alpha: 0.01 for the whole of \`make check\`'s run, Sidak over its
$tests tests. \`make check\` runs it with 100000 samples per incoming direction and 32x33 cells,
\`make check-full\` with 4000000 and 100x101, the sanitizer builds (\`--lite\`) with 20000 and
16x17. Measured here (\`tradeoff/power.c\`, run by \`tradeoff/5-power.sh\`): how often it catches
a pdf whose shape is wrong by a relative 0.5% to 5% (the claimed pdf p (1 + eps sin phi), the
same integral, so only the chi-square can see it), over $runs seeds, for pbrt-v2's default
plastic (Lambertian + Blinn 10, corrected mode) at 45 degrees.

$plot

- With \`make check\`'s settings (1e5 samples, 32x33 cells) the power is $(pw 32x33 100000 0.05) for a
  5% error, $(pw 32x33 100000 0.02) for 2%, $(pw 32x33 100000 0.01) for 1% and $(pw 32x33 100000 0.005) for 0.5%. With
  \`check-full\`'s (4e6, 100x101): $(if [ -n "$(pw 100x101 4000000 0.05)" ]; then
      echo "$(pw 100x101 4000000 0.05), $(pw 100x101 4000000 0.02), $(pw 100x101 4000000 0.01) and $(pw 100x101 4000000 0.005) (4e6 samples are what 2% needs)"
  else echo "not measured (this run stopped at $maxn samples)"; fi).
- Samples needed for a power of 0.9 with 32x33 cells: 5%: $(least 32x33 0.05), 2%: $(least 32x33 0.02),
  1%: $(least 32x33 0.01), 0.5%: $(least 32x33 0.005); with 100x101 cells: 5%: $(least 100x101 0.05),
  2%: $(least 100x101 0.02), 1%: $(least 100x101 0.01), 0.5%: $(least 100x101 0.005). The
  samples needed grow roughly as 1/eps^2 (the chi-square's noncentrality is about n eps^2);
  finer cells cost power at a fixed sample count for an error this smooth (more degrees of
  freedom for the same deviation), and pay off only for errors confined to small regions.
  \`make check\`'s chi-square catches gross errors (a wrong lobe, a sampler ignoring its
  parameter, a pdf off by tens of percent somewhere); a smooth error of a few percent needs
  \`check-full\` or more.
- False alarms (no planted error): $fp runs over every setting, as the significance promises.
- Cost of one test: sampling $(tsamp 100000) s at 1e5 samples, $(tsamp 1000000) s at 1e6$( [ -n "$(tsamp 4000000)" ] && echo ", $(tsamp 4000000) s at 4e6"); the
  expected counts' cubature $(tcub 16x17) s for 16x17 cells, $(tcub 32x33) s for 32x33 and $(tcub 100x101) s for 100x101
  (CPU time of one thread, float build).

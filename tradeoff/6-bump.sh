#!/bin/sh
# 6. Bump mapping: the finite-difference step against the shading normal's
# error (tradeoff/bump.c), float and double builds, and its cost.
. "$TRADEOFF_DIR/lib.sh"
tr_need "$MT_TRADEOFF/bump" "$MT_TRADEOFF_DOUBLE/bump"
if [ "$QUICK" = 1 ]; then npts=256; else npts=4096; fi
for p in float double; do
    if [ $p = float ]; then bin=$MT_TRADEOFF/bump; else bin=$MT_TRADEOFF_DOUBLE/bump; fi
    "$bin" $npts >"$OUT/6-bump-$p.out" || tr_die "$bin failed"
    grep -v '^#' "$OUT/6-bump-$p.out" >"$OUT/6-bump-$p.csv"
done
cost() { awk -v k="$2" '$1 == "#" && $2 == "cost" && $3 == k { print $4 }' "$OUT/6-bump-$1.out"; }
fb=$(cost float ns_per_bump); ft=$(cost float ns_per_texture_eval)
db=$(cost double ns_per_bump); dt=$(cost double ns_per_texture_eval)
printf 'precision,ns_per_bump,ns_per_texture_eval\nfloat,%s,%s\ndouble,%s,%s\n' "$fb" "$ft" "$db" "$dt" >"$OUT/6-bump-cost.csv"
rm -f "$OUT/6-bump-float.out" "$OUT/6-bump-double.out"

# the step of least median error, and the error at pbrt-v2's default step
best() { awk -F, 'NR > 1 && (b == "" || $2 < b) { b = $2; s = $1 } END { printf "%s %s\n", s, b }' "$1"; }
at() { awk -F, -v h="$2" 'NR > 1 && $1 + 0 == h + 0 { print $'"$3"' }' "$1"; }
set -- $(best "$OUT/6-bump-float.csv"); fstep=$1; ferr=$2
set -- $(best "$OUT/6-bump-double.csv"); dstep=$1; derr=$2
dmin=$(awk -F, 'NR == 2 { print $1 }' "$OUT/6-bump-double.csv")
fstep=$(tr_g3 "$fstep"); ferr=$(tr_g3 "$ferr"); derr=$(tr_g3 "$derr")
if [ "$dstep" = "$dmin" ]; then dbest="smaller than any tried: at $(tr_g3 "$dstep") the median error is $derr rad"
else dbest="**$(tr_g3 "$dstep")** ($derr rad)"; fi
f01=$(at "$OUT/6-bump-float.csv" 0.01 2); d01=$(at "$OUT/6-bump-double.csv" 0.01 2)
fmax01=$(at "$OUT/6-bump-float.csv" 0.01 3)
drop01=$(at "$OUT/6-bump-double.csv" 0.01 4)
dropbest=$(awk -F, 'NR > 1 && (b == "" || $4 < b) { b = $4 } END { print b }' "$OUT/6-bump-double.csv")
f7=$(at "$OUT/6-bump-float.csv" 1e-07 2)
for v in f01 d01 fmax01 drop01 dropbest f7; do eval "$v=\$(tr_g3 \"\$$v\")"; done

plot=$(tr_plot 6-bump "Bump mapping: shading-normal error against the step" \
    "6-bump-float.csv, 6-bump-double.csv" "
set title 'Bump mapping (pbrt-v2 Material::Bump): normal error against the finite-difference step, $npts points'
set xlabel 'finite-difference step du = dv (texture-space units)'
set ylabel 'angle to the exact normal (radians)'
eval logxy
set xrange [5e-10:0.5]
set key top right
set yrange [*:30]
set arrow from 0.01, graph 0 to 0.01, graph 1 nohead dt 2 lc rgb '#444444'
set label 'pbrt-v2 default 0.01 (no ray differentials)' at 0.01, graph 0.04 right offset -0.5,0 font ',9'
plot '6-bump-float.csv' using 1:2 title 'float build, median' ls 1, \
     '6-bump-float.csv' using 1:3 title 'float build, maximum' ls 1 dt 3 pt 6, \
     '6-bump-double.csv' using 1:2 title 'double build, median' ls 2, \
     '6-bump-double.csv' using 1:3 title 'double build, maximum' ls 2 dt 3 pt 4, \
     '6-bump-double.csv' using 1:4 title 'double, without the d dN/du terms, median' ls 3 dt 2
") || status=1

cat >"$OUT/6-bump.md" <<EOF
## 6. Bump mapping: the finite-difference step

pbrt-v2's \`Material::Bump\` (core/material.cpp; materia \`mt_bump\`, src/bump.c) differentiates
the displacement by a forward difference with step du = (|du/dx| + |du/dy|) / 2, half the
pixel's footprint in u (likewise v), or **0.01** when the ray has no differentials. Measured
here: the angle between the bumped shading normal and the exact normal of the displaced
surface, over $npts points of a unit sphere displaced by d = 0.05 (u + v)(2 - u - v) (built
from materia's own textures: \`scale\` of two \`bilerp\`), for steps from 1e-9 to 0.3, in the
float and the double build (\`tradeoff/bump.c\`, run by \`tradeoff/6-bump.sh\`).

$plot

- The truncation error grows linearly with the step (h/2 |d_uu| in the tangent); below some
  step the rounding of d(u + h) - d(u) takes over and the error grows as 1/h. The float build's
  best step is **$fstep** (median error $ferr rad); the double build's $dbest.
- At pbrt-v2's default 0.01 the median error is $f01 rad in float (maximum $fmax01) and $d01 in
  double: the truncation error, the same in both. At 1e-7, a small footprint, float's error is
  $f7 rad: in float a step below about $fstep only adds rounding error (the footprint of a
  distant, finely textured surface can be that small; a floor on the step would help).
- Without the d dN/du terms (\`MT_BUMP_DROP_DNDU\`, what many renderers omit) the error
  cannot fall below about $dropbest rad (median; $drop01 at 0.01) however small the step: on a
  curved surface that omission, not the step, limits the accuracy.
- Cost (\`6-bump-cost.csv\`, CPU time of one thread): a bump takes $fb ns in float and $db ns in
  double, against $ft ns and $dt ns for one evaluation of this displacement texture: three
  evaluations and the frame, whatever the step.
EOF
exit ${status:-0}

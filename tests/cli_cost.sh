#!/bin/sh
# cli_cost.sh -- ./tile's cost column is the band's true cost at any scale
# the input allows (the weights rounded to the pair's quantum, about
# 2^-52 (m+n) of the graph's largest tile, gave 2.25e15 for 3.41e15 at
# L = 1e15, h = 1, and 0 at 1e20):
#  - --cost area: two equal right triangles with legs L, h apart make a prism
#    whose lateral area, (2 + sqrt 2) L h, is the least any band between
#    them can have (a tile over an edge e has area at least |e| h / 2) and
#    the aligned band's; the band's cost must be that to 1e-12, for L from
#    1e-300 to 1e300 and h from 1 to L, and the mesh row's cost the same;
#  - --cost span: the band's cost against the least over every acceptable
#    path of the pair, by brute force.
BUILD=${BUILD:-build/chk}
. tests/clilib.sh

prism() {   # prism L H: the two triangles, H apart
  printf 'C 3 0\n0 0\n%s 0\n0 %s\nC 3 %s\n0 0\n%s 0\n0 %s\n' "$1" "$1" "$2" "$1" "$1" > "$T/p.contours"
}

for L in 1e-300 1e-20 1e-6 1 1e6 1e15 1e20 1e100 1e300; do
  for h in 1 L; do
    [ "$h" = L ] && h=$L
    prism "$L" "$h"
    if ! "$BUILD/tile" "$T/p.contours" > "$T/out" 2> "$T/err"; then
      bad "L $L, h $h: $(cat "$T/err")"; continue
    fi
    awk -F, -v L="$L" -v h="$h" '
      NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
      $1 == "0" { band = $c["cost"] } $1 == "mesh" { mesh = $c["cost"] }
      END { want = (2 + sqrt(2)) * L * h
            if (want == 0 || want > 1e308) exit 0   # beyond a double: nothing to compare
            d = (band - want) / want; if (d < 0) d = -d
            if (d > 1e-12 || mesh != band) { printf "band %s, mesh %s, want %.17g\n", band, mesh, want; exit 1 } }' "$T/out" > "$T/why" \
      && ok || bad "L $L, h $h: $(cat "$T/why")"
  done
done

# --cost span: a step down from (i, j) adds the span R(i+1) C(j), one across
# R(i) C(j+1); every start row, every order of 3 steps down and 3 across.
for L in 1 1e15 1e20 1e300; do
  prism "$L" 1
  "$BUILD/tile" "$T/p.contours" --cost span > "$T/out" 2> "$T/err"
  awk -F, -v L="$L" '
    function span(i, j,   dx, dy) {   # in units of L, then times L (no overflow at 1e300)
      dx = (rx[i % 3] - cx[j % 3]) / L; dy = (ry[i % 3] - cy[j % 3]) / L
      return L * sqrt(dx * dx + dy * dy + 1 / L / L) }
    BEGIN { rx[0] = 0; ry[0] = 0; rx[1] = L; ry[1] = 0; rx[2] = 0; ry[2] = L
            for (k = 0; k < 3; k++) { cx[k] = rx[k]; cy[k] = ry[k] }
            best = -1
            for (s = 0; s < 3; s++) for (mask = 0; mask < 64; mask++) {
              down = 0; for (b = 0; b < 6; b++) down += int(mask / 2 ^ b) % 2
              if (down != 3) continue
              i = s; j = 0; sum = 0
              for (b = 0; b < 6; b++) { if (int(mask / 2 ^ b) % 2) i++; else j++; sum += span(i, j) }
              if (best < 0 || sum < best) best = sum } }
    NR == 1 { for (k = 1; k <= NF; k++) c[$k] = k; next }
    $1 == "0" { got = $c["cost"] + 0 }
    END { d = (got - best) / best; if (d < 0) d = -d
          if (d > 1e-12) { printf "span cost %.17g, brute force %.17g\n", got, best; exit 1 } }' "$T/out" > "$T/why" \
    && ok || bad "--cost span, L $L: $(cat "$T/why" "$T/err")"
done

summary

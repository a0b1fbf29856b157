#!/bin/sh
# cli_stackscale.sh -- ./tile's stack surface at every scale, end to end:
# tinypatient_0 (several contours
# a slice, holes, caps) scaled by 2^k, x, y and z, from 2^-1000 to 2^900,
# gives the unit-scale report with every value exactly scaled -- z 2^k, cost
# and area 2^2k, volume 2^3k, as printed by %.17g (0 and inf beyond a
# double) -- and every other column the same, the same OBJ faces and every
# vertex 2^k times the unit one, the same notes with their numbers scaled;
# and the union of crossing contours noted in the file's own coordinates.
# Runs the sanitized build in $BUILD.  (tests/test_stackscale.c holds the library to
# the same on more stacks; this is the program's report and files.)
TILE=${BUILD:-build/chk}/tile
. tests/clilib.sh

scale() {   # scale FILE K: every number but the point counts times 2^K; comments kept (lines as in FILE)
  awk -v k="$2" 'BEGIN { f = 2 ^ k } /^#/ || NF == 0 { print; next }
    /^C / { printf "C %s %.17g\n", $2, $3 * f; next } { printf "%.17g %.17g\n", $1 * f, $2 * f }' "$1"
}

# same_words UNIT SCALED K: line by line, word by word, numbers 2^K apart
# (2^2K after the word "cost"), all else equal.
same_words() {
  awk -v k="$3" '
    function num(s) { return s ~ /^-?([0-9]+\.?[0-9]*|\.[0-9]+)(e[-+]?[0-9]+)?$/ }
    NR == FNR { u[FNR] = $0; nu = FNR; next }
    { n = split(u[FNR], a, /[ ()=,;:]+/); m = split($0, b, /[ ()=,;:]+/); if (n != m) { bad = 1; next }
      d = 1
      for (i = 1; i <= n; i++) {
        if (a[i] != b[i]) {
          x = a[i] + 0; for (j = 0; j < d; j++) x *= 2 ^ k
          if (!num(a[i]) || !num(b[i]) || x != b[i] + 0) bad = 1
        }
        d = a[i] == "cost" ? 2 : 1
      } }
    END { exit bad || FNR != nu }' "$1" "$2"
}

# same_report UNIT.csv SCALED.csv K: by column name; z0, z1 scaled by 2^K,
# cost and area by 2^2K, volume by 2^3K (one factor at a time: each product
# but the last exact), every other column the same text.
same_report() {
  awk -v k="$3" -F, '
    NR == FNR { u[FNR] = $0; nu = FNR; next }
    FNR == 1 { nc = split(u[1], h, ","); if (u[1] != $0) bad = 1; next }
    { n = split(u[FNR], a, ","); if (n != NF || n != nc) { bad = 1; next }
      for (i = 1; i <= n; i++) {
        d = h[i] == "z0" || h[i] == "z1" ? 1 : h[i] == "cost" || h[i] == "area" ? 2 : h[i] == "volume" ? 3 : 0
        if (d == 0 || a[i] == "") { if (a[i] != $i) bad = 1; continue }
        x = a[i] + 0; for (j = 0; j < d; j++) x *= 2 ^ k
        if (sprintf("%.17g", x) != $i) { bad = 1; if (!shown++) print "row " FNR ", " h[i] ": " $i ", want " sprintf("%.17g", x) > "/dev/stderr" }
      } }
    END { exit bad || FNR != nu }' "$1" "$2"
}

DATA=tests/data/slicerrt
cp $DATA/tinypatient_0.contours "$T/t.contours"
"$TILE" "$T/t.contours" --caps -o "$T/u.obj" > "$T/u.csv" 2> "$T/u.err" && ok || bad "unit scale: $(cat "$T/u.err")"
for k in -1000 -540 -300 -1 1 300 900; do
  scale $DATA/tinypatient_0.contours $k > "$T/t.contours"
  "$TILE" "$T/t.contours" --caps -o "$T/s.obj" > "$T/s.csv" 2> "$T/s.err" && ok || bad "2^$k: $(cat "$T/s.err")"
  same_report "$T/u.csv" "$T/s.csv" $k 2> "$T/why" && ok || bad "2^$k: the report is not the unit one scaled: $(cat "$T/why")"
  [ "$(grep -c '^component' "$T/s.csv")" -eq 2 ] && ok || bad "2^$k: $(grep -c '^component' "$T/s.csv") components, want 2"
  ! grep -q nan "$T/s.csv" && ok || bad "2^$k: nan in the report"
  [ "$(grep '^f' "$T/u.obj" | md5sum)" = "$(grep '^f' "$T/s.obj" | md5sum)" ] && ok || bad "2^$k: other triangles"
  grep '^v' "$T/u.obj" > "$T/uv"; grep '^v' "$T/s.obj" > "$T/sv"
  same_words "$T/uv" "$T/sv" $k && ok || bad "2^$k: the vertices are not the unit ones scaled"
  same_words "$T/u.err" "$T/s.err" $k && [ "$(wc -l < "$T/u.err")" -eq "$(wc -l < "$T/s.err")" ] && ok ||
    bad "2^$k: other notes: $(head -2 "$T/s.err")"
done

# Two contours crossing on a slice: merged into their union at any scale,
# the note naming the file's coordinates (it was a refusal, as they were).
printf 'C 3 1.25\n0 0\n1 0\n0 1\nC 3 1.25\n0.5 -1\n3 -1\n0.5 0.5\nC 3 2.5\n0 0\n1 0\n0 1\n' > "$T/x0.contours"
cp "$T/x0.contours" "$T/x.contours"
"$TILE" "$T/x.contours" --caps -o "$T/x.obj" > "$T/out" 2> "$T/u.err"; rc=$?
[ $rc -eq 0 ] && grep -q '^mesh,.*,closed,' "$T/out" &&
  [ "$(cat "$T/u.err")" = "tile: $T/x.contours:1: merged 2 overlapping contours on slice z=1.25 into their union (as --union does): the contours at line 1 and line 5: 1 contour (1 new vertices where they cross)" ] &&
  ok || bad "crossing at unit scale: exit status $rc, $(cat "$T/u.err")"
for k in -1060 -1000 1000; do
  scale "$T/x0.contours" $k > "$T/x.contours"
  "$TILE" "$T/x.contours" --caps -o "$T/x.obj" > "$T/out" 2> "$T/s.err"; rc=$?
  [ $rc -eq 0 ] && [ -s "$T/x.obj" ] && grep -q '^mesh,.*,closed,' "$T/out" && ok || bad "crossing at 2^$k: exit status $rc, or output"
  same_words "$T/u.err" "$T/s.err" $k && ok || bad "crossing at 2^$k: $(cat "$T/s.err")"
done
summary

#!/bin/sh
# cli_geom.sh -- ./tile on hard geometry: contours
# that cross themselves are refused with one line naming both segments' lines,
# exit status 1, nothing on stdout and no output file; stacks scaled by 2^k
# tile as at unit scale; the spike's cost is its area.  Runs the sanitized
# build in $BUILD.
TILE=${BUILD:-build/chk}/tile
. tests/clilib.sh

# refused NAME CONTENT EXPECTED-MESSAGE (after "tile: FILE:")
refused() {
  name=$1; printf '%b' "$2" > "$T/$name.contours"
  "$TILE" "$T/$name.contours" -o "$T/$name.ply" --caps > "$T/out" 2> "$T/err"; rc=$?
  [ $rc -eq 1 ] && ok || bad "$name: exit status $rc, expected 1"
  [ "$(wc -l < "$T/err")" -eq 1 ] && ok || bad "$name: stderr is not one line: $(cat "$T/err")"
  [ "$(cat "$T/err")" = "tile: $T/$name.contours:$3; --skip-bad drops such a contour and tiles the rest" ] && ok ||
    bad "$name: stderr '$(cat "$T/err")', expected 'tile: FILE:$3; --skip-bad drops such a contour and tiles the rest'"
  [ ! -s "$T/out" ] && ok || bad "$name: something on stdout: $(head -c 200 "$T/out")"
  [ -z "$(ls "$T" | grep -v '\.contours$' | grep -v '^out$' | grep -v '^err$')" ] && ok ||
    bad "$name: files left: $(ls "$T")"
}

SQ='C 4 1\n0 0\n3 0\n3 3\n0 3\n'
X='the contour crosses itself: the segment from line'
refused bowtie   "C 4 0\n0 0\n1 1\n1 0\n0 1\n$SQ" \
  "1: $X 2 to line 3 crosses the segment from line 4 to line 5 (0.5 0.5)"
refused star73   "C 7 0\n1000 0\n-901 434\n623 -782\n-223 975\n-223 -975\n623 782\n-901 -434\n$SQ" \
  "1: $X 3 to line 4 crosses the segment from line 7 to line 8 (-357.0723684210526 0)"
refused eight    "C 6 0\n0 0\n1 1\n2 0\n2 1\n1 0\n0 1\n$SQ" \
  "1: $X 2 to line 3 crosses the segment from line 6 to line 7 (0.5 0.5)"
refused touching "C 6 0\n0 0\n2 0\n1 1\n2 2\n0 2\n1 1\n$SQ" \
  "1: $X 3 to line 4 touches the segment from line 6 to line 7 (1 1)"
refused throughvertex "C 5 0\n0 0\n2 0\n2 2\n1 0\n0 2\n$SQ" \
  "1: $X 2 to line 3 touches the segment from line 5 to line 6 (1 0)"
refused overlap  "C 6 0\n0 0\n3 0\n3 1\n-1 1\n-1 0\n1 0\n$SQ" \
  "1: $X 2 to line 3 overlaps the segment from line 7 to line 2 (0 0)"
# The second contour, after comments and a repaired duplicate: its own lines.
refused second   "${SQ}# then\nC 5 2\n\n0 0\n1 1\n1 1\n1 0\n0 1\n" \
  "7: $X 9 to line 10 crosses the segment from line 12 to line 13 (0.5 0.5)"
# Exactness: 1e-300 above a segment is off it, on it is on it (a spur's tip
# on an edge: refused; a spike walked out and back alone is a spur, dropped).
refused onsegment "C 7 0\n0 0\n4 0\n4 4\n2 4\n2 0\n2 4\n0 4\n$SQ" \
  "1: $X 5 to line 6 overlaps the segment from line 6 to line 7 (2 0)"
printf "C 4 0\n0 0\n2 0\n1 1e-300\n1 1\n$SQ" > "$T/off.contours"
"$TILE" "$T/off.contours" -q > "$T/out" 2> "$T/err" && ok || bad "a vertex 1e-300 off a segment refused: $(cat "$T/err")"

# Extreme coordinates (item 7): a real stack scaled by 2^k (z too), down to
# 2^-1000 and up to 2^600, and integer stars scaled into subnormals, tile as at
# unit scale: the same node counts, the same triangles, costs exactly 2^k
# (span) or 2^2k (area) apart.
DATA=tests/data/slicerrt
# bands FILE: "cost,area,nodes" of each band row of a report, by column name.
bands() {
  awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
           $1 ~ /^[0-9]+$/ { print $c["cost"] "," $c["area"] "," $c["nodes"] }' "$1"
}
scale() {   # scale FILE K: every number but the point counts times 2^K
  awk -v k="$2" 'BEGIN { f = 2 ^ k } /^C / { printf "C %s %.17g\n", $2, $3 * f; next }
                 { printf "%.17g %.17g\n", $1 * f, $2 * f }' "$1"
}
"$TILE" $DATA/prostate_1.contours -q --cost span --caps -o "$T/u.obj" > "$T/u.csv" 2>&1 || bad "unit scale failed"
"$TILE" $DATA/prostate_1.contours -q --caps > "$T/ua.csv" 2>&1 || bad "unit scale (area) failed"
for k in -1000 -960 600; do
  scale $DATA/prostate_1.contours $k > "$T/s.contours"
  "$TILE" "$T/s.contours" -q --cost span --caps -o "$T/s.obj" > "$T/s.csv" 2> "$T/err" && ok || bad "2^$k: $(cat "$T/err")"
  bands "$T/u.csv" > "$T/ub"; bands "$T/s.csv" > "$T/sb"
  [ -s "$T/ub" ] && paste -d, "$T/ub" "$T/sb" | awk -F, -v k="$k" '{ if ($3 != $6 || $4 != $1 * 2 ^ k) bad = 1 }
      END { exit bad }' && ok || bad "2^$k: span costs or node counts differ from unit scale"
  [ "$(grep '^f' "$T/u.obj" | md5sum)" = "$(grep '^f' "$T/s.obj" | md5sum)" ] && ok || bad "2^$k: other triangles"
  "$TILE" "$T/s.contours" -q --caps > "$T/sa.csv" 2> "$T/err" && ok || bad "2^$k area: $(cat "$T/err")"
  # area: exact where 2^2k stays in range (k = 600: inf), never nan
  bands "$T/ua.csv" > "$T/ub"; bands "$T/sa.csv" > "$T/sb"
  ! grep -q nan "$T/sa.csv" && paste -d, "$T/ub" "$T/sb" | awk -F, -v k="$k" '{
      w = $1 * 2 ^ (2 * k); if ($4 != w && !($4 == "inf" && k > 0) && !($4 == 0 && w < 1e-300)) bad = 1 }
      END { exit bad }' && ok || bad "2^$k: area costs differ from unit scale: $(head -3 "$T/sa.csv")"
done
# Integer stars (exact at any scale) in subnormals: 2^-1060, the largest
# coordinate about 2^-1049; the parallel run there gives the serial result.
awk 'BEGIN { for (c = 0; c < 3; c++) { n = 30 + 7 * c; printf "C %d %d\n", n, 5 * c
               for (i = 0; i < n; i++) { a = 6.283185307179586 * i / n; r = 1000 + 300 * sin(7 * i + c)
                 printf "%d %d\n", r * cos(a) + 50 * c, r * sin(a) } } }' > "$T/i.contours"
"$TILE" "$T/i.contours" -q --caps -o "$T/iu.obj" > "$T/iu.csv" 2> "$T/err" && ok || bad "integer stars: $(cat "$T/err")"
scale "$T/i.contours" -1060 > "$T/is.contours"
"$TILE" "$T/is.contours" -q --caps -o "$T/is.obj" > "$T/is.csv" 2> "$T/err" && ok || bad "2^-1060: $(cat "$T/err")"
bands "$T/iu.csv" > "$T/ub"; bands "$T/is.csv" > "$T/sb"
[ -s "$T/ub" ] && paste -d, "$T/ub" "$T/sb" | awk -F, '{ if ($3 != $6 || $4 != 0 || $5 != 0) bad = 1 } END { exit bad }' && ok ||
  bad "2^-1060: node counts differ or the area (below a double's range) is not 0: $(cat "$T/is.csv")"
[ "$(grep '^f' "$T/iu.obj" | md5sum)" = "$(grep '^f' "$T/is.obj" | md5sum)" ] && ok || bad "2^-1060: other triangles"
"$TILE" "$T/is.contours" -q --cost span > "$T/ser.csv" 2>&1
"$TILE" "$T/is.contours" -q --cost span --procs 4 > "$T/par.csv" 2>&1
bands "$T/ser.csv" > "$T/sb"; bands "$T/par.csv" > "$T/pb"
[ -s "$T/sb" ] && cmp -s "$T/sb" "$T/pb" && ok || bad "parallel at 2^-1060 differs from serial: $(head -3 "$T/par.csv")"
awk -F, 'NR == 1 { exit !($1 > 0 && $1 < 1e-300) }' "$T/sb" && ok || bad "2^-1060 span costs: $(cat "$T/ser.csv")"
# Decimal scales (rounded): accepted, no nan, span costs within 1e-12.
for f in 1e300 1e-300; do
  awk -v f="$f" '/^C / { printf "C %s %.17g\n", $2, $3 * f; next } { printf "%.17g %.17g\n", $1 * f, $2 * f }' \
    $DATA/prostate_1.contours > "$T/d.contours"
  "$TILE" "$T/d.contours" -q --cost span --caps > "$T/d.csv" 2> "$T/err" && ok || bad "$f: $(cat "$T/err")"
  bands "$T/u.csv" > "$T/ub"; bands "$T/d.csv" > "$T/db"
  ! grep -q nan "$T/d.csv" && paste -d, "$T/ub" "$T/db" | awk -F, -v f="$f" '{
      r = $4 / f / $1 - 1; if (r < 0) r = -r; if (r > 1e-12) bad = 1 } END { exit bad }' && ok ||
    bad "$f: span costs differ from unit scale: $(head -3 "$T/d.csv")"
done

# The quantum (item 9): the spike's cost equals its area to 1e-12 (was 3.4e-4),
# on the paper's plain band.
printf 'C 4 0\n0 0\n1 0\n0.5 3e11\n0 1\nC 4 1\n0 0\n1 0\n1 1\n0 1\n' > "$T/spike.contours"
"$TILE" "$T/spike.contours" --band plain > "$T/spike.csv" 2>&1
bands "$T/spike.csv" | awk -F, 'NR == 1 { d = ($1 - $2) / $2; if (d < 0) d = -d; exit !(d < 1e-12 && $2 > 3.62e11) }' && ok ||
  bad "spike: cost and area differ: $(cat "$T/spike.csv")"

# A span used twice (item 8): the issue's sliver (50 points on a diagonal near
# 1e8, one 1e-8 off it) under a 20-gon of radius 100 one unit up, off to one
# side, on the paper's plain band.  The note names the band and the span (not
# with -q); the spans column says 1 either way, and the mesh is closed (the
# band that uses no span twice).
awk 'BEGIN { print "C 51 0"; for (i = 0; i < 50; i++) printf "%.17g %.17g\n", 1e8 + i, 1e8 + i
             print "100000000 100000000.00000001"; print "C 20 1"
             for (k = 0; k < 20; k++) { a = 6.283185307179586 * k / 20 + 0.1
               printf "%.17g %.17g\n", 1e8 + 100 + 100 * cos(a), 1e8 + 100 + 100 * sin(a) } }' > "$T/sliver.contours"
"$TILE" "$T/sliver.contours" --cost span --band plain > "$T/sl.csv" 2> "$T/err" && ok || bad "sliver refused: $(cat "$T/err")"
grep -q "^tile: $T/sliver.contours:1: the band from this contour (slice z=0) to the slice z=1: its optimum (cost [0-9.]*) uses the span from (100000049 100000049) to ([0-9.]* [0-9.]*) twice" "$T/err" && ok ||
  bad "sliver: no note naming the span: $(cat "$T/err")"
"$TILE" "$T/sliver.contours" --cost span --band plain -q > "$T/slq.csv" 2> "$T/err"
[ ! -s "$T/err" ] && ok || bad "sliver -q: stderr $(cat "$T/err")"
awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next } $1 == "0" { s = $c["spans"] } $1 == "mesh" { j = $c["junction"] }
         END { exit !(s == 1 && j == "closed") }' "$T/slq.csv" && ok || bad "sliver: spans or junction: $(cat "$T/slq.csv")"

summary

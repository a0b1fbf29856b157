#!/bin/sh
# cli_plot.sh -- build/plot: line charts and the surface picture are
# well-formed SVG with what was asked for; bad usage and bad input fail
# cleanly; the same input gives the same bytes.
PLOT=${BUILD:-build/chk}/plot
. tests/clilib.sh

cat > "$T/a.csv" <<'CSV'
points,procs,alloc,speedup,model
100,1,half,1.0,1.0
100,2,half,1.5,1.9
100,3,half,2.0,2.6
200,1,half,1.0,1.0
200,3,half,2.5,2.8
200,2,half,1.8,1.9
100,2,size,9,9
CSV
"$PLOT" lines "$T/a.csv" -x procs -y speedup --series points --where alloc=half --title "T <&>" --yzero -o "$T/a.svg" && ok || bad "lines failed"
head -1 "$T/a.svg" | grep -q '^<svg xmlns="http://www.w3.org/2000/svg"' && tail -1 "$T/a.svg" | grep -q '^</svg>$' && ok || bad "not an SVG document"
[ "$(grep -c '<polyline' "$T/a.svg")" -eq 2 ] && ok || bad "expected 2 lines (points 100 and 200)"
grep -q '>points=100<' "$T/a.svg" && grep -q '>points=200<' "$T/a.svg" && ok || bad "legend"
grep -q 'T &lt;&amp;&gt;' "$T/a.svg" && ok || bad "title not escaped"
# markers (open: white inside): 2 lines of 3 points, and one a legend entry
[ "$(grep -c 'fill="white" stroke-width="1.5"' "$T/a.svg")" -eq 8 ] && ok || bad "the size row should be filtered out (6 markers and 2 in the legend)"
# points sorted by x: 200's rows come 1, 3, 2 in the file, its line 1, 2, 3 left to right
grep '<polyline' "$T/a.svg" | sed -n 2p | sed 's/.*points="//; s/".*//' | tr ' ' '\n' | cut -d, -f1 |
  awk 'NR > 1 && $1 <= last { bad = 1 } { last = $1 } END { exit bad || NR != 3 }' && ok || bad "a line's points are not in x order"
"$PLOT" lines "$T/a.csv" -x procs -y speedup,model --series points --labels sim,model -o "$T/b.svg" && [ "$(grep -c 'stroke-dasharray' "$T/b.svg")" -ge 2 ] && grep -q '>points=100, model<' "$T/b.svg" && ok || bad "two y columns"
"$PLOT" lines "$T/a.csv" -x procs -y speedup --series points --where alloc=half --title "T <&>" --yzero -o "$T/a2.svg" && cmp -s "$T/a.svg" "$T/a2.svg" && ok || bad "two runs differ"
# errors
"$PLOT" lines "$T/a.csv" -x nope -y speedup -o "$T/c.svg" 2> "$T/err"; [ $? -eq 1 ] && grep -q "its header has no column 'nope' (-x)" "$T/err" && [ ! -e "$T/c.svg" ] && ok || bad "unknown column"
"$PLOT" lines "$T/missing.csv" -x procs -y speedup -o "$T/c.svg" 2> "$T/err"; [ $? -eq 1 ] && grep -q 'cannot open' "$T/err" && ok || bad "missing CSV"
printf 'a,b\n1,2,3\n' > "$T/bad.csv"
"$PLOT" lines "$T/bad.csv" -x a -y b -o "$T/c.svg" 2> "$T/err"; [ $? -eq 1 ] && grep -q 'bad.csv:2: 3 fields' "$T/err" && ok || bad "ragged CSV: $(cat "$T/err")"
for args in "" "frob" "lines" "lines $T/a.csv -x procs" "surface" "lines $T/a.csv -x procs -y speedup --bogus 1 -o $T/c.svg"; do
  # shellcheck disable=SC2086
  "$PLOT" $args > /dev/null 2> "$T/err"; [ $? -eq 2 ] && grep -q '^usage: plot' "$T/err" && ok || bad "usage '$args'"
done
# the surface of a real stack, with caps
"$PLOT" surface tests/data/slicerrt/tinypatient_1.contours --caps --title glass -o "$T/s.svg" && ok || bad "surface failed"
[ "$(grep -c '<polygon points=' "$T/s.svg")" -gt 10 ] && [ "$(grep -c '<polygon fill="none"' "$T/s.svg")" -eq 3 ] && ok || bad "surface: triangles and 3 contours expected"
# several contours a slice (tinypatient_0: up to 4, with holes): the surface
# ./tile makes, as many triangles as its mesh row says, every contour drawn
TILE=$(dirname "$PLOT")/tile
tp=tests/data/slicerrt/tinypatient_0.contours
"$PLOT" surface $tp --caps -o "$T/s2.svg" && ok || bad "surface of several contours a slice failed"
want=$("$TILE" $tp --caps -q | awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "n") c = i } $1 == "mesh" { print $c }')
[ -n "$want" ] && grep -q "the surface tilesim derives ($want triangles)" "$T/s2.svg" &&
  [ "$(grep -c '<polygon fill="none"' "$T/s2.svg")" -eq "$(grep -c '^C ' $tp)" ] && ok ||
  bad "tinypatient_0: $want triangles (./tile) and $(grep -c '^C ' $tp) contours expected"
# an ROI of a DICOM RT structure set: the surface ./tile makes of it, its
# notes as ./tile words them; without --roi, or an unknown ROI: one line, exit 1
dcm=tests/data/rtstruct/dicompyler_rtss.dcm
"$PLOT" surface $dcm --roi 'Lt Lung' --caps -o "$T/lung.svg" 2> "$T/perr" && ok || bad "plot surface --roi 'Lt Lung' failed"
want=$("$TILE" $dcm --roi 'Lt Lung' --caps -q | awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "n") c = i } $1 == "mesh" { print $c }')
"$TILE" $dcm --roi 'Lt Lung' --caps -o "$T/lung.obj" 2> "$T/terr" > /dev/null
[ -n "$want" ] && grep -q "the surface tilesim derives ($want triangles)" "$T/lung.svg" &&
  [ "$(grep -c '<polygon fill="none"' "$T/lung.svg")" -eq "$("$TILE" $dcm --list | awk -F, '$2 == "Lt Lung" { print $4 }')" ] &&
  [ "$(sed 's/^plot: //' "$T/perr")" = "$(sed 's/^tile: //' "$T/terr")" ] && ok ||
  bad "Lt Lung: $want triangles and ./tile's notes expected: $(head -c 300 "$T/perr")"
"$PLOT" surface $dcm -o "$T/n.svg" 2> "$T/err"; [ $? -eq 1 ] && [ "$(wc -l < "$T/err")" -eq 1 ] && grep -q 'name the ROI to draw with --roi' "$T/err" && [ ! -e "$T/n.svg" ] && ok || bad "DICOM without --roi: $(cat "$T/err")"
"$PLOT" surface $dcm --roi Nope -o "$T/n.svg" 2> "$T/err"; [ $? -eq 1 ] && [ "$(wc -l < "$T/err")" -eq 1 ] && grep -q "no ROI named or numbered 'Nope'" "$T/err" && [ ! -e "$T/n.svg" ] && ok || bad "unknown ROI: $(cat "$T/err")"
"$PLOT" surface $tp --roi 1 -o "$T/n.svg" 2> "$T/err"; [ $? -eq 2 ] && grep -q -- '--roi is for a DICOM RT structure set' "$T/err" && [ ! -e "$T/n.svg" ] && ok || bad "--roi on a contour file: $(cat "$T/err")"
# a stack ./tile refuses (a contour crossing itself; two crossing on a slice
# are merged into their union now): one line, exit 1, no file
printf 'C 4 0\n0 0\n4 4\n4 0\n0 4\nC 4 1\n0 0\n4 0\n4 4\n0 4\n' > "$T/cross.contours"
"$PLOT" surface "$T/cross.contours" -o "$T/s3.svg" 2> "$T/err"; [ $? -eq 1 ] && grep -q 'cross.contours:[0-9]*: .*cross' "$T/err" &&
  [ "$(wc -l < "$T/err")" -eq 1 ] && [ ! -e "$T/s3.svg" ] && ok || bad "bad stack: $(cat "$T/err")"
# -o names an SVG file: another extension is refused with the reason,
# before any work, in every mode; .SVG is fine
for m in "lines $T/a.csv -x procs -y speedup" "surface $tp" "claims plots/claims_map.csv"; do
  for o in x.png x.pdf x; do
    # shellcheck disable=SC2086
    "$PLOT" $m -o "$T/$o" > /dev/null 2> "$T/err"; rc=$?
    ext=${o#x}; ext=${ext#.}
    [ $rc -eq 2 ] && grep -q "^plot: -o takes a file name ending in .svg: the plotter writes SVG only" "$T/err" &&
      { [ -z "$ext" ] || grep -q "not $ext (" "$T/err"; } && [ ! -e "$T/$o" ] && ok || bad "plot $m -o $o: exit $rc, $(cat "$T/err")"
  done
done
"$PLOT" lines "$T/a.csv" -x procs -y speedup -o "$T/up.SVG" 2> "$T/err" && grep -q '^<svg ' "$T/up.SVG" && ok || bad "-o up.SVG: $(cat "$T/err")"
summary

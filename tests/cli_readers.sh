#!/bin/sh
# cli_readers.sh -- ./tile on what planning systems really export:
# every bad contour named in one run and --skip-bad; a contour written three
# times a slice; overlapping pieces merged by default and with --union;
# notes counted and -v; oblique stacks; a structure set copied as text.  Each case re-encoded
# (contours in reverse order, start points rotated, every other one
# reversed) gives the same bytes.  The DICOM files are written by
# tests/test_slicemerge --write and tests/test_oblique --write (the tests'
# own writer, tests/rtwriter.c).  Runs the sanitized build in $BUILD.
B=${BUILD:-build/chk}
TILE=$B/tile
. tests/clilib.sh

"$B/tests/test_slicemerge" --write "$T" && "$B/tests/test_oblique" --write "$T" || bad "the fixtures were not written"

# A .contours stack re-encoded: contours in reverse order, contour b (in
# the output) from its point b mod n, every other one reversed.
reencode() {
  awk '/^C /{ n++; h[n] = $0; np[n] = $2; next } /^[-0-9]/ { p[n, ++k[n]] = $0 }
       END { for (b = 0; b < n; b++) { c = n - b; m = np[c]; print h[c]
               for (j = 0; j < m; j++) { i = (b % 2) ? (b - j) % m : (b + j) % m; if (i < 0) i += m; print p[c, i + 1] } } }' "$1"
}

# ---- Bad contours: CERR-like, 8 of 26 (3 crossings, 5 pinch points) named in
# one run, then one summary; the 3 spurs are repaired, not bad.
"$TILE" "$T/cerr.dcm" --roi GTV -o "$T/c.stl" > "$T/out" 2> "$T/err"; rc=$?
[ $rc -eq 1 ] && [ ! -e "$T/c.stl" ] && [ ! -s "$T/out" ] && [ "$(wc -l < "$T/err")" -eq 9 ] &&
  [ "$(grep -c "contour item [0-9]*: the contour crosses itself: the segment from point [0-9]* to point [0-9]* crosses" "$T/err")" -eq 3 ] &&
  [ "$(grep -c "contour item [0-9]*: the contour crosses itself: the segment from point [0-9]* to point [0-9]* touches" "$T/err")" -eq 5 ] &&
  tail -1 "$T/err" | grep -qx "tile: $T/cerr.dcm: ROI 1 'GTV': 8 of 26 contours cannot be tiled (54 of 135 points), each named above; --skip-bad drops them and tiles the rest" &&
  ! grep -q spur "$T/err" && ok || bad "cerr: exit $rc: $(cat "$T/err")"
"$TILE" "$T/cerr.dcm" --roi GTV --skip-bad --caps -o "$T/c.stl" > "$T/c.csv" 2> "$T/err"; rc=$?
[ $rc -eq 0 ] && [ -s "$T/c.stl" ] && grep -q '^mesh,.*,closed,' "$T/c.csv" &&
  [ "$(grep -c ": dropped, it cannot be tiled: the contour crosses itself" "$T/err")" -eq 8 ] &&
  [ "$(grep -c "dropped a zero-width spur" "$T/err")" -eq 3 ] &&
  grep -qx "tile: $T/cerr.dcm: ROI 1 'GTV': --skip-bad dropped 8 bad contours of 26 (54 of 135 points); the rest are tiled" "$T/err" &&
  ok || bad "cerr --skip-bad: exit $rc: $(cat "$T/err")"
# The same as a stack, and re-encoded: the same rows and mesh.
"$TILE" "$T/cerr.dcm" --roi GTV --contours "$T/cerr.contours" 2> /dev/null
reencode "$T/cerr.contours" > "$T/cerr2.contours"
"$TILE" "$T/cerr.contours" --skip-bad --caps -o "$T/c1.stl" > "$T/c1.csv" 2> "$T/err1"
"$TILE" "$T/cerr2.contours" --skip-bad --caps -o "$T/c2.stl" > "$T/c2.csv" 2> "$T/err2"
cmp -s "$T/c.csv" "$T/c1.csv" && cmp -s "$T/c.stl" "$T/c1.stl" && cmp -s "$T/c1.csv" "$T/c2.csv" &&
  cmp -s "$T/c1.stl" "$T/c2.stl" && [ "$(grep -c dropped "$T/err2")" -eq 12 ] && [ "$(grep -c dropped "$T/err1")" -eq 12 ] &&
  ok || bad "cerr as a stack, re-encoded: other bytes"
"$TILE" "$T/cerr2.contours" > /dev/null 2> "$T/err"
[ "$(wc -l < "$T/err")" -eq 9 ] && ok || bad "cerr re-encoded: not 8 lines and a summary: $(cat "$T/err")"

# ---- The outline three times a slice (Monaco): one kept, one note; the
# mesh has the outline's 12 points a slice; the re-encoded file the same
# bytes; -v names each of the 12 copies dropped.
"$TILE" "$T/monaco.dcm" --roi External --caps -o "$T/e.stl" > "$T/e.csv" 2> "$T/err"; rc=$?
[ $rc -eq 0 ] && grep -q '^mesh,.*,closed,72,140,' "$T/e.csv" && [ "$(wc -l < "$T/err")" -eq 1 ] &&
  grep -q "contour item 2: dropped 12 contours that repeat another of their slice exactly (the same region: another start point, direction or collinear points), this one a copy of contour item 1 on slice z=-5; -v names each" "$T/err" &&
  ok || bad "monaco External: exit $rc: $(cat "$T/err") $(grep mesh "$T/e.csv")"
"$TILE" "$T/monaco_reenc.dcm" --roi External --caps -o "$T/e2.stl" > "$T/e2.csv" 2> /dev/null
cmp -s "$T/e.csv" "$T/e2.csv" && cmp -s "$T/e.stl" "$T/e2.stl" && ok || bad "monaco External re-encoded: other bytes"
"$TILE" "$T/monaco.dcm" --roi External -v > /dev/null 2> "$T/err"
[ "$(grep -c "dropped the contour: it repeats the contour at contour item" "$T/err")" -eq 12 ] && ok ||
  bad "monaco External -v: $(cat "$T/err")"

# ---- Overlapping pieces (Monaco's GTV: five a slice, three overlapping):
# merged into their union by default, one note a slice naming its contours
# (it was refused, --union suggested); with --union the same bytes, one note
# (-v: one a group); re-encoded, the same bytes.
"$TILE" "$T/monaco.dcm" --roi GTV -o "$T/g0.stl" > "$T/g0.csv" 2> "$T/err"; rc=$?
[ $rc -eq 0 ] && grep -q '^mesh,.*,closed,' "$T/g0.csv" && [ "$(wc -l < "$T/err")" -eq 6 ] &&
  [ "$(grep -c "ROI 2 'GTV', contour item [0-9]*: merged 3 overlapping contours on slice z=[-0-9.]* into their union (as --union does): the contours at contour item [0-9]*, contour item [0-9]* and contour item [0-9]*: 1 contour" "$T/err")" -eq 6 ] &&
  [ "$(sed 's/.* on slice z=\([^ ]*\) .*/\1/' "$T/err" | sort -u | wc -l)" -eq 6 ] &&
  ok || bad "monaco GTV without --union: exit $rc: $(cat "$T/err")"
"$TILE" "$T/monaco.dcm" --roi GTV --union --caps -o "$T/g.stl" > "$T/g.csv" 2> "$T/err"; rc=$?
cmp -s "$T/g0.stl" "$T/g.stl" && cmp -s "$T/g0.csv" "$T/g.csv" && ok || bad "monaco GTV: --union other bytes than the default"
[ $rc -eq 0 ] && grep -q '^mesh,.*,closed,' "$T/g.csv" && [ "$(wc -l < "$T/err")" -eq 1 ] &&
  grep -q "merged 18 overlapping contours in 6 groups on 6 slices into their unions: 6 contours, 0 of them holes" "$T/err" &&
  ok || bad "monaco GTV --union: exit $rc: $(cat "$T/err")"
"$TILE" "$T/monaco_reenc.dcm" --roi GTV --union --caps -o "$T/g2.stl" > "$T/g2.csv" 2> /dev/null
cmp -s "$T/g.csv" "$T/g2.csv" && cmp -s "$T/g.stl" "$T/g2.stl" && ok || bad "monaco GTV re-encoded: other bytes"
"$TILE" "$T/monaco.dcm" --roi GTV --union -v > /dev/null 2> "$T/err"
[ "$(grep -c -- "--union: merged the contours at contour item [0-9]*, contour item [0-9]* and contour item [0-9]* on slice z=" "$T/err")" -eq 6 ] &&
  ok || bad "monaco GTV -v: $(cat "$T/err")"
# The union through a .contours stack, re-encoded: the same bytes.
"$TILE" "$T/monaco.dcm" --roi GTV --contours "$T/gtv.contours" 2> /dev/null
reencode "$T/gtv.contours" > "$T/gtv2.contours"
"$TILE" "$T/gtv.contours" --union --caps -o "$T/g3.stl" > "$T/g3.csv" 2> /dev/null
"$TILE" "$T/gtv2.contours" --union --caps -o "$T/g4.stl" > "$T/g4.csv" 2> /dev/null
cmp -s "$T/g.csv" "$T/g3.csv" && cmp -s "$T/g.stl" "$T/g3.stl" && cmp -s "$T/g3.csv" "$T/g4.csv" && cmp -s "$T/g3.stl" "$T/g4.stl" &&
  ok || bad "gtv.contours --union re-encoded: other bytes"
# A union that touches itself: split there, one piece kept off the point by a
# cut of 2^-20 of its edges; the mesh closed (two squares at a corner below a
# triangle that meets the first: the second ends, a slab of its own).
printf 'C 4 0\n0 0\n1 0\n1 1\n0 1\nC 4 0\n1 1\n2 1\n2 2\n1 2\nC 3 1\n0 0\n1 0\n0 1\n' > "$T/pinch.contours"
"$TILE" "$T/pinch.contours" --union -o "$T/p.stl" > "$T/out" 2> "$T/err"; rc=$?
[ $rc -eq 0 ] && [ -s "$T/p.stl" ] && grep -q '^mesh,.*,closed,' "$T/out" &&
  [ "$(head -1 "$T/err")" = "tile: $T/pinch.contours:1: --union: merged the contours at line 1 and line 6 on slice z=0 into their union: 2 contours (0 new vertices where they cross); it touches itself at (1 1), split there (each piece but one off the point by 2^-20 of its edges)" ] &&
  ok || bad "pinch: exit $rc: $(cat "$T/err")"

# ---- Overlapping pieces in a .contours stack: two squares of side 3 on each
# of 5 slices 1.5 apart, the second 1 right and 2 up of the first, both moving
# (0.25, -0.5) a slice.  With the default options: merged into their union
# (it was refused), one note a slice, a closed mesh whose volume is the
# trapezoid rule's on the union's area in closed form (2 s^2 - (s - 1)(s - 2):
# a sheared prism, exact); --union the same bytes.
awk 'BEGIN { s = 3; for (k = 0; k < 5; k++) { z = 1.5 * k; x = 0.25 * k; y = -0.5 * k
  for (j = 0; j < 2; j++) printf "C 4 %s\n%s %s\n%s %s\n%s %s\n%s %s\n", z, x + j, y + 2 * j, x + j + s, y + 2 * j,
                                  x + j + s, y + 2 * j + s, x + j, y + 2 * j + s } }' > "$T/pieces.contours"
"$TILE" "$T/pieces.contours" -o "$T/pc.stl" > "$T/pc.csv" 2> "$T/err"; rc=$?
[ $rc -eq 0 ] && [ "$(wc -l < "$T/err")" -eq 5 ] &&
  ( for k in 0 1 2 3 4; do l=$((10 * k + 1)) z=$(awk -v k=$k 'BEGIN { print 1.5 * k }')
      grep -qxF "tile: $T/pieces.contours:$l: merged 2 overlapping contours on slice z=$z into their union (as --union does): the contours at line $l and line $((l + 5)): 1 contour (2 new vertices where they cross)" "$T/err" || exit 1
    done ) &&
  mesh_volume_is "$T/pc.csv" "$(awk 'BEGIN { s = 3; for (k = 0; k < 5; k++) { z[k] = 1.5 * k; a[k] = 2 * s * s - (s - 1) * (s - 2) }
                                       for (k = 0; k < 4; k++) want += (a[k] + a[k + 1]) / 2 * (z[k + 1] - z[k])
                                       printf "%.17g", want }')" &&
  ok || bad "pieces: exit $rc: $(grep '^mesh' "$T/pc.csv") $(cat "$T/err")"
"$TILE" "$T/pieces.contours" --union -o "$T/pu.stl" > "$T/pu.csv" 2> /dev/null && cmp -s "$T/pc.stl" "$T/pu.stl" &&
  cmp -s "$T/pc.csv" "$T/pu.csv" && ok || bad "pieces --union: other bytes than the default"

# ---- Duplicate points counted, one line a contour; -v one each.
printf 'C 9 0\n0 0\n0 0\n1 0\n1 0\n1 0\n1 1\n1 1\n0 1\n0 0\nC 3 1\n0 0\n1 0\n0 1\n' > "$T/dup.contours"
"$TILE" "$T/dup.contours" > /dev/null 2> "$T/err"
[ "$(cat "$T/err")" = "tile: $T/dup.contours:1: dropped 4 duplicates of the point before (the first at line 3: 0 0)
tile: $T/dup.contours:10: dropped the repeated closing point (0 0)" ] && ok || bad "counted notes: $(cat "$T/err")"
"$TILE" "$T/dup.contours" -v > /dev/null 2> "$T/err"
[ "$(grep -c "dropped a duplicate of the point before" "$T/err")" -eq 4 ] && ok || bad "-v notes: $(cat "$T/err")"

# ---- Oblique: the set tilted 6 degrees, --list says so; the re-encoded
# file gives the same bytes; the note gives the angle.
"$TILE" "$T/oblique.dcm" > "$T/list" 2> /dev/null
[ "$(tail -n +2 "$T/list" | cut -d, -f1,4,6,10 | tr '\n' ' ')" = "1,14,14,oblique 2,34,14,oblique " ] && ok ||
  bad "oblique --list: $(cat "$T/list")"
"$TILE" "$T/oblique.dcm" --roi all --caps -o "$T/o1/" > "$T/o1.csv" 2> "$T/err"; rc=$?
"$TILE" "$T/oblique_reenc.dcm" --roi all --caps -o "$T/o2/" > "$T/o2.csv" 2> /dev/null
[ $rc -eq 0 ] && cmp -s "$T/o1.csv" "$T/o2.csv" && cmp -s "$T/o1/Body.stl" "$T/o2/Body.stl" &&
  cmp -s "$T/o1/Lungs.stl" "$T/o2/Lungs.stl" &&
  [ "$(grep -c "oblique contours: parallel planes tilted 6 degrees from the axial plane (normal 0.05011361480156" "$T/err")" -eq 2 ] &&
  ok || bad "oblique: exit $rc: $(cat "$T/err")"

# ---- A structure set copied as text (every LF turned into CR LF): corrupt
# or truncated, the byte where it went wrong and the first CR's.
awk 'BEGIN { RS = "\n"; ORS = "\r\n" } { print }' "$T/axial.dcm" | head -c "$(( $(wc -c < "$T/axial.dcm") + $(tr -cd '\n' < "$T/axial.dcm" | wc -c) ))" > "$T/crlf.dcm"
"$TILE" "$T/crlf.dcm" > "$T/out" 2> "$T/err"; rc=$?
first=$(od -An -v -tx1 "$T/crlf.dcm" | tr -s ' \n' '\n\n' | grep -v '^$' | grep -n '^0d$' | head -1 | cut -d: -f1)
[ $rc -eq 1 ] && [ "$(wc -l < "$T/err")" -eq 1 ] && grep -q "^tile: $T/crlf.dcm: byte [0-9]*: " "$T/err" &&
  grep -q "corrupt or truncated" "$T/err" && grep -q "the first CR at byte $((first - 1))): LF turned into CR LF" "$T/err" &&
  ok || bad "CR LF: exit $rc: $(cat "$T/err") (first CR at $((first - 1)))"

# ---- Help: every new option.
"$TILE" --help > "$T/help"
for o in --skip-bad --union "-v, --verbose"; do grep -q -- "^  $o " "$T/help" && ok || bad "tile --help lacks $o"; done
if [ -x "$B/plot" ]; then
  "$B/plot" --help > "$T/help"
  for o in --skip-bad --union "-v, --verbose"; do grep -q -- "^  $o " "$T/help" && ok || bad "plot --help lacks $o"; done
fi

summary

#!/bin/sh
# cli_faithful.sh -- ./tile on what planning systems export, with the default
# options: closed meshes whose bands', caps' and mesh's volumes add
# up, --no-caps open with no volumes, --roi all writing every ROI that tiles
# (exit status 3 when some are refused, a line counting both), oblique planes
# at two decimals, Pinnacle-like degenerate contours, holes on their outer
# contour's boundary, a region touching itself, overlapping pieces merged
# (their union's volume in closed form), branchings; --procs the same
# bytes as the serial tiler.  The DICOM files are written by
# tests/test_faithful --write (the tests' own writer, tests/rtwriter.c).
# Runs the sanitized build in $BUILD.
B=${BUILD:-build/chk}
TILE=$B/tile
. tests/clilib.sh

"$B/tests/test_faithful" --write "$T" || bad "the fixtures were not written"
F=$T/faithful

# ---- --roi all: every ROI that tiles written, the refused named, exit 3.
"$TILE" ${F}_mixed.dcm --roi all -o "$T/m/" > "$T/m.csv" 2> "$T/err"; rc=$?
[ $rc -eq 3 ] && [ "$(ls "$T/m" | tr '\n' ' ')" = "Good.stl Good_too.stl Overlap.stl " ] &&
  grep -qxF "tile: ${F}_mixed.dcm: 3 of 6 ROIs tiled, 2 refused (ROI 2 'Crossing', ROI 5 'Flat': each said above), 1 with nothing to tile" "$T/err" &&
  grep -q "ROI 2 'Crossing', contour item 2: the contour crosses itself.*; skipped$" "$T/err" &&
  grep -q "ROI 4 'Overlap', contour item 1: merged 2 overlapping contours on slice z=0 into their union (as --union does): the contours at contour item 1 and contour item 2: 1 contour" "$T/err" &&
  grep -q "ROI 5 'Flat', contour item 1: the only contour lies on one slice" "$T/err" &&
  [ "$(grep -c '^[0-9]*,[^,]*,mesh,' "$T/m.csv")" -eq 3 ] && [ "$(grep -c '^roi_number,name,band' "$T/m.csv")" -eq 1 ] &&
  ok || bad "--roi all: exit $rc: $(cat "$T/err")"
"$TILE" ${F}_mixed.dcm --roi all -q -o "$T/q/" > /dev/null 2> "$T/err"; rc=$?
[ $rc -eq 3 ] && [ "$(grep -c 'skipped$' "$T/err")" -eq 2 ] && grep -q "3 of 6 ROIs tiled, 2 refused" "$T/err" &&
  ! grep -q "nothing to tile; skipped" "$T/err" && ok || bad "--roi all -q: exit $rc: $(cat "$T/err")"
"$TILE" ${F}_mixed.dcm --roi all --thickness 1 -o "$T/t/" > /dev/null 2> "$T/err"; rc=$?
[ $rc -eq 3 ] && [ "$(ls "$T/t" | wc -l)" -eq 4 ] && grep -q "4 of 6 ROIs tiled, 1 refused" "$T/err" && ok ||
  bad "--roi all --thickness: exit $rc: $(cat "$T/err")"
"$TILE" ${F}_mixed.dcm --roi Crossing -o "$T/o.stl" > "$T/out" 2> "$T/err"; rc=$?
[ $rc -eq 1 ] && [ ! -e "$T/o.stl" ] && [ ! -s "$T/out" ] && ok || bad "one refused ROI: exit $rc"

# ---- Closed by default; the rows' volumes add up; --caps the same bytes;
# --no-caps open, its volume fields empty.
"$TILE" ${F}_mixed.dcm --roi Good -o "$T/g.obj" > "$T/g.csv" 2> "$T/err" && ok || bad "Good: $(cat "$T/err")"
"$TILE" ${F}_mixed.dcm --roi Good --caps -o "$T/g2.obj" > "$T/g2.csv" 2>&1 && cmp -s "$T/g.csv" "$T/g2.csv" &&
  cmp -s "$T/g.obj" "$T/g2.obj" && ok || bad "--caps differs from the default"
awk -F, '$1 ~ /^[0-9]+$/ || $1 == "cap" { s += $13 } $1 == "mesh" { m = $13; j = $7 } $1 == "component" { c += $13 }
         END { d = s - m; if (d < 0) d = -d; e = c - m; if (e < 0) e = -e; exit !(j == "closed" && m > 0 && d <= 1e-9 * m && e <= 1e-9 * m) }' "$T/g.csv" &&
  ok || bad "the volumes do not add up: $(grep -v '^[0-9]' "$T/g.csv")"
"$TILE" ${F}_mixed.dcm --roi Good --no-caps > "$T/n.csv" 2> "$T/err" &&
  awk -F, 'NR > 1 && $13 != "" { bad = 1 } $1 == "mesh" && $7 != "open" { bad = 1 } $1 == "cap" { bad = 1 } END { exit bad }' "$T/n.csv" &&
  ok || bad "--no-caps: $(cat "$T/n.csv")"

# ---- Oblique planes at two decimals: tiled; the bent contour refused.
"$TILE" ${F}_oblique.dcm --roi all -o "$T/ob/" > "$T/ob.csv" 2> "$T/err"; rc=$?
[ $rc -eq 3 ] && [ "$(ls "$T/ob" | tr '\n' ' ')" = "Cyl.stl Cyl_again.stl " ] &&
  grep -q "ROI 3 'Bent', contour item 6: not planar (its points spread 0.3.* mm off their best plane, more than the 0.01.* mm their precision allows)" "$T/err" &&
  [ "$(grep -c 'oblique contours: parallel planes tilted [56]\.[0-9]* degrees' "$T/err")" -eq 2 ] && ok || bad "oblique: exit $rc: $(cat "$T/err")"
"$TILE" ${F}_oblique35.dcm --roi Cyl > "$T/o35.csv" 2> "$T/err" && grep -q 'tilted 26\.7[0-9]* degrees' "$T/err" &&
  grep -q '^mesh,.*,closed,' "$T/o35.csv" && ok || bad "oblique 35: $(cat "$T/err")"

# ---- Pinnacle-like: 84 degenerate contours dropped, one note; -v one each;
# the mesh the clean tube's.
"$TILE" ${F}_pinnacle.dcm --roi Urethra -o "$T/u.obj" > /dev/null 2> "$T/err" &&
  [ "$(grep -c degenerate "$T/err")" -eq 1 ] &&
  grep -q "ROI 1 'Urethra', contour item 1: dropped 84 degenerate contours of 96 (168 points: single points, two points or all collinear, no area)" "$T/err" &&
  ok || bad "Pinnacle-like: $(cat "$T/err")"
"$TILE" ${F}_pinnacle.dcm --roi Urethra -v > /dev/null 2> "$T/err" && [ "$(grep -c 'dropped a degenerate contour' "$T/err")" -eq 84 ] &&
  ok || bad "Pinnacle-like -v: $(grep -c 'dropped a degenerate' "$T/err") notes"
"$TILE" ${F}_pinnacle.dcm --roi 'Urethra clean' -q -o "$T/u2.obj" > /dev/null && cmp -s "$T/u.obj" "$T/u2.obj" && ok ||
  bad "Pinnacle-like: another mesh than the clean tube's"

# ---- Holes on their outer contour's boundary: kept, the same mesh with
# --union; the region's volume.
for r in Notched:22200 Pinched:23250; do
  n=${r%:*} v=${r#*:}
  "$TILE" ${F}_holes.dcm --roi $n -q -o "$T/h1.stl" > "$T/h1.csv" 2> "$T/err" &&
    "$TILE" ${F}_holes.dcm --roi $n -q --union -o "$T/h2.stl" > "$T/h2.csv" && cmp -s "$T/h1.stl" "$T/h2.stl" &&
    awk -F, -v v=$v '$1 == "mesh" { d = $13 - v; if (d < 0) d = -d; exit !($7 == "closed" && d < 1e-9 * v) }' "$T/h1.csv" &&
    ok || bad "$n: $(grep '^mesh' "$T/h1.csv") $(cat "$T/err")"
done
# ---- A region touching itself: split, with --union or without (one note a
# slice without; it was refused), the same bytes.
"$TILE" ${F}_corner.dcm --roi Corner --union -o "$T/c.stl" > "$T/c.csv" 2> "$T/err" && grep -q 'touches itself, split' "$T/err" &&
  grep -q '^mesh,.*,closed,' "$T/c.csv" && ok || bad "corner --union: $(cat "$T/err")"
"$TILE" ${F}_corner.dcm --roi Corner -o "$T/c0.stl" > "$T/c0.csv" 2> "$T/err"; rc=$?
[ $rc -eq 0 ] && cmp -s "$T/c.stl" "$T/c0.stl" && cmp -s "$T/c.csv" "$T/c0.csv" && [ "$(wc -l < "$T/err")" -eq 6 ] &&
  [ "$(grep -c "ROI 1 'Corner', contour item [0-9]*: merged 2 overlapping contours on slice z=[0-9]* into their union (as --union does): .*; it touches itself at (10 10), split there" "$T/err")" -eq 6 ] &&
  ok || bad "corner: exit $rc: $(cat "$T/err")"

# ---- Overlapping pieces: two squares of side 4 a slice, 4 slices 2 apart,
# the second 2 right and 1 up of the first, both moving (1, 0.5) a slice:
# merged into their union by default (it was refused), one note a slice; the
# closed mesh's volume the trapezoid rule's on the union's area in closed
# form (2 s^2 - (s - 2)(s - 1) each slice: a sheared prism, exact); --union
# the same bytes.
"$TILE" ${F}_pieces.dcm --roi Pieces -o "$T/pc.stl" > "$T/pc.csv" 2> "$T/err"; rc=$?
[ $rc -eq 0 ] && [ "$(wc -l < "$T/err")" -eq 4 ] &&
  ( for z in 0 2 4 6; do
      [ "$(grep -c "ROI 1 'Pieces', contour item [0-9]*: merged 2 overlapping contours on slice z=$z into their union (as --union does): the contours at contour item [0-9]* and contour item [0-9]*: 1 contour (2 new vertices where they cross)$" "$T/err")" -eq 1 ] || exit 1
    done ) &&
  mesh_volume_is "$T/pc.csv" "$(awk 'BEGIN { s = 4; for (k = 0; k < 4; k++) { z[k] = 2 * k; a[k] = 2 * s * s - (s - 2) * (s - 1) }
                                       for (k = 0; k < 3; k++) want += (a[k] + a[k + 1]) / 2 * (z[k + 1] - z[k])
                                       printf "%.17g", want }')" &&
  ok || bad "pieces: exit $rc: $(grep '^mesh' "$T/pc.csv") $(cat "$T/err")"
"$TILE" ${F}_pieces.dcm --roi Pieces --union -o "$T/pu.stl" > "$T/pu.csv" 2> /dev/null && cmp -s "$T/pc.stl" "$T/pu.stl" &&
  cmp -s "$T/pc.csv" "$T/pu.csv" && ok || bad "pieces --union: other bytes than the default"

# ---- Branchings: one contour under six; no bridge across a wall: a join
# dropped, named, the mesh closed.  --procs: the serial bytes.
for r in Row Grid Walled; do
  "$TILE" ${F}_branch.dcm --roi $r -o "$T/b.obj" > "$T/b.csv" 2> "$T/err" && grep -q '^mesh,.*,closed,' "$T/b.csv" && ok ||
    bad "$r: $(cat "$T/err")"
done
grep -q "ROI 3 'Walled', contour item 2: not joined to the contour at contour item 4 on slice z=3 (their regions overlap): no bridges can join" "$T/err" &&
  ok || bad "Walled: no note: $(cat "$T/err")"
"$TILE" ${F}_branch.dcm --roi Row -q -o "$T/s.obj" > "$T/s.csv" &&
  "$TILE" ${F}_branch.dcm --roi Row -q --procs 3 -o "$T/p.obj" > "$T/p.csv" && cmp -s "$T/s.obj" "$T/p.obj" &&
  cut -d, -f1-17 "$T/p.csv" | tail -n +2 | cmp -s - "$(tail -n +2 "$T/s.csv" > "$T/s2"; echo "$T/s2")" && ok ||
  bad "--procs 3: not the serial mesh and report"

summary

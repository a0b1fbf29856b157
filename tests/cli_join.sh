#!/bin/sh
# cli_join.sh -- ./tile's joining rules, their notes and the report's joins
# row, and one slice as a slab, from the outside: stacked
# disjoint squares joined by default with one note and apart under --join
# overlap, each contour left apart named; the empty mesh said; the same
# bytes from a file written backwards; --join and --thickness refused with
# the usage line when bad; one slice refused naming --thickness, and with it
# a closed slab whose volume is area x T (a .contours stack and a DICOM ROI,
# judged by the independent mesh checker); the real structure sets: the
# default changes only dicompyler's BODY and Lt Lung (touching contours,
# the same meshes as --join touch), --join overlap gives every real mesh of
# the rule before, BODY under --join nearest is a good mesh; plot surface
# and bench --stack take --join.
TILE=${BUILD:-build/chk}/tile
CHECK=${BUILD:-build/chk}/tests/test_solids
PLOT=${BUILD:-build/chk}/plot
BENCH=${BUILD:-build/chk}/bench
D=tests/data/rtstruct
. tests/clilib.sh

judge() {   # MESH STACK WHAT
  out=$("$CHECK" --check "$1" "$2" 2>&1)
  printf '%s\n' "$out" | tail -1 | grep -q ' 0 failed$' && ok || bad "$3: $(printf '%s\n' "$out" | head -3)"
}
row() { grep "^$1," "$2" | cut -d, -f"$3"; }   # ROW-KIND CSV FIELDS

sq() {   # X Z: the unit square at x = X in the plane z = Z
  printf 'C 4 %s\n%s 0\n%s 0\n%s 1\n%s 1\n' "$2" "$1" "$(($1 + 1))" "$(($1 + 1))" "$1"
}

# ---- Stacked disjoint squares: one square on two slices, one beside it above.
{ sq 0 0; sq 0 1; sq 3 2; sq 3 3; } > "$T/sq.contours"
"$TILE" "$T/sq.contours" --caps -o "$T/sq.obj" > "$T/sq.csv" 2> "$T/err" && ok || bad "squares: $(cat "$T/err")"
[ "$(cat "$T/err")" = "tile: $T/sq.contours:6: joined to the contour at line 11 (slice z=1 to z=2) without overlap: one outer contour on each slice (--join single), gap 2" ] \
  && ok || bad "squares: notes: $(cat "$T/err")"
[ "$(row joins "$T/sq.csv" 7-10)" = "single,1,0,0" ] && [ "$(grep -c '^component,' "$T/sq.csv")" -eq 1 ] \
  && ok || bad "squares: $(cat "$T/sq.csv")"
judge "$T/sq.obj" "$T/sq.contours" "squares"
"$TILE" "$T/sq.contours" --caps -q > "$T/q.csv" 2> "$T/err" && [ ! -s "$T/err" ] && cmp -s "$T/q.csv" "$T/sq.csv" \
  && ok || bad "squares -q: $(cat "$T/err")"
"$TILE" "$T/sq.contours" --caps --join overlap -o "$T/ov.obj" > "$T/ov.csv" 2> "$T/err" && ok || bad "overlap: $(cat "$T/err")"
[ "$(row joins "$T/ov.csv" 7-10)" = "overlap,0,2,0" ] && [ "$(grep -c '^component,' "$T/ov.csv")" -eq 2 ] \
  && grep -qxF "tile: $T/sq.contours:6: no partner for this contour (slice z=1) on slice z=2; nearest there: the contour at line 11, gap 2" "$T/err" \
  && grep -qxF "tile: $T/sq.contours:11: no partner for this contour (slice z=2) on slice z=1; nearest there: the contour at line 6, gap 2" "$T/err" \
  && [ "$(wc -l < "$T/err")" -eq 2 ] && ok || bad "overlap: $(cat "$T/ov.csv" "$T/err")"
judge "$T/ov.obj" "$T/sq.contours" "squares, --join overlap"

# The file backwards, every contour reversed and from another point: the
# same report and mesh.
{ printf 'C 4 3\n3 1\n4 1\n4 0\n3 0\n'; printf 'C 4 2\n4 0\n3 0\n3 1\n4 1\n'
  printf 'C 4 1\n1 1\n1 0\n0 0\n0 1\n'; printf 'C 4 0\n0 1\n1 1\n1 0\n0 0\n'; } > "$T/back.contours"
"$TILE" "$T/back.contours" --caps -q -o "$T/back.obj" > "$T/back.csv" && cmp -s "$T/back.csv" "$T/sq.csv" &&
  cmp -s "$T/back.obj" "$T/sq.obj" && ok || bad "backwards: another report or mesh"

# ---- Nothing joined, no caps: the empty mesh in one line.
{ sq 0 0; sq 3 1; sq 6 2; } > "$T/three.contours"
"$TILE" "$T/three.contours" --join touch --no-caps > "$T/e.csv" 2> "$T/err" && ok || bad "empty: exit status"
grep -qxF "tile: $T/three.contours: the mesh is empty: no contour is joined to one on a neighbouring slice; --join nearest joins contours that lie apart; without --no-caps each contour is closed on its own" "$T/err" \
  && [ "$(row mesh "$T/e.csv" 8-9)" = "12,0" ] && [ "$(row joins "$T/e.csv" 7-10)" = "touch,0,4,0" ] \
  && ok || bad "empty: $(cat "$T/err")"
"$TILE" "$T/three.contours" --join 2 -q > "$T/n.csv" && [ "$(row joins "$T/n.csv" 7-10)" = "2,2,0,0" ] \
  && ok || bad "--join 2: $(row joins "$T/n.csv" 7-10)"
"$TILE" "$T/three.contours" --join 1.5 -q > "$T/n.csv" && [ "$(row joins "$T/n.csv" 7-10)" = "1.5,2,0,0" ] \
  && ok || bad "--join 1.5 (the single rule joins them): $(row joins "$T/n.csv" 7-10)"

# ---- Bad values: the usage line, exit 2.
for args in "--join" "--join near" "--join -1" "--join 1e400" "--thickness 0" "--thickness -2" "--thickness x" "--thickness"; do
  "$TILE" "$T/sq.contours" $args > "$T/out" 2> "$T/err"; rc=$?
  [ $rc -eq 2 ] && grep -q '^usage: tile STACK' "$T/err" && [ ! -s "$T/out" ] && ok || bad "'$args': exit $rc: $(cat "$T/err")"
done
"$TILE" "$T/sq.contours" --join foo 2>&1 | grep -qxF "tile: --join takes overlap, single, touch, nearest or a distance from 0 to 1e300 (foo)" \
  && ok || bad "--join foo: the message"

# ---- One slice: refused without --thickness, a slab with it.
{ printf 'C 4 5\n0 0\n4 0\n4 3\n0 3\n'; printf 'C 4 5\n1 1\n1 2\n2 2\n2 1\n'; } > "$T/one.contours"
"$TILE" "$T/one.contours" -o "$T/one.obj" > "$T/out" 2> "$T/err"; rc=$?
[ $rc -eq 1 ] && [ ! -s "$T/out" ] && [ ! -e "$T/one.obj" ] && [ "$(cat "$T/err")" = "tile: $T/one.contours:1: all 2 contours lie on one slice (z=5): a surface needs two slices, or --thickness T to make this one a slab T thick" ] \
  && ok || bad "one slice: exit $rc: $(cat "$T/err")"
for style in "" "--caps" "--caps --cap-style apex"; do
  "$TILE" "$T/one.contours" --thickness 0.5 $style -o "$T/one.obj" > "$T/one.csv" 2> "$T/err" && ok || bad "slab $style: $(cat "$T/err")"
  # area 12 - 1 = 11, times 0.5
  awk -F, '$1 == "mesh" { d = $13 - 5.5; exit !(d < 1e-12 && d > -1e-12 && $2 == 4.75 && $3 == 5.25 && $7 == "closed") }' "$T/one.csv" \
    && ok || bad "slab $style: $(grep '^mesh' "$T/one.csv")"
  judge "$T/one.obj" "$T/one.contours" "slab $style"
done
# A DICOM ROI of one slice (rt-utils' rt.dcm): a slab of 3 mm, its volume
# 3 times the region's area (the contours' shoelace: the first, the outer
# square, less the hole).
"$TILE" $D/rtutils_rt.dcm --roi 1 --thickness 3 -o "$T/rt.stl" --contours "$T/rt.contours" > "$T/rt.csv" 2> "$T/err" \
  && ok || bad "DICOM slab: $(cat "$T/err")"
judge "$T/rt.stl" "$T/rt.contours" "DICOM slab"
want=$(awk 'function fin(  i, a) { a = 0; for (i = 0; i < n; i++) a += X[i] * Y[(i + 1) % n] - X[(i + 1) % n] * Y[i]
                                    a = (a < 0 ? -a : a) / 2; s += k++ ? -a : a; n = 0 }
            BEGIN { n = 0 } /^#/ { next } /^C / { if (n) fin(); next } { X[n] = $1; Y[n] = $2; n++ }
            END { fin(); printf "%.17g", 3 * s }' "$T/rt.contours")
awk -F, -v w="$want" '$1 == "mesh" { d = ($13 - w) / w; exit !(d < 1e-12 && d > -1e-12 && $7 == "closed") }' "$T/rt.csv" \
  && ok || bad "DICOM slab: volume $(row mesh "$T/rt.csv" 13), want $want"
"$TILE" $D/rtutils_rt.dcm --roi all --thickness 3 -o "$T/rtdir/" > /dev/null 2> "$T/err" && [ -s "$T/rtdir/ROI-1.stl" ] \
  && ! grep -q skipped "$T/err" && ok || bad "DICOM --roi all --thickness: $(cat "$T/err")"

# ---- Real structure sets: under the default only BODY and Lt Lung change,
# and those as --join touch makes them; --join overlap keeps the rule before.
for j in single overlap touch; do
  "$TILE" $D/dicompyler_rtss.dcm --roi all -q --caps --join $j -o "$T/d_$j/" --format obj > "$T/d_$j.csv" 2> "$T/err" \
    && ok || bad "dicompyler --join $j: $(cat "$T/err")"
done
for m in "$T"/d_single/*.obj; do
  b=$(basename "$m")
  case $b in
    BODY.obj|Lt_Lung.obj) ! cmp -s "$m" "$T/d_overlap/$b" && cmp -s "$m" "$T/d_touch/$b" && ok || bad "dicompyler $b: not as --join touch" ;;
    *) cmp -s "$m" "$T/d_overlap/$b" && ok || bad "dicompyler $b: the default changed it" ;;
  esac
done
"$TILE" $D/dicompyler_rtss.dcm --roi all -q --contours "$T/c/" > /dev/null 2>&1
judge "$T/d_single/Lt_Lung.obj" "$T/c/Lt_Lung.contours" "Lt Lung"
[ "$(grep ',Lt Lung,joins,' "$T/d_overlap.csv" | cut -d, -f9-12)" = "overlap,0,77,0" ] &&
  [ "$(grep ',Lt Lung,joins,' "$T/d_single.csv" | cut -d, -f9-12)" = "single,0,71,0" ] && ok || bad "Lt Lung's joins rows"
for f in tests/data/slicerrt/tinypatient_0.contours tests/data/slicerrt/prostate_1.contours; do
  "$TILE" "$f" -q --caps -o "$T/a.obj" > /dev/null && "$TILE" "$f" -q --caps --join overlap -o "$T/b.obj" > /dev/null &&
    cmp -s "$T/a.obj" "$T/b.obj" && ok || bad "$f: the default changed it"
done

# BODY under --join nearest: bridges between contours far apart, some with a
# vertex of the next slice straight over a bridge's end; still a closed
# outward manifold without a degenerate triangle.
"$TILE" $D/dicompyler_rtss.dcm --roi BODY -q --caps --join nearest -o "$T/bn.obj" > "$T/bn.csv" 2> "$T/err" \
  && [ "$(grep '^joins,' "$T/bn.csv" | cut -d, -f7-10)" = "nearest,23,0,0" ] && ok || bad "BODY --join nearest: $(cat "$T/err")"
judge "$T/bn.obj" "$T/c/BODY.contours" "BODY, --join nearest"

# ---- plot surface and bench --stack take the rules too.
"$PLOT" surface "$T/sq.contours" --join overlap --caps -o "$T/p.svg" 2> /dev/null && grep -q '</svg>' "$T/p.svg" && ok || bad "plot --join"
"$PLOT" surface "$T/one.contours" --thickness 1 -o "$T/p1.svg" 2> /dev/null && grep -q '</svg>' "$T/p1.svg" && ok || bad "plot --thickness"
"$PLOT" surface "$T/one.contours" -o "$T/p2.svg" 2> "$T/err"; rc=$?
[ $rc -eq 1 ] && grep -q -- '--thickness T' "$T/err" && [ ! -e "$T/p2.svg" ] && ok || bad "plot one slice: exit $rc: $(cat "$T/err")"
"$PLOT" surface "$T/sq.contours" --join x -o "$T/p3.svg" 2> /dev/null; [ $? -eq 2 ] && ok || bad "plot --join x"
"$BENCH" --stack "$T/sq.contours" --join overlap --repeat 1 -j 1 > "$T/b.csv" 2>&1 && [ "$(tail -1 "$T/b.csv" | cut -d, -f5)" = 2 ] \
  && "$BENCH" --stack "$T/sq.contours" --repeat 1 -j 1 > "$T/b.csv" 2>&1 && [ "$(tail -1 "$T/b.csv" | cut -d, -f5)" = 3 ] \
  && ok || bad "bench --stack --join: $(cat "$T/b.csv")"

"$TILE" --help > "$T/h" && grep -q -- '--join RULE' "$T/h" && grep -q -- '--thickness T' "$T/h" && grep -q "a row 'joins'" "$T/h" \
  && ok || bad "--help lacks --join, --thickness or the joins row"
summary

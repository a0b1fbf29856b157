#!/bin/sh
# cli_keyhole.sh -- ./tile on keyhole contours (geom/keyhole.h): the same
# bytes as the region given as separate contours; MIM's rtutils_dummy_rt
# (ROI-2 and ROI-4 are keyholes) in both encodings, judged by the
# independent mesh checker (tests/meshcheck.c via `test_solids --check`, which
# excuses only segments walked both ways); the refusals that stay, and
# --no-keyholes.
TILE=${BUILD:-build/chk}/tile
CHECK=${BUILD:-build/chk}/tests/test_solids
D=tests/data/rtstruct
. tests/clilib.sh

# ---- A square with a square hole on three slices: one keyhole contour per
# slice (the channel from a different corner on each, with an extra point on
# one side, either winding) against two contours per slice.
cat > "$T/sep.contours" <<'EOF'
C 4 0
0 0
10 0
10 10
0 10
C 4 0
3 3
3 7
7 7
7 3
C 4 1
0 0
10 0
10 10
0 10
C 4 1
3 3
3 7
7 7
7 3
C 4 2
0 0
10 0
10 10
0 10
C 4 2
3 3
3 7
7 7
7 3
EOF
cat > "$T/key.contours" <<'EOF'
# out at (0 0), in at (3 3), an extra point on the way out
C 11 0
0 0
1.5 1.5
3 3
3 7
7 7
7 3
3 3
0 0
10 0
10 10
0 10
# the other way round, from (10 10) to (7 7), starting on the hole
C 10 1
3 7
3 3
7 3
7 7
10 10
10 0
0 0
0 10
10 10
7 7
# from (10 0) to (7 3), the extra point on the way back
C 11 2
10 10
0 10
0 0
10 0
7 3
3 3
3 7
7 7
7 3
8.5 1.5
10 0
EOF
"$TILE" "$T/sep.contours" --caps -o "$T/sep.obj" > "$T/sep.csv" 2> "$T/sep.err" || bad "separate: $(cat "$T/sep.err")"
"$TILE" "$T/key.contours" --caps -o "$T/key.obj" > "$T/key.csv" 2> "$T/key.err" || bad "keyhole: $(cat "$T/key.err")"
cmp -s "$T/sep.csv" "$T/key.csv" && cmp -s "$T/sep.obj" "$T/key.obj" && ok || bad "keyhole and separate contours differ"
[ "$(grep -c 'keyhole: the contour split into 2 loops at' "$T/key.err")" -eq 3 ] &&
  grep -q "^tile: $T/key.contours:2: keyhole: the contour split into 2 loops at (3 3), a channel of length 4.242640687119285 dropped$" "$T/key.err" &&
  ok || bad "keyhole notes: $(cat "$T/key.err")"
"$TILE" "$T/key.contours" --caps -q -o "$T/q.obj" > /dev/null 2> "$T/q.err" && [ ! -s "$T/q.err" ] && ok || bad "-q: $(cat "$T/q.err")"
grep -q '^mesh,.*,closed,.*,0,$' "$T/key.csv" && ok || bad "the square with a hole is not a closed torus: $(grep '^mesh' "$T/key.csv")"

# ---- Refusals: one line naming the file and line, exit 1, no output file.
refused() {   # NAME TEXT EXPECTED [ARGS...]
  name=$1; printf "$2" > "$T/r.contours"; want=$3; shift 3
  rm -f "$T/r.obj"
  "$TILE" "$T/r.contours" "$@" -o "$T/r.obj" > "$T/out" 2> "$T/err"; rc=$?
  [ $rc -eq 1 ] && [ "$(wc -l < "$T/err")" -eq 1 ] && grep -qF "tile: $T/r.contours:$want" "$T/err" &&
    [ ! -e "$T/r.obj" ] && [ ! -s "$T/out" ] && ok ||
    bad "$name: exit $rc, stderr '$(cat "$T/err")', expected 'tile: $T/r.contours:$want'"
}
SQ='C 4 1\n0 0\n9 0\n9 9\n0 9\n'
X='the contour crosses itself: the segment from line'
refused "figure eight at a point" "C 6 0\n0 0\n2 0\n1 1\n2 2\n0 2\n1 1\n$SQ" "1: $X 3 to line 4 touches the segment from line 6 to line 7 (1 1)"
refused "vertex on an edge" "C 5 0\n0 0\n2 0\n2 2\n1 0\n0 2\n$SQ" "1: $X 2 to line 3 touches the segment from line 5 to line 6 (1 0)"
refused "a crossing" "C 4 0\n0 0\n1 1\n1 0\n0 1\n$SQ" "1: $X 2 to line 3 crosses the segment from line 4 to line 5 (0.5 0.5)"
refused "a spur touching an edge" "C 7 0\n0 0\n4 0\n4 4\n2 4\n2 0\n2 4\n0 4\n$SQ" "1: $X 5 to line 6 overlaps the segment from line 6 to line 7 (2 0)"
refused "an edge walked twice one way" "C 6 0\n0 0\n3 0\n3 1\n-1 1\n-1 0\n1 0\n$SQ" "1: $X 2 to line 3 overlaps the segment from line 7 to line 2 (0 0)"
refused "a hole touching its boundary" "C 8 0\n0 0\n8 0\n8 8\n0 8\n0 0\n0 4\n4 4\n4 0\n$SQ" "1: $X"
refused "a channel across a hole" "C 20 0\n0 0\n6 0\n6 5\n7 5\n7 7\n5 7\n5 5\n6 5\n6 0\n12 0\n12 12\n0 12\n0 6\n2 6\n2 10\n10 10\n10 2\n2 2\n2 6\n0 6\n$SQ" "1: $X"
refused "--no-keyholes" "$(sed -n 1,13p "$T/key.contours")\n$SQ" "2: $X 3 to line 4 overlaps the segment from line 9 to line 10 (0 0)" --no-keyholes

# ---- A zero-width spur (a spike walked out and back along itself) encloses
# no area: dropped like a channel, with a note; the same bytes as the
# contour without it.
printf 'C 7 0\n0 0\n4 0\n4 2\n7 2\n4 2\n4 4\n0 4\n%b' "$SQ" > "$T/spur.contours"
printf 'C 5 0\n0 0\n4 0\n4 2\n4 4\n0 4\n%b' "$SQ" > "$T/nospur.contours"
"$TILE" "$T/spur.contours" --caps -o "$T/spur.obj" > "$T/spur.csv" 2> "$T/err" &&
  "$TILE" "$T/nospur.contours" --caps -o "$T/nospur.obj" > "$T/nospur.csv" 2> /dev/null &&
  cmp -s "$T/spur.csv" "$T/nospur.csv" && cmp -s "$T/spur.obj" "$T/nospur.obj" &&
  [ "$(cat "$T/err")" = "tile: $T/spur.contours:1: dropped a zero-width spur (walked out and back along itself) of length 3 at (4 2)" ] &&
  ok || bad "a spur: $(cat "$T/err")"

# ---- MIM's export: every ROI tiles, both encodings the same bytes; each
# mesh a closed outward 2-manifold by the checker, through every input point
# and segment but the channels' (2 segments in ROI-2, 2 in each of ROI-4's 3
# contours); ROI-4's hole runs through: Euler characteristic 0.
for f in rtutils_dummy_rt rtutils_dummy_rt_explicit; do
  "$TILE" $D/$f.dcm --roi all --caps -o "$T/$f/" --format obj --contours "$T/c_$f/" > "$T/$f.csv" 2> "$T/$f.err" &&
    [ "$(ls "$T/$f" | wc -l)" -eq 4 ] && ! grep -q skipped "$T/$f.err" && ok || bad "$f --roi all: $(cat "$T/$f.err")"
  [ "$(grep -c ',mesh,.*,closed,' "$T/$f.csv")" -eq 4 ] && ok || bad "$f: not every mesh row closed"
  sed 's/: byte [0-9]*:/:/' "$T/$f.err" > "$T/$f.why"
done
diff -r "$T/rtutils_dummy_rt" "$T/rtutils_dummy_rt_explicit" > /dev/null && cmp -s "$T/rtutils_dummy_rt.csv" "$T/rtutils_dummy_rt_explicit.csv" &&
  ok || bad "the implicit and explicit encodings differ"
sed "s#rtutils_dummy_rt_explicit#rtutils_dummy_rt#" "$T/rtutils_dummy_rt_explicit.why" | cmp -s - "$T/rtutils_dummy_rt.why" && ok || bad "the encodings' notes differ"
E="$T/rtutils_dummy_rt.err"
for item in "2 'ROI-2', contour item 1" "4 'ROI-4', contour item 1" "4 'ROI-4', contour item 2" "4 'ROI-4', contour item 3"; do
  grep -q "^tile: $D/rtutils_dummy_rt.dcm: byte [0-9]*: ROI $item: keyhole: the contour split into 2 loops at (.*), a channel of length [0-9.]* dropped$" "$E" &&
    ok || bad "no keyhole note for ROI $item: $(cat "$E")"
done
[ "$(grep -c keyhole "$E")" -eq 4 ] && ok || bad "$(grep -c keyhole "$E") keyhole notes, want 4"
for want in 1:0:2 2:2:2 3:0:2 4:6:0; do
  r=${want%%:*}; ch=${want#*:}; ch=${ch%%:*}; chi=${want##*:}
  out=$("$CHECK" --check "$T/rtutils_dummy_rt/ROI-$r.obj" "$T/c_rtutils_dummy_rt/ROI-$r.contours" 2>&1)
  printf '%s\n' "$out" | tail -1 | grep -q ' 0 failed$' && printf '%s\n' "$out" | grep -q "^component 0: chi $chi," &&
    ! printf '%s\n' "$out" | grep -q '^component 1:' &&
    printf '%s\n' "$out" | grep -q "^input: 0/[0-9]* points absent, 0/[0-9]* segments missing, 0 strays, 0 crossing, $ch channel segments$" &&
    ok || bad "ROI-$r by the checker (want chi $chi, $ch channel segments): $(printf '%s\n' "$out" | tail -4)"
done
# The inventory is the file's: 3 contours per ROI.
"$TILE" $D/rtutils_dummy_rt.dcm --list | cut -d, -f1-6 | tail -n +2 > "$T/list"
printf '1,ROI-1,,3,0,3\n2,ROI-2,,3,0,3\n3,ROI-3,,3,0,3\n4,ROI-4,,3,0,3\n' | cmp -s - "$T/list" && ok || bad "--list: $(cat "$T/list")"

# ---- --no-keyholes: today's refusals (ROI-2 alone; with all, skipped).
rm -f "$T/n.stl"
"$TILE" $D/rtutils_dummy_rt.dcm --roi ROI-2 --caps --no-keyholes -o "$T/n.stl" > "$T/out" 2> "$T/err"; rc=$?
[ $rc -eq 1 ] && [ ! -e "$T/n.stl" ] && [ ! -s "$T/out" ] && [ "$(wc -l < "$T/err")" -eq 1 ] &&
  grep -qF "tile: $D/rtutils_dummy_rt.dcm: byte 10014: ROI 2 'ROI-2', contour item 1: the contour crosses itself: the segment from point 35 to point 36 touches the segment from point 44 to point 45 (-39.795 38.086)" "$T/err" &&
  ok || bad "--no-keyholes ROI-2: exit $rc: $(cat "$T/err")"
"$TILE" $D/rtutils_dummy_rt.dcm --roi all --caps --no-keyholes -o "$T/n/" > "$T/out" 2> "$T/err"; rc=$?
[ $rc -eq 3 ] && [ "$(ls "$T/n" | tr '\n' ' ')" = "ROI-1.stl ROI-3.stl " ] && [ "$(grep -c 'crosses itself.*; skipped$' "$T/err")" -eq 1 ] &&
  grep -qxF "tile: $D/rtutils_dummy_rt.dcm: 2 of 4 ROIs tiled, 2 refused (ROI 2 'ROI-2', ROI 4 'ROI-4': each said above)" "$T/err" &&
  grep -q "ROI 4 'ROI-4': 3 of 3 contours cannot be tiled (1015 of 1015 points), each named above; --skip-bad drops them and tiles the rest; skipped$" "$T/err" &&
  [ "$(grep -c "ROI 4 'ROI-4', contour item [123]: the contour crosses itself" "$T/err")" -eq 3 ] &&
  ! grep -q keyhole "$T/err" && ok || bad "--no-keyholes --roi all: exit $rc: $(cat "$T/err")"
summary

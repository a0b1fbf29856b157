#!/bin/sh
# cli_geom.sh -- ./tile on hard geometry (issue 14, items 7-10): contours
# that cross themselves are refused with one line naming both segments' lines,
# exit status 1, nothing on stdout and no output file.  Runs the sanitized
# build in $BUILD.
TILE=${BUILD:-build/chk}/tile
T=$(mktemp -d /tmp/tilesim-geom.XXXXXX)
trap 'rm -rf "$T"' EXIT
pass=0; fail=0
ok()  { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "cli_geom: $*"; }

# refused NAME CONTENT EXPECTED-MESSAGE (after "tile: FILE:")
refused() {
  name=$1; printf '%b' "$2" > "$T/$name.contours"
  "$TILE" "$T/$name.contours" -o "$T/$name.ply" --caps > "$T/out" 2> "$T/err"; rc=$?
  [ $rc -eq 1 ] && ok || bad "$name: exit status $rc, expected 1"
  [ "$(wc -l < "$T/err")" -eq 1 ] && ok || bad "$name: stderr is not one line: $(cat "$T/err")"
  [ "$(cat "$T/err")" = "tile: $T/$name.contours:$3" ] && ok ||
    bad "$name: stderr '$(cat "$T/err")', expected 'tile: FILE:$3'"
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
# Exactness: 1e-300 above a segment is off it, on it is on it.
refused onsegment "C 4 0\n0 0\n2 0\n1 0\n1 1\n$SQ" \
  "1: $X 2 to line 3 overlaps the segment from line 3 to line 4 (2 0)"
printf "C 4 0\n0 0\n2 0\n1 1e-300\n1 1\n$SQ" > "$T/off.contours"
"$TILE" "$T/off.contours" -q > "$T/out" 2> "$T/err" && ok || bad "a vertex 1e-300 off a segment refused: $(cat "$T/err")"

echo "cli_geom: $pass passed, $fail failed"
[ $fail -eq 0 ]

#!/bin/sh
# cli_tile.sh -- ./tile from the outside: every bad input gets a one-line
# "tile: FILE:LINE: what (value)" message, exit status 1 and no output file;
# bad usage gets the usage line and exit status 2; good runs are
# byte-identical from run to run.  Runs the sanitized build in $BUILD.
TILE=${BUILD:-build/chk}/tile
DATA=tests/data/slicerrt
. tests/clilib.sh

# expect_error NAME CONTENT EXPECTED-MESSAGE-SUBSTRING
expect_error() {
  name=$1; printf '%b' "$2" > "$T/$name.contours"
  "$TILE" "$T/$name.contours" -o "$T/$name.obj" > "$T/out" 2> "$T/err"; rc=$?
  [ $rc -eq 1 ] && ok || bad "$name: exit status $rc, expected 1"
  [ "$(wc -l < "$T/err")" -eq 1 ] && ok || bad "$name: stderr is not one line: $(cat "$T/err")"
  grep -qF "tile: $T/$name.contours:$3" "$T/err" && ok || bad "$name: stderr '$(cat "$T/err")' lacks 'tile: FILE:$3'"
  [ ! -e "$T/$name.obj" ] && ok || bad "$name: output file written"
  [ -z "$(ls "$T" | grep tmp)" ] && ok || bad "$name: temporary file left"
}

P3='0 0\n1 0\n0 1\n'
expect_error empty        ''                                  '1: empty file'
expect_error comments     '# nothing\n\n'                     '2: no contours'
expect_error noheader     '1 2\n'                             "1: expected a header 'C <points> <z>' (1 2)"
expect_error garbled      "C 3\n$P3"                          '1: garbled header'
expect_error badcount     "C x 0\n$P3"                        '1: bad point count in header, expected a positive integer (x)'
expect_error badz         "C 3 z\n$P3"                        '1: z is not a number (z)'
expect_error nanz         "C 3 nan\n$P3"                      '1: z is not finite (nan)'
expect_error infpoint     "C 3 0\n0 0\ninf 0\n0 1\n"          '3: x is not finite (inf)'
expect_error nanpoint     "C 3 0\n0 0\n1 nan\n0 1\n"          '3: y is not finite (nan)'
expect_error nonnumeric   "C 3 0\n0 0\n1 abc\n0 1\n"          '3: y is not a number (abc)'
expect_error fewer        "C 4 0\n$P3"                        '4: the contour at line 1 announced 4 points but has 3 (end of file)'
expect_error fewer2       "C 4 0\n${P3}C 3 1\n$P3"            '5: the contour at line 1 announced 4 points but has 3'
expect_error more         "C 3 0\n${P3}2 2\n"                 '5: more point lines than the 3 announced at line 1 (2 2)'
expect_error degenerate   "C 3 0\n0 0\n1 0\n1 0\nC 3 1\n0 0\n1 1\n2 2\n"  ' no contours left to tile: all 2 are degenerate'
expect_error oneleft      "C 3 0\n0 0\n1 0\n1 0\nC 3 1\n$P3"  '5: the only contour lies on one slice (z=1)'
# Contours of a slice that cross or touch are merged into their union (they
# were refused): a closed mesh, a note naming the slice and the contours
# (then, for the piece split off where they touch, its own notes).
expect_union() {
  name=$1; printf '%b' "$2" > "$T/$name.contours"
  "$TILE" "$T/$name.contours" -o "$T/$name.obj" > "$T/out" 2> "$T/err"; rc=$?
  [ $rc -eq 0 ] && grep -q '^mesh,.*,closed,' "$T/out" && [ -s "$T/$name.obj" ] && ok || bad "$name: exit status $rc, expected 0"
  [ "$(head -1 "$T/err")" = "tile: $T/$name.contours:$3" ] && ok || bad "$name: stderr '$(cat "$T/err")', expected 'tile: FILE:$3'"
}
expect_union crossing     "C 3 1\n${P3}C 3 2\n${P3}C 3 1\n0.5 -1\n3 -1\n0.5 0.5\n"  '1: merged 2 overlapping contours on slice z=1 into their union (as --union does): the contours at line 1 and line 9: 1 contour (1 new vertices where they cross)'
expect_union touching     "C 3 1\n${P3}C 3 2\n${P3}C 3 1\n1 0\n3 0\n3 1\n"       '1: merged 2 overlapping contours on slice z=1 into their union (as --union does): the contours at line 1 and line 9: 2 contours (0 new vertices where they cross); it touches itself at (1 0), split there (each piece but one off the point by 2^-20 of its edges)'
expect_error onecontour   "C 3 0\n$P3"                        '1: the only contour lies on one slice (z=0): a surface needs two slices, or --thickness T to make this one a slab T thick'
expect_error oneslice     "C 3 0\n${P3}C 3 0\n2 2\n3 2\n2 3\n"   '1: all 2 contours lie on one slice (z=0): a surface needs two slices, or --thickness T'
expect_error binary       "C 3 0\n\001\002\003\n"             '2: binary data, not a contour file (byte 0x01)'
expect_error nulbyte      "C 3 0\n0 0\n1\000 0\n"             '3: binary data, not a contour file (byte 0x00)'
long=$(head -c 5000 /dev/zero | tr '\0' '7')
expect_error longline     "C 3 0\n$long 0\n"                  '2: line longer than 4096 bytes (5002 bytes)'

# A file that cannot be read.
"$TILE" "$T/missing.contours" > /dev/null 2> "$T/err"; rc=$?
[ $rc -eq 1 ] && grep -qF "tile: $T/missing.contours: cannot open (No such file or directory)" "$T/err" && ok || bad "missing file: $rc $(cat "$T/err")"
"$TILE" "$T" > /dev/null 2> "$T/err"; rc=$?
[ $rc -eq 1 ] && grep -qF "tile: $T: cannot read" "$T/err" && ok || bad "directory: $rc $(cat "$T/err")"
# Random binary garbage never crashes.
for seed in 1 2 3 4 5; do
  head -c 3000 /dev/urandom > "$T/garbage.contours"
  "$TILE" "$T/garbage.contours" > /dev/null 2> "$T/err"; rc=$?
  [ $rc -eq 1 ] && [ "$(wc -l < "$T/err")" -eq 1 ] && ok || bad "garbage: exit $rc: $(head -c 300 "$T/err")"
done

# Bad usage: the usage line and exit status 2.
usage() {
  "$TILE" "$@" > /dev/null 2> "$T/err"; rc=$?
  [ $rc -eq 2 ] && grep -q '^usage: tile STACK' "$T/err" && ok || bad "usage '$*': exit $rc: $(cat "$T/err")"
}
usage
usage --bogus $DATA/tinypatient_1.contours
usage $DATA/tinypatient_1.contours -o
usage $DATA/tinypatient_1.contours --cost volume
usage $DATA/tinypatient_1.contours -o "$T/out.xyz"
usage $DATA/tinypatient_1.contours $DATA/prostate_1.contours
"$TILE" --help > "$T/out" 2>&1 && grep -q '^usage: tile' "$T/out" && ok || bad "--help"

# Good runs: the report, deterministic, the mesh formats.
"$TILE" $DATA/prostate_2.contours -q --caps -o "$T/a.obj" > "$T/a.csv" 2> "$T/err" && ok || bad "prostate_2 failed: $(cat "$T/err")"
[ ! -s "$T/err" ] && ok || bad "-q still printed: $(cat "$T/err")"
head -1 "$T/a.csv" | grep -qx 'band,z0,z1,depth,lower,upper,junction,m,n,bridges,cost,area,volume,nodes,spans,euler,genus' && ok || bad "CSV header: $(head -1 "$T/a.csv")"
[ "$(grep -c '^[0-9]' "$T/a.csv")" -eq 18 ] && ok || bad "expected 18 band rows"
[ "$(grep -c '^cap,' "$T/a.csv")" -eq 2 ] && ok || bad "--caps: expected 2 cap rows"
grep -q '^mesh,-75,-30,,,,closed,' "$T/a.csv" && ok || bad "--caps: no closed mesh row: $(grep '^mesh' "$T/a.csv")"
[ "$(grep -c '^component,.*,closed,.*,2,0$' "$T/a.csv")" -eq 1 ] && ok || bad "--caps: not one component of genus 0"
"$TILE" $DATA/prostate_2.contours -q --caps -o "$T/b.obj" > "$T/b.csv" && cmp -s "$T/a.csv" "$T/b.csv" && cmp -s "$T/a.obj" "$T/b.obj" && ok || bad "two runs differ"
for f in ply stl; do
  "$TILE" $DATA/prostate_2.contours -q --caps -o "$T/a.$f" > /dev/null && "$TILE" $DATA/prostate_2.contours -q --caps -o "$T/b.$f" > /dev/null && cmp -s "$T/a.$f" "$T/b.$f" && ok || bad "$f: two runs differ"
done
# Vertices are shared between bands: one per contour point, as the CSV counts them.
nv=$(awk -F, '/^[0-9]/{s+=$8; last=$9} END{print s+last}' "$T/a.csv")
[ "$(grep -c '^v ' "$T/a.obj")" -eq "$nv" ] && ok || bad "OBJ has $(grep -c '^v ' "$T/a.obj") vertices, the contours $nv points"
# The notes on repaired input, and reading from standard input.
"$TILE" - < $DATA/tinypatient_1.contours > "$T/c.csv" 2> "$T/err" && ok || bad "stdin"
grep -q 'tile: <stdin>:6: dropped the repeated closing point' "$T/err" && ok || bad "no repair note: $(cat "$T/err")"
"$TILE" $DATA/tinypatient_1.contours --cost span -q > "$T/d.csv" && ok || bad "--cost span"
! cmp -s "$T/c.csv" "$T/d.csv" && ok || bad "span and area costs give the same report"
# Under --cost area a plain band's cost is the sum of its triangles' areas.
"$TILE" $DATA/prostate_2.contours -q --band plain > "$T/plain.csv" && ok || bad "--band plain"
awk -F, '/^[0-9]/{ d=$11-$12; if (d<0) d=-d; if (d > 1e-9*$11) bad=1 } END{exit bad}' "$T/plain.csv" && ok || bad "cost and area disagree"
# A branching that no bridge can join: two squares on slice 0 meet one
# U-shaped contour above, and a wall between them (a third contour of slice
# 0, met by nothing above) blocks every segment from one square to the other.
# Not refused: the U joins the first square, the second ends (capped), a note
# names the join dropped, and the mesh is closed.
U='C 8 1\n-1 2\n-1 -12\n12 -12\n12 2\n9 2\n9 -11\n2 -11\n2 2\n'
printf "C 4 0\n0 0\n1 0\n1 1\n0 1\nC 4 0\n10 0\n11 0\n11 1\n10 1\nC 4 0\n5 -10\n6 -10\n6 11\n5 11\n$U" > "$T/nobridge.contours"
"$TILE" "$T/nobridge.contours" -o "$T/nobridge.obj" > "$T/nb.csv" 2> "$T/err" && [ -s "$T/nobridge.obj" ] &&
  grep -qxF "tile: $T/nobridge.contours:6: not joined to the contour at line 16 on slice z=1 (their regions overlap): no bridges can join the contours of the junction it would make" "$T/err" &&
  grep -q '^mesh,.*,closed,' "$T/nb.csv" && grep -q '^joins,,,,,,single,0,[0-9]*,1,' "$T/nb.csv" && ok || bad "nobridge: $(cat "$T/err")"
# Degenerate contours (a point, two points, collinear: no area) are dropped
# with one note that counts them (-v: one each), and the rest tiled.
printf 'C 1 0\n5 5\nC 4 0\n0 0\n4 0\n4 4\n0 4\nC 2 1\n1 1\n2 2\nC 3 1\n0 0\n1 1\n2 2\nC 4 1\n0 0\n4 0\n4 4\n0 4\n' > "$T/degen.contours"
"$TILE" "$T/degen.contours" > "$T/degen.csv" 2> "$T/err" && ok || bad "degenerate contours: $(cat "$T/err")"
[ "$(cat "$T/err")" = "tile: $T/degen.contours:1: dropped 3 degenerate contours of 5 (6 points: single points, two points or all collinear, no area), this one the first: 1 distinct point, no area (z=0); -v names each" ] && ok || bad "degenerate contours: the note: $(cat "$T/err")"
grep -q '^mesh,0,1,,,,closed,8,12,0,16,48,16,' "$T/degen.csv" && ok || bad "degenerate contours: not the 4 x 4 x 1 box: $(grep '^mesh' "$T/degen.csv")"
"$TILE" "$T/degen.contours" -v > /dev/null 2> "$T/err" && [ "$(grep -c 'dropped a degenerate contour' "$T/err")" -eq 3 ] && ok || bad "degenerate contours, -v: $(cat "$T/err")"
# Any number of contours per slice: tinypatient_0 (two on each of 9 slices)
# gives two closed components of genus 0; the same bytes on 1 and 3 threads
# (-j), and with the contours in the reverse order of the file.
"$TILE" $DATA/tinypatient_0.contours -q --caps -j 1 -o "$T/tp1.obj" > "$T/tp1.csv" 2> "$T/err" && ok || bad "tinypatient_0: $(cat "$T/err")"
[ "$(grep -c '^component,.*,closed,.*,2,0$' "$T/tp1.csv")" -eq 2 ] && grep -q '^mesh,.*,closed,' "$T/tp1.csv" && ok || bad "tinypatient_0: not two closed components of genus 0"
"$TILE" $DATA/tinypatient_0.contours -q --caps -j 3 -o "$T/tp3.obj" > "$T/tp3.csv" && cmp -s "$T/tp1.csv" "$T/tp3.csv" && cmp -s "$T/tp1.obj" "$T/tp3.obj" && ok || bad "-j 3 differs from -j 1"
awk '/^C/{n++} {print n "\t" NR "\t" $0}' $DATA/tinypatient_0.contours | sort -k1,1nr -k2,2n | cut -f3- > "$T/rev.contours"
"$TILE" "$T/rev.contours" -q --caps -o "$T/rev.obj" > "$T/rev.csv" && cmp -s "$T/tp1.csv" "$T/rev.csv" && cmp -s "$T/tp1.obj" "$T/rev.obj" && ok || bad "contours in reverse file order: the output differs"
for args in "--procs 3" "--procs 2 --backend threads"; do
  "$TILE" $DATA/tinypatient_0.contours -q --caps $args -o "$T/tpp.obj" > "$T/tpp.csv" 2> "$T/err" && \
    cut -d, -f1-17 "$T/tpp.csv" | tail -n +2 | cmp -s - "$(tail -n +2 "$T/tp1.csv" > "$T/tp1b"; echo "$T/tp1b")" && \
    cmp -s "$T/tpp.obj" "$T/tp1.obj" && ok || bad "tinypatient_0 $args: not the serial report and mesh: $(cat "$T/err")"
done
usage $DATA/tinypatient_0.contours -j 0
usage $DATA/tinypatient_0.contours -j x
usage $DATA/tinypatient_0.contours --cap-style round --caps
usage $DATA/tinypatient_0.contours --cap-style apex --no-caps
usage $DATA/tinypatient_0.contours --caps --no-caps
usage $DATA/tinypatient_0.contours --band least

# The parallel algorithm on the simulated machine: the same report as the
# serial solver in its seventeen columns, the same mesh, and deterministic.
"$TILE" $DATA/prostate_3.contours -q > "$T/ser.csv" -o "$T/ser.obj" && ok || bad "serial prostate_3"
for args in "--procs 1" "--procs 2 --alloc size" "--procs 7 --min-diag 20 --net ideal" "--procs 16 --alloc size --min-diag 80 --net loggp --L 1e-4 --o 2e-5"; do
  "$TILE" $DATA/prostate_3.contours -q $args -o "$T/par.obj" > "$T/par.csv" 2> "$T/err" && ok || bad "$args: $(cat "$T/err")"
  cut -d, -f1-17 "$T/par.csv" | tail -n +2 | cmp -s - "$(tail -n +2 "$T/ser.csv" > "$T/ser9"; echo "$T/ser9")" && ok || bad "$args: the report differs from the serial one"
  cmp -s "$T/par.obj" "$T/ser.obj" && ok || bad "$args: the mesh differs from the serial one"
  head -1 "$T/par.csv" | grep -qx 'band,z0,z1,depth,lower,upper,junction,m,n,bridges,cost,area,volume,nodes,spans,euler,genus,procs,sim_time,msg_boundary,msg_backtrack,msg_bounds,msg_control,bytes,backend' && ok || bad "$args: header $(head -1 "$T/par.csv")"
  awk -F, 'NR>1 && $1 ~ /^[0-9]+$/ && $25 != "sim" {bad=1} END{exit bad}' "$T/par.csv" && ok || bad "$args: backend column is not sim"
done
# The same algorithm on threads: the same report and mesh, real times.
for args in "--procs 1" "--procs 3" "--procs 6 --alloc size --min-diag 20" "--procs 16"; do
  "$TILE" $DATA/prostate_3.contours -q $args --backend threads -o "$T/thr.obj" > "$T/thr.csv" 2> "$T/err" && ok || bad "threads $args: $(cat "$T/err")"
  cut -d, -f1-17 "$T/thr.csv" | tail -n +2 | cmp -s - "$T/ser9" && ok || bad "threads $args: the report differs from the serial one"
  cmp -s "$T/thr.obj" "$T/ser.obj" && ok || bad "threads $args: the mesh differs from the serial one"
  awk -F, 'NR>1 && $1 ~ /^[0-9]+$/ && ($25 != "threads" || $19 <= 0) {bad=1} END{exit bad}' "$T/thr.csv" && ok || bad "threads $args: backend or time column"
done
"$TILE" $DATA/prostate_3.contours -q --procs 5 --trace "$T/t1.json" > "$T/p1.csv" && "$TILE" $DATA/prostate_3.contours -q --procs 5 --trace "$T/t2.json" > "$T/p2.csv" && ok || bad "--trace"
cmp -s "$T/p1.csv" "$T/p2.csv" && cmp -s "$T/t1.json" "$T/t2.json" && ok || bad "two parallel runs or traces differ"
head -1 "$T/t1.json" | grep -q '^{.*"traceEvents":\[$' && tail -c 4 "$T/t1.json" | grep -q ']}' && ok || bad "the JSON trace is not a traceEvents object"
"$TILE" $DATA/prostate_3.contours -q --procs 3 --trace "$T/t.csv" > /dev/null && head -1 "$T/t.csv" | grep -q '^time,rank' && ok || bad "CSV trace"
awk -F, 'NR>1 && $1 ~ /^[0-9]+$/ && $19 <= 0 {bad=1} END{exit bad}' "$T/p1.csv" && ok || bad "a band without simulated time"
usage $DATA/tinypatient_1.contours --procs 0
usage $DATA/tinypatient_1.contours --procs x
usage $DATA/tinypatient_1.contours --procs 4 --alloc third
usage $DATA/tinypatient_1.contours --procs 4 --min-diag 0
usage $DATA/tinypatient_1.contours --procs 4 --net token-ring
usage $DATA/tinypatient_1.contours --procs 4 --m -1
usage $DATA/tinypatient_1.contours --procs 4 --c nan
usage $DATA/tinypatient_1.contours --procs 4 --machine cray
usage $DATA/tinypatient_1.contours --trace "$T/x.json"
usage $DATA/tinypatient_1.contours --backend threads
usage $DATA/tinypatient_1.contours --procs 2 --backend mpi
usage $DATA/tinypatient_1.contours --procs 2 --backend cluster
usage $DATA/tinypatient_1.contours --procs 2 --backend threads --trace "$T/x.json"
usage $DATA/tinypatient_1.contours --procs 2 --backend threads --spin -1
[ ! -e "$T/x.json" ] && ok || bad "a trace written after bad usage"
summary

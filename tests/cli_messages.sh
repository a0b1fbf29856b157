#!/bin/sh
# cli_messages.sh -- what the programs say, in words a user can act on:
#  - names: bench and plot run as tilesim-bench and tilesim-plot (as make
#    install names them) say so in every message, usage line and progress
#    line, and name themselves as bench and plot when run so; help texts
#    name the other programs as installed (tilesim-bench --calibrate);
#  - a bench worker killed by a signal is named, with the signal and its
#    likely cause; plot names a column its CSV lacks; a topology too small
#    counts its processors in good English; tilesim-mpirun's --help gives
#    the --procs default it uses (one processor per rank).
BUILD=${BUILD:-build/chk}
. tests/clilib.sh

# ---- the name a program was run by ----
ln -s "$(pwd)/$BUILD/bench" "$T/tilesim-bench"
ln -s "$(pwd)/$BUILD/plot" "$T/tilesim-plot"
# a word "bench" or "plot" as a command name: at the start of a line, after
# "usage: " or "(", before a blank or ':'.
bare() { grep -nE "(^|usage: |\()$1( |:)" "$2"; }

"$T/tilesim-bench" --ring 2 --laps 1 --topology mesh:1x1 > /dev/null 2> "$T/err"; rc=$?
[ $rc -eq 2 ] && grep -q '^tilesim-bench: topology mesh:1x1 has 1 processor; the run needs 2$' "$T/err" \
  && grep -q '^usage: tilesim-bench --ring P ' "$T/err" && grep -q '(tilesim-bench --help: every mode)$' "$T/err" \
  && ! bare bench "$T/err" > /dev/null && ok || bad "tilesim-bench --ring on mesh:1x1: exit $rc, $(cat "$T/err")"
"$T/tilesim-bench" stray > /dev/null 2> "$T/err"; rc=$?
[ $rc -eq 2 ] && grep -q '^tilesim-bench: tilesim-bench takes options, not arguments; tilesim-bench --help lists them' "$T/err" \
  && ! bare bench "$T/err" > /dev/null && ok || bad "tilesim-bench stray: exit $rc, $(cat "$T/err")"
for mode in --calibrate --claims --claims-map --model --glass --tiler --ring; do
  "$T/tilesim-bench" $mode --zz-no-such-option > /dev/null 2> "$T/err"
  grep -q "^tilesim-bench: " "$T/err" && grep -q "^usage: tilesim-bench $mode" "$T/err" && ! bare bench "$T/err" > /dev/null \
    && ok || bad "tilesim-bench $mode, bad usage: $(cat "$T/err")"
done
"$T/tilesim-bench" --tiler --input "$T/none.contours" --points 20 --repeat 1 > /dev/null 2> "$T/err"
grep -q "^tilesim-bench: .*none.contours" "$T/err" && ! bare bench "$T/err" > /dev/null \
  && ok || bad "tilesim-bench --tiler on a missing stack: $(cat "$T/err")"
TILESIM_PROGRESS_S=0 "$T/tilesim-bench" --points 30 --procs 1..2 --no-wall > /dev/null 2> "$T/err"
grep -q '^tilesim-bench: run 1 of ' "$T/err" && ! bare bench "$T/err" > /dev/null \
  && ok || bad "tilesim-bench's progress: $(cat "$T/err")"
# Run as bench, it says bench.
"$BUILD/bench" --ring 2 --laps 1 --topology mesh:1x1 > /dev/null 2> "$T/err"
grep -q '^bench: topology mesh:1x1 has 1 processor; ' "$T/err" && grep -q '^usage: bench --ring P ' "$T/err" \
  && ok || bad "bench --ring on mesh:1x1: $(cat "$T/err")"

printf 'a,b\n1,2\n2,3\n' > "$T/t.csv"
"$T/tilesim-plot" lines "$T/t.csv" -x a -y nosuch,b --where zz=1 -o "$T/x.svg" > /dev/null 2> "$T/err"; rc=$?
[ $rc -eq 1 ] && grep -q "^tilesim-plot: $T/t.csv: its header has no column 'nosuch' (-y), 'zz' (--where)$" "$T/err" \
  && [ ! -e "$T/x.svg" ] && ok || bad "tilesim-plot -y nosuch: exit $rc, $(cat "$T/err")"
"$BUILD/plot" lines "$T/t.csv" -x a -y b --series nosuch -o "$T/x.svg" > /dev/null 2> "$T/err"
grep -q "^plot: $T/t.csv: its header has no column 'nosuch' (--series)$" "$T/err" && ok || bad "plot --series nosuch: $(cat "$T/err")"
"$T/tilesim-plot" lines > /dev/null 2> "$T/err"
grep -q '^tilesim-plot: lines needs a CSV file first' "$T/err" && grep -q '(tilesim-plot --help: every option)$' "$T/err" \
  && ! bare plot "$T/err" > /dev/null && ok || bad "tilesim-plot lines: $(cat "$T/err")"
"$T/tilesim-plot" claims "$T/t.csv" -o "$T/x.svg" > /dev/null 2> "$T/err"
grep -q '^tilesim-plot: .*not a claims map (tilesim-bench --claims-map)' "$T/err" \
  && ok || bad "tilesim-plot claims on another CSV: $(cat "$T/err")"

# Help texts name the installed programs.
for h in "$BUILD/tilesim-mpirun --help" "$BUILD/tile --help" "$BUILD/bench --help" "$BUILD/plot --help"; do
  $h > "$T/help" 2>&1
  grep -nE '(^|[ (])bench --[a-z]' "$T/help" | grep -v '^[0-9]*: *bench --' > "$T/bare"
  [ ! -s "$T/bare" ] && ok || bad "$h names bench as installed it is not: $(cat "$T/bare")"
done
"$BUILD/tilesim-mpirun" --help | tr -s ' \n' '  ' | grep -q 'tilesim-bench --calibrate' && ok \
  || bad "tilesim-mpirun --help does not name tilesim-bench --calibrate"

# ---- a bench worker killed: named, with its signal and the likely cause ----
"$BUILD/bench" --points 20000 --procs 1..4 --jobs 2 > "$T/out" 2> "$T/err" &
bp=$!
w=""; k=0
while [ -z "$w" ] && [ $k -lt 300 ]; do w=$(ps --ppid $bp -o pid= 2> /dev/null | head -n 1 | tr -d ' '); k=$((k + 1)); sleep 0.1; done
if [ -n "$w" ]; then
  kill -9 "$w"
  wait $bp; rc=$?
  [ $rc -eq 1 ] && grep -qE '^bench: worker [12] of 2, on the run with 20000 points on [0-9]+ processors?, was killed by signal 9 \(SIGKILL\): most likely the system ran out of memory' "$T/err" \
    && [ ! -s "$T/out" ] && ok || bad "a killed worker: exit $rc, $(cat "$T/err")"
else
  kill $bp; wait $bp
  bad "bench --jobs 2 started no worker in 30 s"
fi

# ---- tilesim-mpirun: --procs as its help says ----
cat > "$T/size.c" <<'EOF'
#include <mpi.h>
int main(int argc, char **argv) {
  MPI_Init(&argc, &argv);
  MPI_Barrier(MPI_COMM_WORLD);
  MPI_Finalize();
  return 0;
}
EOF
if "$BUILD/tilesim-mpicc" "$T/size.c" -o "$T/size" > "$T/log" 2>&1; then
  "$BUILD/tilesim-mpirun" -np 3 --stats - "$T/size" > "$T/out" 2> "$T/err"
  procs=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next } { print $c["procs"] }' "$T/out")
  "$BUILD/tilesim-mpirun" --help | grep -E '^  --procs P' > "$T/help"
  [ "$procs" = 3 ] && grep -q 'tilesim-mpirun: one per rank' "$T/help" && ok \
    || bad "tilesim-mpirun -np 3 ran on $procs processors; its help says: $(cat "$T/help")"
else
  bad "tilesim-mpicc size.c: $(cat "$T/log")"
fi

# ---- numbers a person reads: the shortest form that reads back ----
# shortest FILE: each number of each line that is not CSV has no more
# significant digits than the shortest %.Ng that reads back as the same
# double; prints the first that has more.
shortest() {
  awk '!/^[a-z_]+(,[^ ]*)+$/ {
    n = split($0, w, /[ ()=,;:]+/)
    for (i = 1; i <= n; i++) {
      if (w[i] !~ /^-?[0-9]+\.[0-9]+(e[-+]?[0-9]+)?$/) continue
      x = w[i] + 0
      for (p = 1; p <= 17 && sprintf("%." p "g", x) + 0 != x; p++) ;
      m = w[i]; sub(/e.*/, "", m); gsub(/[-.]/, "", m); sub(/^0+/, "", m)
      if (length(m) > p) { print w[i] " (" p " digits read back): " $0; exit }
    } }' "$1"
}
printf 'C 4 0\n-94.156006 -119.210999\n-94.156006 -119.210999\n10 0\n0 10\nC 3 1\n0 0\n10 0\n0 10\n' > "$T/dup.contours"
"$BUILD/tile" "$T/dup.contours" > /dev/null 2> "$T/err"
grep -q "dropped a duplicate of the point before (-94.156006 -119.210999)$" "$T/err" && ok \
  || bad "a note's point: $(cat "$T/err")"
"$BUILD/examples/ring" --procs 4 --net ideal --m 0.1 --per-byte 0 --stats none -- 1 8 > "$T/out" 2>&1
grep -q '^ring: 0.4 s a lap' "$T/out" && ok || bad "ring's lap: $(cat "$T/out")"
"$BUILD/tile" tests/data/rtstruct/dicompyler_rtss.dcm --roi 'Lt Lung' > "$T/out" 2> "$T/err"
[ "$(wc -l < "$T/err")" -ge 10 ] && [ -z "$(shortest "$T/err")" ] && ok || bad "tile's notes: $(shortest "$T/err")"
"$BUILD/examples/pingpong" --procs 2 --net ideal --m 1e-5 --per-byte 1e-9 --stats none -- 3 0 1024 > "$T/out" 2>&1
grep -q '^pingpong: 0 bytes: round trip 2e-5 s, one way 1e-5 s' "$T/out" && [ -z "$(shortest "$T/out")" ] && ok \
  || bad "pingpong's times: $(cat "$T/out")"

summary

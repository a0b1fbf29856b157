#!/bin/sh
# cli_progress.sh -- progress of long runs in a form a log keeps:
# with stderr not a terminal, a whole line every TILESIM_PROGRESS_S
# seconds (default 5; 0 here, a line a step) and a last line when done;
# nothing for a run shorter than the interval, nothing with -q, and stdout
# untouched.  ./tile serial (-j 2) and parallel, bench's sweep, the ring
# on threads, tilesim-mpirun with no count to give.
BUILD=${BUILD:-build/chk}
DATA=tests/data/slicerrt
. tests/clilib.sh
now() { date +%s.%N; }
longer() { awk -v a="$1" -v b="$2" -v s="$3" 'BEGIN { exit !(b - a > s) }'; }

"$BUILD/tile" $DATA/prostate_3.contours -q > "$T/ref.csv" 2>&1
for args in "-j 2" "--procs 3"; do
  # shellcheck disable=SC2086
  TILESIM_PROGRESS_S=0 "$BUILD/tile" $DATA/prostate_3.contours $args > "$T/out" 2> "$T/err"
  n=$(grep -c '^tile: band [0-9]* of 17 ([0-9]*%), [0-9]* s$' "$T/err")
  [ "$n" -ge 5 ] && [ "$n" -le 16 ] && ok || bad "tile $args: $n progress lines: $(cat "$T/err")"
  tail -n 1 "$T/err" | grep -qx 'tile: band 17 of 17, done in [0-9]* s' && ok || bad "tile $args: no last line: $(tail -n 1 "$T/err")"
  grep -v '^tile: band' "$T/err" | grep -q . && bad "tile $args: other lines on stderr: $(cat "$T/err")" || ok
  cut -d, -f1-14 "$T/out" | cmp -s - "$(cut -d, -f1-14 "$T/ref.csv" > "$T/ref14"; echo "$T/ref14")" && ok || bad "tile $args: the report changed"
  # shellcheck disable=SC2086
  TILESIM_PROGRESS_S=0 "$BUILD/tile" $DATA/prostate_3.contours $args -q > /dev/null 2> "$T/err"
  [ ! -s "$T/err" ] && ok || bad "tile $args -q: $(cat "$T/err")"
  # shellcheck disable=SC2086
  t0=$(now); TILESIM_PROGRESS_S=5 "$BUILD/tile" $DATA/prostate_3.contours $args > /dev/null 2> "$T/err"; t1=$(now)
  if longer "$t0" "$t1" 4.5; then ok   # a loaded machine: the run was not short
  else [ ! -s "$T/err" ] && ok || bad "tile $args, a run shorter than 5 s: $(cat "$T/err")"; fi
done
TILESIM_PROGRESS_S=0 "$BUILD/bench" --points 40 --procs 1..4 --jobs 2 > "$T/out" 2> "$T/err"
grep -q '^bench: run [0-9] of 4 ([0-9]*%), [0-9]* s$' "$T/err" && tail -n 1 "$T/err" | grep -qx 'bench: run 4 of 4, done in [0-9]* s' \
  && ok || bad "bench: $(cat "$T/err")"
[ "$(wc -l < "$T/out")" -eq 5 ] && ok || bad "bench: the CSV changed: $(cat "$T/out")"

# A single long step shows too: the line again every interval, its time
# moving, while no run ends (a pair of bench's sweep; a program on threads).
# Checked where the run lasted at least four intervals (0.2 s each).
repeats() {   # repeats FILE REGEX: lines matching, with at least two times
  [ "$(grep -E "$2" "$1" | sed -E 's/.*, ([0-9]+) s$/\1/' | sort -u | wc -l)" -ge 2 ] || \
    [ "$(grep -cE "$2" "$1")" -ge 3 ]
}
t0=$(now); TILESIM_PROGRESS_S=0.2 "$BUILD/bench" --points 2500 --procs 3 > "$T/out" 2> "$T/err"; t1=$(now)
if longer "$t0" "$t1" 0.8; then
  repeats "$T/err" '^bench: run [01] of 2 \([0-9]+%\), [0-9]+ s$' && grep -q '^bench: run 0 of 2 (0%), [0-9]* s$' "$T/err" \
    && ok || bad "bench on one pair: no repeated progress: $(cat "$T/err")"
else echo "cli_progress: skipped: bench --points 2500 --procs 3 took under 0.8 s here (no single long step to show)"; fi
t0=$(now); TILESIM_PROGRESS_S=0.2 "$BUILD/examples/ring" --backend threads --procs 4 --stats none -- 20000 8 > "$T/out" 2> "$T/err"; t1=$(now)
if longer "$t0" "$t1" 0.8; then
  grep -q '^ring: 4 ranks on threads, [0-9]* s$' "$T/err" && tail -n 1 "$T/err" | grep -qx 'ring: 4 ranks on threads, done in [0-9]* s' \
    && ok || bad "ring on threads: no progress: $(cat "$T/err")"
else echo "cli_progress: skipped: ring on threads took under 0.8 s here (no long run to show)"; fi

# tilesim-mpirun with nothing to count and no simulated clock to show (a
# program that computes on the host between two calls, its clock() the
# simulated one): "running" lines, and a last line that says only how long.
cat > "$T/slow.c" << 'EOF'
#include <mpi.h>
int main(int argc, char **argv) {
  MPI_Init(&argc, &argv);
  volatile unsigned long x = 0;
  for (unsigned long i = 0; i < 1500000000ul; i++) x += i;
  MPI_Finalize();
  return 0;
}
EOF
if "$BUILD/tilesim-mpicc" "$T/slow.c" -o "$T/slow" > "$T/log" 2>&1; then
  t0=$(now); TILESIM_PROGRESS_S=0.2 "$BUILD/tilesim-mpirun" -np 1 "$T/slow" > "$T/out" 2> "$T/err"; t1=$(now)
  if longer "$t0" "$t1" 0.8; then
    grep -q '^tilesim-mpirun: running, [0-9]* s$' "$T/err" && tail -n 1 "$T/err" | grep -qx 'tilesim-mpirun: done in [0-9]* s' \
      && ok || bad "tilesim-mpirun, a slow program: $(cat "$T/err")"
  else echo "cli_progress: skipped: the slow MPI program took under 0.8 s here"; fi
else
  bad "tilesim-mpicc slow.c: $(cat "$T/log")"
fi

# Workers forked beside the thread that repeats the lines: a fork that
# copied that thread's lock (the allocator's, while it started) left a
# worker waiting for ever.  Twenty short sweeps on two workers, each given
# two minutes (a hang, not a slow machine, runs past that).
hung=0
for k in 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20; do
  timeout 120 "$BUILD/bench" --points 30 --procs 1..3 --jobs 2 --seed $k > /dev/null 2>&1 || hung=$((hung + 1))
done
[ $hung -eq 0 ] && ok || bad "$hung of 20 sweeps on two workers hung or failed"

summary

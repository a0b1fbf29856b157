#!/bin/sh
# bench_load.sh -- the threads and MPI backends under outside load (make bench-load).
#
# The same parallel run, alone and then beside BUSY busy-loop processes
# (programs that never sleep), each REPEAT times; prints a CSV row per backend
# and P with the medians and their ratio (the goal: under that load
# the run should take at most about 3 times its unloaded time).  Waiting
# ranks must not spin or yield against the threads that work; see
# mp/threads.c and mp/mp_mpi.c.  A benchmark, not a test: run it on an
# otherwise idle machine.
#
#   sh tests/bench_load.sh                   # threads (and mpi if ./tile-mpi is built)
#   PROCS="3 5" BUSY=2 REPEAT=5 STACK=FILE BACKENDS="threads mpi" sh tests/bench_load.sh
#   CPUS=0,1 sh tests/bench_load.sh          # everything pinned to those cores (taskset)
#
# mpirun gets --bind-to none, so that its ranks stay where taskset (CPUS) put
# them, beside the busy loops.
#
# Columns: backend, procs, busy (loops beside the run), repeat; unloaded_s
# and loaded_s, the medians of the command's wall time (for mpi, mpirun's
# start-up included) and ratio = loaded_s / unloaded_s; unloaded_runs_s and
# loaded_runs_s, the medians of the sum of the sim_time column (the master's
# measured time of every pair, start-up excluded) and runs_ratio; checksum:
# the sum of the cost column, the same in every run or the script fails.
set -eu
PROCS=${PROCS:-3 5}
BUSY=${BUSY:-2}
REPEAT=${REPEAT:-5}
STACK=${STACK:-tests/data/slicerrt/prostate_3.contours}
CPUS=${CPUS:-}
if [ -z "${BACKENDS:-}" ]; then
  BACKENDS=threads
  if [ -x ./tile-mpi ] && command -v mpirun >/dev/null 2>&1; then BACKENDS="threads mpi"; fi
fi
PIN=
[ -n "$CPUS" ] && PIN="taskset -c $CPUS"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
tmp=$(mktemp -d)
loops=
cleanup() {
  for p in $loops; do kill "$p" 2>/dev/null || true; done
  rm -rf "$tmp"
}
trap cleanup EXIT INT TERM

now() { date +%s.%N; }

# one BACKEND P: the command's wall seconds, then the sim_time sum and the cost sum
one() {
  t0=$(now)
  if [ "$1" = mpi ]; then
    $PIN mpirun --oversubscribe --bind-to none --mca mpi_yield_when_idle 0 -np "$2" ./tile-mpi "$STACK" -q > "$tmp/out.csv"
  else
    $PIN ./tile "$STACK" -q --backend threads --procs "$2" > "$tmp/out.csv"
  fi
  t1=$(now)
  awk -F, -v t0="$t0" -v t1="$t1" '
    NR == 1 { for (i = 1; i <= NF; i++) { if ($i == "sim_time") st = i; if ($i == "cost") co = i } next }
    { s += $st; c += $co }
    END { printf "%.6f %.6f %.10g\n", t1 - t0, s, c }' "$tmp/out.csv"
}

# median of the first (or second) field of the lines of a file
median() {
  cut -d' ' -f"$2" "$1" | sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'
}

echo "backend,procs,busy,repeat,unloaded_s,loaded_s,ratio,unloaded_runs_s,loaded_runs_s,runs_ratio,checksum"
for b in $BACKENDS; do
  for p in $PROCS; do
    : > "$tmp/u"; : > "$tmp/l"
    one "$b" "$p" > /dev/null   # warm up
    i=0
    while [ $i -lt "$REPEAT" ]; do one "$b" "$p" >> "$tmp/u"; i=$((i + 1)); done
    loops=
    i=0
    while [ $i -lt "$BUSY" ]; do
      $PIN sh -c 'while :; do :; done' &
      loops="$loops $!"
      i=$((i + 1))
    done
    sleep 0.2
    i=0
    while [ $i -lt "$REPEAT" ]; do one "$b" "$p" >> "$tmp/l"; i=$((i + 1)); done
    for q in $loops; do kill "$q" 2>/dev/null || true; done
    for q in $loops; do wait "$q" 2>/dev/null || true; done
    loops=
    sums=$(cut -d' ' -f3 "$tmp/u" "$tmp/l" | sort -u | wc -l)
    if [ "$sums" -ne 1 ]; then
      echo "bench_load: $b P=$p: the runs disagree on the cost (checksums: $(cut -d' ' -f3 "$tmp/u" "$tmp/l" | sort -u | tr '\n' ' '))" >&2
      exit 1
    fi
    uw=$(median "$tmp/u" 1); lw=$(median "$tmp/l" 1)
    ur=$(median "$tmp/u" 2); lr=$(median "$tmp/l" 2)
    awk -v b="$b" -v p="$p" -v k="$BUSY" -v r="$REPEAT" -v uw="$uw" -v lw="$lw" -v ur="$ur" -v lr="$lr" \
      -v c="$(cut -d' ' -f3 "$tmp/u" | head -1)" \
      'BEGIN { printf "%s,%s,%s,%s,%.4f,%.4f,%.2f,%.4f,%.4f,%.2f,%s\n", b, p, k, r, uw, lw, lw / uw, ur, lr, lr / ur, c }'
  done
done

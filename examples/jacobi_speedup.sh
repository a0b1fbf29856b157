#!/bin/sh
# jacobi_speedup.sh -- the Jacobi example's speedup T(1)/T(P) on two machines,
# as CSV on stdout: a sweep is a loop over runs of the same program.
#   sh examples/jacobi_speedup.sh [JACOBI] > speedup.csv
# JACOBI: the built example (default build/examples/jacobi).  The machines:
# the tc2000 profile (its bus: one message at a time in the whole machine)
# and a 4x4 torus with the tc2000's costs; a point's update costs 1 us
# (--c 1e-6), a 256 x 256 grid, 100 steps.  Simulated, so the same bytes on
# every run.
set -eu
J=${1:-build/examples/jacobi}
ARGS="--c 1e-6 --stats none -- 256 256 100"
echo "machine,procs,time,speedup"
for machine in bus torus; do
  opt=""
  [ $machine = torus ] && opt="--topology torus:4x4"
  t1=$("$J" --procs 1 $opt $ARGS | awk '/ steps on / { print $10 }')
  for P in 1 2 3 4 6 8 10 12 14 16; do
    t=$("$J" --procs $P $opt $ARGS | awk '/ steps on / { print $10 }')
    awk -v m=$machine -v p=$P -v t=$t -v t1=$t1 'BEGIN { printf "%s,%d,%s,%.6f\n", m, p, t, t1 / t }'
  done
done

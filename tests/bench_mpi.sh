#!/bin/sh
# bench_mpi.sh -- make bench-mpirun: the same MPI programs under tilesim-mpirun
# and SimGrid's smpirun (issue 19), on equivalent machines: tilesim's --net
# ideal with m = 2^-12 s and no per-byte cost, SimGrid's Constant network
# with latency-factor 2^-12 (tests/simgrid/platform.xml, as make simgrid
# runs it).  A 16-rank ring of RING_LAPS laps (default 62500: 10^6 messages)
# and a ping-pong of PP round trips (default 100000: 2 x 10^5 messages), each
# run REPEAT times (default 3), the two simulators interleaved; the best
# wall-clock time of each, messages a second, the ratio, and the simulated
# times, which must be equal (exact binary costs).  Then the time to start
# 4096 ranks of a small program and the memory per rank.
# Needs smpicc and smpirun (Debian: libsimgrid-dev) for the comparison;
# without them tilesim's figures alone.
set -eu
cd "$(dirname "$0")/.."
RING_LAPS=${RING_LAPS:-62500}
PP=${PP:-100000}
REPEAT=${REPEAT:-3}
M=0.000244140625
T=$(mktemp -d /tmp/tilesim-benchmpi.XXXXXX)
trap 'rm -rf "$T"' EXIT
now() { date +%s.%N; }
./tilesim-mpicc -O2 tests/mpirun/ring.c -o "$T/ring"
./tilesim-mpicc -O2 tests/mpirun/pingpong.c -o "$T/pingpong"
SG=""
if command -v smpicc > /dev/null 2>&1 && command -v smpirun > /dev/null 2>&1; then
  smpicc -O2 tests/mpirun/ring.c -o "$T/ring.sg" 2> /dev/null
  smpicc -O2 tests/mpirun/pingpong.c -o "$T/pingpong.sg" 2> /dev/null
  SG=yes
fi
SGOPT="-platform tests/simgrid/platform.xml -hostfile tests/simgrid/hostfile --cfg=network/model:Constant
  --cfg=network/latency-factor:$M --cfg=smpi/simulate-computation:no --cfg=smpi/host-speed:1Gf --cfg=smpi/wtime:0
  --cfg=smpi/test:0 --cfg=smpi/async-small-thresh:1000000000 --cfg=smpi/send-is-detached-thresh:1000000000
  --log=xbt_cfg.thres:warning --log=smpi_config.thres:warning --log=smpi.thres:warning"
echo "program,simulator,ranks,messages,best_wall_s,messages_per_s,sim_time"
# one NAME NP MESSAGES ARGS: both simulators, REPEAT times interleaved.
one() {
  name=$1; np=$2; msgs=$3; shift 3
  bt=1e99; bs=1e99; st=""; ss=""
  i=0
  while [ $i -lt "$REPEAT" ]; do
    t0=$(now); out=$(./tilesim-mpirun -np "$np" --net ideal --m $M --per-byte 0 "$T/$name" "$@"); t1=$(now)
    bt=$(awk -v a="$t0" -v b="$t1" -v m="$bt" 'BEGIN { d = b - a; print (d < m ? d : m) }')
    st=$(printf '%s\n' "$out" | awk '{ print $NF == "s" ? $(NF - 1) : $NF }')
    if [ -n "$SG" ]; then
      t0=$(now); out=$(smpirun -np "$np" $SGOPT "$T/$name.sg" "$@" 2> "$T/sg.err"); t1=$(now)
      bs=$(awk -v a="$t0" -v b="$t1" -v m="$bs" 'BEGIN { d = b - a; print (d < m ? d : m) }')
      ss=$(printf '%s\n' "$out" | awk '{ print $NF == "s" ? $(NF - 1) : $NF }')
    fi
    i=$((i + 1))
  done
  awk -v n="$name" -v p="$np" -v m="$msgs" -v b="$bt" -v s="$st" 'BEGIN { printf "%s,tilesim,%d,%d,%.4f,%.0f,%s\n", n, p, m, b, m / b, s }'
  if [ -n "$SG" ]; then
    awk -v n="$name" -v p="$np" -v m="$msgs" -v b="$bs" -v s="$ss" 'BEGIN { printf "%s,smpi,%d,%d,%.4f,%.0f,%s\n", n, p, m, b, m / b, s }'
    awk -v n="$name" -v a="$bt" -v b="$bs" -v x="$st" -v y="$ss" \
      'BEGIN { printf "# %s: tilesim %.1f times as fast as SMPI; simulated times %s\n", n, b / a, (x == y ? "equal" : "DIFFER: " x " against " y) }'
    [ "$st" = "$ss" ] || exit 1
  fi
}
one ring 16 $((16 * RING_LAPS)) "$RING_LAPS"
one pingpong 2 $((2 * PP)) "$PP"
# Starting many ranks: 4096 copies of a small program, and the memory.
cat > "$T/hello.c" <<'EOC'
#include <mpi.h>
#include <stdio.h>
int main(int argc, char **argv) {
  int r, p, s = 0;
  MPI_Init(&argc, &argv);
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  MPI_Comm_size(MPI_COMM_WORLD, &p);
  MPI_Reduce(&r, &s, 1, MPI_INT, MPI_SUM, 0, MPI_COMM_WORLD);
  if (r == 0) printf("%d ranks, sum %d\n", p, s);
  MPI_Finalize();
  return 0;
}
EOC
./tilesim-mpicc -O2 "$T/hello.c" -o "$T/hello"
for np in 1 4096; do
  t0=$(now); ./tilesim-mpirun -np $np --stack 256k --stats "$T/s$np.csv" "$T/hello" > /dev/null; t1=$(now)
  awk -v n=$np -v a="$t0" -v b="$t1" 'BEGIN { printf "# start and run %d ranks of a small program: %.2f s\n", n, b - a }'
done
if [ -x /usr/bin/time ]; then
  for np in 1024 4096; do
    /usr/bin/time -f "%M" -o "$T/rss$np" ./tilesim-mpirun -np $np --stack 256k "$T/hello" > /dev/null
  done
  awk -v a="$(cat "$T/rss1024")" -v b="$(cat "$T/rss4096")" 'BEGIN { printf "# memory: %.0f KB a rank (the growth of the largest resident size from 1024 to 4096 ranks, --stack 256k)\n", (b - a) / 3072 }'
fi

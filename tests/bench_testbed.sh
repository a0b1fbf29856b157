#!/bin/sh
# bench_testbed.sh -- make bench-testbed: the library adds nothing to the
# simulator's cost.  The token ring of examples/ring.c (a user's
# program through tilesim.h) and ./bench --ring (the simulator driven
# directly) on the same machine: 16 ranks, --net ideal, one 8-byte token,
# no compute, LAPS laps (default 250000: 4 M messages).  Each runs REPEAT
# times (default 5), the two interleaved; the best wall-clock time of each,
# as messages a second, and their ratio.  The simulated times are the
# checksum: they must be equal.
set -eu
LAPS=${LAPS:-250000}
REPEAT=${REPEAT:-5}
RING=${RING:-build/examples/ring}
BENCH=${BENCH:-./bench}
NET="--net ideal --m 2.5e-6 --per-byte 1e-9"
now() { date +%s.%N; }
best_e=1e99; best_b=1e99
i=0
while [ $i -lt "$REPEAT" ]; do
  t0=$(now); out_e=$("$RING" --procs 16 $NET --stats none -- "$LAPS" 8); t1=$(now)
  out_b=$("$BENCH" --ring 16 --laps "$LAPS" --work 0 $NET); t2=$(now)
  best_e=$(awk -v a="$t0" -v b="$t1" -v best="$best_e" 'BEGIN { d = b - a; print (d < best ? d : best) }')
  best_b=$(awk -v a="$t1" -v b="$t2" -v best="$best_b" 'BEGIN { d = b - a; print (d < best ? d : best) }')
  i=$((i + 1))
done
sim_e=$(printf '%s\n' "$out_e" | awk '/ s a lap/ { printf "%.9f", $2 * '"$LAPS"' }')
sim_b=$(printf '%s\n' "$out_b" | awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "sim_time") c = i } NR == 2 { printf "%.9f", $c }')
echo "program,ranks,laps,messages,best_wall_s,messages_per_s,sim_time"
awk -v e="$best_e" -v b="$best_b" -v l="$LAPS" -v se="$sim_e" -v sb="$sim_b" 'BEGIN {
  m = 16 * l
  printf "examples/ring,16,%d,%d,%.4f,%.0f,%s\n", l, m, e, m / e, se
  printf "bench --ring,16,%d,%d,%.4f,%.0f,%s\n", l, m, b, m / b, sb
  printf "# the example at %.3f times bench --ring'\''s rate; simulated times %s\n", b / e, (se == sb ? "equal" : "DIFFER")
}'
[ "$sim_e" = "$sim_b" ]

#!/bin/sh
# cli_ranks.sh -- ranks by the hundred thousand on the simulator (sim/coro.h's
# sets of stacks): examples/ring.c on 100,000 ranks against the closed form
# of its simulated time, the same run twice under two memory layouts (address
# randomisation off, a longer environment) giving byte-identical output,
# summary and trace, and a stack overflow named in a run of more ranks than
# have guard pages of their own (tests/testbed/misbehave.c deep), with no
# false alarm below the stack's size; the bounds (the threads backend keeps
# 4096).  Correctness only: no timings.
BUILD=${BUILD:-build/chk}
EX=$BUILD/examples
. tests/clilib.sh

# Costs that are binary fractions, so that every sum is exact: m = 2^-20 s,
# 2^-30 s a byte.  N ranks on 4096 processors, rank r on r mod 4096, so no
# two neighbours share one: a lap of the ring is N hops of m + 8 per_byte.
N=100000
M=0.00000095367431640625
B=0.000000000931322574615478515625
IDEAL="--net ideal --m $M --per-byte $B"

# ---- 100,000 ranks: the closed form ------------------------------------------
"$EX/ring" --ranks $N --procs 4096 $IDEAL --stats "$T/s.csv" -- 2 8 > "$T/o" 2> "$T/e" || bad "ring on $N ranks: $(head -3 "$T/e")"
grep -q "^ring: $N ranks, 2 laps of 8 bytes: the token came back every lap\$" "$T/o" && ok \
  || bad "ring on $N ranks: $(head -3 "$T/o")"
lap=$(awk '/ s a lap/ { print $2 }' "$T/o")
want=$(awk -v n=$N -v m=$M -v b=$B 'BEGIN { printf "%.17g", n * (m + 8 * b) }')
# The same double: the summary prints the shortest form that reads back.
[ -n "$lap" ] && awk -v a="$lap" -v b="$want" 'BEGIN { exit !(a == b) }' && ok || bad "ring on $N ranks: $lap s a lap, the closed form says $want"
span=$(awk -F, 'NR == 2 { print $4 }' "$T/s.csv")
awk -v a="$span" -v b="$want" 'BEGIN { exit !(a == 2 * b) }' && ok \
  || bad "ring on $N ranks: makespan $span, the closed form says 2 x $want"
msgs=$(awk -F, 'NR == 2 { print $2 "," $5 "," $15 }' "$T/s.csv")
[ "$msgs" = "$N,$((2 * N)),0" ] && ok || bad "ring on $N ranks: ranks,messages,unread $msgs"

# ---- the same run under two memory layouts: the same bytes -------------------
# One lap, traced; the second without address randomisation and with a
# longer environment, so that every stack, heap block and mapping lies
# elsewhere.
"$EX/ring" --ranks $N --procs 4096 $IDEAL --stats "$T/s1.csv" --trace "$T/t1.csv" -- 1 8 > "$T/o1" 2> "$T/e1" \
  || bad "traced ring: $(head -3 "$T/e1")"
pad=$(awk 'BEGIN { while (i++ < 3000) printf "x" }')
if setarch "$(uname -m)" -R true 2> /dev/null; then norand="setarch $(uname -m) -R"; else norand=""; fi
TILESIM_LAYOUT_PAD=$pad $norand "$EX/ring" --ranks $N --procs 4096 $IDEAL --stats "$T/s2.csv" --trace "$T/t2.csv" -- 1 8 \
  > "$T/o2" 2> "$T/e2" || bad "traced ring, other layout: $(head -3 "$T/e2")"
for f in o s t; do
  a=$T/${f}1; b=$T/${f}2
  [ $f = s ] && a=$T/s1.csv && b=$T/s2.csv
  [ $f = t ] && a=$T/t1.csv && b=$T/t2.csv
  [ -s "$a" ] && cmp -s "$a" "$b" && ok || bad "$N ranks under two memory layouts: $(basename "$a") and $(basename "$b") differ"
done
lines=$(wc -l < "$T/t1.csv")
[ "$lines" -gt "$N" ] && ok || bad "the trace of $N ranks has $lines lines"

# ---- a stack overflow among more ranks than have guard pages -----------------
# 16,400 ranks: their stacks share guard pages (coro.h, CORO_GUARDED), so
# checks find an overflow.  Rank 1 writes 100 KiB of a 64 KiB stack (into
# its soft zone): the run fails, naming it; 50 KiB is no overflow.
R=16400
"$BUILD/testbed/misbehave" --ranks $R --stack 64k --stats none -- deep 100 > "$T/o" 2> "$T/e"; rc=$?
[ $rc -eq 1 ] && [ "$(cat "$T/e")" = "misbehave: rank 1 overflowed its stack of 64 KiB (--stack sets it)" ] && ok \
  || bad "an overflow on $R ranks: exit $rc, $(head -3 "$T/e")"
"$BUILD/testbed/misbehave" --ranks $R --stack 64k --stats none -- deep 50 > "$T/o" 2> "$T/e" && [ ! -s "$T/e" ] && ok \
  || bad "50 KiB of a 64 KiB stack on $R ranks: $(head -3 "$T/e")"

# ---- the bounds ------------------------------------------------------------
"$EX/ring" --ranks 1000001 > "$T/o" 2> "$T/e"; rc=$?
[ $rc -eq 2 ] && grep -q '^ring: --ranks takes a whole number from 1 to 1000000 (1000001)$' "$T/e" && ok \
  || bad "--ranks 1000001: exit $rc, $(head -1 "$T/e")"
"$EX/ring" --ranks 4097 --backend threads > "$T/o" 2> "$T/e"; rc=$?
[ $rc -eq 2 ] && grep -q '^ring: --backend threads runs 1 to 4096 ranks, a thread each (--ranks 4097)$' "$T/e" \
  && [ ! -s "$T/o" ] && ok || bad "--ranks 4097 on threads: exit $rc, $(head -1 "$T/e")"
"$EX/ring" --procs 4 --stack 8k > "$T/o" 2> "$T/e"; rc=$?
[ $rc -eq 2 ] && grep -q '^ring: --stack takes bytes from 16k to 1G, like 256k or 1M (8k)$' "$T/e" && ok \
  || bad "--stack 8k: exit $rc, $(head -1 "$T/e")"

summary

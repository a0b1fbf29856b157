#!/bin/sh
# cli_testbed.sh -- users' own programs on tilesim's machines: the
# examples (examples/*.c, built against the installed headers and the
# public library) against closed forms of the model, on --net ideal and on a
# topology, with binary-fraction costs so that every simulated time is
# exact; the same results on threads (and MPI, where the MPI build is
# there); byte-identical summaries and traces; the machine's options with
# the same messages as ./tile; the errors (tests/testbed/misbehave.c).
BUILD=${BUILD:-build/chk}
EX=$BUILD/examples
. tests/clilib.sh

M=0.25; C=0.125; B=0.0625; R=0.5   # m, c, per_byte, hop latency: binary fractions
IDEAL="--net ideal --m $M --c $C --per-byte $B"

# same A B WHAT: two numbers equal exactly (awk's doubles, as C's).
same() {
  if awk -v a="$1" -v b="$2" 'BEGIN { exit !(a == b) }'; then ok; else bad "$3: $1, the closed form says $2"; fi
}
# field FILE REGEX N: the N-th blank-separated word of the first line matching.
field() { awk -v n="$3" "/$2/ { print \$n; exit }" "$1"; }
# tree P H: when rank 0 holds the total of the binomial reduction on P
# ranks, each step costing H (m + 8 per_byte + c) once both partial sums
# are there: ready(r, 2k) = max(ready(r, k), ready(r + k, k) + H) for the
# ranks r that are multiples of 2k, a partner r + k < P (the model of
# sim.h: sends are instant on --net ideal, a receive waits for arrival).
tree() { awk -v p="$1" -v h="$2" -v c=$C 'BEGIN {
  for (r = 0; r < p; r++) t[r] = 0
  for (k = 1; k < p; k *= 2)
    for (r = 0; r < p; r += 2 * k)
      if (r + k < p) { a = t[r + k] + h - c; t[r] = (t[r] > a ? t[r] : a) + c }
  print t[0] }'; }
# scan P H: when the last rank holds its prefix (Hillis and Steele): in
# round d every rank r >= d waits for r - d's partial sum, sent when r - d
# finished the round before, then adds (c).
scan() { awk -v p="$1" -v h="$2" -v c=$C 'BEGIN {
  for (r = 0; r < p; r++) t[r] = 0
  for (d = 1; d < p; d *= 2) {
    for (r = 0; r < p; r++) u[r] = t[r]
    for (r = d; r < p; r++) { a = u[r - d] + h - c; t[r] = (u[r] > a ? u[r] : a) + c }
  }
  print t[p - 1] }'; }

# ---- pingpong: a round trip is 2 (m + h r + L per_byte) ------------------------
"$EX/pingpong" --procs 2 $IDEAL --stats none -- 3 0 8 1024 > "$T/o" 2> "$T/e" || bad "pingpong: $(cat "$T/e")"
for L in 0 8 1024; do
  same "$(field "$T/o" "^pingpong: $L bytes:" 6)" "$(awk -v l=$L "BEGIN { print 2 * ($M + l * $B) }")" \
    "pingpong $L bytes, ideal: round trip"
done
grep -q '^pingpong: checked 3 sizes x 3 round trips$' "$T/o" && ok || bad "pingpong: not checked: $(cat "$T/o")"
# Ranks 0 and 1 three links apart on a line of 8 (a placement file).
printf '0\n3\n1\n2\n4\n5\n6\n7\n' > "$T/place"
"$EX/pingpong" --procs 8 --topology line --m $M --c $C --per-byte $B --hop-latency $R --place "file:$T/place" \
  --stats none -- 2 0 64 > "$T/o" 2> "$T/e" || bad "pingpong, line: $(cat "$T/e")"
for L in 0 64; do
  same "$(field "$T/o" "^pingpong: $L bytes:" 6)" "$(awk -v l=$L "BEGIN { print 2 * ($M + 3 * $R + l * $B) }")" \
    "pingpong $L bytes, 3 hops on a line: round trip"
done

# ---- ring: a lap is n hops of m (+ r) + L per_byte ----------------------------
for n in 2 5 16; do
  "$EX/ring" --procs $n $IDEAL --stats none -- 4 16 > "$T/o" 2> "$T/e" || bad "ring $n: $(cat "$T/e")"
  same "$(field "$T/o" '^ring: .* s a lap' 2)" "$(awk "BEGIN { print $n * ($M + 16 * $B) }")" "ring of $n, ideal: a lap"
done
"$EX/ring" --procs 1 $IDEAL --local 0.5 --stats none -- 4 16 > "$T/o" 2> "$T/e" || bad "ring 1: $(cat "$T/e")"
same "$(field "$T/o" '^ring: .* s a lap' 2)" 0.5 "ring of 1 (to itself, --local 0.5): a lap"
"$EX/ring" --procs 8 --topology ring --m $M --c $C --per-byte $B --hop-latency $R --stats none -- 3 8 > "$T/o" \
  2> "$T/e" || bad "ring on a ring: $(cat "$T/e")"
same "$(field "$T/o" '^ring: .* s a lap' 2)" "$(awk "BEGIN { print 8 * ($M + $R + 8 * $B) }")" \
  "ring of 8 on a ring topology: a lap"

# ---- jacobi: a step is m (+ r) + 8 NX per_byte + (NY / P) NX c ---------------
for P in 1 2 4 8; do
  "$EX/jacobi" --procs $P $IDEAL --stats none -- 16 32 5 > "$T/o" 2> "$T/e" || bad "jacobi $P: $(cat "$T/e")"
  step=$(awk -v p=$P "BEGIN { print (p > 1 ? $M + 8 * 16 * $B : 0) + (32 / p) * 16 * $C }")
  same "$(field "$T/o" '^jacobi: 16 x 32, 5 steps' 10)" "$(awk "BEGIN { print 5 * $step }")" "jacobi on $P, ideal: 5 steps"
  field "$T/o" '^jacobi: checksum' 3 >> "$T/sums"
done
[ "$(sort -u "$T/sums" | wc -l)" -eq 1 ] && ok || bad "jacobi: the checksum changes with P: $(cat "$T/sums")"
"$EX/jacobi" --procs 4 --topology ring --m $M --c $C --per-byte $B --hop-latency $R --stats none -- 16 32 5 \
  > "$T/o" 2> "$T/e" || bad "jacobi on a ring: $(cat "$T/e")"
same "$(field "$T/o" '^jacobi: 16 x 32, 5 steps' 10)" "$(awk "BEGIN { print 5 * ($M + $R + 8 * 16 * $B + 8 * 16 * $C) }")" \
  "jacobi on 4, ring topology: 5 steps"

# ---- reduce and scan: ceil(log2 P) (m + 8 per_byte + c) ------------------------
H=$(awk "BEGIN { print $M + 8 * $B + $C }")
for P in 1 2 3 4 5 8 9 16; do
  "$EX/reduce" --procs $P $IDEAL --stats none > "$T/o" 2> "$T/e" || bad "reduce $P: $(cat "$T/e")"
  same "$(field "$T/o" '^reduce: reduction' 3)" "$(tree $P $H)" "reduce on $P"
  grep -q "^reduce: $P ranks: total $(awk -v n=$P 'BEGIN { print n * (n + 1) * (2 * n + 1) / 6 }'), checked$" "$T/o" \
    && ok || bad "reduce on $P: the total: $(cat "$T/o")"
  "$EX/reduce" --procs $P $IDEAL --stats none -- scan > "$T/o" 2> "$T/e" || bad "scan $P: $(cat "$T/e")"
  same "$(field "$T/o" '^reduce: scan' 3)" "$(scan $P $H)" "scan on $P"
done
# On powers of two, both are log2 P steps.
same "$(tree 16 $H)" "$(awk "BEGIN { print 4 * $H }")" "the reduction's recurrence on 16 ranks"
same "$(scan 16 $H)" "$(awk "BEGIN { print 4 * $H }")" "the scan's recurrence on 16 ranks"

# ---- farm: k rounds of 2 m + 24 per_byte + c, then m + 8 per_byte --------------
for W in 1 3 4; do
  T_=$((5 * W))
  "$EX/farm" --procs $((W + 1)) $IDEAL -- $T_ 1 > "$T/o" 2> "$T/e" || bad "farm $W: $(cat "$T/e")"
  same "$(field "$T/o" '^farm: [0-9.e-]* s$' 2)" "$(awk "BEGIN { print 5 * (2 * $M + 24 * $B + $C) }")" "farm on $W workers: the master's time"
  same "$(awk -F, 'NR == 4 { print $4 }' "$T/o")" "$(awk "BEGIN { print 5 * (2 * $M + 24 * $B + $C) + $M + 8 * $B }")" \
    "farm on $W workers: the makespan"
  grep -q "^farm: $T_ tasks on $W workers: total $(awk -v t=$T_ 'BEGIN { print t * (t - 1) * (2 * t - 1) / 6 }'), checked$" \
    "$T/o" && ok || bad "farm on $W workers: $(cat "$T/o")"
done

# ---- the same results on threads (and MPI): every line but the timings ---------
results() { grep -v -e ' s$' -e ' s, ' -e ' s a lap' "$1" | sort; }
for run in "ring -- 5 32" "pingpong -- 2 0 8 4096" "jacobi -- 24 40 7" "reduce" "reduce -- scan" "farm -- 60 5"; do
  set -- $run
  prog=$1; shift
  "$EX/$prog" --procs 4 --stats none "$@" > "$T/sim" 2> "$T/e" || bad "$prog on sim: $(cat "$T/e")"
  "$EX/$prog" --procs 4 --backend threads --stats none "$@" > "$T/thr" 2> "$T/e" || bad "$prog on threads: $(cat "$T/e")"
  results "$T/sim" > "$T/a"; results "$T/thr" > "$T/b"
  [ -s "$T/a" ] && cmp -s "$T/a" "$T/b" && ok || bad "$prog: threads gave other results: $(cat "$T/b") / $(cat "$T/a")"
done
if [ "${MPI_STATUS:-}" = yes ] && [ -x build/mpi/examples/jacobi ]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
  for run in "ring -- 5 32" "pingpong -- 2 0 8 4096" "jacobi -- 24 40 7" "reduce" "farm -- 60 5"; do
    set -- $run
    prog=$1; shift
    "$EX/$prog" --procs 4 --stats none "$@" > "$T/sim" 2> "$T/e"
    timeout 60 ${MPIRUN:-mpirun} -np 4 build/mpi/examples/$prog --stats none "$@" > "$T/mpi" 2> "$T/e" \
      || bad "$prog under mpirun: $(cat "$T/e")"
    results "$T/sim" > "$T/a"; results "$T/mpi" > "$T/b"
    cmp -s "$T/a" "$T/b" && ok || bad "$prog: MPI gave other results: $(cat "$T/b") / $(cat "$T/a")"
  done
else
  echo "cli_testbed: skipped: the examples on MPI (${MPI_STATUS:-make check sets MPI_STATUS})"
fi

# ---- deterministic: two runs, the same summary and traces ----------------------
for tr in csv json; do
  for i in 1 2; do
    "$EX/jacobi" --procs 6 --topology mesh:3x2 --trace "$T/t$i.$tr" -- 12 20 4 > "$T/s$i" 2> "$T/e" || bad "jacobi --trace: $(cat "$T/e")"
  done
  cmp -s "$T/t1.$tr" "$T/t2.$tr" && cmp -s "$T/s1" "$T/s2" && [ -s "$T/t1.$tr" ] && ok \
    || bad "two runs gave other $tr traces or summaries"
done
head -1 "$T/t1.csv" | grep -q '^time,rank,proc,event,peer,tag,bytes,duration,msg,arrival$' && ok || bad "the CSV trace's header"
tail -c 4 "$T/t1.json" | grep -q ']}' && ok || bad "the JSON trace is not closed"

# ---- the summary ---------------------------------------------------------------
"$EX/reduce" --procs 4 $IDEAL > "$T/o" 2>&1
[ "$(sed -n 3p "$T/o")" = "backend,ranks,procs,makespan,messages,bytes,compute_sum,compute_max,wait_sum,wait_max,cpu_wait_sum,cpu_wait_max,overhead_sum,overhead_max,unread,deadlock,abort_code" ] \
  && [ "$(sed -n 4p "$T/o")" = "sim,4,4,1.75,3,24,0.375,0.25,2.25,1.5,0,0,0,0,0,0," ] && ok \
  || bad "reduce's summary on 4 ranks (3 messages of 8 bytes, 3 additions, rank 0 done at 2 (m + 8 b + c)): $(cat "$T/o")"
"$EX/reduce" --procs 4 $IDEAL --stats "$T/stats.csv" > "$T/o" 2>&1
[ "$(wc -l < "$T/o")" -eq 2 ] && [ "$(sed -n 2p "$T/stats.csv")" = "sim,4,4,1.75,3,24,0.375,0.25,2.25,1.5,0,0,0,0,0,0," ] \
  && ok || bad "--stats FILE: $(cat "$T/o") / $(cat "$T/stats.csv")"
"$EX/reduce" --procs 4 --backend threads > "$T/o" 2>&1
sed -n 4p "$T/o" | grep -Eq '^threads,4,4,[0-9.e-]+,3,24,,,[0-9.e-]+,[0-9.e-]+,,,,,0,0,$' && ok \
  || bad "the threads backend's summary: $(cat "$T/o")"
# Ranks outnumber processors; sleeping does not hold a processor.
"$EX/ring" --procs 2 --ranks 8 $IDEAL --local 0.5 -- 1 8 > "$T/o" 2> "$T/e" || bad "--ranks 8 --procs 2: $(cat "$T/e")"
sed -n 4p "$T/o" | grep -q '^sim,8,2,' && ok || bad "--ranks 8 --procs 2: $(cat "$T/o")"
same "$(field "$T/o" '^ring: .* s a lap' 2)" "$(awk "BEGIN { print 8 * ($M + 8 * $B) }")" \
  "8 ranks on 2 processors, placed r mod 2: every hop crosses"
"$BUILD/testbed/misbehave" --procs 1 --ranks 3 $IDEAL -- sleep > "$T/o" 2> "$T/e" || bad "sleep: $(cat "$T/e")"
same "$(awk -F, 'NR == 2 { print $4 }' "$T/o")" "$(awk "BEGIN { print 2 + $C }")" "3 ranks sleeping 0, 1, 2 s on one processor"
"$BUILD/testbed/misbehave" --procs 3 --stats none -- args one "two words" > "$T/o" 2>&1
[ "$(cat "$T/o")" = "$(printf 'misbehave: argv[0] = (name)\nmisbehave: argv[1] = args\nmisbehave: argv[2] = one\nmisbehave: argv[3] = two words')" ] \
  && ok || bad "tilesim_argv: $(cat "$T/o")"
"$EX/ring" --procs 6 --topology mesh:3x2 --place snake --print-place --stats none > "$T/o" 2> "$T/e"
[ "$(grep -c '^place: rank' "$T/e")" -eq 6 ] && grep -q '^place:   0   1   2$' "$T/e" && grep -q '^place:   5   4   3$' "$T/e" \
  && ok || bad "--print-place: $(cat "$T/e")"

# A long run says how far it has got (here a line at every chance: 160,000
# switches, a chance every 65,536), and how it ended.
TILESIM_PROGRESS_S=0 "$EX/ring" --procs 16 --stats none -- 10000 8 > "$T/o" 2> "$T/e"
[ "$(grep -c '^ring: simulated [0-9.e+-]* s, [0-9.e+-]* M calls, [0-9]* s$' "$T/e")" -eq 2 ] \
  && grep -q '^ring: simulated [0-9.e+-]* s, [0-9.e+-]* M calls, done in [0-9]* s$' "$T/e" && ok \
  || bad "progress of a long run: $(cat "$T/e")"

# ---- errors --------------------------------------------------------------------
"$BUILD/testbed/misbehave" --procs 3 -- deadlock > "$T/o" 2> "$T/e"; rc=$?
[ $rc -eq 1 ] && [ "$(wc -l < "$T/e")" -eq 1 ] && grep -q '^misbehave: deadlock at t=0: rank 0 waits in recv(src=1, tag=7); rank 1 waits in recv(src=2, tag=7); rank 2 waits in recv(src=0, tag=7)$' "$T/e" \
  && grep -q '^sim,3,3,0,0,0,.*,0,1,$' "$T/o" && ok || bad "deadlock: exit $rc, $(cat "$T/e") / $(cat "$T/o")"
"$BUILD/testbed/misbehave" --procs 3 --stats none -- badrank > "$T/o" 2> "$T/e"; rc=$?
[ $rc -eq 1 ] && grep -q '^misbehave: rank 1: mp_send to rank 8, which does not exist (3 ranks)$' "$T/e" \
  && grep -q 'send returned -2' "$T/o" && ok || bad "bad rank: exit $rc, $(cat "$T/e")"
"$BUILD/testbed/misbehave" --procs 3 --stats none -- badtag > "$T/o" 2> "$T/e"; rc=$?
[ $rc -eq 1 ] && grep -q '^misbehave: rank 1: mp_send to rank 0 with tag -4: tags are >= 0$' "$T/e" && ok \
  || bad "negative tag: exit $rc, $(cat "$T/e")"
for be in sim threads; do
  "$BUILD/testbed/misbehave" --procs 4 --backend $be -- abort > "$T/o" 2> "$T/e"; rc=$?
  [ $rc -eq 3 ] && grep -q '^misbehave: rank 2 gives up$' "$T/e" && grep -q ',3$' "$T/o" && ok \
    || bad "abort on $be: exit $rc, $(cat "$T/e") / $(cat "$T/o")"
  "$BUILD/testbed/misbehave" --procs 2 --backend $be --stats none -- exit > "$T/o" 2> "$T/e" \
    && [ "$(cat "$T/o")" = "misbehave: got 5" ] && [ ! -s "$T/e" ] && ok || bad "mp_exit on $be: $(cat "$T/o") $(cat "$T/e")"
done
"$BUILD/testbed/misbehave" --procs 2 --backend threads -- deadlock > "$T/o" 2> "$T/e"; rc=$?
[ $rc -eq 1 ] && grep -q 'rank 0 waits in recv(src=1, tag=7); rank 1 waits in recv(src=0, tag=7)$' "$T/e" && ok \
  || bad "deadlock on threads: exit $rc, $(cat "$T/e")"
# The trace within its limit, or no file.
"$EX/jacobi" --procs 4 --trace "$T/big.csv" --trace-limit 1000 > "$T/o" 2> "$T/e"; rc=$?
[ $rc -eq 1 ] && grep -q "^jacobi: $T/big.csv: the trace would take .* bytes), more than the limit of 1.0 kB; --trace-limit .* (or none) writes it$" "$T/e" \
  && [ -z "$(ls "$T" | grep big)" ] && ok || bad "--trace-limit: exit $rc, $(cat "$T/e"), $(ls "$T")"
"$EX/jacobi" --procs 4 --trace "$T/big.csv" --trace-limit 1G --stats none > "$T/o" 2> "$T/e" && [ -s "$T/big.csv" ] \
  && ok || bad "--trace-limit 1G: $(cat "$T/e")"
# Bad usage: one line, the usage, exit 2; the machine's messages are ./tile's.
for args in "--procs 0" "--procs 4097" "--net torus" "--m -1" "--c abc" "--topology torus:0x3" "--hop-latency 1e10" \
            "--switching wormhole" "--place nowhere" "--backend mpi" "--machine cray" "--slowdown -1" "--trace-limit 5Q"; do
  "$EX/ring" $args > "$T/o" 2> "$T/e"; rc=$?
  "$BUILD/tile" tests/data/slicerrt/tinypatient_1.contours --procs 2 $args > /dev/null 2> "$T/te"
  [ $rc -eq 2 ] && [ ! -s "$T/o" ] && [ "$(head -1 "$T/e" | sed 's/^ring: //')" = "$(head -1 "$T/te" | sed 's/^tile: //')" ] \
    && sed -n 2p "$T/e" | grep -q '^usage: ring ' && ok || bad "$args: exit $rc, $(cat "$T/e") / tile: $(head -1 "$T/te")"
done
for args in "--bogus 1" "stray" "--procs" "--backend threads --topology ring" "--backend threads --trace t.csv" "--trace-limit 1M"; do
  "$EX/ring" $args > "$T/o" 2> "$T/e"; rc=$?
  [ $rc -eq 2 ] && [ ! -s "$T/o" ] && [ "$(wc -l < "$T/e")" -eq 2 ] && ok || bad "$args: exit $rc, $(cat "$T/e")"
done
"$EX/ring" --procs 17 --topology mesh:4x4 > "$T/o" 2> "$T/e"; rc=$?
[ $rc -eq 2 ] && grep -q '^ring: .*16' "$T/e" && ok || bad "a machine too small: exit $rc, $(cat "$T/e")"
"$EX/ring" --help > "$T/o" 2> "$T/e" && [ ! -s "$T/e" ] && grep -q -- '--ranks R' "$T/o" && grep -q -- '--stats FILE' "$T/o" \
  && grep -q -- '--topology NAME' "$T/o" && ok || bad "--help"

# ---- doc/testbed.md: its examples' outputs are the programs' ---------------------
# Every ```console block: each "$ COMMAND" line is run (build/examples/ read as
# $BUILD/examples/) and its output must be the lines that follow, exactly.
awk -v T="$T" '
  /^```console$/ { inb = 1; next }
  /^```$/ { inb = 0; next }
  inb && /^\$ / { n++; cmd = substr($0, 3); print cmd > (T "/doc" n ".cmd"); close(T "/doc" n ".cmd"); printf "" > (T "/doc" n ".want"); next }
  inb { print >> (T "/doc" n ".want") }
' doc/testbed.md
n=0
for c in "$T"/doc*.cmd; do
  [ -e "$c" ] || break
  n=$((n + 1))
  cmd=$(sed "s|build/examples/|$BUILD/examples/|g" "$c")
  sh -c "$cmd" > "$T/got" 2>&1
  cmp -s "$T/got" "${c%.cmd}.want" && ok || bad "doc/testbed.md: '$(cat "$c")' prints: $(diff "${c%.cmd}.want" "$T/got" | head -5)"
done
[ $n -ge 6 ] && ok || bad "doc/testbed.md: only $n console examples found"
# Its speedup table is examples/jacobi_speedup.sh's (plots/testbed_jacobi.csv), to two places.
awk -F, 'NR > 1 { s[$1 "," $2] = sprintf("%.2f", $4) } END { for (k in s) print k "," s[k] }' plots/testbed_jacobi.csv > "$T/sp"
awk -F'|' '/^\| [0-9]+ \| [0-9.]+ \| [0-9.]+ \|$/ { gsub(/ /, ""); print "bus," $2 "," $3; print "torus," $2 "," $4 }' doc/testbed.md > "$T/tab"
[ -s "$T/tab" ] && [ -z "$(sort "$T/tab" | comm -23 - "$(sort "$T/sp" > "$T/sps"; echo "$T/sps")")" ] && ok \
  || bad "doc/testbed.md: the speedup table is not plots/testbed_jacobi.csv's: $(sort "$T/tab" | comm -23 - "$T/sps")"

summary

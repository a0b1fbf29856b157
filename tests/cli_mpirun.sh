#!/bin/sh
# cli_mpirun.sh -- unmodified MPI programs on tilesim's machines:
# tilesim-mpicc and tilesim-mpirun.
#   - MPICH's examples (Debian's mpich-doc: cpi, hellow, srtest, icpi), which
#     no one here wrote, on 1 to 16 ranks: the lines they print are Open MPI's
#     (mpicc and mpirun), sorted, wall-clock figures aside;
#   - the project's own MPI programs (tests/mpi/*.c, each checking itself):
#     the same lines as under Open MPI, on the simulator and on threads;
#   - privatization (tests/mpirun/privatize.c): a static, a global array,
#     getopt's state, rand, random, drand48 and strtok, each rank's own: the
#     same lines as Open MPI's processes print;
#   - a loop that waits for the clock (tests/mpirun/clockwait.c: libc's
#     clocks and MPI_Wtime, inside MPI and out): stopped, naming the call;
#     1024 reads with a --wtime-cost of 2^-10;
#   - closed forms on --net ideal with binary costs, exactly
#     (tests/mpirun/closed.c): a ping-pong, a binomial broadcast, a
#     dissemination barrier, a ring allgather, a recursive-doubling allreduce;
#   - two runs with --compute none, and with --compute blocks, give the same
#     bytes: output, summary, trace;
#   - the errors: a deadlock naming each rank's MPI call, crashes (SIGSEGV, a
#     stack overflow, SIGFPE, abort), exit and return without MPI_Finalize, an
#     unimplemented call, an invalid argument under MPI_ERRORS_ARE_FATAL; no
#     copy of a program left in $TMPDIR, also when killed; bad usage;
#   - 4096 ranks of a small program; 20,000, sharing mappings of its code.
BUILD=${BUILD:-build/chk}
RUN=$BUILD/tilesim-mpirun
CC_=$BUILD/tilesim-mpicc
. tests/clilib.sh
own_tmpdir
notemp() { [ -z "$(ls "$TMPDIR")" ] && ok || bad "$1: left in \$TMPDIR: $(ls "$TMPDIR")"; }

build() {   # build NAME SOURCE [FLAGS]: tilesim-mpicc SOURCE -o $T/NAME
  name=$1; src=$2; shift 2
  "$CC_" "$@" "$src" -o "$T/$name" -lm > "$T/build.log" 2>&1 && ok || bad "tilesim-mpicc $src: $(cat "$T/build.log")"
}

OMPI=""
if [ "${MPI_STATUS:-}" = yes ]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
  export OMPI_MCA_mpi_yield_when_idle=1
  # Windows (tests/mpi/rma_*.c): Open MPI's ucx component fails to make them as
  # root here, and its others need the shared-memory transport without its
  # single-copy mechanism (as tests/cli_mpiprogs.sh runs them).
  export OMPI_MCA_osc=^ucx OMPI_MCA_btl_vader_single_copy_mechanism=none
  OMPI=yes
else
  echo "cli_mpirun: skipped: comparisons with Open MPI (${MPI_STATUS:-make check sets MPI_STATUS})"
fi
# ompi NAME SOURCE: the same program built by Open MPI's mpicc.
ompi_build() { ${MPICC:-mpicc} "$2" -o "$T/$1.ompi" -lm > "$T/build.log" 2>&1 || bad "mpicc $2: $(cat "$T/build.log")"; }
# same_lines WHAT A B: the two outputs, sorted, are equal.
same_lines() {
  sort "$2" > "$T/sa"; sort "$3" > "$T/sb"
  cmp -s "$T/sa" "$T/sb" && [ -s "$T/sa" ] && ok || bad "$1: tilesim and Open MPI differ: $(diff "$T/sa" "$T/sb" | head -6)"
}

# ---- MPICH's examples -----------------------------------------------------------
EXD=${MPICH_EXAMPLES:-/usr/share/doc/mpich/examples}
if [ -f "$EXD/cpi.c" ] && [ -f "$EXD/srtest.c" ]; then
  for p in cpi hellow srtest icpi; do
    build "$p" "$EXD/$p.c"
    [ -n "$OMPI" ] && ompi_build "$p" "$EXD/$p.c"
  done
  # Wall-clock figures aside (the "wall clock time" lines); and the last
  # digits of floating-point sums: tilesim's reductions add in one fixed
  # order (doc/mpi-support.md), Open MPI's in its tree's, so pi's sixteenth
  # digit may differ.  Numbers of more than 12 decimals are compared
  # rounded to 12 (pi to 3.141592654423, its error to 0.000000000833).
  strip() {
    grep -v 'wall clock time' "$1" | awk '{
      out = ""; s = $0
      while (match(s, /[0-9]+\.[0-9][0-9][0-9][0-9][0-9][0-9][0-9][0-9][0-9][0-9][0-9][0-9][0-9]+/)) {
        out = out substr(s, 1, RSTART - 1) sprintf("%.12f", substr(s, RSTART, RLENGTH)); s = substr(s, RSTART + RLENGTH)
      }
      print out s }'
  }
  for n in 1 2 3 4 7 16; do
    for p in cpi hellow srtest icpi; do
      [ $p = srtest ] && [ $n -lt 2 ] && continue
      printf '1000\n0\n' > "$T/in"
      "$RUN" -np $n "$T/$p" < "$T/in" > "$T/out" 2> "$T/err" || bad "$p on $n ranks: $(cat "$T/err")"
      if [ -n "$OMPI" ]; then
        timeout 60 ${MPIRUN:-mpirun} -np $n "$T/$p.ompi" < "$T/in" > "$T/oout" 2> "$T/oerr" || bad "$p under Open MPI on $n: $(cat "$T/oerr")"
        strip "$T/out" > "$T/a"; strip "$T/oout" > "$T/b"
        same_lines "$p on $n ranks" "$T/a" "$T/b"
      fi
    done
  done
  "$RUN" -np 5 "$T/cpi" > "$T/out" 2> "$T/err"
  grep -q '^pi is approximately 3.1415926544231' "$T/out" && grep -c '^Process [0-4] of 5 is on ' "$T/out" | grep -qx 5 \
    && ok || bad "cpi on 5 ranks: $(cat "$T/out" "$T/err")"
else
  echo "cli_mpirun: skipped: MPICH's examples ($EXD/cpi.c not found: apt-get install mpich-doc)"
fi

# ---- the project's own MPI programs --------------------------------------------------
for src in tests/mpi/*.c; do
  name=$(basename "$src" .c)
  [ "$name" = contract ] && continue   # the MPI backend's own test (tests/cli_mpi.sh)
  build "$name" "$src"
  [ -n "$OMPI" ] && ompi_build "$name" "$src"
  for n in 4 3; do
    for be in sim threads; do
      timeout 120 "$RUN" -np $n --backend $be "$T/$name" > "$T/out" 2> "$T/err"; rc=$?
      [ $rc -eq 0 ] && ok || bad "$name on $n ranks ($be): exit $rc, $(tail -3 "$T/err")"
    done
    if [ -n "$OMPI" ]; then
      timeout 120 ${MPIRUN:-mpirun} -np $n "$T/$name.ompi" > "$T/oout" 2> "$T/oerr"; rc=$?
      [ $rc -eq 0 ] && ok || bad "$name under Open MPI on $n: exit $rc, $(tail -3 "$T/oerr")"
      same_lines "$name on $n ranks" "$T/out" "$T/oout"
    fi
  done
done

# ---- privatization -----------------------------------------------------------------
build privatize tests/mpirun/privatize.c
ARGS="-a one -c -b two rest more"
for be in sim threads; do
  "$RUN" -np 5 --backend $be "$T/privatize" $ARGS > "$T/priv.$be" 2> "$T/err" || bad "privatize ($be): $(cat "$T/err")"
  [ "$(grep -c 'table its own' "$T/priv.$be")" -eq 5 ] && [ "$(grep -c 'getopt a=one c=- b=two ; optind 6 of 8, first operand rest' "$T/priv.$be")" -eq 5 ] \
    && [ "$(grep -c 'strtok alpha beta gamma delta $' "$T/priv.$be")" -eq 5 ] \
    && [ "$(grep -c 'getopt again c=- b=two ?=x a=one c=- ; optind 6, then word$' "$T/priv.$be")" -eq 5 ] && ok \
    || bad "privatize ($be): $(cat "$T/priv.$be")"
  for r in 0 1 2 3 4; do grep -q "^rank $r: counter $((r + 1)), table its own$" "$T/priv.$be" && ok || bad "rank $r's static ($be)"; done
done
if [ -n "$OMPI" ]; then
  ompi_build privatize tests/mpirun/privatize.c
  timeout 60 ${MPIRUN:-mpirun} -np 5 "$T/privatize.ompi" $ARGS > "$T/oout" 2> "$T/oerr" || bad "privatize under Open MPI: $(cat "$T/oerr")"
  same_lines "privatize (rand, random, drand48 as glibc's, per rank)" "$T/priv.sim" "$T/oout"
fi
# The same program built in a strict POSIX mode: getopt is glibc's __posix_getopt there.
sed 's/^#define _DEFAULT_SOURCE$/#define _POSIX_C_SOURCE 200809L\n#define _XOPEN_SOURCE 700/' tests/mpirun/privatize.c > "$T/posix.c"
build posix "$T/posix.c"
"$RUN" -np 3 "$T/posix" -a one rest -c > "$T/out" 2> "$T/err"
[ "$(grep -c 'getopt a=one ; optind 3 of 5, first operand rest' "$T/out")" -eq 3 ] && ok \
  || bad "getopt in POSIX mode (stops at the first operand): $(cat "$T/out" "$T/err")"

# ---- a loop that waits for the clock ----------------------------------------------
# libc's clocks and MPI_Wtime are the rank's simulated clock: a loop that
# reads one until a second has passed is stopped with one line naming the
# call (the clock cannot move), and with --wtime-cost 2^-10 takes 1024 reads.
build clockwait tests/mpirun/clockwait.c
for how in 0:gettimeofday 1:clock 2:time 3:clock_gettime 4:MPI_Wtime; do
  n=${how%%:*} call=${how#*:}
  timeout 60 "$RUN" -np 2 "$T/clockwait" $n > "$T/out" 2> "$T/err"; rc=$?
  [ $rc -eq 1 ] && grep -q "^tilesim-mpirun: rank 0: $call called 100000 times at t=0 s without the rank's clock moving" "$T/err" \
    && grep -q -- '--wtime-cost' "$T/err" && [ ! -s "$T/out" ] && ok || bad "a loop on $call: exit $rc: $(cat "$T/out" "$T/err")"
  "$RUN" -np 2 --wtime-cost 0.0009765625 "$T/clockwait" $n > "$T/out" 2> "$T/err" \
    && [ "$(cat "$T/out")" = "waited a second in 1024 reads" ] && ok || bad "a loop on $call, --wtime-cost: $(cat "$T/out" "$T/err")"
done
for when in before after; do   # outside MPI too
  timeout 60 "$RUN" -np 2 "$T/clockwait" 1 $when > "$T/out" 2> "$T/err"; rc=$?
  [ $rc -eq 1 ] && grep -q "^tilesim-mpirun: rank 0: clock called 100000 times at t=" "$T/err" && [ ! -s "$T/out" ] \
    && ok || bad "a loop on clock $when MPI: exit $rc: $(cat "$T/out" "$T/err")"
  "$RUN" -np 2 --wtime-cost 0.0009765625 "$T/clockwait" 1 $when > "$T/out" 2> "$T/err" \
    && [ "$(cat "$T/out")" = "waited a second in 1024 reads" ] && ok \
    || bad "a loop on clock $when MPI, --wtime-cost: $(cat "$T/out" "$T/err")"
done

# ---- closed forms: --net ideal, m = 1/4, per_byte = 1/16 -----------------------------
build closed tests/mpirun/closed.c
IDEAL="--net ideal --m 0.25 --per-byte 0.0625 --c 0.125"
# check OP BYTES NP COLL AWKEXPR: every rank's time equals AWKEXPR (r: the rank, h: m + BYTES per_byte).
check() {
  op=$1; by=$2; np=$3; coll=$4; expr=$5
  "$RUN" -np $np $IDEAL ${coll:+--coll $coll} "$T/closed" $op $by > "$T/out" 2> "$T/err" || bad "$op on $np: $(cat "$T/err")"
  awk -v by=$by -v p=$np '
    function pop(x,  c) { c = 0; while (x > 0) { c += x % 2; x = int(x / 2) } return c }
    function lg(x,  k, v) { k = 0; v = 1; while (v < x) { v *= 2; k++ } return k }
    { r = $2 + 0; h = 0.25 + by * 0.0625; want = '"$expr"'; if ($3 != want) { print "rank " r ": " $3 ", the closed form says " want; bad = 1 } n++ }
    END { exit bad || n != p }' "$T/out" > "$T/why" && ok || bad "$op $by bytes on $np ranks ($coll): $(cat "$T/why" "$T/out")"
}
check pingpong 8 2 "" '(r == 0 ? 2 * h : h)'
check pingpong 1000 5 "" '(r == 0 ? 2 * h : r == 1 ? h : 0)'
for np in 2 3 6 8 13; do
  check barrier 0 $np barrier=dissemination 'lg(p) * 0.25'
  check bcast 40 $np bcast=binomial 'pop(r) * h'
  check allgather 24 $np allgather=ring '(p - 1) * h'
done
for np in 2 4 8 16; do check allreduce 32 $np allreduce=recursive_doubling 'lg(p) * h'; done

# ---- deterministic: none and blocks, twice each ---------------------------------------
build ring tests/mpirun/ring.c
build ringb tests/mpirun/ring.c --count-blocks
for mode in none blocks; do
  prog=$T/ring; [ $mode = blocks ] && prog=$T/ringb
  for i in 1 2; do
    "$RUN" -np 6 --topology mesh:3x2 --compute $mode --stats "$T/s$i.csv" --trace "$T/t$i.json" "$prog" 50 > "$T/o$i" 2> "$T/e$i" \
      || bad "--compute $mode: $(cat "$T/e$i")"
  done
  cmp -s "$T/o1" "$T/o2" && cmp -s "$T/s1.csv" "$T/s2.csv" && cmp -s "$T/t1.json" "$T/t2.json" && [ -s "$T/t1.json" ] && ok \
    || bad "--compute $mode: two runs differ"
  tail -1 "$T/s1.csv" | grep -q ",$mode,yes$" && ok || bad "--compute $mode: the summary: $(cat "$T/s1.csv")"
  cp "$T/o1" "$T/ring.$mode"
done
# The trace names every MPI call that took time or moved a message: 4 ranks,
# 2 laps of the ring: 8 MPI_Send and 8 MPI_Recv slices, each around its
# send or its wait and receive.
"$RUN" -np 4 --trace "$T/calls.csv" "$T/ring" 2 > /dev/null 2> "$T/e" || bad "ring --trace: $(cat "$T/e")"
[ "$(grep -c ',MPI_Send,' "$T/calls.csv")" -eq 8 ] && [ "$(grep -c ',MPI_Recv,' "$T/calls.csv")" -eq 8 ] \
  && [ "$(grep -c ',send,' "$T/calls.csv")" -eq 8 ] && ok || bad "the trace's MPI calls: $(cut -d, -f4 "$T/calls.csv" | sort | uniq -c | tr '\n' ' ')"
"$RUN" -np 4 --trace "$T/calls.json" "$T/ring" 2 > /dev/null 2>&1 && grep -q '"name":"MPI_Recv"' "$T/calls.json" && ok \
  || bad "the JSON trace has no MPI_Recv slice"
# Blocks cost time; none does not: the blocks' run is slower by a positive amount.
a=$(awk '{ print $(NF - 1) }' "$T/ring.none"); b=$(awk '{ print $(NF - 1) }' "$T/ring.blocks")
awk -v a="$a" -v b="$b" 'BEGIN { exit !(b > a) }' && ok || bad "--compute blocks charged nothing: $a s against $b s"
# A basic block costs --block-c: cpi's loop at -O2 is one block an iteration.
build blocks tests/mpirun/blocks.c --count-blocks -O2
for n in 1000 3000; do
  "$RUN" -np 1 --compute blocks --block-c 1 "$T/blocks" $n > "$T/b$n" 2> "$T/e" || bad "blocks $n: $(cat "$T/e")"
done
a=$(awk '{ print $(NF - 1) }' "$T/b1000"); b=$(awk '{ print $(NF - 1) }' "$T/b3000")
awk -v a="$a" -v b="$b" 'BEGIN { exit !(b - a == 2000) }' && ok || bad "--compute blocks --block-c 1: 1000 and 3000 intervals took $a and $b s, not 2000 s apart"
"$RUN" -np 2 --compute blocks "$T/ring" 5 > "$T/o" 2> "$T/e"; rc=$?
[ $rc -eq 2 ] && grep -q -- '--count-blocks' "$T/e" && ok || bad "--compute blocks on a program that does not count: exit $rc, $(cat "$T/e")"
"$RUN" -np 2 --compute host --stats - "$T/ring" 5 > "$T/o" 2> "$T/e" && tail -1 "$T/o" | grep -q ',host,no$' && ok \
  || bad "--compute host: the summary says reproducible: $(cat "$T/o" "$T/e")"

# ---- errors ---------------------------------------------------------------------------
cat > "$T/dl.c" <<'EOF'
#include <mpi.h>
int main(int argc, char **argv) {
  int r, v;
  MPI_Init(&argc, &argv);
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  MPI_Recv(&v, 1, MPI_INT, (r + 1) % 3, 7, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  MPI_Finalize();
  return 0;
}
EOF
build dl "$T/dl.c"
for be in sim threads; do
  timeout 60 "$RUN" -np 3 --backend $be "$T/dl" > "$T/o" 2> "$T/e"; rc=$?
  [ $rc -eq 1 ] && grep -q 'rank 0 waits in MPI_Recv(source=1, tag=7, MPI_COMM_WORLD); rank 1 waits in MPI_Recv(source=2, tag=7, MPI_COMM_WORLD); rank 2 waits in MPI_Recv(source=0, tag=7, MPI_COMM_WORLD)$' "$T/e" \
    && ok || bad "deadlock ($be): exit $rc, $(cat "$T/e")"
done
cat > "$T/crash.c" <<'EOF'
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
static int deep(int n) { volatile char buf[4096]; buf[0] = (char)n; return n ? deep(n - 1) + buf[0] : 0; }
int main(int argc, char **argv) {
  int r, v = 5;
  MPI_Init(&argc, &argv);
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  if (r == 2) {
    if (strcmp(argv[1], "segv") == 0) *(volatile int *)0 = 1;
    if (strcmp(argv[1], "fpe") == 0) { volatile int z = 0; printf("%d\n", 7 / z); }
    if (strcmp(argv[1], "stack") == 0) printf("%d\n", deep(1000));
    if (strcmp(argv[1], "abort") == 0) abort();
    if (strcmp(argv[1], "exit") == 0) exit(3);
    if (strcmp(argv[1], "spawn") == 0) { MPI_Comm c; MPI_Comm_spawn("x", MPI_ARGV_NULL, 1, MPI_INFO_NULL, 0, MPI_COMM_WORLD, &c, MPI_ERRCODES_IGNORE); }
    if (strcmp(argv[1], "badrank") == 0) MPI_Send(&v, 1, MPI_INT, 7, 0, MPI_COMM_WORLD);
    if (strcmp(argv[1], "badcount") == 0) MPI_Send(&v, -1, MPI_INT, 0, 0, MPI_COMM_WORLD);
    if (strcmp(argv[1], "abortcode") == 0) MPI_Abort(MPI_COMM_WORLD, 9);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  if (strcmp(argv[1], "nofinal") == 0) return 0;
  MPI_Finalize();
  if (strcmp(argv[1], "exitafter") == 0) exit(4);
  return 0;
}
EOF
"$CC_" "$T/crash.c" -o "$T/crash" > "$T/build.log" 2>&1 && grep -q "^tilesim-mpicc: warning: $T/crash calls MPI_Comm_spawn, which tilesim does not implement" "$T/build.log" \
  && ok || bad "tilesim-mpicc names the unimplemented call: $(cat "$T/build.log")"
ck() {   # ck WHAT STATUS REGEX
  timeout 60 "$RUN" -np 4 "$T/crash" "$1" > "$T/o" 2> "$T/e"; rc=$?
  [ $rc -eq "$2" ] && grep -q "$3" "$T/e" && ok || bad "$1: exit $rc (not $2), $(cat "$T/e")"
  notemp "$1"
}
ck segv 139 '^tilesim-mpirun: rank 2 crashed: SIGSEGV (segmentation fault)$'
ck fpe 136 '^tilesim-mpirun: rank 2 crashed: SIGFPE (arithmetic exception)$'
ck stack 139 '^tilesim-mpirun: rank 2 crashed: SIGSEGV (a stack overflow: its stack is 1024 KiB; --stack sets it)$'
ck abort 134 '^tilesim-mpirun: rank 2 called abort()$'
ck exit 1 '^tilesim-mpirun: rank 2 called exit(3) without calling MPI_Finalize$'
ck nofinal 1 'returned from main without calling MPI_Finalize$'
ck spawn 1 '^tilesim-mpirun: rank 2 called MPI_Comm_spawn, which tilesim does not implement$'
ck badrank 1 '^tilesim-mpirun: rank 2: MPI_Send: .*rank 7'
ck badcount 1 '^tilesim-mpirun: rank 2: MPI_Send: .*count'
ck abortcode 9 'rank 2'
timeout 60 "$RUN" -np 4 "$T/crash" exitafter > "$T/o" 2> "$T/e"; rc=$?
[ $rc -eq 4 ] && [ ! -s "$T/e" ] && ok || bad "exit(4) after MPI_Finalize: exit $rc, $(cat "$T/e")"
"$RUN" -np 4 --stack 8M "$T/crash" stack > "$T/o" 2> "$T/e"; rc=$?
[ $rc -eq 0 ] && ok || bad "--stack 8M: a deep recursion still fails: exit $rc, $(cat "$T/e")"
# Where there are no memory files (memfd_create fails: a shim preloaded
# says so), the program's copy is a file in $TMPDIR, removed once mapped:
# the same run, and nothing left; killed while loading, nothing left either.
printf '#include <errno.h>\nint memfd_create(const char *n, unsigned f);\nint memfd_create(const char *n, unsigned f) { (void)n; (void)f; errno = ENOSYS; return -1; }\n' > "$T/nomemfd.c"
if cc -shared -fPIC "$T/nomemfd.c" -o "$T/nomemfd.so" 2> "$T/e"; then
  ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}verify_asan_link_order=0" LD_PRELOAD="$T/nomemfd.so" \
    "$RUN" -np 300 "$T/crash" none > "$T/o" 2> "$T/e" && [ ! -s "$T/e" ] && ok || bad "300 ranks from a file: $(cat "$T/e")"
  notemp "300 ranks from a file"
  (ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}verify_asan_link_order=0" LD_PRELOAD="$T/nomemfd.so" \
    exec "$RUN" -np 4096 "$T/crash" none > /dev/null 2>&1) &
  pid=$!
  sleep 0.05
  kill -TERM $pid 2> /dev/null
  wait $pid 2> /dev/null
else
  bad "cannot build the memfd_create shim: $(cat "$T/e")"
fi
notemp "killed while loading"

# ---- bad usage ----------------------------------------------------------------------
for args in "" "-np 4" "-np 0 $T/ring" "-np 1000001 $T/ring" "-np 4097 --backend threads $T/ring" "--bogus 1 -np 2 $T/ring" "-np 2 --backend mpi $T/ring" \
            "-np 2 --compute fast $T/ring" "-np 2 --coll bcast=ring $T/ring" "-np 2 /bin/true" "-np 2 $T/nothing" \
            "-np 2 --backend threads --trace x.csv $T/ring" "-np 2 --stack 1k $T/ring"; do
  "$RUN" $args > "$T/o" 2> "$T/e"; rc=$?
  [ $rc -eq 2 ] && [ ! -s "$T/o" ] && [ -s "$T/e" ] && ok || bad "tilesim-mpirun $args: exit $rc, $(cat "$T/e")"
done
"$RUN" --help > "$T/o" 2>&1 && grep -q -- '--compute MODE' "$T/o" && grep -q -- '--topology NAME' "$T/o" && ok || bad "--help"
"$CC_" --showme -c x.c > "$T/o" 2>&1 && grep -q -- '^cc -I.*/include/tilesim/mpi -c x.c -fPIC' "$T/o" && ! grep -q -- '-shared' "$T/o" && ok \
  || bad "tilesim-mpicc --showme: $(cat "$T/o")"
"$CC_" > "$T/o" 2> "$T/e"; rc=$?
[ $rc -eq 2 ] && ok || bad "tilesim-mpicc without files: exit $rc"
# Several files, compiled apart and linked: -c, extra flags passed on.
printf '#include <mpi.h>\nint twice(int x);\nint main(int c, char **v) { int r; MPI_Init(&c, &v); MPI_Comm_rank(MPI_COMM_WORLD, &r); printf_r(twice(r)); MPI_Finalize(); return 0; }\n' > "$T/m.c"
printf '#include <stdio.h>\nint twice(int x) { return X * x; }\nvoid printf_r(int v) { printf("got %%d\\n", v); }\n' > "$T/t.c"
sed -i 's/^int twice(int x);/int twice(int x); void printf_r(int v);/' "$T/m.c"
"$CC_" -c "$T/m.c" -o "$T/m.o" && "$CC_" -DX=2 -c "$T/t.c" -o "$T/t.o" && "$CC_" "$T/m.o" "$T/t.o" -o "$T/two" \
  && "$RUN" -np 3 "$T/two" > "$T/o" 2> "$T/e" && [ "$(sort "$T/o" | tr '\n' ' ')" = "got 0 got 2 got 4 " ] && ok \
  || bad "two files compiled apart: $(cat "$T/o" "$T/e")"

# ---- scale ---------------------------------------------------------------------------
cat > "$T/hello.c" <<'EOF'
#include <mpi.h>
#include <stdio.h>
int main(int argc, char **argv) {
  int r, p, sum = 0;
  MPI_Init(&argc, &argv);
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  MPI_Comm_size(MPI_COMM_WORLD, &p);
  MPI_Reduce(&r, &sum, 1, MPI_INT, MPI_SUM, 0, MPI_COMM_WORLD);
  if (r == 0) printf("%d ranks, sum %d\n", p, sum);
  MPI_Finalize();
  return 0;
}
EOF
build hello "$T/hello.c"
"$RUN" -np 4096 --stack 256k "$T/hello" > "$T/o" 2> "$T/e" && grep -q '^4096 ranks, sum 8386560$' "$T/o" && ok \
  || bad "4096 ranks: $(cat "$T/o" "$T/e" | head -3)"
notemp "4096 ranks"
# 20,000 ranks: more than the loader gives a code mapping each (a quarter of
# vm.max_map_count's room): consecutive ranks share mappings of repeated
# code, and the run stays within the kernel's mappings.  The last rank counts
# them in /proc/self/maps.
cat > "$T/maps.c" <<'EOF'
#include <mpi.h>
#include <stdio.h>
#include <string.h>
int main(int argc, char **argv) {
  int r, p, sum = 0;
  MPI_Init(&argc, &argv);
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  MPI_Comm_size(MPI_COMM_WORLD, &p);
  MPI_Allreduce(&r, &sum, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  if (r == p - 1) {
    char line[1024];
    int all = 0, code = 0;
    FILE *f = fopen("/proc/self/maps", "r");
    while (f && fgets(line, sizeof line, f)) all++, code += strstr(line, "tilesim-program") != NULL;
    if (f) fclose(f);
    printf("%d ranks, sum %d, %d mappings, %d of code\n", p, sum, all, code);
  }
  MPI_Finalize();
  return 0;
}
EOF
build maps "$T/maps.c"
"$RUN" -np 20000 --stack 64k "$T/maps" > "$T/o" 2> "$T/e" \
  && awk '$1 == 20000 && $4 == "199990000," && $5 < 65530 && $7 > 0 && $7 < 20000 { ok = 1 } END { exit !ok }' "$T/o" && ok \
  || bad "20,000 ranks: $(cat "$T/o" "$T/e" | head -3)"

# MPI_Isendrecv's request ends, then MPI_Finalize with nothing between: the
# send's reference is the request's, settled once (a rank's end settled it
# a second time: a double free after the program's last line).  Closed form:
# each rank gets its left neighbour's last value, rank * 10 + 3.
cat > "$T/isr.c" << 'EOF'
#include <mpi.h>
#include <stdio.h>
int main(int argc, char **argv) {
  int r, n, out[4], in[4] = {-1, -1, -1, -1};
  MPI_Init(&argc, &argv);
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  MPI_Comm_size(MPI_COMM_WORLD, &n);
  for (int i = 0; i < 4; i++) out[i] = r * 10 + i;
  MPI_Request q;
  MPI_Isendrecv(out, 4, MPI_INT, (r + 1) % n, 0, in, 4, MPI_INT, (r + n - 1) % n, 0, MPI_COMM_WORLD, &q);
  MPI_Wait(&q, MPI_STATUS_IGNORE);
  printf("%d got %d\n", r, in[3]);
  MPI_Finalize();
  return 0;
}
EOF
"$CC_" "$T/isr.c" -o "$T/isr" > "$T/build.log" 2>&1 || bad "isendrecv: $(cat "$T/build.log")"
for np in 2 4; do
  "$RUN" -np $np "$T/isr" > "$T/o" 2> "$T/e"; rc=$?
  want=$(awk -v n=$np 'BEGIN { for (r = 0; r < n; r++) printf "%d got %d\n", r, ((r + n - 1) % n) * 10 + 3 }')
  [ $rc -eq 0 ] && [ "$(sort -n "$T/o")" = "$want" ] && [ ! -s "$T/e" ] && ok \
    || bad "isendrecv then finalize on $np ranks: exit $rc, $(cat "$T/o" "$T/e" | head -4)"
done

# A program's libc names bind as ld.so would bind them in a process of its
# own: an interposer earlier in the search order first (make check's build
# has the sanitizer's malloc), so the program and the runner share one
# allocator.  The reference is the dynamic linker's own answer, dlsym.
cat > "$T/alloc.c" << 'EOF'
#define _GNU_SOURCE
#include <dlfcn.h>
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
int main(int argc, char **argv) {
  void *(*m)(size_t) = malloc;
  void (*f)(void *) = free;
  MPI_Init(&argc, &argv);
  printf("malloc %s, free %s\n", (void *)m == dlsym(RTLD_DEFAULT, "malloc") ? "the process's" : "another",
         (void *)f == dlsym(RTLD_DEFAULT, "free") ? "the process's" : "another");
  MPI_Finalize();
  return 0;
}
EOF
"$CC_" "$T/alloc.c" -o "$T/alloc" > "$T/build.log" 2>&1 || bad "alloc.c: $(cat "$T/build.log")"
"$RUN" -np 1 "$T/alloc" > "$T/o" 2> "$T/e" && [ "$(cat "$T/o")" = "malloc the process's, free the process's" ] && ok \
  || bad "a program's malloc: $(cat "$T/o" "$T/e")"

summary

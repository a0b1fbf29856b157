#!/bin/sh
# cli_rma.sh -- the one-sided examples (examples/mpi/halo_fence.c and
# lock_counter.c) built by tilesim-mpicc and run by tilesim-mpirun:
#   - their closed forms on --net ideal with binary costs, exactly, for
#     several rank counts, widths and steps (the formulas are the programs'
#     own comments): a fence's halo exchange costs (2 + ceil(log2 P)) m +
#     8 W b a step, a lock-based counter 2 m + 8 b an increment;
#   - what each program checks (the halo's ghost cells, every value of the
#     counter fetched once), also on threads and on a torus;
#   - two runs with a trace and statistics give the same bytes;
#   - under Open MPI (mpicc, mpirun), the same checks pass.
BUILD=${BUILD:-build/chk}
RUN=$BUILD/tilesim-mpirun
CC_=$BUILD/tilesim-mpicc
. tests/clilib.sh
own_tmpdir

for p in halo_fence lock_counter; do
  "$CC_" examples/mpi/$p.c -o "$T/$p" > "$T/build.log" 2>&1 && ok || bad "tilesim-mpicc $p.c: $(cat "$T/build.log")"
done

# ---- closed forms: --net ideal, m = 1/4, per_byte = 1/16 ------------------------------
IDEAL="--net ideal --m 0.25 --per-byte 0.0625"
# closed PROG NP ARGS AWKEXPR: the largest time the program prints equals AWKEXPR
# (p: the ranks, lg: ceil(log2 p), a1, a2: the arguments, m, b).
closed() {
  prog=$1; np=$2; args=$3; expr=$4
  "$RUN" -np $np $IDEAL "$T/$prog" $args > "$T/out" 2> "$T/err" || { bad "$prog on $np ($args): $(cat "$T/err" "$T/out")"; return; }
  grep -q "wrong" "$T/out" && bad "$prog on $np ($args): $(grep wrong "$T/out" | head -3)"
  set -- $args
  awk -v p=$np -v a1="${1:-0}" -v a2="${2:-0}" '
    function clg(x,  k, v) { k = 0; v = 1; while (v < x) { v *= 2; k++ } return k }
    / s$/ { t = $(NF - 1) + 0; if (t > max) max = t; n++ }
    END { m = 0.25; b = 0.0625; lg = clg(p); want = '"$expr"';
          if (max != want) { printf "%.17g, the closed form says %.17g\n", max, want; exit 1 } }' "$T/out" > "$T/why" \
    && ok || bad "$prog on $np ranks ($args): $(cat "$T/why")"
}
for np in 3 4 5 8 13; do
  closed halo_fence $np "4 10" 'lg * m + a2 * ((2 + lg) * m + 8 * a1 * b)'
  closed halo_fence $np "1 3" 'lg * m + a2 * ((2 + lg) * m + 8 * a1 * b)'
  closed lock_counter $np "6" '2 * m + 8 * b + (p - 1) * a1 * (2 * m + 8 * b)'
done
closed halo_fence 16 "32 2" 'lg * m + a2 * ((2 + lg) * m + 8 * a1 * b)'
closed lock_counter 2 "7" 'a1 * (4 * m + 16 * b)'
# The counter's value and every rank's check, in the output.
"$RUN" -np 6 $IDEAL "$T/lock_counter" 5 > "$T/out" 2>&1 && grep -q "^lock_counter: counter 25$" "$T/out" && ok \
  || bad "lock_counter's counter: $(cat "$T/out")"

# ---- the checks elsewhere: threads, a torus -------------------------------------------
for m in "--backend threads" "--topology torus:3x3 --hop-latency 1e-5"; do
  "$RUN" -np 9 $m "$T/halo_fence" 3 6 > "$T/out" 2>&1 && [ "$(grep -c ' s$' "$T/out")" -eq 9 ] && ! grep -q wrong "$T/out" \
    && ok || bad "halo_fence ($m): $(cat "$T/out")"
  "$RUN" -np 9 $m "$T/lock_counter" 4 > "$T/out" 2>&1 && grep -q "^lock_counter: counter 32$" "$T/out" && ok \
    || bad "lock_counter ($m): $(cat "$T/out")"
done

# ---- deterministic: the same bytes twice --------------------------------------------
for i in 1 2; do
  "$RUN" -np 5 --topology ring --stats "$T/s$i.csv" --trace "$T/t$i.json" "$T/lock_counter" 3 > "$T/o$i" 2> "$T/e$i" \
    || bad "lock_counter on a ring: $(cat "$T/e$i")"
done
cmp -s "$T/o1" "$T/o2" && cmp -s "$T/s1.csv" "$T/s2.csv" && cmp -s "$T/t1.json" "$T/t2.json" && [ -s "$T/t1.json" ] && ok \
  || bad "lock_counter: two runs differ"

# ---- Open MPI ------------------------------------------------------------------------
if [ "${MPI_STATUS:-}" = yes ]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
  export OMPI_MCA_btl_vader_single_copy_mechanism=none OMPI_MCA_osc=^ucx
  for p in halo_fence lock_counter; do
    ${MPICC:-mpicc} examples/mpi/$p.c -o "$T/$p.ompi" > "$T/build.log" 2>&1 || bad "mpicc $p.c: $(cat "$T/build.log")"
  done
  timeout 120 ${MPIRUN:-mpirun} -np 4 "$T/halo_fence.ompi" 4 10 > "$T/out" 2>&1 && ! grep -q wrong "$T/out" && ok \
    || bad "halo_fence under Open MPI: $(cat "$T/out")"
  timeout 120 ${MPIRUN:-mpirun} -np 4 "$T/lock_counter.ompi" 5 > "$T/out" 2>&1 && grep -q "^lock_counter: counter 15$" "$T/out" \
    && ok || bad "lock_counter under Open MPI: $(cat "$T/out")"
else
  echo "cli_rma: skipped: the examples under Open MPI (${MPI_STATUS:-make check sets MPI_STATUS})"
fi

summary

#!/bin/sh
# cli_mpi.sh -- the MPI build under mpirun: the backend's contract test
# (tests/mpi/contract.c) on 4 processes, then tile-mpi on a real stack
# across 4 processes, its report and mesh bit for bit the serial ./tile's,
# and bench-mpi.  Where $MPICC cannot build an MPI program (MPI_STATUS, from
# make check's probe) it says so and counts nothing; make check builds
# build/mpi first when it can.
MPIDIR=${MPIDIR:-build/mpi}
TILE=${BUILD:-build/chk}/tile
DATA=tests/data/slicerrt
. tests/clilib.sh

# make check probes $MPICC once (make mpi-probe) and says here whether it
# builds an MPI program: MPI_STATUS is "yes" or why not.  Nothing is looked
# for here.
MPIRUN=${MPIRUN:-mpirun}
if [ "${MPI_STATUS:-}" != yes ]; then
  echo "cli_mpi: skipped: ${MPI_STATUS:-MPI_STATUS is not set (make check probes the MPI compiler)}; the MPI tests were not run (apt-get install openmpi-bin libopenmpi-dev)"
  echo "cli_mpi: 0 passed, 0 failed"
  exit 0
fi
for p in tile-mpi bench-mpi contract-mpi; do need "$MPIDIR/bin/$p" "make mpi"; done
open_mpi
run() { np=$1; shift; "$MPIRUN" $OVER -np "$np" "$@"; }

# The backend's contract, on 4 processes: its own summary line counts here.
run 4 "$MPIDIR/bin/contract-mpi" > "$T/contract" 2>&1; rc=$?
line=$(grep -E '^contract_mpi: [0-9]+ passed, [0-9]+ failed$' "$T/contract")
if [ -n "$line" ]; then
  p=$(echo "$line" | sed -E 's/.*: ([0-9]+) passed, ([0-9]+) failed/\1/')
  f=$(echo "$line" | sed -E 's/.*: ([0-9]+) passed, ([0-9]+) failed/\2/')
  pass=$((pass + p)); fail=$((fail + f))
  [ "$f" -gt 0 ] && cat "$T/contract"
  [ $rc -eq 0 ] && ok || bad "contract-mpi exited $rc"
else
  bad "contract-mpi died (exit $rc): $(tail -5 "$T/contract")"
fi

# tile-mpi on 4 processes (the master and 3 slaves): the serial report in
# its seventeen columns, bit for bit, and the same mesh.
"$TILE" $DATA/prostate_2.contours -q -o "$T/ser.obj" > "$T/ser.csv" && ok || bad "serial tile failed"
tail -n +2 "$T/ser.csv" > "$T/ser9"
run 4 "$MPIDIR/bin/tile-mpi" $DATA/prostate_2.contours -q -o "$T/mpi.obj" > "$T/mpi.csv" 2> "$T/err" \
  && ok || bad "tile-mpi on 4 processes failed: $(cat "$T/err")"
cut -d, -f1-17 "$T/mpi.csv" | tail -n +2 | cmp -s - "$T/ser9" && ok || bad "4 processes: the report differs from the serial one"
cut -d, -f11 "$T/mpi.csv" | cmp -s - "$(cut -d, -f11 "$T/ser.csv" > "$T/sercost"; echo "$T/sercost")" \
  && ok || bad "4 processes: the cost column differs"
cmp -s "$T/mpi.obj" "$T/ser.obj" && ok || bad "4 processes: the mesh differs from the serial one"
awk -F, 'NR>1 && $1 ~ /^[0-9]+$/ && ($18 != 4 || $25 != "mpi" || $19 <= 0 || $20 <= 0) {bad=1} END{exit bad}' "$T/mpi.csv" \
  && ok || bad "4 processes: procs, backend, time or boundary columns: $(sed -n 2p "$T/mpi.csv")"
# Fewer ranks than processes, the size allocation, d = 20; a real stack of another patient.
"$TILE" $DATA/prostate_4.contours -q > "$T/ser4.csv" && tail -n +2 "$T/ser4.csv" > "$T/ser4"
run 4 "$MPIDIR/bin/tile-mpi" $DATA/prostate_4.contours -q --procs 3 --alloc size --min-diag 20 > "$T/mpi4.csv" 2> "$T/err" \
  && ok || bad "tile-mpi --procs 3: $(cat "$T/err")"
cut -d, -f1-17 "$T/mpi4.csv" | tail -n +2 | cmp -s - "$T/ser4" && ok || bad "--procs 3: the report differs from the serial one"
# One process: the serial solver, as ./tile without --procs.
run 1 "$MPIDIR/bin/tile-mpi" $DATA/prostate_2.contours -q > "$T/one.csv" 2> "$T/err" && cmp -s "$T/one.csv" "$T/ser.csv" \
  && ok || bad "tile-mpi on 1 process is not the serial report: $(cat "$T/err")"
# More ranks than processes: bad usage, exit 2, nothing on stdout.
run 2 "$MPIDIR/bin/tile-mpi" $DATA/tinypatient_1.contours --procs 5 > "$T/out" 2> "$T/err"; rc=$?
[ $rc -ne 0 ] && [ ! -s "$T/out" ] && grep -q 'needs 5 ranks; the mpi run has 2' "$T/err" \
  && ok || bad "--procs 5 on 2 processes: exit $rc, $(cat "$T/err")"

# bench-mpi: the same optimum on every row, as the simulator's, the mpi backend.
run 3 "$MPIDIR/bin/bench-mpi" --points 80 --procs 1..3 --repeat 2 > "$T/b.csv" 2> "$T/err" \
  && ok || bad "bench-mpi: $(cat "$T/err")"
sim=$("$BUILD/bench" --points 80 --procs 3 2>/dev/null | tail -1 | cut -d, -f15)
[ "$(tail -n +2 "$T/b.csv" | wc -l)" -eq 3 ] && [ -n "$sim" ] && \
  awk -F, -v c="$sim" 'NR>1 && ($15 != c || $23 != "mpi" || $9 <= 0) {bad=1} END{exit bad}' "$T/b.csv" \
  && ok || bad "bench-mpi rows: $(cat "$T/b.csv")"

summary

#!/bin/sh
# cli_mpiprogs.sh -- the MPI programs of tests/mpi/ built with Open MPI's
# mpicc and run under its mpirun: the datatype, operation, collective,
# topology and I/O programs (dtype_*, op_*, coll_*, topo_*, io_*) on 1, 3
# and 8 processes, the point-to-point, communicator, attribute,
# error-handler, info and one-sided ones (p2p_*, comm_*, attr_*, err_*,
# info_*, rma_*) on 2 and 5 (the one-sided ones with Open MPI's osc
# components but ucx, which fails to make windows as root on this host:
# OMPI_MCA_osc=^ucx).  Each
# must pass its own checks and print the same "NAME: P passed, F failed"
# line as on tilesim's simulator (build/chk/tests/test_mpiprogs NAME NP
# mpich, build/chk/tests/test_mpiprogs_p2p NAME NP).  Where $MPICC cannot
# build an MPI program (MPI_STATUS, from make check's probe) it says so and
# counts nothing.
BUILD=${BUILD:-build/chk}
. tests/clilib.sh

if [ "${MPI_STATUS:-}" != yes ]; then
  echo "cli_mpiprogs: skipped: ${MPI_STATUS:-MPI_STATUS is not set (make check probes the MPI compiler)}; the MPI programs were not run under Open MPI (apt-get install openmpi-bin libopenmpi-dev)"
  echo "cli_mpiprogs: 0 passed, 0 failed"
  exit 0
fi
MPICC=${MPICC:-mpicc}
MPIRUN=${MPIRUN:-mpirun}
for d in test_mpiprogs test_mpiprogs_p2p; do need "$BUILD/tests/$d" "make check builds it"; done
open_mpi

# group DRIVER "DRIVER'S EXTRA ARGUMENTS" "PROCESS COUNTS" SOURCES...
group() {
  driver="$BUILD/tests/$1"; extra=$2; counts=$3; shift 3
  for src in "$@"; do
    name=$(basename "$src" .c)
    if ! "$MPICC" -std=c11 -O1 -Itests/mpi -o "$T/$name" "$src" -lm > "$T/cc.log" 2>&1; then
      bad "$MPICC cannot build $src: $(head -3 "$T/cc.log")"
      continue
    fi
    ok
    for np in $counts; do
      "$MPIRUN" $OVER -np $np "$T/$name" > "$T/out" 2>&1; rc=$?
      ompi=$(grep -E "^$name: [0-9]+ passed, [0-9]+ failed\$" "$T/out")
      "$driver" "$name" $np $extra > "$T/sim" 2>&1
      sim=$(grep -E "^$name: [0-9]+ passed, [0-9]+ failed\$" "$T/sim")
      if [ $rc -eq 0 ] && [ -n "$ompi" ] && echo "$ompi" | grep -q ' 0 failed$'; then ok; else
        bad "$name on $np processes under Open MPI: exit $rc: $(grep -v '^\[' "$T/out" | tail -3)"; fi
      [ -n "$sim" ] && [ "$sim" = "$ompi" ] && ok || bad "$name on $np: Open MPI says '$ompi', tilesim '$sim'"
    done
  done
}
group test_mpiprogs mpich "1 3 8" tests/mpi/dtype_*.c tests/mpi/op_*.c tests/mpi/coll_*.c tests/mpi/topo_*.c \
  tests/mpi/io_*.c
group test_mpiprogs_p2p "" "2 5" tests/mpi/p2p_*.c tests/mpi/comm_*.c tests/mpi/attr_*.c tests/mpi/err_*.c \
  tests/mpi/info_*.c
export OMPI_MCA_osc=^ucx
group test_mpiprogs_p2p "" "2 5" tests/mpi/rma_*.c

summary

#!/bin/sh
# cli_simgrid.sh -- make check's part of tests/simgrid.sh: where SimGrid's
# smpicc builds an MPI program (SMPI_STATUS=yes, make check's probe of
# $SMPICC), tile-mpi (built by it into build/smpi) under $SMPIRUN and the
# sanitized ./tile on tilesim's simulator must give the same reports and the
# same times within 1% (here: exactly) on a real pair, for P = 2, 3, 5 and
# 9.  Otherwise it says why it was skipped and counts nothing.
QUICK=1 NOBUILD=1 TILE=${BUILD:-build/chk}/tile sh tests/simgrid.sh

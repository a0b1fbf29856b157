#!/bin/sh
# cli_solids.sh -- ./tile end to end on sliced analytic solids, judged by an
# independent mesh checker: tests/test_solids.c run with --tile (the sanitized
# build in $BUILD).  The multi-contour solids and the second-encoding tests
# are enabled when ./tile accepts several contours per slice: see
# several_per_slice in tests/test_solids.c, or run with TILESIM_SOLIDS_ALL=1.
BUILD=${BUILD:-build/chk}
exec "$BUILD/tests/test_solids" --tile "$BUILD/tile"

/* data.h -- where ./bench finds the data its defaults name: the source
 * tree's tests/data (beside the program or here), PREFIX/share/tilesim once
 * installed (make install copies tests/data/slicerrt and tests/data/rtstruct
 * there), or a folder the user names (--data DIR). */
#ifndef BENCH_DATA_H
#define BENCH_DATA_H

#include <stddef.h>

/* A file named as "tests/data/SUB/FILE" (the defaults) or "FILE" (a bare
 * name): itself if it is readable as given, or if it is some other path
 * (has a '/' but does not start with tests/data/); else the first readable
 * of ROOT/SUB/FILE (and for a bare name ROOT/FILE, ROOT/slicerrt/FILE,
 * ROOT/rtstruct/FILE) for ROOT in: dir (if not NULL), BIN/../share/tilesim,
 * BIN/tests/data, BIN/../../tests/data (BIN: the program's folder), and
 * tests/data here.  0 and the path in out, or -1 and a message saying where
 * it looked in out. */
int bench_data_find(const char *name, const char *dir, char *out, size_t len);

#endif

#!/bin/sh
# cli_install.sh -- make install: the
# programs under the names they are installed by (tile, tilesim-bench,
# tilesim-plot), their man pages and documents, and the data bench's
# defaults name go under PREFIX, and the installed programs work from any
# folder: tilesim-bench --tiler, --stack and --dicom find their data in
# PREFIX/share/tilesim, or where --data says; --help is on stdout and names
# the program as installed; man -w finds every page through MANPATH, and
# through PATH alone (man-db adds PATH_ELEMENT/../share/man).  Installs
# make check's sanitized build into a folder of its own (make install-files
# IBIN=... DESTDIR=...), and runs it from another; then make uninstall
# removes every file it wrote, and nothing else.
BUILD=${BUILD:-build/chk}
. tests/clilib.sh
mk() { env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make --no-print-directory -s "$@"; }

mk install-files DESTDIR="$T/root" PREFIX=/opt/ts IBIN="$BUILD" IPLOT="$BUILD/plot" ILIB="$BUILD/lib/libtilesim.a" > "$T/log" 2>&1 \
  && ok || bad "make install-files: $(cat "$T/log")"
P=$T/root/opt/ts
for f in bin/tile bin/tilesim-bench bin/tilesim-plot share/tilesim/slicerrt/prostate_0.contours \
         share/tilesim/slicerrt/README.md share/tilesim/rtstruct/dicompyler_rtss.dcm share/tilesim/rtstruct/README.md \
         share/man/man1/tile.1 share/man/man1/tilesim-bench.1 share/man/man1/tilesim-plot.1 \
         share/man/man5/tilesim-contours.5 share/man/man7/tilesim.7 share/doc/tilesim/paper.md; do
  [ -e "$P/$f" ] && ok || bad "not installed: $f"
done
[ ! -e "$P/bin/bench" ] && ok || bad "installed as bin/bench: a name other software uses (tilesim-bench)"
# Every page of doc/, and no other, under its section.
for pg in doc/*.[1-9]; do
  n=$(basename "$pg"); s=${n##*.}
  cmp -s "$pg" "$P/share/man/man$s/$n" && ok || bad "$pg is not installed as share/man/man$s/$n"
done
# man finds them: through MANPATH, and through PATH alone.
if command -v man > /dev/null 2>&1; then
  for pg in tile.1 tilesim-bench.1 tilesim-plot.1 tilesim.3 tilesim-contours.5 tilesim.7; do
    s=${pg##*.}; n=${pg%.*}
    w=$(MANPATH="$P/share/man" man -w "$s" "$n" 2> "$T/err")
    [ "$w" = "$P/share/man/man$s/$pg" ] && ok || bad "MANPATH=\$P/share/man man -w $s $n: '$w' $(cat "$T/err")"
  done
  w=$(env -u MANPATH PATH="$P/bin:$PATH" man -w tilesim-bench 2> "$T/err")
  [ "$w" = "$P/share/man/man1/tilesim-bench.1" ] && ok || bad "man -w tilesim-bench with $P/bin on the PATH: '$w' $(cat "$T/err")"
else
  echo "cli_install: skipped: man -w (man is not installed here: apt-get install man-db)"
fi

mkdir "$T/elsewhere" && cd "$T/elsewhere" || exit 1
# The default stack's name, and a bare name: both from the installed data.
"$P/bin/tilesim-bench" --tiler --points 20 --naive 20 --input tests/data/slicerrt/prostate_3.contours --repeat 1 > out 2> err \
  && grep -q '^stack:prostate_3.contours,18,' out && ok || bad "bench --tiler, installed: $(cat err)"
"$P/bin/tilesim-bench" --tiler --points 20 --input prostate_2.contours --repeat 1 > out 2> err \
  && grep -q '^stack:prostate_2.contours,' out && ok || bad "bench --tiler --input prostate_2.contours: $(cat err)"
"$P/bin/tilesim-bench" --stack tests/data/slicerrt/prostate_3.contours -j 1 --repeat 1 > out 2> err \
  && [ "$(wc -l < out)" -eq 2 ] && ok || bad "bench --stack, installed: $(cat err)"
"$P/bin/tilesim-bench" --dicom --repeat 1 > out 2> err && grep -q 'dicompyler_rtss.dcm,1940626,' out \
  && ok || bad "bench --dicom, installed: $(cat err)"
"$P/bin/tilesim-plot" --help > out 2> err && [ ! -s err ] && grep -q '^usage: tilesim-plot lines' out \
  && ok || bad "tilesim-plot --help: not on stdout, or not named tilesim-plot"
"$P/bin/tilesim-bench" --help > out 2> err && [ ! -s err ] && grep -q '^usage: tilesim-bench \[OPTIONS\]' out \
  && grep -q '^  tilesim-bench --ring P' out && ok || bad "tilesim-bench --help: not on stdout, or not named tilesim-bench"
"$P/bin/tilesim-bench" --stack --help > out 2> err && grep -q '^usage: tilesim-bench --stack' out \
  && ok || bad "tilesim-bench --stack --help: $(head -1 out)"
"$P/bin/tile" "$P/share/tilesim/slicerrt/tinypatient_1.contours" -q > out 2> err && ok || bad "tile, installed: $(cat err)"

# The testbed's library: a user's program built outside the tree
# through pkg-config, from the installed example and headers (with the
# sanitizers of the installed build); and one with globals of the names
# tilesim uses inside (xmalloc, trace_new, sim_run, ...), which must link
# and keep its own.
for f in lib/libtilesim.a lib/pkgconfig/tilesim.pc include/tilesim/tilesim.h include/tilesim/mp.h \
         share/tilesim/examples/ring.c share/tilesim/examples/jacobi.c; do
  [ -e "$P/$f" ] && ok || bad "not installed: $f"
done
if command -v pkg-config > /dev/null 2>&1; then
  PC="env PKG_CONFIG_PATH=$P/lib/pkgconfig PKG_CONFIG_SYSROOT_DIR=$T/root pkg-config"
  SAN="-fsanitize=address,undefined -fno-omit-frame-pointer"
  cp "$P/share/tilesim/examples/ring.c" .
  if ${CC:-cc} -std=c11 $SAN ring.c $($PC --cflags --libs tilesim) -o ring > log 2>&1; then
    ./ring --procs 4 --net ideal --m 0.25 --per-byte 0 -- 2 8 > out 2> err \
      && grep -q '^ring: 1 s a lap' out && grep -q '^sim,4,4,2,8,64,' out && ok || bad "ring through pkg-config: $(cat out err)"
  else
    bad "ring through pkg-config does not build: $(cat log)"
  fi
  cat > mine.c <<'EOF2'
#include <stdio.h>
#include <stdlib.h>
#include <tilesim/tilesim.h>
/* Names tilesim uses inside; the program's own. */
void *xmalloc(size_t n) { return malloc(n + 1); }
int trace_new = 7, sim_run = 8, args_long = 9;
int place_parse(void) { return 10; }
static void rank(mp *self, void *ud) { (void)ud; (void)self; }
int main(int argc, char **argv) {
  printf("mine: %d %d %d %d %s\n", trace_new, sim_run, args_long, place_parse(), tilesim_version());
  free(xmalloc(1));
  return tilesim_main(argc, argv, rank, NULL);
}
EOF2
  if ${CC:-cc} -std=c11 $SAN mine.c $($PC --cflags --libs tilesim) -o mine > log 2>&1; then
    ./mine --procs 2 > out 2> err && grep -q '^mine: 7 8 9 10 ' out && grep -q '^sim,2,2,' out && ok \
      || bad "a program with tilesim's inner names: $(cat out err)"
  else
    bad "a program with tilesim's inner names does not link: $(cat log)"
  fi
else
  echo "cli_install: skipped: the library through pkg-config (pkg-config not found)"
fi

# The MPI tools: the installed tilesim-mpicc finds the
# installed mpi.h and libtilesim_mpi.so beside itself, the installed
# tilesim-mpirun runs what it built, and the program run on its own finds
# the installed library and says how to run it.
for f in bin/tilesim-mpicc bin/tilesim-mpicxx bin/tilesim-mpirun include/tilesim/mpi/mpi.h \
         include/tilesim/mpi/mpi_funcs.h lib/tilesim/libtilesim_mpi.so; do
  [ -e "$P/$f" ] && ok || bad "not installed: $f"
done
cat > hello.c <<'EOF2'
#include <mpi.h>
#include <stdio.h>
int main(int argc, char **argv) {
  int r, p;
  MPI_Init(&argc, &argv);
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  MPI_Comm_size(MPI_COMM_WORLD, &p);
  printf("rank %d of %d\n", r, p);
  MPI_Finalize();
  return 0;
}
EOF2
"$P/bin/tilesim-mpicc" hello.c -o hello > log 2>&1 && "$P/bin/tilesim-mpirun" -np 3 ./hello > out 2> err \
  && [ "$(sort out | tr '\n' ' ')" = "rank 0 of 3 rank 1 of 3 rank 2 of 3 " ] && ok \
  || bad "the installed tilesim-mpicc and tilesim-mpirun: $(cat log out err)"
./hello > out 2> err; rc=$?
[ $rc -eq 2 ] && grep -q 'tilesim-mpirun -np N ./hello$' err && ok || bad "the installed program run on its own: exit $rc, $(cat out err)"
if command -v c++ > /dev/null 2>&1; then
  "$P/bin/tilesim-mpicxx" -x c++ hello.c -o hellox > log 2>&1 && "$P/bin/tilesim-mpirun" -np 2 ./hellox > out 2> err \
    && [ "$(sort out | tr '\n' ' ')" = "rank 0 of 2 rank 1 of 2 " ] && ok \
    || bad "the installed tilesim-mpicxx: $(cat log out err)"
fi

# Without the data: a message saying where it looked and what to do, exit 1.
mv "$P/share/tilesim" "$T/data"
"$P/bin/tilesim-bench" --tiler --points 20 --input prostate_2.contours --repeat 1 > out 2> err; rc=$?
[ $rc -eq 1 ] && grep -q '^tilesim-bench: prostate_2.contours: not found.*share/tilesim.*--data DIR says where it is$' err \
  && ok || bad "no data: exit $rc, $(cat err)"
# --data DIR: there.
"$P/bin/tilesim-bench" --tiler --points 20 --input prostate_2.contours --data "$T/data" --repeat 1 > out 2> err \
  && grep -q '^stack:prostate_2.contours,' out && ok || bad "--data: $(cat err)"

# make uninstall: every file make install wrote is gone, and the folders
# that are tilesim's own; a file of someone else's, and its folder, stay.
cd - > /dev/null || exit 1
mv "$T/data" "$P/share/tilesim"
echo mine > "$P/bin/mytool"
mkdir -p "$P/share/doc/tilesim/notes" && echo mine > "$P/share/doc/tilesim/notes/mine.txt"
mk uninstall DESTDIR="$T/root" PREFIX=/opt/ts > "$T/log" 2>&1 && ok || bad "make uninstall: $(cat "$T/log")"
left=$(cd "$T/root" && find . -type f | sort | tr '\n' ' ')
[ "$left" = "./opt/ts/bin/mytool ./opt/ts/share/doc/tilesim/notes/mine.txt " ] && ok \
  || bad "make uninstall left files of its own, or removed another's: $left"
for d in share/tilesim include/tilesim; do
  [ ! -e "$P/$d" ] && ok || bad "make uninstall left $d"
done
grep -q "share/doc/tilesim is not empty: left as it is" "$T/log" && ok || bad "make uninstall does not say what it left: $(cat "$T/log")"
rm -r "$P/share/doc/tilesim/notes" "$P/bin/mytool"
mk uninstall DESTDIR="$T/root" PREFIX=/opt/ts > "$T/log" 2>&1 && [ ! -e "$P/share/doc/tilesim" ] && ok \
  || bad "make uninstall twice: $(cat "$T/log")"

summary

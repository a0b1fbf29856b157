#!/bin/sh
# cli_outputs.sh -- a file a program is asked to write is checked before its
# work (tilesim(7): a failed run prints no data row): tile -o, --trace,
# --contours and -o DIR/; a program of one's own's --stats and --trace;
# tilesim-mpirun's; bench -o, --claims-map -o, --ring's traces; plot -o.
# Each into a folder that does not exist, and onto a folder: exit 1, one
# line naming the path, and no sign of the work: nothing on stdout (tile's
# report, the program's own lines and summary), no progress line, and no
# complaint about an input that comes later (a missing stack).
BUILD=${BUILD:-build/chk}
. tests/clilib.sh
export TILESIM_PROGRESS_S=0   # a progress line at every step: work shows

NO=$T/no/such/folder
mkdir "$T/dir" "$T/dir.obj" "$T/dir.json" "$T/dir.csv" "$T/dir.svg"   # folders where files should go
STACK=tests/data/slicerrt/tinypatient_0.contours
DCM=tests/data/rtstruct/dicompyler_rtss.dcm

# refused NAME PATH CMD...: exit 1, stderr one line naming PATH, stdout empty.
refused() {
  name=$1; path=$2; shift 2
  "$@" > "$T/out" 2> "$T/err"; rc=$?
  [ $rc -eq 1 ] && [ "$(wc -l < "$T/err")" -eq 1 ] && grep -qF -- "$path" "$T/err" && [ ! -s "$T/out" ] && ok \
    || bad "$name: exit $rc, stdout $(wc -c < "$T/out") bytes, stderr: $(head -c 600 "$T/err")"
}

for p in "$NO/x" "$T/dir"; do
  case $p in "$T/dir") what=folder ;; *) what=missing ;; esac
  o=$p.obj; t=$p.json; s=$p.csv
  refused "tile -o ($what)" "$o" "$BUILD/tile" $STACK -o "$o"
  refused "tile --trace ($what)" "$t" "$BUILD/tile" $STACK --procs 2 --trace "$t"
  [ $what = missing ] && refused "tile FILE.dcm --contours ($what)" "$s" "$BUILD/tile" $DCM --roi Heart --contours "$s"
  refused "ring --stats ($what)" "$s" "$BUILD/examples/ring" --procs 4 --stats "$s" -- 2 8
  refused "ring --trace ($what)" "$t" "$BUILD/examples/ring" --procs 4 --trace "$t" -- 2 8
  refused "bench -o ($what)" "$s" "$BUILD/bench" --points 30 --procs 1..3 --input "$T/none.contours" -o "$s"
  refused "bench --claims-map -o ($what)" "$s" "$BUILD/bench" --claims-map --input "$T/none.contours" -o "$s"
  refused "bench --ring --trace-json ($what)" "$t" "$BUILD/bench" --ring 4 --laps 2 --trace-json "$t"
  refused "plot surface -o ($what)" "$p.svg" "$BUILD/plot" surface "$T/none.contours" -o "$p.svg"
  refused "plot lines -o ($what)" "$p.svg" "$BUILD/plot" lines "$T/none.csv" -x a -y b -o "$p.svg"
done
refused "tile FILE.dcm -o DIR/ (missing parent)" "$NO" "$BUILD/tile" $DCM --roi all -q -o "$NO/"
# A folder tile makes is made only when the run succeeds, and its files are there.
"$BUILD/tile" $DCM --roi Heart --roi 'Lt Lung' -q -o "$T/new/" > /dev/null 2>&1 && [ -s "$T/new/Heart.stl" ] && ok \
  || bad "tile --roi ... -o NEW/: $(ls "$T/new" 2>&1)"

# tilesim-mpirun: --stats and --trace, before a program's line is printed.
cat > "$T/hello.c" <<'EOF'
#include <mpi.h>
#include <stdio.h>
int main(int argc, char **argv) {
  MPI_Init(&argc, &argv);
  printf("hello\n");
  MPI_Finalize();
  return 0;
}
EOF
if "$BUILD/tilesim-mpicc" "$T/hello.c" -o "$T/hello" > "$T/log" 2>&1; then
  refused "tilesim-mpirun --stats" "$NO/s.csv" "$BUILD/tilesim-mpirun" -np 2 --stats "$NO/s.csv" "$T/hello"
  refused "tilesim-mpirun --trace" "$T/dir" "$BUILD/tilesim-mpirun" -np 2 --trace "$T/dir" "$T/hello"
  "$BUILD/tilesim-mpirun" -np 2 --stats "$T/s.csv" "$T/hello" > "$T/out" 2> "$T/err" && [ -s "$T/s.csv" ] \
    && [ "$(cat "$T/out")" = "hello
hello" ] && ok || bad "tilesim-mpirun --stats FILE: $(cat "$T/out" "$T/err")"
else
  bad "tilesim-mpicc hello.c: $(cat "$T/log")"
fi
# Nothing left behind by the checks.
left=$(find "$T" -name '*.tmp*' | head -3)
[ -z "$left" ] && ok || bad "temporary files left: $left"

summary

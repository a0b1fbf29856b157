#!/bin/sh
# cli_mpiwrap.sh -- MPI programs as people write them, built by
# tilesim-mpicc and tilesim-mpicxx and run by tilesim-mpirun:
#   - a C program that uses libc's per-process names for its own purposes
#     (tests/mpirun/names.c: a struct member optarg, locals named rand and
#     time, ...) and C++ programs (tests/mpirun/cxxranks.cc: static objects,
#     exceptions, containers, iostreams, thread_local; cxxenv.cc: MPI_Init
#     and MPI_Finalize in a static object's constructor and destructor), and
#     thread-local variables (tests/mpirun/tls.c) print, sorted, what
#     Open MPI's mpicc/mpicxx and mpirun print, on the simulator and on
#     threads;
#   - a project with a Makefile (tests/mpirun/project) built by make
#     CC=tilesim-mpicc (objects, then a link) runs as Open MPI's build does;
#   - the compiler: TILESIM_CC and TILESIM_CXX are honoured, CC is not, and
#     a compiler that runs the wrapper again is refused (under a timeout, a
#     process limit and a fuse, so that a regression cannot fork without end);
#   - the errors: a program run on its own says how to run it (exit 2); a
#     call of a function tilesim has never heard of fails the link, named;
#     the warning names only the unimplemented functions the program's code
#     calls; tilesim-mpirun says what a file not built by tilesim-mpicc is;
#   - -show, -showme, --showme:compile, --showme:link, -compile_info;
#   - libtilesim_mpi.so defines what tilesim-mpirun exports, no more, no less.
BUILD=${BUILD:-build/chk}
RUN=$BUILD/tilesim-mpirun
MCC=$BUILD/tilesim-mpicc
MCXX=$BUILD/tilesim-mpicxx
. tests/clilib.sh
own_tmpdir
unset CC CXX TILESIM_CC TILESIM_CXX

OMPI=""
if [ "${MPI_STATUS:-}" = yes ]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
  export OMPI_MCA_mpi_yield_when_idle=1
  OMPI=yes
else
  echo "cli_mpiwrap: skipped: comparisons with Open MPI (${MPI_STATUS:-make check sets MPI_STATUS})"
fi
HAVECXX=""
if command -v c++ > /dev/null 2>&1; then HAVECXX=yes; else echo "cli_mpiwrap: skipped: C++ (no c++ compiler)"; fi
# same_lines WHAT A B: the two outputs, sorted, are equal and not empty.
same_lines() {
  sort "$2" > "$T/sa"; sort "$3" > "$T/sb"
  cmp -s "$T/sa" "$T/sb" && [ -s "$T/sa" ] && ok || bad "$1: tilesim and Open MPI differ: $(diff "$T/sa" "$T/sb" | head -6)"
}

# ---- programs with libc's names, and C++ -------------------------------------
"$MCC" -Wall tests/mpirun/names.c -o "$T/names" > "$T/log" 2>&1 && ok || bad "tilesim-mpicc names.c: $(cat "$T/log")"
for be in sim threads; do
  "$RUN" -np 4 --backend $be "$T/names" -v -n word rest > "$T/names.$be" 2> "$T/e" && ok || bad "names ($be): $(cat "$T/e")"
done
grep -q '^rank 3: o.optarg member o.optind 10 o.rand() 4 exits 4 ' "$T/names.sim" && ok || bad "names: $(cat "$T/names.sim")"
# Thread-local variables, each rank's own (the program's __tls_get_addr is the loader's).
"$MCC" -O2 tests/mpirun/tls.c -o "$T/tls" > "$T/log" 2>&1 && ok || bad "tilesim-mpicc tls.c: $(cat "$T/log")"
for be in sim threads; do
  "$RUN" -np 7 --backend $be "$T/tls" > "$T/tls.$be" 2> "$T/e" && grep -qx '7 of 7 ranks see their own thread-local variables' "$T/tls.$be" \
    && ok || bad "tls ($be): $(cat "$T/tls.$be" "$T/e")"
done
if [ -n "$HAVECXX" ]; then
  "$MCXX" -Wall -O2 tests/mpirun/cxxranks.cc -o "$T/cxx" > "$T/log" 2>&1 && ok || bad "tilesim-mpicxx cxxranks.cc: $(cat "$T/log")"
  # Under make check's sanitized tilesim-mpirun, a program's delete of what
  # libstdc++'s own operator new made (libstdc++ binds its new to itself)
  # looks like malloc against delete to AddressSanitizer: as in any
  # uninstrumented C++ code in a sanitized process, not a fault of either.
  for be in sim threads; do
    ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}alloc_dealloc_mismatch=0" "$RUN" -np 5 --backend $be "$T/cxx" \
      > "$T/cxx.$be" 2> "$T/e" && ok || bad "cxxranks ($be): $(cat "$T/e")"
  done
  # Each rank's own exception in flight: rethrown after an MPI call inside
  # the catch, while the other ranks caught theirs.
  [ "$(grep -c '^rank \([0-4]\): first rank \1 hit bottom; again rank \1 hit bottom code \1\?0; depth ' "$T/cxx.sim")" -eq 5 ] \
    && [ "$(grep -c 'constructions 1 order registry second; local static 101 102$' "$T/cxx.sim")" -eq 5 ] \
    && [ "$(grep -c 'registry destroyed after main' "$T/cxx.sim")" -eq 5 ] && ok || bad "cxxranks: $(cat "$T/cxx.sim")"
  # MPI_Init in a static object's constructor, MPI_Finalize in its destructor.
  "$MCXX" tests/mpirun/cxxenv.cc -o "$T/cxxenv" > "$T/log" 2>&1 && ok || bad "tilesim-mpicxx cxxenv.cc: $(cat "$T/log")"
  ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}alloc_dealloc_mismatch=0" "$RUN" -np 3 "$T/cxxenv" > "$T/cxxenv.sim" 2> "$T/e" \
    && [ "$(grep -c 'finalized 1 after main$' "$T/cxxenv.sim")" -eq 3 ] && ok || bad "cxxenv: $(cat "$T/cxxenv.sim" "$T/e")"
fi
if [ -n "$OMPI" ]; then
  ${MPICC:-mpicc} tests/mpirun/names.c -o "$T/names.ompi" > "$T/log" 2>&1 || bad "mpicc names.c: $(cat "$T/log")"
  timeout 60 ${MPIRUN:-mpirun} -np 4 "$T/names.ompi" -v -n word rest > "$T/oout" 2> "$T/oerr" || bad "names under Open MPI: $(cat "$T/oerr")"
  for be in sim threads; do same_lines "names ($be)" "$T/names.$be" "$T/oout"; done
  ${MPICC:-mpicc} -O2 tests/mpirun/tls.c -o "$T/tls.ompi" > "$T/log" 2>&1 || bad "mpicc tls.c: $(cat "$T/log")"
  timeout 60 ${MPIRUN:-mpirun} -np 7 "$T/tls.ompi" > "$T/oout" 2> "$T/oerr" || bad "tls under Open MPI: $(cat "$T/oerr")"
  same_lines "tls" "$T/tls.sim" "$T/oout"
  if [ -n "$HAVECXX" ]; then
    ${MPICXX:-mpicxx} -O2 tests/mpirun/cxxranks.cc -o "$T/cxx.ompi" > "$T/log" 2>&1 || bad "mpicxx cxxranks.cc: $(cat "$T/log")"
    timeout 60 ${MPIRUN:-mpirun} -np 5 "$T/cxx.ompi" > "$T/oout" 2> "$T/oerr" || bad "cxxranks under Open MPI: $(cat "$T/oerr")"
    for be in sim threads; do same_lines "cxxranks ($be)" "$T/cxx.$be" "$T/oout"; done
    ${MPICXX:-mpicxx} tests/mpirun/cxxenv.cc -o "$T/cxxenv.ompi" > "$T/log" 2>&1 || bad "mpicxx cxxenv.cc: $(cat "$T/log")"
    timeout 60 ${MPIRUN:-mpirun} -np 3 "$T/cxxenv.ompi" > "$T/oout" 2> "$T/oerr" || bad "cxxenv under Open MPI: $(cat "$T/oerr")"
    same_lines "cxxenv" "$T/cxxenv.sim" "$T/oout"
  fi
fi

# err(3) and warn(3) name the program, as in its own process (each rank's
# line whole on the simulator; Open MPI's processes write theirs in pieces
# that interleave, so no comparison).
printf '#include <mpi.h>\n#include <err.h>\nint main(int c, char **v) { int r; MPI_Init(&c, &v); MPI_Comm_rank(MPI_COMM_WORLD, &r); warnx("rank %%d warns", r); MPI_Finalize(); return 0; }\n' > "$T/warnx.c"
"$MCC" "$T/warnx.c" -o "$T/warnx" > "$T/log" 2>&1 && "$RUN" -np 2 "$T/warnx" > /dev/null 2> "$T/e" \
  && [ "$(grep -c '^warnx: rank [01] warns$' "$T/e")" -eq 2 ] && ok || bad "warnx: $(cat "$T/log" "$T/e")"

# ---- a project built by make CC=tilesim-mpicc ------------------------------------
if command -v make > /dev/null 2>&1; then
  cp -r tests/mpirun/project "$T/proj"
  make -s -C "$T/proj" CC="$PWD/$MCC" > "$T/log" 2>&1 && [ -f "$T/proj/main.o" ] && [ -f "$T/proj/stats.o" ] && ok \
    || bad "make CC=tilesim-mpicc: $(cat "$T/log")"
  "$RUN" -np 3 "$T/proj/heat" 40 > "$T/heat.ts" 2> "$T/e" && grep -q '^3 ranks, 40 steps: min ' "$T/heat.ts" && ok \
    || bad "the project's program: $(cat "$T/heat.ts" "$T/e")"
  # CC in the environment (make's default, as `CC=tilesim-mpicc make` sets it):
  # tilesim-mpicc does not take its compiler from it.
  make -s -C "$T/proj" clean > /dev/null
  (CC="$PWD/$MCC"; export CC; timeout 60 make -s -C "$T/proj") > "$T/log" 2>&1 && [ -x "$T/proj/heat" ] && ok \
    || bad "CC=tilesim-mpicc in the environment: $(head -5 "$T/log")"
  if [ -n "$OMPI" ]; then
    cp -r tests/mpirun/project "$T/projo"
    make -s -C "$T/projo" CC="${MPICC:-mpicc}" > "$T/log" 2>&1 || bad "make CC=mpicc: $(cat "$T/log")"
    timeout 60 ${MPIRUN:-mpirun} -np 3 "$T/projo/heat" 40 > "$T/heat.om" 2> "$T/oerr" || bad "heat under Open MPI: $(cat "$T/oerr")"
    same_lines "the project's program" "$T/heat.ts" "$T/heat.om"
  fi
else
  echo "cli_mpiwrap: skipped: a project built by make (no make)"
fi

# ---- the compiler ---------------------------------------------------------------------
printf '#include <mpi.h>\n#include <stdio.h>\nint main(int c, char **v) { int r; MPI_Init(&c, &v); MPI_Comm_rank(MPI_COMM_WORLD, &r); printf("hi %%d\\n", r); MPI_Finalize(); return 0; }\n' > "$T/hi.c"
printf '#!/bin/sh\necho "$@" >> "%s/cc.log"\nexec cc "$@"\n' "$T" > "$T/mycc"
chmod +x "$T/mycc"
TILESIM_CC="$T/mycc" "$MCC" "$T/hi.c" -o "$T/hi" > "$T/log" 2>&1 && grep -q "hi.c" "$T/cc.log" && "$RUN" -np 2 "$T/hi" > "$T/o" 2>&1 \
  && [ "$(sort "$T/o" | tr '\n' ' ')" = "hi 0 hi 1 " ] && ok || bad "TILESIM_CC: $(cat "$T/log" "$T/o")"
if [ -n "$HAVECXX" ]; then
  printf '#!/bin/sh\necho "$@" >> "%s/cxx.log"\nexec c++ "$@"\n' "$T" > "$T/mycxx"
  chmod +x "$T/mycxx"
  TILESIM_CXX="$T/mycxx" "$MCXX" -x c++ "$T/hi.c" -o "$T/hix" > "$T/log" 2>&1 && grep -q "hi.c" "$T/cxx.log" && ok \
    || bad "TILESIM_CXX: $(cat "$T/log")"
fi
# A compiler that is the wrapper, directly or through a script: refused,
# exit 2, a handful of processes at most.  The script is a fuse: past 20
# calls it stops, so that a regression fails here rather than forking on.
printf '#!/bin/sh\nn=$(cat "%s/fuse" 2>/dev/null || echo 0); echo $((n + 1)) > "%s/fuse"\n[ "$n" -ge 20 ] && exit 99\nexec "%s" "$@"\n' \
  "$T" "$T" "$PWD/$MCC" > "$T/loop"
chmod +x "$T/loop"
for via in "$PWD/$MCC" "$T/loop"; do
  rm -f "$T/fuse"
  (ulimit -u 256 2> /dev/null; TILESIM_CC="$via" timeout 20 "$MCC" "$T/hi.c" -o "$T/never") > "$T/o" 2> "$T/e"; rc=$?
  [ $rc -eq 2 ] && grep -q 'must name a C compiler' "$T/e" && [ "$(cat "$T/fuse" 2> /dev/null || echo 0)" -le 1 ] && ok \
    || bad "TILESIM_CC=$via: exit $rc, $(cat "$T/fuse" 2> /dev/null) calls, $(head -3 "$T/e")"
done

# ---- errors -----------------------------------------------------------------------------
# Run on its own: how to run it, exit 2, nothing else.
"$T/hi" > "$T/o" 2> "$T/e"; rc=$?
[ $rc -eq 2 ] && [ ! -s "$T/o" ] && grep -q "tilesim-mpirun -np N $T/hi\$" "$T/e" && ok || bad "run on its own: exit $rc, $(cat "$T/o" "$T/e")"
# A program linked by the plain compiler against libtilesim_mpi.so, without
# tilesim-mpicc's layout (read-only, code and data segments a page apart,
# RELRO): the loader's other layout, two mappings a rank, the same answers.
cc -fPIC -shared -I "$(dirname "$MCC")/../include/tilesim/mpi" tests/mpirun/names.c -o "$T/plain" \
  "$(dirname "$MCC")/../lib/tilesim/libtilesim_mpi.so" > "$T/log" 2>&1 \
  && "$RUN" -np 4 "$T/plain" -v -n word rest > "$T/plain.out" 2> "$T/e" && cmp -s "$T/plain.out" "$T/names.sim" && ok \
  || bad "a program linked otherwise: $(cat "$T/log" "$T/e" | head -5)"
# A program that calls no MPI function (the linker would drop a library it
# needs nothing from): the same, and tilesim-mpirun runs it.
printf 'int main(void) { return 0; }\n' > "$T/nompi.c"
"$MCC" "$T/nompi.c" -o "$T/nompi" > "$T/o" 2>&1 && "$RUN" -np 2 "$T/nompi" > "$T/o" 2>&1 && ok || bad "a program without MPI calls: $(cat "$T/o")"
"$T/nompi" > "$T/o" 2> "$T/e"; rc=$?
[ $rc -eq 2 ] && grep -q "tilesim-mpirun -np N $T/nompi\$" "$T/e" && ok || bad "without MPI calls, on its own: exit $rc, $(cat "$T/o" "$T/e")"
# A function tilesim has never heard of: an MPI-4 one, a typo.  The link
# fails naming it, and leaves no program.
for f in MPI_Session_init MPI_Comm_rnak; do
  printf '#include <mpi.h>\nint %s(void *a, void *b);\nint main(int c, char **v) { MPI_Init(&c, &v); %s(0, 0); return MPI_Finalize(); }\n' $f $f > "$T/unk.c"
  "$MCC" "$T/unk.c" -o "$T/unk" > "$T/o" 2>&1; rc=$?
  [ $rc -ne 0 ] && grep -q "undefined reference to .$f" "$T/o" && [ ! -e "$T/unk" ] && ok || bad "$f: exit $rc, $(cat "$T/o")"
done
# The warning names what the program's code calls: not what it takes the
# address of (a callback, a function pointer), not what an archive's unused
# functions call (as MPICH's test library's).
cat > "$T/lib.c" <<'EOF'
#include <mpi.h>
int used(void) { return MPI_Barrier(MPI_COMM_WORLD); }
int unused(void) { return MPI_Comm_disconnect(0); }
EOF
cat > "$T/warn.c" <<'EOF'
#include <mpi.h>
#include <stdio.h>
int used(void);
int main(int c, char **v) {
  MPI_Init(&c, &v);
  MPI_Comm_copy_attr_function *volatile cb = MPI_COMM_NULL_COPY_FN;
  int (*volatile fp)(const char *) = MPI_Close_port;
  used();
  if (c > 5) MPI_Comm_spawn("x", MPI_ARGV_NULL, 1, MPI_INFO_NULL, 0, MPI_COMM_SELF, 0, MPI_ERRCODES_IGNORE);
  printf("%d\n", cb != 0 && fp != 0);
  return MPI_Finalize();
}
EOF
"$MCC" -c "$T/lib.c" -o "$T/lib.o" && ar rcs "$T/libw.a" "$T/lib.o" && "$MCC" "$T/warn.c" "$T/libw.a" -o "$T/warn" > "$T/o" 2>&1 \
  && [ "$(grep -c warning "$T/o")" -eq 1 ] && grep -q "^tilesim-mpicc: warning: $T/warn calls MPI_Comm_spawn, which tilesim does not implement: a run stops if it calls it\$" "$T/o" \
  && "$RUN" -np 2 "$T/warn" > /dev/null 2>&1 && ok || bad "the warning names what the code calls: $(cat "$T/o")"
# libtilesim_mpi.so defines exactly what tilesim-mpirun gives programs: a
# function one has and the other lacks would pass the link and fail the run,
# or fail the link of a program tilesim-mpirun could run.
LIBDIR=$(dirname "$MCC")/../lib/tilesim
if command -v nm > /dev/null 2>&1; then
  nm -D --defined-only "$RUN" | awk '{ print $3 }' | grep -E '^(P?MPI_|tilesim_|smpi_|sg_file_|__sanitizer_cov)' | sort > "$T/exp"
  nm -D --defined-only "$LIBDIR/libtilesim_mpi.so" | awk '{ print $3 }' | grep -E '^(P?MPI_|tilesim_|smpi_|sg_file_|__sanitizer_cov)' | sort > "$T/stub"
  [ "$(wc -l < "$T/exp")" -gt 800 ] && cmp -s "$T/exp" "$T/stub" && ok \
    || bad "libtilesim_mpi.so and tilesim-mpirun's exports differ: $(diff "$T/exp" "$T/stub" | head -5)"
else
  echo "cli_mpiwrap: skipped: libtilesim_mpi.so against tilesim-mpirun's exports (no nm)"
fi
# A program written for SMPI removes its files with SimGrid's sg_file calls
# (MPICH's io tests as SimGrid keeps them): it links against
# libtilesim_mpi.so and runs.  The reference: the file the program made
# with MPI-IO is gone, and sg_file_get_name gives the path it was given.
cat > "$T/sg.c" << 'EOF'
#include <mpi.h>
#include <stdio.h>
typedef struct sg_file *sg_file_t;   /* simgrid/plugins/file_system.h's */
sg_file_t sg_file_open(const char *fullpath, void *data);
const char *sg_file_get_name(const struct sg_file *fd);
void sg_file_unlink(sg_file_t fd);
int main(int argc, char **argv) {
  MPI_File f;
  MPI_Init(&argc, &argv);
  MPI_File_open(MPI_COMM_WORLD, argv[1], MPI_MODE_CREATE | MPI_MODE_WRONLY, MPI_INFO_NULL, &f);
  MPI_File_close(&f);
  sg_file_t s = sg_file_open(argv[1], NULL);
  printf("%s\n", sg_file_get_name(s));
  sg_file_unlink(s);
  MPI_Finalize();
  return 0;
}
EOF
"$MCC" "$T/sg.c" -o "$T/sg" > "$T/o" 2>&1 && "$RUN" -np 1 "$T/sg" "$T/sgfile" > "$T/o" 2>&1 \
  && [ "$(cat "$T/o")" = "$T/sgfile" ] && [ ! -e "$T/sgfile" ] && ok || bad "sg_file calls: $(cat "$T/o")"
# Files not built by tilesim-mpicc: what they are, and how to build one.
printf '#!/bin/sh\necho hi\n' > "$T/script"
chmod +x "$T/script"
cc -c "$T/hi.c" -I "$(dirname "$MCC")/../include/tilesim/mpi" -o "$T/hi.o" 2> /dev/null
printf 'int f(void) { return 1; }\n' > "$T/f.c" && cc -shared -fPIC "$T/f.c" -o "$T/libf.so"
CAT=$(command -v cat)
for f in "$T/script:a script" "$CAT:a program not built by tilesim-mpicc" "$T/hi.o:an object file" \
         "$T/libf.so:a shared library"; do
  file=${f%%:*}; what=${f#*:}
  "$RUN" -np 2 "$file" > "$T/o" 2> "$T/e"; rc=$?
  [ $rc -eq 2 ] && [ ! -s "$T/o" ] && grep -q "is $what.*build it with tilesim-mpicc" "$T/e" && ok \
    || bad "tilesim-mpirun $file: exit $rc, $(cat "$T/e")"
done
if [ -n "$OMPI" ]; then
  ${MPICC:-mpicc} "$T/hi.c" -o "$T/hi.ompi" 2> /dev/null
  "$RUN" -np 2 "$T/hi.ompi" > "$T/o" 2> "$T/e"; rc=$?
  [ $rc -eq 2 ] && grep -q "is a program built for another MPI (it needs libmpi" "$T/e" && ok || bad "Open MPI's program: exit $rc, $(cat "$T/e")"
fi
# A damaged program: a clear line, exit 2.
head -c 1000 "$T/hi" > "$T/cut"
"$RUN" -np 2 "$T/cut" > "$T/o" 2> "$T/e"; rc=$?
[ $rc -eq 2 ] && [ "$(wc -l < "$T/e")" -eq 1 ] && grep -q "$T/cut is a damaged ELF file (corrupt or truncated: .* (byte [0-9]*))" "$T/e" && ok \
  || bad "a truncated program: exit $rc, $(cat "$T/e")"

# -static cannot be loaded: refused, exit 2, no program.
"$MCC" -static "$T/hi.c" -o "$T/static" > "$T/o" 2>&1; rc=$?
[ $rc -eq 2 ] && grep -q -- '-static' "$T/o" && [ ! -e "$T/static" ] && ok || bad "-static: exit $rc, $(cat "$T/o")"

# ---- -show and friends ----------------------------------------------------------------
"$MCC" -show x.c -o x > "$T/o" 2>&1 && grep -q '^cc -I[^ ]*/include/tilesim/mpi x.c -o x -fPIC .* -shared .*libtilesim_mpi.so' "$T/o" && ok \
  || bad "tilesim-mpicc -show: $(cat "$T/o")"
"$MCC" -showme -c x.c > "$T/o" 2>&1 && ! grep -q 'shared' "$T/o" && grep -q ' -c x.c ' "$T/o" && ok || bad "-showme -c: $(cat "$T/o")"
"$MCC" --showme:compile > "$T/o" 2>&1 && grep -q '^-I[^ ]*/include/tilesim/mpi -fPIC' "$T/o" && ok || bad "--showme:compile: $(cat "$T/o")"
"$MCC" --showme:link > "$T/o" 2>&1 && grep -q '^-shared .*libtilesim_mpi.so .*-Wl,-rpath,' "$T/o" && ok || bad "--showme:link: $(cat "$T/o")"
"$MCC" -compile_info > "$T/o" 2>&1 && grep -q '^cc -I' "$T/o" && ok || bad "-compile_info: $(cat "$T/o")"
TILESIM_CXX="g++ -g" "$MCXX" -show y.cc > "$T/o" 2>&1 && grep -q '^g++ -g -I[^ ]* y.cc ' "$T/o" && ok || bad "tilesim-mpicxx -show: $(cat "$T/o")"
"$MCXX" --help > "$T/o" 2>&1 && grep -q 'TILESIM_CXX' "$T/o" && ok || bad "tilesim-mpicxx --help: $(cat "$T/o")"
"$MCXX" > "$T/o" 2> "$T/e"; rc=$?
[ $rc -eq 2 ] && [ -s "$T/e" ] && ok || bad "tilesim-mpicxx without arguments: exit $rc"

[ -z "$(ls "$TMPDIR")" ] && ok || bad "left in \$TMPDIR: $(ls "$TMPDIR")"
summary

#!/bin/sh
# cli_mpiprobe.sh -- the MPI detection: make mpi-probe
# compiles two lines of MPI once and says "yes" or why not; the MPI tests
# take that answer and look for nothing themselves.  Checked with an mpicc
# that does not exist (MPICC=no-such), a fake mpicc on the PATH that exists
# but cannot compile (Debian's openmpi-bin without libopenmpi-dev), one
# that compiles but has no mpirun beside it, and what tests/cli_mpi.sh and
# tests/simgrid.sh then say.  Runs make in a folder of its own.
. tests/clilib.sh
# make as a user runs it, not as part of make check's own make.
mk() { env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make --no-print-directory -s PROBE="$T/probe" "$@"; }

mkdir -p "$T/bin" "$T/bin2"
cat > "$T/bin/mpicc" <<'EOF'
#!/bin/sh
# a fake mpicc: the wrapper is installed, the headers are not
echo "probe.c:1:10: fatal error: mpi.h: No such file or directory" >&2
exit 1
EOF
cat > "$T/bin2/mpicc" <<'EOF'
#!/bin/sh
# a fake mpicc that builds anything (by doing nothing)
for a; do case $prev in -o) : > "$a" ;; esac; prev=$a; done
exit 0
EOF
chmod +x "$T/bin/mpicc" "$T/bin2/mpicc"

mk mpi-probe MPICC=no-such SMPICC=no-such-either && ok || bad "make mpi-probe MPICC=no-such failed"
[ "$(cat "$T/probe/mpicc")" = "no-such not found" ] && ok || bad "MPICC=no-such: $(cat "$T/probe/mpicc")"
[ "$(cat "$T/probe/smpicc")" = "no-such-either not found" ] && ok || bad "SMPICC=no-such-either: $(cat "$T/probe/smpicc")"

PATH="$T/bin:$PATH" mk mpi-probe MPICC=mpicc && ok || bad "make mpi-probe with a broken mpicc failed"
case $(cat "$T/probe/mpicc") in
  "mpicc cannot build a two-line MPI program: probe.c:1:10: fatal error: mpi.h: No such file or directory") ok ;;
  *) bad "a broken mpicc: $(cat "$T/probe/mpicc")" ;;
esac

PATH="$T/bin2:$PATH" mk mpi-probe MPICC=mpicc MPIRUN=no-such-mpirun && ok || bad "make mpi-probe without mpirun failed"
[ "$(cat "$T/probe/mpicc")" = "no-such-mpirun not found" ] && ok || bad "no mpirun: $(cat "$T/probe/mpicc")"

# The tests take the answer: skipped, saying why, nothing counted, exit 0.
for why in "no-such not found" "mpicc cannot build a two-line MPI program: mpi.h: No such file or directory"; do
  out=$(MPI_STATUS="$why" sh tests/cli_mpi.sh 2>&1); rc=$?
  [ $rc -eq 0 ] && printf '%s\n' "$out" | grep -qF "cli_mpi: skipped: $why" &&
    printf '%s\n' "$out" | tail -n 1 | grep -qx 'cli_mpi: 0 passed, 0 failed' && ok || bad "cli_mpi with '$why': $rc $out"
  out=$(SMPI_STATUS="$why" QUICK=1 NOBUILD=1 sh tests/simgrid.sh 2>&1); rc=$?
  [ $rc -eq 0 ] && printf '%s\n' "$out" | grep -qF "simgrid: skipped: $why" && ok || bad "simgrid.sh with '$why': $rc $out"
done
# Without an answer they do not go looking: they say so.
out=$(env -u MPI_STATUS sh tests/cli_mpi.sh 2>&1)
printf '%s\n' "$out" | grep -q '^cli_mpi: skipped: MPI_STATUS is not set' && ok || bad "cli_mpi without MPI_STATUS: $out"
# tests/run.sh repeats the skipped lines before its last line.
out=$(MPI_STATUS="no-such not found" sh tests/run.sh build/chk tests/cli_mpi.sh 2>&1)
printf '%s\n' "$out" | tail -n 3 | head -n 2 | grep -qx '  cli_mpi: skipped: no-such not found; the MPI tests were not run (apt-get install openmpi-bin libopenmpi-dev)' &&
  printf '%s\n' "$out" | tail -n 1 | grep -qx '0 passed, 0 failed' && ok || bad "run.sh's summary: $out"

summary

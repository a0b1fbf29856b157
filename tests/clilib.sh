# clilib.sh -- what the command-line tests (tests/cli_*.sh) share; each
# sources it first (`. tests/clilib.sh`, from the tree's root):
#   NAME     the script's name without .sh (cli_foo), which prefixes its lines;
#   T        a new directory under /tmp, removed when the script exits or is
#            interrupted;
#   ok       counts a check passed;  bad WHY  counts one failed and says WHY;
#   summary  the last line tests/run.sh reads, "NAME: P passed, F failed",
#            and the script's exit status (0 when nothing failed);
#   need FILE WHY  a program the script needs: when FILE is not there to run,
#            a failed check naming it and WHY, the summary, exit 1;
#   mesh_volume_is CSV WANT  the report CSV's mesh row says closed, and a
#            volume (column 13) WANT to 1e-9 of it;
#   own_tmpdir  TMPDIR=$T/tmp, made, for the programs run: what they leave
#            there shows;
#   open_mpi    the settings $MPIRUN needs here when it is Open MPI's: root
#            allowed, plain copies in its shared-memory transport (containers
#            forbid cross-process ones), and OVER=--oversubscribe (else empty)
#            for more ranks than cores.
NAME=$(basename "$0" .sh)
T=$(mktemp -d "/tmp/tilesim-${NAME#cli_}.XXXXXX") || exit 1
trap 'rm -rf "$T"' EXIT
trap 'exit 1' INT TERM
pass=0; fail=0
ok()  { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "$NAME: $*"; }
summary() {
  echo "$NAME: $pass passed, $fail failed"
  [ "$fail" -eq 0 ]
}
need() {
  [ -x "$1" ] && return 0
  bad "$1 is missing ($2)"
  summary
  exit 1
}
mesh_volume_is() {
  awk -F, -v want="$2" '$1 == "mesh" { d = $13 - want; if (d < 0) d = -d; ok = $7 == "closed" && d <= 1e-9 * want }
                        END { exit !ok }' "$1"
}
own_tmpdir() {
  export TMPDIR="$T/tmp"
  mkdir -p "$TMPDIR"
}
open_mpi() {
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
  export OMPI_MCA_btl_vader_single_copy_mechanism=none
  OVER=""
  "$MPIRUN" --version 2>/dev/null | grep -q "Open MPI" && OVER="--oversubscribe"
}

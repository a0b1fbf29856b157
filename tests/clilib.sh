# clilib.sh -- what the command-line tests (tests/cli_*.sh) share; each
# sources it first (`. tests/clilib.sh`, from the tree's root):
#   NAME     the script's name without .sh (cli_foo), which prefixes its lines;
#   T        a new directory under /tmp, removed when the script exits or is
#            interrupted;
#   ok       counts a check passed;  bad WHY  counts one failed and says WHY;
#   summary  the last line tests/run.sh reads, "NAME: P passed, F failed",
#            and the script's exit status (0 when nothing failed).
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

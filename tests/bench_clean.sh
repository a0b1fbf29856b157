#!/bin/sh
# bench_clean.sh -- the end-to-end form of tests/cli_benchclean.sh (not in
# make check: a minute or two): clone this repository's HEAD afresh, run
# make bench in it twice, and require git status to stay clean after each.
#   sh tests/bench_clean.sh          (JOBS=N as for make bench)
set -u
T=$(mktemp -d /tmp/tilesim-clean.XXXXXX)
trap 'rm -rf "$T"' EXIT
git clone -q "$(git rev-parse --show-toplevel)" "$T/clone" || exit 1
cd "$T/clone" || exit 1
bad=0
for run in 1 2; do
  if ! make -s bench > "$T/log" 2>&1; then echo "bench_clean: make bench failed: $(tail -5 "$T/log")"; exit 1; fi
  dirty=$(git status --porcelain)
  if [ -n "$dirty" ]; then echo "bench_clean: run $run left the tree dirty:"; echo "$dirty"; bad=1; fi
done
[ $bad -eq 0 ] && echo "bench_clean: make bench twice on a fresh clone: the tree stays clean"
exit $bad

#!/bin/sh
# run.sh BUILD TEST... -- run every test (programs and tests/cli_*.sh scripts),
# echo their output, and end with the line "N passed, N failed".
# Each test ends its output with "NAME: P passed, F failed"; a test that dies
# without that line counts as one failure.  Exit status 1 on any failure.
# A test that skips part of itself says "NAME: skipped: why"; those lines
# are repeated just before the last line, so that what was not run shows.
build=$1; shift
passed=0; failed=0; skipped=""
# No progress lines from long runs in the tests' output (util/progress.h);
# a test that checks them sets its own interval.
export TILESIM_PROGRESS_S=${TILESIM_PROGRESS_S:-86400}
# Memory: AddressSanitizer keeps 256 MB of freed memory per process by
# default (its quarantine, where a use after free is caught); 32 MB keeps
# the catch for recent frees and the largest test near 200 MB instead of
# 600 MB (test_variants), so that make check fits beside other work.  The
# caller's ASAN_OPTIONS come after, and win.
export ASAN_OPTIONS="quarantine_size_mb=32${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
# Each test's peak memory (its largest process), where GNU time is there:
# the largest is said before the last line.
TIMEV=""
if /usr/bin/time -f %M -o /dev/null true 2> /dev/null; then TIMEV=/usr/bin/time; fi
rss=$(mktemp /tmp/tilesim-rss.XXXXXX)
trap 'rm -f "$rss"' EXIT
maxkb=0; maxname=""
for t in "$@"; do
  case $t in
    *.sh) out=$(BUILD=$build ${TIMEV:+$TIMEV -f %M -o "$rss"} sh "$t" 2>&1); rc=$? ;;
    *)    out=$(${TIMEV:+$TIMEV -f %M -o "$rss"} ${VALGRIND:-} "$t" 2>&1); rc=$? ;;
  esac
  if [ -n "$TIMEV" ]; then
    kb=$(tail -n 1 "$rss" 2> /dev/null)
    case $kb in ''|*[!0-9]*) ;; *) if [ "$kb" -gt "$maxkb" ]; then maxkb=$kb; maxname=${t##*/}; fi ;; esac
  fi
  printf '%s\n' "$out"
  skipped="$skipped$(printf '%s\n' "$out" | grep -E '^[A-Za-z0-9_.-]+: skipped: ' | sed 's/^/  /')
"
  line=$(printf '%s\n' "$out" | grep -E '^[A-Za-z0-9_.-]+: [0-9]+ passed, [0-9]+ failed$' | tail -n 1)
  if [ -n "$line" ]; then
    p=$(printf '%s' "$line" | sed -E 's/.*: ([0-9]+) passed, ([0-9]+) failed/\1/')
    f=$(printf '%s' "$line" | sed -E 's/.*: ([0-9]+) passed, ([0-9]+) failed/\2/')
    passed=$((passed + p)); failed=$((failed + f))
    if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then
      echo "$t: exit status $rc"; failed=$((failed + 1))
    fi
  else
    echo "$t: died (exit status $rc) before its summary line"; failed=$((failed + 1))
  fi
done
if [ -n "$maxname" ]; then
  echo "largest memory: $maxname, $((maxkb / 1024)) MB (each test runs alone; make check's peak is this and make's)"
fi
if [ -n "$(printf '%s' "$skipped" | tr -d '\n')" ]; then
  echo "skipped (not run here, and why):"
  printf '%s' "$skipped" | grep -v '^$'
fi
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]

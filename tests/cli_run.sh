#!/bin/sh
# cli_run.sh -- make check's runner (tests/run.sh) as make check needs it
# beside other work: AddressSanitizer's quarantine bounded for every test
# (the caller's ASAN_OPTIONS still winning), and the largest test's peak
# memory said before the last line (where GNU time is there), after the
# skipped lines' place is kept just before the last line.
BUILD=${BUILD:-build/chk}
. tests/clilib.sh

# A test that says what it was given, and one that holds 40 MB for a moment.
cat > "$T/cli_probe.sh" <<'EOF2'
echo "probe: ASAN_OPTIONS=$ASAN_OPTIONS"
head -c 41943040 /dev/zero | sort | wc -c | sed 's/^/probe: held /'
echo "probe: 1 passed, 0 failed"
EOF2
out=$(env -u ASAN_OPTIONS sh tests/run.sh "$BUILD" "$T/cli_probe.sh" 2>&1)
printf '%s\n' "$out" | grep -qx 'probe: ASAN_OPTIONS=quarantine_size_mb=32' && ok || bad "the quarantine: $out"
out=$(ASAN_OPTIONS=quarantine_size_mb=8:detect_leaks=1 sh tests/run.sh "$BUILD" "$T/cli_probe.sh" 2>&1)
printf '%s\n' "$out" | grep -qx 'probe: ASAN_OPTIONS=quarantine_size_mb=32:quarantine_size_mb=8:detect_leaks=1' \
  && ok || bad "the caller's options after: $out"
if /usr/bin/time -f %M -o /dev/null true 2> /dev/null; then
  printf '%s\n' "$out" | tail -n 2 | head -n 1 | grep -qE '^largest memory: cli_probe.sh, (3[5-9]|[4-9][0-9]|[0-9]{3,}) MB ' \
    && printf '%s\n' "$out" | tail -n 1 | grep -qx '1 passed, 0 failed' && ok || bad "the largest memory: $out"
else
  echo "cli_run: skipped: the largest memory (GNU time is not installed: apt-get install time)"
fi

summary

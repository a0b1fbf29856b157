#!/bin/sh
# run.sh DIR SECONDS JOBS TARGET... -- run each libFuzzer target in DIR/bin
# for SECONDS on DIR/corpus/TARGET (seeded from tests/fuzz/corpus_NAME/, NAME
# the target less its fuzz_ prefix); print its executions and corpus, and
# fail if it found a crash, a leak, a timeout or undefined behaviour (the
# input is kept as DIR/crash-..., DIR/timeout-...; replay: DIR/bin/TARGET FILE).
dir=$1; secs=$2; jobs=$3; shift 3
status=0
for t in "$@"; do
  name=${t#fuzz_}
  corpus=$dir/corpus/$name
  mkdir -p "$corpus"
  cp tests/fuzz/corpus_"$name"/* "$corpus"/ 2> /dev/null
  log=$dir/$t.log
  if [ "$jobs" -gt 1 ]; then
    (cd "$dir" && "./bin/$t" "corpus/$name" -max_total_time="$secs" -timeout=10 -rss_limit_mb=2048 \
       -max_len=65536 -print_final_stats=1 -jobs="$jobs" -workers="$jobs" -artifact_prefix=./ > "$t.log" 2>&1)
    rc=$?
    cat "$dir"/fuzz-*.log >> "$log" 2> /dev/null
  else
    "$dir/bin/$t" "$corpus" -max_total_time="$secs" -timeout=10 -rss_limit_mb=2048 -max_len=65536 \
      -print_final_stats=1 -artifact_prefix="$dir/" > "$log" 2>&1
    rc=$?
  fi
  execs=$(grep 'stat::number_of_executed_units' "$log" | awk '{s += $2} END {print s + 0}')
  size=$(ls "$corpus" | wc -l)
  if [ $rc -eq 0 ]; then
    echo "make fuzz: $t: $execs executions in ${secs} s ($jobs job(s)), corpus $size inputs, nothing found"
  else
    echo "make fuzz: $t: FAILED (exit $rc) after $execs executions; see $log:"
    grep -E 'ERROR|pipeline:|SUMMARY|Test unit written' "$log" | head -5
    status=1
  fi
done
exit $status

#!/bin/sh
# cli_benchcores.sh -- make bench-cores' script (tests/bench_cores.sh) as a
# smoke test, not a timing: with small sizes, CORES=2 and the sanitized
# programs of $BUILD it runs every step and writes well-formed CSV, Markdown
# and SVG whose figures agree with the runs it lists (the fastest, the
# median, the speedups and errors recomputed here; a prediction rerun on the
# simulator from the calibration's options; the optimum against the serial
# solver's), and nothing else; a short budget stops it at the budget with
# what it had and no process left; bad settings are refused with one line.
BUILD=${BUILD:-build/chk}
. tests/clilib.sh
run() { env BIN="$BUILD" PLOT="$BUILD/plot" CORES=2 CAL_REPEAT=1 "$@" sh tests/bench_cores.sh; }
HEADER=what,variant,input,procs,runs,measured_s,measured_speedup,predicted_s,predicted_speedup,error,median_s,checksum
SMALL="tests/data/slicerrt/tinypatient_0.contours|tests/data/slicerrt/prostate_3.contours"

# descendants PID: every process below PID, from /proc's parent links.
descendants() {
  for f in /proc/[0-9]*/stat; do { read -r l < "$f"; } 2> /dev/null && echo "${f#/proc/} ${l##*) }"; done |
    awk -v root="$1" '{ sub(/\/stat$/, "", $1); par[$1] = $3 }
      END { want[root] = 1; do { more = 0; for (p in par) if (!(p in want) && (par[p] in want)) { want[p] = 1; more = 1 } } while (more)
            for (p in want) if (p != root) print p }'
}
# guarded SECONDS OUT ERR SETTING...: the script, ended with everything below it
# after SECONDS (a broken script must not hang make check).
guarded() {
  g=$1 o=$2 e=$3
  shift 3
  run "$@" > "$o" 2> "$e" &
  gp=$!
  (
    i=0
    while [ $i -lt "$g" ] && kill -0 $gp 2> /dev/null; do sleep 1; i=$((i + 1)); done
    if kill -0 $gp 2> /dev/null; then
      # shellcheck disable=SC2046
      kill $(descendants $gp) $gp 2> /dev/null
      echo "the script was still running after $g s" >> "$e"
    fi
  ) &
  gw=$!
  wait $gp
  grc=$?
  wait $gw
  return $grc
}

# well_svg FILE LINES: an SVG document (xmllint where there is one) with LINES polylines.
well_svg() {
  if command -v xmllint > /dev/null 2>&1; then xmllint --noout "$1" 2> "$T/xml" || { bad "$1: $(cat "$T/xml")"; return; }; fi
  head -n 1 "$1" | grep -q '^<svg xmlns="http://www.w3.org/2000/svg"' && [ "$(tail -n 1 "$1")" = "</svg>" ] \
    && [ "$(grep -c '<polyline' "$1")" -eq "$2" ] && ok || bad "$1: not an SVG of $2 lines: $(head -c 300 "$1")"
}
# tables FILE: every Markdown table's rows have its header's number of cells.
tables() {
  awk '/^\|/ { n = gsub(/\|/, "|"); if (!inside) { want = n; inside = 1; nt++ } else if (n != want) { bad = 1; print "row " NR ": " $0 } next }
    { inside = 0 } END { if (bad || nt == 0) exit 1; print nt }' "$1"
}

# ---- A complete run: every step, the figures checked against the runs --------------
# (A budget and a guard far beyond what the run takes, so that a loaded
# machine still completes it: no check here is a timing.)
guarded 900 "$T/a.out" "$T/a.err" BUDGET=600 OUT="$T/a" POINTS=200,120 VARIANTS=paper,dynamic+block8 REPEAT=2 MESSAGES=300 STACKS="$SMALL"; rc=$?
[ $rc -eq 0 ] && [ ! -s "$T/a.out" ] && grep -q '^bench-cores: \[[0-9]* s of 600\] done: .*(complete: 2 passes in [0-9]* s)$' "$T/a.err" \
  && ok || bad "a complete run: exit $rc: $(cat "$T/a.err")"
[ "$(cd "$T/a" && ls -A | tr '\n' ' ')" = "bench-cores.log calibrate.csv cores.csv cores.md cores.svg cores_tile.svg runs.csv " ] \
  && ok || bad "the output folder holds: $(ls -A "$T/a")"
grep -q '^bench-cores: \[[0-9]* s of 600\] pass 1: threads, 200 points, P = 1,2,3: [0-9.]* s$' "$T/a/bench-cores.log" \
  && grep -q '^bench-cores: \[[0-9]* s of 600\] pass 2: ./tile.s stacks, N = 2,1: [0-9.]* s$' "$T/a/bench-cores.log" \
  && grep -q '^bench: the calibration took' "$T/a/bench-cores.log" && ok || bad "the log: $(cat "$T/a/bench-cores.log")"
csv=$T/a/cores.csv
[ "$(head -n 1 "$csv")" = "$HEADER" ] && ok || bad "cores.csv header: $(head -n 1 "$csv")"
awk -F, 'NF != 12 { exit 1 }' "$csv" && [ "$(grep -c '^threads,' "$csv")" -eq 12 ] && [ "$(grep -c '^tile,' "$csv")" -eq 4 ] \
  && [ "$(wc -l < "$csv")" -eq 17 ] && ok || bad "cores.csv rows: $(cat "$csv")"
# Every row from runs.csv, recomputed: the fastest, how many, the median, the
# speedup against P = 1 (N = 1), the prediction's speedup and error.
[ "$(head -n 1 "$T/a/runs.csv")" = "what,variant,input,procs,pass,time_s,checksum" ] \
  && [ "$(wc -l < "$T/a/runs.csv")" -eq 33 ] && ok || bad "runs.csv: $(cat "$T/a/runs.csv")"
awk -F, '
  function near(a, b, tol) { return a - b <= tol && b - a <= tol }
  FNR == 1 { f++; next }
  f == 1 { k = $1 "," $2 "," $3 "," $4; n[k]++; t[k, n[k]] = $6; if (!(k in lo) || $6 + 0 < lo[k]) lo[k] = $6 + 0; next }
  { k = $1 "," $2 "," $3 "," $4; k1 = $1 "," $2 "," $3 ",1"
    m = n[k]; for (i = 1; i <= m; i++) s[i] = t[k, i] + 0
    for (i = 1; i <= m; i++) for (j = i + 1; j <= m; j++) if (s[j] < s[i]) { x = s[i]; s[i] = s[j]; s[j] = x }
    med = m % 2 ? s[(m + 1) / 2] : (s[m / 2] + s[m / 2 + 1]) / 2
    if ($5 != m || m != 2 || !near($6, lo[k], 1e-6) || !near($11, med, 1e-6) || !near($7, lo[k1] / lo[k], 0.0005 + 1e-5 * lo[k1] / lo[k])) {
      print "row " FNR ": " $0 " (runs " m ", fastest " lo[k] ", median " med ")"; bad = 1 }
    if ($1 == "threads") {
      if ($8 <= 0 || !near($10, $8 / $6 - 1, 0.0001 + 1e-6 / $6 * (1 + $8 / $6))) { print "prediction of row " FNR ": " $0; bad = 1 }
      p[$2 "," $3 "," $4] = $8
      if ($4 == 1 && $9 != "1.000") { print "predicted speedup at P = 1: " $0; bad = 1 }
    } else if ($8 != "" || $9 != "" || $10 != "") { print "a prediction for a stack: " $0; bad = 1 }
    sp[FNR] = $9; key[FNR] = $2 "," $3
  }
  END { exit bad }' "$T/a/runs.csv" "$csv" > "$T/check" && ok || bad "cores.csv against runs.csv: $(cat "$T/check")"
# A prediction, rerun here on the simulator with the options the calibration gave for that size and P.
opts=$(awk -F, '$1 == 200 && $2 == 3 { print $6 }' "$T/a/calibrate.csv")
# shellcheck disable=SC2086
sim=$("$BUILD/bench" --points 200 --procs 3 $opts --variant dynamic+block8 | awk -F, 'NR == 2 { printf "%.6f", $9 }')
got=$(awk -F, '$2 == "dynamic+block8" && $3 == 200 && $4 == 3 { print $8 }' "$csv")
[ -n "$opts" ] && [ -n "$sim" ] && [ "$sim" = "$got" ] && ok || bad "the prediction at 200 points, P = 3: $got, the simulator $sim ($opts)"
# The optimum: the serial solver's on the simulator, for every threads row of a size.
for n in 120 200; do
  want=$("$BUILD/bench" --points $n --procs 1 | awk -F, 'NR == 2 { print $15 }')
  awk -F, -v n=$n -v w="$want" '$1 == "threads" && $3 == n && $12 != w { exit 1 }' "$csv" && [ -n "$want" ] \
    && ok || bad "the checksums at $n points are not the optimum $want: $(grep ",$n," "$csv")"
done
# The stacks' checksum: the bands' costs as ./tile reports them, summed.
"$BUILD/tile" tests/data/slicerrt/prostate_3.contours --caps -q > "$T/tile.csv"
want=$(awk -F, 'NR > 1 && $1 ~ /^[0-9]+$/ { s += $11 } END { printf "%.6f", s }' "$T/tile.csv")
got=$(awk -F, '$1 == "tile" && $3 ~ /prostate_3/ { printf "%.6f\n", $12 }' "$csv" | sort -u)
[ "$got" = "$want" ] && ok || bad "prostate_3's checksum $got, ./tile's bands $want"
# The Markdown: what ran, where; a table per variant and one for the stacks.
md=$T/a/cores.md
n=$(tables "$md") && [ "$n" -eq 3 ] && ok || bad "cores.md tables: $n"
grep -q '^## Cores: 2 cores' "$md" && grep -q '^Measured by `make bench-cores BUDGET=600 OUT=.*`.*: complete: 2 passes in' "$md" \
  && grep -q '^- commit: ' "$md" && grep -q '^- compiler: ' "$md" && grep -q '^| 3 | .* ms | .* | .* ms | .* | [-+][0-9.]*% |' "$md" \
  && grep -q '^| 2 | .* ms | .* | .* ms | .* |$' "$md" && [ $(($(grep -c '^```' "$md") % 2)) -eq 0 ] && ! grep -q 'Not measured' "$md" \
  && ok || bad "cores.md: $(cat "$md")"
well_svg "$T/a/cores.svg" 8
well_svg "$T/a/cores_tile.svg" 3

# ---- A short budget: the calibration, far too long, stopped at the budget ------------
# What shows that it stopped at its budget is its own account (the step
# stopped, the files saying so, nothing left running), not the time it took
# here, which a loaded machine stretches; the budget leaves pass 1's short
# steps room on a loaded machine, and the guard only catches a hang.
guarded 300 "$T/b.out" "$T/b.err" BUDGET=10 OUT="$T/b" POINTS=100 VARIANTS=paper REPEAT=3 MESSAGES=100000000 STACKS="$SMALL"; rc=$?
[ $rc -eq 0 ] && grep -q 'calibration.*: stopped at the budget after' "$T/b.err" \
  && ok || bad "a short budget: exit $rc: $(cat "$T/b.err")"
left=$(for f in /proc/[0-9]*/cmdline; do { tr '\0' ' ' < "$f"; } 2> /dev/null; echo; done | grep -c -- '--messages 10000000[0]')
[ "$left" -eq 0 ] && ok || bad "$left calibration processes left running"
[ "$(head -n 1 "$T/b/cores.csv")" = "$HEADER" ] && [ "$(grep -c '^threads,paper,100,[123],1,[0-9.]*,[0-9.]*,,,,' "$T/b/cores.csv")" -eq 3 ] \
  && [ "$(grep -c '^tile,' "$T/b/cores.csv")" -eq 4 ] && [ ! -e "$T/b/calibrate.csv" ] && ok || bad "short budget, cores.csv: $(cat "$T/b/cores.csv")"
grep -q ': stopped at the budget after [0-9]* s, in pass 1 of 3\.$' "$T/b/cores.md" && grep -q '^Not measured (the run ended first): no predictions\.$' "$T/b/cores.md" \
  && n=$(tables "$T/b/cores.md") && [ "$n" -eq 2 ] && ok || bad "short budget, cores.md: $(cat "$T/b/cores.md")"
well_svg "$T/b/cores.svg" 1
[ "$(cd "$T/b" && ls -A | tr '\n' ' ')" = "bench-cores.log cores.csv cores.md cores.svg cores_tile.svg runs.csv " ] \
  && ok || bad "short budget, the output folder holds: $(ls -A "$T/b")"

# ---- Refusals: one line and the usage line, status 2 (1 for what cannot be done), nothing written
refused() {   # refused STATUS MESSAGE SETTING...
  want=$1 msg=$2
  shift 2
  run OUT="$T/r" "$@" > "$T/r.out" 2> "$T/r.err"; rc=$?
  [ $rc -eq "$want" ] && [ ! -s "$T/r.out" ] && [ "$(head -n 1 "$T/r.err")" = "bench-cores: $msg" ] && [ ! -e "$T/r" ] \
    && { [ "$want" -ne 2 ] || grep -q '^usage: make bench-cores \[BUDGET=SECONDS\] \[OUT=DIR\]' "$T/r.err"; } \
    && ok || bad "$*: exit $rc (want $want, '$msg'): $(cat "$T/r.err")"
}
refused 2 "BUDGET takes a whole number from 1 to 86400 (0)" BUDGET=0
refused 2 "BUDGET takes a whole number from 1 to 86400 (ten)" BUDGET=ten
refused 2 "BUDGET takes a whole number from 1 to 86400 (86401)" BUDGET=86401
refused 2 "BUDGET takes a whole number from 1 to 86400 ()" BUDGET=
refused 2 "REPEAT takes a whole number from 1 to 1000 (0)" REPEAT=0
refused 2 "POINTS takes sizes separated by commas, e.g. 4000,2000 (4000,,2000)" POINTS=4000,,2000
refused 2 "a size of POINTS takes a whole number from 3 to 100000 (2)" POINTS=2
refused 2 "VARIANTS: bench: --variant takes variants like paper, fit, size, block16, dynamic, dynamic+block16 (bogus)" VARIANTS=paper,bogus
refused 1 "STACKS: tests/data/nothing.contours: no such file" STACKS=tests/data/nothing.contours
refused 1 "$T/none/bench is not built (make bench-cores builds it; or make, then this script)" BIN="$T/none"
: > "$T/file"
run OUT="$T/file" > "$T/r.out" 2> "$T/r.err"; rc=$?
[ $rc -eq 2 ] && [ "$(head -n 1 "$T/r.err")" = "bench-cores: OUT: $T/file exists and is not a folder" ] && [ ! -s "$T/file" ] \
  && ok || bad "OUT a file: exit $rc: $(cat "$T/r.err")"
run OUT="$T/file/sub" > "$T/r.out" 2> "$T/r.err"; rc=$?
[ $rc -eq 1 ] && [ "$(head -n 1 "$T/r.err")" = "bench-cores: OUT: cannot create the folder $T/file/sub" ] \
  && ok || bad "OUT under a file: exit $rc: $(cat "$T/r.err")"
run OUT= > "$T/r.out" 2> "$T/r.err"; rc=$?
[ $rc -eq 2 ] && [ "$(head -n 1 "$T/r.err")" = "bench-cores: OUT names the output folder, and is empty" ] \
  && ok || bad "OUT empty: exit $rc: $(cat "$T/r.err")"
env BIN="$BUILD" OUT="$T/r" sh tests/bench_cores.sh 60 > "$T/r.out" 2> "$T/r.err"; rc=$?
[ $rc -eq 2 ] && [ "$(head -n 1 "$T/r.err")" = "bench-cores: the settings go in the environment, not as arguments (60)" ] && [ ! -e "$T/r" ] \
  && ok || bad "an argument: exit $rc: $(cat "$T/r.err")"

summary

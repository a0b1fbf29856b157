#!/bin/sh
# cli_bench.sh -- ./bench's command line: modes, CSV, checksums, bad usage.
# Run by make check with BUILD=build/chk (the sanitized build).
bench=${BUILD:-build/chk}/bench
passed=0; failed=0
ok()   { passed=$((passed + 1)); }
fail() { failed=$((failed + 1)); echo "cli_bench: $*"; }

# A ring: header, one row, the checksum P*K, exit 0.
out=$("$bench" --ring 5 --laps 7 --profile unit --net ideal --m 0.25 --c 0.125 --work 2 2>&1); rc=$?
[ $rc -eq 0 ] && ok || fail "--ring 5 --laps 7 exited $rc: $out"
printf '%s\n' "$out" | head -n 1 | grep -q '^procs,laps,net,m,c,work,messages,sim_time,.*wall_s,messages_per_s,.*checksum$' \
  && ok || fail "ring header: $out"
row=$(printf '%s\n' "$out" | sed -n 2p)
case $row in
  5,7,ideal,0.25,0.125,2,35,17.500000000,*,35) ok ;;  # 35 hops of 2*0.125 + 0.25
  *) fail "ring row: $row" ;;
esac

for net in bus loggp; do
  "$bench" --ring 3 --laps 4 --net $net >/dev/null 2>&1 && ok || fail "--net $net failed"
done

# A trace from the command line parses as JSON-ish and has a CSV header.
tmp=${TMPDIR:-/tmp}/cli_bench.$$
"$bench" --ring 3 --laps 2 --profile unit --trace-csv "$tmp.csv" --trace-json "$tmp.json" >/dev/null 2>&1 \
  && ok || fail "traced ring failed"
head -n 1 "$tmp.csv" 2>/dev/null | grep -q '^time,rank,proc,event,' && ok || fail "trace CSV header"
grep -q '"traceEvents"' "$tmp.json" 2>/dev/null && tail -n 1 "$tmp.json" | grep -q '^]}$' \
  && ok || fail "trace JSON shape"
rm -f "$tmp.csv" "$tmp.json"

# The switch mode.
out=$("$bench" --switch 1000 2>&1); rc=$?
[ $rc -eq 0 ] && printf '%s\n' "$out" | head -n 1 | grep -q '^backend,switches,wall_s,ns_per_switch$' \
  && ok || fail "--switch 1000: $out"

# Bad usage: a usage line on stderr, exit 2, nothing on stdout.
for args in "--frob" "--ring" "--ring 0 --laps 1" "--ring 4" "--ring 4 --laps x" \
            "--ring 4 --laps 2 --net token" "--ring 4 --laps 2 --m -1" \
            "--ring 4 --laps 2 --bogus 1" "--ring 4 --laps 2 --profile nope" "--switch" "--switch 1" \
            "--procs 0" "--procs 1..x" "--points 2" "--alloc third" "--min-diag 0" "--m -1" "--jobs 0" \
            "--tiler --points 1" "--procs 4 --net token" "--backend mpi" "--backend threads --jobs 2" \
            "--stack -j 0" "--stack -j 1,x" "--stack --repeat 0" "--stack --frob" \
            "--model --backend threads" "--procs 2 --points 50 --trace $tmp.json" \
            "--union 3:100" "--union blob:0:100" "--union star:3:2" "--union blob:3:100x" "--union --repeat 0"; do
  # shellcheck disable=SC2086
  "$bench" $args >"$tmp.out" 2>"$tmp.err"; rc=$?
  if [ $rc -eq 2 ] && [ ! -s "$tmp.out" ] && grep -q '^usage: bench' "$tmp.err"; then ok
  else fail "bench $args: exit $rc, stderr: $(cat "$tmp.err")"; fi
done
rm -f "$tmp.out" "$tmp.err"

# --help, and MODE --help (anywhere after the mode): on stdout, exit 0,
# the program named as it was run; a mode's help is that mode's alone.
out=$("$bench" --help 2>&1) && printf '%s\n' "$out" | grep -q '^usage: bench \[OPTIONS\]' \
  && [ "$(printf '%s\n' "$out" | grep -c '^  bench --')" -eq 11 ] && ok || fail "bench --help: $out"
out=$("$bench" --procs 2 --help 2>&1) && printf '%s\n' "$out" | grep -q '^usage: bench \[OPTIONS\]' && ok || fail "bench --procs 2 --help: $out"
for m in --ring --switch --model --glass --claims --claims-map --calibrate --dicom --stack --tiler --union; do
  out=$("$bench" $m --help 2>&1) && printf '%s\n' "$out" | head -1 | grep -q "^usage: bench $m" \
    && ! printf '%s\n' "$out" | grep -q '^  bench' && ok || fail "bench $m --help: $out"
done
out=$("$bench" --stack x.contours -h 2>&1) && printf '%s\n' "$out" | grep -q '^usage: bench --stack' && ok || fail "bench --stack x -h: $out"

# --stack: a whole stack on 1 and 2 threads, the same surface (the checksums) on each.
out=$("$bench" --stack tests/data/slicerrt/tinypatient_0.contours -j 1,2 --repeat 1 2>&1); rc=$?
[ $rc -eq 0 ] && [ "$(printf '%s\n' "$out" | wc -l)" -eq 3 ] && printf '%s\n' "$out" | head -1 | \
  grep -q '^input,slices,contours,points,bands,bridges,caps,threads,runs,read_ms,tile_ms,band_ms,speedup,cost,volume$' && \
  printf '%s\n' "$out" | awk -F, 'NR > 1 { if ($5 != 16 || $11 <= 0 || $8 != NR - 1) bad = 1; c[$14]++; v[$15]++ }
    END { n = 0; for (k in c) n++; m = 0; for (k in v) m++; exit bad || n != 1 || m != 1 }' \
  && ok || fail "--stack: $out"

# --union: the exact union of overlapping contours on a slice; two smooth
# blobs give one loop, whatever the repeats (the checksums), and spiky stars
# a union with holes.
out=$("$bench" --union blob:2:200 star:3:300 --repeat 2 2>&1); rc=$?
[ $rc -eq 0 ] && [ "$(printf '%s\n' "$out" | wc -l)" -eq 3 ] && printf '%s\n' "$out" | head -1 | \
  grep -q '^input,contours,points,groups,loops,holes,new_vertices,runs,union_ms,us_per_point,loop_points,area2$' && \
  printf '%s\n' "$out" | awk -F, '$1 == "blob:2:200" && !($4 == 1 && $5 == 1 && $6 == 0 && $7 > 0 && $9 > 0) { bad = 1 }
    $1 == "star:3:300" && !($4 == 1 && $6 > 0 && $5 == $6 + 1) { bad = 1 } END { exit bad }' \
  && ok || fail "--union: $out"

# Measured runs on threads: the same optimum as the simulator's, a backend column.
out=$("$bench" --points 60 --procs 1,3 --backend threads 2>&1); rc=$?
sim=$("$bench" --points 60 --procs 3 2>&1)
[ $rc -eq 0 ] && [ "$(printf '%s\n' "$out" | tail -n +2 | wc -l)" -eq 2 ] && ok || fail "--backend threads: $out"
printf '%s\n' "$out" | awk -F, 'NR>1 && ($23 != "threads" || $9 <= 0 || $5 != "") {bad=1} END{exit bad}' \
  && ok || fail "--backend threads rows: $out"
[ "$(printf '%s\n' "$out" | tail -1 | cut -d, -f15)" = "$(printf '%s\n' "$sim" | tail -1 | cut -d, -f15)" ] \
  && ok || fail "threads and sim optima differ: $out / $sim"

# Calibration: a row per P, the options to paste, the threads run's optimum.
out=$("$bench" --calibrate --points 60 --procs 1,3 --repeat 2 --messages 200 2>"$tmp.err"); rc=$?
[ $rc -eq 0 ] && [ "$(printf '%s\n' "$out" | tail -n +2 | wc -l)" -eq 2 ] && ok || fail "--calibrate: $out $(cat "$tmp.err")"
printf '%s\n' "$out" | head -1 | grep -q '^points,procs,slaves,tables,c,options,measured_s,predicted_s,error,.*,cost$' && ok || fail "--calibrate header"
printf '%s\n' "$out" | tail -n +2 | awk -F, '$6 !~ /^--net loggp --L [0-9.e+-]+ --o 0 --g [0-9.e+-]+ --G [0-9.e+-]+ --o-send .* --wake [0-9.e+-]+ --o-wake [0-9.e+-]+ --slowdown [0-9.e+-]+ --slowdown-spin [0-9.e+-]+ --back-c [0-9.e+-]+( --table-c [0-9.e+-]+)? --c [0-9.e+-]+$/ || $7 <= 0 || $8 <= 0 {bad=1} END{exit bad}' \
  && ok || fail "--calibrate rows: $out"
grep -q '^bench: 60 points: c = .* s per node' "$tmp.err" && grep -q '^bench:   so o_send .* s/byte, o_recv' "$tmp.err" && grep -q '^bench: the calibration took' "$tmp.err" && ok || fail "--calibrate stderr: $(cat "$tmp.err")"
[ "$(printf '%s\n' "$out" | tail -1 | cut -d, -f19)" = "$(printf '%s\n' "$sim" | tail -1 | cut -d, -f15)" ] \
  && ok || fail "--calibrate optimum differs from the simulator's"
# --options-only: the same model, no parallel run: a row per size and P with
# the first six columns alone, which P use tables as the full calibration
# says, and c the --c of the options.
full=$("$bench" --calibrate --points 60 --procs 1,6 --repeat 1 --messages 200 2>/dev/null)
out=$("$bench" --calibrate --points 60,2600 --procs 1,6 --repeat 1 --messages 200 --options-only 2>"$tmp.err"); rc=$?
[ $rc -eq 0 ] && [ "$(printf '%s\n' "$out" | head -1)" = "points,procs,slaves,tables,c,options" ] \
  && [ "$(printf '%s\n' "$out" | sed -n 2,3p | cut -d, -f1-4)" = "$(printf '%s\n' "$full" | tail -n +2 | cut -d, -f1-4)" ] \
  && [ "$(printf '%s\n' "$out" | tail -n +2 | cut -d, -f1-4 | tr '\n' ' ')" = "60,1,1,1 60,6,5,0 2600,1,1,0 2600,6,5,0 " ] \
  && printf '%s\n' "$out" | tail -n +2 | awk -F, 'NF != 6 || $6 !~ /^--net loggp .* --back-c [0-9.e+-]+( --table-c [0-9.e+-]+)? --c [0-9.e+-]+$/ { exit 1 }
      { n = split($6, w, " "); if (w[n] != $5) exit 1 }' \
  && grep -q '^bench: the calibration took' "$tmp.err" \
  && ok || fail "--calibrate --options-only: exit $rc: $out / $full $(cat "$tmp.err")"
for args in "--calibrate --points 2" "--calibrate --procs 0" "--calibrate --bogus 1" "--calibrate --repeat"; do
  # shellcheck disable=SC2086
  "$bench" $args >"$tmp.out" 2>"$tmp.err"; rc=$?
  [ $rc -eq 2 ] && [ ! -s "$tmp.out" ] && grep -q '^usage: bench --calibrate' "$tmp.err" && ok || fail "bench $args: exit $rc"
done
rm -f "$tmp.out" "$tmp.err"

"$bench" --help | grep -q -- '--ring P --laps K' && ok || fail "--help does not list --ring"

# --model: the section 7.2 experiment; one row per (D, P), the model's formula.
out=$("$bench" --model --diag 40 --procs 2,4 --net ideal --m 0.001 --c 0.0001 2>&1); rc=$?
[ $rc -eq 0 ] && [ "$(printf '%s\n' "$out" | wc -l)" -eq 3 ] && ok || fail "--model: $out"
# model = c D / p + m (p - 1): 40 nodes, p = 3 slaves: 0.0001*40/3 + 0.001*2
printf '%s\n' "$out" | awk -F, '$1==40 && $2==4 { d = $10 - (0.0001*40/3 + 0.002); exit (d < -1e-9 || d > 1e-9) }' && ok || fail "--model formula: $out"
# --glass: a valid stack that ./tile accepts.
"$bench" --glass --slices 6 --points 12 -o "$tmp.contours" && "${BUILD:-build/chk}/tile" "$tmp.contours" -q --caps > "$tmp.out" && [ "$(grep -c '^[0-9]' "$tmp.out")" -eq 5 ] && ok || fail "--glass"
rm -f "$tmp.contours" "$tmp.out"

echo "cli_bench: $passed passed, $failed failed"
[ $failed -eq 0 ]

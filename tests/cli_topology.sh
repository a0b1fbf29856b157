#!/bin/sh
# cli_topology.sh -- topologies and placement from the command line: the bus
# topology against the bus model and full (no network cost) against ideal, bit
# for bit on the paper's sweeps, in the same binary; sweeps over --topology and
# --place lists; the ring's closed forms; ./tile's columns, maps and traces;
# bad usage.  Run by make check with BUILD=build/chk (the sanitized build).
bench=${BUILD:-build/chk}/bench
tile=${BUILD:-build/chk}/tile
passed=0; failed=0
ok()   { passed=$((passed + 1)); }
fail() { failed=$((failed + 1)); echo "cli_topology: $*"; }
tmp=${TMPDIR:-/tmp}/cli_topology.$$
trap 'rm -f "$tmp".*' EXIT

# The paper's sweeps (Fig. 16 and 18/19): --topology bus is the bus model.
"$bench" --alloc half,size --jobs 2 >"$tmp.bus" 2>&1 && ok || fail "the bus sweep failed: $(head -3 "$tmp.bus")"
"$bench" --alloc half,size --jobs 2 --topology bus >"$tmp.tbus" 2>&1 && ok || fail "the bus topology sweep failed"
# points,procs,alloc,sim_time,speedup,cost
cut -d, -f1-3,9,10,15 "$tmp.bus" >"$tmp.a"; cut -d, -f1-3,9,10,15 "$tmp.tbus" >"$tmp.b"
[ "$(wc -l <"$tmp.a")" -eq 161 ] && cmp -s "$tmp.a" "$tmp.b" && ok \
  || fail "--topology bus differs from the bus: $(diff "$tmp.a" "$tmp.b" | head -4)"
# full with no hop latency and no per-byte cost is ideal (with no per-byte cost).
"$bench" --jobs 2 --net ideal --per-byte 0 >"$tmp.ideal" 2>&1 && ok || fail "the ideal sweep failed"
"$bench" --jobs 2 --topology full --hop-latency 0 --per-byte 0 >"$tmp.full" 2>&1 && ok || fail "the full sweep failed"
cut -d, -f1-3,9,10,15 "$tmp.ideal" >"$tmp.a"; cut -d, -f1-3,9,10,15 "$tmp.full" >"$tmp.b"
[ "$(wc -l <"$tmp.a")" -eq 81 ] && cmp -s "$tmp.a" "$tmp.b" && ok \
  || fail "full with no network cost differs from ideal: $(diff "$tmp.a" "$tmp.b" | head -4)"
# ... and the bus is not ideal, so the comparisons can tell.
cmp -s "$tmp.ideal" "$tmp.bus" && fail "ideal and bus sweeps are the same" || ok

# A sweep over topologies and placements: a row for each, the network's columns,
# the same optimum on every row of the pair.
"$bench" --points 60 --procs 1..6 --topology line,mesh:3x2,hypercube:3,butterfly:2 \
  --place linear,snake,gray,random:4 --hop-latency 1e-5 --switching store-and-forward >"$tmp.sw" 2>"$tmp.err" \
  && ok || fail "topology sweep failed: $(cat "$tmp.err")"
head -n 1 "$tmp.sw" | grep -Eq ',backend,topology,place,hop_latency,switching,hops_per_msg,hop_bytes,max_link_msgs,max_link_bytes,link_wait(,|$)' \
  && ok || fail "sweep header: $(head -n 1 "$tmp.sw")"
[ "$(tail -n +2 "$tmp.sw" | wc -l)" -eq $((4 * 4 * 6)) ] && ok || fail "sweep rows: $(wc -l <"$tmp.sw")"
[ "$(tail -n +2 "$tmp.sw" | cut -d, -f15 | sort -u | wc -l)" -eq 1 ] && ok || fail "placement changed the optimum"
awk -F, 'NR > 1 && ($5 != "topology" || $24 == "" || $25 == "" || $27 != "store-and-forward" || ($2 > 1 && ($28 < 1 || $29 <= 0 || $30 < 1))) {bad = 1}
         END {exit bad}' "$tmp.sw" && ok || fail "sweep rows: $(sed -n 2,3p "$tmp.sw")"
# Linear placement on a line: a slave's neighbours are one link away, so the
# boundary costs (msg_boundary) cross one link each, the master's messages more.
awk -F, '$2 == 6 && $24 == "line" && $25 == "linear" && $28 < 1.0001 {bad = 1} END {exit bad}' "$tmp.sw" \
  && ok || fail "line, linear, P = 6: every message one link"
# build/plot: a series per (topology, place), named by --labels in order.
plot=${BUILD:-build/chk}/plot
if "$plot" lines "$tmp.sw" -x procs -y speedup --series topology,place --where topology=line -o "$tmp.svg" \
     >/dev/null 2>&1 && [ "$(grep -c '<polyline' "$tmp.svg")" -eq 4 ] && grep -q '>line random:4<' "$tmp.svg"; then ok
else fail "plot --series topology,place"; fi
"$plot" lines "$tmp.sw" -x procs -y speedup --series topology,place --where place=gray --labels a,b,c,d \
  -o "$tmp.svg" >/dev/null 2>&1 && grep -q '>c<' "$tmp.svg" && ! grep -q '>hypercube:3 gray<' "$tmp.svg" \
  && ok || fail "plot --labels for series"
# Without --topology: empty network columns, the placement named.
"$bench" --points 40 --procs 2 | tail -n 1 | grep -Eq ',sim,,linear,,,,,,,(,|$)' && ok || fail "plain row's network columns"

# --print-place: the map, on stderr.
"$bench" --points 40 --procs 5 --topology mesh:3x2 --place snake --print-place >/dev/null 2>"$tmp.err"
grep -q '^place: 5 ranks on mesh:3x2 (P = 5, placement snake), 6 processors$' "$tmp.err" \
  && grep -q '^place: rank 3 -> processor 5 (x 2, y 1)$' "$tmp.err" && grep -q '^place:   .   4   3$' "$tmp.err" \
  && ok || fail "--print-place: $(cat "$tmp.err")"

# The ring checks its own closed form on every topology (exit 1 otherwise).
for args in "--topology line" "--topology ring --switching store-and-forward" "--topology mesh:4x2 --place snake" \
            "--topology torus:3x3 --place random:2" "--topology hypercube:3 --place gray" "--topology butterfly:2" \
            "--topology full" "--topology bus --hop-latency 0.25"; do
  # shellcheck disable=SC2086
  out=$("$bench" --ring 8 --laps 5 --profile unit --m 0.25 --c 0.125 --per-byte 0.0625 --hop-latency 0.5 $args 2>&1) \
    && ok || fail "--ring 8 $args: $out"
done
out=$("$bench" --ring 9 --laps 4 --topology torus:3x3 --place random:1 --tokens all 2>&1) && \
  printf '%s\n' "$out" | tail -n 1 | grep -q ',torus:3x3,random:1,all,.*,36$' && ok || fail "--tokens all: $out"
out=$("$bench" --ring 4 --laps 2 --topology line --print-place 2>&1 >/dev/null)
printf '%s\n' "$out" | grep -q '^place:   0   1   2   3$' && ok || fail "ring --print-place: $out"

# ./tile: the same optimum on any topology, the network's columns per pair.
stack=tests/data/slicerrt/tinypatient_1.contours
"$tile" "$stack" --procs 4 -q >"$tmp.t0" 2>&1 && ok || fail "tile --procs 4 failed"
"$tile" "$stack" --procs 4 -q --topology hypercube:2 --place gray --hop-latency 1e-5 >"$tmp.t1" 2>&1 && ok \
  || fail "tile --topology failed: $(head -3 "$tmp.t1")"
[ "$(cut -d, -f11 "$tmp.t0")" = "$(cut -d, -f11 "$tmp.t1")" ] && ok || fail "tile: the topology changed a cost"
head -n 1 "$tmp.t1" | grep -q ',backend,hops_per_msg,hop_bytes,max_link_msgs,max_link_bytes,link_wait$' && ok \
  || fail "tile header: $(head -n 1 "$tmp.t1")"
awk -F, 'NR > 1 && $1 ~ /^[0-9]+$/ && ($26 < 1 || $26 > 2 || $27 <= 0) {bad = 1} END {exit bad}' "$tmp.t1" && ok \
  || fail "tile network columns: $(sed -n 2p "$tmp.t1")"
"$tile" "$stack" --procs 4 -q --topology line --trace "$tmp.json" >/dev/null 2>&1 && \
  grep -q '"name":"network"' "$tmp.json" && grep -q '"link 1>2"' "$tmp.json" && ok || fail "tile trace has no link tracks"

# Bad usage: one line naming the problem, a usage line, exit 2, nothing on stdout.
printf '0\n1\n1\n' >"$tmp.place"
for args in "--topology star" "--topology mesh:2x2 --procs 5" "--topology line --backend threads" \
            "--place random:x" "--place file:$tmp.none" "--place file:$tmp.place" "--switching wormhole" \
            "--hop-latency -1"; do
  case $args in --procs*|*--procs*) p= ;; *) p="--procs 3" ;; esac
  # shellcheck disable=SC2086
  "$tile" "$stack" $p $args >"$tmp.out" 2>"$tmp.err"; rc=$?
  if [ $rc -eq 2 ] && [ ! -s "$tmp.out" ] && grep -q '^usage: tile' "$tmp.err"; then ok
  else fail "tile $args: exit $rc: $(cat "$tmp.err")"; fi
done
"$tile" "$stack" --place snake >"$tmp.out" 2>"$tmp.err"; rc=$?
[ $rc -eq 2 ] && [ ! -s "$tmp.out" ] && grep -q 'need --procs' "$tmp.err" && ok || fail "tile --place without --procs: exit $rc"
"$tile" "$stack" --procs 3 --place "file:$tmp.place" 2>&1 | grep -q "$tmp.place:3: processor 1 is placed twice" \
  && ok || fail "a bad placement file is not named with its line"
for args in "--topology line --net ideal" "--topology mesh:2x2 --procs 1..5" "--topology line, " \
            "--place linear,file:$tmp.none" "--topology line --backend threads" "--ring 4 --laps 1 --topology nope" \
            "--ring 4 --laps 1 --topology mesh:1x2" "--ring 4 --laps 1 --tokens 2" \
            "--ring 4 --laps 1 --net ideal --topology line"; do
  # shellcheck disable=SC2086
  "$bench" $args >"$tmp.out" 2>"$tmp.err"; rc=$?
  if [ $rc -eq 2 ] && [ ! -s "$tmp.out" ] && grep -q '^usage: bench' "$tmp.err"; then ok
  else fail "bench $args: exit $rc: $(cat "$tmp.err")"; fi
done

echo "cli_topology: $passed passed, $failed failed"
[ "$failed" -eq 0 ]

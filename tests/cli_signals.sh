#!/bin/sh
# cli_signals.sh -- nothing but complete files, whatever stops a run:
#   - a program killed by SIGINT, SIGTERM, SIGHUP, SIGPIPE or SIGQUIT while
#     its temporary file exists (the harness polls for it, then signals)
#     removes it and dies of that same signal; a file already at the target
#     is left as it was;
#   - killed mid-write (SIGXFSZ, the file size limit, strikes inside the
#     write) every writer does the same: the mesh, bench -o, --model,
#     --glass, plot -o, the traces;
#   - a write that fails (the limit with SIGXFSZ ignored) is a failed run:
#     exit 1, the target untouched, no data row on stdout (bench --ring);
#   - a trace larger than --trace-limit is refused before anything is
#     written, and the size it gives is the size the trace has.
# Runs the sanitized build in $BUILD.
BUILD=${BUILD:-build/chk}
case $BUILD in /*) ;; *) BUILD=$PWD/$BUILD ;; esac
DATA=$PWD/tests/data/slicerrt
. tests/clilib.sh
cd "$T" || exit 1

# A background job of a shell without job control ignores SIGINT and SIGQUIT
# (and the programs leave an ignored signal ignored), and one started by
# nohup ignores SIGHUP: env puts them back.
DEF=""
if env --default-signal=INT true 2>/dev/null; then DEF="env --default-signal=INT,QUIT,HUP"; fi

signum() {   # Linux's numbers (dash's kill -l does not take a name)
  case $1 in HUP) echo 1 ;; INT) echo 2 ;; QUIT) echo 3 ;; PIPE) echo 13 ;; TERM) echo 15 ;;
             XFSZ) echo 25 ;; *) echo 0 ;; esac
}

# killed SIG NAME TARGET CMD... -- run CMD in the background; once a
# temporary file beside TARGET exists, send SIG; the run must die of SIG
# and leave no temporary file, and TARGET as it was before.
killed() {
  sig=$1; name=$2; target=$3; shift 3
  before=absent; [ -e "$target" ] && before=$(cat "$target")
  # shellcheck disable=SC2086
  $DEF "$@" > out 2> err &
  p=$!
  i=0
  while [ $i -lt 600 ] && [ -z "$(ls "$target".tmp* 2>/dev/null)" ]; do
    kill -0 $p 2>/dev/null || break
    sleep 0.02; i=$((i + 1))
  done
  if [ -z "$(ls "$target".tmp* 2>/dev/null)" ]; then
    kill -KILL $p 2>/dev/null; wait $p
    bad "$name: no temporary file appeared: $(cat err)"
    rm -f "$target".tmp*
    return
  fi
  kill -"$sig" $p; wait $p 2>/dev/null; rc=$?
  want=$((128 + $(signum "$sig")))
  [ $rc -eq $want ] && ok || bad "$name: SIG$sig: exit status $rc, want $want (died of the signal): $(cat err)"
  [ -z "$(ls "$target".tmp* 2>/dev/null)" ] && ok || bad "$name: SIG$sig left $(ls "$target".tmp*)"
  after=absent; [ -e "$target" ] && after=$(cat "$target")
  [ "$after" = "$before" ] && ok || bad "$name: SIG$sig: the target changed ($before -> $(printf '%.40s' "$after"))"
  rm -f "$target".tmp*
}

TILE=$BUILD/tile BENCH=$BUILD/bench
# The traced run's temporary file lives as long as the run (--trace-limit
# none: no measuring run first); the ring's too.
for sig in TERM INT HUP PIPE QUIT; do
  [ -z "$DEF" ] && { [ $sig = INT ] || [ $sig = QUIT ]; } && continue
  killed $sig "tile --trace" t.json "$TILE" "$DATA/prostate_0.contours" -q --procs 8 --trace t.json --trace-limit none
done
echo keep > t.csv
killed TERM "tile --trace over a file" t.csv "$TILE" "$DATA/prostate_0.contours" -q --procs 8 --trace t.csv --trace-limit none
killed INT "bench --ring --trace-json" r.json "$BENCH" --ring 8 --laps 10000000 --trace-json r.json --trace-limit none
echo keep > r.csv
killed HUP "bench --ring --trace-csv over a file" r.csv "$BENCH" --ring 8 --laps 10000000 --trace-csv r.csv --trace-limit none
rm -f t.csv r.csv
[ -z "$DEF" ] && echo "cli_signals: skipped: SIGINT and SIGQUIT were not sent (env --default-signal is missing, and a background job ignores them)"

# Mid-write: the file size limit (512 bytes) strikes inside the write; the
# default action of SIGXFSZ ends the process.
midwrite() {
  name=$1; target=$2; shift 2
  rm -f "$target"
  { (ulimit -f 1; ulimit -c 0; exec "$@") > out 2> err; } 2>/dev/null; rc=$?
  [ $rc -eq $((128 + $(signum XFSZ))) ] && ok || bad "$name: exit status $rc, want death by SIGXFSZ: $(cat err)"
  [ -z "$(ls "$target"* 2>/dev/null)" ] && ok || bad "$name: left $(ls "$target"*)"
}
midwrite "tile -o" m.ply "$TILE" "$DATA/prostate_2.contours" -q -o m.ply
midwrite "tile --trace" t.csv "$TILE" "$DATA/prostate_3.contours" -q --procs 3 --trace t.csv
midwrite "bench -o" b.csv "$BENCH" --points 40 --procs 1..4 -o b.csv
midwrite "bench --model -o" mo.csv "$BENCH" --model --diag 20,30 --procs 2..6 -o mo.csv
midwrite "bench --glass -o" g.contours "$BENCH" --glass --slices 6 --points 12 -o g.contours
midwrite "bench --ring --trace-json" r.json "$BENCH" --ring 3 --laps 100 --trace-json r.json
printf 'points,procs,speedup\n1,1,1\n1,2,2\n' > s.csv
midwrite "plot -o" p.svg "$BUILD/plot" lines s.csv -x procs -y speedup -o p.svg

# A write that fails: exit 1, the target as it was, no data row.
echo keep > r.csv
(trap '' XFSZ; ulimit -f 1; exec "$BENCH" --ring 3 --laps 1000 --trace-csv r.csv) > out 2> err; rc=$?
[ $rc -eq 1 ] && ok || bad "ring, trace write fails: exit $rc, want 1: $(cat err)"
[ "$(cat r.csv)" = keep ] && ok || bad "ring, trace write fails: the target changed"
[ ! -s out ] && ok || bad "ring, trace write fails: printed $(cat out)"
[ -z "$(ls r.csv.tmp* 2>/dev/null)" ] && ok || bad "ring, trace write fails: left a temporary file"
echo keep > m.obj
(trap '' XFSZ; ulimit -f 1; exec "$TILE" "$DATA/prostate_2.contours" -q -o m.obj) > out 2> err; rc=$?
[ $rc -eq 1 ] && [ "$(cat m.obj)" = keep ] && [ -z "$(ls m.obj.tmp* 2>/dev/null)" ] && ok ||
  bad "tile -o, write fails: exit $rc, target $(head -c 20 m.obj), $(cat err)"

# The trace size: refused above the limit before anything is written, the
# message giving the size; the size is the written trace's, byte for byte.
for f in t.csv t.json; do
  "$TILE" "$DATA/prostate_3.contours" -q --procs 5 --trace $f --trace-limit 100k > out 2> err; rc=$?
  [ $rc -eq 1 ] && [ ! -s out ] && [ ! -e $f ] && [ -z "$(ls $f.tmp* 2>/dev/null)" ] && ok ||
    bad "--trace $f --trace-limit 100k: exit $rc, $(cat err)"
  grep -q "^tile: $f: the trace would take .* ([0-9]* bytes), more than the limit of 100 kB; --trace-limit [0-9]*M (or none) writes it$" err \
    && ok || bad "--trace-limit message: $(cat err)"
  said=$(sed -n 's/.*(\([0-9]*\) bytes).*/\1/p' err)
  "$TILE" "$DATA/prostate_3.contours" -q --procs 5 --trace $f > /dev/null 2> err && ok || bad "--trace $f: $(cat err)"
  [ "$(wc -c < $f)" = "$said" ] && ok || bad "--trace $f: the refusal said $said bytes, the trace has $(wc -c < $f)"
done
"$BENCH" --ring 4 --laps 50 --trace-csv r.csv --trace-json r.json --trace-limit 1000 > out 2> err; rc=$?
[ $rc -eq 1 ] && [ ! -s out ] && [ "$(cat r.csv)" = keep ] && [ ! -e r.json ] &&
  grep -q '^bench: r.csv and r.json: the trace would take .* bytes), more than the limit of 1.0 kB' err &&
  ok || bad "ring --trace-limit 1000: exit $rc, $(cat err)"

summary

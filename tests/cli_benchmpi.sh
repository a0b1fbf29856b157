#!/bin/sh
# cli_benchmpi.sh -- make bench-mpi's script (tests/bench_mpi.sh) as a smoke
# test, not a timing: with small sizes and the sanitized tools of $BUILD it
# runs every program (beside smpirun where make check found SimGrid), and
# writes a CSV whose checksums are the programs' closed forms, the same on
# both simulators with the same simulated times, a Markdown table with a row
# per run, four SVG pictures and nothing else; with ROUNDS a row per run in
# the CSV and the medians in the table; a run over TIMEOUT is a row that says
# so and the benchmark goes on; bad settings are refused with one line and
# nothing written.
BUILD=${BUILD:-build/chk}
. tests/clilib.sh
if [ "${SMPI_STATUS:-}" = yes ]; then SMPI=auto; else SMPI=no; echo "cli_benchmpi: skipped: the runs beside smpirun (${SMPI_STATUS:-make check sets SMPI_STATUS})"; fi
run() {
  env BIN="$BUILD" PLOT="$BUILD/plot" EXAMPLES="$BUILD/examples" SMPI=$SMPI BW_SIZES=64,4096 WINDOW=4 BW_ITERS=2 \
    A2A_RANKS=4 A2A_SIZES=64,1024 A2A_ITERS=2 BC_SIZES=4096 BC_RANKS=4 BC_ITERS=2 RING_RANKS=4 RING_LAPS=10 RANKS=3,8 AR_COUNT=4 AR_ITERS=2 MP_RANKS=100 \
    SMPI_RANKS=8 "$@" sh tests/bench_mpi.sh
}

# ---- a whole run ---------------------------------------------------------------
run OUT="$T/a" > "$T/a.out" 2> "$T/a.err"; rc=$?
[ $rc -eq 0 ] && [ ! -s "$T/a.out" ] && grep -q "^bench-mpi: \[[0-9]* s\] wrote $T/a: " "$T/a.err" && ok \
  || bad "a run: exit $rc: $(head -5 "$T/a.err")"
[ "$(cd "$T/a" && ls -A | tr '\n' ' ')" = "bench-mpi-ranks-rss.svg bench-mpi-ranks.svg bench-mpi-size-rss.svg bench-mpi-size.svg bench-mpi.csv bench-mpi.log bench-mpi.md " ] \
  && ok || bad "the output folder holds: $(ls -A "$T/a")"
csv=$T/a/bench-mpi.csv
[ "$(head -n 1 "$csv")" = "program,simulator,ranks,bytes,wall_s,peak_rss_kb,sim_time,checksum,status" ] && ok \
  || bad "the CSV's header: $(head -n 1 "$csv")"
n=$(awk -F, 'NR > 1 && $2 == "tilesim"' "$csv" | wc -l)
[ "$n" -eq 11 ] && ok || bad "$n runs on tilesim, not 11: $(cat "$csv")"
awk -F, 'NR > 1 && $9 != "\"ok\""' "$csv" > "$T/notok"
[ ! -s "$T/notok" ] && ok || bad "runs not ok: $(cat "$T/notok")"
# The checksums, from the programs' closed forms (tests/mpirun/*.c).
awk -F, '
  function bw(b, w, it,   s, i, k) { for (i = 0; i < it; i++) for (k = 0; k < w; k++) s += 2 * ((i + 1) * 1000003 + k * 7919) + 1; return s }
  function a2a(p, it,   s, a, d, i) { for (a = 0; a < p; a++) for (d = 0; d < p; d++) for (i = 0; i < it; i++)
      s += 2 * (a * 2 ^ 40 + d * 2 ^ 20) + (2 * i + 1) + (2 * i + 2); return s }
  function bc(p, size, it,   s, i, at) { for (i = 0; i < it; i++) { for (at = 0; at + 8 <= size; at += 4096) s += i * 2 ^ 40 + 2 * at + 1
      s += i * 2 ^ 40 + 2 * (size - 8) + 1 } return p * s }
  function ar(p, c, it,   s, i, k) { for (k = 0; k < it; k++) for (i = 0; i < c; i++) s += p * (p - 1) / 2 + p * (i + k); return s }
  NR > 1 { want = $1 == "bw" ? bw($4, 4, 2) : $1 == "alltoall" ? a2a($3, 2) : $1 == "bcast" ? bc($3, $4, 2) : $1 == "ring" ? $3 * 10 \
      : $1 == "startup" ? ar($3, 1, 1) : $1 == "allreduce" ? ar($3, 4, 2) : $1 == "mp-ring" ? $3 : -1
    if (sprintf("%.0f", want) != $8) { print "row " NR ": " $0 " (the closed form: " sprintf("%.0f", want) ")"; bad = 1 } }
  END { exit bad }' "$csv" > "$T/sums" && ok || bad "checksums: $(cat "$T/sums")"
awk -F, 'NR > 1 && ($5 + 0 <= 0 || $6 + 0 <= 0 || $7 + 0 <= 0)' "$csv" > "$T/zero"
[ ! -s "$T/zero" ] && ok || bad "rows without a time, a peak or a simulated time: $(cat "$T/zero")"
if [ $SMPI = auto ]; then
  n=$(awk -F, 'NR > 1 && $2 == "smpi"' "$csv" | wc -l)
  [ "$n" -eq 10 ] && ok || bad "$n runs on smpirun, not 10 (all but the mp.h ring): $(cat "$csv")"
  awk -F, 'NR > 1 { k = $1 "," $3 "," $4; if (k in s && (s[k] != $7 || c[k] != $8)) { print "differ: " $0; bad = 1 } s[k] = $7; c[k] = $8 }
    END { exit bad }' "$csv" > "$T/diff" && ok || bad "the two simulators: $(cat "$T/diff")"
fi
# The Markdown: a table, a row per program, ranks and size.
md=$T/a/bench-mpi.md
rows=$(grep -c '^| [a-z]' "$md")
[ "$rows" -eq 12 ] && grep -q '^Measured by `make bench-mpi` on ' "$md" && grep -q '^| mp-ring | 100 | 8 | ' "$md" \
  && awk '/^\|/ { n = gsub(/\|/, "|"); if (!w) w = n; else if (n != w) exit 1 }' "$md" && ok || bad "bench-mpi.md: $(cat "$md")"
for f in size size-rss ranks ranks-rss; do
  svg=$T/a/bench-mpi-$f.svg
  head -n 1 "$svg" | grep -q '^<svg xmlns="http://www.w3.org/2000/svg"' && [ "$(tail -n 1 "$svg")" = "</svg>" ] \
    && [ "$(grep -c '<polyline' "$svg")" -ge 2 ] && ok || bad "bench-mpi-$f.svg: $(head -c 200 "$svg")"
done

# ---- a run over TIMEOUT: a row that says so, and the rest goes on ----------------
run OUT="$T/b" TIMEOUT=1 RING_LAPS=100000000 BW_SIZES=64 A2A_SIZES=64 RANKS=3 SMPI=no > "$T/b.out" 2> "$T/b.err"; rc=$?
[ $rc -eq 0 ] && grep -q '^ring,tilesim,4,8,[0-9.]*,[0-9]*,,,"stopped after 1 s"$' "$T/b/bench-mpi.csv" \
  && grep -q '^mp-ring,tilesim,100,8,.*,"ok"$' "$T/b/bench-mpi.csv" && ok \
  || bad "TIMEOUT=1: exit $rc: $(cat "$T/b/bench-mpi.csv" "$T/b.err" 2> /dev/null | head -20)"
left=$(for f in /proc/[0-9]*/cmdline; do { tr '\0' ' ' < "$f"; } 2> /dev/null; echo; done | grep -c -- ' 100000000 8 $')
[ "$left" -eq 0 ] && ok || bad "$left runs left behind after TIMEOUT"

# ---- ROUNDS: a row per run, the table the medians ---------------------------------
run OUT="$T/m" ROUNDS=3 BW_SIZES=4096 A2A_SIZES=64 RANKS=3 MP_RANKS=0 > "$T/m.out" 2> "$T/m.err"; rc=$?
csv=$T/m/bench-mpi.csv md=$T/m/bench-mpi.md
[ $rc -eq 0 ] && [ "$(awk -F, 'NR > 1 && $1 == "bw" && $2 == "tilesim"' "$csv" | wc -l)" -eq 3 ] \
  && [ "$(grep -c '^| bw | 2 | 4096 | ' "$md")" -eq 1 ] && grep -q 'each the median of 3 runs' "$md" && ok \
  || bad "ROUNDS=3: exit $rc: $(cat "$csv" "$T/m.err" 2> /dev/null | head -20)"
# The table's tilesim wall and peak, against the median of the CSV's three runs
# (sorted here by sort(1)).
for p in bw alltoall bcast ring startup allreduce; do
  want=$(awk -F, -v p=$p 'NR > 1 && $1 == p && $2 == "tilesim" { print $5 }' "$csv" | sort -g | sed -n 2p)
  peak=$(awk -F, -v p=$p 'NR > 1 && $1 == p && $2 == "tilesim" { print $6 }' "$csv" | sort -g | sed -n 2p)
  got=$(awk -F'|' -v p=$p '$2 == " " p " " { print $5 "|" $6; exit }' "$md")
  want=$(printf '%s s | %.0f MiB' "$want" "$(awk -v k="$peak" 'BEGIN { printf "%.0f", k / 1024 }')")
  [ "$(echo "$got" | sed 's/^ *//; s/ *$//')" = "$want" ] && ok || bad "ROUNDS=3, $p: the table says '$got', the median of the runs '$want'"
done

# ---- refusals: one line, the usage line, status 2, nothing written ---------------
refused() {   # refused MESSAGE SETTING...
  msg=$1
  shift
  run OUT="$T/r" "$@" > "$T/r.out" 2> "$T/r.err"; rc=$?
  [ $rc -eq 2 ] && [ ! -s "$T/r.out" ] && [ "$(head -n 1 "$T/r.err")" = "bench-mpi: $msg" ] && [ ! -e "$T/r" ] \
    && grep -q '^usage: make bench-mpi \[OUT=DIR\]' "$T/r.err" && ok || bad "$*: exit $rc (want 2, '$msg'): $(cat "$T/r.err")"
}
refused "WINDOW takes whole numbers from 1 to 4096 (0)" WINDOW=0
refused "BW_SIZES takes whole numbers separated by commas (64,,128)" BW_SIZES=64,,128
refused "RANKS takes whole numbers from 2 to 1000000 (2000000)" RANKS=2000000
refused "SMPI takes auto or no (yes)" SMPI=yes
refused "ROUNDS takes whole numbers from 1 to 1000 (0)" ROUNDS=0
refused "BC_SIZES takes whole numbers from 32 to 1073741824 (16)" BC_SIZES=16
env OUT="$T/r" sh tests/bench_mpi.sh now > "$T/r.out" 2> "$T/r.err"; rc=$?
[ $rc -eq 2 ] && [ "$(head -n 1 "$T/r.err")" = "bench-mpi: the settings go in the environment, not as arguments (now)" ] \
  && [ ! -e "$T/r" ] && ok || bad "an argument: exit $rc: $(cat "$T/r.err")"

summary

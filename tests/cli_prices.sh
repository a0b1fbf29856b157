#!/bin/sh
# cli_prices.sh -- the prices of a slave's weight table and of its
# backtracking (--table-c, --back-c; par.h) from the command line: 0 by
# default, so the tc2000 sweeps are the paper's bit for bit (with both given
# as 0 too: every column but the host's wall time); set, the runs whose
# slaves pay them take longer, with the same optimum, nodes and messages;
# bad values refused.  (tests/test_master.c holds the closed forms.)
# Run by make check with BUILD=build/chk (the sanitized build).
BENCH=${BUILD:-build/chk}/bench
. tests/clilib.sh

# every column but wall_s (16)
cols() { cut -d, -f1-15,17- "$1"; }

"$BENCH" --points 100,200 --alloc half,size > "$T/a.csv" 2> "$T/err" && ok || bad "default: $(cat "$T/err")"
"$BENCH" --points 100,200 --alloc half,size --table-c 0 --back-c 0 > "$T/z.csv" 2> "$T/err" && ok || bad "0: $(cat "$T/err")"
[ "$(tail -n +2 "$T/a.csv" | wc -l)" -eq 64 ] && ok || bad "rows: $(wc -l < "$T/a.csv")"
cols "$T/a.csv" > "$T/a.cut"; cols "$T/z.csv" > "$T/z.cut"
cmp -s "$T/a.cut" "$T/z.cut" && ok || bad "prices 0 changed the tc2000 sweep: $(diff "$T/a.cut" "$T/z.cut" | head -3)"

# Priced: a table on every slave of few (P <= 5; 100 and 200 points are
# small), backtracking wherever a group has two or more slaves (and mu(0)).
# At P = 1 the one slave does everything: the time grows by exactly its
# table, m (n+1) cells, and one backtracked path, m + n steps (m = n =
# points).  Elsewhere the messages move in time and the sum of the times
# grows; the optimum, nodes and messages stay.
"$BENCH" --points 100,200 --alloc half,size --table-c 2e-6 --back-c 1e-6 > "$T/p.csv" 2> "$T/err" \
  && ok || bad "priced: $(cat "$T/err")"
paste -d, "$T/a.csv" "$T/p.csv" | awk -F, -v n="$(head -1 "$T/a.csv" | tr ',' '\n' | wc -l)" 'NR > 1 {
    if ($15 != $(n + 15) || $14 != $(n + 14) || $12 != $(n + 12)) moved = 1   # cost, nodes, messages
    if ($2 == 1) {
      want = $1 * ($1 + 1) * 2e-6 + 2 * $1 * 1e-6
      d = $(n + 9) - $9 - want
      if (d > 1e-9 || d < -1e-9) { printf "P=1, %d points: %.9f s more, want %.9f\n", $1, $(n + 9) - $9, want; moved = 1 }
    }
    a += $9; p += $(n + 9) }
  END { exit moved || !(p > a) }' > "$T/why" && ok || bad "priced runs: $(cat "$T/why")"

# Refused: not seconds.
for v in -1 x '' 1e10; do
  "$BENCH" --points 100 --procs 2 --table-c "$v" > /dev/null 2> "$T/err" && bad "--table-c '$v' accepted" \
    || { grep -q -- '--table-c' "$T/err" && ok || bad "--table-c '$v': $(cat "$T/err")"; }
  "$BENCH" --points 100 --procs 2 --back-c "$v" > /dev/null 2> "$T/err" && bad "--back-c '$v' accepted" \
    || { grep -q -- '--back-c' "$T/err" && ok || bad "--back-c '$v': $(cat "$T/err")"; }
done

summary

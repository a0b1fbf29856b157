#!/bin/sh
# cli_claimsmap.sh -- bench --claims-map on a small grid (100 and 200 points;
# the bus and the ideal network; two message costs; a generated pair and a
# real one; and LogGP): every row's verdicts and best d equal those of bench --claims
# on the same sweeps made by plain ./bench; --jobs 2 gives the bytes of
# --jobs 1; the CSV's form; bad usage; build/plot claims draws the grid.
BENCH=${BUILD:-build/chk}/bench
PLOT=${BUILD:-build/chk}/plot
. tests/clilib.sh
REAL=tests/data/slicerrt/tinypatient_1.contours

"$BENCH" --claims-map --points 100,200 --net bus,ideal --m 2.75e-4,2.6e-3 --jobs 2 -o "$T/map.csv" 2> "$T/err" && ok ||
  bad "the map: $(cat "$T/err")"
"$BENCH" --claims-map --points 100,200 --net bus,ideal --m 2.75e-4,2.6e-3 --jobs 1 > "$T/map1.csv" 2> "$T/err" && ok ||
  bad "the map, --jobs 1: $(cat "$T/err")"
cmp -s "$T/map.csv" "$T/map1.csv" && ok || bad "--jobs 2 differs from --jobs 1"
"$BENCH" --claims-map --input "$REAL" --pair 0,1 --m 2.75e-4 --jobs 2 -o "$T/real.csv" 2> "$T/err" && ok ||
  bad "the real pairs: $(cat "$T/err")"

head -1 "$T/map.csv" | grep -q '^net,m,c,m_over_c,L,o,g,G,per_byte,master_c,input,pair,seed,points,claim1,claim2,claim3,claim4,claim5,claim6,claim7,t2_t1,t3_t2,t4_t3,t6_t5,half_best_p,half_best_speedup,size_t4_t3,size_t6_t5,size_best_p,size_best_speedup,best_d$' &&
  ok || bad "header: $(head -1 "$T/map.csv")"
[ "$(tail -n +2 "$T/map.csv" | wc -l)" -eq 4 ] && [ "$(tail -n +2 "$T/real.csv" | wc -l)" -eq 2 ] && ok ||
  bad "expected 4 and 2 rows"
# every row: its configuration, m/c = m/c, verdicts 1, 0 or n/a, as many fields as the header
awk -F, 'NR == 1 { n = NF; next }
         NF != n || ($1 != "bus" && $1 != "ideal") || $3 != 5e-05 || ($4 - $2 / $3) ^ 2 > 1e-18 || $10 != 5e-07 { bad = 1 }
         { for (i = 15; i <= 21; i++) if ($i != "1" && $i != "0" && $i != "n/a") bad = 1 }
         END { exit bad }' "$T/map.csv" && ok || bad "a row's form: $(cat "$T/map.csv")"
# one size per real pair: claim 7 n/a, the pair's own points
awk -F, 'NR > 1 && ($11 != "'"$REAL"'" || $13 != "n/a" || $21 != "n/a" || $14 != ($12 == 0 ? 4 : 8)) { bad = 1 }
         END { exit bad }' \
  "$T/real.csv" && ok || bad "the real pairs' rows: $(cat "$T/real.csv")"

# Each row against plain ./bench's sweeps judged by bench --claims.
yn() { case $1 in yes) echo 1 ;; no) echo 0 ;; *) echo "$1" ;; esac; }
check_row() {   # LINE: a map row; the rest: how ./bench makes the pair
  line=$1; shift
  net=$(echo "$line" | cut -d, -f1) m=$(echo "$line" | cut -d, -f2) pts=$(echo "$line" | cut -d, -f14)
  lat=--m; [ "$net" = loggp ] && lat=--L   # under loggp the map's m is the latency
  "$BENCH" "$@" --alloc half,size --net "$net" $lat "$m" --jobs 2 -o "$T/sp.csv" 2> "$T/err" &&
    "$BENCH" "$@" --points "$pts" --alloc size --min-diag 20,40,60,80,100 --net "$net" $lat "$m" --jobs 2 \
      -o "$T/md.csv" 2>> "$T/err" && "$BENCH" --claims "$T/sp.csv" "$T/md.csv" > "$T/claims.csv" 2>> "$T/err" ||
    { bad "plain sweeps for $net m=$m: $(cat "$T/err")"; return; }
  want=""
  for c in 1 2 3 4 5 6 7; do
    v=$(sed -n "s/^\"$c [^\"]*\",\([^,]*\),.*/\1/p" "$T/claims.csv")
    want="$want,$(yn "$v")"
  done
  got=$(echo "$line" | cut -d, -f15-21)
  [ ",$got" = "$want" ] && ok || bad "$net m=$m $*: the map says $got, bench --claims $want"
  d=$(sed -n 's/.*; the best is d=\([0-9]*\)"$/\1/p' "$T/claims.csv")
  [ "$(echo "$line" | cut -d, -f32)" = "${d:-n/a}" ] && ok || bad "$net m=$m: best d $(echo "$line" | cut -d, -f32), bench --claims $d"
  bp=$(sed -n 's/^"4 .*best overall [0-9.]* at \([0-9]*\)"$/\1/p' "$T/claims.csv")
  [ "$(echo "$line" | cut -d, -f26)" = "$bp" ] && ok || bad "$net m=$m: half's best P $(echo "$line" | cut -d, -f26), bench --claims $bp"
}
tail -n +2 "$T/map.csv" | while IFS= read -r line; do check_row "$line" --points 100,200; done > "$T/rows.log"
tail -n +2 "$T/real.csv" | sed -n 2p | while IFS= read -r line; do check_row "$line" --input "$REAL" --pair 1; done >> "$T/rows.log"
"$BENCH" --claims-map --net loggp --m 2.75e-4 --o 1e-5 --g 2e-5 --points 60,120 > "$T/loggp.csv" 2> "$T/err" && ok ||
  bad "loggp: $(cat "$T/err")"
awk -F, 'NR == 2 && $1 == "loggp" && $5 == $2 && $6 == 1e-05 && $7 == 2e-05 { good = 1 } END { exit !good }' "$T/loggp.csv" &&
  ok || bad "loggp's row: $(cat "$T/loggp.csv")"
tail -n +2 "$T/loggp.csv" | while IFS= read -r line; do check_row "$line" --points 60,120 --o 1e-5 --g 2e-5; done >> "$T/rows.log"
# (the loops run in subshells: their verdicts come back through the log)
n=$(grep -c . "$T/rows.log"); [ "$n" -eq 0 ] && pass=$((pass + 18)) || { fail=$((fail + n)); cat "$T/rows.log"; }

# Bad usage: one line, exit 2, no output.
for args in "--pair 0" "--alloc size" "--net bus,token" "--procs 1..4" "--m -1" "--jobs 0" "--input $REAL --points 100" \
            "--topology line" "--frobnicate 1" "--c 0 --master-c 1e-6"; do
  # shellcheck disable=SC2086
  "$BENCH" --claims-map $args -o "$T/no.csv" > /dev/null 2> "$T/err"; rc=$?
  [ $rc -eq 2 ] && [ ! -e "$T/no.csv" ] && grep -q '^bench: ' "$T/err" && ok || bad "$args: exit $rc, $(head -1 "$T/err")"
done
"$BENCH" --claims-map --input "$REAL" --pair 9 -o "$T/no.csv" > /dev/null 2> "$T/err"; rc=$?
[ $rc -eq 1 ] && [ ! -e "$T/no.csv" ] && grep -q 'no pair 9' "$T/err" && ok || bad "--pair 9: exit $rc, $(cat "$T/err")"

# The grid: a panel per net and pair, 7 cells a configuration, the tc2000 column outlined.
cat "$T/map.csv" > "$T/both.csv"; tail -n +2 "$T/real.csv" >> "$T/both.csv"
"$PLOT" claims "$T/both.csv" --title "a <map>" -o "$T/map.svg" 2> "$T/err" && ok || bad "plot claims: $(cat "$T/err")"
head -1 "$T/map.svg" | grep -q '^<svg xmlns="http://www.w3.org/2000/svg"' && tail -1 "$T/map.svg" | grep -q '^</svg>$' && ok ||
  bad "not an SVG document"
[ "$(grep -c 'height="22" fill="#' "$T/map.svg")" -eq $((7 * 6)) ] && ok || bad "expected 42 cells (6 configurations)"
[ "$(grep -c 'font-weight="bold">\(bus\|ideal\), ' "$T/map.svg")" -eq 4 ] && ok || bad "expected 4 panels"
grep -q '>bus, tinypatient_1.contours pair 1<' "$T/map.svg" && grep -q '>ideal, generated pair, seed 1993<' "$T/map.svg" &&
  ok || bad "panel titles"
[ "$(grep -c 'stroke-width="2.5"' "$T/map.svg")" -eq 5 ] && ok || bad "the tc2000 column: 4 outlines and the legend's"
grep -q 'a &lt;map&gt;' "$T/map.svg" && ok || bad "title not escaped"
# held, failed and n/a cells as the CSV says: count the colours against the verdicts
cells=$(awk -F, 'NR > 1 { for (i = 15; i <= 21; i++) n[$i]++ } END { printf "%d %d %d", n["1"], n["0"], n["n/a"] }' "$T/both.csv")
drawn=$(printf '%d %d %d' "$(grep -c 'height="22" fill="#2ca02c"' "$T/map.svg")" "$(grep -c 'height="22" fill="#d62728"' "$T/map.svg")" \
  "$(grep -c 'height="22" fill="#d9d9d9"' "$T/map.svg")")
[ "$cells" = "$drawn" ] && ok || bad "cells held/failed/n/a: CSV $cells, drawn $drawn"
"$PLOT" claims "$T/both.csv" --title "a <map>" -o "$T/map2.svg" && cmp -s "$T/map.svg" "$T/map2.svg" && ok || bad "not deterministic"
"$PLOT" claims "$T/sp.csv" -o "$T/no.svg" > /dev/null 2> "$T/err"; [ $? -eq 1 ] && [ ! -e "$T/no.svg" ] &&
  grep -q 'not a claims map' "$T/err" && ok || bad "a sweep is not a map: $(cat "$T/err")"
summary

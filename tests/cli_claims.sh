#!/bin/sh
# cli_claims.sh -- the paper's claims (sections 6 and 7) on a reduced sweep,
# 200 and 500 points, P = 1..16, both allocations, run by the sanitized
# ./bench; `bench --claims` reads them back.  Asserted: the claims that this
# size can show (1, 2, 3, 4, 7, and 5's "size beats half"); 6 is checked for
# the form of its report (doc/paper.md, "The paper's claims": what holds and why).
# Also: --jobs 2 gives exactly the rows of --jobs 1, speedup is T(1)/T(P),
# and `cost` is one optimum per pair.
BENCH=${BUILD:-build/chk}/bench
. tests/clilib.sh

"$BENCH" --points 200,500 --alloc half,size --jobs 2 -o "$T/sp.csv" 2> "$T/err" && ok || bad "sweep: $(cat "$T/err")"
"$BENCH" --points 300 --procs 1..4 --alloc size --jobs 1 > "$T/j1.csv" && "$BENCH" --points 300 --procs 1..4 --alloc size --jobs 2 > "$T/j2.csv" && ok || bad "jobs runs"
cut -d, -f1-15,17- "$T/j1.csv" > "$T/j1c"; cut -d, -f1-15,17- "$T/j2.csv" > "$T/j2c"
cmp -s "$T/j1c" "$T/j2c" && ok || bad "--jobs 2 differs from --jobs 1 (wall_s aside)"
head -1 "$T/sp.csv" | grep -q '^points,procs,alloc,min_diag,net,m,c,seed,sim_time,speedup,efficiency,messages,bytes,nodes,cost,wall_s' && ok || bad "header: $(head -1 "$T/sp.csv")"
[ "$(tail -n +2 "$T/sp.csv" | wc -l)" -eq 64 ] && ok || bad "expected 64 rows"
# speedup = T(1)/T(P) of the same points and allocation; one cost per pair
awk -F, 'NR>1 { k=$1","$3; if ($2==1) t1[k]=$9; t[NR]=$9; key[NR]=k; sp[NR]=$10; c[$1]=c[$1]==""?$15:c[$1]; if (c[$1]!=$15) badc=1 }
         END { for (i in t) { d = t1[key[i]]/t[i] - sp[i]; if (d < -1e-5 || d > 1e-5) bads=1 } exit bads+badc }' "$T/sp.csv" && ok || bad "speedup is not T(1)/T(P), or a pair has two costs"
"$BENCH" --claims "$T/sp.csv" --require 1,2,3,4,7 > "$T/claims.csv" 2> "$T/err" && ok || bad "claims: $(cat "$T/err") $(cat "$T/claims.csv")"
[ "$(grep -c '^"[1-7] [^"]*",\(yes\|no\|n/a\),".*"$' "$T/claims.csv")" -eq 7 ] && ok || bad "claims report: $(cat "$T/claims.csv")"
grep -q '^"5 [^"]*",\(yes\|no\),"500 pts: summed speedup size' "$T/claims.csv" && ok || bad "claim 5 report"
# Claim 5's first half holds at this size (size beats half); its plateaus do not
# go (doc/paper.md: the generated pairs split evenly).
grep -q '^"5 .*(better, ' "$T/claims.csv" && ok || bad "claim 5: size is not better than half: $(grep '^"5 ' "$T/claims.csv")"
grep -q '^"6 [^"]*",n/a,"no min-diag sweep given"$' "$T/claims.csv" && ok || bad "claim 6 without a sweep"
# A claim that does not hold makes --require fail.
"$BENCH" --claims "$T/sp.csv" --require 6 > /dev/null 2>&1; [ $? -eq 1 ] && ok || bad "--require 6 without a d sweep should fail"
"$BENCH" --claims /nonexistent.csv > /dev/null 2> "$T/err"; [ $? -eq 1 ] && grep -q 'cannot open' "$T/err" && ok || bad "missing CSV"
summary

#!/bin/sh
# cli_variants.sh -- the variants of the parallel algorithm from the command
# line: ./bench --variant and the --block/--schedule/--alloc lists,
# ./tile with each variant giving the serial mesh, bad usage.
# Run by make check with BUILD=build/chk (the sanitized build).
BENCH=${BUILD:-build/chk}/bench
TILE=${BUILD:-build/chk}/tile
DATA=tests/data/slicerrt
. tests/clilib.sh

# One sweep, the paper beside five variants: 6 x 3 rows, the variant, block,
# schedule and idle columns, one optimum on every row.
"$BENCH" --points 80 --procs 1,2,5 --variant paper,fit,block7,dynamic,dynamic+block7,size+block2 \
  > "$T/v.csv" 2> "$T/err" && ok || bad "--variant: $(cat "$T/err")"
head -1 "$T/v.csv" | grep -q ',link_wait,variant,block,schedule,idle_per_slave$' && ok || bad "header: $(head -1 "$T/v.csv")"
[ "$(tail -n +2 "$T/v.csv" | wc -l)" -eq 18 ] && ok || bad "rows: $(wc -l < "$T/v.csv")"
awk -F, 'NR > 1 { print $33 "," $34 "," $35 "," $3 }' "$T/v.csv" | sort -u > "$T/names"
printf '%s\n' "block7,7,static,half" "dynamic+block7,7,dynamic,half" "dynamic,1,dynamic,half" \
  "fit,1,static,fit" "paper,1,static,half" "size+block2,2,static,size" | sort | cmp -s - "$T/names" \
  && ok || bad "variant columns: $(cat "$T/names")"
[ "$(tail -n +2 "$T/v.csv" | cut -d, -f15 | sort -u | wc -l)" -eq 1 ] && ok || bad "optima differ: $(cut -d, -f15 "$T/v.csv")"
awk -F, 'NR > 1 && ($36 < 0 || $36 > $9) { bad = 1 } END { exit bad }' "$T/v.csv" && ok || bad "idle per slave out of [0, time]"
# The blocked variants send fewer boundary messages than the paper at P = 5.
awk -F, 'NR > 1 && $2 == 5 { b[$33] = $17 } END { exit !(b["block7"] < b["paper"] && b["dynamic+block7"] < b["dynamic"]) }' \
  "$T/v.csv" && ok || bad "block7 does not cut the boundary messages"

# The option lists as a cross product: paper, block4, dynamic, dynamic+block4.
"$BENCH" --points 60 --procs 4 --block 1,4 --schedule static,dynamic > "$T/x.csv" 2> "$T/err" && ok || bad "lists: $(cat "$T/err")"
[ "$(tail -n +2 "$T/x.csv" | cut -d, -f33 | tr '\n' ' ')" = "paper block4 dynamic dynamic+block4 " ] \
  && ok || bad "cross product: $(cut -d, -f33 "$T/x.csv" | tr '\n' ' ')"

# Measured on threads: the same optimum as simulated.
"$BENCH" --points 60 --procs 3 --backend threads --repeat 1 --variant dynamic+block4,fit+block2 > "$T/t.csv" 2> "$T/err" \
  && ok || bad "threads: $(cat "$T/err")"
[ "$(tail -n +2 "$T/t.csv" | cut -d, -f15 | sort -u)" = "$(sed -n 2p "$T/x.csv" | cut -d, -f15)" ] \
  && ok || bad "threads optimum: $(cut -d, -f15 "$T/t.csv")"

# ./tile: every variant gives the serial report (but the node count, which
# ghost nodes raise) and the serial mesh, on the simulator and on threads.
"$TILE" $DATA/prostate_3.contours -q -o "$T/ser.obj" > "$T/ser.csv" && ok || bad "serial prostate_3"
tail -n +2 "$T/ser.csv" | cut -d, -f1-8 > "$T/ser8"
for args in "--procs 6 --alloc fit --min-diag 20" "--procs 9 --block 7" "--procs 12 --schedule dynamic" \
            "--procs 16 --schedule dynamic --block 64 --min-diag 80" "--procs 5 --schedule dynamic --block 2 --backend threads"; do
  # shellcheck disable=SC2086
  "$TILE" $DATA/prostate_3.contours -q $args -o "$T/par.obj" > "$T/par.csv" 2> "$T/err" && ok || bad "$args: $(cat "$T/err")"
  tail -n +2 "$T/par.csv" | cut -d, -f1-8 | cmp -s - "$T/ser8" && ok || bad "$args: the report differs from the serial one"
  cmp -s "$T/par.obj" "$T/ser.obj" && ok || bad "$args: the mesh differs from the serial one"
done

# Bad usage: a usage line, exit 2, nothing on stdout.
for args in "--variant frob" "--variant block0" "--variant paper+" "--variant paper --block 2" \
            "--block 0" "--block x" "--schedule sometimes" "--alloc half,size,fit,half"; do
  # shellcheck disable=SC2086
  "$BENCH" $args > "$T/out" 2> "$T/err"; rc=$?
  [ $rc -eq 2 ] && [ ! -s "$T/out" ] && grep -q '^usage: bench' "$T/err" && ok || bad "bench $args: exit $rc, $(cat "$T/err")"
done
for args in "--block 0" "--schedule sometimes" "--alloc third"; do
  # shellcheck disable=SC2086
  "$TILE" $DATA/tinypatient_1.contours --procs 4 $args > "$T/out" 2> "$T/err"; rc=$?
  [ $rc -eq 2 ] && [ ! -s "$T/out" ] && ok || bad "tile $args: exit $rc, $(cat "$T/err")"
done

summary

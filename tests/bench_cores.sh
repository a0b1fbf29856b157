#!/bin/sh
# bench_cores.sh -- everything in tilesim that depends on the number of cores,
# measured on this machine in one command within a time budget (make
# bench-cores).  doc/bench-cores.md says how to run it and what each
# file holds.
#
#   make bench-cores [BUDGET=SECONDS] [OUT=DIR]
#   BUDGET=480 OUT=build/cores sh tests/bench_cores.sh      (from the tree's root)
#
# What it measures, in this order (the first steps give the whole shape, the
# later ones only more repetitions, so a short budget still covers every P):
#   1. pass 1, coarse: the threads backend (./bench --backend threads) at each
#      size of POINTS, every variant of VARIANTS, at P = 1, 2, 3, 5, 9, 17, ...
#      (2^k slaves) and P = PMAX; then ./tile's stack surface (./bench --stack:
#      what ./tile --caps -j N does, the stack already in memory) on each of
#      STACKS at N = 1, 2, 4, 8, ... and N = cores;
#   2. pass 1, fine: the other P and N;
#   3. the calibration (./bench --calibrate --options-only: micro-benchmarks
#      alone) and the calibrated simulator's prediction at every P, every size
#      and variant (./bench on the simulator, CORES runs side by side);
#   4. passes 2 .. REPEAT: every P and N again, each pass in the opposite
#      order of the one before (P and the variants), so that a slow spell of
#      the machine touches every P alike.
# A measured time is the fastest of the passes that reached it.  Before each
# step it compares what the same step took last time with the time left, and
# skips a step that would not fit; a step still running at the budget is
# stopped (what it had measured is lost: a step is a few seconds), and what
# the others measured is kept.  Every run's optimum is checked: the same for
# every variant, P and pass (a fast wrong answer shows).
#
# Settings (environment; BUDGET and OUT also as make variables):
#   BUDGET     seconds for the whole run, 1 to 86400 (default 480)
#   OUT        the output folder (default build/cores); only the files below
#              are written there (and a work folder, removed at the end)
#   REPEAT     passes (default 10): the fastest of up to REPEAT runs each
#   POINTS     sizes of the generated pair, in order of importance (4000,2000)
#   VARIANTS   the algorithms (paper,dynamic+block16,dynamic+block32)
#   STACKS     the stacks, separated by '|' (dicompyler's BODY and Lt Lung,
#              prostate_0)
#   CORES      the cores to use (default: those this process may run on)
#   PMAX       the largest P (default CORES, at least 3: two slaves)
#   CAL_REPEAT, MESSAGES   the calibration's --repeat (5) and --messages (100000)
#   BIN, PLOT  where bench is (.) and the plotter (build/plot)
#   COMMIT     the commit to name, where the tree has no .git (a bare copy)
#
# Output in OUT: cores.csv, cores.md, cores.svg, cores_tile.svg, runs.csv,
# calibrate.csv, bench-cores.log.  Exit status: 0 done (also when the budget
# ended the run), 1 a run failed or disagreed on its optimum (what was
# measured is written all the same), 2 bad usage.  Needs only a POSIX shell
# and awk, date, sleep, mkdir, rm, mv, cat (no network, nothing installed).
set -u
LC_ALL=C
export LC_ALL
NAME=bench-cores
USAGE="usage: make bench-cores [BUDGET=SECONDS] [OUT=DIR]   (or BUDGET=.. OUT=.. sh tests/bench_cores.sh; doc/bench-cores.md)"

usage() { echo "$NAME: $*" >&2; echo "$USAGE" >&2; exit 2; }
die() { echo "$NAME: $*" >&2; exit 1; }
whole() {   # whole NAME VALUE MIN MAX: VALUE a whole number in [MIN, MAX]
  case $2 in '' | *[!0-9]*) usage "$1 takes a whole number from $3 to $4 ($2)" ;; esac
  [ ${#2} -le 9 ] && [ "$2" -ge "$3" ] && [ "$2" -le "$4" ] || usage "$1 takes a whole number from $3 to $4 ($2)"
}

[ $# -eq 0 ] || usage "the settings go in the environment, not as arguments ($1)"
BUDGET=${BUDGET-480}
OUT=${OUT-build/cores}
REPEAT=${REPEAT:-10}
POINTS=${POINTS:-4000,2000}
VARIANTS=${VARIANTS:-paper,dynamic+block16,dynamic+block32}
STACKS=${STACKS:-tests/data/rtstruct/dicompyler_rtss.dcm:BODY|tests/data/rtstruct/dicompyler_rtss.dcm:Lt Lung|tests/data/slicerrt/prostate_0.contours}
CAL_REPEAT=${CAL_REPEAT:-5}
MESSAGES=${MESSAGES:-100000}
BIN=${BIN:-.}
PLOT=${PLOT:-build/plot}
whole BUDGET "$BUDGET" 1 86400
whole REPEAT "$REPEAT" 1 1000
whole CAL_REPEAT "$CAL_REPEAT" 1 1000
whole MESSAGES "$MESSAGES" 10 100000000
case $POINTS in '' | ,* | *, | *,,* | *[!0-9,]*) usage "POINTS takes sizes separated by commas, e.g. 4000,2000 ($POINTS)" ;; esac
for n in $(echo "$POINTS" | tr , ' '); do whole "a size of POINTS" "$n" 3 100000; done
[ -n "$OUT" ] || usage "OUT names the output folder, and is empty"
[ -n "$STACKS" ] || usage "STACKS is empty"

# The cores: those this process may run on (nproc follows taskset), else online.
detected=$( (nproc) 2>/dev/null || getconf _NPROCESSORS_ONLN 2>/dev/null || echo 1)
case $detected in '' | *[!0-9]*) detected=1 ;; esac
CORES=${CORES:-$detected}
whole CORES "$CORES" 1 4096
PMAX=${PMAX:-$CORES}
[ "$PMAX" -ge 3 ] 2>/dev/null || PMAX=3
whole PMAX "$PMAX" 1 64

# Tools and data, before anything is written.
[ -f tests/bench_cores.sh ] && [ -d tests/data ] || die "run from the source tree's root (make bench-cores does)"
[ -x "$BIN/bench" ] || die "$BIN/bench is not built (make bench-cores builds it; or make, then this script)"
[ -x "$PLOT" ] || die "$PLOT is not built (make builds it)"
oldifs=$IFS
IFS='|'
for s in $STACKS; do
  f=${s%%.dcm:*}
  [ "$f" != "$s" ] && f=$f.dcm
  [ -f "$f" ] || die "STACKS: $f: no such file"
done
IFS=$oldifs
err=$("$BIN/bench" --points 10 --procs 1 --variant "$VARIANTS" 2>&1 >/dev/null) || usage "VARIANTS: ${err%%
*}"

if [ -e "$OUT" ] && [ ! -d "$OUT" ]; then usage "OUT: $OUT exists and is not a folder"; fi
mkdir -p "$OUT" 2>/dev/null && [ -d "$OUT" ] || die "OUT: cannot create the folder $OUT"
W=$OUT/.bench-cores.$$
mkdir "$W" 2>/dev/null || die "OUT: cannot write in $OUT"
LOG=$OUT/bench-cores.log
UNIT=
WATCH=
STOP=
FAIL=
cleanup() {
  [ -n "$UNIT" ] && kill_unit "$UNIT"
  [ -n "$WATCH" ] && kill "$WATCH" 2>/dev/null
  rm -rf "$W"
}
trap cleanup EXIT
trap 'STOP=interrupted; [ -n "$UNIT" ] && kill_unit "$UNIT"' INT TERM HUP
rm -f "$OUT/cores.csv" "$OUT/cores.md" "$OUT/cores.svg" "$OUT/cores_tile.svg" "$OUT/runs.csv" "$OUT/calibrate.csv"
: > "$LOG"
# bench's own progress lines stay out of the log: this script says where it is.
TILESIM_PROGRESS_S=86400
export TILESIM_PROGRESS_S

# Time: seconds since the epoch, with a fraction where date has %N.
case $(date +%s.%N) in
  *N* | '') now() { date +%s; } ;;
  *) now() { date +%s.%N; } ;;
esac
if sleep 0.01 2>/dev/null; then FRAC=1; else FRAC=0; fi
calc() { awk "BEGIN { $1 }"; }
T0=$(now)
# Measuring ends RESERVE s before the budget: the files are written in that time.
RESERVE=2
[ "$BUDGET" -lt 20 ] && RESERVE=1
END=$(calc "printf \"%.3f\", $T0 + $BUDGET - $RESERVE")
elapsed() { calc "printf \"%.0f\", $(now) - $T0"; }
say() {
  line="$NAME: [$(elapsed) s of $BUDGET] $*"
  echo "$line" >&2
  echo "$line" >> "$LOG"
}

# The children of a process (bench --jobs forks its workers), from /proc:
# the fourth field of /proc/PID/stat, after the command's name in brackets.
children() {
  want=$1
  for f in /proc/[0-9]*/stat; do
    { read -r line < "$f"; } 2>/dev/null || continue
    set -f
    # shellcheck disable=SC2086
    set -- ${line##*) }
    set +f
    [ "${2:-}" = "$want" ] || continue
    f=${f#/proc/}
    echo "${f%/stat}"
  done
}
kill_unit() {
  kids=$(children "$1")
  # shellcheck disable=SC2086
  kill -TERM "$1" $kids 2>/dev/null
}

# watch PID SECONDS MARK: stop PID after SECONDS (and leave MARK), unless it ends first.
watch() {
  r=$2
  while kill -0 "$1" 2>/dev/null; do
    if calc "exit !($r <= 0)"; then
      : > "$3"
      kill_unit "$1"
      sleep 1
      kill -KILL "$1" 2>/dev/null
      exit 0
    fi
    if [ $FRAC = 1 ]; then s=$(calc "print ($r > 1) ? 1 : $r"); else s=1; fi
    sleep "$s"
    r=$(calc "print $r - $s")
  done
}

# step LABEL ESTIMATE OUTFILE COMMAND...: run COMMAND (stdout to OUTFILE,
# stderr kept in $W/err) unless the budget is spent or ESTIMATE (seconds; 0:
# unknown) exceeds what is left; stop it at the budget.  0 done, 1 failed,
# 3 stopped (budget or interrupt), 4 skipped.  DUR: how long it took.
step() {
  label=$1 est=$2 out=$3
  shift 3
  [ -n "$STOP" ] && return 3
  left=$(calc "printf \"%.3f\", $END - $(now)")
  if calc "exit !($left <= 0)"; then
    STOP=budget
    say "the budget is spent: stopping before $label"
    return 3
  fi
  if calc "exit !($est > $left)"; then
    say "skipped $label: it took $est s last time, $left s are left"
    SKIPS="$SKIPS$label; "
    return 4
  fi
  rm -f "$W/killed"
  t0=$(now)
  "$@" > "$out" 2> "$W/err" &
  UNIT=$!
  watch "$UNIT" "$left" "$W/killed" &
  WATCH=$!
  rc=0
  { wait "$UNIT"; } 2>/dev/null || rc=$?   # (no "Terminated" from the shell)
  while kill -0 "$UNIT" 2>/dev/null; do rc=0; { wait "$UNIT"; } 2>/dev/null || rc=$?; done   # a trap interrupted wait
  kill "$WATCH" 2>/dev/null
  wait "$WATCH" 2>/dev/null
  UNIT='' WATCH=''
  DUR=$(calc "printf \"%.1f\", $(now) - $t0")
  if [ -f "$W/killed" ]; then
    STOP=budget
    say "$label: stopped at the budget after $DUR s (what it measured is lost)"
    return 3
  fi
  if [ -n "$STOP" ]; then
    say "$label: interrupted after $DUR s"
    return 3
  fi
  if [ $rc -ne 0 ]; then
    STOP=failed
    FAIL="$label failed (exit status $rc): $(head -n 3 "$W/err" | tr '\n' ' ')"
    say "$FAIL"
    return 1
  fi
  say "$label: $DUR s"
  return 0
}

# The P and N lists: coarse (1, 2, 2^k + 1, the largest) and fine (the rest).
lists() {   # lists MAX KIND -> "coarse fine", comma-separated, '-' for none
  awk -v m="$1" -v kind="$2" 'BEGIN {
    c[1] = 1; if (m >= 2) c[2] = 1; c[m] = 1
    for (k = 2; k < m; k *= 2) c[kind == "P" ? k + 1 : k] = 1
    for (i = 1; i <= m; i++) if (i in c) co = co (co == "" ? "" : ",") i; else fi = fi (fi == "" ? "" : ",") i
    print co, (fi == "" ? "-" : fi) }'
}
rev() { echo "$1" | awk -F, '{ for (i = NF; i >= 1; i--) printf "%s%s", $i, (i > 1 ? "," : "\n") }'; }
# shellcheck disable=SC2046
set -- $(lists "$PMAX" P)
P_COARSE=$1 P_FINE=$2
# shellcheck disable=SC2046
set -- $(lists "$CORES" N)
N_COARSE=$1 N_FINE=$2
P_ALL=$(awk -v m="$PMAX" 'BEGIN { for (i = 1; i <= m; i++) printf "%s%d", (i > 1 ? "," : ""), i; print "" }')
N_ALL=$(awk -v m="$CORES" 'BEGIN { for (i = 1; i <= m; i++) printf "%s%d", (i > 1 ? "," : ""), i; print "" }')
VARIANTS_REV=$(rev "$VARIANTS")
SIZES=$(echo "$POINTS" | tr , ' ')
SIZES_UP=$(echo "$POINTS" | tr , '\n' | sort -n -u | tr '\n' , | sed 's/,$//')
SKIPS=

# The host, before anything runs.
model=$(awk -F': *' '/^model name/ { print $2; exit }' /proc/cpuinfo 2>/dev/null)
[ -n "$model" ] || model=$(awk -F': *' '/^(Hardware|cpu model|Processor)/ { print $2; exit }' /proc/cpuinfo 2>/dev/null)
[ -n "$model" ] || model="$(uname -m) (no model name in /proc/cpuinfo)"
mem=$(awk '/^MemTotal:/ { printf "%.1f GiB", $2 / 1048576; exit }' /proc/meminfo 2>/dev/null)
[ -n "$mem" ] || mem=unknown
cc=$( ("${CC:-cc}" --version) 2>/dev/null | head -n 1)
[ -n "$cc" ] || cc="${CC:-cc} (no --version)"
if [ -n "${COMMIT:-}" ]; then
  commit=$COMMIT
elif command -v git >/dev/null 2>&1 && git rev-parse --git-dir >/dev/null 2>&1; then
  commit=$(git rev-parse --short=12 HEAD 2>/dev/null)
  [ -n "$(git status --porcelain --untracked-files=no 2>/dev/null | head -n 1)" ] && commit="$commit (and changes not committed)"
elif [ -f .git/HEAD ]; then
  ref=$(sed -n 's/^ref: //p' .git/HEAD)
  if [ -z "$ref" ]; then commit=$(head -c 12 .git/HEAD)
  elif [ -f ".git/$ref" ]; then commit=$(head -c 12 ".git/$ref")
  else commit=$(awk -v r="$ref" '$2 == r { print substr($1, 1, 12) }' .git/packed-refs 2>/dev/null)
  fi
  commit="${commit:-unknown} (read from .git; changes not checked)"
else
  commit="unknown (no .git here; COMMIT=... names it)"
fi
{
  echo "cores|$CORES$([ "$CORES" != "$detected" ] && echo " (CORES; this process may run on $detected)")"
  echo "model|$model"
  echo "memory|$mem"
  echo "system|$(uname -sr 2>/dev/null) $(uname -m 2>/dev/null)"
  echo "compiler|$cc${CFLAGS:+, CFLAGS $CFLAGS}"
  echo "commit|$commit"
  echo "date|$(date -u '+%Y-%m-%d %H:%M UTC')"
  echo "load|$(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null) (1, 5, 15 min, before the run)"
} > "$W/host"
say "host: $CORES cores, $model, $mem; $cc; commit $commit"
say "plan: P = 1..$PMAX (coarse $P_COARSE first), N = 1..$CORES, $POINTS points, $VARIANTS; $REPEAT passes"
if awk -v c="$CORES" '{ exit !($1 > 0.25 * c) }' /proc/loadavg 2>/dev/null; then
  say "the machine is busy (load $(cut -d' ' -f1 /proc/loadavg) on $CORES cores): other programs slow and scatter the figures"
fi

: > "$W/runs"
: > "$W/pred"
: > "$W/stackinfo"
# threads PASS SIZE PLIST VLIST: one pass of the threads backend.
threads() {
  est=0
  [ "$1" -gt 1 ] && eval "est=\${EST_T$2:-0}"
  step "pass $1: threads, $2 points, P = $3" "$est" "$W/unit" \
    "$BIN/bench" --points "$2" --procs "$3" --backend threads --repeat 1 --variant "$4" || return $?
  awk -F, -v pass="$1" 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
    { print "threads|" $c["variant"] "|" $c["points"] "|" $c["procs"] "|" pass "|" $c["sim_time"] "|" $c["cost"] }' \
    "$W/unit" >> "$W/runs"
  [ "$1" -gt 1 ] && eval "EST_T$2=\$DUR"
  return 0
}
# stacks PASS NLIST: one pass of the stack surface on every stack.
stacks() {
  est=0
  [ "$1" -gt 1 ] && est=${EST_S:-0}
  st_pass=$1 st_nl=$2
  IFS='|'
  set -f
  # shellcheck disable=SC2086
  set -- $STACKS
  set +f
  IFS=$oldifs
  step "pass $st_pass: ./tile's stacks, N = $st_nl" "$est" "$W/unit" \
    "$BIN/bench" --stack "$@" -j "$st_nl" --repeat 1 || return $?
  awk -F, -v pass="$st_pass" -v info="$W/stackinfo" 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
    { print "tile||" $c["input"] "|" $c["threads"] "|" pass "|" $c["tile_ms"] / 1000 "|" $c["cost"] " " $c["volume"]
      print $c["input"] "|" $c["slices"] "|" $c["contours"] "|" $c["points"] "|" $c["bands"] >> info }' \
    "$W/unit" >> "$W/runs"
  [ "$st_pass" -gt 1 ] && EST_S=$DUR
  return 0
}

# 1-2. Pass 1, coarse then fine; the fine step's estimates start from pass 1.
for s in $SIZES; do threads 1 "$s" "$P_COARSE" "$VARIANTS" && eval "EST_T$s=\$DUR"; done
stacks 1 "$N_COARSE" && EST_S=$DUR
for s in $SIZES; do
  [ "$P_FINE" = - ] && break
  if threads 1 "$s" "1,$P_FINE" "$VARIANTS_REV"; then
    eval "e=\${EST_T$s:-0}"
    e=$(calc "print $e + $DUR")
    eval "EST_T$s=\$e"
  fi
done
[ "$N_FINE" != - ] && stacks 1 "$N_FINE" && EST_S=$(calc "print ${EST_S:-0} + $DUR")

# 3. The calibration, and the simulator's prediction for every P.
if step "calibration (bench --calibrate --options-only, $SIZES_UP points)" 0 "$W/cal" \
  "$BIN/bench" --calibrate --points "$SIZES_UP" --procs "1..$PMAX" --repeat "$CAL_REPEAT" \
  --messages "$MESSAGES" --options-only; then
  mv "$W/cal" "$OUT/calibrate.csv"
  grep -e '^bench:' -e '^    --' "$W/err" >> "$LOG"
  # One simulator run per size and group of P with the same options.
  awk -F, 'NR > 1 { k = $1 "|" $6; if (!(k in g)) o[++n] = k; g[k] = g[k] (g[k] == "" ? "" : ",") $2 }
    END { for (i = 1; i <= n; i++) { split(o[i], a, "|"); print a[1] "|" g[o[i]] "|" a[2] } }' \
    "$OUT/calibrate.csv" > "$W/groups"
  jobs=$CORES
  [ "$jobs" -gt 256 ] && jobs=256
  while IFS='|' read -r pts pl opts; do
    # shellcheck disable=SC2086
    step "predictions: the simulator, $pts points, P = $pl" 0 "$W/unit" \
      "$BIN/bench" --points "$pts" --procs "$pl" $opts --variant "$VARIANTS" --jobs "$jobs" || break
    awk -F, -v pl=",$pl," 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
      index(pl, "," $c["procs"] ",") { print $c["variant"] "|" $c["points"] "|" $c["procs"] "|" $c["sim_time"] }' \
      "$W/unit" >> "$W/pred"
  done < "$W/groups"
fi

# 4. Passes 2 .. REPEAT, every other one backwards.
pass=2
while [ $pass -le "$REPEAT" ] && [ -z "$STOP" ]; do
  pl=$P_ALL nl=$N_ALL vl=$VARIANTS
  [ $((pass % 2)) -eq 0 ] && pl=$(rev "$P_ALL") nl=$(rev "$N_ALL") vl=$VARIANTS_REV
  for s in $SIZES; do threads $pass "$s" "$pl" "$vl"; done
  stacks $pass "$nl"
  pass=$((pass + 1))
done
passes=$((pass - 1))
[ -z "$STOP" ] && STOP='done'

# ---- The files -----------------------------------------------------------------
total=$(elapsed)
case $STOP in
  done) how="complete: $REPEAT passes in $total s" ;;
  budget) how="stopped at the budget after $total s, in pass $passes of $REPEAT" ;;
  interrupted) how="interrupted after $total s, in pass $passes of $REPEAT" ;;
  *) how="stopped after $total s, in pass $passes of $REPEAT, by a failure: $FAIL" ;;
esac
[ -n "$SKIPS" ] && how="$how; skipped for the budget: $SKIPS"
say "writing $OUT: $how"

# runs.csv: every measurement.
{
  echo "what,variant,input,procs,pass,time_s,checksum"
  awk -F'|' '{ in3 = $3; if (in3 ~ /[",]/) { gsub(/"/, "\"\"", in3); in3 = "\"" in3 "\"" }
    print $1 "," $2 "," in3 "," $4 "," $5 "," $6 "," $7 }' "$W/runs"
} > "$W/runs.csv" && mv "$W/runs.csv" "$OUT/runs.csv"

# cores.csv, the plots' CSV and the Markdown tables, in one awk program.
CMD="make bench-cores BUDGET=$BUDGET OUT=$OUT"
awk -F'|' -v variants="$VARIANTS" -v sizes="$SIZES_UP" -v stacks="$STACKS" -v pmax="$PMAX" -v nmax="$CORES" \
  -v out="$W" -v cmd="$CMD" -v how="$how" -v budget="$BUDGET" -v total="$total" -v load_end="$(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null)" '
  function qcsv(s) { if (s ~ /[",]/) { gsub(/"/, "\"\"", s); s = "\"" s "\"" } return s }
  function short(s,  t) { t = s; if (t ~ /\.dcm:/) sub(/.*\.dcm:/, "", t); else { sub(/.*\//, "", t); sub(/\.contours$/, "", t) } return t }
  function median(list,  n, a, i, j, x) {
    n = split(list, a, " ")
    for (i = 2; i <= n; i++) { x = a[i] + 0; for (j = i - 1; j >= 1 && a[j] + 0 > x; j--) a[j + 1] = a[j]; a[j + 1] = x }
    return n % 2 ? a[(n + 1) / 2] : (a[n / 2] + a[n / 2 + 1]) / 2
  }
  function ms(t) { return t == "" ? "" : sprintf(t < 0.1 ? "%.2f ms" : "%.1f ms", t * 1000) }
  FILENAME == out "/host" { host[++nh] = $0; next }
  FILENAME == out "/stackinfo" { info[$1] = $2 " slices, " $3 " contours, " $4 " points, " $5 " bands"; next }
  FILENAME == out "/pred" { pred[$1 "|" $2 "|" $3] = $4; next }
  {   # a run: what|variant|input|procs|pass|time|checksum
    k = $1 "|" $2 "|" $3 "|" $4
    if (!(k in best) || $6 + 0 < best[k] + 0) best[k] = $6
    all[k] = all[k] " " $6; runs[k]++
    ck = ($1 == "threads" ? $3 : $1 "|" $3)   # one optimum per size, whatever the variant; per stack
    if (!(ck in sum)) sum[ck] = $7
    else if (sum[ck] != $7) { bad = bad "\n- " ($1 == "threads" ? $3 " points" : $3) ": " $7 " against " sum[ck] " (pass " $5 ", P/N = " $4 ")" }
  }
  END {
    nv = split(variants, V, ","); ns = split(sizes, S, ","); nst = split(stacks, ST, "|")
    csv = out "/cores.csv"; pc = out "/plot.csv"; tc = out "/tile.csv"; md = out "/cores.md"
    print "what,variant,input,procs,runs,measured_s,measured_speedup,predicted_s,predicted_speedup,error,median_s,checksum" > csv
    print "variant,procs,measured,predicted" > pc
    print "stack,threads,speedup" > tc
    for (v = 1; v <= nv; v++)
      for (s = 1; s <= ns; s++)
        for (p = 1; p <= pmax; p++) {
          k = "threads|" V[v] "|" S[s] "|" p; k1 = "threads|" V[v] "|" S[s] "|1"
          pk = V[v] "|" S[s] "|" p; pk1 = V[v] "|" S[s] "|1"
          if (!(k in best)) { miss[V[v] " at " S[s] " points"] = miss[V[v] " at " S[s] " points"] " " p; continue }
          m = best[k]; sp = (k1 in best) ? sprintf("%.3f", best[k1] / m) : ""
          pr = (pk in pred) ? pred[pk] : ""; psp = (pr != "" && pk1 in pred) ? sprintf("%.3f", pred[pk1] / pr) : ""
          e = pr != "" ? sprintf("%+.4f", pr / m - 1) : ""
          printf "threads,%s,%s,%d,%d,%.6f,%s,%s,%s,%s,%.6f,%s\n", V[v], S[s], p, runs[k], m, sp,
            pr == "" ? "" : sprintf("%.6f", pr), psp, e, median(all[k]), sum[S[s]] > csv
          printf "%s %s,%d,%s,%s\n", V[v], S[s], p, sp == "" ? "nan" : sp, psp == "" ? "nan" : psp > pc
          hasv[V[v]] = 1; T[k] = ms(m); TS[k] = sp; TP[k] = psp; TPT[k] = ms(pr); TE[k] = e == "" ? "" : sprintf("%+.1f%%", 100 * e)
          if (pr != "") { ne[V[v] "|" S[s]]++; ev = pr / m - 1; if (ev < 0.1 && ev > -0.1) n10[V[v] "|" S[s]]++ }
          if (runs[k] < minruns || minruns == "") minruns = runs[k]
          if (runs[k] > maxruns) maxruns = runs[k]
        }
    for (t = 1; t <= nst; t++)
      for (n = 1; n <= nmax; n++) {
        k = "tile||" ST[t] "|" n; k1 = "tile||" ST[t] "|1"
        if (!(k in best)) { miss["./tile " short(ST[t])] = miss["./tile " short(ST[t])] " " n; continue }
        m = best[k]; sp = (k1 in best) ? sprintf("%.3f", best[k1] / m) : ""
        split(sum["tile|" ST[t]], cs, " ")
        printf "tile,,%s,%d,%d,%.6f,%s,,,,%.6f,%s\n", qcsv(ST[t]), n, runs[k], m, sp, median(all[k]), cs[1] > csv
        printf "%s,%d,%s\n", short(ST[t]), n, sp == "" ? "nan" : sp > tc
        hast = 1; T[k] = ms(m); TS[k] = sp
        if (runs[k] < minruns || minruns == "") minruns = runs[k]
        if (runs[k] > maxruns) maxruns = runs[k]
      }
    for (n = 1; n <= nmax; n++) printf "ideal,%d,%d\n", n, n > tc

    # The Markdown.
    for (i = 1; i <= nh; i++) { split(host[i], h, "|"); H[h[1]] = substr(host[i], length(h[1]) + 2) }
    print "## Cores: " H["cores"] " cores, " H["model"] > md
    print "" > md
    print "Measured by `" cmd "` (tests/bench_cores.sh) on " H["date"] ": " how "." > md
    print "" > md
    print "- host: " H["cores"] " cores, " H["model"] ", " H["memory"] ", " H["system"] > md
    print "- compiler: " H["compiler"] > md
    print "- commit: " H["commit"] > md
    print "- load: " H["load"] "; " load_end " after it" > md
    split(H["load"], L, " "); if (L[1] > 0.25 * nmax) print "- **the machine was busy** before the run (a load above a quarter of its cores): other programs slowed and scattered these figures" > md
    if (maxruns) print "- each time the fastest of " (minruns == maxruns ? minruns : minruns " to " maxruns) " run" (maxruns > 1 ? "s" : "") " (the runs column of cores.csv; every run in runs.csv)" > md
    if (bad != "") print "- **the optima disagree** (a wrong answer somewhere):" bad > md
    print "" > md
    print "### The threads backend: T(1)/T(P), measured and predicted" > md
    print "" > md
    print "`./bench --points N --procs P --backend threads --variant V`, the generated pair (seed 1993); P counts the master" > md
    print "(P - 1 slaves).  Predicted: the simulator with the options `bench --calibrate` printed for this host (below);" > md
    print "error = predicted / measured - 1." > md
    for (v = 1; v <= nv; v++) {
      print "" > md
      print "**" V[v] "**" > md
      print "" > md
      if (!(V[v] in hasv)) { print "Not measured (the run ended first)." > md; continue }
      line = "| P |"; sep = "|---|"
      for (s = 1; s <= ns; s++) { line = line " " S[s] ": measured | speedup | predicted | speedup | error |"; sep = sep "---|---|---|---|---|" }
      print line > md; print sep > md
      for (p = 1; p <= pmax; p++) {
        line = "| " p " |"; any = 0
        for (s = 1; s <= ns; s++) {
          k = "threads|" V[v] "|" S[s] "|" p
          if (k in T) any = 1
          line = line " " T[k] " | " TS[k] " | " TPT[k] " | " TP[k] " | " TE[k] " |"
        }
        if (any) print line > md
      }
      w = ""
      for (s = 1; s <= ns; s++) if (ne[V[v] "|" S[s]]) w = w (w == "" ? "" : "; ") S[s] " points: " n10[V[v] "|" S[s]] + 0 " of " ne[V[v] "|" S[s]]
      if (w != "") { print "" > md; print "Predicted within 10%: " w "." > md }
    }
    print "" > md
    print "### ./tile -j N: whole stacks" > md
    print "" > md
    print "`./bench --stack STACK -j N`: the surface as `./tile STACK --caps -j N` makes it, from the stack in memory." > md
    print "" > md
    if (!hast) print "Not measured (the run ended first)." > md
    else {
      line = "| N |"; sep = "|---|"
      for (t = 1; t <= nst; t++) { line = line " " short(ST[t]) " | speedup |"; sep = sep "---|---|" }
      print line > md; print sep > md
      for (n = 1; n <= nmax; n++) {
        line = "| " n " |"; any = 0
        for (t = 1; t <= nst; t++) { k = "tile||" ST[t] "|" n; if (k in T) any = 1; line = line " " T[k] " | " TS[k] " |" }
        if (any) print line > md
      }
    }
    print "" > md
    for (t = 1; t <= nst; t++) print "- " short(ST[t]) ": " ST[t] (ST[t] in info ? " (" info[ST[t]] ")" : " (not measured)") > md
    nm = 0
    for (x in miss) nm++
    if (nm) {
      print "" > md
      print "### Not measured (the run ended first)" > md
      print "" > md
      for (v = 1; v <= nv; v++) for (s = 1; s <= ns; s++) { x = V[v] " at " S[s] " points"; if (x in miss) print "- " x ": P =" miss[x] > md }
      for (t = 1; t <= nst; t++) { x = "./tile " short(ST[t]); if (x in miss) print "- " x ": N =" miss[x] > md }
    }
    exit bad != ""
  }' "$W/host" "$W/stackinfo" "$W/pred" "$W/runs"
sums=$?

# The calibration, under the tables.
{
  echo
  echo "### The calibration"
  echo
  if [ -f "$OUT/calibrate.csv" ]; then
    echo "\`./bench --calibrate --points $SIZES_UP --procs 1..$PMAX --repeat $CAL_REPEAT --messages $MESSAGES --options-only\`"
    echo "(calibrate.csv: the options for every size and P); what its micro-benchmarks measured:"
    echo
    echo '```'
    grep -e '^bench:' -e '^    --' "$LOG"
    echo '```'
  else
    echo "Not measured (the run ended first): no predictions."
  fi
} >> "$W/cores.md"

# The pictures.
pl_ok=1
if awk -F, 'NR > 1 && $4 != "nan" { f = 1 } END { exit !f }' "$W/plot.csv"; then ys=measured,predicted labels="measured,predicted"
else ys=measured labels=measured; fi
"$PLOT" lines "$W/plot.csv" -x procs -y "$ys" --series variant --labels "$labels" --yzero \
  --title "Threads backend, $(echo "$SIZES_UP" | sed "s/,/ and /g") points: T(1)/T(P) measured, and predicted (dashed)" \
  --xlabel "processors P (P - 1 slaves)" --ylabel "speedup T(1)/T(P)" -o "$W/cores.svg" 2>> "$LOG" || pl_ok=0
"$PLOT" lines "$W/tile.csv" -x threads -y speedup --series stack --yzero \
  --title "./tile -j N: whole stacks, speedup against one thread" \
  --xlabel "threads N" --ylabel "speedup T(1)/T(N)" -o "$W/cores_tile.svg" 2>> "$LOG" || pl_ok=0
[ $pl_ok = 1 ] || { STOP=failed; FAIL="$FAIL build/plot failed (bench-cores.log)"; }
for f in cores.csv cores.md cores.svg cores_tile.svg; do [ -f "$W/$f" ] && mv "$W/$f" "$OUT/$f"; done
say "done: $OUT/cores.md, cores.csv, cores.svg, cores_tile.svg, runs.csv$([ -f "$OUT/calibrate.csv" ] && echo ", calibrate.csv") ($how)"
if [ $sums -ne 0 ]; then say "the optima disagree: see $OUT/cores.md"; exit 1; fi
case $STOP in
  failed) exit 1 ;;
  interrupted) exit 130 ;;
esac
exit 0

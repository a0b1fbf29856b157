#!/bin/sh
# bench_mpi.sh -- make bench-mpi: MPI programs under tilesim-mpirun and, in
# the same run, under SimGrid's smpirun where it is installed: the host's
# time and peak memory against the message size and the ranks.
#
#   make bench-mpi [OUT=DIR]            (or OUT=.. sh tests/bench_mpi.sh)
#
# The programs (tests/mpirun/, written for this benchmark; none of the OSU
# suite's code), each printing a checksum of its results and its simulated
# time, which the table sets side by side:
#   bw         an osu_bw-like window: WINDOW nonblocking sends of each size of
#              BW_SIZES from rank 0 to rank 1, BW_ITERS times (2 ranks)
#   alltoall   MPI_Alltoall of each size of A2A_SIZES a pair, A2A_ITERS times,
#              on A2A_RANKS ranks (pairwise exchange on both simulators)
#   bcast      MPI_Bcast of each size of BC_SIZES from rank 0, BC_ITERS times,
#              on BC_RANKS ranks (scatter and ring allgather on both)
#   ring       a token of 8 bytes round RING_RANKS ranks, RING_LAPS laps
#   startup    MPI_Init, an allreduce of one integer, MPI_Finalize, on each
#              number of RANKS (the whole run is the start-up)
#   allreduce  AR_ITERS allreduces of AR_COUNT integers on each number of
#              RANKS (recursive doubling on both simulators)
#   mp-ring    examples/ring.c (mp.h, no MPI) on MP_RANKS ranks, one lap
# The same costs on both: every message 2^-12 s whatever its size (tilesim
# --net ideal --m 2^-12 --per-byte 0; SimGrid's Constant network model with
# that latency, one host per rank, computing not simulated), so the simulated
# times must agree where the algorithms do.  smpirun runs only up to
# SMPI_RANKS ranks: its start-up grows about as the square of the ranks
# (here 4.3 s for 1000 ranks, 52 s for 3000).
#
# Settings (environment):
#   OUT        the output folder (build/bench-mpi): bench-mpi.csv (a row per
#              run), bench-mpi.md (the tables), bench-mpi-size.svg and
#              bench-mpi-size-rss.svg (time and peak memory against the
#              message size), bench-mpi-ranks.svg and bench-mpi-ranks-rss.svg
#              (against the ranks), bench-mpi.log (the progress)
#   BW_SIZES (1024,65536,1048576,4194304)  WINDOW (64)  BW_ITERS (10)
#   A2A_SIZES (1024,16384,262144)  A2A_RANKS (16)  A2A_ITERS (10)
#   BC_SIZES (16777216)  BC_RANKS (16)  BC_ITERS (3)
#   RING_RANKS (16)  RING_LAPS (62500)
#   RANKS (1000,10000,100000)  AR_COUNT (256)  AR_ITERS (4)
#   MP_RANKS (1000000; 0: none)  SMPI_RANKS (1000)  SMPI (auto, or no)
#   ROUNDS (1) each run this many times, tilesim-mpirun and smpirun taking
#              turns: the CSV has a row per run, the table and the pictures
#              the median of each one's wall time and of its peak (the host's
#              own noise, page faults above all, moves single runs a lot)
#   TIMEOUT    seconds a run may take before it is stopped and marked so (900)
#   BIN, PLOT, EXAMPLES   where tilesim-mpirun and tilesim-mpicc are (.), the
#              plotter (build/plot), examples/ring (build/examples)
# A run that fails or is stopped is a row with its status, and the benchmark
# goes on; the exit status is 1 if any checksum is wrong or the two
# simulators' checksums differ, 2 for bad usage, else 0.  Progress goes to
# stderr (and the log).  A benchmark: it asserts nothing about time.
set -u
LC_ALL=C
export LC_ALL
NAME=bench-mpi
USAGE="usage: make bench-mpi [OUT=DIR]   (settings in the environment: tests/bench_mpi.sh says which)"
usage() { echo "$NAME: $*" >&2; echo "$USAGE" >&2; exit 2; }
die() { echo "$NAME: $*" >&2; exit 1; }
list() {   # list NAME VALUE MIN MAX: comma-separated whole numbers in [MIN, MAX]
  case $2 in '' | ,* | *, | *,,* | *[!0-9,]*) usage "$1 takes whole numbers separated by commas ($2)" ;; esac
  for v in $(echo "$2" | tr , ' '); do
    [ ${#v} -le 9 ] && [ "$v" -ge "$3" ] && [ "$v" -le "$4" ] || usage "$1 takes whole numbers from $3 to $4 ($2)"
  done
}

[ $# -eq 0 ] || usage "the settings go in the environment, not as arguments ($1)"
OUT=${OUT-build/bench-mpi}
BW_SIZES=${BW_SIZES:-1024,65536,1048576,4194304}
WINDOW=${WINDOW:-64}
BW_ITERS=${BW_ITERS:-10}
A2A_SIZES=${A2A_SIZES:-1024,16384,262144}
A2A_RANKS=${A2A_RANKS:-16}
A2A_ITERS=${A2A_ITERS:-10}
BC_SIZES=${BC_SIZES:-16777216}
BC_RANKS=${BC_RANKS:-16}
BC_ITERS=${BC_ITERS:-3}
RING_RANKS=${RING_RANKS:-16}
RING_LAPS=${RING_LAPS:-62500}
RANKS=${RANKS:-1000,10000,100000}
AR_COUNT=${AR_COUNT:-256}
AR_ITERS=${AR_ITERS:-4}
MP_RANKS=${MP_RANKS:-1000000}
SMPI_RANKS=${SMPI_RANKS:-1000}
SMPI=${SMPI:-auto}
ROUNDS=${ROUNDS:-1}
TIMEOUT=${TIMEOUT:-900}
BIN=${BIN:-.}
PLOT=${PLOT:-build/plot}
EXAMPLES=${EXAMPLES:-build/examples}
list BW_SIZES "$BW_SIZES" 16 1073741824
list WINDOW "$WINDOW" 1 4096
list BW_ITERS "$BW_ITERS" 1 1000000
list A2A_SIZES "$A2A_SIZES" 16 67108864
list A2A_RANKS "$A2A_RANKS" 2 4096
list A2A_ITERS "$A2A_ITERS" 1 1000000
list BC_SIZES "$BC_SIZES" 32 1073741824
list BC_RANKS "$BC_RANKS" 2 4096
list BC_ITERS "$BC_ITERS" 1 1000000
list RING_RANKS "$RING_RANKS" 2 1000000
list RING_LAPS "$RING_LAPS" 1 100000000
list RANKS "$RANKS" 2 1000000
list AR_COUNT "$AR_COUNT" 1 100000000
list AR_ITERS "$AR_ITERS" 1 1000000
list MP_RANKS "$MP_RANKS" 0 1000000
list SMPI_RANKS "$SMPI_RANKS" 0 1000000
list TIMEOUT "$TIMEOUT" 1 86400
list ROUNDS "$ROUNDS" 1 1000
case $SMPI in auto | no) ;; *) usage "SMPI takes auto or no ($SMPI)" ;; esac
[ -n "$OUT" ] || usage "OUT names the output folder, and is empty"
[ -f tests/bench_mpi.sh ] || die "run from the source tree's root (make bench-mpi does)"
for t in tilesim-mpirun tilesim-mpicc; do [ -x "$BIN/$t" ] || die "$BIN/$t is not built (make bench-mpi builds it)"; done
[ -x "$PLOT" ] || die "$PLOT is not built (make builds it)"
[ "$MP_RANKS" -eq 0 ] || [ -x "$EXAMPLES/ring" ] || die "$EXAMPLES/ring is not built (make builds it)"
if [ -e "$OUT" ] && [ ! -d "$OUT" ]; then usage "OUT: $OUT exists and is not a folder"; fi
mkdir -p "$OUT" 2> /dev/null && [ -d "$OUT" ] || die "OUT: cannot create the folder $OUT"
W=$OUT/.bench-mpi.$$
mkdir "$W" 2> /dev/null || die "OUT: cannot write in $OUT"
trap 'rm -rf "$W"' EXIT
trap 'exit 130' INT TERM HUP
LOG=$OUT/bench-mpi.log
: > "$LOG"
TILESIM_PROGRESS_S=86400   # the runs' own progress lines stay out: this script says where it is
export TILESIM_PROGRESS_S

case $(date +%s.%N) in *N* | '') now() { date +%s; } ;; *) now() { date +%s.%N; } ;; esac
T0=$(now)
say() {
  line="$NAME: [$(awk -v a="$T0" -v b="$(now)" 'BEGIN { printf "%.0f", b - a }') s] $*"
  echo "$line" >&2
  echo "$line" >> "$LOG"
}
TIMER=
[ -x /usr/bin/time ] && /usr/bin/time -f '%e %M' -o "$W/probe" true 2> /dev/null && TIMER=/usr/bin/time
TO=
command -v timeout > /dev/null 2>&1 && TO="timeout -s KILL $TIMEOUT"

# ---- the programs, built by both compilers ----------------------------------
PROGS="bw alltoall bcast ring allreduce"
for p in $PROGS; do
  "$BIN/tilesim-mpicc" -O2 "tests/mpirun/$p.c" -o "$W/$p" 2> "$W/cc.err" || die "tilesim-mpicc $p.c: $(head -n 3 "$W/cc.err")"
done
SG=
if [ "$SMPI" = auto ] && command -v smpicc > /dev/null 2>&1 && command -v smpirun > /dev/null 2>&1; then
  SG=yes
  for p in $PROGS; do smpicc -O2 "tests/mpirun/$p.c" -o "$W/$p.sg" > "$W/cc.err" 2>&1 || SG=; done
  [ -n "$SG" ] || say "smpicc cannot build the programs ($(head -n 1 "$W/cc.err")): tilesim alone"
fi
[ "$SMPI" = auto ] && [ -z "$SG" ] && ! command -v smpirun > /dev/null 2>&1 && say "smpirun is not installed: tilesim alone"

M=0.000244140625   # 2^-12 s a message
TSOPT="--net ideal --m $M --per-byte 0 --coll allreduce=recursive_doubling,alltoall=pairwise,bcast=scatter_ring_allgather"
SGOPT="--cfg=network/model:Constant --cfg=network/latency-factor:$M --cfg=smpi/simulate-computation:no
  --cfg=smpi/host-speed:1Gf --cfg=smpi/wtime:0 --cfg=smpi/test:0 --cfg=smpi/async-small-thresh:1000000000
  --cfg=smpi/send-is-detached-thresh:1000000000 --cfg=smpi/allreduce:rdb --cfg=smpi/alltoall:pair --cfg=smpi/bcast:scatter_LR_allgather
  --log=xbt_cfg.thres:warning --log=smpi_config.thres:warning --log=smpi.thres:warning"
# A platform of N hosts of 2^30 flop/s and no links (the Constant model), and its hostfile.
platform() {
  [ -f "$W/plat$1.xml" ] && return
  { echo "<?xml version='1.0'?>"
    echo '<!DOCTYPE platform SYSTEM "https://simgrid.org/simgrid.dtd">'
    echo '<platform version="4.1"><zone id="machine" routing="None">'
    awk -v n="$1" 'BEGIN { for (i = 0; i < n; i++) printf "<host id=\"h%d\" speed=\"1073741824f\"/>\n", i }'
    echo '</zone></platform>'; } > "$W/plat$1.xml"
  awk -v n="$1" 'BEGIN { for (i = 0; i < n; i++) print "h" i }' > "$W/hosts$1"
}

# ---- one run ---------------------------------------------------------------------
# run PROGRAM SIMULATOR RANKS BYTES COMMAND...: time it, keep its peak memory,
# read its checksum and simulated time, and append a row.
echo "program,simulator,ranks,bytes,wall_s,peak_rss_kb,sim_time,checksum,status" > "$W/rows"
run() {
  prog=$1 sim=$2 np=$3 bytes=$4
  shift 4
  t0=$(now)
  if [ -n "$TIMER" ]; then
    $TO $TIMER -f '%e %M' -o "$W/time" "$@" > "$W/out" 2> "$W/err"; rc=$?
  else
    $TO "$@" > "$W/out" 2> "$W/err"; rc=$?
  fi
  t1=$(now)
  wall=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.3f", b - a }')
  rss=
  [ -n "$TIMER" ] && [ -s "$W/time" ] && rss=$(awk 'END { print $2 }' "$W/time")
  # "checksum C, T s" (ring: "token C, T s"); examples/ring: "the token came
  # back every lap", then "T s a lap" (its checksum: the ranks the token
  # went through).
  line=$(grep -m 1 -e 'checksum' -e ': token ' -e ' s a lap' "$W/out")
  sum=$(printf '%s\n' "$line" | awk '{ for (i = 1; i < NF; i++) if ($i == "checksum" || $i == "token") { v = $(i + 1); sub(/,$/, "", v); print v; exit } }')
  st=$(printf '%s\n' "$line" | awk '{ for (i = 2; i <= NF; i++) if ($i == "s" || $i == "s,") { print $(i - 1); exit } }')
  grep -q 'the token came back every lap' "$W/out" && sum=$np
  if [ $rc -eq 0 ] && [ -n "$sum" ]; then status=ok
  elif [ $rc -eq 137 ] || [ $rc -eq 124 ]; then status="stopped after $TIMEOUT s"
  else status="failed ($rc): $(cat "$W/out" "$W/err" | grep -v '^$' | head -n 1 | tr -d '",' | cut -c 1-120)"
  fi
  echo "$prog,$sim,$np,$bytes,$wall,$rss,$st,$sum,\"$status\"" >> "$W/rows"
  say "$prog on $sim, $np ranks${bytes:+, $bytes bytes}: $wall s, ${rss:-?} KB peak, $status"
}
# both NAME PROGRAM RANKS BYTES ARGS...: under tilesim-mpirun, then smpirun.
both() {
  name=$1 exe=$2 np=$3 bytes=$4
  shift 4
  i=0
  while [ $i -lt "$ROUNDS" ]; do
    i=$((i + 1))
    # shellcheck disable=SC2086
    run "$name" tilesim "$np" "$bytes" "$BIN/tilesim-mpirun" -np "$np" $TSOPT "$W/$exe" "$@"
    [ -n "$SG" ] && [ "$np" -le "$SMPI_RANKS" ] || continue
    platform "$np"
    # shellcheck disable=SC2086
    run "$name" smpi "$np" "$bytes" smpirun -np "$np" -platform "$W/plat$np.xml" -hostfile "$W/hosts$np" $SGOPT "$W/$exe.sg" "$@"
  done
}

say "host: $(nproc 2> /dev/null || echo ?) cores, $(awk '/^MemTotal:/ { printf "%.1f GiB", $2 / 1048576 }' /proc/meminfo 2> /dev/null); load $(cut -d' ' -f1-3 /proc/loadavg 2> /dev/null)"
for s in $(echo "$BW_SIZES" | tr , ' '); do both bw bw 2 "$s" "$s" "$WINDOW" "$BW_ITERS"; done
for s in $(echo "$A2A_SIZES" | tr , ' '); do both alltoall alltoall "$A2A_RANKS" "$s" "$s" "$A2A_ITERS"; done
for s in $(echo "$BC_SIZES" | tr , ' '); do both bcast bcast "$BC_RANKS" "$s" "$s" "$BC_ITERS"; done
both ring ring "$RING_RANKS" 8 "$RING_LAPS" 8
for n in $(echo "$RANKS" | tr , ' '); do
  both startup allreduce "$n" 8 1 1
  both allreduce allreduce "$n" $((AR_COUNT * 8)) "$AR_COUNT" "$AR_ITERS"
done
[ "$MP_RANKS" -gt 0 ] && run mp-ring tilesim "$MP_RANKS" 8 "$EXAMPLES/ring" --ranks "$MP_RANKS" --procs 4096 --net ideal --m "$M" \
  --per-byte 0 --stats none -- 1 8
mv "$W/rows" "$OUT/bench-mpi.csv"
# A row per program, ranks, size and simulator: the median of its runs' wall
# times and of their peaks (ROUNDS), the first ok run's simulated time and
# checksum, and ok only if every run was (else the first failure's status).
awk -F, 'function median(list,   v, n, i, j, x) { n = split(list, v, " ")
      for (i = 2; i <= n; i++) { x = v[i] + 0; for (j = i - 1; j >= 1 && v[j] + 0 > x; j--) v[j + 1] = v[j]; v[j + 1] = x }
      return n % 2 ? v[(n + 1) / 2] : (v[n / 2] + v[n / 2 + 1]) / 2 }
  NR == 1 { print; next }
  { k = $1 "," $2 "," $3 "," $4; if (!(k in st)) { o[++n] = k; st[k] = $9; s[k] = $7; c[k] = $8 }
    else if (st[k] == "\"ok\"" && $9 != "\"ok\"") st[k] = $9
    if ($9 == "\"ok\"" && s[k] == "") s[k] = $7
    if ($9 == "\"ok\"" && c[k] == "") c[k] = $8
    w[k] = w[k] " " $5; if ($6 != "") r[k] = r[k] " " $6 }
  END { for (i = 1; i <= n; i++) { k = o[i]
      printf "%s,%.3f,%s,%s,%s,%s\n", k, median(w[k]), r[k] == "" ? "" : sprintf("%.0f", median(r[k])), s[k], c[k], st[k] } }' \
  "$OUT/bench-mpi.csv" > "$W/med.csv"

# ---- the tables ----------------------------------------------------------------
commit=$(git rev-parse --short=12 HEAD 2> /dev/null || echo unknown)
[ -n "$(git status --porcelain --untracked-files=no 2> /dev/null | head -n 1)" ] && commit="$commit (and changes not committed)"
{
  echo "## MPI programs on tilesim-mpirun$([ -n "$SG" ] && echo " and SimGrid's smpirun")"
  echo
  echo "Measured by \`make bench-mpi\` on $(date -u '+%Y-%m-%d %H:%M UTC'): $(nproc 2> /dev/null || echo ?) cores," \
    "$(awk '/^MemTotal:/ { printf "%.1f GiB", $2 / 1048576 }' /proc/meminfo 2> /dev/null), commit $commit;" \
    "$(smpirun --version 2> /dev/null | head -n 1 | sed 's/ *$//')."
  echo "Every message costs 2^-12 s on both; wall is the host's seconds for the whole run (start-up included)," \
    "peak the largest resident size$([ "$ROUNDS" -gt 1 ] && echo ", each the median of $ROUNDS runs (the two simulators taking turns)");" \
    "ratio = smpirun's / tilesim's."
  echo "bw: $WINDOW nonblocking sends of the size from rank 0 to rank 1, $BW_ITERS times;" \
    "alltoall: MPI_Alltoall of the size a pair, $A2A_ITERS times; bcast: MPI_Bcast of the size, $BC_ITERS times;" \
    "ring: a token of 8 bytes, $RING_LAPS laps;" \
    "startup: MPI_Init, an allreduce of one integer, MPI_Finalize; allreduce: $AR_ITERS of $AR_COUNT integers;" \
    "mp-ring: examples/ring.c (mp.h, no MPI), one lap.  A row that failed says why."
  echo
  awk -F, 'NR > 1 { k = $1 "," $3 "," $4; if (!(k in seen)) { seen[k] = 1; o[++n] = k }
      w[k, $2] = $5; r[k, $2] = $6; s[k, $2] = $7; c[k, $2] = $8; st[k, $2] = $9 }
    function mb(v) { return v == "" ? "?" : sprintf("%.0f MiB", v / 1024) }
    function cell(k, sim,   t) { if (!((k, sim) in w)) return "| | "; t = st[k, sim]; gsub(/"/, "", t)
      if (t != "ok") return "| " t " | "
      return "| " w[k, sim] " s | " mb(r[k, sim]) " " }
    END {
      print "| program | ranks | bytes | tilesim wall | tilesim peak | smpirun wall | smpirun peak | time ratio | memory ratio | simulated s (tilesim, smpirun) | checksums |"
      print "|---|---|---|---|---|---|---|---|---|---|---|"
      for (i = 1; i <= n; i++) {
        k = o[i]; split(k, a, ",")
        tr = ""; mr = ""; sims = s[k, "tilesim"]; cs = c[k, "tilesim"]
        if ((k, "smpi") in w && st[k, "smpi"] == "\"ok\"" && st[k, "tilesim"] == "\"ok\"") {
          tr = sprintf("%.2f", w[k, "smpi"] / w[k, "tilesim"])
          if (r[k, "smpi"] != "" && r[k, "tilesim"] != "") mr = sprintf("%.2f", r[k, "smpi"] / r[k, "tilesim"])
          sims = sims ", " s[k, "smpi"] (s[k, "smpi"] == s[k, "tilesim"] ? " (equal)" : " (differ)")
          cs = cs (c[k, "smpi"] == c[k, "tilesim"] ? " (equal)" : " DIFFER: " c[k, "smpi"])
        }
        printf "| %s | %s | %s %s%s| %s | %s | %s | %s |\n", a[1], a[2], a[3], cell(k, "tilesim"), cell(k, "smpi"), tr, mr, sims, cs
      }
    }' "$W/med.csv"
  echo
  echo "The settings: BW_SIZES=$BW_SIZES WINDOW=$WINDOW BW_ITERS=$BW_ITERS A2A_SIZES=$A2A_SIZES A2A_RANKS=$A2A_RANKS" \
    "A2A_ITERS=$A2A_ITERS BC_SIZES=$BC_SIZES BC_RANKS=$BC_RANKS BC_ITERS=$BC_ITERS RING_RANKS=$RING_RANKS RING_LAPS=$RING_LAPS RANKS=$RANKS AR_COUNT=$AR_COUNT AR_ITERS=$AR_ITERS" \
    "MP_RANKS=$MP_RANKS SMPI_RANKS=$SMPI_RANKS ROUNDS=$ROUNDS."
} > "$W/md" && mv "$W/md" "$OUT/bench-mpi.md"

# ---- the pictures: log2 of the size, log10 of the ranks -----------------------
awk -F, 'NR == 1 { print "program,simulator,log2_bytes,log10_ranks,wall_s,peak_rss_mib"; next }
  $9 == "\"ok\"" { printf "%s,%s,%.3f,%.3f,%s,%.1f\n", $1, $2, log($4) / log(2), log($3) / log(10), $5, $6 / 1024 }' \
  "$W/med.csv" > "$W/plot.csv"
pic() {   # pic FILE X Y XLABEL YLABEL TITLE WHERE...
  f=$1 x=$2 y=$3 xl=$4 yl=$5 ti=$6
  shift 6
  n=$(awk -F, -v want="$*" 'NR > 1 { split(want, w, " "); for (i in w) if (w[i] == $1) { print; break } }' "$W/plot.csv" | wc -l)
  [ "$n" -gt 0 ] || return 0
  awk -F, -v want="$*" 'NR == 1 { print; next } { split(want, w, " "); for (i in w) if (w[i] == $1) { print; break } }' \
    "$W/plot.csv" > "$W/pic.csv"
  "$PLOT" lines "$W/pic.csv" -x "$x" -y "$y" --series program,simulator --title "$ti" --xlabel "$xl" --ylabel "$yl" --yzero \
    -o "$OUT/$f" 2> "$W/plot.err" || say "$f: $(head -n 1 "$W/plot.err")"
}
pic bench-mpi-size.svg log2_bytes wall_s "log2 of the message size (bytes)" "host seconds" \
  "bw (2 ranks), alltoall and bcast: host time against the message size" bw alltoall bcast
pic bench-mpi-size-rss.svg log2_bytes peak_rss_mib "log2 of the message size (bytes)" "peak resident MiB" \
  "bw (2 ranks), alltoall and bcast: peak memory against the message size" bw alltoall bcast
pic bench-mpi-ranks.svg log10_ranks wall_s "log10 of the ranks" "host seconds" \
  "start-up, allreduce and the mp.h ring: host time against the ranks" startup allreduce mp-ring
pic bench-mpi-ranks-rss.svg log10_ranks peak_rss_mib "log10 of the ranks" "peak resident MiB" \
  "start-up, allreduce and the mp.h ring: peak memory against the ranks" startup allreduce mp-ring
say "wrote $OUT: bench-mpi.csv, bench-mpi.md and the pictures"

# A wrong checksum, or two simulators that disagree on one, fails the benchmark.
awk -F, 'NR > 1 && $9 == "\"ok\"" { k = $1 "," $3 "," $4; if ((k in c) && c[k] != $8) bad = 1; c[k] = $8 }
  END { exit bad }' "$OUT/bench-mpi.csv" || die "the simulators' checksums differ: $OUT/bench-mpi.md"
! grep -q 'wrong' "$OUT/bench-mpi.csv" || die "a program found a wrong result: $OUT/bench-mpi.csv"
exit 0

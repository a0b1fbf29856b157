#!/bin/sh
# cli_benchclean.sh -- make bench leaves a fresh clone clean:
# what it writes under plots/ holds no host time and is the same
# bytes on every run.  Checked here:
#   - every ./bench sweep of make bench's recipe that writes under plots/ or
#     build/ (make -n bench) passes --no-wall;
#   - the committed sweeps under plots/ have an empty wall_s column;
#   - the same commands, on reduced sizes (the sanitized build is slower),
#     run twice give the same bytes: the paper's sweep (--jobs 1 and 2),
#     a real pair, --model, --glass, a topology sweep, the variants, the
#     claims read back, and the plots drawn from them.
# (sh tests/bench_clean.sh runs the whole of make bench twice in a fresh
# clone and checks git status: the end-to-end check, a minute or two.)
BUILD=${BUILD:-build/chk}
case $BUILD in /*) ;; *) BUILD=$PWD/$BUILD ;; esac
DATA=$PWD/tests/data/slicerrt
. tests/clilib.sh

# The recipe: every paper-mode sweep with -o passes --no-wall.
env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make --no-print-directory -n bench 2>/dev/null |
  grep '^\./bench ' | grep -- ' -o ' | grep -v -- '--model\|--glass\|--claims' > "$T/sweeps"
[ -s "$T/sweeps" ] && ok || bad "make -n bench shows no ./bench sweep"
n=$(grep -vc -- '--no-wall' "$T/sweeps")
[ "$n" -eq 0 ] && ok || bad "$n sweeps of make bench keep this host's times: $(grep -v -- '--no-wall' "$T/sweeps")"

# The committed sweeps: no host time.
for f in plots/*.csv; do
  awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "wall_s") c = i; next } c && $c != "" { bad = 1 }
           END { exit bad }' "$f" && ok || bad "$f holds host times in wall_s"
done

# Twice, the same bytes.
cd "$T" || exit 1
B=$BUILD/bench P="$BUILD/plot lines"
run() {   # run DIR: the commands into DIR
  d=$1
  mkdir -p "$d"
  "$B" --points 40,60 --procs 1..16 --alloc half,size --jobs 2 --no-wall -o "$d/speedup.csv" &&
  "$B" --points 40,60 --procs 1..16 --alloc half,size --jobs 1 --no-wall -o "$d/speedup1.csv" &&
  "$B" --points 90 --procs 1..4 --alloc size --min-diag 20,40 --jobs 2 --no-wall -o "$d/min_diag.csv" &&
  "$B" --input "$DATA/prostate_3.contours" --pair 5 --procs 1..4 --alloc half,size --jobs 2 --no-wall -o "$d/real.csv" &&
  "$B" --model --diag 20,40 --procs 2..4 -o "$d/model.csv" &&
  "$B" --glass --slices 6 --points 16 -o "$d/glass.contours" &&
  "$B" --points 60 --procs 1..4 --jobs 2 --no-wall --topology line --place linear,random:1 \
       --hop-latency 1e-4 --switching store-and-forward -o "$d/topology.csv" &&
  "$B" --points 60 --procs 1..4 --variant paper,fit,block8,dynamic --jobs 2 --no-wall -o "$d/variants.csv" &&
  "$B" --claims "$d/speedup.csv" "$d/min_diag.csv" > "$d/claims.csv" &&
  $P "$d/speedup.csv" -x procs -y speedup --series points --where alloc=half --yzero --title t -o "$d/a.svg" &&
  $P "$d/topology.csv" -x procs -y speedup --series topology,place --yzero -o "$d/b.svg" &&
  "$BUILD/plot" surface "$d/glass.contours" --title g -o "$d/c.svg"
}
run one 2> err1 && ok || bad "the first run failed: $(cat err1)"
run two 2> err2 && ok || bad "the second run failed: $(cat err2)"
for f in one/*; do
  cmp -s "$f" "two/${f#one/}" && ok || bad "$f differs from run to run"
done
cmp -s one/speedup.csv one/speedup1.csv && ok || bad "--jobs 2 and --jobs 1 differ"
awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "wall_s") c = i; next } $c != "" { bad = 1 } END { exit !c || bad }' \
  one/speedup.csv && ok || bad "--no-wall left host times in wall_s"

summary

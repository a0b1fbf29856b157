#!/bin/sh
# cli_args.sh -- every option of every mode of every program, given bad
# values: empty, blanks, hexadecimal, negative, out of range, underflowing,
# too many list items, malformed ranges (5..1, 1,,2), unknown words.  Each
# must be refused as bad usage: exit status 2, nothing on stdout, no file
# written, and on stderr exactly two lines: "PROG: " and a message naming
# the option and what it accepts (the range), then the usage hint.
# Runs the sanitized build in $BUILD; every run in an empty folder.
BUILD=${BUILD:-build/chk}
case $BUILD in /*) ;; *) BUILD=$PWD/$BUILD ;; esac
DATA=$PWD/tests/data/slicerrt
. tests/clilib.sh
mkdir "$T/run"
cd "$T/run" || exit 1   # every run here: the files a bad run would write would show
printf 'points,procs,alloc,min_diag,sim_time\n' > "$T/sweep.csv"

# refused PROG WANT ARG;ARG;...  -- run PROG with the ';'-separated
# arguments (@E is the empty string) in the empty folder $T/run; WANT is what the
# first line of stderr must contain after "PROG: ".
refused() {
  prog=$1; want=$2; args=$3
  old=$IFS; IFS=';'; set -f
  # shellcheck disable=SC2086
  set -- $args
  IFS=$old; set +f
  n=$#; i=0
  while [ $i -lt $n ]; do   # rotate, turning @E into ""
    a=$1; shift; [ "$a" = @E ] && a=""; set -- "$@" "$a"; i=$((i + 1))
  done
  "$BUILD/$prog" "$@" > "$T/out" 2> "$T/err"; rc=$?
  name=${prog##*/}
  # builtins only, so that 700 cases stay quick: two lines on stderr, no file here
  l1=""; l2=""; three=0
  { IFS= read -r l1; IFS= read -r l2; IFS= read -r l3 && three=1; } < "$T/err"
  files=""
  for f in * .[!.]*; do [ -e "$f" ] && files="$files $f"; done
  if [ $rc -eq 2 ] && [ ! -s "$T/out" ] && [ -n "$l2" ] && [ $three -eq 0 ] && [ -z "$files" ] &&
     case $l1 in "$name: "*"$want"*) true ;; *) false ;; esac &&
     case $l2 in "usage: $name"*) true ;; *) false ;; esac; then ok
  else
    bad "$name $args: exit $rc, want 2 and '$name: ...$want...'; stdout $(wc -c < "$T/out") bytes, files:$files, stderr: $(cat "$T/err")"
    rm -rf ./* ./.[!.]* 2>/dev/null
  fi
}

# The bad values of each kind of option.
u64_bad="@E; 3;3 ;0x10;-1;abc;1.5;1e3;+1;18446744073709551616"
seconds_bad="@E; 3;3 ;0x10;1e-400;-1;nan;inf;abc;1.5e9;1e999;3s"
name_bad="@E;--x"
bytes_bad="@E;-1;1.5;0x10;1X;abc;1e3;18446744073709551616"
whole_bad() {   # LO HI
  lo=$1; hi=$2
  printf '%s' "@E; $lo;$lo ;0x10;1e3;1.5;abc;$((lo - 1));$((hi + 1));99999999999999999999999;+$lo"
}
list_bad() {   # LO HI MAX
  lo=$1; hi=$2; max=$3; many=$lo; k=1
  while [ $k -le "$max" ]; do many="$many,$lo"; k=$((k + 1)); done
  printf '%s' "@E;$lo,,$lo;$lo,;,$lo;$hi..$lo;$((lo - 1));$((hi + 1));$lo..x;0x10; $lo;$many;$lo...$hi"
}
reallist_bad="@E;0,,0;0,;1..2;1e-400;-1;abc;0x1;inf;2e9"
word_bad() { printf '%s' "@E;x; $1;$1 ;$1,$1;$(printf '%s' "$1" | tr a-z A-Z)"; }

# each PROG WANT PREFIX OPT VALUES [SUFFIX] -- every value of VALUES for OPT.
each() {
  prog=$1; want=$2; prefix=$3; opt=$4; values=$5; suffix=${6:-}
  old=$IFS; IFS=';'; set -f
  for v in $values; do
    IFS=$old
    refused "$prog" "$want" "${prefix:+$prefix;}$opt;$v${suffix:+;$suffix}"
    IFS=';'
  done
  IFS=$old; set +f
}

STACK=$DATA/tinypatient_1.contours
secs="--m --c --per-byte --local --L --o --g --G"

# ---- tile ---------------------------------------------------------------
P="$STACK;-o;m.obj;--procs;2"
each tile "--procs takes a whole number from 1 to 4096" "$STACK" --procs "$(whole_bad 1 4096)"
each tile "--min-diag takes a whole number from 1 to 1073741824" "$P" --min-diag "$(whole_bad 1 1073741824)"
each tile "--backend takes sim or threads" "$P" --backend "$(word_bad sim)"
each tile "--spin takes seconds from 0 to 10" "$P;--backend;threads" --spin "@E; 1;0x1;1e-400;-1;11;nan"
each tile "--alloc takes half" "$P" --alloc "$(word_bad half)"
each tile "--block takes a whole number from 1 to 1048576" "$P" --block "$(whole_bad 1 1048576)"
each tile "--schedule takes static or dynamic" "$P" --schedule "$(word_bad static)"
each tile "--machine takes tc2000" "$P" --machine "$(word_bad unit)"
each tile "--net takes ideal" "$P" --net "$(word_bad bus)"
each tile "--topology: unknown topology" "$P" --topology "@E;x; ring;RING;ring,ring"
each tile "--topology: topology 'mesh:0x3': mesh:WxH takes two whole numbers from 1 up" "$P" --topology "mesh:0x3"
each tile "--topology: topology 'hypercube:23': hypercube:d takes a dimension from 0 to 22" "$P" --topology "hypercube:23"
each tile "--hop-latency takes seconds from 0 to 1e9" "$P;--topology;ring" --hop-latency "$seconds_bad"
each tile "--switching takes cut-through or store-and-forward" "$P;--topology;ring" --switching "$(word_bad cut-through)"
each tile "--place: unknown placement" "$P" --place "@E;x;SNAKE"
each tile "--place: placement 'random:x': random:SEED takes a whole number" "$P" --place "random:x"
for o in $secs --o-send --o-send-byte --o-recv --o-recv-byte --wake --o-wake; do
  each tile "$o takes seconds from 0 to 1e9" "$P" "$o" "$seconds_bad"
done
each tile "--slowdown takes a factor from 0 to 1000" "$P" --slowdown "@E;-1;1001;0x1;nan"
each tile "--slowdown-spin takes a factor from 0 to 1000" "$P" --slowdown-spin "@E;-1;1001;0x1;nan"
each tile "--cost takes area or span" "$STACK" --cost "$(word_bad area)"
each tile "-j takes a whole number from 1 to 1024" "$STACK" -j "$(whole_bad 1 1024)"
each tile "--cap-style takes flat or apex" "$STACK;--caps" --cap-style "$(word_bad flat)"
each tile "-o takes a mesh file name" "$STACK" -o "$name_bad"
each tile "-o takes a file ending in .obj, .ply or .stl" "$STACK" -o "m.xyz;m"
each tile "--trace takes a file name" "$P" --trace "$name_bad"
each tile "--format takes stl, obj or ply" "$STACK" --format "$(word_bad stl)"
each tile "--contours takes a .contours file name" "$STACK" --contours "$name_bad"
each tile "--roi takes a ROI's name" "$STACK" --roi "@E"
each tile "--trace-limit takes bytes from 0 to 18446744073709551615" "$P;--trace;t.csv" --trace-limit "$bytes_bad"

# ---- bench (the paper's experiments) ----------------------------------------
O="-o;out.csv"
each bench "--procs takes whole numbers from 1 to 4096" "$O" --procs "$(list_bad 1 4096 256)"
each bench "--points takes whole numbers from 3 to 100000" "$O" --points "$(list_bad 3 100000 256)"
each bench "--min-diag takes whole numbers from 1 to 1073741824" "$O" --min-diag "$(list_bad 1 1073741824 256)"
each bench "--m takes numbers from 0 to 1e9" "$O" --m "$reallist_bad"
each bench "--c takes numbers from 0 to 1e9" "$O" --c "$reallist_bad"
each bench "--alloc takes half" "$O" --alloc "@E;x;half,;,half;half,,size;half size;HALF"
each bench "--net takes ideal" "$O" --net "$(word_bad bus)"
each bench "--machine takes tc2000" "$O" --machine "$(word_bad tc2000)"
each bench "--backend takes sim or threads" "$O" --backend "$(word_bad threads)"
each bench "--spin takes seconds from 0 to 10" "$O" --spin "@E;-1;11;0x1"
for o in --per-byte --local --L --o --g --G; do each bench "$o takes seconds from 0 to 1e9" "$O" "$o" "$seconds_bad"; done
each bench "--seed takes a whole number from 0 to 18446744073709551615" "$O" --seed "$u64_bad"
each bench "--jobs takes a whole number from 1 to 256" "$O" --jobs "$(whole_bad 1 256)"
each bench "--repeat takes a whole number from 1 to 1000" "$O" --repeat "$(whole_bad 1 1000)"
each bench "--input takes a contour stack" "$O" --input "$name_bad"
each bench "--block takes whole numbers from 1 to 1048576" "$O" --block "$(list_bad 1 1048576 256)"
each bench "--schedule takes static or dynamic" "$O" --schedule "@E;x;static,;static,dynamic,static"
each bench "--variant" "$O" --variant "@E;x;paper,,fit"
each bench "--topology" "$O" --topology "@E;x;ring,,line;mesh:0x2"
each bench "--place" "$O" --place "@E;x;linear,"
each bench "--pair takes a whole number from 0 to 1073741824" "$O;--input;$STACK" --pair "$(whole_bad 0 1073741824)"
each bench "-o takes a file name" "" -o "$name_bad"

# ---- bench --model, --glass, --claims, --calibrate -------------------------------
M="--model;-o;out.csv"
each bench "--diag takes whole numbers from 4 to 5000" "$M" --diag "$(list_bad 4 5000 256)"
each bench "--procs takes whole numbers from 1 to 4096" "$M" --procs "$(list_bad 1 4096 256)"
each bench "--net takes ideal" "$M" --net "$(word_bad loggp)"
for o in --m --c; do each bench "$o takes seconds from 0 to 1e9" "$M" "$o" "$seconds_bad"; done
each bench "-o takes a file name" "--model" -o "$name_bad"
G="--glass;-o;g.contours"
each bench "--slices takes a whole number from 3 to 10000" "$G" --slices "$(whole_bad 3 10000)"
each bench "--points takes a whole number from 3 to 100000" "$G" --points "$(whole_bad 3 100000)"
each bench "-o takes a file name" "--glass" -o "$name_bad"
each bench "--require takes whole numbers from 1 to 7" "--claims;$T/sweep.csv" --require "$(list_bad 1 7 7)"
C="--calibrate"
each bench "--points takes whole numbers from 3 to 100000" "$C" --points "$(list_bad 3 100000 256)"
each bench "--procs takes whole numbers from 1 to 64" "$C" --procs "$(list_bad 1 64 256)"
each bench "--repeat takes a whole number from 1 to 1000" "$C" --repeat "$(whole_bad 1 1000)"
each bench "--messages takes a whole number from 10 to 100000000" "$C" --messages "$(whole_bad 10 100000000)"
each bench "--seed takes a whole number from 0 to 18446744073709551615" "$C" --seed "$u64_bad"

# ---- bench --tiler -----------------------------------------------------------------
each bench "--points takes whole numbers from 3 to 100000" "--tiler" --points "$(list_bad 3 100000 16)"
each bench "--naive takes a whole number from 3 to 5000" "--tiler" --naive "$(whole_bad 3 5000)"
each bench "--input takes a contour stack" "--tiler" --input "$name_bad"
each bench "--cost takes area or span" "--tiler" --cost "$(word_bad span)"
each bench "--seed takes a whole number from 0 to 18446744073709551615" "--tiler" --seed "$u64_bad"
each bench "--repeat takes a whole number from 1 to 1000" "--tiler" --repeat "$(whole_bad 1 1000)"
each bench "--data takes a folder" "--tiler" --data "$name_bad"

each bench "--repeat takes a whole number from 1 to 100000" "--dicom" --repeat "$(whole_bad 1 100000)"

# ---- bench --ring, --switch ---------------------------------------------------------
R="--ring;3;--laps;2;--trace-csv;r.csv"
each bench "--ring takes a whole number from 1 to 1000000" "" --ring "$(whole_bad 1 1000000)" "--laps;2"
each bench "--laps takes a whole number from 1 to 1000000000" "--ring;3" --laps "$(whole_bad 1 1000000000)"
each bench "--stack takes bytes from 16k to 1G, like 256k or 1M" "--ring;3;--laps;2" --stack "@E;abc;1.5;0x10;15999;8k;1000000001;2G;none; 64k"
each bench "--net takes ideal" "$R" --net "$(word_bad ideal)"
each bench "--profile takes tc2000 or unit" "$R" --profile "$(word_bad unit)"
for o in --m --c; do each bench "$o takes seconds from 0 to 1e9" "$R" "$o" "$seconds_bad"; done
each bench "--work takes units from 0 to 1e9" "$R" --work "$seconds_bad"
each bench "--trace-csv takes a file name" "--ring;3;--laps;2" --trace-csv "$name_bad"
each bench "--trace-json takes a file name" "--ring;3;--laps;2" --trace-json "$name_bad"
each bench "--trace-limit takes bytes from 0 to 18446744073709551615" "$R" --trace-limit "$bytes_bad"
each bench "--per-byte takes seconds from 0 to 1e9" "$R" --per-byte "$seconds_bad"
each bench "--hop-latency takes seconds from 0 to 1e9" "$R;--topology;ring" --hop-latency "$seconds_bad"
each bench "--topology: unknown topology" "$R" --topology "@E;x;RING"
each bench "--place: unknown placement" "$R" --place "@E;x"
each bench "--switching takes cut-through or store-and-forward" "$R;--topology;ring" --switching "$(word_bad cut-through)"
each bench "--tokens takes 1 or all" "$R" --tokens "$(word_bad all);2"
refused bench "--ring P --laps K sends P x K messages, at most 1e10" "--ring;1000000;--laps;1000000"
each bench "--switch takes a whole number from 2 to 10000000000" "" --switch "$(whole_bad 2 10000000000)"

# ---- build/plot ---------------------------------------------------------------------------
L="lines;$T/sweep.csv"
each plot "-x takes a column name" "$L" -x "$name_bad" "-y;procs;-o;p.svg"
each plot "-y takes 1 to 8 names, comma-separated, none empty" "$L;-x;procs" -y "@E;a,,b;a,;,a;1,2,3,4,5,6,7,8,9" "-o;p.svg"
each plot "--series takes 1 to 4 names" "$L;-x;procs;-y;sim_time" --series "@E;a,,b;a,;1,2,3,4,5" "-o;p.svg"
each plot "--where takes COL=VALUE" "$L;-x;procs;-y;sim_time" --where "@E;=x;x" "-o;p.svg"
each plot "--labels takes 1 to 16 names" "$L;-x;procs;-y;sim_time" --labels "@E;a,,b;1,2,3,4,5,6,7,8,9,10,11,12,13,14,15,16,17" "-o;p.svg"
each plot "-o takes a file name" "$L;-x;procs;-y;sim_time" -o "$name_bad"
each plot "--cost takes area or span" "surface;$STACK" --cost "$(word_bad area)" "-o;s.svg"
each plot "-o takes a file name" "surface;$STACK" -o "$name_bad"
each plot "-o takes a file name" "claims;$T/sweep.csv" -o "$name_bad"

# ---- the command lines themselves ----------------------------------------------------------
refused tile "unknown option (--bogus)" "$STACK;--bogus;1"
refused tile "unknown option (--bogus)" "$STACK;--bogus"
refused tile "--procs needs a value" "$STACK;--procs"
refused tile "one contour stack at a time" "$STACK;$STACK"
refused tile "--trace-limit needs --trace" "$STACK;--procs;2;--trace-limit;1G"
refused bench "bench takes options, not arguments" "extra"
refused bench "unknown option (--bogus)" "--bogus;1"
refused bench "an option needs a value (--procs)" "--procs"
refused bench "--pair needs --input" "--pair;3"
refused bench "unknown option (--bogus)" "--claims;$T/sweep.csv;--bogus"
refused bench "at most two sweeps" "--claims;a.csv;b.csv;c.csv"
refused bench "no sweep given" "--claims"
refused bench "unknown option (--bogus)" "--dicom;--bogus"
for mode in --model --glass --calibrate --tiler; do
  refused bench "unknown option (--bogus)" "$mode;--bogus;1"
  refused bench "unexpected argument (extra)" "$mode;extra"
done
refused bench "unknown option (--bogus)" "--ring;3;--laps;2;--bogus;1"
refused bench "unexpected argument (extra)" "--switch;100;extra"
refused plot "unknown option (--bogus)" "$L;-x;procs;-y;sim_time;-o;p.svg;--bogus;1"
refused plot "unknown option (--bogus)" "claims;$T/sweep.csv;--bogus"
refused plot "unknown mode, use lines, surface or claims (frob)" "frob"

# --help goes to stdout, exit 0, for every program.
for p in tile bench plot; do
  "$BUILD/$p" --help > "$T/out" 2> "$T/err"; rc=$?
  [ $rc -eq 0 ] && [ ! -s "$T/err" ] && grep -q "^usage: $p" "$T/out" && ok || bad "$p --help: exit $rc, stderr $(cat "$T/err")"
done

summary

#!/bin/sh
# cli_install.sh -- make install (issue 14, item 12): the programs and the
# data bench's defaults name go under PREFIX, and the installed programs
# work from any folder: bench --tiler, --stack and --dicom find their data
# in PREFIX/share/tilesim, or where --data says; tilesim-plot --help is on
# stdout.  Installs make check's sanitized build into a folder of its own
# (make install-files IBIN=... DESTDIR=...), and runs it from another.
BUILD=${BUILD:-build/chk}
T=$(mktemp -d /tmp/tilesim-install.XXXXXX)
trap 'rm -rf "$T"' EXIT
pass=0; fail=0
ok()  { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "cli_install: $*"; }
mk() { env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make --no-print-directory -s "$@"; }

mk install-files DESTDIR="$T/root" PREFIX=/opt/ts IBIN="$BUILD" IPLOT="$BUILD/plot" > "$T/log" 2>&1 \
  && ok || bad "make install-files: $(cat "$T/log")"
P=$T/root/opt/ts
for f in bin/tile bin/bench bin/tilesim-plot share/tilesim/slicerrt/prostate_0.contours \
         share/tilesim/slicerrt/README.md share/tilesim/rtstruct/dicompyler_rtss.dcm share/tilesim/rtstruct/README.md; do
  [ -e "$P/$f" ] && ok || bad "not installed: $f"
done

mkdir "$T/elsewhere" && cd "$T/elsewhere" || exit 1
# The default stack's name, and a bare name: both from the installed data.
"$P/bin/bench" --tiler --points 20 --naive 20 --input tests/data/slicerrt/prostate_3.contours --repeat 1 > out 2> err \
  && grep -q '^stack:prostate_3.contours,18,' out && ok || bad "bench --tiler, installed: $(cat err)"
"$P/bin/bench" --tiler --points 20 --input prostate_2.contours --repeat 1 > out 2> err \
  && grep -q '^stack:prostate_2.contours,' out && ok || bad "bench --tiler --input prostate_2.contours: $(cat err)"
"$P/bin/bench" --stack tests/data/slicerrt/prostate_3.contours -j 1 --repeat 1 > out 2> err \
  && [ "$(wc -l < out)" -eq 2 ] && ok || bad "bench --stack, installed: $(cat err)"
"$P/bin/bench" --dicom --repeat 1 > out 2> err && grep -q 'dicompyler_rtss.dcm,1940626,' out \
  && ok || bad "bench --dicom, installed: $(cat err)"
"$P/bin/tilesim-plot" --help > out 2> err && [ ! -s err ] && grep -q '^usage: plot' out \
  && ok || bad "tilesim-plot --help: not on stdout"
"$P/bin/tile" "$P/share/tilesim/slicerrt/tinypatient_1.contours" -q > out 2> err && ok || bad "tile, installed: $(cat err)"

# Without the data: a message saying where it looked and what to do, exit 1.
mv "$P/share/tilesim" "$T/data"
"$P/bin/bench" --tiler --points 20 --input prostate_2.contours --repeat 1 > out 2> err; rc=$?
[ $rc -eq 1 ] && grep -q '^bench: prostate_2.contours: not found.*share/tilesim.*--data DIR says where it is$' err \
  && ok || bad "no data: exit $rc, $(cat err)"
# --data DIR: there.
"$P/bin/bench" --tiler --points 20 --input prostate_2.contours --data "$T/data" --repeat 1 > out 2> err \
  && grep -q '^stack:prostate_2.contours,' out && ok || bad "--data: $(cat err)"

echo "cli_install: $pass passed, $fail failed"
[ $fail -eq 0 ]

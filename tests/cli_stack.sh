#!/bin/sh
# cli_stack.sh -- ./tile on real structures with several contours per slice,
# judged by the independent mesh checker (tests/meshcheck.c, as
# `test_solids --check MESH STACK`): every ROI of dicompyler's plan (BODY up
# to 4 contours a slice, Lt Lung up to 7 and 77 holes, ...), MIM's and
# pydicom's, with flat and apex caps, must be closed, outward 2-manifolds
# without degenerate triangles, through every input point and segment.
TILE=${BUILD:-build/chk}/tile
CHECK=${BUILD:-build/chk}/tests/test_solids
D=tests/data/rtstruct
. tests/clilib.sh

judge() {   # MESH STACK WHAT
  out=$("$CHECK" --check "$1" "$2" 2>&1)
  printf '%s\n' "$out" | tail -1 | grep -q ' 0 failed$' && ok || bad "$3: $(printf '%s\n' "$out" | head -3)"
}

"$TILE" $D/dicompyler_rtss.dcm --roi all -q --contours "$T/c/" > /dev/null 2>&1 && ok || bad "dicompyler: --contours"
for style in flat apex; do
  "$TILE" $D/dicompyler_rtss.dcm --roi all -q --caps --cap-style $style -o "$T/$style/" --format obj \
    > "$T/$style.csv" 2> "$T/err" && ok || bad "dicompyler --roi all --cap-style $style: $(cat "$T/err")"
  [ "$(ls "$T/$style" | wc -l)" -eq 9 ] && ok || bad "$style: $(ls "$T/$style" | wc -l) meshes, want 9"
  for m in "$T/$style"/*.obj; do
    b=$(basename "$m" .obj)
    judge "$m" "$T/c/$b.contours" "dicompyler $b, $style caps"
  done
  # every mesh row closed
  [ "$(grep -c ',mesh,.*,closed,' "$T/$style.csv")" -eq 9 ] && ok || bad "$style: not every mesh row closed"
done
for r in ROI-1 ROI-3; do
  "$TILE" $D/rtutils_dummy_rt.dcm --roi $r -q --caps -o "$T/r.obj" --contours "$T/r.contours" > /dev/null 2> "$T/err" \
    && judge "$T/r.obj" "$T/r.contours" "rtutils $r" || bad "rtutils $r: $(cat "$T/err")"
done
"$TILE" $D/pydicom_rtstruct.dcm --roi patient -q --caps -o "$T/p.obj" --contours "$T/p.contours" > /dev/null 2> "$T/err" \
  && judge "$T/p.obj" "$T/p.contours" "pydicom patient" || bad "pydicom: $(cat "$T/err")"
summary

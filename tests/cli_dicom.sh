#!/bin/sh
# cli_dicom.sh -- ./tile on DICOM RT structure sets: --list against the data
# README's inventory, the same bytes from implicit and explicit encodings and
# from the ROI's converted .contours stack (and from the generator's own
# stack), every refusal (one line naming the file, exit 1, no output file),
# warnings, usage errors, ROIs in other planes, --roi all -o DIR/.
# The synthetic files are written by tests/test_rtstruct --write (the test
# writer, tests/rtwriter.c).  Runs the sanitized build in $BUILD.
B=${BUILD:-build/chk}
TILE=$B/tile
D=tests/data/rtstruct
. tests/clilib.sh

mkdir "$T/f"
"$B/tests/test_rtstruct" --write "$T/f" || bad "test_rtstruct --write failed"
F=$T/f

# ---- --list: the inventory of shared/data/rtstruct/README.md (roi_number,
# name, type, contours, skipped, slices), written here by hand.
list_is() {   # FILE EXPECTED-ROWS
  "$TILE" "$1" --list > "$T/list" 2> "$T/err"; rc=$?
  [ $rc -eq 0 ] && [ ! -s "$T/err" ] && ok || bad "--list $1: exit $rc: $(cat "$T/err")"
  head -1 "$T/list" | grep -qx 'roi_number,name,type,contours,skipped,slices,points,z_min,z_max,plane' && ok || bad "--list header: $(head -1 "$T/list")"
  tail -n +2 "$T/list" | cut -d, -f1-6 > "$T/got"
  printf '%s\n' "$2" > "$T/want"
  cmp -s "$T/got" "$T/want" && ok || bad "--list $1: got
$(cat "$T/got")
expected
$(cat "$T/want")"
}
list_is $D/dicompyler_rtss.dcm '1,BODY,EXTERNAL,141,0,98
2,Areola,AVOIDANCE,0,0,0
3,Borders,CTV,2,0,2
4,Breast,GTV,48,0,47
5,Heart,ORGAN,33,0,33
6,Lt Lung,AVOIDANCE,165,0,80
7,Nodes,AVOIDANCE,4,0,4
8,Scar,AVOIDANCE,6,0,6
9,Tumor Bed,CTV,18,0,18
10,Tumor Bed Block,GTV,24,0,24'
list_is $D/pydicom_rtstruct.dcm '1,patient,EXTERNAL,3,0,3
2,Isocenter 1,ISOCENTER,0,1,0
3,Isocenter 2,ISOCENTER,0,1,0'
for f in rtutils_dummy_rt rtutils_dummy_rt_explicit; do
  list_is $D/$f.dcm '1,ROI-1,,3,0,3
2,ROI-2,,3,0,3
3,ROI-3,,3,0,3
4,ROI-4,,3,0,3'
done
list_is $D/rtutils_rt.dcm '1,ROI-1,,2,0,1'
# The points and planes the data README gives: BODY 51,846 points; pydicom's
# three contours of 5, 6 and 6 points at z = -200 .. -180; rt.dcm's 4 + 8
# points at z = 60; MIM's 315 to 1,015 points per ROI, 5 mm apart.
"$TILE" $D/dicompyler_rtss.dcm --list | grep -q '^1,BODY,EXTERNAL,141,0,98,51846,' && ok || bad "BODY points"
"$TILE" $D/pydicom_rtstruct.dcm --list | grep -qx '1,patient,EXTERNAL,3,0,3,17,-200.0,-180.0,axial' && ok || bad "pydicom patient row"
"$TILE" $D/rtutils_rt.dcm --list | grep -qx '1,ROI-1,,2,0,1,12,60.0,60.0,axial' && ok || bad "rt.dcm row"
"$TILE" $D/rtutils_dummy_rt.dcm --list | tail -n +2 | cut -d, -f7-10 | sort -n > "$T/mim"
printf '315,60,70,axial\n356,60,70,axial\n418,60,70,axial\n1015,60,70,axial\n' | cmp -s - "$T/mim" && ok || bad "MIM points: $(cat "$T/mim")"

# The converter on every ROI: the stacks hold the inventory's contours and
# slices (several contours per slice included: converting does not tile).
"$TILE" $D/dicompyler_rtss.dcm --roi all --contours "$T/stacks/" > "$T/out" 2> "$T/err"; rc=$?
[ $rc -eq 0 ] && [ ! -s "$T/out" ] && grep -q "ROI 2 'Areola' has no contours to tile; skipped" "$T/err" && ok || bad "--contours DIR/: exit $rc: $(cat "$T/err")"
for want in BODY:141:98 Borders:2:2 Breast:48:47 Heart:33:33 Lt_Lung:165:80 Nodes:4:4 Scar:6:6 Tumor_Bed:18:18 Tumor_Bed_Block:24:24; do
  f=${want%%:*}; c=${want#*:}; c=${c%%:*}; sl=${want##*:}
  got=$(grep -c '^C ' "$T/stacks/$f.contours" 2>/dev/null)
  gsl=$(grep '^C ' "$T/stacks/$f.contours" 2>/dev/null | awk '{print $3}' | sort -u | wc -l)
  [ "$got" = "$c" ] && [ "$gsl" -eq "$sl" ] && ok || bad "$f.contours: $got contours on $gsl slices, expected $c on $sl"
done

# ---- Without --roi: the list, and what to add.
"$TILE" $D/rtutils_rt.dcm > "$T/out" 2> "$T/err"; rc=$?
[ $rc -eq 0 ] && head -1 "$T/out" | grep -q '^roi_number,name' && grep -q 'add --roi NAME|NUMBER' "$T/err" && ok || bad "bare file: $rc $(cat "$T/err")"

# ---- Implicit and explicit encodings of the same set: the same bytes (ROI-2
# and ROI-4 are keyhole contours, split into their loops: tests/cli_keyhole.sh;
# were one refused, the same refusal).
for r in 1 2 3 4; do
  for f in rtutils_dummy_rt rtutils_dummy_rt_explicit; do
    "$TILE" $D/$f.dcm --roi $r -q --caps -o "$T/$f.obj" > "$T/$f.csv" 2> "$T/$f.err"; echo $? > "$T/$f.rc"
    "$TILE" $D/$f.dcm --roi $r -q --caps -o "$T/$f.stl" > /dev/null 2>&1
    sed 's/^tile: [^:]*: byte [0-9]*: //' "$T/$f.err" > "$T/$f.why"
  done
  [ "$(cat "$T/rtutils_dummy_rt.rc")" -eq 0 ] && ok || bad "MIM ROI $r refused: $(cat "$T/rtutils_dummy_rt.err")"
  if [ "$(cat "$T/rtutils_dummy_rt.rc")" -eq 0 ]; then
    cmp -s "$T/rtutils_dummy_rt.csv" "$T/rtutils_dummy_rt_explicit.csv" && cmp -s "$T/rtutils_dummy_rt.obj" "$T/rtutils_dummy_rt_explicit.obj" &&
      cmp -s "$T/rtutils_dummy_rt.stl" "$T/rtutils_dummy_rt_explicit.stl" && ok || bad "MIM ROI $r: implicit and explicit differ"
  else
    cmp -s "$T/rtutils_dummy_rt.rc" "$T/rtutils_dummy_rt_explicit.rc" && cmp -s "$T/rtutils_dummy_rt.why" "$T/rtutils_dummy_rt_explicit.why" &&
      grep -q "ROI $r 'ROI-$r', contour item [0-9]*: the contour crosses itself" "$T/rtutils_dummy_rt.why" &&
      ok || bad "MIM ROI $r: implicit '$(cat "$T/rtutils_dummy_rt.err")', explicit '$(cat "$T/rtutils_dummy_rt_explicit.err")'"
  fi
done
# The generated set in four encodings (implicit/explicit, defined/undefined
# lengths, with and without preamble and meta): every file the same.
for f in gen_implicit gen_implicit_undefined gen_explicit gen_explicit_undefined; do
  "$TILE" $F/$f.dcm --roi all -q --caps -o "$T/$f/" --format obj > "$T/$f.csv" 2> "$T/err" || bad "$f: $(cat "$T/err")"
done
for f in gen_implicit_undefined gen_explicit gen_explicit_undefined; do
  cmp -s "$T/gen_implicit.csv" "$T/$f.csv" && diff -r "$T/gen_implicit" "$T/$f" > /dev/null && ok || bad "$f differs from gen_implicit"
done
[ "$(ls "$T/gen_implicit" | wc -l)" -eq 4 ] && head -1 "$T/gen_implicit.csv" | grep -q '^roi_number,name,band,' && ok || bad "--roi all: $(ls "$T/gen_implicit")"

# ---- An ROI is tiled exactly as its stack: --contours, then ./tile on it,
# gives the same report and mesh as --roi directly; and the generated set's
# ROIs give the same bytes as the generator's own stacks (contour_write).
same_as_stack() {   # FILE ROI [STACK]
  "$TILE" "$1" --roi "$2" -q --caps -o "$T/a.obj" > "$T/a.csv" 2> "$T/err" || { bad "$1 --roi $2: $(cat "$T/err")"; return; }
  "$TILE" "$1" --roi "$2" -q --contours "$T/s.contours" > "$T/none" 2> "$T/err" && [ ! -s "$T/none" ] || bad "$1 --roi $2 --contours: $(cat "$T/err")"
  "$TILE" "${3:-$T/s.contours}" -q --caps -o "$T/b.obj" > "$T/b.csv" 2> "$T/err" || bad "stack of $1 ROI $2: $(cat "$T/err")"
  cmp -s "$T/a.csv" "$T/b.csv" && cmp -s "$T/a.obj" "$T/b.obj" && ok || bad "$1 ROI $2: not the same bytes as its stack ${3:-}"
  # closed: every edge as often one way as the other
  awk '$1 == "f" { e[$2 " " $3]++; e[$3 " " $4]++; e[$4 " " $2]++ }
       END { for (k in e) { split(k, p, " "); if (e[p[2] " " p[1]] != e[k]) exit 1 } }' "$T/a.obj" && ok || bad "$1 ROI $2: mesh not closed"
}
for r in 3 5 7 8 9 10; do same_as_stack $D/dicompyler_rtss.dcm $r; done
same_as_stack $D/pydicom_rtstruct.dcm patient
for r in ROI-1 ROI-2 ROI-3 ROI-4; do same_as_stack $D/rtutils_dummy_rt.dcm $r; done
for r in 1 4 7 10; do same_as_stack $F/gen_explicit_undefined.dcm $r $F/gen_$r.contours; done

# ---- Refusals: one line naming the file, exit 1, no output file.
refused() {   # NAME FILE EXPECTED [ARGS...]
  name=$1; file=$2; want=$3; shift 3
  rm -f "$T/r.stl" "$T/r.contours"
  "$TILE" "$file" "$@" -o "$T/r.stl" --contours "$T/r.contours" > "$T/out" 2> "$T/err"; rc=$?
  [ $rc -eq 1 ] && [ "$(wc -l < "$T/err")" -eq 1 ] && grep -qF "tile: $file: " "$T/err" && grep -qF "$want" "$T/err" &&
    [ ! -e "$T/r.stl" ] && [ ! -e "$T/r.contours" ] && [ ! -s "$T/out" ] && [ -z "$(ls "$T" | grep tmp)" ] &&
    ok || bad "$name: exit $rc, stdout $(wc -c < "$T/out") bytes, stderr '$(cat "$T/err")', expected 'tile: $file: $want'"
}

# ---- Several contours per slice: the ROIs that have them tile
# into closed meshes, the same bytes as their stacks; the surface's notes
# name the ROI's contour items.
for r in 1 4 6; do
  same_as_stack $D/dicompyler_rtss.dcm $r
  grep -q '^mesh,.*,closed,' "$T/a.csv" && ok || bad "ROI $r: the report's mesh row is not closed: $(grep '^mesh' "$T/a.csv")"
done
"$TILE" $D/dicompyler_rtss.dcm --roi 'Lt Lung' > /dev/null 2> "$T/err"
grep -q "^tile: $D/dicompyler_rtss.dcm: byte [0-9]*: ROI 6 'Lt Lung', contour item [0-9]*: " "$T/err" && ! grep -q 'as a stack\|line [0-9]' "$T/err" &&
  ok || bad "Lt Lung's notes: $(cat "$T/err")"
# rt.dcm's ROI is one slice (an outer contour and its hole).
refused oneslice $D/rtutils_rt.dcm "byte 1810: ROI 1 'ROI-1', contour item 1: all 2 contours lie on one slice (z=60): a surface needs two slices, or --thickness T to make this one a slab T thick" --roi 1

refused bigendian $F/bigendian.dcm 'byte 132: transfer syntax Explicit VR Big Endian is not supported (1.2.840.10008.1.2.2)' --roi 7
refused deflated $F/deflated.dcm 'byte 132: transfer syntax Deflated Explicit VR Little Endian is not supported (1.2.840.10008.1.2.1.99)' --roi 7
refused private_ts $F/private_ts.dcm 'byte 132: unsupported transfer syntax, only implicit and explicit VR little endian (1.2.3.4.5.6)' --roi 7
refused ct $F/ct.dcm 'byte 318: not an RT structure set: the Modality (0008,0060) is CT' --roi 7
refused deep $F/deep.dcm 'sequences nested deeper than 16' --roi 7
refused pastparent $F/pastparent.dcm 'has length' --roi 7
grep -q 'its parent ends at byte' "$T/err" && ok || bad "pastparent: $(cat "$T/err")"
refused count $F/count.dcm "ROI 7 'Prostate', contour item 1: NumberOfContourPoints is 5 but ContourData holds 12 values (4 points)" --roi 7
refused nonnumeric $F/nonnumeric.dcm "ROI 7 'Prostate', contour item 1, point 3: y is not a number (abc)" --roi Prostate
refused nonfinite $F/nonfinite.dcm "ROI 7 'Prostate', contour item 1, point 4: x is not finite (1e999)" --roi 7
refused triplets $F/triplets.dcm "ROI 7 'Prostate', contour item 1: ContourData holds 7 values, not x y z triplets" --roi 7
refused oblique $F/oblique.dcm "ROI 7 'Prostate', contour item 2: not planar (its points spread 0.497 mm off their best plane, more than the 0.1 mm their precision allows)" --roi 7
refused onecontour $F/onecontour.dcm "ROI 7 'Prostate', contour item 1: the only contour lies on one slice (z=5): a surface needs two slices, or --thickness T" --roi 7
# Two overlapping contours on a slice: merged into their union (they were
# refused), one note; --union the same bytes.
"$TILE" $F/twoperslice.dcm --roi 7 -o "$T/tw.stl" > "$T/tw.csv" 2> "$T/err"; rc=$?
[ $rc -eq 0 ] && grep -q '^mesh,.*,closed,' "$T/tw.csv" &&
  [ "$(cat "$T/err")" = "tile: $F/twoperslice.dcm: byte 518: ROI 7 'Prostate', contour item 1: merged 2 overlapping contours on slice z=5 into their union (as --union does): the contours at contour item 1 and contour item 2: 1 contour (2 new vertices where they cross)" ] &&
  "$TILE" $F/twoperslice.dcm --roi 7 --union -o "$T/tw2.stl" > "$T/tw2.csv" 2> /dev/null && cmp -s "$T/tw.stl" "$T/tw2.stl" &&
  ok || bad "twoperslice: exit $rc: $(cat "$T/err")"
refused unknown $D/dicompyler_rtss.dcm "no ROI named or numbered 'Lung' (the ROIs: 1 'BODY', 2 'Areola'," --roi Lung
refused unknown2 $D/dicompyler_rtss.dcm "no ROI named or numbered '11'" --roi 11
refused samenames $F/samenames.dcm "ROIs 3 and 4 are both named 'Same'; choose one by its number (Same)" --roi Same
refused empty $D/dicompyler_rtss.dcm "ROI 2 'Areola' has no contours to tile" --roi Areola
refused points $D/pydicom_rtstruct.dcm "ROI 2 'Isocenter 1' has no closed planar contours to tile (1 contour of another type)" --roi 2
head -c 1000000 $D/dicompyler_rtss.dcm > "$T/cut.dcm"
refused truncated "$T/cut.dcm" 'truncated: the file ends at byte 1000000' --roi 3
printf 'C 3 0\n0 0\n1 0\n0 1\nC 3 1\n0 0\n1 0\n0 1\n' > "$T/y.contours"
refused notdicom "$T/y.contours" 'not a DICOM file; --list, --roi, --contours and --format read DICOM RT structure sets' --roi 1
# Truncations and byte flips of a real file through the program: exit 0
# or one line (the library-level tests do every truncation).
for n in 0 1 131 132 133 200 300 500 700 900 1100 1300 1500 1700 1900 2100 2300 2500 2533; do
  head -c $n $D/pydicom_rtstruct.dcm > "$T/cut.dcm"
  "$TILE" "$T/cut.dcm" --roi all -q -o "$T/cutdir/" > /dev/null 2> "$T/err"; rc=$?
  { [ $rc -eq 0 ] || { [ $rc -eq 1 ] && [ "$(wc -l < "$T/err")" -eq 1 ]; }; } && ok || bad "cut at $n: exit $rc: $(cat "$T/err")"
done

# ---- Warnings, once each, on stderr; -q silences them.
"$TILE" $F/warnings.dcm --roi all -o "$T/w/" > "$T/out" 2> "$T/err"; rc=$?
[ $rc -eq 0 ] && ok || bad "warnings.dcm: exit $rc: $(cat "$T/err")"
for w in "ROIContourSequence item 3 references ROI 99, which the StructureSetROISequence does not define; its 3 contours are ignored" \
         "ROI 1 'Body': skipped 1 POINT and 1 OPEN_PLANAR contours; only CLOSED_PLANAR contours are tiled" \
         "ROI 2 'Nothing' has no contours to tile; skipped" \
         "ROI 3 'Orphan' has no contours to tile; skipped"; do
  [ "$(grep -cF "$w" "$T/err")" -eq 1 ] && ok || bad "warning '$w' not once in: $(cat "$T/err")"
done
# Sanitised names; two that differ only in case get their ROI numbers.
(cd "$T/w" && ls) > "$T/names"
printf 'Body.stl\nLt_Lung_left_4.stl\nlt_lung_left_5.stl\nroi_6.stl\n' | cmp -s - "$T/names" && ok || bad "mesh names: $(cat "$T/names")"
grep -q '^4,Lt Lung/left,pair,' "$T/out" || grep -q '^4,Lt Lung/left,0,' "$T/out" && ok || bad "report rows: $(head -3 "$T/out")"
"$TILE" $F/warnings.dcm --roi all -q -o "$T/w2/" > /dev/null 2> "$T/err" && [ ! -s "$T/err" ] && ok || bad "-q: $(cat "$T/err")"
"$TILE" $D/pydicom_rtstruct.dcm --roi patient > /dev/null 2> "$T/err"
grep -q "tile: $D/pydicom_rtstruct.dcm: ROI 1 'patient': 2 of 3 contours ran clockwise; reversed to counter-clockwise" "$T/err" &&
  grep -q "tile: $D/pydicom_rtstruct.dcm: byte 1458: ROI 1 'patient', contour item 1, point 5: dropped the repeated closing point" "$T/err" &&
  ok || bad "pydicom notes: $(cat "$T/err")"

# ---- Sagittal and coronal ROIs: turned into z and back.  The report and
# the faces are the axial ROI's; the vertices are its, axes permuted.
for p in axial sagittal coronal; do
  "$TILE" $F/$p.dcm --roi 1 -q --caps -o "$T/$p.obj" > "$T/$p.csv" 2> "$T/err" || bad "$p: $(cat "$T/err")"
  "$TILE" $F/$p.dcm --list | grep -q ",$p\$" && ok || bad "$p: --list plane"
done
cmp -s "$T/axial.csv" "$T/sagittal.csv" && cmp -s "$T/axial.csv" "$T/coronal.csv" && ok || bad "planes: reports differ"
grep '^f' "$T/axial.obj" > "$T/fa"; grep '^f' "$T/sagittal.obj" > "$T/fs"; grep '^f' "$T/coronal.obj" > "$T/fc"
cmp -s "$T/fa" "$T/fs" && cmp -s "$T/fa" "$T/fc" && ok || bad "planes: faces differ"
awk '$1 == "v" { print "v", $4, $2, $3 }' "$T/axial.obj" > "$T/vs"   # sagittal: x = h, y = u, z = v
awk '$1 == "v" { print "v", $3, $4, $2 }' "$T/axial.obj" > "$T/vc"   # coronal: x = v, y = h, z = u
grep '^v' "$T/sagittal.obj" | cmp -s - "$T/vs" && grep '^v' "$T/coronal.obj" | cmp -s - "$T/vc" && ok || bad "planes: vertices not permuted"

# ---- Usage: the usage line, exit 2.
usage() {
  "$TILE" "$@" > /dev/null 2> "$T/err"; rc=$?
  [ $rc -eq 2 ] && grep -q '^usage: tile STACK' "$T/err" && ok || bad "usage '$*': exit $rc: $(cat "$T/err")"
}
usage $D/rtutils_rt.dcm --list --roi 1
usage $D/rtutils_rt.dcm -o "$T/x.stl"
usage $D/rtutils_rt.dcm --roi all -o "$T/x.stl"
usage $D/rtutils_rt.dcm --roi 1 --roi 2 --contours "$T/x.contours"
usage $D/rtutils_rt.dcm --roi 1 -o "$T/x.stl" --format obj
usage $D/rtutils_rt.dcm --roi 1 --format vrml
usage $D/rtutils_rt.dcm --roi
usage $D/rtutils_rt.dcm --roi all --procs 2 --trace "$T/t.csv"
[ ! -e "$T/x.stl" ] && [ ! -e "$T/x.contours" ] && ok || bad "usage errors wrote files"

summary

#!/bin/sh
# cli_layers.sh -- the layer check (tests/layers.sh, its table
# tests/layers.txt): the tree as it stands passes, its include path is the
# Makefile's, and the check fails where it must, on small trees made here:
# an include up a layer, sideways, angled, into a folder with no line, a
# cycle of files and one of folders, a stale exception; and on a copy of this
# tree with one include that runs up a layer.
. tests/clilib.sh

# The tree as it stands.
out=$(sh tests/layers.sh . 2>&1) && printf '%s\n' "$out" | grep -qE '^layers: [0-9]+ files, ' \
  && ok || bad "this tree: $out"

# The table's include path is the one the Makefile gives the compiler: BASE's
# -I folders for every file, TSMPIPFLAGS's for the MPI test programs.
idirs() {
  awk -v v="$1" '$1 == v { on = 1 }
    on { for (i = 1; i <= NF; i++) if ($i ~ /^-I/) printf "%s ", substr($i, 3); if ($NF != "\\") exit }' Makefile
}
tdirs() { sed -n "s|^search$1:||p" tests/layers.txt | tr -s ' \t' '\n\n' | grep . | tr '\n' ' '; }
[ -n "$(idirs BASE)" ] && [ "$(idirs BASE)" = "$(tdirs '')" ] && ok \
  || bad "search: is '$(tdirs '')', the Makefile's BASE has '$(idirs BASE)'"
[ -n "$(idirs TSMPIPFLAGS)" ] && [ "$(idirs TSMPIPFLAGS)" = "$(tdirs ' tests/mpi/')" ] && ok \
  || bad "search tests/mpi/: is '$(tdirs ' tests/mpi/')', TSMPIPFLAGS has '$(idirs TSMPIPFLAGS)'"

# A small tree ($T/t) and its table: put FILE LINE... writes FILE; check runs
# the check on the tree; try FILE LINE adds LINE to FILE for one check; has
# RC LINE: the check exited RC and printed LINE (an extended regex).
put() { f=$T/t/$1; shift; mkdir -p "${f%/*}"; printf '%s\n' "$@" > "$f"; }
check() { out=$(sh tests/layers.sh "$T/t" 2>&1); rc=$?; }
try() { cp "$T/t/$1" "$T/save"; printf '%s\n' "$2" >> "$T/t/$1"; check; cp "$T/save" "$T/t/$1"; }
has() { [ "$rc" -eq "$1" ] && printf '%s\n' "$out" | grep -qxE "$2"; }
tab=$T/t/tests/layers.txt
mkdir -p "$T/t/tests"
printf '%s\n' '# a test table' 'search: . lib' 'util:' 'mp:     util' 'sim:    mp util' 'geo:    util' \
  'mpi:    mp/mp.h util' 'app:    *' 'lib:    util' 'private mp/backend.h: sim' > "$T/table"
cp "$T/table" "$tab"
put util/xmem.h '#include <stdio.h>' '#include <string.h>'
put util/xmem.c '#include "xmem.h"'
put mp/mp.h '#include "util/xmem.h"'
put mp/backend.h '#include "mp.h"'
put mp/chan.h '#include "mp.h"'
put sim/sim.c '#include "mp/mp.h"' '#include "mp/backend.h"' '#  include "../util/xmem.h"'
put geo/geom.c '#include "util/xmem.h"'
put mpi/state.c '#include "mp/mp.h"' '#include "state.h"'
put mpi/state.h '/* #include "mp/backend.h" in a comment is no include */'
put app/bench/main.c '#include "bench.h"' '#include "sim/sim.c"' '#include "geo/geom.c"' '#include <mpi/state.h>'
put app/bench/bench.h '#include "../plot/plot.h"'
put app/plot/plot.h '#include "mp/mp.h"'
put build/gen.h '#include "util/xmem.c"' '#include "app/bench/bench.h"'
good='layers: 12 files, [0-9]+ includes, [0-9]+ across folders, 0 exceptions'
check
has 0 "$good" && ok || bad "a tree within the rules: $rc $out"

# Each fault: one line naming the file, the line and the edge, and exit 1;
# names that are not the tree's are no edge.  A row: the file, the line
# added to it for one check, the exit status and a line the check prints
# (an extended regex), what the row shows.  The tree's table, then with a
# path of util's own, then with a folder lib on the common path.
faults() {
  while IFS='|' read -r f l r e what; do
    try "$f" "$l"; has "$r" "$e" && ok || bad "$what: $rc $out"
  done
}
faults <<EOF
util/xmem.c|#include "mp/mp.h"|1|util/xmem.c:2: includes mp/mp.h: util may not include mp|up a layer
mp/mp.h|#include "../sim/sim.c"|1|mp/mp.h:2: includes sim/sim.c: mp may not include sim|up, relative
geo/geom.c|#include "mp/mp.h"|1|geo/geom.c:2: includes mp/mp.h: geo may not include mp|sideways
mpi/state.c|#include "mp/chan.h"|1|mpi/state.c:3: includes mp/chan.h: mpi may not include mp|a file kept from mpi
mpi/state.c|#include "mp/backend.h"|1|mpi/state.c:3: includes mp/backend.h: mp/backend.h is private to mp sim|a private file
app/plot/plot.h|#include "mp/backend.h"|1|app/plot/plot.h:2: includes mp/backend.h: mp/backend.h is private to mp sim|a private file, to a folder that may include all
util/xmem.c|#include <geo/geom.c>|1|util/xmem.c:2: includes geo/geom.c: util may not include geo|angled, on the path
util/xmem.c|#include <backend.h>|0|$good|an angled name not on the path is the system's
util/xmem.c|#include "geom.c"|0|$good|a quoted name found nowhere is none of the tree's
EOF
printf '%s\n' 'search util/: mp' >> "$tab"
faults <<EOF
util/xmem.c|#include <chan.h>|1|util/xmem.c:2: includes mp/chan.h: util may not include mp|a path of util's
geo/geom.c|#include <backend.h>|0|$good|a path of util's is not geo's
EOF
cp "$T/table" "$tab"
put lib/lib.h '/* found on the path */'
faults <<EOF
geo/geom.c|#include "lib.h"|1|geo/geom.c:2: includes lib/lib.h: geo may not include lib|quoted, on the path
EOF
rm -r "$T/t/lib"
put new/x.c '#include "util/xmem.h"'
check
has 1 'new/x.c: in no layer \(new has no line in .*\)' && ok || bad "a folder with no line: $rc $out"
rm -r "$T/t/new"

# Cycles: two files of different folders that include each other (the
# rules allow both ways here); two folders whose files do, file by file.
printf '%s\n' 'p: *' 'q: *' >> "$tab"
put p/a.h '#include "q/b.h"'
put q/b.h '#include "p/a.h"'
check
has 1 'cycle: (p/a.h -> q/b.h -> p/a.h|q/b.h -> p/a.h -> q/b.h)' && ok || bad "a cycle of files: $rc $out"
put q/b.h '#include "q/c.h"'
put q/c.h '#include "p/d.h"'
put p/d.h '/* none */'
check
has 1 'cycle: (p -> q -> p|q -> p -> q) \(folders\)' && ! printf '%s\n' "$out" | grep -q '^cycle: [a-z]/' \
  && ok || bad "a cycle of folders, none of files: $rc $out"
rm -r "$T/t/p" "$T/t/q"

# An exception allows its include; once the include is gone it fails.
cp "$T/table" "$tab"; printf '%s\n' 'except geo/geom.c -> mp/mp.h' >> "$tab"
try geo/geom.c '#include "mp/mp.h"'
has 0 'layers: 12 files, .*, 1 exceptions' && ok || bad "an exception allows: $rc $out"
check
has 1 '.*/layers.txt:11: except geo/geom.c -> mp/mp.h: no longer occurs \(remove the line\)' \
  && ok || bad "a stale exception: $rc $out"
cp "$T/table" "$tab"; printf '%s\n' 'sim mp' >> "$tab"
check
has 1 '.*/layers.txt:11: not FOLDER: NAME\.\.\.' && ok || bad "a bad line: $rc $out"
out=$(sh tests/layers.sh "$T/none" 2>&1); rc=$?
[ $rc -eq 2 ] && ok || bad "no such folder: $rc $out"

# This tree, copied, with one include that runs up a layer: util/ reaching
# for the simulator.
mkdir "$T/copy"
find . -name build -prune -o -name '.?*' -prune -o -type f \( -name '*.[ch]' -o -name layers.txt \) -print |
  tar -cf - -T - | (cd "$T/copy" && tar -xf -)
printf '#include "sim/sim.h"\n' >> "$T/copy/util/xmem.c"
out=$(sh tests/layers.sh "$T/copy" 2>&1); rc=$?
has 1 "util/xmem.c:$(($(grep -c '' util/xmem.c) + 1)): includes sim/sim.h: util may not include sim" \
  && ok || bad "this tree with util/xmem.c including sim/sim.h: $rc $out"

summary

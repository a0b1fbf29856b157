#!/bin/sh
# cli_docs.sh -- the manual against the programs, as curl's
# test1139 and git's t0450 hold theirs:
#  - every option each program's --help (and each mode's: bench MODE
#    --help) prints appears in its man page, and every option the page
#    names is in the help, compared both ways on the page rendered to text
#    (doc/tile.1, doc/tilesim-bench.1 section by section, doc/tilesim-plot.1;
#    tile-mpi too where the MPI build is there); every option a page names
#    is one the program takes, asked of the program itself (it must not
#    answer "unknown option"); tilesim(7) and tilesim-contours(5) name only
#    options some program takes; every option string in the sources is on
#    some page;
#  - every page passes mandoc -Tlint (style messages included, but for
#    references to pages not installed here), or groff -ww without a word
#    where mandoc is missing;
#  - README.md is under 200 lines and every file it names exists; every
#    link in doc/*.md leads to a file;
#  - the verdicts doc/paper.md quotes equal plots/claims.csv,
#    plots/real_claims.csv and plots/claims_map.csv, and the claims README
#    shows are plots/claims.csv's, as jq tests its manual's examples.
# Where neither mandoc nor groff is installed the page checks are skipped,
# and said so.  A reference that is not an option of the page's program
# (mpirun's --oversubscribe on tile's page) is listed in ALLOW below, with
# why.
BUILD=${BUILD:-build/chk}
TILE=$BUILD/tile
BENCH=$BUILD/bench
PLOT=$BUILD/plot
MPIDIR=${MPIDIR:-build/mpi}
. tests/clilib.sh

# Names a page or a help text gives that are not options of that program
# or mode: "WHERE OPTION  why".  WHERE is tile, bench (the whole page),
# bench:sweep, bench:--MODE, plot.
ALLOW='
tile --calibrate          tilesim-bench measures --table-c and --back-c (tile --help, the page)
tile --oversubscribe      mpirun'"'"'s, in the MPI notes
tile --mca                mpirun'"'"'s
tile --allow-run-as-root  mpirun'"'"'s
tile -np                  mpirun'"'"'s
bench --oversubscribe     mpirun'"'"'s, in an example
bench --mca               mpirun'"'"'s
bench:--ring --machine    what --profile is called elsewhere
bench:--claims-map --claims  the mode whose judge it shares
bench:--calibrate --table-c  the options it measures and prints, not takes
bench:--calibrate --back-c
bench:--calibrate --o-send
bench:--calibrate --o-send-byte
bench:--calibrate --o-recv
bench:--calibrate --o-recv-byte
bench:--calibrate --L
bench:--calibrate --g
bench:--calibrate --G
bench:--calibrate --wake
bench:--calibrate --o-wake
bench:--calibrate --slowdown
bench:--calibrate --slowdown-spin
tilesim-mpirun --ranks    the machine option it refuses (-np gives the ranks)
tilesim-mpirun -o         tilesim-mpicc'"'"'s, in the examples
tilesim-mpirun --count-blocks  tilesim-mpicc'"'"'s, which --compute blocks needs
tilesim-mpirun --calibrate     tilesim-bench'"'"'s, which measures --block-c
tilesim-mpicc -I          the compiler'"'"'s, which the page says comes first
tilesim-mpicc --gc-sections  the linker'"'"'s, which the page says it passes
tilesim-mpicxx -I         the compiler'"'"'s
plot --claims-map         tilesim-bench'"'"'s, whose CSV it draws
plot --m                  tilesim-bench'"'"'s, in the example that makes a map
'
# Strings in the sources that look like options and are not tilesim's: the
# compiler flags tilesim-mpicc passes on or tests for (those that take a
# value, those it adds), MPICH's and Open MPI's one-dash names of -show
# and --showme:compile (which opts() cannot tell from words: the page has
# them), a pragma's warning, and mpirun's -np.
NOTOPTS='-MM -Wunused-parameter -fPIC -include -shared -np -D -L -MF -MQ -MT -T -U -e -l -u -z --param -aux-info
  -Xassembler -Xlinker -Xpreprocessor -idirafter -imacros -iprefix -iquote -isystem -fdata-sections
  -ffunction-sections -show -showme -compile-info -link-info -static -static-pie'
allowed() { printf '%s\n' "$ALLOW" | awk -v w="$1" '$1 == w { print $2 }' | sort -u; }

# The options a text names: --long, and -x alone (not -np, not x-y).
opts() {
  grep -oE -- '(^|[^A-Za-z0-9_-])--?[A-Za-z][A-Za-z0-9-]*' | sed -E 's/^[^-]*//; s/-+$//' |
    awk '/^--/ || length($0) == 2' | sort -u
}

# compare WHERE HELP PAGE: the options of HELP and PAGE (files of text)
# agree, less --help, -h and WHERE's allowed names.
compare() {
  allowed "$1" > "$T/allow"
  printf -- '--help\n-h\n' >> "$T/allow"
  opts < "$2" | grep -vxF -f "$T/allow" > "$T/in_help"
  opts < "$3" | grep -vxF -f "$T/allow" > "$T/in_page"
  miss=$(comm -23 "$T/in_help" "$T/in_page" | tr '\n' ' ')
  extra=$(comm -13 "$T/in_help" "$T/in_page" | tr '\n' ' ')
  [ -z "$miss" ] && ok || bad "$1: the help names options its page does not: $miss"
  [ -z "$extra" ] && ok || bad "$1: the page names options the help does not: $extra"
  [ -s "$T/in_page" ] && ok || bad "$1: no options found on the page"
}

# probe WHERE OPTIONS_FILE CMD...: every option is one CMD takes (CMD OPT
# --zz-no-such-option must not say "unknown option (OPT)" or "does not
# take (OPT)"; the sentinel makes it stop before any work).
probe() {
  where=$1; list=$2; shift 2
  for o in $(cat "$list"); do
    timeout 30 "$@" "$o" --zz-no-such-option > /dev/null 2> "$T/perr" < /dev/null
    if grep -qE "(unknown option|does not take) \\($o\\)" "$T/perr"; then
      bad "$where: the page names $o, which the program does not take: $(head -1 "$T/perr")"
    else ok; fi
  done
}

for p in "$TILE" "$BENCH" "$PLOT"; do
  need "$p" "make check builds it"
done

# ---- rendering and lint ----------------------------------------------------
BS=$(printf '\b')
if command -v mandoc > /dev/null 2>&1; then RENDER=mandoc
elif command -v groff > /dev/null 2>&1; then RENDER=groff
else RENDER=""; fi
render() {
  case $RENDER in
    mandoc) mandoc -Tascii -O width=1000 "$1" ;;
    groff) groff -mdoc -Tascii -P-cbou -rLL=1000n "$1" 2> /dev/null ;;
  esac | sed "s/.$BS//g"
}
PAGES="doc/tile.1 doc/tilesim-bench.1 doc/tilesim-plot.1 doc/tilesim-mpicc.1 doc/tilesim-mpicxx.1 doc/tilesim-mpirun.1 doc/tilesim.3 doc/tilesim-contours.5 doc/tilesim.7"
for pg in $PAGES; do [ -f "$pg" ] && ok || bad "$pg is missing"; done
# Every page in doc/ is one of those (a new page joins the checks here).
for pg in doc/*.[1-9]; do
  case " $PAGES " in *" $pg "*) ok ;; *) bad "$pg is not checked here: add it to PAGES" ;; esac
done

if [ "$RENDER" = mandoc ]; then
  for pg in $PAGES; do
    # Style messages count, but for cross-references to pages that are not
    # installed on this machine (ours, before make install; mpirun's).
    mandoc -Tlint -W style "$pg" 2> /dev/null | grep -v 'STYLE: referenced manual not found' > "$T/lint"
    [ ! -s "$T/lint" ] && ok || bad "mandoc -Tlint $pg: $(cat "$T/lint")"
  done
elif [ "$RENDER" = groff ]; then
  echo "cli_docs: skipped: mandoc -Tlint (mandoc is not installed: apt-get install mandoc); groff -ww checks the pages instead"
  for pg in $PAGES; do
    groff -mdoc -ww -z "$pg" > "$T/lint" 2>&1
    [ ! -s "$T/lint" ] && ok || bad "groff -mdoc -ww $pg: $(cat "$T/lint")"
  done
else
  echo "cli_docs: skipped: the man pages against the programs (neither mandoc nor groff is installed: apt-get install mandoc)"
fi

if [ -n "$RENDER" ]; then
  for pg in $PAGES; do render "$pg" > "$T/$(basename "$pg").txt"; done
  # A section of a rendered page: from its heading to the next one.
  section() { awk -v h="$2" '$0 == h { on = 1; next } on && /^[A-Z]/ { exit } on' "$1"; }
  # A subsection "   PREFIX...": to the next subsection or section.
  subsection() { awk -v h="   $2" 'index($0, h) == 1 { on = 1; next } on && (/^[A-Z]/ || /^   [^ ]/) { exit } on' "$1"; }

  # ---- tile ----
  "$TILE" --help > "$T/tile.help" 2>&1 && ok || bad "tile --help failed"
  compare tile "$T/tile.help" "$T/tile.1.txt"
  opts < "$T/tile.1.txt" | grep -vxF -f "$T/allow" > "$T/tile.opts"
  probe tile "$T/tile.opts" "$TILE"
  if [ -x "$MPIDIR/bin/tile-mpi" ] && [ "${MPI_STATUS:-}" = yes ]; then
    # One process: MPI singleton; only the help.
    OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 timeout 60 "$MPIDIR/bin/tile-mpi" --help > "$T/tmpi.help" 2> /dev/null \
      && ok || bad "tile-mpi --help failed"
    compare tile "$T/tmpi.help" "$T/tile.1.txt"
  fi

  # ---- bench: the sweep, then each mode, against its section ----
  "$BENCH" --help > "$T/bench.help" 2>&1 && ok || bad "bench --help failed"
  compare bench "$T/bench.help" "$T/tilesim-bench.1.txt"
  opts < "$T/tilesim-bench.1.txt" | grep -vxF -f "$T/allow" > "$T/all.opts"
  # The page names only options of some mode.
  opts < "$T/bench.help" > "$T/bench.helpopts"
  extra=$(comm -13 "$T/bench.helpopts" "$T/all.opts" | tr '\n' ' ')
  [ -z "$extra" ] && ok || bad "tilesim-bench.1 names options no mode takes: $extra"
  awk '/^  [^ ]+ \[--procs/ { on = 1 } on && /^$/ { exit } on' "$T/bench.help" > "$T/sweep.help"
  section "$T/tilesim-bench.1.txt" "THE PAPER'S EXPERIMENTS" > "$T/sweep.page"
  compare bench:sweep "$T/sweep.help" "$T/sweep.page"
  opts < "$T/sweep.page" | grep -vxF -f "$T/allow" > "$T/sweep.opts"
  probe bench:sweep "$T/sweep.opts" "$BENCH"
  awk '/^  [^ ]+ --[a-z-]+ / { print $2 }' "$T/bench.help" | sort > "$T/modes.help"
  section "$T/tilesim-bench.1.txt" MODES | awk '/^   --[a-z-]+:/ { sub(/:.*/, ""); sub(/^ +/, ""); print }' | sort > "$T/modes.page"
  [ "$(wc -l < "$T/modes.help")" -ge 10 ] && cmp -s "$T/modes.help" "$T/modes.page" && ok \
    || bad "bench --help's modes ($(tr '\n' ' ' < "$T/modes.help")) and the page's ($(tr '\n' ' ' < "$T/modes.page")) differ"
  for m in $(cat "$T/modes.help"); do
    "$BENCH" "$m" --help > "$T/mode.help" 2>&1 && grep -q "^usage: [^ ]* $m" "$T/mode.help" && ok \
      || bad "bench $m --help: $(head -1 "$T/mode.help")"
    section "$T/tilesim-bench.1.txt" MODES | subsection /dev/stdin "$m:" > "$T/mode.page"
    compare "bench:$m" "$T/mode.help" "$T/mode.page"
    opts < "$T/mode.page" | grep -vxF -f "$T/allow" | grep -vxF -- "$m" > "$T/mode.opts"
    case $m in   # what comes before the options in a command line
      --ring) pre="--ring 2 --laps 1" ;;
      --switch) pre="--switch 2" ;;
      --claims) pre="--claims x.csv" ;;
      *) pre=$m ;;
    esac
    # shellcheck disable=SC2086
    probe "bench:$m" "$T/mode.opts" "$BENCH" $pre
  done

  # ---- plot: each option is taken by one of its modes ----
  "$PLOT" --help > "$T/plot.help" 2>&1 && ok || bad "plot --help failed"
  compare plot "$T/plot.help" "$T/tilesim-plot.1.txt"
  opts < "$T/tilesim-plot.1.txt" | grep -vxF -f "$T/allow" > "$T/plot.opts"
  for o in $(cat "$T/plot.opts"); do
    taken=0
    for m in "lines x.csv" "surface x.contours" "claims x.csv"; do
      # shellcheck disable=SC2086
      timeout 30 "$PLOT" $m "$o" --zz-no-such-option > /dev/null 2> "$T/perr" < /dev/null
      grep -qE "(unknown option|does not take) \\($o\\)" "$T/perr" || taken=1
    done
    [ $taken -eq 1 ] && ok || bad "plot: the page names $o, which no mode of plot takes"
  done

  # ---- tilesim-mpicc, tilesim-mpicxx, tilesim-mpirun ----
  "$BUILD/tilesim-mpicc" --help > "$T/mpicc.help" 2>&1 && ok || bad "tilesim-mpicc --help failed"
  compare tilesim-mpicc "$T/mpicc.help" "$T/tilesim-mpicc.1.txt"
  "$BUILD/tilesim-mpicxx" --help > "$T/mpicxx.help" 2>&1 && ok || bad "tilesim-mpicxx --help failed"
  compare tilesim-mpicxx "$T/mpicxx.help" "$T/tilesim-mpicxx.1.txt"
  "$BUILD/tilesim-mpirun" --help > "$T/mpirun.help" 2>&1 && ok || bad "tilesim-mpirun --help failed"
  compare tilesim-mpirun "$T/mpirun.help" "$T/tilesim-mpirun.1.txt"
  opts < "$T/tilesim-mpirun.1.txt" | grep -vxF -f "$T/allow" > "$T/mpirun.opts"
  probe tilesim-mpirun "$T/mpirun.opts" "$BUILD/tilesim-mpirun"

  # ---- tilesim(7), tilesim-contours(5): options some program takes ----
  # A program of one's own on tilesim.h takes the machine's options and its own (--ranks, --stats).
  EXAMPLE=$BUILD/examples/ring
  [ -x "$EXAMPLE" ] || EXAMPLE=build/examples/ring
  "$EXAMPLE" --help > "$T/lib.help" 2>&1 && ok || bad "$EXAMPLE --help failed"
  cat "$T/tile.help" "$T/bench.help" "$T/plot.help" "$T/lib.help" "$T/mpirun.help" "$T/mpicc.help" | opts > "$T/any.opts"
  for pg in tilesim.7 tilesim-contours.5; do
    extra=$(opts < "$T/$pg.txt" | comm -13 "$T/any.opts" - | tr '\n' ' ')
    [ -z "$extra" ] && ok || bad "$pg names options no program takes: $extra"
  done

  # ---- the sources: every option string is on some page ----
  cat "$T"/*.[1357].txt | opts > "$T/documented"
  for d in util mp sim machine mpi mpirun algo input surface run prog plots; do ls "$d"/*.c 2> /dev/null; done > "$T/sources"
  xargs grep -ohE '"--?[A-Za-z][A-Za-z0-9-]*"' < "$T/sources" | tr -d '"' | sort -u > "$T/literals"
  printf '%s\n' $NOTOPTS | sort > "$T/notopts"
  missing=$(comm -23 "$T/literals" "$T/documented" | comm -23 - "$T/notopts" | tr '\n' ' ')
  [ -z "$missing" ] && ok || bad "options in the sources that no page documents: $missing"
fi

# ---- README: short, and every file it names exists ----
n=$(wc -l < README.md)
[ "$n" -lt 200 ] && ok || bad "README.md has $n lines (under 200)"
# Files it names: link targets, and inline code that is a path in the tree
# (outside fenced blocks, which hold example commands and their outputs).
awk '/^```/ { f = !f; next } !f' README.md > "$T/readme"
{ grep -oE '\]\([^)#]+' "$T/readme" | sed 's/^](//' | grep -vE '^[a-z]+:'
  grep -oE '`[a-z][A-Za-z0-9_.-]*/[A-Za-z0-9_./-]*`' "$T/readme" | tr -d '`' | grep -v '^build/'
} | sed 's,/$,,' | sort -u > "$T/named"
[ "$(wc -l < "$T/named")" -ge 10 ] && ok || bad "README.md names fewer than 10 files (the check found $(wc -l < "$T/named"))"
for f in $(cat "$T/named"); do
  [ -e "$f" ] && ok || bad "README.md names $f, which does not exist"
done

# The claims README.md shows as make bench prints them begin as plots/claims.csv's
# lines do (up to the "..." that cuts them short).
grep -E '^"[1-7] ' README.md | sed 's/ *\.\.\.".*$//' > "$T/readme_claims"
[ -s "$T/readme_claims" ] && ok || bad "README.md shows no line of plots/claims.csv"
while IFS= read -r l; do
  grep -qF -- "$l" plots/claims.csv && ok || bad "README.md shows a claim as plots/claims.csv does not: $l"
done < "$T/readme_claims"

# The documents' links, relative to doc/, lead to files.
for md in doc/*.md; do
  for f in $(grep -oE '\]\([^)#]+' "$md" | sed 's/^](//' | grep -vE '^[a-z]+:' | sort -u); do
    [ -e "doc/$f" ] && ok || bad "$md links to $f, which does not exist"
  done
done

# ---- the verdicts doc/paper.md quotes equal make bench's ----
# The table after "<!-- verdicts: GEN.csv REAL.csv -->": rows "| N | ... |
# GEN | REAL |", holds / fails / n/a against the CSVs' yes / no / n/a.
verdicts() { sed -n -E '2,$ s/^"([1-7]) [^"]*",([^,]*),.*/\1 \2/p' "$1"; }
marker=$(grep -m 1 '^<!-- verdicts: ' doc/paper.md)
gen=$(echo "$marker" | awk '{ print $3 }'); real=$(echo "$marker" | awk '{ print $4 }')
if [ -f "$gen" ] && [ -f "$real" ]; then
  awk '/^<!-- verdicts: / { on = 1; next } on && /^\| [1-7] \|/ { print; seen = 1 } on && seen && /^$/ { exit }' doc/paper.md |
    awk -F'|' '{ for (i = 2; i <= NF; i++) gsub(/^ +| +$/, "", $i)
                 v["holds"] = "yes"; v["fails"] = "no"; v["n/a"] = "n/a"
                 print $2, v[$(NF - 2)], v[$(NF - 1)] }' > "$T/quoted"
  verdicts "$gen" > "$T/g"; verdicts "$real" > "$T/r"
  join "$T/g" "$T/r" > "$T/csv"
  [ "$(wc -l < "$T/quoted")" -eq 7 ] && cmp -s "$T/quoted" "$T/csv" && ok \
    || bad "doc/paper.md's verdicts differ from $gen and $real: $(diff "$T/quoted" "$T/csv" | tr '\n' ' ')"
else bad "doc/paper.md: no '<!-- verdicts: GEN.csv REAL.csv -->' table, or its CSVs are missing"; fi
# The map: rows "| PAIR | M/C | c1 .. c7 |" after "<!-- claims-map: MAP.csv -->",
# PAIR "seed N" or "STACK pair K"; each against the row of the CSV.
map=$(grep -m 1 '^<!-- claims-map: ' doc/paper.md | awk '{ print $3 }')
if [ -f "$map" ]; then
  awk '/^<!-- claims-map: / { on = 1; next } on && /^\| (seed|[a-z0-9_.\/]+ pair) / { print; seen = 1 } on && seen && /^$/ { exit }' doc/paper.md |
    awk -F'|' '{ for (i = 2; i <= NF; i++) gsub(/^ +| +$/, "", $i)
                 s = $2; sub(/^seed /, "generated n/a ", s); sub(/ pair /, " ", s)
                 line = s " " $3; for (i = 4; i <= 10; i++) line = line " " $i; print line }' | sort > "$T/qmap"
  awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
           { n = split($c["input"], part, "/"); b = part[n]; sub(/\.contours$/, "", b)
             id = ($c["input"] == "generated") ? "generated n/a " $c["seed"] : b " " $c["pair"]
             line = id " " $c["m_over_c"]; for (k = 1; k <= 7; k++) line = line " " $c["claim" k]; print line }' "$map" |
    sort > "$T/cmap"
  [ "$(wc -l < "$T/qmap")" -ge 5 ] && cmp -s "$T/qmap" "$T/cmap" && ok \
    || bad "doc/paper.md's claims map differs from $map: $(diff "$T/qmap" "$T/cmap" | tr '\n' ' ')"
else bad "doc/paper.md: no '<!-- claims-map: MAP.csv -->' table, or its CSV is missing"; fi

summary

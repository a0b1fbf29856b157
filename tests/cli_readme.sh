#!/bin/sh
# cli_readme.sh -- every command README.md shows under "Examples" and
# "Installing" works, in order, on a fresh clone after make: each exits 0
# and makes the files it names with -o.  The clone is a folder of links to
# the tree's files and to make's programs where make puts them (./tile,
# ./bench, build/plot, build/include, build/rel/lib/libtilesim.a), here
# make check's sanitized build (cc adds the sanitizers to link with its
# library); "make" itself is taken as done, "make install PREFIX=P" installs
# into a folder of the test's own (make install-files, as cli_install.sh
# does), and the commands after it see P's pkg-config file as the README
# says they need (PKG_CONFIG_PATH=P/lib/pkgconfig).
BUILD=${BUILD:-build/chk}
ROOT=$(pwd)
. tests/clilib.sh
mk() { env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make --no-print-directory -s -C "$ROOT" "$@"; }

S=$T/clone
mkdir -p "$S/build/rel/lib"
for f in "$ROOT"/* "$ROOT"/.[!.]*; do   # the tree, less what make writes
  case ${f##*/} in build|tile|bench|tilesim-mpicc|tilesim-mpirun|*-mpi|'.[!.]*') ;; *) ln -s "$f" "$S/${f##*/}" ;; esac
done
for p in tile bench tilesim-mpicc tilesim-mpirun; do ln -sf "$ROOT/$BUILD/$p" "$S/$p"; done
ln -s "$ROOT/$BUILD/plot" "$S/build/plot"
ln -s "$ROOT/build/include" "$S/build/include"
ln -s "$ROOT/$BUILD/lib/libtilesim.a" "$S/build/rel/lib/libtilesim.a"
case $BUILD in */rel) SAN="" ;; *) SAN="-fsanitize=address,undefined -fno-omit-frame-pointer" ;; esac

# The fenced sh blocks of a section, a command a line.
block() {
  awk -v h="## $1" '$0 == h { on = 1; next } on && /^## / { exit }
                    on && /^```sh$/ { f = 1; next } on && /^```$/ { f = 0; next } on && f' "$ROOT/README.md"
}
block Examples > "$T/examples"
block Installing > "$T/installing"
[ "$(grep -c . "$T/examples")" -ge 8 ] && ok || bad "README.md's Examples show $(grep -c . "$T/examples") commands"
grep -q '^make install PREFIX=' "$T/installing" && ok || bad "README.md's Installing has no make install PREFIX=..."

# run FILE: each command in the clone, in order, in one shell (cc builds
# with the sanitizers, PKG_CONFIG_PATH as set).
run() {
  while IFS= read -r line; do
    case $line in
      make) ok; continue ;;   # done: the clone has make's programs
      "make install PREFIX="*)
        P=$T/prefix
        mk install-files PREFIX="$P" IBIN="$ROOT/$BUILD" IPLOT="$ROOT/$BUILD/plot" \
          ILIB="$ROOT/$BUILD/lib/libtilesim.a" > "$T/log" 2>&1 && ok || bad "'$line': $(cat "$T/log")"
        export PKG_CONFIG_PATH="$P/lib/pkgconfig"
        continue ;;
    esac
    ( cd "$S" && cc() { command "${CC:-cc}" $SAN "$@"; } && eval "$line" ) > "$T/out" 2>&1; rc=$?
    [ $rc -eq 0 ] && ok || bad "'$line': exit $rc: $(tail -n 5 "$T/out")"
    for o in $(echo "$line" | grep -oE -- '-o [^ ]+' | cut -c4-); do
      [ -s "$S/$o" ] && ok || bad "'$line' made no $o"
    done
  done < "$1"
}
run "$T/examples"
grep -q '^pi is 3.14159265358' "$T/out" && ok || bad "the MPI example's answer: $(cat "$T/out")"
if command -v pkg-config > /dev/null 2>&1; then
  rm -f "$S/ring"
  run "$T/installing"
  [ -x "$S/ring" ] && ok || bad "Installing: ring was not built through pkg-config"
else
  echo "cli_readme: skipped: README's Installing commands (pkg-config not found: apt-get install pkgconf)"
fi

summary

#!/bin/sh
# cli_pages.sh -- the man pages' text as a reader meets it (cli_docs.sh holds
# their options against the programs):
#  - every cell of a .Bl -column table but a row's last fits its column's
#    width string, so that no two columns run together on a terminal
#    ("275 us per messagea locked enqueue");
#  - every paragraph (.Pp) that opens with text opens a sentence: a capital
#    letter, a digit or a quote, never a fragment;
#  - the literal examples of tilesim-contours(5) that say which contour lies
#    above which ("# a triangle above a square") are stacks ./tile reads, and
#    the contour named above is the one with the larger z (the band's upper
#    contour: n points).
BUILD=${BUILD:-build/chk}
TILE=$BUILD/tile
. tests/clilib.sh

PAGES=$(ls doc/*.[1-9])
[ -n "$PAGES" ] && ok || bad "no man pages in doc/"

# ---- tables: "FILE:LINE: cell 'TEXT' (N characters) is wider than its column (W)" ----
# A cell's printed width: the words left once mdoc's macro names (Sy, Cm,
# Ar, ...) and quotes are taken out; Fl adds its dash, Ql two quotes.
for pg in $PAGES; do
  awk -v F="$pg" '
    function words(s,   n, i, a, out, w) {
      n = split(s, a, /[ \t]+/); out = ""
      for (i = 1; i <= n; i++) {
        w = a[i]
        if (w == "") continue
        if (w ~ /^(Sy|Cm|Ar|Li|Em|Dq|Pa|Va|Ev|Ic|Nm|No|Ns|Sq|Pq|Xr|Dv|Er|Fn|Fa|Ft|Cd|Ms|Tn)$/) continue
        if (w == "Fl") { pending = "-"; continue }
        if (w == "Ql") { out = out (out == "" ? "" : " ") "\047\047"; continue }
        out = out (out == "" ? "" : " ") pending w; pending = ""
      }
      gsub(/"/, "", out); gsub(/\\&/, "", out); gsub(/\\e/, "\\", out)
      return out
    }
    /^\.Bl / && / -column / {
      on = 1; nw = 0; s = $0; sub(/^\.Bl +-column +/, "", s)
      while (s != "") {
        if (s ~ /^-/) break
        if (s ~ /^"/) { match(s, /^"[^"]*"/); w[++nw] = substr(s, 2, RLENGTH - 2); s = substr(s, RLENGTH + 1) }
        else { match(s, /^[^ ]+/); w[++nw] = substr(s, 1, RLENGTH); s = substr(s, RLENGTH + 1) }
        sub(/^ +/, "", s)
      }
      next
    }
    on && /^\.El/ { on = 0; next }
    on && /^\.It / {
      row = substr($0, 5); n = split(row, cell, / Ta |\t/)
      for (i = 1; i < n && i <= nw; i++) {
        c = words(cell[i])
        if (length(c) > length(w[i]))
          printf "%s:%d: cell \047%s\047 (%d characters) is wider than its column (\047%s\047, %d)\n", F, NR, c, length(c), w[i], length(w[i])
      }
    }' "$pg" > "$T/cols"
  [ ! -s "$T/cols" ] && ok || bad "$(cat "$T/cols")"
done

# ---- paragraphs open sentences ----
for pg in $PAGES; do
  awk -v F="$pg" 'prev == ".Pp" && $0 !~ /^\./ && $0 !~ /^[A-Z0-9(`"\\]/ { printf "%s:%d: a paragraph opens with a fragment: %s\n", F, NR, $0 }
                  { prev = $1 }' "$pg" > "$T/pp"
  [ ! -s "$T/pp" ] && ok || bad "$(cat "$T/pp")"
done

# ---- "# a X above a Y" in tilesim-contours(5): X is the upper contour ----
points_of() {
  case $1 in triangle) echo 3 ;; square) echo 4 ;; pentagon) echo 5 ;; hexagon) echo 6 ;; *) echo 0 ;; esac
}
awk '/^\.Bd -literal/ { on = 1; k++; next } /^\.Ed/ { on = 0 } on { print > ("'"$T"'/ex" k) }' doc/tilesim-contours.5
seen=0
for ex in "$T"/ex*; do
  claim=$(grep -m 1 -E '^# an? [a-z]+ above an? [a-z]+' "$ex") || continue
  seen=$((seen + 1))
  up=$(points_of "$(echo "$claim" | awk '{ print $3 }')")
  down=$(points_of "$(echo "$claim" | awk '{ print $6 }')")
  if ! "$TILE" - < "$ex" > "$T/out" 2> "$T/err"; then
    bad "tilesim-contours.5's example '$claim' is refused: $(cat "$T/err")"
    continue
  fi
  # The band row: m points on the lower contour (z0), n on the upper (z1).
  got=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next } $1 == "0" { print $c["m"], $c["n"]; exit }' "$T/out")
  [ "$got" = "$down $up" ] && ok || bad "tilesim-contours.5: '$claim', but tile puts $(echo "$got" | awk '{ print $1 }') points below and $(echo "$got" | awk '{ print $2 }') above"
done
[ $seen -ge 1 ] && ok || bad "tilesim-contours.5 has no example saying which contour lies above which"

summary

#!/bin/sh
# layers.sh [ROOT [TABLE]] -- check the tree's #include lines against its
# layers (TABLE, default ROOT/tests/layers.txt, says what is allowed and how
# names are found).  Reads every .c and .h below ROOT but build/ and hidden
# folders, and each #include "..." or <...> in them that names a file of the
# tree; prints one line per fault and exits 1 if there is any:
#   FILE:LINE: includes HEADER: FOLDER may not include FOLDER
#   FILE: in no layer (FOLDER has no line in TABLE)
#   cycle: FILE -> ... -> FILE            (files of different folders)
#   cycle: FOLDER -> ... -> FOLDER        (folders, through allowed includes)
#   FILE:LINE: includes HEADER: HEADER is private to FOLDER FOLDER...
#   TABLE:LINE: ...                       (a stale exception, a bad line)
# and on success one line: "layers: N files, N includes, N across folders,
# N exceptions".  Exit 2 for bad usage.
root=${1:-.}
table=${2:-$root/tests/layers.txt}
[ -d "$root" ] || { echo "layers: $root: not a folder" >&2; exit 2; }
[ -r "$table" ] || { echo "layers: $table: cannot read the table" >&2; exit 2; }
T=$(mktemp -d /tmp/tilesim-layers.XXXXXX) || exit 2
trap 'rm -rf "$T"' EXIT
(cd "$root" && find . -name build -prune -o -name '.?*' -prune -o \
  -type f \( -name '*.c' -o -name '*.h' \) -print) | sed 's|^\./||' | LC_ALL=C sort > "$T/files"
# Every include line: FILE:LINE:TEXT.
(cd "$root" && tr '\n' '\0' < "$T/files" | xargs -0 grep -n -H -E \
  '^[[:space:]]*#[[:space:]]*include[[:space:]]*[<"]' /dev/null) > "$T/incs"
LC_ALL=C awk -v table="$table" '
function err(s) { print s; nerr++ }
# The path a/b/../c/./d.h as c/d.h; "" if it climbs out of the tree.
function norm(p,    n, i, k, part, out) {
  n = split(p, part, "/"); k = 0
  for (i = 1; i <= n; i++) {
    if (part[i] == "" || part[i] == ".") continue
    if (part[i] == "..") { if (k == 0) return ""; k--; continue }
    out[++k] = part[i]
  }
  p = ""
  for (i = 1; i <= k; i++) p = p (i > 1 ? "/" : "") out[i]
  return p
}
function dir(p) { return sub(/\/[^\/]*$/, "", p) ? p : "." }
# The folder of the table that holds a file: its longest FOLDER line.
function layer(f,    d) {
  for (d = dir(f); ; d = dir(d)) {
    if (d in allow) return d
    if (d == ".") return ""
  }
}
function may(a, b, f,    n, i, w) {
  n = split(allow[a], w, " ")
  for (i = 1; i <= n; i++)
    if (w[i] == "*" || w[i] == b || w[i] == f) return 1
  return 0
}
# The file a name resolves to for file f ("" if none in the tree).
function resolve(f, name, quoted,    p, n, i, s, w) {
  if (quoted && (p = norm(dir(f) "/" name)) != "" && p in isfile) return p
  n = split(search[""], w, " ")
  for (i = 1; i <= n; i++) if ((p = norm(w[i] "/" name)) != "" && p in isfile) return p
  for (s in search) {
    if (s == "" || index(f, s) != 1) continue
    n = split(search[s], w, " ")
    for (i = 1; i <= n; i++) if ((p = norm(w[i] "/" name)) != "" && p in isfile) return p
  }
  return ""
}
# Is there a path of includes from a to b?  (Breadth first.)
function reaches(a, b,    q, head, tail, seen, x, i, n, w) {
  head = 1; tail = 0; q[++tail] = a; seen[a] = 1
  while (head <= tail) {
    x = q[head++]
    if (x == b) { pathto(b, seen, a); return 1 }
    n = split(out[x], w, " ")
    for (i = 1; i <= n; i++)
      if (!(w[i] in seen)) { seen[w[i]] = x; q[++tail] = w[i] }
  }
  return 0
}
function pathto(b, seen, a,    x, s) {
  s = b
  for (x = b; x != a; x = seen[x]) s = seen[x] " -> " s
  route = s
}
BEGIN {
  while ((getline line < table) > 0) {
    tl++
    sub(/#.*/, "", line)
    if (line ~ /^[ \t]*$/) continue
    if (line ~ /^except[ \t]/) {
      if (split(line, w, /[ \t]+/) != 4 || w[3] != "->") { err(table ":" tl ": except FILE -> FILE"); continue }
      exc[w[2] " " w[4]] = tl; nexc++
      continue
    }
    if (line ~ /^private[ \t]/) {
      if (index(line, ":") == 0) { err(table ":" tl ": private FILE: FOLDER..."); continue }
      pf = substr(line, 9, index(line, ":") - 9); gsub(/[ \t]/, "", pf)
      pv = " " substr(line, index(line, ":") + 1) " "; gsub(/[ \t]+/, " ", pv)
      priv[pf] = pv   # " FOLDER ... "
      continue
    }
    if (line ~ /^search[ \t:]/) {
      if (index(line, ":") == 0) { err(table ":" tl ": search PREFIX...: DIR..."); continue }
      pre = substr(line, 7, index(line, ":") - 7); dirs = substr(line, index(line, ":") + 1)
      if (split(pre, w, /[ \t]+/) == 0 || pre ~ /^[ \t]*$/) search[""] = search[""] " " dirs
      else for (i in w) if (w[i] != "") search[w[i]] = search[w[i]] " " dirs
      continue
    }
    if (line !~ /^[^ \t:]+:/) { err(table ":" tl ": not FOLDER: NAME..."); continue }
    d = substr(line, 1, index(line, ":") - 1)
    allow[d] = substr(line, index(line, ":") + 1); folders[++nf] = d
  }
  close(table)
  if (nf == 0) err(table ": no folders")
}
FILENAME == ARGV[1] { isfile[$0] = 1; nfiles++; next }
{
  # FILE:LINE:#include ...
  f = $0; sub(/:.*/, "", f)
  rest = substr($0, length(f) + 2); ln = rest; sub(/:.*/, "", ln)
  text = substr(rest, length(ln) + 2)
  if (match(text, /"[^"]*"/)) { name = substr(text, RSTART + 1, RLENGTH - 2); q = 1 }
  else if (match(text, /<[^>]*>/)) { name = substr(text, RSTART + 1, RLENGTH - 2); q = 0 }
  else next
  h = resolve(f, name, q)
  if (h == "" || h == f) next
  nincs++
  if (index(" " out[f] " ", " " h " ") == 0) out[f] = out[f] " " h
  a = layer(f); b = layer(h)
  if (a == "") { if (!(f in nolayer)) err(f ": in no layer (" dir(f) " has no line in " table ")"); nolayer[f] = 1; next }
  if (b == "") next   # said for h itself
  if (dir(f) != dir(h)) cross[f " " h] = 1
  if (a == b) next
  ncross++
  if ((h in priv) && index(priv[h], " " a " ") == 0) {
    if ((f " " h) in exc) { used[f " " h] = 1; next }
    err(f ":" ln ": includes " h ": " h " is private to " b substr(priv[h], 1, length(priv[h]) - 1)); next
  }
  if (may(a, b, h)) { fedge[a " " b] = 1; next }
  if ((f " " h) in exc) { used[f " " h] = 1; next }
  err(f ":" ln ": includes " h ": " a " may not include " b)
}
END {
  for (f in isfile) if (layer(f) == "" && !(f in nolayer)) err(f ": in no layer (" dir(f) " has no line in " table ")")
  for (k in exc) if (!(k in used)) {
    split(k, w, " ")
    err(table ":" exc[k] ": except " w[1] " -> " w[2] ": no longer occurs (remove the line)")
  }
  # Cycles of files through different folders: an include across folders
  # that the included file reaches back to.
  for (k in cross) {
    split(k, w, " ")
    if (reaches(w[2], w[1]) && !(route in saidcycle)) { saidcycle[route] = 1; err("cycle: " w[1] " -> " route) }
  }
  # Cycles of folders through includes the rules allow (not the exceptions).
  for (k in fedge) { split(k, w, " "); fout[w[1]] = fout[w[1]] " " w[2] }
  for (k in fedge) {
    split(k, w, " ")
    delete seen; head = 1; tail = 0; qq[++tail] = w[2]; seen[w[2]] = w[1]; found = 0
    while (head <= tail && !found) {
      x = qq[head++]
      if (x == w[1]) { found = 1; break }
      n = split(fout[x], v, " ")
      for (i = 1; i <= n; i++) if (!(v[i] in seen)) { seen[v[i]] = x; qq[++tail] = v[i] }
    }
    if (found) {
      s = w[1]; for (x = w[1]; x != w[2]; x = seen[x]) s = seen[x] " -> " s
      s = w[1] " -> " s
      if (!(w[1] in saidf)) { saidf[w[1]] = 1; err("cycle: " s " (folders)") }
    }
  }
  if (nerr) exit 1
  printf "layers: %d files, %d includes, %d across folders, %d exceptions\n", nfiles, nincs, ncross, nexc
}' "$T/files" "$T/incs"

#!/usr/bin/env bash
# The module rule, checked (docs/design-notes.md, "Where things go"; registered by
# tests/module_rule.cmake, label `architecture`).
#   usage: tests/module_rule.sh SOURCE_DIR BUILD_DIR      (BUILD_DIR: a built CMake tree)
#
# Modules: each core/<subdir> and each core/<file stem> (core/app.c + core/app.h = core/app),
# each plugins/<name>, tools/<name> and extras/<name>, sdk, sdk/example (a plugin). Tests
# (tests/, any */tests/ folder) are white-box and belong to no module: they are never offenders.
# Public files: sdk/include/**, a plugin's, tool's or extra's include/** folder (the documented
# API of a library it exports for tools, e.g. plugins/envmap/include/envmap/*.h), and the
# documented headers of the core's internal libraries listed in PUBLIC_HEADERS below.
#
# It reads the sources' #include lines, the CMake source lists (add_library, add_executable,
# target_sources, shadelab_add_plugin in the modules' CMake files), the build's per-target
# include paths, dependency files and object files (CMakeFiles/<target>.dir/), and the symbols
# each object defines and uses (nm). It FAILS when
#   1. a plugin, extra or tool includes another module's private file (resolved as the compiler
#      does: the including file's folder, then the include path of the targets compiling it),
#      or compiles one (a source of its targets, by the CMake lists and by the objects built);
#      the core including or compiling a file of a plugin, tool or extra fails too;
#   2. a plugin's or tool's object uses a symbol defined only in another plugin's, tool's or
#      extra's objects and not declared in that module's public headers (and likewise for the
#      core's objects: the core never calls up into a tool);
#   3. a cycle between the core's modules, from #include edges and from nm edges (an object's
#      undefined symbol -> the core object defining it), listed with the files behind it.
#   4. a GLSL #include of another plugin's file: shared GLSL is an SDK contract (the shader
#      library, `#include "sl:NAME"`, e.g. sl:ggx_brdf.glsl).
# Exit status: 0 when the enforced rules hold, 1 when one is broken, 2 on bad usage.
set -euo pipefail
if [ $# -ne 2 ]; then echo "usage: $0 SOURCE_DIR BUILD_DIR" >&2; exit 2; fi
SRC=$(cd "$1" && pwd -P) || { echo "module_rule: no source directory $1" >&2; exit 2; }
BUILD=$(cd "$2" && pwd -P) || { echo "module_rule: no build directory $2" >&2; exit 2; }
NM=${NM:-nm}
T=$(mktemp -d "${TMPDIR:-/tmp}/shadelab-module-rule.XXXXXX")
trap 'rm -rf "$T"' EXIT

# Documented public headers of the core's internal libraries (each says so in its first lines):
#   core/toolkit/toolkit.h      shadelab_toolkit: the core as tools see it
#   core/quality/autoquality.h  shadelab_quality: --auto-quality, shared by the viewer and the bench
PUBLIC_HEADERS="core/toolkit/toolkit.h core/quality/autoquality.h"

# The source directory as this build tree's CMake spelled it (a symlinked path, say).
CMSRC=$(sed -n 's/^CMAKE_HOME_DIRECTORY:INTERNAL=//p' "$BUILD/CMakeCache.txt" 2>/dev/null || true)

# ---- the source tree's files (build trees inside it left out) -------------------------------
prune=()
while IFS= read -r c; do
  prune+=(-path "$(dirname "$c")" -prune -o)
done < <(find "$SRC" -mindepth 2 -maxdepth 4 -name CMakeCache.txt 2>/dev/null)
find "$SRC" -path "$SRC/.git" -prune -o "${prune[@]}" -type f -print | sed "s|^$SRC/||" | LC_ALL=C sort >"$T/files"
grep -E '\.(c|h|cc|cpp|cxx|hh|hpp|glsl|frag|vert|geom|comp)$' "$T/files" >"$T/code" || true
(cd "$SRC" && xargs -d '\n' -r grep -HnE '^[[:space:]]*#[[:space:]]*include[[:space:]]*[<"]' <"$T/code" || true) >"$T/includes"
# identifiers of the public headers of plugins, tools and extras (what rule 2 lets others call)
grep -E '^(plugins|tools|extras)/[^/]+/include/' "$T/code" >"$T/pubheaders" || true
(cd "$SRC" && xargs -d '\n' -r grep -oHE '[A-Za-z_][A-Za-z0-9_]*' <"$T/pubheaders" || true) | LC_ALL=C sort -u >"$T/pubids"
# the CMake files of the modules that may not reach into others
grep -E '^(plugins|tools|extras)/.*(CMakeLists\.txt|\.cmake)$' "$T/files" | sed "s|^|$SRC/|" >"$T/cmakefiles" || true
mapfile -t cmakefiles <"$T/cmakefiles" # one per line: a checkout's path may hold spaces

# ---- the build: target folders, include paths, dependency files, symbols --------------------
if [ -f "$BUILD/CMakeFiles/TargetDirectories.txt" ]; then
  cat "$BUILD/CMakeFiles/TargetDirectories.txt"
else # not a Makefile tree: every CMakeFiles/*.dir outside nested build trees
  find "$BUILD" -type d -path '*/CMakeFiles/*.dir' | while IFS= read -r d; do
    top=${d%%/CMakeFiles/*}
    if [ "$top" = "$BUILD" ] || [ ! -f "$top/CMakeCache.txt" ]; then echo "$d"; fi
  done
fi | while IFS= read -r d; do if [ -d "$d" ]; then echo "$d"; fi; done >"$T/tdirs"
: >"$T/flags" ; : >"$T/deps" ; : >"$T/objs"
if [ -s "$T/tdirs" ]; then
  sed 's|$|/flags.make|' "$T/tdirs" | while IFS= read -r f; do if [ -f "$f" ]; then echo "$f"; fi; done \
    | xargs -d '\n' -r awk '/^(C|CXX)_INCLUDES = /{ d = FILENAME; sub(/\/flags\.make$/, "", d); print d "\t" substr($0, index($0, "=") + 2) }' >"$T/flags"
  xargs -d '\n' -r sh -c 'find "$@" -name "*.o"' find <"$T/tdirs" | LC_ALL=C sort -u >"$T/objs"
  # dependency files: OBJECT <tab> SOURCE <tab> every file it read (first rule only)
  sed 's|$|.d|' "$T/objs" | while IFS= read -r f; do if [ -f "$f" ]; then echo "$f"; fi; done \
    | xargs -d '\n' -r awk '
        FNR == 1 { if (out != "") print out; out = ""; n = 0; done = 0; obj = FILENAME; sub(/\.d$/, "", obj) }
        done { next }
        { line = $0; cont = sub(/\\$/, "", line)
          m = split(line, w, /[ \t]+/)
          for (i = 1; i <= m; i++) {
            if (w[i] == "") continue
            if (w[i] ~ /:$/) { if (n > 0 || out != "") { done = 1; break } ; continue }
            n++; out = (n == 1 ? obj "\t" w[i] : out "\t" w[i])
          }
          if (!cont && n > 0) done = 1 }
        END { if (out != "") print out }' >"$T/deps"
  xargs -d '\n' -r "$NM" -A -g <"$T/objs" 2>/dev/null >"$T/nm" || true
fi
[ -f "$T/nm" ] || : >"$T/nm"

# ---- the check --------------------------------------------------------------------------------
awk -v SRC="$SRC" -v CMSRC="$CMSRC" -v BUILD="$BUILD" -v PUBLIC_HEADERS="$PUBLIC_HEADERS" -f - \
    sec=files "$T/files" sec=inc "$T/includes" sec=pubids "$T/pubids" sec=tdirs "$T/tdirs" \
    sec=flags "$T/flags" sec=deps "$T/deps" sec=nm "$T/nm" sec=cmake "${cmakefiles[@]}" <<'AWK'
function norm(p,   a, n, i, k, out, res) {
  n = split(p, a, "/"); k = 0
  for (i = 1; i <= n; i++) {
    if (a[i] == "" && i > 1) continue
    if (a[i] == ".") continue
    if (a[i] == ".." && k > 0 && out[k] != ".." && out[k] != "") { k--; continue }
    out[++k] = a[i]
  }
  res = ""
  for (i = 1; i <= k; i++) res = res (i > 1 ? "/" : "") out[i]
  return res
}
# absolute path -> SRC-relative path, "@b/…" inside the build tree, "" elsewhere
function rel(p) {
  p = norm(p)
  if (index(p, BUILD "/") == 1) return "@b/" substr(p, length(BUILD) + 2)
  if (index(p, SRC "/") == 1) return substr(p, length(SRC) + 2)
  if (CMSRC != "" && index(p, CMSRC "/") == 1) return substr(p, length(CMSRC) + 2)
  return ""
}
function dirname(p) { if (p !~ /\//) return ""; sub(/\/[^\/]*$/, "", p); return p }
function module_of(r,   a, n, s) {
  if (r ~ /^@b\//) return "(generated)"
  n = split(r, a, "/")
  if (a[1] == "sdk") return (a[2] == "example" && n > 2) ? "sdk/example" : "sdk"
  if (a[1] == "core") { if (n == 2) { s = a[2]; sub(/\.[^.]*$/, "", s); return "core/" s } return "core/" a[2] }
  if (a[1] == "plugins" || a[1] == "tools" || a[1] == "extras") return n > 2 ? a[1] "/" a[2] : a[1]
  if (n == 1) return "(top)"
  return a[1]
}
function kind_of(m) {
  if (m == "sdk/example" || m ~ /^plugins\//) return "plugin"
  if (m ~ /^tools\//) return "tool"
  if (m ~ /^extras\//) return "extra"
  if (m ~ /^core\//) return "core"
  if (m == "sdk") return "sdk"
  if (m == "tests") return "test"
  return "other"
}
function guarded(k) { return k == "plugin" || k == "tool" || k == "extra" }
function is_test(r) { return r ~ /(^|\/)tests\// }
function is_public(r) { return r ~ /^sdk\/include\// || r ~ /^(plugins|tools|extras)\/[^\/]+\/include\// || (r in PUB) }
function is_glsl(r) { return r ~ /\.(glsl|frag|vert|geom|comp)$/ }
function add_dir(key, d, arr, seen) { if (!((key, d) in seen)) { seen[key, d] = 1; arr[key] = (arr[key] == "" ? d : arr[key] " " d) } }
function violation(msg) { nviol++; VIOL[nviol] = msg }
function resolve(r, q, name,   d, c, dirs, n, i, D) {
  if (q == "\"") { d = dirname(r); c = norm((d == "" ? "" : d "/") name); if (c in FILES) return c }
  if (is_glsl(r)) return ""
  dirs = (r in FILEINC) ? FILEINC[r] : ((module_of(r) in MODINC) ? MODINC[module_of(r)] : ALLINC)
  n = split(dirs, D, " ")
  for (i = 1; i <= n; i++) { c = rel(D[i] "/" name); if (c != "" && c !~ /^@b\// && (c in FILES)) return c }
  return ""
}
function target_owner(td,   b) {   # the module whose CMake file defined the target
  b = substr(td, length(BUILD) + 2); sub(/\/?CMakeFiles\/[^\/]*$/, "", b)
  return b == "" ? "(top)" : module_of(b "/CMakeLists.txt")
}
function obj_target(o) { match(o, /\/CMakeFiles\/[^\/]*\.dir\//); return substr(o, 1, RSTART + RLENGTH - 2) }
function obj_source(o,   td, b, r) {   # without a dependency file: from the object's own path
  if (o in OSRC) return OSRC[o]
  td = obj_target(o); r = substr(o, length(td) + 2); sub(/\.o$/, "", r); gsub(/__\//, "../", r)
  b = substr(td, length(BUILD) + 2); sub(/\/?CMakeFiles\/[^\/]*$/, "", b)
  return rel(SRC "/" (b == "" ? "" : b "/") r)
}
function short(list, max,   a, n, i, s) {
  n = split(list, a, " "); s = ""
  for (i = 1; i <= n && i <= max; i++) s = s (i > 1 ? ", " : "") a[i]
  if (n > max) s = s ", +" (n - max) " more"
  return s
}
BEGIN {
  FS = "\t"; nviol = 0
  n = split(PUBLIC_HEADERS, a, " "); for (i = 1; i <= n; i++) PUB[a[i]] = 1
}
sec == "files"  { FILES[$0] = 1; next }
sec == "inc"    { p = index($0, ":"); f = substr($0, 1, p - 1); rest = substr($0, p + 1)
                  p = index(rest, ":"); ln = substr(rest, 1, p - 1); txt = substr(rest, p + 1)
                  if (!match(txt, /include[ \t]*[<"][^>"]*[>"]/)) next
                  s = substr(txt, RSTART, RLENGTH); sub(/^include[ \t]*/, "", s)
                  ni++; IF[ni] = f; IL[ni] = ln; IQ[ni] = substr(s, 1, 1); IN[ni] = substr(s, 2, length(s) - 2); next }
sec == "pubids" { p = index($0, ":"); PUBID[module_of(substr($0, 1, p - 1)), substr($0, p + 1)] = 1; next }
sec == "tdirs"  { TD[$0] = 1; next }
sec == "flags"  { n = split($2, w, " "); for (i = 1; i <= n; i++) {
                    d = ""
                    if (w[i] ~ /^-I./) d = substr(w[i], 3)
                    else if ((w[i] == "-I" || w[i] == "-isystem" || w[i] == "-iquote") && i < n) d = w[++i]
                    if (d != "") { add_dir($1, d, TINC, SEENT); add_dir("", d, ALLINC_A, SEENA) } }
                  next }
sec == "deps"   { o = $1; td = obj_target(o); OSRC[o] = rel($2); OBJS[o] = 1
                  for (i = 2; i <= NF; i++) { r = rel($i); if (r != "" && r !~ /^@b\//) READS[o, ++NREAD[o]] = r }
                  next }
sec == "nm"     { p = index($0, ":"); o = substr($0, 1, p - 1); rest = substr($0, p + 1)
                  n = split(rest, w, " "); if (n < 2) next
                  sym = w[n]; ty = w[n - 1]; OBJS[o] = 1
                  if (ty == "U") USES[o] = USES[o] " " sym
                  else if (ty ~ /^[A-Z]$/) { if (!((sym, o) in DEFSEEN)) { DEFSEEN[sym, o] = 1; DEF[sym] = DEF[sym] " " o } }
                  next }
sec == "cmake"  { line = $0; sub(/^[ \t]*#.*/, "", line); sub(/[ \t]#[^"]*$/, "", line)
                  CM[FILENAME] = CM[FILENAME] " " line; next }
END {
  ALLINC = ALLINC_A[""]
  # ---- objects: their source, module, target; include paths per file and per module ------
  for (o in OBJS) {
    td = obj_target(o); s = obj_source(o); OS[o] = s; OT[o] = td
    if (s == "" || is_test(s)) TESTT[td] = 1
    if (target_owner(td) == "tests") TESTT[td] = 1
  }
  for (o in OBJS) {
    td = OT[o]; m = module_of(OS[o])
    if (!(td in TINC)) continue
    n = split(TINC[td], D, " ")
    for (i = 1; i <= n; i++) add_dir(m, D[i], MODINC, SEENM)
    for (k = 1; k <= NREAD[o]; k++) for (i = 1; i <= n; i++) add_dir(READS[o, k], D[i], FILEINC, SEENF)
    if (!NREAD[o]) for (i = 1; i <= n; i++) add_dir(OS[o], D[i], FILEINC, SEENF)
  }
  nobj = 0; for (o in OBJS) nobj++
  ntd = 0; for (td in TD) ntd++

  # ---- 1. includes ------------------------------------------------------------------------
  for (i = 1; i <= ni; i++) {
    f = IF[i]; if (is_test(f)) continue
    fm = module_of(f); fk = kind_of(fm)
    if (IN[i] ~ /^sl:/) continue                          # the core's GLSL library: SDK contract
    t = resolve(f, IQ[i], IN[i]); if (t == "" || is_test(t)) continue
    tm = module_of(t); tk = kind_of(tm)
    if (tm == fm) continue
    if (guarded(fk) && !is_public(t)) {
      if (is_glsl(f)) { violation(f ":" IL[i] ": GLSL includes " t " of " tm " (shared GLSL belongs in the SDK shader library, #include \"sl:NAME\")"); continue }
      violation(f ":" IL[i] ": includes " t ", a private file of " tm)
    } else if (fk == "core" && guarded(tk)) {
      violation(f ":" IL[i] ": the core includes " t " of " tk " " tm " (the core never depends on a " tk ")")
    } else if (fk == "core" && tk == "core") {
      key = fm SUBSEP tm
      if (!((key, f, t) in EVSEEN)) { EVSEEN[key, f, t] = 1; EV[key] = EV[key] "\n        " f " includes " t }
      EDGE[fm, tm] = 1; NODE[fm] = 1; NODE[tm] = 1
    }
  }
  # ---- 1. compiled sources: the CMake lists ---------------------------------------------------
  for (cf in CM) {
    r = rel(cf); owner = module_of(r); if (!guarded(kind_of(owner)) || is_test(r)) continue
    text = CM[cf]; base = dirname(r)
    while (match(text, /(add_library|add_executable|target_sources|shadelab_add_plugin)[ \t]*\([^)]*\)/)) {
      call = substr(text, RSTART, RLENGTH); text = substr(text, RSTART + RLENGTH)
      cmd = call; sub(/[ \t]*\(.*/, "", cmd)
      sub(/^[^(]*\(/, "", call); sub(/\)$/, "", call); gsub(/"/, "", call)
      n = split(call, w, /[ \t]+/); first = 1
      for (i = 1; i <= n; i++) {
        tok = w[i]; if (tok == "") continue
        if (first) { first = 0; continue }                 # the target's name
        if (tok !~ /\.(c|cc|cpp|cxx|h|hpp|m)$/ || tok ~ /\$</) continue
        gsub(/\$\{(CMAKE_CURRENT_SOURCE_DIR|CMAKE_CURRENT_LIST_DIR)\}/, SRC "/" base, tok)
        gsub(/\$\{(PROJECT_SOURCE_DIR|CMAKE_SOURCE_DIR|shadelab_SOURCE_DIR)\}/, SRC, tok)
        if (tok ~ /\$\{/) continue                         # another variable: the objects tell
        s = (tok ~ /^\//) ? rel(tok) : norm((base == "" ? "" : base "/") tok)
        if (s == "" || s ~ /^@b\// || is_test(s)) continue
        if (module_of(s) != owner)
          violation(r ": " cmd "(…) compiles " s ", a file of " module_of(s))
      }
    }
  }
  # ---- 1. compiled sources: the objects built ----------------------------------------------
  for (o in OBJS) {
    td = OT[o]; s = OS[o]; if (TESTT[td] || s == "" || s ~ /^@b\//) continue
    owner = target_owner(td); sm = module_of(s)
    if (guarded(kind_of(owner)) && sm != owner && !((td, s) in CSEEN)) {
      CSEEN[td, s] = 1; tn = td; sub(/^.*\//, "", tn); sub(/\.dir$/, "", tn)
      violation("target " tn " (defined by " owner ") compiles " s ", a file of " sm)
    }
    if (kind_of(owner) == "core" && guarded(kind_of(sm)))
      violation("core target " td " compiles " s " of " sm)
  }
  # ---- 2. symbols -----------------------------------------------------------------------------
  for (o in OBJS) {
    s = OS[o]; if (s == "" || TESTT[OT[o]] || is_test(s)) continue
    m = module_of(s); k = kind_of(m)
    if (!guarded(k) && k != "core") continue
    n = split(USES[o], U, " ")
    for (i = 1; i <= n; i++) {
      sym = U[i]; nd = split(DEF[sym], DO, " "); if (nd == 0) continue
      ok = 0; others = ""; cores = ""
      for (j = 1; j <= nd; j++) {
        d = DO[j]; ds = OS[d]; if (ds == "" || TESTT[OT[d]] || is_test(ds)) continue
        dm = module_of(ds); dk = kind_of(dm)
        if (dm == m || (!guarded(dk) && dk != "core")) { ok = 1; continue }
        if (dk == "core") { if (k == "core") cores = cores " " ds; else ok = 1; continue }
        if (PUBID[dm, sym] && k != "core") { ok = 1; continue }
        others = others " " ds
      }
      if (k == "core") {
        if (cores != "") {
          # nm edge between core modules (reported)
          split(cores, C, " "); dm = module_of(C[1])
          if (dm != m) {
            key = m SUBSEP dm; EDGE[m, dm] = 1; NODE[m] = 1; NODE[dm] = 1
            if (!((key, s, C[1]) in SYMN)) { SYMK[key, ++NSYMK[key]] = s SUBSEP C[1] }
            SYMN[key, s, C[1]] = SYMN[key, s, C[1]] " " sym
          }
          continue
        }
        if (!ok && others != "") violation(s ": the core uses " sym ", defined only in" others)
        continue
      }
      if (!ok && others != "") {
        key = s " (" m ") uses" SUBSEP others
        if (!(key in R2)) R2ORDER[++NR2] = key
        R2[key] = R2[key] " " sym
      }
    }
  }
  for (i = 1; i <= NR2; i++) {
    split(R2ORDER[i], P, SUBSEP)
    violation(P[1] " " short(substr(R2[R2ORDER[i]], 2), 6) ", defined only in" P[2] \
              " and not declared in a public header of " module_of(substr(P[2], 2)))
  }
  for (key in NSYMK) for (j = 1; j <= NSYMK[key]; j++) {
    split(SYMK[key, j], P, SUBSEP)
    EV[key] = EV[key] "\n        " P[1] " uses " short(substr(SYMN[key, P[1], P[2]], 2), 4) " (" P[2] ")"
  }

  # ---- the report --------------------------------------------------------------------------
  print "module rule: " SRC " (build " BUILD ")"
  print "  read " ni " #include lines, " ntd " target folders, " nobj " objects"
  if (nobj == 0) violation(BUILD ": no object files under CMakeFiles/<target>.dir/ (build the tree first)")
  report_cycles()
  if (core_cycles) {
    print "\nFAIL: " core_cycles " cyclic group(s) between core modules: the core's modules form layers" \
          "\n(docs/architecture.md); move the shared piece down or pass it in, so that nothing calls upward."
    exit 1
  }
  if (nviol) {
    print "\nFAIL: " nviol " violation(s) of the module rule:"
    for (i = 1; i <= nviol; i++) print "  " VIOL[i] | "LC_ALL=C sort -u"
    close("LC_ALL=C sort -u")
    print "A plugin, tool or extra may include and call only public files: sdk/include/shadelab/*.h, a" \
          "\nmodule's include/ folder, " PUBLIC_HEADERS "; what two of them share goes" \
          "\nthere (docs/design-notes.md, \"Where things go\")."
    exit 1
  }
  print "\nOK: no plugin, extra or tool includes, compiles or calls another module's private code;" \
        " the core depends on no plugin, extra or tool."
}

# ---- core cycles: Tarjan's strongly connected components, then the elementary cycles ----------
function strongconnect(v,   w, n, i, A) {
  IDX[v] = LOW[v] = ++counter; STACK[++sp] = v; ONST[v] = 1
  n = split(ADJ[v], A, " ")
  for (i = 1; i <= n; i++) {
    w = A[i]
    if (!(w in IDX)) { strongconnect(w); if (LOW[w] < LOW[v]) LOW[v] = LOW[w] }
    else if (ONST[w] && IDX[w] < LOW[v]) LOW[v] = IDX[w]
  }
  if (LOW[v] == IDX[v]) {
    nscc++; SCCN[nscc] = 0
    do { w = STACK[sp--]; ONST[w] = 0; COMP[w] = nscc; SCC[nscc, ++SCCN[nscc]] = w } while (w != v)
  }
}
function cycles_from(s, v, depth,   n, i, A, w, j, line) {
  if (ncyc >= 40) return
  n = split(ADJ[v], A, " ")
  for (i = 1; i <= n; i++) {
    w = A[i]
    if (COMP[w] != COMP[s] || ORD[w] < ORD[s]) continue
    if (w == s) {
      ncyc++; line = ""
      for (j = 1; j <= depth; j++) line = line PATH[j] " -> "
      CYC[ncyc] = line s; CYCLEN[ncyc] = depth
      for (j = 1; j <= depth; j++) CYCHOP[ncyc, j] = PATH[j] SUBSEP (j < depth ? PATH[j + 1] : s)
      continue
    }
    if (ONPATH[w] || depth >= 6) continue
    ONPATH[w] = 1; PATH[depth + 1] = w
    cycles_from(s, w, depth + 1)
    ONPATH[w] = 0
  }
}
function report_cycles(   v, w, k, i, j, n, c, list, cmd, key) {
  cmd = "LC_ALL=C sort"
  for (k in EDGE) { split(k, P, SUBSEP); ADJL[P[1]] = ADJL[P[1]] " " P[2] }
  n = 0; for (v in NODE) { NL[++n] = v }
  # a fixed order (sorted names), so the report is the same every run
  for (i = 2; i <= n; i++) { v = NL[i]; for (j = i - 1; j >= 1 && NL[j] > v; j--) NL[j + 1] = NL[j]; NL[j + 1] = v }
  for (i = 1; i <= n; i++) ORD[NL[i]] = i
  for (v in ADJL) { c = split(ADJL[v], A2, " "); for (i = 2; i <= c; i++) { w = A2[i]; for (j = i - 1; j >= 1 && ORD[A2[j]] > ORD[w]; j--) A2[j + 1] = A2[j]; A2[j + 1] = w }
                    ADJ[v] = ""; for (i = 1; i <= c; i++) ADJ[v] = ADJ[v] " " A2[i] }
  counter = 0; sp = 0; nscc = 0
  for (i = 1; i <= n; i++) if (!(NL[i] in IDX)) strongconnect(NL[i])
  big = 0; for (c = 1; c <= nscc; c++) if (SCCN[c] > 1) big++
  print "\ncycles between core modules (edges: #include, and nm: an undefined"
  print "symbol of one module's object -> the core object defining it); " n " core modules, " big " cyclic group(s)"
  for (c = 1; c <= nscc; c++) {
    if (SCCN[c] < 2) continue
    list = ""; for (i = 1; i <= n; i++) if (COMP[NL[i]] == c) list = list " " NL[i]
    print "  group:" list
    ncyc = 0
    for (i = 1; i <= n; i++) { v = NL[i]; if (COMP[v] != c) continue; ONPATH[v] = 1; PATH[1] = v; cycles_from(v, v, 1); ONPATH[v] = 0 }
    for (k = 1; k <= ncyc; k++) {
      print "    cycle: " CYC[k]
      for (j = 1; j <= CYCLEN[k]; j++) {
        key = CYCHOP[k, j]; split(key, P, SUBSEP)
        print "      " P[1] " -> " P[2] ":" EV[key]
      }
    }
    if (ncyc >= 40) print "    (first 40 cycles of at most 6 modules listed)"
  }
  core_cycles = big
}
AWK

#!/usr/bin/env bash
# The project's own import graph: which source file of src/ uses which, from the code itself.
#
#   bash scripts/imports.sh           summary: import circles and arrows pointing back up
#   bash scripts/imports.sh --edges   every edge, one a line: "from.rs -> to.rs: names"
#
# The summary exits 1 if there is an import circle between files or an arrow pointing back up,
# else 0 (--edges always exits 0; a bad argument exits 2).
#
# An edge is a `use crate::...` (or `berry_evolve::` from the binary's src/cli), a `crate::`
# path in code or in a serde attribute string ("crate::sim::spec::exact::array"), a `super::`
# or `self::` path that leaves its file, or a path through a child module (`use lock::...` in
# run/mod.rs). Multi-line `use` groups with nested braces are expanded; comments, doc comments
# and other strings are ignored. A path is resolved to the file that defines the item: a name
# a module re-exports (`pub use world::World` in sim/mod.rs) leads on to the file it comes
# from, so `crate::sim::World` is an edge to sim/world.rs, not to sim/mod.rs, and `mod x;`
# declarations and re-exports are not edges themselves. Edges from `#[cfg(test)]` modules
# count like the others (the file depends on them either way) and are marked "(test)".
#
# (a) Circles: strongly connected components of more than one file.
# (b) Arrows back up: an edge from a file of a lower layer to a file of a higher one, in the
#     layer order below (a file's layer is its top module; main.rs belongs to cli).
#
# Layer order, lowest first ("a | b": b may use a, a must not use b; names in one group may use
# each other), the picture of src/lib.rs:
#   - geometry, seed, validate (the range checks), input (reading a user's file safely) and cpu
#     (does this CPU have the build's extensions) and invocation (how messages name the program)
#     use nothing of the crate: the bottom.
#   - experiment sits under evo: the experiment file, [evolution] included, is data that evo
#     reads.
#   - view (the pictures: render, the replay page, plots, the archive's heat map) draws what
#     record reads and writes (traces, tables) and puts the replay page on disk with record's
#     atomic writes; cli says what to draw: between record and run.
#   - run (one run folder: lock, loop, checkpoints, resume) uses sim, brain, evo, experiment and
#     record and is used only by main.rs and cli: between view and cli.
LAYERS="geometry seed validate input cpu invocation | sim | brain | experiment | evo | record | view | run | cli"
set -euo pipefail
cd "$(dirname "$0")/.."
mode=${1:-summary}
case "$mode" in
summary | --edges) ;;
*) echo "usage: bash scripts/imports.sh [--edges]" >&2; exit 2 ;;
esac
exec python3 - "$mode" "$LAYERS" <<'PY'
import os, re, signal, sys

# Piped into head: stop quietly when the reader goes away.
signal.signal(signal.SIGPIPE, signal.SIG_DFL)

mode, layer_text = sys.argv[1], sys.argv[2]
LAYER = {}
for rank, group in enumerate(layer_text.split("|")):
    for name in group.split():
        LAYER[name] = rank

# ---- files and the module each one is ----------------------------------------------------
# A module is (crate, path tuple); crate "lib" (src/lib.rs) or "bin" (src/main.rs + src/cli).
files = sorted(os.path.join(d, f)[len("src/"):] for d, _, fs in os.walk("src")
               for f in fs if f.endswith(".rs"))

def module_of(rel):
    krate = "bin" if rel == "main.rs" or rel.startswith("cli/") else "lib"
    parts = rel[:-3].split("/")
    if parts[-1] in ("mod", "lib", "main"):
        parts = parts[:-1]
    return krate, tuple(parts)

MODFILE = {}   # (crate, path) -> file, for file modules and (below) inline modules
for rel in files:
    MODFILE[module_of(rel)] = rel

def children(mod):
    k, p = mod
    return {q[len(p)] for (kk, q) in MODFILE if kk == k and len(q) == len(p) + 1 and q[:len(p)] == p}

# ---- lexing: blank out comments and strings, keep path-like strings ------------------------
PATH_STRING = re.compile(r"^\s*((?:crate|super|self)(?:::\w+)+)\s*$")

def strip(src):
    """Comments and string literals become spaces (newlines kept). Returns the text and the
    list of (offset, path) for strings that are a whole crate path (serde attributes)."""
    out, paths, i, n = [], [], 0, len(src)
    def blank(s):
        return "".join("\n" if c == "\n" else " " for c in s)
    while i < n:
        c = src[i]
        if src.startswith("//", i):
            j = src.find("\n", i)
            j = n if j < 0 else j
            out.append(blank(src[i:j])); i = j
        elif src.startswith("/*", i):
            depth, j = 1, i + 2
            while j < n and depth:
                if src.startswith("/*", j): depth += 1; j += 2
                elif src.startswith("*/", j): depth -= 1; j += 2
                else: j += 1
            out.append(blank(src[i:j])); i = j
        elif c in "rb\"" and (i == 0 or not (src[i-1].isalnum() or src[i-1] == "_")):
            m = re.compile(r'(b?r)(#*)"|b?"').match(src, i)
            if not m:
                out.append(c); i += 1; continue
            if m.group(1):   # raw string: ends at "###
                end = '"' + m.group(2)
                j = src.find(end, m.end())
                j = n if j < 0 else j + len(end)
            else:
                j = m.end()
                while j < n and src[j] != '"':
                    j += 2 if src[j] == "\\" else 1
                j += 1
            body = src[m.end():j - 1 - (len(m.group(2)) if m.group(1) else 0)]
            pm = PATH_STRING.match(body)
            if pm:
                paths.append((i, pm.group(1)))
            out.append(blank(src[i:j])); i = j
        elif c == "'":
            # a char literal ('x', '\n', '\u{1F}') or a lifetime / label ('a)
            if i + 1 < n and src[i+1] == "\\":
                j = i + 2
                while j < n and src[j] != "'":
                    j += 1
                out.append(blank(src[i:j+1])); i = j + 1
            elif i + 2 < n and src[i+2] == "'":
                out.append("   "); i += 3
            else:
                out.append(c); i += 1
        else:
            out.append(c); i += 1
    return "".join(out), paths

# ---- use trees -------------------------------------------------------------------------------
def split_top(s):
    """Split s at commas outside braces."""
    parts, depth, cur = [], 0, []
    for ch in s:
        if ch == "{": depth += 1
        elif ch == "}": depth -= 1
        if ch == "," and depth == 0:
            parts.append("".join(cur)); cur = []
        else:
            cur.append(ch)
    parts.append("".join(cur))
    return [p.strip() for p in parts if p.strip()]

def expand(tree, prefix=()):
    """`a::{b, c::{d, self}, e as f}` -> [(a,b), (a,c,d), (a,c), (a,e)] as (segments, alias)."""
    tree = re.sub(r"\s+", " ", tree).strip()
    if tree.startswith("::"):
        tree = tree[2:]
    if tree.startswith("{"):
        inner = tree[1:tree.rindex("}")]
        return [x for part in split_top(inner) for x in expand(part, prefix)]
    m = re.match(r"^([\w$]+)\s*::\s*(.*)$", tree, re.S)
    if m:
        return expand(m.group(2), prefix + (m.group(1),))
    m = re.match(r"^([\w$]+|\*)(?:\s+as\s+(\w+))?$", tree)
    if not m:
        return []
    name = m.group(1)
    if name == "self":
        return [(prefix, prefix[-1] if prefix else None)]
    return [(prefix + (name,), m.group(2) or name)]

# ---- scanning one file -----------------------------------------------------------------------
REEXPORT = {}  # (module, name) -> (crate, absolute segments)
RAW = []       # (file, module scope, segments, is_test, line, in_use)
ALIASES = []   # (file, scope, segments, alias) of every private `use`, to find module aliases
TEXT = {}      # file -> (blanked text, in_use, scope_at, line)

USE = re.compile(r"\b(pub(?:\s*\([^)]*\))?\s+)?use\s+")
CODE_PATH = re.compile(r"(?<![\w:])\$?(crate|super|self|berry_evolve)((?:\s*::\s*\w+)+)")
CHILD_PATH = re.compile(r"(?<![\w:$.])([a-z_]\w*)((?:\s*::\s*\w+)+)")
MOD_OPEN = re.compile(r"\bmod\s+(\w+)\s*\{")
CFG_TEST = re.compile(r"#\[cfg\(test\)\]\s*(?:#\[[^\]]*\]\s*)*(?:pub(?:\([^)]*\))?\s+)?mod\s+\w+\s*\{")

def scan(rel):
    src = open("src/" + rel, encoding="utf-8").read()
    text, string_paths = strip(src)
    base = module_of(rel)
    # scopes of inline modules: (open brace offset, close offset, module, is_test)
    scopes = []
    for m in MOD_OPEN.finditer(text):
        start = m.end() - 1
        depth, j = 0, start
        while j < len(text):
            if text[j] == "{": depth += 1
            elif text[j] == "}":
                depth -= 1
                if depth == 0: break
            j += 1
        is_test = any(t.end() == m.end() for t in CFG_TEST.finditer(text, max(0, m.start() - 200), m.end()))
        scopes.append((start, j, m.group(1), is_test))
    def scope_at(pos):
        path, test = list(base[1]), False
        for s, e, name, t in scopes:   # in order of opening, so outer before inner
            if s < pos < e:
                path.append(name); test = test or t
        return (base[0], tuple(path)), test
    for s, e, name, t in scopes:
        mod, _ = scope_at(s + 1)
        MODFILE.setdefault(mod, rel)
    line = lambda pos: text.count("\n", 0, pos) + 1
    reexports = []
    used = []   # spans of use statements, to keep code paths from counting twice
    for m in USE.finditer(text):
        if m.start() > 0 and (text[m.start()-1].isalnum() or text[m.start()-1] in "_$"):
            continue
        end = text.find(";", m.end())
        used.append((m.start(), end))
        scope, test = scope_at(m.start())
        for segs, alias in expand(text[m.end():end]):
            if not segs:
                continue
            if m.group(1) and alias and alias != "*":
                REEXPORT[(scope, alias)] = (scope, segs)
                reexports.append((rel, scope, segs, test, line(m.start()), alias))
            else:
                RAW.append((rel, scope, segs, test, line(m.start()), True))
                if alias and alias != "*":
                    ALIASES.append((rel, scope, segs, alias))
    def in_use(pos):
        return any(s <= pos < e for s, e in used)
    # A re-export is an edge only if the file's own code uses the name too.
    for rel_, scope, segs, test, ln, alias in reexports:
        if any(not in_use(u.start()) for u in re.finditer(r"(?<![\w:])" + re.escape(alias) + r"\b", text)):
            RAW.append((rel_, scope, segs, test, ln, True))
    for m in CODE_PATH.finditer(text):
        if in_use(m.start()):
            continue
        scope, test = scope_at(m.start())
        segs = (m.group(1),) + tuple(re.findall(r"\w+", m.group(2)))
        RAW.append((rel, scope, segs, test, line(m.start()), False))
    for m in CHILD_PATH.finditer(text):
        if in_use(m.start()):
            continue
        scope, test = scope_at(m.start())
        if m.group(1) in children(scope):
            segs = (m.group(1),) + tuple(re.findall(r"\w+", m.group(2)))
            RAW.append((rel, scope, segs, test, line(m.start()), False))
    for pos, p in string_paths:
        scope, test = scope_at(pos)
        RAW.append((rel, scope, tuple(p.split("::")), test, line(pos), False))
    TEXT[rel] = (text, in_use, scope_at, line)

for rel in files:
    scan(rel)

# ---- resolving a path to the file that defines it --------------------------------------------
def absolute(scope, segs):
    """(crate, segments from the crate root) or None for another crate."""
    k, p = scope
    head = segs[0]
    if head in ("crate", "$crate"):
        return k, tuple(segs[1:])
    if head == "berry_evolve":
        return "lib", tuple(segs[1:])
    if head in ("super", "self"):
        p = list(p)
        while segs and segs[0] in ("super", "self"):
            if segs[0] == "super":
                if not p:
                    return None
                p.pop()
            segs = segs[1:]
        return k, tuple(p) + tuple(segs)
    if head in children(scope):
        return k, tuple(p) + tuple(segs)
    return None   # std, serde, ... or a local item

def resolve(k, segs, guard=0):
    """Follow the longest module prefix, then a re-export of the next name if there is one."""
    n = len(segs)
    while n > 0 and (k, segs[:n]) not in MODFILE:
        n -= 1
    mod = (k, segs[:n])
    if n < len(segs) and (mod, segs[n]) in REEXPORT and guard < 20:
        scope, target = REEXPORT[(mod, segs[n])]
        a = absolute(scope, target)
        if a:
            return resolve(a[0], a[1] + segs[n+1:], guard + 1)
    if mod not in MODFILE:
        return None, segs
    return MODFILE[mod], segs[n:] or (segs[-1:] if segs else ("crate",))

def names_module(k, segs):
    return (k, segs) in MODFILE

# A module brought in by `use` (`use crate::evo::lockstep;`) and used as `lockstep::chunks`
# in code: the items named through it join the edge's names.
for rel, scope, segs, alias in ALIASES:
    a = absolute(scope, segs)
    if not a or not names_module(*a):
        continue
    text, in_use, scope_at, line = TEXT[rel]
    for m in re.finditer(r"(?<![\w:$.])" + re.escape(alias) + r"\s*::\s*(\w+)", text):
        if not in_use(m.start()):
            sc, test = scope_at(m.start())
            RAW.append((rel, sc, tuple(segs) + (m.group(1),), test, line(m.start()), False))

edges = {}   # (from, to) -> {"names": set, "test": bool (all uses in test code)}
for rel, scope, segs, test, ln, _ in RAW:
    a = absolute(scope, segs)
    if not a:
        continue
    to, rest = resolve(*a)
    if not to or to == rel:
        continue
    e = edges.setdefault((rel, to), {"names": set(), "test": True})
    e["names"].add(rest[0] if rest else "?")
    e["test"] = e["test"] and test

def layer_of(rel):
    k, p = module_of(rel)
    top = "cli" if k == "bin" else (p[0] if p else "lib")
    return top, LAYER.get(top)

if mode == "--edges":
    for (a, b), e in sorted(edges.items()):
        mark = " (test)" if e["test"] else ""
        print(f"{a} -> {b}: {', '.join(sorted(e['names']))}{mark}")
    sys.exit(0)

# ---- (a) circles: Tarjan's strongly connected components ------------------------------------
graph = {f: sorted(b for (a, b) in edges if a == f) for f in files}
index, low, stack, on, comps, counter = {}, {}, [], set(), [], [0]
sys.setrecursionlimit(10000)
def strong(v):
    index[v] = low[v] = counter[0]; counter[0] += 1
    stack.append(v); on.add(v)
    for w in graph[v]:
        if w not in index:
            strong(w); low[v] = min(low[v], low[w])
        elif w in on:
            low[v] = min(low[v], index[w])
    if low[v] == index[v]:
        comp = []
        while True:
            w = stack.pop(); on.discard(w); comp.append(w)
            if w == v: break
        comps.append(sorted(comp))
for f in files:
    if f not in index:
        strong(f)
circles = sorted(c for c in comps if len(c) > 1)
status = 0
print(f"{len(files)} files, {len(edges)} edges between files")
print()
print(f"(a) import circles between files: {len(circles)}")
for c in circles:
    status = 1
    members = set(c)
    print(f"  {len(c)} files: {', '.join(c)}")
    for (a, b), e in sorted(edges.items()):
        if a in members and b in members:
            mark = " (test)" if e["test"] else ""
            print(f"      {a} -> {b}: {', '.join(sorted(e['names']))}{mark}")

# ---- (b) arrows pointing back up the layer order ---------------------------------------------
print()
unknown = sorted({layer_of(f)[0] for f in files if layer_of(f)[1] is None and layer_of(f)[0] != "lib"})
for u in unknown:
    print(f"  note: module '{u}' has no place in the layer order; its edges are not checked")
back = [(a, b, e) for (a, b), e in sorted(edges.items())
        if layer_of(a)[1] is not None and layer_of(b)[1] is not None and layer_of(a)[1] < layer_of(b)[1]]
print(f"(b) arrows pointing back up ({layer_text.replace('|', '<-')}): {len(back)}")
for a, b, e in back:
    status = 1
    mark = " (test)" if e["test"] else ""
    print(f"  {layer_of(a)[0]} -> {layer_of(b)[0]}:  {a} -> {b}: {', '.join(sorted(e['names']))}{mark}")
sys.exit(status)
PY

#!/usr/bin/env python3
"""Prints the dependency cycles between the modules of a Rust crate's source folder and
exits 1 if there is one.

Usage: scripts/module_cycles.py SRC [DEPTH]   (DEPTH 1: top-level modules; 3 by default)

A module depends on another when its non-test code names it by a `crate::...` or `super::...`
path (a parent and its own children are not counted). Written here, as a reading of the
paths rather than the compiler's name resolution, so that CI runs it without installing a
tool; a path it misses (a glob import, a macro) is a cycle it does not see.
"""
import os, re, sys
from collections import defaultdict
root = sys.argv[1]  # e.g. src
level = int(sys.argv[2]) if len(sys.argv) > 2 else 3  # module depth
def modpath(f):
    rel = os.path.relpath(f, root)[:-3].split(os.sep)
    if rel[-1] in ('mod', 'lib'): rel = rel[:-1]
    return rel
files = []
for d, _, fs in os.walk(root):
    for x in fs:
        if x.endswith('.rs') and x != 'tests.rs': files.append(os.path.join(d, x))
mods = {tuple(modpath(f)) for f in files}
def resolve(path):
    # longest prefix that is a module (file)
    for k in range(len(path), 0, -1):
        if tuple(path[:k]) in mods: return tuple(path[:k])
    return None
edges = defaultdict(set)
for f in files:
    m = tuple(modpath(f))
    src = open(f).read()
    # strip test modules roughly
    src = re.split(r'#\[cfg\(test\)\]', src)[0]
    src = re.sub(r'//[^\n]*', '', src)
    isdir = os.path.basename(f) in ('mod.rs', 'lib.rs')
    for mt in re.finditer(r'\b(crate|super)((?:::[a-z_][a-z0-9_]*)+)', src):
        parts = mt.group(2).strip(':').split('::')
        if mt.group(1) == 'crate': base = []
        else:
            base = list(m) if isdir else list(m[:-1])
            base = base[:-1] if isdir else base
            # super from a file module m = parent of m
            base = list(m[:-1])
        t = resolve(base + parts)
        if t and t != m:
            a, b = m[:level], t[:level]
            if a != b and not (a[:len(b)] == b or b[:len(a)] == a):
                edges[a].add(b)
# Tarjan SCC
idx = {}; low = {}; st = []; on = set(); out = []; c = [0]
sys.setrecursionlimit(10000)
def sc(v):
    idx[v] = low[v] = c[0]; c[0] += 1; st.append(v); on.add(v)
    for w in edges[v]:
        if w not in idx: sc(w); low[v] = min(low[v], low[w])
        elif w in on: low[v] = min(low[v], idx[w])
    if low[v] == idx[v]:
        comp = []
        while True:
            w = st.pop(); on.discard(w); comp.append(w)
            if w == v: break
        if len(comp) > 1: out.append(comp)
for v in list(edges):
    if v not in idx: sc(v)
for comp in out:
    names = sorted('::'.join(x) for x in comp)
    print('cycle:', ', '.join(names))
    for a in comp:
        for b in edges[a]:
            if b in comp: print('   ', '::'.join(a), '->', '::'.join(b))
sys.exit(1 if out else 0)

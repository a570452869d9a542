#!/usr/bin/env python3
"""Every #include in include/abu/<L>/ and src/<L>/ (and python/src, the top) must name a header
of layer L or below: core < model < input < equilibria < linear < continuation < dynamics <
scan < analysis < output < cli, python. A quoted include without "abu/<layer>/" is a header next
to the file (same layer): it must exist there. And no source or header over 600 lines
(docs/developers.md, Layout: one idea per file). Prints each violation; exit 1 if any.
  check_layers.py SOURCE_DIR"""
import os, re, sys
root = sys.argv[1] if len(sys.argv) > 1 else '.'
order = ['core', 'model', 'input', 'equilibria', 'linear', 'continuation', 'dynamics', 'scan',
         'analysis', 'output', 'cli', 'python']
rank = {l: i for i, l in enumerate(order)}
rank['python'] = rank['cli']
bad, files, includes = [], 0, 0
for base in ('include/abu', 'src', 'python/src'):
    for dirpath, _, names in os.walk(os.path.join(root, base)):
        for name in sorted(names):
            if not name.endswith(('.hpp', '.cpp', '.h')):
                continue
            path = os.path.join(dirpath, name)
            rel = os.path.relpath(path, root)
            layer = 'python' if rel.startswith('python/') else rel.split('/')[2 if rel.startswith('include/') else 1]
            if layer not in rank:
                bad.append(f'{rel}: not in a known layer ({layer})')
                continue
            files += 1
            for n, line in enumerate(open(path, encoding='utf-8'), 1):
                m = re.match(r'\s*#\s*include\s+"([^"]+)"', line)
                if not m:
                    continue
                includes += 1
                target = m.group(1)
                t = re.match(r'abu/(\w+)/', target)
                if t:
                    if t.group(1) not in rank:
                        bad.append(f'{rel}:{n}: unknown layer in {target}')
                    elif rank[t.group(1)] > rank[layer]:
                        bad.append(f'{rel}:{n}: {layer} includes {target} ({t.group(1)} is above {layer})')
                elif not os.path.exists(os.path.join(dirpath, target)):
                    bad.append(f'{rel}:{n}: "{target}" is neither abu/<layer>/... nor next to the file')
# One idea per file: none over 600 lines (src, include, python, tests).
longest = 600
for base in ('include/abu', 'src', 'python/src', 'tests'):
    for dirpath, _, names in os.walk(os.path.join(root, base)):
        for name in sorted(names):
            if name.endswith(('.hpp', '.cpp', '.h')):
                path = os.path.join(dirpath, name)
                lines = sum(1 for _ in open(path, encoding='utf-8'))
                if lines > longest:
                    bad.append(f'{os.path.relpath(path, root)}: {lines} lines (at most {longest})')
print('\n'.join(bad))
print(f'{files} files, {includes} quoted includes checked, {len(bad)} violations')
sys.exit(1 if bad else 0)

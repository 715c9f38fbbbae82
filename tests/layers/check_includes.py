#!/usr/bin/python3
"""Checks every #include "voxcd/..." of host/, ref/ and sysc/ against the layer table (host/layers.txt)."""
import os
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s+"voxcd/([^"]+)"')
SOURCES = ('.h', '.hpp', '.cpp', '.in')
# What every unit may include besides its own entries: the utilities (ref/util, which may include nothing else of
# voxcd) and the contract (ref, which every unit but ref/util may include).
UTIL = 'ref/util'
BASE = ('ref', UTIL)


def read_table(path):
    """The table's units with what each may use, and its exceptions as {(file, header): reason}."""
    rules, exceptions = {}, {}
    for number, line in enumerate(open(path, encoding='utf-8'), 1):
        line = line.split('#', 1)[0].strip()
        if not line:
            continue
        if line.startswith('exception:'):
            edge, _, reason = line[len('exception:'):].partition(':')
            source, _, header = edge.partition('->')
            if not reason.strip() or not header.strip():
                sys.exit(f'{path}:{number}: an exception needs FILE -> HEADER: reason')
            exceptions[(source.strip(), header.strip())] = reason.strip()
            continue
        unit, _, uses = line.partition(':')
        rules[unit.strip()] = [u.strip() for u in uses.split(',') if u.strip() not in ('', '-')]
    return rules, exceptions


def unit_of(path, units):
    """The longest unit that holds path (a file in a detail/ belongs to the unit above it), or None."""
    best = None
    for unit in units:
        if path == unit or path.startswith(unit + '/'):
            if best is None or len(unit) > len(best):
                best = unit
    return best


def closure(rules):
    """Each unit's allowed units and headers, host/ ones transitively (ref/fast, sysc only where named); exits on a cycle.
    Every unit may use ref/util and ref besides, except ref/util, which may use nothing but itself."""
    done, allowed = set(), {}

    def visit(unit, stack):
        if unit in stack:
            sys.exit('layer table has a cycle: ' + ' -> '.join(stack + [unit]))
        if unit in done:
            return allowed[unit]
        result = {unit} if unit == UTIL else {unit, *BASE}
        for entry in rules.get(unit, []):
            result.add(entry)
            if entry in rules:
                result |= {e for e in visit(entry, stack + [unit]) if e.startswith('host/')}
        done.add(unit)
        allowed[unit] = result
        return result

    for unit in rules:
        visit(unit, [])
    return allowed


def public_headers(root):
    """The installed headers: VOXCD_PUBLIC_HEADERS in host/package/install.cmake, and host/voxcd.h."""
    text = open(os.path.join(root, 'host/package/install.cmake'), encoding='utf-8').read()
    names = set(re.findall(r'\b((?:host|ref|sysc)/[\w/]+\.h)\b', text))
    return names | {'host/voxcd.h'}


def in_detail(path):
    return '/detail/' in '/' + path


def detail_owner(header):
    """The folder whose detail/ holds header: host/object for host/object/detail/x.h."""
    return header[:('/' + header).rfind('/detail/') - 1] if in_detail(header) else None


def violations(root, rules, allowed, public):
    """Every include against the table, as (file, line, header, rule broken)."""
    found = []
    for top in ('host', 'ref', 'sysc'):
        for folder, _, files in os.walk(os.path.join(root, top)):
            for name in sorted(files):
                if not name.endswith(SOURCES):
                    continue
                path = os.path.relpath(os.path.join(folder, name), root)
                unit = unit_of(path, rules)
                for number, line in enumerate(open(os.path.join(root, path), encoding='utf-8', errors='replace'), 1):
                    match = INCLUDE.match(line)
                    if not match:
                        continue
                    header = match.group(1)
                    target = unit_of(header, rules)
                    if target is None:
                        continue  # version.h and other generated headers belong to no unit
                    owner = detail_owner(header)
                    if owner and not (unit == owner or (unit or '').startswith(owner + '/')):
                        found.append((path, number, header, f'{header} is in {owner}/detail/, internal to {owner}'))
                    elif path in public and in_detail(header):
                        found.append((path, number, header, f'installed header {path} includes detail/ header'))
                    elif unit is not None and target not in allowed[unit] and header not in allowed[unit]:
                        found.append((path, number, header, f'{unit} may not use {target} (host/layers.txt)'))
    return found


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), '../..'))
    rules, exceptions = read_table(os.path.join(root, 'host/layers.txt'))
    found = violations(root, rules, closure(rules), public_headers(root))
    failed = [v for v in found if (v[0], v[2]) not in exceptions]
    used = {(v[0], v[2]) for v in found}
    stale = [e for e in exceptions if e not in used]
    for path, number, header, rule in failed:
        print(f'{path}:{number}: includes {header}: {rule}')
    for source, header in stale:
        print(f'host/layers.txt: exception {source} -> {header} no longer needed: remove it')
    print(f'{len(found)} includes against the table, {len(found) - len(failed)} of them known exceptions, '
          f'{len(failed)} new, {len(stale)} stale exceptions')
    return 1 if failed or stale else 0


if __name__ == '__main__':
    sys.exit(main())

#!/usr/bin/python3
"""Every random test takes its seed from tests/seed.h (voxcd::test::seed: VOXCD_SEED, else the test's default).

Fails, naming file and line, where a test reads VOXCD_SEED itself or seeds a standard random engine with a literal
number (a seed that VOXCD_SEED cannot change)."""
import os
import re
import sys

ENGINE = re.compile(r'std::(?:mt19937(?:_64)?|minstd_rand0?|ranlux(?:24|48)(?:_base)?|knuth_b|default_random_engine)'
                    r'\s+\w+\s*[({]\s*([^)}]*)[)}]')
LITERAL = re.compile(r'^\s*(?:0[xX][0-9a-fA-F]+|\d+)[uUlL]*\s*$')
GETENV = re.compile(r'getenv\(\s*"VOXCD_SEED"\s*\)')


def problems(root):
    """(path, line, reason) for every place that seeds a test another way."""
    for base, _, files in os.walk(os.path.join(root, 'tests')):
        for name in sorted(files):
            if not name.endswith(('.cpp', '.h')):
                continue
            path = os.path.join(base, name)
            rel = os.path.relpath(path, root)
            for number, line in enumerate(open(path, encoding='utf-8'), 1):
                if rel != 'tests/seed.h' and GETENV.search(line):
                    yield rel, number, 'reads VOXCD_SEED itself: call voxcd::test::seed(default) (tests/seed.h)'
                m = ENGINE.search(line)
                if m and LITERAL.match(m.group(1)):
                    yield rel, number, (f'seeds a random engine with the literal {m.group(1).strip()}: '
                                        'VOXCD_SEED cannot replace it; use voxcd::test::seed(default)')


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), '..', '..')
    found = list(problems(root))
    for rel, number, reason in found:
        print(f'{rel}:{number}: {reason}')
    if found:
        sys.exit(1)
    print('every random test takes its seed from tests/seed.h')


if __name__ == '__main__':
    main()

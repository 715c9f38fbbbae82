# scan.py: the places in an RTL file where a single-point mutant can go (bench/mutation.sh).
#
# A site is a span of one source line that is an expression of its own: the right-hand side of a one-line
# `assign`, of a one-line assignment in an always block, the condition of an `if` in an always block, or the next
# value or the reset value of a `VOXCD_FF register. Only whole one-line statements are taken (a statement that
# continues on the next line is skipped), never inside functions, parameters, generate conditions or assertions,
# so that replacing the span by `(voxcd_mut(K) ? (mutant) : (original))` keeps the source valid.
import re
from dataclasses import dataclass

IDENT_LHS = r"[A-Za-z_][\w.]*(?:\[[^\]]*\])*(?:\.[A-Za-z_]\w*(?:\[[^\]]*\])*)*"


@dataclass
class Site:
    file: str      # file name in rtl/
    line: int      # 1-based line number
    start: int     # span [start, end) within the line
    end: int
    kind: str      # 'rhs' (an assigned value), 'cond' (an if's condition), 'next' / 'reset' (a register's)
    lhs: str       # the assigned variable (rhs, next), else ''
    blocking: bool  # the assignment is `=` (always_comb or assign), not `<=`


def strip_comment(line):
    i = line.find("//")
    return line if i < 0 else line[:i]


def balanced(text, i):
    """Index just past the parenthesis group that opens at text[i] == '(', or -1."""
    depth = 0
    for j in range(i, len(text)):
        if text[j] == "(":
            depth += 1
        elif text[j] == ")":
            depth -= 1
            if depth == 0:
                return j + 1
    return -1


def statement_sites(fname, lineno, code, procedural):
    """Sites of one code line (comment stripped) that holds whole statements."""
    sites = []
    m = re.match(r"\s*assign\s+(" + IDENT_LHS + r")\s*=\s*", code)
    if m:
        end = code.rstrip().rfind(";")
        if end > m.end() and code.rstrip().endswith(";") and code.count(";") == 1:
            sites.append(Site(fname, lineno, m.end(), end, "rhs", m.group(1), True))
        return sites
    if not procedural:
        return sites
    pos = 0
    m = re.match(r"\s*(end\s+)?(else\s+)?", code)
    pos = m.end()
    if re.match(r"for\s*\(", code[pos:]):  # a loop header: its body may follow on the line
        close = balanced(code, code.index("(", pos))
        if close < 0:
            return sites
        pos = close
    m = re.match(r"\s*if\s*\(", code[pos:])
    if m:
        open_at = pos + m.end() - 1
        close = balanced(code, open_at)
        if close < 0:
            return sites
        sites.append(Site(fname, lineno, open_at + 1, close - 1, "cond", "", False))
        pos = close
    rest = code[pos:]
    m = re.match(r"\s*(" + IDENT_LHS + r")\s*(<=|=)\s*", rest)
    if m and rest.rstrip().endswith(";") and rest.count(";") == 1:
        start = pos + m.end()
        end = pos + rest.rstrip().rfind(";")
        if end > start:
            sites.append(Site(fname, lineno, start, end, "rhs", m.group(1), m.group(2) == "="))
    return sites


def ff_sites(fname, lineno, code):
    """The next value and the reset value of a `VOXCD_FF(q, d, reset) line."""
    m = re.match(r"\s*`VOXCD_FF\(", code)
    if not m:
        return []
    close = balanced(code, m.end() - 1)
    if close < 0:
        return []
    args, depth, start = [], 0, m.end()
    for j in range(m.end(), close - 1):
        c = code[j]
        depth += c in "([{"
        depth -= c in ")]}"
        if c == "," and depth == 0:
            args.append((start, j))
            start = j + 1
    args.append((start, close - 1))
    if len(args) != 3:
        return []
    q = code[args[0][0]:args[0][1]].strip()

    def trimmed(a):
        s, e = a
        while code[s] == " ":
            s += 1
        while code[e - 1] == " ":
            e -= 1
        return s, e
    (ds, de), (rs, re_) = trimmed(args[1]), trimmed(args[2])
    return [Site(fname, lineno, ds, de, "next", q, False), Site(fname, lineno, rs, re_, "reset", q, False)]


def scan(fname, text):
    """Every site of a file's text."""
    sites = []
    in_always = False
    depth = 0
    skip_until = None
    prev_end_ok = True
    for n, raw in enumerate(text.split("\n"), 1):
        code = strip_comment(raw)
        stripped = code.strip()
        if skip_until:
            if re.search(skip_until, stripped):
                skip_until = None
            prev_end_ok = True
            continue
        if re.match(r"(function|task)\b", stripped):
            skip_until = r"\bend(function|task)\b"
            continue
        # Not functional: elaboration-time code, assertions, system tasks, and the cov_* signals only cover
        # properties read (docs/verification.md, "Coverage").
        if (re.match(r"initial\b", stripped) or "VOXCD_ASSERT" in stripped or "VOXCD_COVER" in stripped
                or "$" in stripped or re.search(r"\bcov_", stripped)):
            prev_end_ok = stripped.endswith(";") or not stripped
            continue
        if not stripped:
            continue
        starts_always = re.match(r"always(_comb|_ff|_latch)?\b", stripped) is not None
        if starts_always:
            in_always, depth = True, 0
        if prev_end_ok and not starts_always:
            if stripped.startswith("`VOXCD_FF("):
                sites += ff_sites(fname, n, code)
            elif not re.match(r"(localparam|parameter|typedef|input|output|logic|wire|int\b|genvar)", stripped):
                sites += statement_sites(fname, n, code, in_always)
        if in_always:
            depth += len(re.findall(r"\bbegin\b", code)) - len(re.findall(r"\bend\b", code))
            if depth <= 0 and not starts_always:
                in_always = False
        prev_end_ok = bool(re.search(r"(;|\bbegin(\s*:\s*\w+)?|\bend(\s*:\s*\w+)?|\belse|\bendcase)\s*$", stripped))
    return sites

# operators.py: the single-point changes one site can take (bench/mutation.sh). Each mutant of a site is its
# expression with one change: a binary operator swapped for its partner, a negation dropped, a constant off by one,
# a bit select moved by one, a condition negated or forced, a register's update dropped (it keeps its value) or its
# reset value inverted.
import re

TOKEN = re.compile(r"""
    (?P<ws>\s+)
  | (?P<lit>\d*'[sS]?[bBdDhHoO][0-9a-fA-F_xzXZ?]+)
  | (?P<fill>'[01xzXZ](?![\w(]))
  | (?P<cast>'\()
  | (?P<id>`?[A-Za-z_$][\w$]*(?:::[A-Za-z_]\w*)*)
  | (?P<num>\d+)
  | (?P<op><<<|>>>|===|!==|<<|>>|<=|>=|==|!=|&&|\|\||\+:|-:|~&|~\||~\^|\^~|[-+*/%&|^~!<>?:=(){}\[\],.;@#])
""", re.X)

# Binary operators and the one each becomes.
SWAP = {"+": "-", "-": "+", "&": "|", "|": "&", "^": "|", "&&": "||", "||": "&&", "==": "!=", "!=": "==",
        "<": "<=", "<=": "<", ">": ">=", ">=": ">", "<<": ">>", ">>": "<<"}
OPERAND_END = {"lit", "fill", "id", "num"}


def tokens(expr):
    out, i = [], 0
    while i < len(expr):
        m = TOKEN.match(expr, i)
        if not m:
            return None
        out.append((m.lastgroup, m.start(), m.end(), m.group()))
        i = m.end()
    return out


def literal_step(text, step):
    """A sized literal's value plus step, in the same base and size, or None where it would not fit."""
    m = re.match(r"(\d*)'([sS]?)([bBdDhHoO])([0-9a-fA-F_]+)$", text)
    if not m:
        return None
    size, sgn, base, digits = m.groups()
    radix = {"b": 2, "d": 10, "h": 16, "o": 8}[base.lower()]
    value = int(digits.replace("_", ""), radix) + step
    if value < 0 or (size and value >= 1 << int(size)):
        return None
    body = {2: format(value, "b"), 10: str(value), 16: format(value, "x"), 8: format(value, "o")}[radix]
    return f"{size}'{sgn}{base}{body}"


def expression_mutants(expr):
    """(description, mutated expression) for every single-point change of an expression."""
    toks = tokens(expr)
    if toks is None:
        return []
    out = []
    prev = None   # kind of the previous significant token
    bracket = []  # open brackets: '[' for selects
    for idx, (kind, s, e, text) in enumerate(toks):
        if kind == "ws":
            continue
        binary = prev in OPERAND_END or prev in (")", "]", "}")
        if kind == "op":
            if text in SWAP and binary:
                out.append((f"operator {text} -> {SWAP[text]}", expr[:s] + SWAP[text] + expr[e:]))
            elif text in ("!", "~") and not binary:
                out.append((f"drop {text}", expr[:s] + expr[e:]))
            if text == "[":
                bracket.append(idx)
            elif text == "]" and bracket:
                bracket.pop()
        elif kind == "lit":
            for step in (1, -1):
                new = literal_step(text, step)
                if new:
                    out.append((f"constant {text} -> {new}", expr[:s] + new + expr[e:]))
        elif kind == "fill":
            new = {"'0": "'1", "'1": "'0"}.get(text)
            if new:
                out.append((f"constant {text} -> {new}", expr[:s] + new + expr[e:]))
        elif kind == "num":
            after = next((t for t in toks[idx + 1:] if t[0] != "ws"), None)
            if after and after[3] in ("'(",) or (after and after[0] == "cast"):
                pass  # a cast's width
            elif bracket and after and after[3] == "*":
                pass  # a part-select's stride (K*i +: W): moved, the last i selects past the vector (4-state X), on
                #       which Verilator 5.006 stops with an internal error however lint-clean the mutant is
            else:
                inside = bool(bracket)
                what = "bit select" if inside else "constant"
                for step in (1, -1):
                    v = int(text) + step
                    if v >= 0:
                        out.append((f"{what} {text} -> {v}", expr[:s] + str(v) + expr[e:]))
        prev = text if kind == "op" else kind
    return out


def site_mutants(site, expr):
    """(description, mutated span text) for a scanned site whose span text is expr."""
    if site.kind == "cond":
        return ([("condition negated", f"!({expr})"), ("condition forced true", "1'b1"),
                 ("condition forced false", "1'b0")] + expression_mutants(expr))
    if site.kind == "next":
        return [("register update dropped", site.lhs)] + expression_mutants(expr)
    if site.kind == "reset":
        return [(f"reset value {expr} inverted", f"~({expr})")]
    out = expression_mutants(expr)
    if not site.blocking and re.match(r"[A-Za-z_]\w*$", site.lhs):
        out.insert(0, ("register update dropped", site.lhs))
    return out

"""The type stubs (host/python/voxcd.pyi, beside the module in the build tree and once installed) and the module agree:
every public name of the module is in the stub and every name the stub declares is in the module, a class's public
members likewise, each error class has the stub's bases, and every function's and method's parameters (names, order,
which are keyword-only, defaults) are the signatures pybind11 gives in the first lines of their docstrings."""
import ast
import inspect
import re
from pathlib import Path

import pytest

import voxcd

STUB = Path(voxcd.__file__).resolve().parent / "voxcd.pyi"
# What every pybind11 class has, and what Python gives every class: not the module's own members.
INHERITED = {"__init__", "__new__", "__doc__", "__module__", "__dict__", "__weakref__", "__repr__", "__eq__",
             "__hash__", "__len__", "__getstate__", "__setstate__"}
DUNDERS_IN_STUB = {"__init__", "__eq__", "__hash__", "__len__"}


@pytest.fixture(scope="module")
def stub():
    assert STUB.is_file(), f"no stub beside the module: {STUB}"
    return ast.parse(STUB.read_text(), filename=str(STUB))


def public(name):
    return not name.startswith("_") or name == "__version__"


def stub_names(body):
    """Names the stub declares in a module's or a class's body: functions, classes, annotated and assigned names."""
    names = {}
    for node in body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            names.setdefault(node.name, []).append(node)
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            names.setdefault(node.target.id, []).append(node)
        elif isinstance(node, ast.Assign):
            for t in node.targets:
                if isinstance(t, ast.Name):
                    names.setdefault(t.id, []).append(node)
    return names


def split_top(text):
    """Splits a parameter list at the commas outside brackets and quotes."""
    parts, depth, quote, cur = [], 0, None, ""
    for ch in text:
        if quote:
            quote = None if ch == quote else quote
        elif ch in "'\"":
            quote = ch
        elif ch in "([{":
            depth += 1
        elif ch in ")]}":
            depth -= 1
        elif ch == "," and depth == 0:
            parts.append(cur.strip())
            cur = ""
            continue
        cur += ch
    if cur.strip():
        parts.append(cur.strip())
    return parts


def literal(text):
    """(True, the value) of a literal; (False, the text) of anything else (a default pybind11 prints as a repr)."""
    try:
        return True, ast.literal_eval(text)
    except (ValueError, SyntaxError):
        return False, text


def pybind_signatures(f, name):
    """Each overload's parameters from pybind11's docstring: [(name, keyword_only, has_default, default)], self
    left out."""
    doc = f.__doc__ or ""
    sigs = []
    for line in doc.splitlines():
        m = re.match(r"^(?:\d+\. )?" + re.escape(name) + r"\((.*)\) -> .*$", line)
        if not m:
            continue
        params, kw = [], False
        for p in split_top(m.group(1)):
            if p == "*":
                kw = True
                continue
            head, _, default = p.partition(" = ")
            pname = head.split(":")[0].strip()
            if pname == "self":
                continue
            params.append((pname, kw, bool(default), literal(default) if default else None))
        sigs.append(params)
    assert sigs, f"{name}: pybind11 gave no signature in its docstring"
    return sigs


def stub_signature(fn):
    a = fn.args
    positional = a.posonlyargs + a.args
    defaults = [None] * (len(positional) - len(a.defaults)) + list(a.defaults)
    params = [(p.arg, False, d is not None, literal(ast.unparse(d)) if d is not None else None)
              for p, d in zip(positional, defaults) if p.arg != "self"]
    params += [(p.arg, True, d is not None, literal(ast.unparse(d)) if d is not None else None)
               for p, d in zip(a.kwonlyargs, a.kw_defaults)]
    return params


def is_property(fn):
    return any(isinstance(d, ast.Name) and d.id == "property" for d in fn.decorator_list)


def test_every_public_name_is_in_the_stub_and_every_stubbed_name_in_the_module(stub):
    module = {n for n in dir(voxcd) if public(n)}
    stubbed = {n for n in stub_names(stub.body) if public(n)}
    assert sorted(module - stubbed) == [], "public names of the module missing from voxcd.pyi"
    assert sorted(stubbed - module) == [], "names voxcd.pyi declares that the module does not have"


def test_every_class_member_agrees(stub):
    for name, nodes in stub_names(stub.body).items():
        node = nodes[0]
        if not isinstance(node, ast.ClassDef) or not public(name):
            continue
        cls = getattr(voxcd, name)
        bases = [ast.unparse(b) for b in node.bases]
        if issubclass(cls, BaseException):
            assert [b.__name__ for b in cls.__bases__] == bases, name
            continue
        members = {m for m in vars(cls) if public(m) or m in DUNDERS_IN_STUB} - (INHERITED - DUNDERS_IN_STUB)
        if "__init__(" not in (vars(cls).get("__init__").__doc__ or "") if "__init__" in vars(cls) else False:
            members.discard("__init__")  # a class made only by the module's functions: pybind11's refusing __init__
        stubbed = set(stub_names(node.body))
        assert sorted(members - stubbed) == [], f"members of voxcd.{name} missing from voxcd.pyi"
        assert sorted(stubbed - members) == [], f"members voxcd.pyi gives voxcd.{name} that it does not have"
        for member, defs in stub_names(node.body).items():
            fns = [d for d in defs if isinstance(d, ast.FunctionDef)]
            if not fns or is_property(fns[0]):
                assert all(is_property(f) for f in fns) == isinstance(vars(cls)[member], property), \
                    f"voxcd.{name}.{member}: a property in one and not the other"
                continue
            compare(getattr(cls, member), member, fns, f"voxcd.{name}.{member}")


def compare(f, name, fns, what):
    got = pybind_signatures(f, name)
    want = [stub_signature(fn) for fn in fns]
    assert len(got) == len(want), f"{what}: {len(got)} overloads in the module, {len(want)} in voxcd.pyi"
    for g, w in zip(got, want):
        assert [p[:3] for p in w] == [p[:3] for p in g], f"{what}: the parameters differ"
        for (pname, _, has, gd), (_, _, _, wd) in zip(g, w):
            if has and gd[0] and wd[0]:
                assert (type(gd[1]), gd[1]) == (type(wd[1]), wd[1]), \
                    f"{what}: {pname}'s default is {gd[1]!r} in the module, {wd[1]!r} in voxcd.pyi"


def test_every_function_has_the_modules_parameters(stub):
    for name, nodes in stub_names(stub.body).items():
        fns = [n for n in nodes if isinstance(n, ast.FunctionDef)]
        if fns and public(name):
            assert inspect.isbuiltin(getattr(voxcd, name)), name
            compare(getattr(voxcd, name), name, fns, f"voxcd.{name}")


def test_the_stub_names_the_cpp_vocabulary(stub):
    """One vocabulary: both_directions (True but where the scene decides), broadphase, shell_count, report."""
    text = STUB.read_text()
    assert "both_directions: bool = True" in text and "both_directions: Optional[bool] = None" in text
    assert "pruning: Optional[str] = None" in text and "def shell_count(self) -> int" in text

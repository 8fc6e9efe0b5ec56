# The type stubs (python/nimbus/__init__.pyi) declare every public call of the module with the
# parameters it takes, in order, and which of them are keyword-only: a stub that drifts from the
# code (a call missing, a parameter renamed, added or made positional) fails here.
import ast
import inspect
import pathlib

import nimbus

STUBS = pathlib.Path(nimbus.__file__).with_name("__init__.pyi")


def stub_signatures():
    tree = ast.parse(STUBS.read_text())
    found = {}

    def signature(fn):
        a = fn.args
        return ([p.arg for p in a.posonlyargs + a.args], [p.arg for p in a.kwonlyargs],
                a.vararg is not None, a.kwarg is not None)

    for node in tree.body:
        if isinstance(node, ast.FunctionDef):
            found[node.name] = signature(node)
        elif isinstance(node, ast.ClassDef):
            for item in node.body:
                if isinstance(item, ast.FunctionDef):
                    found[f"{node.name}.{item.name}"] = signature(item)
    return found


def code_signature(fn):
    params = inspect.signature(fn).parameters.values()
    positional = [p.name for p in params if p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD)]
    keyword = [p.name for p in params if p.kind == p.KEYWORD_ONLY]
    return (positional, keyword, any(p.kind == p.VAR_POSITIONAL for p in params),
            any(p.kind == p.VAR_KEYWORD for p in params))


def test_every_public_function_has_a_stub_with_its_parameters():
    stubs = stub_signatures()
    functions = [name for name in nimbus.__all__ if inspect.isfunction(getattr(nimbus, name))]
    assert {"render", "generate", "read_image", "write_image"} <= set(functions)
    for name in functions:
        assert name in stubs, f"{name}: no stub in {STUBS.name}"
        assert stubs[name] == code_signature(getattr(nimbus, name)), name


def test_every_public_name_is_declared_in_the_stubs():
    text = STUBS.read_text()
    for name in nimbus.__all__:
        assert f"def {name}(" in text or f"class {name}" in text or f"{name}:" in text, name

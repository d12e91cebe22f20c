"""The type stubs (graspkit/_graspkit.pyi) name exactly what the module has."""

import ast
import inspect
import pathlib

import graspkit
import graspkit._graspkit as extension

STUBS = pathlib.Path(graspkit.__file__).with_name("_graspkit.pyi")


def stub_names():
    tree = ast.parse(STUBS.read_text())
    top, members = set(), {}
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            top.add(node.name)
        if isinstance(node, ast.ClassDef):
            names = set()
            for item in node.body:
                if isinstance(item, (ast.FunctionDef, ast.AnnAssign)):
                    names.add(item.name if isinstance(item, ast.FunctionDef) else item.target.id)
            members[node.name] = names
    return top, members


def test_every_public_name_has_a_stub_and_every_stub_a_name():
    top, members = stub_names()
    public = {n for n in dir(extension) if not n.startswith("_")}
    assert public == top
    for name, stubbed in members.items():
        cls = getattr(extension, name)
        if issubclass(cls, BaseException):
            continue
        own = {n for n, _ in inspect.getmembers(cls)
               if not n.startswith("__") and n not in ("_pybind11_conduit_v1_",)}
        assert own == stubbed - {"__init__", "__len__", "__bool__"}, name


def test_every_function_and_method_has_a_docstring_or_is_obvious():
    for name in dir(extension):
        obj = getattr(extension, name)
        if name.startswith("_") or not callable(obj):
            continue
        assert obj.__doc__, name

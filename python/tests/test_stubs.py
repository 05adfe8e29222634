"""The type stubs (python/sylva/_sylva.pyi) name exactly what the extension module has: every
public class, function and member at run time is in the stubs, and the stubs invent nothing.
Docstrings: every public callable of the module has one."""

import ast
import inspect
from pathlib import Path

import pytest

import sylva
from sylva import _sylva

STUB = Path(__file__).resolve().parents[1] / "sylva" / "_sylva.pyi"
# Stub-only names: type aliases and the shared bases of the planar classes.
STUB_ONLY = {"ArrayLike", "Array", "MeasurementModel", "InverseModel", "PlanarEkf", "_PlanarEkf", "_PlanarFrontEnd"}


def stub_members():
    tree = ast.parse(STUB.read_text())
    classes = {}
    functions = set()
    for node in tree.body:
        if isinstance(node, ast.ClassDef):
            names = set()
            for base in node.bases:
                names |= classes.get(getattr(base, "id", ""), set())
            for item in node.body:
                if isinstance(item, ast.FunctionDef):
                    names.add(item.name)
                elif isinstance(item, ast.AnnAssign) and isinstance(item.target, ast.Name):
                    names.add(item.target.id)
            classes[node.name] = names
        elif isinstance(node, ast.FunctionDef):
            functions.add(node.name)
        elif isinstance(node, (ast.Assign, ast.AnnAssign)):
            target = node.targets[0] if isinstance(node, ast.Assign) else node.target
            functions.add(target.id)
    return classes, functions


def public(names):
    return {n for n in names if not n.startswith("__") or n in {"__len__", "__contains__", "__copy__", "__deepcopy__"}}


def runtime_members(cls):
    if isinstance(cls, type) and issubclass(cls, BaseException):
        return {"code"}
    names = set()
    for name, value in vars(cls).items():
        if name in {"__init__", "__module__", "__doc__", "__repr__", "__entries", "__members__", "__index__", "__int__",
                    "__eq__", "__ne__", "__hash__", "__getstate__", "__setstate__", "__str__"}:
            continue
        names.add(name)
    if hasattr(cls, "__members__"):  # an enum: its values and name/value
        names |= set(cls.__members__) | {"name", "value"}
    return public(names)


def test_every_runtime_name_is_in_the_stubs_and_no_more():
    classes, functions = stub_members()
    runtime = {n for n in dir(_sylva) if not n.startswith("_")}
    stubbed = (set(classes) | functions) - STUB_ONLY
    assert runtime - stubbed == set(), "in the module, missing from the stubs"
    assert stubbed - runtime == set(), "in the stubs, missing from the module"


@pytest.mark.parametrize("name", sorted(n for n in dir(_sylva) if isinstance(getattr(_sylva, n), type)))
def test_class_members_match(name):
    classes, _ = stub_members()
    cls = getattr(_sylva, name)
    stub = public(classes[name]) - {"__init__"}
    assert runtime_members(cls) - stub == set(), f"{name}: members missing from the stubs"
    assert stub - runtime_members(cls) == set(), f"{name}: stub members missing at run time"


def test_public_callables_have_docstrings():
    undocumented = []
    for name in dir(sylva):
        if name.startswith("_"):
            continue
        obj = getattr(sylva, name)
        if (inspect.isclass(obj) or callable(obj)) and not (obj.__doc__ or "").strip():
            undocumented.append(name)
    assert undocumented == []

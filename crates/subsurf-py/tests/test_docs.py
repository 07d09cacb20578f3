"""The package's surface: `dir(subsurf)` lists only its own names; every public function and
class has a docstring naming its parameters and a complete annotation in the one typed source
(no separate stub file to drift from it)."""

import inspect
from pathlib import Path

import subsurf


def test_only_the_package_names_are_public():
    public = [n for n in dir(subsurf) if not n.startswith("_")]
    assert sorted(public) == sorted(subsurf.__all__), set(public) ^ set(subsurf.__all__)


def _callables():
    for name in subsurf.__all__:
        obj = getattr(subsurf, name)
        if inspect.isfunction(obj):
            yield name, obj
        elif inspect.isclass(obj) and not issubclass(obj, BaseException):
            for m, f in vars(obj).items():
                if inspect.isfunction(f) and (not m.startswith("_") or m == "__init__"):
                    yield f"{name}.{m}", f
                elif isinstance(f, classmethod):
                    yield f"{name}.{m}", f.__func__


def test_docstrings_and_annotations():
    for name in subsurf.__all__:
        obj = getattr(subsurf, name)
        assert obj.__doc__ and len(obj.__doc__) > 20, name
        if inspect.isfunction(obj):
            for p in inspect.signature(obj).parameters:
                assert p in obj.__doc__ or p in ("mesh",), (name, p)
    for name, f in _callables():
        sig = inspect.signature(f)
        for p in sig.parameters.values():
            if p.name in ("self", "cls") or p.kind in (p.VAR_KEYWORD, p.VAR_POSITIONAL):
                continue
            assert p.annotation is not inspect.Parameter.empty, (name, p.name)
        assert sig.return_annotation is not inspect.Signature.empty, name
    pkg = Path(subsurf.__file__).parent
    assert (pkg / "py.typed").exists() and not (pkg / "__init__.pyi").exists()

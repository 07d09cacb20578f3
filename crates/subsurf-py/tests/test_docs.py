"""Every public function and class has a docstring naming its parameters; stubs ship."""

import inspect
from pathlib import Path

import subsurf


def test_docstrings_and_stubs():
    for name in subsurf.__all__:
        obj = getattr(subsurf, name)
        assert obj.__doc__ and len(obj.__doc__) > 20, name
        if inspect.isfunction(obj):
            for p in inspect.signature(obj).parameters:
                assert p in obj.__doc__ or p in ("mesh",), (name, p)
    pkg = Path(subsurf.__file__).parent
    assert (pkg / "py.typed").exists() and (pkg / "__init__.pyi").exists()

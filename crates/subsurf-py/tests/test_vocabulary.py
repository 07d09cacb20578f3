"""docs/vocabulary.md holds for Python: every keyword of every public function and method is in
the concept table for that function, the compiled module's text signatures use no old name,
an unknown or old keyword raises TypeError naming it (and the new name), and the option
values are the table's."""

import inspect
import types

import numpy as np
import pytest

import subsurf
from subsurf import _subsurf
from conftest import REPO

TETRA = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=np.float32)
TETRA_FACES = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]


def _code_spans(cell):
    return [s for k, s in enumerate(cell.split("`")) if k % 2 == 1]


def table():
    text = (REPO / "docs" / "vocabulary.md").read_text()
    body = text[text.index("<!-- vocabulary:begin -->"):text.index("<!-- vocabulary:end -->")]
    lines = [line for line in body.splitlines() if line.startswith("|")]
    header = [c.strip() for c in lines[0].strip("|").split("|")]
    assert header == ["Concept", "Rust", "CLI flag", "Commands", "Python keyword", "Python",
                      "File", "Values", "Old names"]
    rows = []
    for line in lines[2:]:
        c = [x.strip() for x in line.strip("|").split("|")]
        assert len(c) == len(header), line
        rows.append({
            "concept": c[0],
            "keywords": _code_spans(c[4]),
            "functions": _code_spans(c[5]),
            "values": _code_spans(c[7]),
            "old": [o for o in _code_spans(c[8]) if not o.startswith("--")],
        })
        assert bool(rows[-1]["keywords"]) == bool(rows[-1]["functions"]), line
    return rows


def public_callables():
    """(name as the table writes it, function): `Mesh` for the constructor, `Mesh.write`,
    `tessellate`, ..."""
    for name in subsurf.__all__:
        obj = getattr(subsurf, name)
        if inspect.isfunction(obj):
            yield name, obj
        elif inspect.isclass(obj) and not issubclass(obj, BaseException):
            for m, f in vars(obj).items():
                if isinstance(f, classmethod):
                    f = f.__func__
                if not inspect.isfunction(f) or (m.startswith("_") and m != "__init__"):
                    continue
                yield (name if m == "__init__" else f"{name}.{m}"), f


def keywords(f):
    """The parameters a caller may name."""
    return [p.name for p in inspect.signature(f).parameters.values()
            if p.name not in ("self", "cls") and p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY)]


def test_signatures_match_the_table():
    rows = table()
    funcs = dict(public_callables())
    for row in rows:
        for name in row["functions"]:
            assert name in funcs, f"{row['concept']}: no public {name}"
            params = keywords(funcs[name])
            for k in row["keywords"]:
                assert k in params, f"{name}{inspect.signature(funcs[name])} has no {k} ({row['concept']})"
            for old in row["old"]:
                assert old not in params, f"{name} still takes the old {old} ({row['concept']})"
    for name, f in funcs.items():
        for k in keywords(f):
            assert any(k in r["keywords"] and name in r["functions"] for r in rows), \
                f"{name}: keyword {k} is not in docs/vocabulary.md for {name}"


def _private_callables():
    for cls_name, cls in vars(_subsurf).items():
        if inspect.isclass(cls) and cls_name.startswith("_"):
            yield cls_name[1:], cls
            for m, f in vars(cls).items():
                if not m.startswith("__") and callable(f):
                    yield f"{cls_name[1:]}.{m}", f
        elif callable(cls) and not inspect.isclass(cls):
            yield cls_name, cls


def test_text_signatures_use_no_old_name():
    rows = table()
    checked = 0
    for name, f in _private_callables():
        sig = getattr(f, "__text_signature__", None)
        if not sig:
            continue
        params = [p.name for p in inspect.signature(f).parameters.values()]
        for row in rows:
            if name in row["functions"]:
                for old in row["old"]:
                    assert old not in params, f"_subsurf {name}{sig}: old {old} ({row['concept']})"
        checked += 1
    assert checked >= 10, checked
    assert "tess" in inspect.signature(_subsurf.tessellate).parameters
    assert "positions" in inspect.signature(_subsurf._Mesh).parameters


def test_unknown_keyword_raises_type_error():
    checked = 0
    for name, f in public_callables():
        if any(p.kind == p.VAR_KEYWORD for p in inspect.signature(f).parameters.values()):
            continue
        with pytest.raises(TypeError) as e:
            f(no_such_keyword=1)
        msg = str(e.value)
        assert "no_such_keyword" in msg, (name, msg)
        accepted = keywords(f)
        if accepted:
            assert "accepted: " + ", ".join(accepted) in msg, (name, msg)
        checked += 1
    assert checked >= 15, checked
    # Through the var-keyword path too.
    fake = types.SimpleNamespace(vertices=TETRA, faces=np.array(TETRA_FACES))
    with pytest.raises(TypeError, match="triangle_subdivision"):
        subsurf.Mesh.from_trimesh(fake, triangles="smooth")


def test_old_keywords_name_the_new_one():
    funcs = dict(public_callables())
    checked = 0
    for row in table():
        for old in row["old"]:
            for name in row["functions"]:
                with pytest.raises(TypeError) as e:
                    funcs[name](**{old: 1})
                msg = str(e.value)
                assert repr(old) in msg and row["keywords"][0] in msg.split("accepted")[0], msg
                checked += 1
    assert checked >= 8, checked
    mesh = subsurf.Mesh(TETRA, TETRA_FACES)
    with pytest.raises(AttributeError, match="positions"):
        mesh.points


@pytest.mark.parametrize("keyword", ["scheme", "boundary", "crease_method",
                                     "triangle_subdivision", "uv_interpolation"])
def test_option_values_are_the_table(keyword):
    (row,) = [r for r in table() if keyword in r["keywords"] and "Mesh" in r["functions"]]
    assert row["values"]
    for v in row["values"]:
        assert subsurf.Mesh(TETRA, TETRA_FACES, **{keyword: v}).options[keyword] == v
    with pytest.raises(ValueError) as e:
        subsurf.Mesh(TETRA, TETRA_FACES, **{keyword: "no-such-value"})
    for v in row["values"]:
        assert v in str(e.value), str(e.value)


def test_method_and_backend_values():
    rows = table()
    mesh = subsurf.Mesh(TETRA, TETRA_FACES)
    (method,) = [r for r in rows if r["keywords"] == ["method"]]
    with pytest.raises(ValueError) as e:
        subsurf.tessellate(mesh, "nope")
    assert all(v in str(e.value) for v in method["values"]), str(e.value)
    (backend,) = [r for r in rows if r["keywords"] == ["backend"]]
    with pytest.raises(ValueError) as e:
        subsurf.tessellate(mesh, backend="nope")
    assert all(v in str(e.value) for v in backend["values"]), str(e.value)
    # level for refine, tess for the others, as --level and --tess.
    cube = subsurf.read(REPO / "testdata" / "shapes" / "catmark_cube.obj")
    assert len(subsurf.tessellate(cube, "refine", level=1)[2]) == 6 * 4 * 2
    assert len(subsurf.tessellate(cube, "limit", tess=3)[2]) == 6 * 4 * 2
    with pytest.raises(ValueError, match="use level"):
        subsurf.tessellate(cube, "refine", tess=3)
    with pytest.raises(ValueError, match="use tess"):
        subsurf.tessellate(cube, "limit", level=3)

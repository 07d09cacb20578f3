"""Live crease edits of a LimitSurface (`set_sharpness`): the edited surface evaluates, bit for
bit, as a LimitSurface built from the edited mesh (same control points); bad edits are refused
before any work, naming the edit."""

import threading
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

import subsurf
from conftest import SHAPES


def edited(mesh, creases=None, sharpness=None, corners=None, corner_sharpness=None):
    """`mesh` with the crease and corner values replaced (as set_sharpness applies them)."""
    pairs, s = mesh.creases
    cv, cs = mesh.corners
    key = {tuple(sorted(p)): i for i, p in enumerate(pairs.tolist())}
    pairs, s = [list(p) for p in pairs.tolist()], list(s.tolist())
    for p, x in zip([] if creases is None else creases, [] if sharpness is None else sharpness):
        k = tuple(sorted(int(v) for v in p))
        if k in key:
            s[key[k]] = float(x)
        else:
            key[k] = len(pairs)
            pairs.append(list(k))
            s.append(float(x))
    ckey = {v: i for i, v in enumerate(cv.tolist())}
    cv, cs = list(cv.tolist()), list(cs.tolist())
    for v, x in zip([] if corners is None else corners, [] if corner_sharpness is None else corner_sharpness):
        if int(v) in ckey:
            cs[ckey[int(v)]] = float(x)
        else:
            ckey[int(v)] = len(cv)
            cv.append(int(v))
            cs.append(float(x))
    return subsurf.Mesh(
        mesh.positions, (mesh.face_counts, mesh.face_indices),
        creases=np.array(pairs, dtype=np.uint32).reshape(-1, 2), crease_sharpness=np.array(s),
        corners=np.array(cv, dtype=np.uint32), corner_sharpness=np.array(cs),
        holes=mesh.holes, **mesh.options)


def grid(surf, n=9):
    """Every ptex face at n x n parameters, its edges included (a crease of sharpness s
    moves the surface within about 2^-s of it)."""
    t = np.linspace(0.0, 1.0, n)
    u, v = np.meshgrid(t, t)
    f = np.repeat(np.arange(surf.num_ptex_faces, dtype=np.uint32), n * n)
    return f, np.tile(u.ravel(), surf.num_ptex_faces), np.tile(v.ravel(), surf.num_ptex_faces)


def same(a, b):
    q = grid(a)
    for x, y in zip(a.evaluate(*q), b.evaluate(*q)):
        assert np.array_equal(x, y, equal_nan=True)


@pytest.mark.parametrize("name", ["catmark_cube_creases1", "catmark_pyramid_creases2",
                                  "catmark_torus_creases0", "catmark_car"])
def test_edits_equal_fresh_surfaces(name):
    mesh = subsurf.read(SHAPES / f"{name}.obj")
    pairs, own = mesh.creases
    assert len(pairs) > 0
    surf = subsurf.LimitSurface(mesh)
    outcomes = []
    for s in (2.0, 3.5, None):
        values = own if s is None else np.full(len(pairs), s, dtype=np.float32)
        outcomes.append(surf.set_sharpness(pairs, values))
        same(surf, subsurf.LimitSurface(edited(mesh, pairs, values)))
    # The first edit rebuilds (keeping the levels); the same values again change nothing.
    assert outcomes[0] == "rebuilt"
    assert all(o in ("updated", "rebuilt") for o in outcomes)
    assert surf.set_sharpness(pairs, own) == "unchanged"
    same(surf, subsurf.LimitSurface(mesh))


def test_car_own_values_update_in_place_and_follow_new_points():
    mesh = subsurf.read(SHAPES / "catmark_car.obj")
    pairs, own = mesh.creases
    surf = subsurf.LimitSurface(mesh)
    moved = mesh.positions * np.float32(1.25) + np.float32(0.5)
    surf.update(moved)
    assert surf.set_sharpness(pairs, 3.5) == "rebuilt"
    assert surf.set_sharpness(pairs, own) == "updated"
    assert surf.set_sharpness(pairs, 3.5) == "updated"
    fresh = subsurf.LimitSurface(edited(mesh, pairs, np.full(len(pairs), 3.5)))
    fresh.update(moved)
    same(surf, fresh)


def test_editable_surfaces_make_their_first_edit_in_place():
    mesh = subsurf.read(SHAPES / "catmark_car.obj")
    pairs, own = mesh.creases
    surf = subsurf.LimitSurface(mesh, editable=True)
    same(surf, subsurf.LimitSurface(mesh))
    # The structure is kept from the car's own values to 3.5: in place from the first edit.
    assert surf.set_sharpness(pairs, 3.5) == "updated"
    same(surf, subsurf.LimitSurface(edited(mesh, pairs, np.full(len(pairs), 3.5))))
    assert subsurf.LimitSurface(mesh).set_sharpness(pairs, 3.5) == "rebuilt"
    with pytest.raises(TypeError, match="editable"):
        subsurf.LimitSurface(mesh, editable="yes")


def test_corner_and_new_crease_edits():
    mesh = subsurf.read(SHAPES / "catmark_cube_creases1.obj")
    faces = mesh.faces()
    new_edge = [faces[0][0], faces[0][1]]
    surf = subsurf.LimitSurface(mesh)
    surf.set_sharpness([new_edge], [1.5], corners=[faces[2][2]], corner_sharpness=[4.0])
    same(surf, subsurf.LimitSurface(edited(mesh, [new_edge], [1.5], [faces[2][2]], [4.0])))
    # One (c, 3) / (c, 2) array each, as Mesh takes them.
    surf.set_sharpness(np.array([new_edge + [0.0]]), corners=np.array([[faces[2][2], 0.0]]))
    same(surf, subsurf.LimitSurface(edited(mesh, [new_edge], [0.0], [faces[2][2]], [0.0])))


def test_bad_edits_name_the_edit_and_change_nothing():
    mesh = subsurf.read(SHAPES / "catmark_cube_creases1.obj")
    pairs, own = mesh.creases
    surf = subsurf.LimitSurface(mesh)
    ref = subsurf.LimitSurface(mesh)
    f0 = mesh.faces()[0]
    not_an_edge = [f0[0], f0[2]]  # the diagonal of a quad
    with pytest.raises(subsurf.MeshError) as e:
        surf.set_sharpness([pairs[0], not_an_edge], [2.0, 2.0])
    assert e.value.edit == 1 and "not joined by an edge" in str(e.value)
    with pytest.raises(subsurf.MeshError) as e:
        surf.set_sharpness([pairs[0]], [-1.0])
    assert e.value.edit == 0
    with pytest.raises(subsurf.MeshError) as e:
        surf.set_sharpness([pairs[0]], [1.0], corners=[mesh.num_vertices], corner_sharpness=[1.0])
    assert e.value.edit == 1 and "does not exist" in str(e.value)
    with pytest.raises(ValueError):
        surf.set_sharpness([pairs[0]], [1.0, 2.0])
    with pytest.raises(ValueError, match="without creases"):
        surf.set_sharpness(crease_sharpness=2.0)
    with pytest.raises(ValueError, match="without corners"):
        surf.set_sharpness(corner_sharpness=[2.0])
    same(surf, ref)


def test_edits_while_other_threads_evaluate():
    """Evaluations in four threads while the main thread edits: no deadlock, every result one
    of the two surfaces, and the last state that of the last edit."""
    mesh = subsurf.read(SHAPES / "catmark_car.obj")
    pairs, own = mesh.creases
    surf = subsurf.LimitSurface(mesh)
    q = grid(surf, 5)
    states = [surf.evaluate(*q)[0]]
    surf.set_sharpness(pairs, 3.5)
    states.append(surf.evaluate(*q)[0])
    assert not np.array_equal(states[0], states[1])
    stop = threading.Event()

    def evaluate():
        seen = 0
        while not stop.is_set():
            p = surf.evaluate(*q)[0]
            assert any(np.array_equal(p, s) for s in states)
            seen += 1
        return seen

    with ThreadPoolExecutor(4) as pool:
        futures = [pool.submit(evaluate) for _ in range(4)]
        for k in range(12):
            surf.set_sharpness(pairs, own if k % 2 == 0 else 3.5)
        stop.set()
        assert sum(f.result(timeout=120) for f in futures) > 0
    assert np.array_equal(surf.evaluate(*q)[0], states[1])


def test_loop_surfaces_refuse_sharpness_edits():
    mesh = subsurf.read(SHAPES / "loop_pole8.obj")
    surf = subsurf.LimitSurface(mesh)
    with pytest.raises(subsurf.UnsupportedError):
        surf.set_sharpness([[0, 1]], [1.0])
    with pytest.raises(subsurf.UnsupportedError, match="editable Loop"):
        subsurf.LimitSurface(mesh, editable=True)


def test_one_sharpness_value_for_every_tag():
    """One value is every tag's, for a Mesh as for set_sharpness (the shared tag reading)."""
    mesh = subsurf.read(SHAPES / "catmark_cube_creases1.obj")
    pairs, _ = mesh.creases
    one = subsurf.Mesh(mesh.positions, (mesh.face_counts, mesh.face_indices), creases=pairs,
                       crease_sharpness=2.5, corners=[0, 1], corner_sharpness=3.0)
    assert np.array_equal(one.creases[1], np.full(len(pairs), 2.5, dtype=np.float32))
    assert np.array_equal(one.corners[1], np.full(2, 3.0, dtype=np.float32))
    surf = subsurf.LimitSurface(mesh)
    surf.set_sharpness(pairs, 2.5, corners=[0, 1], corner_sharpness=3.0)
    same(surf, subsurf.LimitSurface(one))

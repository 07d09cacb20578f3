"""USD stages written by Pixar's own library (usd-core, `pxr`) for tests/io_usd.rs.

Usage:
  python3 usd_gen.py write OUT_DIR   stages (usda, usdc, usdz) + OUT_DIR/expected.json
  python3 usd_gen.py dump FILE        every mesh prim of FILE as JSON on standard output
  python3 usd_gen.py dumpall FILE...  {FILE: dump of FILE} for several files in one run
  python3 usd_gen.py same A B         exits 0 when layers A and B hold the same specs and values

`write` authors every UsdGeomMesh attribute subsurf reads (all crease forms, corners, holes,
st indexed and not, leftHanded, several prims under transforms) and writes, for each mesh
prim, the `Mesh` subsurf should read, computed here independently of subsurf: leftHanded
faces keep their first vertex and reverse the rest (as OpenSubdiv's USD consumers flip them),
crease chains become one tag per edge, USD's defaults fill unauthored options.

`dump` reads a file subsurf wrote through `Usd.Stage.Open` and prints each mesh prim's
authored values, its world transform and the other prims of the stage.
"""

import json
import os
import sys

from pxr import Gf, Sdf, Usd, UsdGeom, UsdUtils, Vt

CUBE_POINTS = [
    (-0.5, -0.5, 0.5), (0.5, -0.5, 0.5), (-0.5, 0.5, 0.5), (0.5, 0.5, 0.5),
    (-0.5, 0.5, -0.5), (0.5, 0.5, -0.5), (-0.5, -0.5, -0.5), (0.5, -0.5, -0.5),
]
CUBE_FACES = [[0, 1, 3, 2], [2, 3, 5, 4], [4, 5, 7, 6], [6, 7, 1, 0], [1, 7, 5, 3], [6, 0, 2, 4]]


def grid(n):
    """An n x n quad grid in the xy plane (open boundary)."""
    pts = [(float(i), float(j), 0.1 * ((i * 7 + j * 3) % 5)) for j in range(n + 1) for i in range(n + 1)]
    faces = []
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            faces.append([a, a + 1, a + n + 2, a + n + 1])
    return pts, faces


def flat(faces):
    return [len(f) for f in faces], [v for f in faces for v in f]


def flip(face):
    return [face[0]] + face[1:][::-1]


def define(stage, path, pts, faces, **attrs):
    mesh = UsdGeom.Mesh.Define(stage, path)
    counts, idx = flat(faces)
    mesh.CreatePointsAttr(Vt.Vec3fArray([Gf.Vec3f(*p) for p in pts]))
    mesh.CreateFaceVertexCountsAttr(Vt.IntArray(counts))
    mesh.CreateFaceVertexIndicesAttr(Vt.IntArray(idx))
    for name, value in attrs.items():
        getattr(mesh, "Create" + name[0].upper() + name[1:] + "Attr")(value)
    return mesh


def expected(pts, faces, left=False, creases=(), corners=(), holes=(), uv=None, **opts):
    """The subsurf `Mesh` a reader should produce, as plain JSON."""
    fs = [flip(f) if left else list(f) for f in faces]
    counts, idx = flat(fs)
    out = {
        "positions": [list(p) for p in pts],
        "face_counts": counts,
        "face_indices": idx,
        "creases": [list(c) for c in creases],
        "corners": [list(c) for c in corners],
        "holes": list(holes),
        "scheme": opts.get("scheme", "catmullClark"),
        "boundary": opts.get("boundary", "edgeAndCorner"),
        "fvar": opts.get("fvar", "cornersPlus1"),
        "triangles": opts.get("triangles", "catmullClark"),
    }
    if uv is not None:
        values, corner_idx = uv
        # Face-varying data follows each face's corners, so it flips with the face.
        per_face, k = [], 0
        for f in faces:
            c = corner_idx[k:k + len(f)]
            per_face.append(flip(c) if left else c)
            k += len(f)
        out["uv_values"] = [list(v) for v in values]
        out["uv_indices"] = [i for c in per_face for i in c]
    return out


def chain_edges(indices, lengths, sharp):
    """Crease chains as one (v0, v1, s) per edge; one sharpness per chain or per edge."""
    per_edge = len(sharp) != len(lengths)
    edges, k, e = [], 0, 0
    for c, n in enumerate(lengths):
        for i in range(n - 1):
            s = sharp[e] if per_edge else sharp[c]
            edges.append((indices[k + i], indices[k + i + 1], s))
            e += 1
        k += n
    return edges


def write(out):
    stage = Usd.Stage.CreateInMemory()
    UsdGeom.SetStageUpAxis(stage, UsdGeom.Tokens.y)
    world = UsdGeom.Xform.Define(stage, "/World")
    world.AddTranslateOp().Set(Gf.Vec3d(1.0, 2.0, 3.0))
    stage.SetDefaultPrim(world.GetPrim())
    exp = {}

    # A: cube, leftHanded, one sharpness per crease chain, corners, a hole, st indexed.
    c_idx, c_len, c_sharp = [0, 1, 3, 2, 4, 5], [4, 2], [2.5, 10.0]
    uv_vals = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0), (0.5, 0.5)]
    uv_idx = [(i * 3 + k) % 5 for i in range(6) for k in range(4)]
    a = define(stage, "/World/A", CUBE_POINTS, CUBE_FACES,
               orientation=UsdGeom.Tokens.leftHanded,
               creaseIndices=Vt.IntArray(c_idx), creaseLengths=Vt.IntArray(c_len),
               creaseSharpnesses=Vt.FloatArray(c_sharp),
               cornerIndices=Vt.IntArray([6, 7]), cornerSharpnesses=Vt.FloatArray([3.0, 1.5]),
               holeIndices=Vt.IntArray([2]))
    pv = UsdGeom.PrimvarsAPI(a).CreatePrimvar("st", Sdf.ValueTypeNames.TexCoord2fArray,
                                             UsdGeom.Tokens.faceVarying)
    pv.Set(Vt.Vec2fArray([Gf.Vec2f(*v) for v in uv_vals]))
    pv.SetIndices(Vt.IntArray(uv_idx))
    exp["/World/A"] = expected(CUBE_POINTS, CUBE_FACES, left=True,
                               creases=chain_edges(c_idx, c_len, c_sharp),
                               corners=[(6, 3.0), (7, 1.5)], holes=[2], uv=(uv_vals, uv_idx))

    # B: grid under a rotated, scaled xform; one sharpness per crease edge; st not indexed;
    # every option authored away from USD's defaults.
    grp = UsdGeom.Xform.Define(stage, "/World/Group")
    grp.AddRotateXYZOp().Set(Gf.Vec3f(0.0, 90.0, 0.0))
    grp.AddScaleOp().Set(Gf.Vec3f(2.0, 2.0, 2.0))
    pts, faces = grid(3)
    c_idx, c_len, c_sharp = [0, 1, 2, 3, 5, 6, 7], [4, 3], [1.0, 2.0, 3.0, 4.0, 5.0]
    b = define(stage, "/World/Group/B", pts, faces,
               subdivisionScheme=UsdGeom.Tokens.bilinear,
               interpolateBoundary=UsdGeom.Tokens.edgeOnly,
               faceVaryingLinearInterpolation=UsdGeom.Tokens.all,
               triangleSubdivisionRule=UsdGeom.Tokens.smooth,
               creaseIndices=Vt.IntArray(c_idx), creaseLengths=Vt.IntArray(c_len),
               creaseSharpnesses=Vt.FloatArray(c_sharp))
    nc = sum(len(f) for f in faces)
    uv_vals = [(0.01 * i, 1.0 - 0.02 * i) for i in range(nc)]
    pv = UsdGeom.PrimvarsAPI(b).CreatePrimvar("st", Sdf.ValueTypeNames.TexCoord2fArray,
                                             UsdGeom.Tokens.faceVarying)
    pv.Set(Vt.Vec2fArray([Gf.Vec2f(*v) for v in uv_vals]))
    exp["/World/Group/B"] = expected(pts, faces, creases=chain_edges(c_idx, c_len, c_sharp),
                                     uv=(uv_vals, list(range(nc))), scheme="bilinear",
                                     boundary="edgeOnly", fvar="all", triangles="smooth")

    # C: triangles for Loop, boundary none, fvar boundaries.
    tri_pts = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0.5)]
    tri_faces = [[0, 1, 2], [2, 1, 3]]
    define(stage, "/C", tri_pts, tri_faces, subdivisionScheme=UsdGeom.Tokens.loop,
           interpolateBoundary=UsdGeom.Tokens.none,
           faceVaryingLinearInterpolation=UsdGeom.Tokens.boundaries)
    exp["/C"] = expected(tri_pts, tri_faces, scheme="loop", boundary="none", fvar="boundaries")

    # D: a polygon mesh (scheme none) next to a non-mesh prim.
    define(stage, "/World/D", CUBE_POINTS, CUBE_FACES, subdivisionScheme=UsdGeom.Tokens.none,
           faceVaryingLinearInterpolation=UsdGeom.Tokens.cornersOnly)
    exp["/World/D"] = expected(CUBE_POINTS, CUBE_FACES, scheme="none", fvar="cornersOnly")
    UsdGeom.Sphere.Define(stage, "/World/Ball").CreateRadiusAttr(0.25)

    for p in exp:
        xf = UsdGeom.Xformable(stage.GetPrimAtPath(p)).ComputeLocalToWorldTransform(0)
        exp[p]["world"] = [list(xf.GetRow(r)) for r in range(4)]
    stage.GetRootLayer().Export(os.path.join(out, "stage.usda"))
    stage.GetRootLayer().Export(os.path.join(out, "stage.usdc"))
    UsdUtils.CreateNewUsdzPackage(Sdf.AssetPath(os.path.join(out, "stage.usdc")),
                                  os.path.join(out, "stage.usdz"))
    with open(os.path.join(out, "expected.json"), "w") as f:
        json.dump(exp, f)


def dump(path):
    print(json.dumps(read_stage(path)))


def read_stage(path):
    stage = Usd.Stage.Open(path)
    if not stage:
        raise SystemExit(f"pxr could not open {path}")
    meshes, others = {}, []
    for prim in stage.Traverse():
        if not prim.IsA(UsdGeom.Mesh):
            others.append([str(prim.GetPath()), str(prim.GetTypeName())])
            continue
        m = UsdGeom.Mesh(prim)
        get = lambda a: a.Get() if a.HasAuthoredValue() else None
        d = {
            "points": [list(p) for p in m.GetPointsAttr().Get()],
            "faceVertexCounts": list(m.GetFaceVertexCountsAttr().Get()),
            "faceVertexIndices": list(m.GetFaceVertexIndicesAttr().Get()),
            "subdivisionScheme": str(m.GetSubdivisionSchemeAttr().Get()),
            "orientation": str(m.GetOrientationAttr().Get()),
            "interpolateBoundary": str(m.GetInterpolateBoundaryAttr().Get()),
            "faceVaryingLinearInterpolation": str(m.GetFaceVaryingLinearInterpolationAttr().Get()),
            "triangleSubdivisionRule": str(m.GetTriangleSubdivisionRuleAttr().Get()),
            "world": [list(r) for r in
                      (UsdGeom.Xformable(prim).ComputeLocalToWorldTransform(0).GetRow(i)
                       for i in range(4))],
        }
        for a in ["creaseIndices", "creaseLengths", "creaseSharpnesses", "cornerIndices",
                  "cornerSharpnesses", "holeIndices"]:
            v = get(getattr(m, "Get" + a[0].upper() + a[1:] + "Attr")())
            d[a] = list(v) if v is not None else []
        pv = UsdGeom.PrimvarsAPI(m).GetPrimvar("st")
        if pv and pv.HasAuthoredValue():
            d["st_interpolation"] = str(pv.GetInterpolation())
            d["st"] = [list(v) for v in pv.Get()]
            ind = pv.GetIndices()
            d["st_indices"] = list(ind) if ind is not None and len(ind) else None
        extent = m.GetExtentAttr().Get()
        d["extent"] = [list(e) for e in extent] if extent else None
        meshes[str(prim.GetPath())] = d
    return {"meshes": meshes, "others": others}


if __name__ == "__main__":
    if sys.argv[1] == "write":
        os.makedirs(sys.argv[2], exist_ok=True)
        write(sys.argv[2])
    elif sys.argv[1] == "same":
        a, b = (Sdf.Layer.FindOrOpen(f) for f in sys.argv[2:4])
        if not a or not b:
            raise SystemExit("pxr could not open both layers")
        ta, tb = a.ExportToString(), b.ExportToString()
        if ta != tb:
            import difflib
            sys.stdout.writelines(difflib.unified_diff(
                ta.splitlines(True), tb.splitlines(True), sys.argv[2], sys.argv[3]))
            raise SystemExit(1)
    elif sys.argv[1] == "dumpall":
        print(json.dumps({f: read_stage(f) for f in sys.argv[2:]}))
    else:
        dump(sys.argv[2])

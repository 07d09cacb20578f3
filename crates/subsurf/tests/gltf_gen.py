"""glTF files from other writers (trimesh, pygltflib) for tests/io_gltf_read.rs.

Usage: python3 gltf_gen.py OUT_DIR

Writes the files and OUT_DIR/expected.json: for each file, its triangles in world space as
corner positions (and UVs in subsurf's convention, v = 1 - v_gltf, when the file has them),
computed here with numpy and trimesh, independently of subsurf.
"""

import base64
import json
import os
import sys

import numpy as np
import pygltflib
import trimesh


def seam_cube():
    """A unit cube with one UV chart per face: 24 vertices, positions repeated at seams."""
    verts, uvs, faces = [], [], []
    for axis in range(3):
        for sign in (-1.0, 1.0):
            u_ax, v_ax = [a for a in range(3) if a != axis]
            base = len(verts)
            for du, dv in ((0, 0), (1, 0), (1, 1), (0, 1)):
                p = [0.0, 0.0, 0.0]
                p[axis] = 0.5 * sign
                p[u_ax] = du - 0.5
                p[v_ax] = dv - 0.5
                verts.append(p)
                uvs.append([(axis * 2 + (sign > 0) + du) / 6.0, dv * 0.5 + 0.25])
            quad = [base, base + 1, base + 2, base + 3]
            # Outward winding: the normal (u x v) points along +axis for an even permutation.
            outward = np.cross(np.eye(3)[u_ax], np.eye(3)[v_ax])[axis] * sign > 0
            if not outward:
                quad = quad[::-1]
            faces += [[quad[0], quad[1], quad[2]], [quad[0], quad[2], quad[3]]]
    return np.array(verts), np.array(uvs), np.array(faces)


def corners(world, faces, uvs=None):
    out = {"positions": world[faces].reshape(-1, 3).tolist()}
    if uvs is not None:
        uv = uvs[faces].reshape(-1, 2).copy()
        uv[:, 1] = 1.0 - uv[:, 1]
        out["uvs"] = uv.tolist()
    return out


def with_trimesh(out, expected):
    v, uv, f = seam_cube()
    # trimesh stores UVs with the origin at the bottom left and flips v on export.
    # A PBR material without an image: no PIL needed.
    mat = trimesh.visual.material.PBRMaterial(baseColorFactor=[200, 200, 200, 255])
    visual = trimesh.visual.TextureVisuals(uv=uv * [1, -1] + [0, 1], material=mat)
    cube = trimesh.Trimesh(vertices=v, faces=f, visual=visual, process=False)
    cube.export(os.path.join(out, "tm_cube.glb"))
    files = trimesh.Scene(cube).export(file_type="gltf")
    for name, data in files.items():
        with open(os.path.join(out, "tm_cube_" + name if name != "model.gltf" else "tm_cube.gltf"), "wb") as fh:
            fh.write(data)
    # The .gltf names its buffers: rewrite the names to the prefixed files.
    path = os.path.join(out, "tm_cube.gltf")
    doc = json.load(open(path))
    for b in doc["buffers"]:
        b["uri"] = "tm_cube_" + b["uri"]
    json.dump(doc, open(path, "w"))
    expected["tm_cube.glb"] = corners(v, f, uv)
    expected["tm_cube.gltf"] = corners(v, f, uv)

    # A scene: three cubes under translation, rotation + scale, and a mirror.
    T = trimesh.transformations
    scene = trimesh.Scene()
    mats = [
        T.translation_matrix([3, 0, 0]),
        T.concatenate_matrices(T.translation_matrix([0, 4, 0]), T.rotation_matrix(np.pi / 2, [0, 0, 1]), np.diag([2, 1, 1, 1])),
        T.concatenate_matrices(T.translation_matrix([0, 0, -5]), np.diag([-1, 1, 1, 1])),
    ]
    for k, m in enumerate(mats):
        g = trimesh.Trimesh(vertices=v, faces=f, process=False)
        scene.add_geometry(g, node_name=f"cube{k}", geom_name=f"cube{k}", transform=m)
    scene.export(os.path.join(out, "tm_scene.glb"))
    world = scene.to_geometry()
    # trimesh keeps a mirrored instance's triangles as stored; the glTF rule (and subsurf)
    # reverses their winding so they stay outward.
    tris = []
    for k, m in enumerate(mats):
        w = trimesh.transform_points(v, m)
        ff = f[:, ::-1] if np.linalg.det(m[:3, :3]) < 0 else f
        tris.append(w[ff].reshape(-1, 3))
    assert np.allclose(np.sort(np.concatenate(tris), axis=0), np.sort(world.vertices[world.faces].reshape(-1, 3), axis=0))
    expected["tm_scene.glb"] = {"positions": np.concatenate(tris).tolist()}


def with_pygltflib(out, expected):
    v, uv, f = seam_cube()
    pos = v.astype(np.float32)
    tex = uv.astype(np.float32)
    # Two primitives: the first 6 triangles as u8 indices, the rest as a u16 triangle strip
    # of single triangles is not possible, so: u16 triangles, and a u32 fan of one quad.
    i8 = f[:6].astype(np.uint8).tobytes()
    i16 = f[6:10].astype(np.uint16).tobytes()
    fan = np.array([f[10][0], f[10][1], f[10][2], f[11][2]], dtype=np.uint32).tobytes()
    blobs = [pos.tobytes(), tex.tobytes(), i8, i16, fan]
    data = b""
    views = []
    for b in blobs:
        views.append(pygltflib.BufferView(buffer=0, byteOffset=len(data), byteLength=len(b)))
        data += b + b"\0" * (-len(b) % 4)
    acc = [
        pygltflib.Accessor(bufferView=0, componentType=pygltflib.FLOAT, count=24, type="VEC3",
                           min=pos.min(0).tolist(), max=pos.max(0).tolist()),
        pygltflib.Accessor(bufferView=1, componentType=pygltflib.FLOAT, count=24, type="VEC2"),
        pygltflib.Accessor(bufferView=2, componentType=pygltflib.UNSIGNED_BYTE, count=18, type="SCALAR"),
        pygltflib.Accessor(bufferView=3, componentType=pygltflib.UNSIGNED_SHORT, count=12, type="SCALAR"),
        pygltflib.Accessor(bufferView=4, componentType=pygltflib.UNSIGNED_INT, count=4, type="SCALAR"),
    ]
    attrs = pygltflib.Attributes(POSITION=0, TEXCOORD_0=1)
    prims = [
        pygltflib.Primitive(attributes=attrs, indices=2, mode=pygltflib.TRIANGLES),
        pygltflib.Primitive(attributes=attrs, indices=3, mode=pygltflib.TRIANGLES),
        pygltflib.Primitive(attributes=attrs, indices=4, mode=pygltflib.TRIANGLE_FAN),
        pygltflib.Primitive(attributes=attrs, mode=pygltflib.POINTS),
    ]
    # Node 0 (TRS) has child node 1 (matrix) holding the mesh.
    q = [0.0, np.sin(np.pi / 4), 0.0, np.cos(np.pi / 4)]  # 90 degrees about y.
    child = np.eye(4)
    child[:3, 3] = [0, 0, 2]
    gltf = pygltflib.GLTF2(
        scene=0,
        scenes=[pygltflib.Scene(nodes=[0])],
        nodes=[
            pygltflib.Node(translation=[1, 0, 0], rotation=q, scale=[1, 3, 1], children=[1]),
            pygltflib.Node(matrix=child.T.flatten().tolist(), mesh=0),
        ],
        meshes=[pygltflib.Mesh(name="cube", primitives=prims)],
        accessors=acc,
        bufferViews=views,
        buffers=[pygltflib.Buffer(byteLength=len(data))],
    )
    gltf.set_binary_blob(data)
    gltf.save_binary(os.path.join(out, "pg_cube.glb"))
    # The same as .gltf with a data: URI.
    gltf.buffers[0].uri = "data:application/octet-stream;base64," + base64.b64encode(data).decode()
    gltf.save_json(os.path.join(out, "pg_cube.gltf"))

    R = trimesh.transformations.quaternion_matrix([q[3], q[0], q[1], q[2]])
    world_m = trimesh.transformations.translation_matrix([1, 0, 0]) @ R @ np.diag([1, 3, 1, 1]) @ child
    world = trimesh.transform_points(v, world_m)
    ff = np.concatenate([f[:10], [[f[10][1], f[10][2], f[10][0]], [f[10][2], f[11][2], f[10][0]]]])
    expected["pg_cube.glb"] = corners(world, ff, uv)
    expected["pg_cube.gltf"] = corners(world, ff, uv)
    expected["pg_cube.glb"]["local"] = corners(v, ff, uv)["positions"]


def main():
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    expected = {}
    with_trimesh(out, expected)
    with_pygltflib(out, expected)
    with open(os.path.join(out, "expected.json"), "w") as fh:
        json.dump(expected, fh)


if __name__ == "__main__":
    main()

# Copied verbatim (below this header) from the p-rep specification, shared/spec/verify_prep.py,
# so that a clone of this repository can run the prep_verify test without the specification folder.
# It is an independent numpy implementation of prep.md; do not edit it to make a test pass.
#!/usr/bin/env python3
"""verify_prep.py -- numpy-only reference and checker for the p-rep of Myles/Yeo/Peters 2008,
written straight from prep.md (same symbols and equation numbers).

  python3 verify_prep.py                  self-test on built-in closed meshes (C0 / G1 / B-spline checks)
  python3 verify_prep.py --vectors        also print the test vectors quoted in prep.md
  python3 verify_prep.py MESH.obj BB.npy  check YOUR bi-5 BB control points for a closed quad OBJ mesh.
        BB.npy: float array (F,6,6,3); BB[f,i,j] = b_ij of face f, with i running along v0->v1 and
        j along v0->v3, where (v0,v1,v2,v3) = the face's vertices as listed in the OBJ file (counter-clockwise).
        Also accepts (F,4,4,3) g plus (F,6,6,3) h, stacked as an .npz archive with keys 'g' and 'h'.
"""
import sys
import numpy as np
from math import comb

# ------------------------------------------------------------------------------------------------
# Mesh: closed, consistently oriented (ccw) manifold quad mesh.  One-ring numbering as in prep.md §1:
# at vertex p0 of valence n, sector k (k=0..n-1) is the face (p0, p_{2k+1}, p_{2k+2}, p_{2k+3});
# odd p's are edge neighbours, even p's are face-diagonal neighbours, indices mod 2n (p_{2n+1}=p_1).
class Mesh:
    def __init__(self, V, F):
        self.V, self.F = np.asarray(V, float), np.asarray(F, int)
        self.he = {(q[c], q[(c + 1) % 4]): (f, c) for f, q in enumerate(self.F) for c in range(4)}
        assert len(self.he) == 4 * len(self.F), "repeated directed edge: non-manifold or inconsistent orientation"
        assert all((b, a) in self.he for (a, b) in self.he), "mesh has a boundary: the p-rep needs a CLOSED mesh"
        first = {}
        for f, q in enumerate(self.F):
            for c in range(4):
                first.setdefault(q[c], (f, c))
        self.ring, self.sector = [], {}            # sector[(f,c)] = k of face f at its corner c
        for v in range(len(self.V)):
            f, c = first[v]; ring, f0 = [], f
            while True:
                q = self.F[f]
                self.sector[(f, c)] = len(ring) // 2
                ring += [q[(c + 1) % 4], q[(c + 2) % 4]]            # p_{2k+1}, p_{2k+2}
                f, c = self.he[(v, q[(c + 3) % 4])]                 # next sector: face owning v -> p_{2k+3}
                if f == f0:
                    break
            self.ring.append(ring)
        self.val = np.array([len(r) // 2 for r in self.ring])
        assert self.val.min() >= 3, "valence < 3"

# ------------------------------------------------------------------------------------------------
# Vertex stage: (2) limit point, (3) tangent coefficients, (4) interior coefficients      (d = 3)
def lam(n):                                   # subdominant Catmull-Clark eigenvalue lambda_n
    c = np.cos(2 * np.pi / n)
    return (c + 5 + np.sqrt((c + 9) * (c + 1))) / 16

def vertex_stage(V, n, d=3):
    p0, P = V[0], V[1:]                       # V = [p0, p1, ..., p2n]
    pe, pf = P[0::2], P[1::2]                 # pe[j-1] = p_{2j-1},  pf[j-1] = p_{2j}
    g00 = (n * n * p0 + 4 * pe.sum(0) + pf.sum(0)) / (n * (n + 5))                          # (2)
    w = 16 * lam(n) - 4
    sig = 0.53 if n == 3 else 1 / (4 * lam(n))
    a = 2 * np.pi * np.arange(n + 1) / n
    c, s = np.cos(a), np.sin(a)                                                               # c^j, s^j
    e1 = sig / (d * (2 + w)) * ((w * c[:-1])[:, None] * pe + (c[:-1] + c[1:])[:, None] * pf).sum(0)   # (3)
    e2 = sig / (d * (2 + w)) * ((w * s[:-1])[:, None] * pe + (s[:-1] + s[1:])[:, None] * pf).sum(0)
    t = g00 + np.outer(c[:-1], e1) + np.outer(s[:-1], e2)                                      # g^k_10, k=0..n-1
    g11 = np.array([(4 * p0 + 2 * (pe[k] + pe[(k + 1) % n]) + pf[k]) / 9 for k in range(n)])  # (4)
    return g00, e1, e2, t, g11

# corner frames: local (i,j) at corner c of a (d+1)x(d+1) array -> face (global) index
def gidx(c, i, j, d):
    return [(i, j), (d - j, i), (d - i, d - j), (j, d - i)][c]

def local(A, c):
    d = A.shape[0] - 1
    return np.array([[A[gidx(c, i, j, d)] for j in range(d + 1)] for i in range(d + 1)])

# ------------------------------------------------------------------------------------------------
# Edge stage: perturbation h20,h30,h21,h31 of the edge v0->v1 (local frame of corner v0), eqs (8),(9)
def edge_h(g, gs, n0, n1, h31="sym"):
    Z = np.zeros(3)
    if n0 == 4 and n1 == 4:                                                   # Case 1
        return Z, Z, Z, Z
    c0, c1 = np.cos(2 * np.pi / n0), np.cos(2 * np.pi / n1)
    S0, S1 = g[1, 1] + gs[1, 1], g[2, 1] + gs[1, 2]
    T0, T1 = g[0, 1] + gs[1, 0], g[3, 1] + gs[1, 3]
    g00, g10, g20, g30 = g[0, 0], g[1, 0], g[2, 0], g[3, 0]
    if n1 == 4:                                                               # Case 2 <n0,4>
        h20 = h30 = 3 / 40 * (-2 * g00 + (6 - 6 / c0) * g10 - 4 * g20 + 3 / c0 * S0)
        h21 = (1 - 2 * c0 / 5) * h20 + 3 / 100 * (2 * c0 * g00 + (12 - 6 * c0) * g10 + (6 + 2 * c0) * g20
                                                  + 2 * c0 * g30 - 6 * S0 - 3 * S1)
        if h31 == "sym":
            h31v = h30 + 3 / 100 * (6 * g10 + (12 - 2 * c0) * g20 + (2 + 2 * c0) * g30 - 3 * S0 - 6 * S1 - T1)
        else:   # exactly as printed in (8)
            h31v = h30 + 3 / 100 * ((-2 + 2 * c0) * g00 + (6 - 2 * c0) * g10 + (12 - 2 * c0) * g20 + (2 + 2 * c0) * g30
                                    + 2 * g[0, 1] - 9 * g[2, 1] - 2 * g[3, 1] - 6 * gs[1, 1] - 3 * gs[1, 2])
        return h20, h30, h21, h31v
    if n0 == 4:                                                               # Case 3 <4,n1>
        h20 = h30 = 3 / 40 * (-2 * g30 + (6 - 6 / c1) * g20 - 4 * g10 + 3 / c1 * S1)
        h31v = (1 - 2 * c1 / 5) * h30 + 3 / 100 * (2 * c1 * g30 + (12 - 6 * c1) * g20 + (6 + 2 * c1) * g10
                                                   + 2 * c1 * g00 - 6 * S1 - 3 * S0)
        if h31 == "sym":
            h21 = h20 + 3 / 100 * (6 * g20 + (12 - 2 * c1) * g10 + (2 + 2 * c1) * g00 - 3 * S1 - 6 * S0 - T0)
        else:
            h21 = h20 + 3 / 100 * ((-2 + 2 * c1) * g30 + (6 - 2 * c1) * g20 + (12 - 2 * c1) * g10 + (2 + 2 * c1) * g00
                                   + 2 * g[3, 1] - 9 * g[1, 1] - 2 * g[0, 1] - 6 * gs[1, 2] - 3 * gs[1, 1])
        return h20, h30, h21, h31v
    h20 = 3 / 40 * (-2 * c1 / c0 * g00 + (4 + (2 * c1 - 6) / c0) * g10 - 4 * g20 + 3 / c0 * S0)   # Case 4
    h30 = 3 / 40 * (-2 * c0 / c1 * g30 + (4 + (2 * c0 - 6) / c1) * g20 - 4 * g10 + 3 / c1 * S1)
    h21 = (1 - 3 * c0 / 5 - 2 * c1 / 5) * h20 + 3 * c0 / 5 * h30 + 3 / 100 * (
        4 * c1 * g00 + (12 - 8 * c0) * g10 + (6 + 6 * c0 - 4 * c1) * g20 + 2 * c0 * g30 - 6 * S0 - 3 * S1)
    h31v = (1 - 3 * c1 / 5 - 2 * c0 / 5) * h30 + 3 * c1 / 5 * h20 + 3 / 100 * (
        4 * c0 * g30 + (12 - 8 * c1) * g20 + (6 + 6 * c1 - 4 * c0) * g10 + 2 * c1 * g00 - 6 * S1 - 3 * S0)
    return h20, h30, h21, h31v

# ------------------------------------------------------------------------------------------------
E35 = np.array([[10, 0, 0, 0], [4, 6, 0, 0], [1, 6, 3, 0], [0, 3, 6, 1], [0, 0, 6, 4], [0, 0, 0, 10]]) / 10.

def build(m, h31="sym"):
    """returns g (F,4,4,3), h (F,6,6,3), b = E g E^T + h  (F,6,6,3)   -- eq. (10)"""
    vs = [vertex_stage(m.V[[v] + m.ring[v]], m.val[v]) for v in range(len(m.V))]
    g = np.zeros((len(m.F), 4, 4, 3)); h = np.zeros((len(m.F), 6, 6, 3))
    for f, q in enumerate(m.F):
        for c in range(4):                                       # corner data, rotated into the face frame
            g00, _, _, t, g11 = vs[q[c]]; k = m.sector[(f, c)]; n = m.val[q[c]]
            for (i, j), val in (((0, 0), g00), ((1, 0), t[k]), ((0, 1), t[(k + 1) % n]), ((1, 1), g11[k])):
                g[f][gidx(c, i, j, 3)] = val
    for f, q in enumerate(m.F):
        for c in range(4):                                       # edge leaving corner c (ccw)
            f2, c2 = m.he[(q[(c + 1) % 4], q[c])]                # neighbour = sector k-1 at v_c
            hs = edge_h(local(g[f], c), local(g[f2], (c2 + 1) % 4), m.val[q[c]], m.val[q[(c + 1) % 4]], h31)
            for (i, j), val in zip(((2, 0), (3, 0), (2, 1), (3, 1)), hs):
                h[f][gidx(c, i, j, 5)] = val
    b = np.einsum('ia,jb,fabk->fijk', E35, E35, g) + h
    return g, h, b

# ------------------------------------------------------------------------------------------------
# Checks: C0 (shared boundary control points), G1 (normal angle along each edge, residual of (5))
def bern(d, t):
    B = np.array([comb(d, i) * (1 - t) ** (d - i) * t ** i for i in range(d + 1)])
    Bm = np.array([comb(d - 1, i) * (1 - t) ** (d - 1 - i) * t ** i for i in range(d)])
    z = np.zeros((1,) + Bm.shape[1:])
    return B, d * (np.vstack([z, Bm]) - np.vstack([Bm, z]))

def derivs(P, u, v):                                             # S_u, S_v of a BB patch at points (u,v)
    (Bu, dBu), (Bv, dBv) = bern(P.shape[0] - 1, u), bern(P.shape[0] - 1, v)
    return np.einsum('in,jn,ijk->nk', dBu, Bv, P), np.einsum('in,jn,ijk->nk', Bu, dBv, P)

def check(m, b, ns=101):
    u = np.linspace(0, 1, ns); z = 0 * u; out = dict(C0=0., angle=0., res5=0., C1_at_4=0.)
    for f, q in enumerate(m.F):
        for c in range(4):
            f2, c2 = m.he[(q[(c + 1) % 4], q[c])]
            L, Ls = local(b[f], c), local(b[f2], (c2 + 1) % 4)  # patch k and patch k-1 at v_c
            n0, n1 = m.val[q[c]], m.val[q[(c + 1) % 4]]
            out['C0'] = max(out['C0'], np.abs(L[:, 0] - Ls[0, :]).max())
            Su, Sv = derivs(L, u, z); Sus, Svs = derivs(Ls, z, u)
            N1, N2 = np.cross(Su, Sv), np.cross(Sus, Svs)
            ang = np.arctan2(np.linalg.norm(np.cross(N1, N2), axis=1), np.einsum('ik,ik->i', N1, N2))
            c0, c1 = np.cos(2 * np.pi / n0), np.cos(2 * np.pi / n1)
            lam_u = {(True, True): 0 * u, (False, True): 2 * c0 * (1 - u) ** 2,
                     (True, False): -2 * c1 * u ** 2}.get((n0 == 4, n1 == 4), 2 * c0 * (1 - u) - 2 * c1 * u)
            r = np.linalg.norm(Sv + Sus - lam_u[:, None] * Su, axis=1) / np.linalg.norm(Su, axis=1).max()
            out['angle'] = max(out['angle'], ang.max()); out['res5'] = max(out['res5'], r.max())
            for end, nn in ((-1, n1), (0, n0)):   # C1 (not only G1) at a valence-4 end: dv b^k + dw b^{k-1} = 0
                if nn == 4:
                    out['C1_at_4'] = max(out['C1_at_4'], r[end])
    return out

# ------------------------------------------------------------------------------------------------
# Built-in test meshes (deterministic)
def cube():
    V = [[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)]
    return Mesh(V, [[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4], [1, 5, 7, 3]])

def capped_prism(n):        # valences n (cap centres), 3 (corners), 4 (mid-edges): <n,4>,<3,4>,<3,3>,<4,4>
    a = lambda i: 2 * np.pi * i / n
    V = [[0, 0, 1], [0, 0, -1]]
    for z in (1, -1):
        V += [[np.cos(a(i)), np.sin(a(i)), z] for i in range(n)] + [[np.cos(a(i + .5)), np.sin(a(i + .5)), z] for i in range(n)]
    T, M, B, BM = (lambda i: 2 + i % n), (lambda i: 2 + n + i % n), (lambda i: 2 + 2 * n + i % n), (lambda i: 2 + 3 * n + i % n)
    F = []
    for i in range(n):
        F += [[0, M(i - 1), T(i), M(i)], [1, BM(i), B(i), BM(i - 1)], [T(i), B(i), BM(i), M(i)], [M(i), BM(i), B(i + 1), T(i + 1)]]
    return Mesh(V, F)

def icosphere1():
    t = (1 + 5 ** .5) / 2
    V = [np.array(v, float) / np.linalg.norm(v) for v in [[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t],
         [0, 1, t], [0, -1, -t], [0, 1, -t], [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]]]
    T = [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4], [11, 10, 2], [10, 7, 6], [7, 1, 8],
         [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9], [4, 9, 5], [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1]]
    mid = {}
    for a_, b_, c_ in T:
        for x, y in ((a_, b_), (b_, c_), (c_, a_)):
            if (min(x, y), max(x, y)) not in mid:
                p = V[x] + V[y]; V.append(p / np.linalg.norm(p)); mid[(min(x, y), max(x, y))] = len(V) - 1
    return np.array(V)

MIXED40 = [[35, 4, 24, 27], [33, 4, 35, 34], [7, 19, 20, 12], [1, 15, 22, 23], [7, 18, 16, 15], [23, 9, 32, 41], [34, 36, 3, 32],
    [3, 36, 37, 38], [30, 17, 1, 23], [12, 21, 11, 13], [34, 35, 2, 36], [37, 6, 39, 8], [32, 3, 38, 40], [37, 36, 2, 26],
    [28, 29, 19, 7], [28, 7, 17, 31], [39, 28, 31, 8], [28, 39, 6, 29], [16, 18, 0, 14], [41, 32, 40, 8], [15, 1, 17, 7],
    [12, 20, 10, 21], [37, 26, 29, 6], [12, 0, 18, 7], [21, 10, 29, 26], [22, 33, 9, 23], [8, 40, 38, 37], [34, 32, 9, 33],
    [33, 22, 25, 4], [8, 30, 23, 41], [27, 26, 2, 35], [31, 17, 30, 8], [5, 14, 0, 12], [19, 29, 10, 20], [13, 11, 27, 24],
    [13, 24, 4, 25], [11, 21, 26, 27], [16, 14, 5, 15], [15, 5, 25, 22], [12, 13, 25, 5]]   # valences 3,4,5,6; all pairs

def torus(nu=8, nv=6):
    V = [[(2 + .7 * np.cos(2 * np.pi * j / nv)) * np.cos(2 * np.pi * i / nu), (2 + .7 * np.cos(2 * np.pi * j / nv)) *
          np.sin(2 * np.pi * i / nu), .7 * np.sin(2 * np.pi * j / nv)] for i in range(nu) for j in range(nv)]
    ix = lambda i, j: (i % nu) * nv + j % nv
    return Mesh(V, [[ix(i, j), ix(i + 1, j), ix(i + 1, j + 1), ix(i, j + 1)] for i in range(nu) for j in range(nv)])

def wobble(m, a=0.03):      # deterministic, non-symmetric perturbation (no RNG)
    i = np.arange(len(m.V))[:, None]
    return Mesh(m.V + a * np.sin(12.9898 * i + np.array([0., 1.7, 3.1])), m.F)

def bspline_check(m, g):    # faces with four valence-4 corners must equal the B-spline -> Bezier conversion
    A = np.array([[1, 4, 1, 0], [0, 4, 2, 0], [0, 2, 4, 0], [0, 1, 4, 1]]) / 6.
    err = 0.
    for f, q in enumerate(m.F):
        if all(m.val[q] == 4):
            P = np.zeros((4, 4, 3))                          # 4x4 B-spline grid from the four one-rings
            for cc, (bi, bj) in enumerate(((1, 1), (2, 1), (2, 2), (1, 2))):
                v = q[cc]; kk = m.sector[(f, cc)]; rr = m.ring[v]
                loc = {(0, 0): m.V[v]}
                dirs = [(1, 0), (0, 1), (-1, 0), (0, -1)]
                for j in range(4):
                    (x, y), (x2, y2) = dirs[j], dirs[(j + 1) % 4]
                    loc[(x, y)] = m.V[rr[(2 * (kk + j)) % 8]]; loc[(x + x2, y + y2)] = m.V[rr[(2 * (kk + j) + 1) % 8]]
                for (x, y), p in loc.items():
                    gi, gj = gidx(cc, x, y, 0)
                    P[bi + gi, bj + gj] = p
            err = max(err, np.abs(g[f] - np.einsum('ia,jb,abk->ijk', A, A, P)).max())
    return err

def read_obj(path):
    V, F = [], []
    for line in open(path):
        w = line.split()
        if w and w[0] == 'v': V.append([float(x) for x in w[1:4]])
        if w and w[0] == 'f': F.append([int(x.split('/')[0]) - 1 for x in w[1:]])
    assert all(len(q) == 4 for q in F), "quads only"
    return Mesh(V, F)

def fmt(x):
    return "(" + ", ".join("%.10f" % v for v in x) + ")"

if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if not a.startswith('--')]
    if len(args) == 2:                                           # check a user's BB control points
        m = read_obj(args[0]); data = np.load(args[1])
        if args[1].endswith('.npz'):                             # p-rep form: b = E g E^T + h   (10)
            b = np.einsum('ia,jb,fabk->fijk', E35, E35, data['g']) + data['h']
        else:
            b = data
        r = check(m, b)
        print("your b:  C0 %.2e   G1 max normal angle %.2e rad   residual(5) %.2e   C1@valence4 %.2e" % tuple(r.values()))
        print("G1 surface:", "PASS" if r['C0'] < 1e-9 and r['angle'] < 1e-7 and r['C1_at_4'] < 1e-7 else "FAIL")
        for v in ("sym", "printed"):
            print("max |your b - reference b (h31=%s)| = %.3e" % (v, np.abs(b - build(m, v)[2]).max()))
        sys.exit(0)
    tests = [("cube", cube()), ("cube, wobbled", wobble(cube())), ("capped pentagonal prism, wobbled", wobble(capped_prism(5))),
             ("capped hexagonal prism", capped_prism(6)), ("mixed40 (val 3-6, all pairs)", Mesh(icosphere1(), MIXED40)),
             ("mixed40, wobbled", wobble(Mesh(icosphere1(), MIXED40), 0.02)), ("torus (all valence 4), wobbled", wobble(torus()))]
    ok = True
    print("%-36s %-8s %9s %10s %10s %10s %10s" % ("mesh", "h31", "C0", "angle/rad", "res(5)", "C1@val4", "Bspl(n=4)"))
    for name, m in tests:
        for v in ("sym", "printed"):
            g, h, b = build(m, v); r = check(m, b); e = bspline_check(m, g)
            ok &= r['C0'] < 1e-12 and r['angle'] < 1e-10 and r['res5'] < 1e-10 and r['C1_at_4'] < 1e-10 and e < 1e-12
            print("%-36s %-8s %9.1e %10.1e %10.1e %10.1e %10.1e" % (name, v, r['C0'], r['angle'], r['res5'], r['C1_at_4'], e))
    print("ALL CHECKS PASSED" if ok else "SOME CHECK FAILED")
    if '--vectors' in sys.argv:
        m = cube(); g, h, b = build(m)
        print("\nCube [0,1]^3, face 0 = (v0,v1,v2,v3) = (0,0,0),(0,0,1),(0,1,1),(0,1,0):")
        for i in range(4):
            print("  " + "  ".join("g%d%d=%s" % (i, j, fmt(g[0, i, j])) for j in range(4)))
        for (i, j) in sorted(set(zip(*np.nonzero(np.abs(h[0]).sum(-1) > 0)))):
            print("  h%d%d=%s" % (i, j, fmt(h[0, i, j])))
        print("  b_i0, b_i1 (bi-5, eq. 10):")
        for i in range(6):
            print("  b%d0=%s  b%d1=%s" % (i, fmt(b[0, i, 0]), i, fmt(b[0, i, 1])))
        m = wobble(Mesh(icosphere1(), MIXED40), 0.02)                 # vertex-stage vector: first valence-5 vertex
        v = int(np.nonzero(m.val == 5)[0][0]); n = 5
        g00, e1, e2, t, g11 = vertex_stage(m.V[[v] + m.ring[v]], n)
        print("\nVertex stage, n=5 (wobbled mixed40, vertex %d): lambda_5=%.12f w_5=%.12f sigma_5=%.12f" % (v, lam(5), 16 * lam(5) - 4, 1 / (4 * lam(5))))
        for i, p in enumerate(m.V[[v] + m.ring[v]]):
            print("  p%d = %s" % (i, fmt(p)))
        print("  g00 = %s\n  e1 = %s\n  e2 = %s" % (fmt(g00), fmt(e1), fmt(e2)))
        for k in range(n):
            print("  k=%d: g^k_10 = %s   g^k_11 = %s" % (k, fmt(t[k]), fmt(g11[k])))
        g, _, _ = build(m)
        for want in ((5, 4), (4, 6), (6, 5)):                     # Case 2, Case 3, Case 4 (c0 != c1)
            f, c = next((f, c) for f, q in enumerate(m.F) for c in range(4) if (m.val[q[c]], m.val[q[(c + 1) % 4]]) == want)
            q = m.F[f]; f2, c2 = m.he[(q[(c + 1) % 4], q[c])]
            gl, gsl = local(g[f], c), local(g[f2], (c2 + 1) % 4)
            print("\nEdge <%d,%d>: wobbled mixed40, face %d, corner %d. Inputs (local frame of corner v0):" % (want + (f, c)))
            for (i, j) in ((0, 0), (1, 0), (2, 0), (3, 0), (0, 1), (1, 1), (2, 1), (3, 1)):
                print("  g%d%d  = %s" % (i, j, fmt(gl[i, j])))
            for (i, j) in ((1, 0), (1, 1), (1, 2), (1, 3)):
                print("  g*%d%d = %s" % (i, j, fmt(gsl[i, j])))
            for var in ("sym", "printed"):
                hs = edge_h(gl, gsl, want[0], want[1], var)
                print("  h31-variant=%s:" % var)
                for nm, x in zip(("h20", "h30", "h21", "h31"), hs):
                    print("    %s = %s" % (nm, fmt(x)))

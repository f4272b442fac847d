#!/usr/bin/env python3
"""Render triangle meshes to a PNG, one panel per mesh, side by side (standard library only).

Usage:
  python3 scripts/render_mesh.py OUT.png MESH [MESH ...] [--focus X,Y,Z] [--radius R]
      [--view AZIMUTH,ELEVATION] [--size WxH] [--flat-color R,G,B] [--edges]

MESH: OBJ (v/f; polygons fan-triangulated), OFF, or PLY (ascii / binary little or big
endian); per-face red/green/blue PLY properties are used as face colours.

Camera: orthographic, shared by all panels.  --focus: point at the panel centre
(default: bounding-box centre of the first mesh).  --radius: half the visible width
in mesh units (default: half the first mesh's bounding-box diagonal); only triangles
with a vertex within 2*radius of the focus are drawn.  --view AZ,EL in degrees
(default 0,0: looking along -Z, Y up, X right; azimuth orbits the camera towards +X,
elevation towards +Y).  --size is per panel (default 800x800).

Shading: z-buffered flat Lambert with a headlight plus ambient, in the face colour
or --flat-color (default 200,200,200).  Back faces are drawn darker and bluish so
folded triangles stand out.  --edges overlays a thin dark wireframe.

--distance-to MESH [--distance-scale D]: colour each drawn face by how far its
centroid lies from MESH, blue at 0 to red at D or more (default: a hundredth of the
first mesh's bounding-box diagonal).  Rendering a target with --distance-to the
pair's remesh.obj shows what the remesh leaves out: a finger it cuts off is red,
though the remesh's own stretch colours cannot show a finger it does not have.

Example (remeshed hand beside the target's hand):
  python3 scripts/render_mesh.py hands.png out/remesh.obj target.obj \\
      --focus -0.8,1.33,-0.05 --radius 0.1 --edges
Example (the target's hand coloured by its distance to the remesh, red from 5 mm):
  python3 scripts/render_mesh.py gap.png target.obj --distance-to out/remesh.obj \\
      --distance-scale 0.005 --focus -0.8,1.33,-0.05 --radius 0.1 --edges
"""
import argparse, math, os, struct, sys, zlib

PLY_TYPES = dict(zip('char int8 uchar uint8 short int16 ushort uint16 int int32 uint uint32 '
                     'float float32 double float64'.split(), 'bbBBhhHHiiIIffdd'))  # -> struct codes


class MeshError(Exception):
    """A mesh file that cannot be read; the message names the problem."""


def fan(poly):
    return [(poly[0], poly[k], poly[k + 1]) for k in range(1, len(poly) - 1)]


def load_obj(data):
    verts, faces = [], []
    for line in data.decode('utf-8', 'replace').splitlines():
        t = line.split()
        if t and t[0] == 'v':
            verts.append(tuple(float(x) for x in t[1:4]))
        elif t and t[0] == 'f':  # 1-based, negative = relative; 0 ends up out of range
            idx = [int(w.split('/')[0]) for w in t[1:]]
            faces += fan([i - 1 if i > 0 else len(verts) + i if i < 0 else -1 for i in idx])
    return verts, faces, None


def load_off(data):
    lines = [t for t in (l.split('#')[0].split() for l in data.decode('utf-8', 'replace').splitlines()) if t]
    if not lines or not lines[0][0].endswith('OFF'):
        raise MeshError('missing OFF header')
    if len(lines[0]) == 1:  # counts on the line after "OFF"
        lines[:2] = [lines[0] + lines[1]]
    nv, nf, body = int(lines[0][1]), int(lines[0][2]), lines[1:]
    if len(body) < nv + nf:
        raise MeshError('truncated: expected %d vertex and %d face lines' % (nv, nf))
    verts = [tuple(float(x) for x in l[:3]) for l in body[:nv]]
    faces = []
    for l in body[nv:nv + nf]:
        faces += fan([int(x) for x in l[1:1 + int(l[0])]])
    return verts, faces, None


def load_ply(data):
    end = data.find(b'end_header')
    if not data.startswith(b'ply') or end < 0:
        raise MeshError('not a PLY file (missing "ply" magic or end_header)')
    body = data.index(b'\n', end) + 1
    fmt, elems = None, []
    for line in data[:end].decode('ascii', 'replace').splitlines():
        t = line.split()
        if t and t[0] == 'format':
            fmt = t[1]
        elif t and t[0] == 'element':
            elems.append((t[1], int(t[2]), []))
        elif t and t[0] == 'property':  # (name, list count type or None, value type)
            elems[-1][2].append((t[4], PLY_TYPES[t[2]], PLY_TYPES[t[3]]) if t[1] == 'list'
                                else (t[2], None, PLY_TYPES[t[1]]))
    if fmt == 'ascii':
        toks = iter(data[body:].split())
        def read(t):
            return (float if t in 'fd' else int)(next(toks))
    elif fmt in ('binary_little_endian', 'binary_big_endian'):
        S, pos = {t: struct.Struct('<>'[fmt[7] == 'b'] + t) for t in 'bBhHiIfd'}, [body]
        def read(t):
            v, = S[t].unpack_from(data, pos[0])
            pos[0] += S[t].size
            return v
    else:
        raise MeshError('unsupported PLY format %r' % fmt)
    rows = {name: [{p: [read(t) for _ in range(read(lt))] if lt else read(t) for p, lt, t in props}
                   for _ in range(count)] for name, count, props in elems}
    verts = [(r['x'], r['y'], r['z']) for r in rows.get('vertex', ())]
    faces, colors = [], []
    for r in rows.get('face', ()):
        tris = fan(r['vertex_indices'] if 'vertex_indices' in r else r['vertex_index'])
        faces += tris
        if 'red' in r:
            colors += [(r['red'], r['green'], r['blue'])] * len(tris)
    return verts, faces, colors or None


def load_mesh(path):
    try:
        with open(path, 'rb') as f:
            data = f.read()
    except OSError as ex:
        raise MeshError('cannot read: %s' % ex.strerror)
    ext = os.path.splitext(path)[1].lower()
    loader = {'.obj': load_obj, '.off': load_off, '.ply': load_ply}.get(ext)
    if loader is None:
        raise MeshError('unknown mesh format %r (expected .obj, .off or .ply)' % ext)
    try:
        verts, faces, colors = loader(data)
    except (StopIteration, struct.error):
        raise MeshError('truncated: data ends before the counts in the header are met')
    except (ValueError, IndexError, KeyError) as ex:
        raise MeshError('malformed %s file (%s: %s)' % (ext[1:].upper(), type(ex).__name__, ex))
    if not faces:
        raise MeshError('no faces')
    if any(len(v) != 3 or not all(map(math.isfinite, v)) for v in verts):
        raise MeshError('vertex with missing or non-finite coordinates')
    n = len(verts)
    if any(not 0 <= i < n for tri in faces for i in tri):
        raise MeshError('face index out of range (%d vertices)' % n)
    return verts, faces, colors


def point_triangle_distance(p, a, b, c):
    """Distance from point p to triangle abc (Ericson's closest-point regions)."""
    sub = lambda u, v: (u[0] - v[0], u[1] - v[1], u[2] - v[2])
    dot = lambda u, v: u[0] * v[0] + u[1] * v[1] + u[2] * v[2]
    ab, ac, ap = sub(b, a), sub(c, a), sub(p, a)
    d1, d2 = dot(ab, ap), dot(ac, ap)
    if d1 <= 0 and d2 <= 0:
        return math.dist(p, a)
    bp = sub(p, b)
    d3, d4 = dot(ab, bp), dot(ac, bp)
    if d3 >= 0 and d4 <= d3:
        return math.dist(p, b)
    cp = sub(p, c)
    d5, d6 = dot(ab, cp), dot(ac, cp)
    if d6 >= 0 and d5 <= d6:
        return math.dist(p, c)
    vc, vb, va = d1 * d4 - d3 * d2, d5 * d2 - d1 * d6, d3 * d6 - d5 * d4
    along = lambda u, e, t: tuple(u[k] + t * e[k] for k in range(3))
    if vc <= 0 and d1 >= 0 and d3 <= 0:
        return math.dist(p, along(a, ab, d1 / (d1 - d3)))
    if vb <= 0 and d2 >= 0 and d6 <= 0:
        return math.dist(p, along(a, ac, d2 / (d2 - d6)))
    if va <= 0 and d4 - d3 >= 0 and d5 - d6 >= 0:
        return math.dist(p, along(b, sub(c, b), (d4 - d3) / ((d4 - d3) + (d5 - d6))))
    den = va + vb + vc
    if den == 0:  # degenerate triangle: its edges are the nearest it has
        return min(math.dist(p, a), math.dist(p, b), math.dist(p, c))
    v, w = vb / den, vc / den
    return math.dist(p, tuple(a[k] + v * ab[k] + w * ac[k] for k in range(3)))


def distance_colors(verts, faces, other, focus, reach, scale):
    """Per face of (verts, faces) whose centroid lies within `reach` of `focus`: blue to red by
    the centroid's distance to mesh `other` ((verts, faces, _)), red from `scale` on; grey beyond
    `reach` (not drawn).  Only `other`'s triangles within `scale` of a centroid are tested,
    through a grid of cells `scale` wide."""
    overts, ofaces, _ = other
    cells = {}
    for k, tri in enumerate(ofaces):
        pts = [overts[i] for i in tri]
        lo = [min(q[j] for q in pts) for j in range(3)]
        hi = [max(q[j] for q in pts) for j in range(3)]
        if any(lo[j] > focus[j] + reach + scale or hi[j] < focus[j] - reach - scale for j in range(3)):
            continue
        c0 = [math.floor(v / scale) for v in lo]
        c1 = [math.floor(v / scale) for v in hi]
        for x in range(c0[0], c1[0] + 1):
            for y in range(c0[1], c1[1] + 1):
                for z in range(c0[2], c1[2] + 1):
                    cells.setdefault((x, y, z), []).append(k)
    colors = []
    for tri in faces:
        centroid = tuple(sum(verts[i][j] for i in tri) / 3.0 for j in range(3))
        if math.dist(centroid, focus) > reach:
            colors.append((200, 200, 200))
            continue
        cx, cy, cz = (math.floor(v / scale) for v in centroid)
        near = {k for x in (cx - 1, cx, cx + 1) for y in (cy - 1, cy, cy + 1) for z in (cz - 1, cz, cz + 1)
                for k in cells.get((x, y, z), ())}
        d = min([point_triangle_distance(centroid, *(overts[i] for i in ofaces[k])) for k in near] + [scale])
        t = d / scale
        colors.append((int(255 * t), int(80 * (1 - t)), int(255 * (1 - t))))
    return colors


def render(verts, faces, colors, cam, W, H, flat, edges):
    (fx, fy, fz), radius, (r, u, b) = cam
    s = W / (2.0 * radius)
    P, near, lim = [], [], (2 * radius) ** 2
    for x, y, z in verts:
        x, y, z = x - fx, y - fy, z - fz
        near.append(x * x + y * y + z * z <= lim)
        cx = x * r[0] + y * r[1] + z * r[2]
        cy = x * u[0] + y * u[1] + z * u[2]
        P.append((cx, cy, x * b[0] + y * b[1] + z * b[2], W / 2 + cx * s, H / 2 - cy * s))
    fb, zb = bytearray(bytes((40, 42, 48)) * (W * H)), [-math.inf] * (W * H)
    for k, (i0, i1, i2) in enumerate(faces):
        if not (near[i0] or near[i1] or near[i2]):
            continue
        p0, p1, p2 = P[i0], P[i1], P[i2]
        xs, ys = (p0[3], p1[3], p2[3]), (p0[4], p1[4], p2[4])
        x0, x1 = max(0, math.ceil(min(xs) - 0.5)), min(W - 1, math.floor(max(xs) - 0.5))
        y0, y1 = max(0, math.ceil(min(ys) - 0.5)), min(H - 1, math.floor(max(ys) - 0.5))
        area = (xs[1] - xs[0]) * (ys[2] - ys[0]) - (xs[2] - xs[0]) * (ys[1] - ys[0])
        if x0 > x1 or y0 > y1 or area == 0:
            continue
        # Lambert shading with a headlight; normal in camera space (z towards viewer).
        ax, ay, az = p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]
        bx, by, bz = p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]
        nx, ny, nz = ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx
        lam = 0.25 + 0.75 * abs(nz) / (math.sqrt(nx * nx + ny * ny + nz * nz) or 1)
        c = colors[k] if colors else flat
        tint = (1, 1, 1) if nz >= 0 else (0.45, 0.5, 0.8)  # back faces: darker, bluish
        col = bytes(min(255, int(c[j] * lam * tint[j])) for j in range(3))
        dark = bytes(v // 3 for v in col)
        # Edge functions E = A*px + B*py + C, >= 0 inside; depth is a plane in screen space.
        sg, E = (1 if area > 0 else -1), []
        for j, m in ((1, 2), (2, 0), (0, 1)):
            A, B = sg * (ys[j] - ys[m]), sg * (xs[m] - xs[j])
            E.append((A, B, -(A * xs[j] + B * ys[j]), math.hypot(A, B)))
        zx = ((p1[2] - p0[2]) * (ys[2] - ys[0]) - (p2[2] - p0[2]) * (ys[1] - ys[0])) / area
        zy = ((p2[2] - p0[2]) * (xs[1] - xs[0]) - (p1[2] - p0[2]) * (xs[2] - xs[0])) / area
        zc = p0[2] - zx * xs[0] - zy * ys[0]
        xlo, xhi = min(xs), max(xs)
        for y in range(y0, y1 + 1):
            py, lo, hi = y + 0.5, xlo, xhi
            for A, B, C, _ in E:
                v = B * py + C
                if A > 0:
                    lo = max(lo, -v / A)
                elif A < 0:
                    hi = min(hi, -v / A)
                elif v < 0:
                    hi = -1
            xa, xb = max(x0, math.ceil(lo - 0.5)), min(x1, math.floor(hi - 0.5))
            if xa > xb:
                continue
            z, row = zc + zx * (xa + 0.5) + zy * py, y * W
            if edges:
                d = [((A * (xa + 0.5) + B * py + C) / L, A / L) for A, B, C, L in E]
            for x in range(xa, xb + 1):
                i = row + x
                if z > zb[i]:
                    zb[i] = z
                    fb[3 * i:3 * i + 3] = dark if edges and min(d0 + dx * (x - xa) for d0, dx in d) < 0.6 else col
                z += zx
    return fb


def write_png(path, W, H, rgb):
    raw = b''.join(b'\x00' + bytes(rgb[3 * W * y:3 * W * (y + 1)]) for y in range(H))
    def chunk(tag, payload):
        return struct.pack('>I', len(payload)) + tag + payload + struct.pack('>I', zlib.crc32(tag + payload))
    with open(path, 'wb') as f:
        f.write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', W, H, 8, 2, 0, 0, 0))
                + chunk(b'IDAT', zlib.compress(raw, 6)) + chunk(b'IEND', b''))


def floats(n, desc, lo=-1e300, hi=1e300, sep=','):
    def parse(text):
        try:
            vals = [float(v) for v in text.split(sep)]
        except ValueError:
            vals = []
        if len(vals) != n or not all(lo <= v <= hi for v in vals):
            raise argparse.ArgumentTypeError('expected %s, got %r' % (desc, text))
        return vals if n > 1 else vals[0]
    return parse


def main(argv):
    for k in range(len(argv) - 2, -1, -1):  # let "--focus -0.8,1,0" work, not only "--focus=..."
        if argv[k] in ('--focus', '--radius', '--view', '--size', '--flat-color', '--distance-scale'):
            argv[k:k + 2] = [argv[k] + '=' + argv[k + 1]]
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('out', metavar='OUT.png')
    ap.add_argument('meshes', nargs='+', metavar='MESH')
    ap.add_argument('--focus', metavar='X,Y,Z', type=floats(3, 'three numbers X,Y,Z'))
    ap.add_argument('--radius', metavar='R', type=floats(1, 'a positive number', 1e-300))
    ap.add_argument('--view', metavar='AZ,EL', type=floats(2, 'AZIMUTH,ELEVATION in degrees'),
                    default=[0, 0])
    ap.add_argument('--size', metavar='WxH', type=floats(2, 'WxH, 1..10000 pixels', 1, 10000, 'x'),
                    default=[800, 800])
    ap.add_argument('--flat-color', metavar='R,G,B', type=floats(3, 'R,G,B in 0..255', 0, 255),
                    default=[200, 200, 200])
    ap.add_argument('--edges', action='store_true')
    ap.add_argument('--distance-to', metavar='MESH')
    ap.add_argument('--distance-scale', metavar='D', type=floats(1, 'a positive number', 1e-300))
    try:
        a = ap.parse_args(argv)
    except SystemExit as ex:  # usage errors exit with 1 (argparse uses 2); -h still exits 0
        sys.exit(1 if ex.code else 0)
    (W, H), meshes = map(int, a.size), []
    for path in a.meshes:
        try:
            meshes.append(load_mesh(path))
        except MeshError as ex:
            sys.exit('render_mesh.py: %s: %s' % (path, ex))
    used = [meshes[0][0][i] for i in {i for tri in meshes[0][1] for i in tri}]
    lo, hi = [min(c) for c in zip(*used)], [max(c) for c in zip(*used)]
    focus = a.focus or [(l + h) / 2 for l, h in zip(lo, hi)]
    radius = a.radius or (math.dist(lo, hi) / 2 or 1.0)
    if a.distance_to:
        try:
            other = load_mesh(a.distance_to)
        except MeshError as ex:
            sys.exit('render_mesh.py: %s: %s' % (a.distance_to, ex))
        scale = a.distance_scale or (math.dist(lo, hi) / 100 or 1.0)
        meshes = [(v, f, distance_colors(v, f, other, focus, 3 * radius, scale)) for v, f, _ in meshes]
    az, el = (math.radians(v) for v in a.view)
    b = (math.cos(el) * math.sin(az), math.sin(el), math.cos(el) * math.cos(az))  # towards viewer
    r = (math.cos(az), 0.0, -math.sin(az))  # screen right
    u = (b[1] * r[2] - b[2] * r[1], b[2] * r[0] - b[0] * r[2], b[0] * r[1] - b[1] * r[0])  # up
    gap = 4
    TW = len(meshes) * (W + gap) - gap
    img = bytearray(b'\x10' * (TW * H * 3))
    for n, (verts, faces, colors) in enumerate(meshes):
        fb = render(verts, faces, colors, (focus, radius, (r, u, b)), W, H, a.flat_color, a.edges)
        for y in range(H):
            o = 3 * (y * TW + n * (W + gap))
            img[o:o + 3 * W] = fb[3 * W * y:3 * W * (y + 1)]
    try:
        write_png(a.out, TW, H, img)
    except OSError as ex:
        sys.exit('render_mesh.py: %s: cannot write: %s' % (a.out, ex.strerror))
    print(a.out)


if __name__ == '__main__':
    main(sys.argv[1:])

#!/usr/bin/env python3
"""Make the bundled test garment: a tube top over the torso of the SMPL template, with UVs.

Usage: python3 scripts/make_garment.py [TEMPLATE.obj] [OUT.obj]
(defaults: tests/data/human_man.obj -> tests/data/garment_torso.obj; standard library only)

How: the template's faces whose three corners lie between 0.95 m and 1.28 m high (above the
crotch and the buttocks, below the armpits) and within 0.25 m of the body's mid-plane (no arm
or hand) are kept, their largest connected piece taken (the torso band); each kept vertex is
moved 1 cm out along its area-weighted vertex normal. UVs are cylindrical: u is the angle about
the vertical axis (seam at the back, where faces crossing it get their own texture coordinates
at u + 1), v the height within the band. Vertices are numbered in the template's order.
"""
import math
import sys

LOW, HIGH, HALF_WIDTH, OFFSET = 0.95, 1.28, 0.25, 0.01


def read_obj(path):
    vertices, faces = [], []
    for line in open(path):
        t = line.split()
        if t and t[0] == 'v':
            vertices.append(tuple(float(x) for x in t[1:4]))
        elif t and t[0] == 'f':
            faces.append(tuple(int(w.split('/')[0]) - 1 for w in t[1:4]))
    return vertices, faces


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def vertex_normals(vertices, faces):
    normals = [(0.0, 0.0, 0.0)] * len(vertices)
    for f in faces:
        n = cross(sub(vertices[f[1]], vertices[f[0]]), sub(vertices[f[2]], vertices[f[0]]))
        for v in f:
            normals[v] = tuple(normals[v][k] + n[k] for k in range(3))
    return [tuple(c / math.sqrt(sum(x * x for x in n)) for c in n) for n in normals]


def largest_piece(faces):
    """The faces of the largest edge-connected piece, in their original order."""
    by_edge = {}
    for i, f in enumerate(faces):
        for k in range(3):
            by_edge.setdefault(frozenset((f[k], f[(k + 1) % 3])), []).append(i)
    piece = [-1] * len(faces)
    sizes = []
    for start in range(len(faces)):
        if piece[start] >= 0:
            continue
        piece[start], stack, size = len(sizes), [start], 0
        while stack:
            i = stack.pop()
            size += 1
            f = faces[i]
            for k in range(3):
                for j in by_edge[frozenset((f[k], f[(k + 1) % 3]))]:
                    if piece[j] < 0:
                        piece[j] = len(sizes)
                        stack.append(j)
        sizes.append(size)
    best = sizes.index(max(sizes))
    return [f for i, f in enumerate(faces) if piece[i] == best]


def main():
    template = sys.argv[1] if len(sys.argv) > 1 else 'tests/data/human_man.obj'
    out = sys.argv[2] if len(sys.argv) > 2 else 'tests/data/garment_torso.obj'
    vertices, faces = read_obj(template)
    normals = vertex_normals(vertices, faces)
    inside = [LOW <= v[1] <= HIGH and abs(v[0]) <= HALF_WIDTH for v in vertices]
    band = largest_piece([f for f in faces if all(inside[v] for v in f)])
    used = sorted({v for f in band for v in f})  # the template's order
    number = {v: i for i, v in enumerate(used)}
    lines = ['# tube top over the torso of %s, made by scripts/make_garment.py' % template.split('/')[-1]]
    for v in used:
        p = tuple(vertices[v][k] + OFFSET * normals[v][k] for k in range(3))
        lines.append('v %.6f %.6f %.6f' % p)
    uv_index, uvs, face_lines = {}, [], []

    def texture(v, wrap):
        key = (v, wrap)
        if key not in uv_index:
            x, y, z = vertices[v]
            u = math.atan2(x, z) / (2 * math.pi) + 0.5 + wrap  # 0 and 1 at the back
            uv_index[key] = len(uvs)
            uvs.append((u, (y - LOW) / (HIGH - LOW)))
        return uv_index[key]

    for f in band:
        us = [math.atan2(vertices[v][0], vertices[v][2]) / (2 * math.pi) + 0.5 for v in f]
        crosses = max(us) - min(us) > 0.5  # the face spans the seam: lift its low corners by 1
        corners = [texture(v, 1 if crosses and u < 0.5 else 0) for v, u in zip(f, us)]
        face_lines.append('f ' + ' '.join('%d/%d' % (number[v] + 1, t + 1) for v, t in zip(f, corners)))
    lines += ['vt %.6f %.6f' % uv for uv in uvs] + face_lines
    open(out, 'w').write('\n'.join(lines) + '\n')
    print('%s: %d vertices, %d faces, %d texture coordinates' % (out, len(used), len(band), len(uvs)))


if __name__ == '__main__':
    main()

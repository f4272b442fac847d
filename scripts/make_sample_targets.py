#!/usr/bin/env python3
"""Generate tests/data/sample_targets/: the small target folder of the README's main command.

Every target is derived from the SMPL meshes in tests/data (CC BY 4.0, see ATTRIBUTION.md), so
all four share SMPL's vertex order and their ground truth (NAME.gt.txt) is the identity. Each
uses another anchor format of the folder convention:

  woman          human_woman.obj as it is                        anchors: JSON (vertex indices)
  woman_turned   the woman rotated 40 deg about (1, 2, 0.5),      anchors: plain text (name index)
                 scaled by 1.25 and moved by (0.3, -0.2, 0.1)
  man_flipped    human_man.obj with a different triangulation:    anchors: MeshLab .pp (3-D points)
                 the diagonal of every nearly planar quad of two
                 triangles flipped (face-disjoint, greedy in edge
                 order); same vertices
  man_bent       the man's upper body bent forward smoothly       anchors: JSON (vertex indices)
                 (a circular bend of 30 deg over the part above
                 the waist; below it nothing moves)

Pure Python (no numpy), deterministic: running it again gives byte-identical files.
Usage: scripts/make_sample_targets.py [REPO_ROOT]
"""

import json
import math
import pathlib
import shutil
import sys

ROOT = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parent.parent)
DATA = ROOT / "tests" / "data"
OUT = DATA / "sample_targets"

ATTRIBUTION = ("Derived from the SMPL template mesh (Max Planck Society e.V. via SMPL, CC BY 4.0) by "
               "scripts/make_sample_targets.py; see tests/data/ATTRIBUTION.md")


def read_obj(path):
    vertices, faces = [], []
    for line in path.read_text().splitlines():
        parts = line.split()
        if not parts:
            continue
        if parts[0] == "v":
            vertices.append(tuple(float(x) for x in parts[1:4]))
        elif parts[0] == "f":
            faces.append(tuple(int(p.split("/")[0]) - 1 for p in parts[1:4]))
    return vertices, faces


def write_obj(path, vertices, faces, what):
    lines = [f"# {what}", f"# {ATTRIBUTION}"]
    lines += ["v %.6f %.6f %.6f" % v for v in vertices]
    lines += ["f %d %d %d" % (a + 1, b + 1, c + 1) for a, b, c in faces]
    path.write_text("\n".join(lines) + "\n")


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def norm(a):
    return math.sqrt(dot(a, a))


def unit_normal(vertices, face):
    a, b, c = (vertices[i] for i in face)
    n = cross(sub(b, a), sub(c, a))
    length = norm(n)
    return tuple(x / length for x in n) if length > 0 else (0.0, 0.0, 0.0)


def rotation(axis, degrees):
    """Rodrigues' rotation matrix about `axis`."""
    length = norm(axis)
    x, y, z = (c / length for c in axis)
    t = math.radians(degrees)
    c, s, C = math.cos(t), math.sin(t), 1 - math.cos(t)
    return ((c + x * x * C, x * y * C - z * s, x * z * C + y * s),
            (y * x * C + z * s, c + y * y * C, y * z * C - x * s),
            (z * x * C - y * s, z * y * C + x * s, c + z * z * C))


def turned(vertices):
    r = rotation((1.0, 2.0, 0.5), 40.0)
    scale, shift = 1.25, (0.3, -0.2, 0.1)
    return [tuple(scale * dot(r[k], v) + shift[k] for k in range(3)) for v in vertices]


def flipped(vertices, faces, max_dihedral_degrees=10.0):
    """Flip the diagonal of nearly planar quads: each face takes part in at most one flip, a
    flip never creates an edge that already exists, and both new triangles keep the old normal's side."""
    edge_faces = {}
    for f, face in enumerate(faces):
        for k in range(3):
            a, b = face[k], face[(k + 1) % 3]
            edge_faces.setdefault((min(a, b), max(a, b)), []).append(f)
    edges = set(edge_faces)
    faces = list(faces)
    used = set()
    cos_limit = math.cos(math.radians(max_dihedral_degrees))
    for (a, b) in sorted(edge_faces):
        pair = edge_faces[(a, b)]
        if len(pair) != 2 or pair[0] in used or pair[1] in used:
            continue
        f1, f2 = pair
        # Orient so that f1 = (p, q, c) and f2 = (q, p, d) for the directed edge p -> q of f1.
        face1 = faces[f1]
        k = next(k for k in range(3) if {face1[k], face1[(k + 1) % 3]} == {a, b})
        p, q, c = face1[k], face1[(k + 1) % 3], face1[(k + 2) % 3]
        d = next(v for v in faces[f2] if v not in (p, q))
        if c == d or (min(c, d), max(c, d)) in edges:
            continue
        n1, n2 = unit_normal(vertices, faces[f1]), unit_normal(vertices, faces[f2])
        if dot(n1, n2) < cos_limit:
            continue
        new1, new2 = (c, p, d), (d, q, c)
        average = tuple(x + y for x, y in zip(n1, n2))
        m1, m2 = unit_normal(vertices, new1), unit_normal(vertices, new2)
        if dot(m1, average) <= 0.5 or dot(m2, average) <= 0.5 or dot(m1, m2) < cos_limit:
            continue
        faces[f1], faces[f2] = new1, new2
        edges.discard((a, b))
        edges.add((min(c, d), max(c, d)))
        used.update((f1, f2))
    return faces, len(used) // 2


def bent(vertices, waist_y=1.0, degrees=30.0):
    """Circular bend about the x axis: points above `waist_y` follow an arc whose angle grows
    linearly with height, reaching `degrees` at the top of the head; below the waist nothing moves."""
    top = max(v[1] for v in vertices)
    kappa = math.radians(degrees) / (top - waist_y)
    radius = 1.0 / kappa
    out = []
    for x, y, z in vertices:
        if y <= waist_y:
            out.append((x, y, z))
            continue
        theta = kappa * (y - waist_y)
        out.append((x, waist_y + (radius - z) * math.sin(theta), radius - (radius - z) * math.cos(theta)))
    return out


def anchors(path):
    return [(a["name"], a["vertex"]) for a in json.loads(path.read_text())["anchors"]]


def write_anchors_json(path, named, what):
    document = {"description": f"{what}; the 41 SMPL landmarks of tests/data/human.anchors.json (29 from "
                               "github.com/DavidBoja/SMPL-Anthropometry, MIT License, (c) 2023 David Bojanic; "
                               "12 extremities made for xparam), see tests/data/ATTRIBUTION.md",
                "anchors": [{"name": n, "vertex": v} for n, v in named]}
    path.write_text(json.dumps(document, indent=2) + "\n")


def quoted(name):
    return '"%s"' % name.replace("\\", "\\\\").replace('"', '\\"') if (" " in name or "#" in name) else name


def write_anchors_text(path, named):
    lines = ["# the 41 SMPL landmarks of tests/data/human.anchors.json (29 from github.com/DavidBoja/SMPL-Anthropometry,",
             "# MIT License, (c) 2023 David Bojanic; 12 extremities made for xparam) as 0-based vertex indices",
             "# of woman_turned.obj", "# name index"]
    lines += [f"{quoted(n)} {v}" for n, v in named]
    path.write_text("\n".join(lines) + "\n")


def write_picked_points(path, named, vertices, mesh_name):
    lines = ["<!DOCTYPE PickedPoints>", "<PickedPoints>", " <DocumentData>",
             f'  <DataFileName name="{mesh_name}"/>', " </DocumentData>"]
    for n, v in named:
        x, y, z = vertices[v]
        name = n.replace("&", "&amp;").replace('"', "&quot;")
        lines.append(f' <point x="{x:.6f}" y="{y:.6f}" z="{z:.6f}" active="1" name="{name}"/>')
    lines.append("</PickedPoints>")
    path.write_text("\n".join(lines) + "\n")


def write_identity(path, n):
    path.write_text("# ground truth: template vertex i corresponds to target vertex i (shared SMPL order)\n" +
                    "".join(f"{i}\n" for i in range(n)))


def main():
    OUT.mkdir(exist_ok=True)
    man_v, man_f = read_obj(DATA / "human_man.obj")
    woman_v, woman_f = read_obj(DATA / "human_woman.obj")
    man_anchors = anchors(DATA / "human.anchors.json")
    woman_anchors = anchors(DATA / "human.anchors.json")

    shutil.copyfile(DATA / "human_woman.obj", OUT / "woman.obj")
    write_anchors_json(OUT / "woman.anchors.json", woman_anchors, "anchors of woman.obj")

    write_obj(OUT / "woman_turned.obj", turned(woman_v), woman_f,
              "human_woman.obj rotated 40 deg about (1, 2, 0.5), scaled 1.25, moved by (0.3, -0.2, 0.1)")
    write_anchors_text(OUT / "woman_turned.anchors.txt", woman_anchors)

    flipped_faces, flips = flipped(man_v, man_f)
    write_obj(OUT / "man_flipped.obj", man_v, flipped_faces,
              f"human_man.obj with {flips} edge flips (nearly planar quads), same vertices")
    write_picked_points(OUT / "man_flipped.pp", man_anchors, man_v, "man_flipped.obj")

    write_obj(OUT / "man_bent.obj", bent(man_v), man_f,
              "human_man.obj with the upper body bent forward 30 deg (circular bend above y = 1.0)")
    write_anchors_json(OUT / "man_bent.anchors.json", man_anchors, "anchors of man_bent.obj")

    for name, n in (("woman", len(woman_v)), ("woman_turned", len(woman_v)), ("man_flipped", len(man_v)),
                    ("man_bent", len(man_v))):
        write_identity(OUT / f"{name}.gt.txt", n)
    print(f"wrote {OUT} ({flips} flips in man_flipped)")


if __name__ == "__main__":
    main()

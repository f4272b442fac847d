#!/usr/bin/env python3
"""Writes tests/data/malformed/: tiny mesh files that read_triangle_soup must refuse with an
InputError naming the file, plus a few that are syntactically fine but topologically bad
(non-manifold edge: three faces on one edge), which it must read (tests/io/mesh_reader_test.cpp
lists those). Deterministic: running it again rewrites the same bytes.

Usage: scripts/make_malformed_corpus.py [output_dir]   (default: tests/data/malformed)
"""
import os
import random
import struct
import sys

# A tetrahedron-like fan: vertices 0..4, faces sharing edge (0, 1) three times when NONMANIFOLD.
VERTICES = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, -1.0, 0.0), (0.0, 0.0, 1.0)]
TRIANGLES = [(0, 1, 2), (1, 0, 3), (0, 3, 4)]
NONMANIFOLD = [(0, 1, 2), (1, 0, 3), (0, 1, 4)]
HUGE = 2000000000


def obj(vertices, faces, extra=""):
    lines = ["v %s %s %s" % v for v in vertices]
    lines += ["f " + " ".join(str(i) for i in f) for f in faces]
    return ("\n".join(lines) + "\n" + extra).encode()


def off(vertices, faces, counts=None, extra=""):
    counts = counts or "%d %d 0" % (len(vertices), len(faces))
    lines = ["OFF", counts] + ["%s %s %s" % v for v in vertices]
    lines += ["%d " % len(f) + " ".join(str(i) for i in f) for f in faces]
    return ("\n".join(lines) + "\n" + extra).encode()


def ply_ascii(vertices, faces, nv=None, nf=None, index_type="int", extra=""):
    header = ["ply", "format ascii 1.0", "element vertex %d" % (len(vertices) if nv is None else nv),
              "property float x", "property float y", "property float z",
              "element face %d" % (len(faces) if nf is None else nf),
              "property list uchar %s vertex_indices" % index_type, "end_header"]
    body = ["%s %s %s" % v for v in vertices] + ["%d " % len(f) + " ".join(str(i) for i in f) for f in faces]
    return ("\n".join(header + body) + "\n" + extra).encode()


def ply_binary(vertices, faces, big_endian=False, nv=None, nf=None, count_type="uchar", coord="float"):
    order = ">" if big_endian else "<"
    header = ["ply", "format binary_%s_endian 1.0" % ("big" if big_endian else "little"),
              "element vertex %d" % (len(vertices) if nv is None else nv),
              "property %s x" % coord, "property %s y" % coord, "property %s z" % coord,
              "element face %d" % (len(faces) if nf is None else nf),
              "property list %s int vertex_indices" % count_type, "end_header"]
    data = b"".join(struct.pack(order + ("3f" if coord == "float" else "3d"), *v) for v in vertices)
    count_format = {"uchar": "B", "uint": "I"}[count_type]
    for f in faces:
        data += struct.pack(order + count_format, len(f)) + struct.pack(order + "%di" % len(f), *f)
    return ("\n".join(header) + "\n").encode() + data


def stl_binary(triangles, count=None):
    data = b"xparam malformed corpus".ljust(80, b" ") + struct.pack("<I", len(triangles) if count is None else count)
    for t in triangles:
        data += struct.pack("<3f", 0.0, 0.0, 0.0) + b"".join(struct.pack("<3f", *c) for c in t) + b"\0\0"
    return data


def stl_ascii(triangles, extra=""):
    lines = ["solid corpus"]
    for t in triangles:
        lines += ["facet normal 0 0 0", "outer loop"] + ["vertex %s %s %s" % c for c in t]
        lines += ["endloop", "endfacet"]
    return ("\n".join(lines) + "\nendsolid corpus\n" + extra).encode()


def corners(vertices, faces):
    return [tuple(vertices[i] for i in f) for f in faces]


def random_bytes(seed, size):
    rng = random.Random(seed)
    data = bytearray(rng.randrange(256) for _ in range(size))
    data[0] = 0x9F  # never 'p' (ply), 's' (solid), 'O' (OFF) or a letter starting an OBJ statement
    return bytes(data)


def corpus():
    V, T, N = VERTICES, TRIANGLES, NONMANIFOLD
    nan_v = [V[0], (float("nan"), 0.0, 0.0)] + V[2:]
    inf_v = [V[0], (0.0, float("inf"), 0.0)] + V[2:]
    one_based = [tuple(i + 1 for i in f) for f in T]
    files = {
        # OBJ
        "obj_empty.obj": b"",
        # Cut inside a line: OBJ declares no counts, so a cut between lines cannot be detected.
        "obj_truncated.obj": obj(V, one_based)[:len(b"v 0.0 0.0 0.0\nv 1.0 0.0")],
        "obj_nan.obj": obj(nan_v, one_based),
        "obj_inf.obj": obj(inf_v, one_based),
        "obj_out_of_range.obj": obj(V, one_based[:2] + [(1, 2, 9)]),
        "obj_zero_index.obj": obj(V, [(0, 1, 2)] + one_based),
        "obj_negative_out_of_range.obj": obj(V, one_based + [(-1, -2, -9)]),
        "obj_repeated_index.obj": obj(V, one_based + [(1, 2, 2)]),
        "obj_two_corners.obj": obj(V, one_based + [(1, 2)]),
        "obj_garbage_token.obj": obj(V, one_based).replace(b"v 1.0 0.0 0.0", b"v 1.0 abc 0.0"),
        "obj_garbage_corner.obj": obj(V, one_based + [("1", "2x", "3")]),
        "obj_unknown_statement.obj": obj(V, one_based, "xyz 1 2 3\n"),
        "obj_no_faces.obj": obj(V, []),
        "obj_freeform.obj": obj(V, one_based, "cstype bspline\n"),
        "obj_random_bytes.obj": random_bytes(1, 150),
        "obj_nonmanifold.obj": obj(V, [tuple(i + 1 for i in f) for f in N]),
        # OFF
        "off_empty.off": b"",
        "off_huge_counts.off": off(V[:1], [(0, 0, 0)], counts="2000000000 1 0"),
        "off_huge_face_count.off": off(V, T, counts="5 2000000000 0"),
        "off_huge_polygon.off": off(V, T, extra="2000000000 0 1 2\n").replace(b"5 3 0", b"5 4 0"),
        "off_truncated.off": off(V, T)[:-12],
        "off_missing_vertex.off": off(V[:4], T, counts="5 3 0"),
        "off_nan.off": off(nan_v, T),
        "off_inf.off": off(inf_v, T),
        "off_out_of_range.off": off(V, T[:2] + [(0, 1, 7)]),
        "off_negative_index.off": off(V, T[:2] + [(0, -1, 2)]),
        "off_repeated_index.off": off(V, T[:2] + [(0, 2, 0)]),
        "off_two_corners.off": off(V, T[:2] + [(0, 1)]),
        "off_garbage_token.off": off(V, T).replace(b"1.0 0.0 0.0", b"1.0 zero 0.0"),
        "off_trailing_garbage.off": off(V, T, extra="3 0 1 2\n"),
        "off_bad_header.off": b"OFFX\n" + off(V, T)[4:],
        "off_4d.off": b"4OFF\n" + off(V, T)[4:],
        "off_binary.off": b"OFF BINARY\n" + struct.pack(">3i", 5, 3, 0) + b"\0" * 60,
        "off_random_bytes.off": random_bytes(2, 150),
        "off_nonmanifold.off": off(V, N),
        # PLY
        "ply_empty.ply": b"",
        "ply_random_bytes.ply": random_bytes(3, 150),
        "ply_no_end_header.ply": ply_ascii(V, T).replace(b"end_header\n", b""),
        "ply_unknown_format.ply": ply_ascii(V, T).replace(b"format ascii 1.0", b"format ebcdic 1.0"),
        "ply_no_face_element.ply": b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                                   b"property float y\nproperty float z\nend_header\n0 0 0\n1 0 0\n0 1 0\n",
        "ply_ascii_truncated.ply": ply_ascii(V, T)[:-7],
        "ply_ascii_huge_count.ply": ply_ascii(V, T, nf=HUGE),
        "ply_ascii_nan.ply": ply_ascii(nan_v, T),
        "ply_ascii_out_of_range.ply": ply_ascii(V, T[:2] + [(0, 1, 5)]),
        "ply_ascii_negative_index.ply": ply_ascii(V, T[:2] + [(0, -4, 2)]),
        "ply_ascii_repeated_index.ply": ply_ascii(V, T[:2] + [(3, 3, 4)]),
        "ply_ascii_two_corners.ply": ply_ascii(V, T[:2] + [(0, 1)]),
        "ply_ascii_garbage_token.ply": ply_ascii(V, T).replace(b"\n3 0 1 2", b"\n3 0 one 2"),
        "ply_ascii_uchar_overflow.ply": ply_ascii(V, T).replace(b"\n3 0 1 2", b"\n259 0 1 2"),
        "ply_ascii_trailing_garbage.ply": ply_ascii(V, T, extra="3 0 1 2\n"),
        "ply_binary_le_truncated.ply": ply_binary(V, T)[:-5],
        "ply_binary_be_truncated.ply": ply_binary(V, T, big_endian=True)[:-30],
        "ply_binary_huge_vertex_count.ply": ply_binary(V, T, nv=HUGE),
        "ply_binary_huge_face_count.ply": ply_binary(V, T, nf=HUGE),
        "ply_binary_huge_list_length.ply": ply_binary(V, T, count_type="uint").replace(
            struct.pack("<I", 3) + struct.pack("<3i", *T[2]), struct.pack("<I", HUGE) + struct.pack("<3i", *T[2])),
        "ply_binary_nan.ply": ply_binary(nan_v, T),
        "ply_binary_be_inf.ply": ply_binary(inf_v, T, big_endian=True, coord="double"),
        "ply_binary_out_of_range.ply": ply_binary(V, T[:2] + [(0, 1, 5)]),
        "ply_binary_negative_index.ply": ply_binary(V, T[:2] + [(0, -1, 2)], big_endian=True),
        "ply_binary_repeated_index.ply": ply_binary(V, T[:2] + [(4, 1, 4)]),
        "ply_binary_trailing_bytes.ply": ply_binary(V, T) + b"\0\0\0\0",
        "ply_binary_lying_low_count.ply": ply_binary(V, T, nf=2),
        "ply_ascii_nonmanifold.ply": ply_ascii(V, N),
        "ply_binary_nonmanifold.ply": ply_binary(V, N, big_endian=True),
        # STL
        "stl_empty.stl": b"",
        "stl_random_bytes.stl": random_bytes(4, 151),
        "stl_binary_huge_count.stl": stl_binary(corners(V, T), count=HUGE),
        "stl_binary_truncated.stl": stl_binary(corners(V, T))[:-25],
        "stl_binary_nan.stl": stl_binary(corners(nan_v, T)),
        "stl_binary_no_triangles.stl": stl_binary([]),
        "stl_ascii_truncated.stl": stl_ascii(corners(V, T))[:-40],
        "stl_ascii_inf.stl": stl_ascii(corners(inf_v, T)),
        "stl_ascii_garbage_token.stl": stl_ascii(corners(V, T)).replace(b"outer loop", b"outer lop", 1),
        "stl_ascii_degenerate.stl": stl_ascii(corners(V, T + [(0, 1, 1)])),
        "stl_ascii_nonmanifold.stl": stl_ascii(corners(V, N)),
        "stl_binary_nonmanifold.stl": stl_binary(corners(V, N)),
        # any format
        "unknown_extension.xyz": obj(V, one_based),
    }
    return files


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "tests", "data", "malformed")
    os.makedirs(out, exist_ok=True)
    for name, data in sorted(corpus().items()):
        with open(os.path.join(out, name), "wb") as f:
            f.write(data)
    print("wrote %d files to %s" % (len(corpus()), out))


if __name__ == "__main__":
    main()

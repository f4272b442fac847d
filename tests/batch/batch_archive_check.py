#!/usr/bin/env python3
"""Check a batch archive with h5py and numpy only, independently of xparam's reader.

Usage: batch_archive_check.py ARCHIVE EXPECTED.json

EXPECTED.json: {"targets": {"NAME": {"ok": true|false, "error_contains": ["...", ...]}, ...}}
listing every target the archive must hold. Checked:
  - /targets/name is exactly the expected names, sorted (byte order);
  - status and error text of each target (a failed target's error holds every given part);
  - an ok target whose mesh_file is an OBJ: each remesh vertex is the barycentric combination
    (corr_bary) of the corners of its face (corr_face) of that file, in the file's corner
    order; its metrics are finite; a failed target's arrays are NaN / -1.
Exits 0 when everything holds, 1 with a message on the first problem.
"""
import json
import sys

import h5py
import numpy as np


def read_obj(path):
    vertices, faces = [], []
    with open(path) as f:
        for line in f:
            parts = line.split()
            if parts and parts[0] == "v":
                vertices.append([float(x) for x in parts[1:4]])
            elif parts and parts[0] == "f":
                faces.append([int(p.split("/")[0]) - 1 for p in parts[1:4]])
    return np.array(vertices), np.array(faces)


def fail(message):
    print(f"batch_archive_check: {message}", file=sys.stderr)
    sys.exit(1)


def main():
    if len(sys.argv) != 3:
        fail(__doc__)
    expected = json.load(open(sys.argv[2]))["targets"]
    with h5py.File(sys.argv[1], "r") as f:
        t = f["targets"]
        names = list(t["name"].asstr()[:])
        if names != sorted(expected, key=lambda n: n.encode("utf-8")):
            fail(f"names {names}, expected {sorted(expected)}")
        status = t["status"][:]
        errors = list(t["error"].asstr()[:])
        mesh_files = list(t["mesh_file"].asstr()[:])
        metrics = t["metrics"][:]
        for row, name in enumerate(names):
            want = expected[name]
            if bool(status[row]) != want["ok"]:
                fail(f"{name}: status {status[row]}, expected ok={want['ok']} (error: {errors[row]})")
            for part in want.get("error_contains", []):
                if part not in errors[row]:
                    fail(f"{name}: error {errors[row]!r} lacks {part!r}")
            remesh = t["remesh_vertices"][row]
            face = t["corr_face"][row]
            bary = t["corr_bary"][row]
            if not want["ok"]:
                if errors[row] == "" or not np.all(np.isnan(remesh)) or not np.all(face == -1):
                    fail(f"{name}: a failed row must have an error and NaN / -1 arrays")
                continue
            if errors[row] != "":
                fail(f"{name}: ok but error {errors[row]!r}")
            for column in ("E_L2", "E_ang", "area_ratio"):
                if column in metrics.dtype.names and not np.isfinite(metrics[row][column]):
                    fail(f"{name}: metric {column} is not finite")
            if mesh_files[row].lower().endswith(".obj"):
                vertices, faces = read_obj(mesh_files[row])
                corners = vertices[faces[face]]  # (V, 3 corners, 3)
                rebuilt = np.einsum("vk,vkd->vd", bary, corners)
                worst = np.max(np.linalg.norm(rebuilt - remesh, axis=1))
                if worst > 1e-9:
                    fail(f"{name}: corr_bary on {mesh_files[row]} misses remesh_vertices by {worst}")
    print(f"batch_archive_check: {sys.argv[1]}: {len(names)} targets as expected")


if __name__ == "__main__":
    main()

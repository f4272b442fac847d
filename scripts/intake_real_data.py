#!/usr/bin/env python3
"""The scan intake on ../shared/data: `xparam check` with `--intake strict` (the verdict before the
intake) and with the default intake, over every mesh; then `xparam pair` for the SHREC'19 shapes the
strict check refuses (or calls usable with a genus the template does not have), against the SMPL template (shrec19_connectivity/44.off) with the 73 CAESAR
landmarks carried over by each shape's registration to SMPL (its ground truth, as bench/evaluate).
Prints a table; exit 0. Usage:
    scripts/intake_real_data.py --xparam BUILD/src/cli/xparam [--data ../shared/data] [--out DIR]
        [--pairs 8,9,...] [--pair-options '--max-hole 2'] [--no-pairs]
"""
import argparse
import json
import math
import pathlib
import subprocess
import sys
import tempfile

MESH_SUFFIXES = {".off", ".ply", ".obj", ".stl"}


def check(xparam, meshes, strict):
    args = [str(xparam), "check", "--json"] + (["--intake", "strict"] if strict else []) + [str(m) for m in meshes]
    run = subprocess.run(args, capture_output=True, text=True)
    return {entry["file"]: entry for entry in json.loads(run.stdout)}


def read_off(path):
    """Vertices and triangles of a triangle OFF file."""
    tokens = []
    with open(path) as f:
        for line in f:
            line = line.split("#")[0].strip()
            if line:
                tokens.extend(line.split())
    assert tokens[0] == "OFF"
    n, m = int(tokens[1]), int(tokens[2])
    vertices = [tuple(float(t) for t in tokens[4 + 3 * i:7 + 3 * i]) for i in range(n)]
    at = 4 + 3 * n
    faces = []
    for _ in range(m):
        k = int(tokens[at])
        faces.append([int(t) for t in tokens[at + 1:at + 1 + k]])
        at += 1 + k
    return vertices, faces


def area(vertices, faces):
    total = 0.0
    for face in faces:
        a = vertices[face[0]]
        for b, c in zip(face[1:-1], face[2:]):
            u = [vertices[b][k] - a[k] for k in range(3)]
            v = [vertices[c][k] - a[k] for k in range(3)]
            cross = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
            total += 0.5 * math.sqrt(sum(x * x for x in cross))
    return total


def read_obj_vertices(path):
    return [tuple(float(t) for t in line.split()[1:4]) for line in open(path) if line.startswith("v ")]


def distance(a, b):
    return math.sqrt(sum((x - y) ** 2 for x, y in zip(a, b)))


def pair(xparam, data, shape, out, extra):
    shrec = data / "shrec19_connectivity"
    caesar = json.loads((data / "faust_landmarks/smpl_caesar_landmark_indices.json").read_text())
    matches = [int(line.split()[0]) for line in (shrec / f"{shape}.smpl_matches.txt").read_text().split("\n") if line.strip()]
    # Landmarks the registration puts on one target vertex cannot be two anchors: the later is left out.
    source, target, used = {}, {}, set()
    for name, smpl_vertex in caesar.items():
        if matches[smpl_vertex] in used:
            continue
        used.add(matches[smpl_vertex])
        source[name] = smpl_vertex
        target[name] = matches[smpl_vertex]
    out.mkdir(parents=True, exist_ok=True)
    (out / "source.anchors.json").write_text(json.dumps(source))
    (out / "target.anchors.json").write_text(json.dumps(target))
    run = subprocess.run([str(xparam), "pair", "-q", "--source", str(shrec / "44.off"), "--source-anchors",
                          str(out / "source.anchors.json"), "--target", str(shrec / f"{shape}.off"),
                          "--target-anchors", str(out / "target.anchors.json"), "--out", str(out / "pair")] + extra,
                         capture_output=True, text=True)
    if run.returncode != 0:
        return {"status": run.returncode, "error": (run.stderr.strip().splitlines() or [""])[-1]}
    remesh = read_obj_vertices(out / "pair/remesh.obj")
    truth, faces = read_off(shrec / f"{shape}.off")
    metrics = json.loads((out / "pair/metrics.json").read_text())
    errors = [distance(remesh[k], truth[matches[k]]) for k in range(len(remesh))]
    # In % of the square root of the file's area, as the README's evaluation tables.
    return {"status": 0, "gt_mean": sum(errors) / len(errors), "gt_percent": 100 * sum(errors) / len(errors) / math.sqrt(area(truth, faces)),
            "on_filled": metrics["intake"]["template_vertices_on_filled_surface"],
            "flipped": metrics["flipped_faces"], "E_L2": metrics["E_L2"], "steps": metrics["intake"]["steps"]}


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--xparam", required=True)
    parser.add_argument("--data", default=str(pathlib.Path(__file__).resolve().parents[2] / "shared/data"))
    parser.add_argument("--out", default=None)
    parser.add_argument("--pairs", default=None, help="SHREC'19 shape ids to pair (default: those refused before)")
    parser.add_argument("--no-pairs", action="store_true")
    parser.add_argument("--pair-options", default="", help="extra options of xparam pair, e.g. '--max-hole 2'")
    args = parser.parse_args()
    data = pathlib.Path(args.data)
    meshes = sorted(p for p in data.rglob("*") if p.suffix.lower() in MESH_SUFFIXES and p.is_file())
    before = check(args.xparam, meshes, strict=True)
    after = check(args.xparam, meshes, strict=False)
    usable_before = sum(1 for e in before.values() if e["valid"])
    usable_after = sum(1 for e in after.values() if e["valid"])
    print(f"{len(meshes)} meshes: usable before the intake (--intake strict) {usable_before}, after {usable_after}")
    for path in meshes:
        b, a = before[str(path)], after[str(path)]
        if b["valid"] and a["valid"]:
            continue
        rel = path.relative_to(data)
        if a["valid"]:
            steps = "; ".join(a.get("intake", {}).get("steps", []))
            print(f"  now usable  {rel}: {steps} (genus {a['intake']['genus_after']})")
        else:
            why = a.get("intake_refusal") or "; ".join((a.get("intake", {}).get("problems_after") or a["problems"])[:2])
            print(f"  refused     {rel}: {why}")
    if args.no_pairs:
        return 0
    # Refused before, or usable but of another genus than the template (pair refuses those).
    refused = [p.stem for p in meshes if p.parent.name == "shrec19_connectivity" and
               (not before[str(p)]["valid"] or before[str(p)]["genus"] != 0)]
    shapes = args.pairs.split(",") if args.pairs else sorted(refused, key=int)
    out = pathlib.Path(args.out) if args.out else pathlib.Path(tempfile.mkdtemp(prefix="intake_pairs_"))
    print("SHREC'19 shape vs SMPL (44.off), 73 CAESAR landmarks; ground-truth error = mean distance of each "
          "template vertex's image to its registration's vertex")
    extra = args.pair_options.split() if args.pair_options else []
    for shape in shapes:
        r = pair(args.xparam, data, shape, out / shape, extra)
        if r["status"] != 0:
            print(f"  {shape:>3}{' ' + ' '.join(extra) if extra else ''}: refused (exit {r['status']}): {r['error']}", flush=True)
        else:
            print(f"  {shape:>3}{' ' + ' '.join(extra) if extra else ''}: gt error {r['gt_mean']:.4f} ({r['gt_percent']:.2f}% of sqrt(area)), "
                  f"E_L2 {r['E_L2']:.3f}, folds {r['flipped']}, template vertices on filled surface {r['on_filled']}; "
                  f"intake: {'; '.join(r['steps'])}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())

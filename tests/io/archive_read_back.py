#!/usr/bin/env python3
"""An independent reader of xparam archives (schemas/archive.md) with h5py and numpy only.

Usage:
  archive_read_back.py ARCHIVE EXPECTED.json  check the layout, then every value against the JSON
                                              written by tests/io/archive_test.cpp
  archive_read_back.py --open ARCHIVE         read every dataset and check the layout's invariants
  archive_read_back.py --compare A B          A and B hold identical deterministic datasets
                                              (everything but /targets/timings)
Exits 0 when everything holds, 1 with a message on the first problem.
"""
import json
import math
import os
import sys
import xml.etree.ElementTree as ElementTree

import h5py
import numpy as np

STAGES = ["load", "anchors", "layout", "optimize", "parameterize", "compose", "outputs", "total"]
METRICS = ["E_L2", "E_ang", "stretch_max_sv", "flipped_faces", "strictly_folded_faces", "area_ratio", "gt_error",
           "swaps", "merges", "released_anchors", "dropped_faces", "dropped_area", "holes_filled", "filled_area",
           "on_filled_vertices", "max_distance_to_scan", "file_faces"]
# Wall-clock seconds are the one dataset that differs between identical runs.
NON_DETERMINISTIC = {"/targets/timings"}


class Mismatch(Exception):
    pass


def require(condition, message):
    if not condition:
        raise Mismatch(message)


def strings(dataset):
    return [s.decode("utf-8") if isinstance(s, bytes) else s for s in dataset[()]]


def attr_text(obj, name):
    value = obj.attrs[name]
    return value.decode("utf-8") if isinstance(value, bytes) else str(value)


def check_layout(path):
    """Opens the archive, reads every dataset, checks shapes and invariants; returns the file."""
    f = h5py.File(path, "r")
    require(attr_text(f, "format") == "xparam-archive", "format attribute")
    require(int(f.attrs["schema_version"]) == 5, "schema_version")
    for name in ("xparam_version", "git_revision", "options_json"):
        attr_text(f, name)
    json.loads(attr_text(f, "options_json"))

    tv = f["template/vertices"]
    tf = f["template/faces"]
    require(tv.ndim == 2 and tv.shape[1] == 3 and tv.dtype == np.float64, "template/vertices shape or type")
    require(tf.ndim == 2 and tf.shape[1] == 3 and tf.dtype == np.int32, "template/faces shape or type")
    n_v, n_f = tv.shape[0], tf.shape[0]
    faces = tf[()]
    require(faces.size == 0 or (faces.min() >= 0 and faces.max() < n_v), "template face index range")
    require(len(strings(f["template/anchor_names"])) == f["template/anchor_vertices"].shape[0], "anchors")
    curve_names = strings(f["template/curves/names"])
    n_c = len(curve_names)
    offsets = f["template/curves/offsets"][()]
    require(offsets.shape == (n_c + 1,) and offsets[0] == 0 and np.all(np.diff(offsets) >= 0), "template curve offsets")
    require(f["template/curves/face"].shape == (offsets[-1],), "template curve faces")
    require(f["template/curves/bary"].shape == (offsets[-1], 3), "template curve barycentrics")

    t = f["targets"]
    names = strings(t["name"])
    n = len(names)
    require(all(a < b for a, b in zip(names, names[1:])), "targets sorted by name (byte order) and unique")
    for column in ("error", "diagnosis", "mesh_file", "anchors_file", "mesh_sha256", "anchors_sha256"):
        require(len(strings(t[column])) == n, column + " length")
    status_dtype = h5py.check_enum_dtype(t["status"].dtype)
    require(status_dtype == {"failed": 0, "ok": 1, "suspect": 2}, "status enum")
    ok = t["status"][()] != 0  # ok or suspect: the map exists
    shapes = {"remesh_vertices": (n, n_v, 3), "corr_face": (n, n_v), "corr_bary": (n, n_v, 3),
              "distance_to_scan": (n, n_v), "face_patch": (n, n_f), "face_l2_stretch": (n, n_f), "face_angle_distortion": (n, n_f)}
    for name, shape in shapes.items():
        d = t[name]
        require(d.shape == shape, f"{name} shape {d.shape} != {shape}")
        require(d.chunks == (1,) + shape[1:], f"{name} not chunked one subject per chunk: {d.chunks}")
        require(d.compression == "gzip" and d.compression_opts == 4, f"{name} compression")
        values = d[()]
        failed = values[~ok]
        if values.dtype.kind == "f":
            require(np.all(np.isnan(failed)), f"{name}: failed rows not NaN")
            require(np.all(np.isfinite(values[ok])), f"{name}: ok rows not finite")
        else:
            require(np.all(failed == -1), f"{name}: failed rows not -1")
    corr = t["corr_face"][()][ok]
    require(corr.size == 0 or corr.min() >= 0, "corr_face of ok targets")
    n_a = f["template/anchor_vertices"].shape[0]
    anchor_miss = t["anchor_miss"][()]
    require(anchor_miss.shape == (n, n_a), "anchor_miss shape")
    require(np.all(np.isnan(anchor_miss[~ok])), "anchor_miss: failed rows not NaN")
    released = t["metrics"]["released_anchors"][ok]
    require(np.array_equal(np.sum(~np.isnan(anchor_miss[ok]), axis=1), released),
            "anchor_miss: one distance per released anchor")
    metrics = t["metrics"]
    require(metrics.shape == (n,) and list(metrics.dtype.names) == METRICS, "metrics table columns")
    timings = t["timings"]
    require(timings.shape == (n, len(STAGES)), "timings shape")
    require([s.decode() if isinstance(s, bytes) else s for s in timings.attrs["stages"]] == STAGES, "stages")
    curve_offsets = t["curves/offsets"][()]
    require(curve_offsets.shape == (n, n_c + 1), "target curve offsets shape")
    flat = curve_offsets[:, :].copy()
    if n:
        require(np.all(np.diff(flat, axis=1) >= 0), "target curve offsets increase")
        require(np.all(flat[1:, 0] == flat[:-1, -1]) and flat[0, 0] == 0, "target curve offsets are contiguous")
        require(np.all(flat[~ok, 0] == flat[~ok, -1]), "failed targets have curve points")
    total = int(flat[-1, -1]) if n else 0
    for name in ("face", "bary", "xyz"):
        require(t["curves/" + name].shape[0] == total, "curve " + name + " rows")
    check_xdmf(path, f, names, ok)
    return f


def check_xdmf(path, f, names, ok):
    sidecar = os.path.splitext(path)[0] + ".xdmf"
    if not os.path.exists(sidecar):
        return
    root = ElementTree.parse(sidecar).getroot()  # raises on malformed XML
    require(root.tag == "Xdmf", "XDMF root element")
    collection = root.find("Domain/Grid")
    require(collection.get("CollectionType") == "Temporal", "temporal collection")
    grids = collection.findall("Grid")
    grid_names = [g.get("Name") for g in grids]
    ok_names = [m for m, good in zip(names, ok) if good]
    require(grid_names == ok_names, f"one grid per ok target: grids {grid_names}, ok targets {ok_names}")
    archive_name = os.path.basename(path)
    for grid in grids:
        row = int(grid.find("Time").get("Value"))
        require(names[row] == grid.get("Name"), "grid time is the target's row")
        for item in grid.iter("DataItem"):
            if item.get("Format") != "HDF":
                continue
            file_name, dataset = item.text.strip().split(":", 1)
            require(file_name == archive_name, "XDMF names the archive")
            dims = tuple(int(x) for x in item.get("Dimensions").split())
            require(f[dataset].shape == dims, f"XDMF dimensions of {dataset}")


def close(a, b):
    a = np.asarray(a, dtype=np.float64)
    b = np.asarray(b, dtype=np.float64)
    return a.shape == b.shape and np.array_equal(a, b, equal_nan=True)


def nan_of(values):
    """JSON null stands for NaN."""
    if isinstance(values, list):
        return [nan_of(v) for v in values]
    return math.nan if values is None else values


def check_values(f, expected):
    require(attr_text(f, "xparam_version") == expected["xparam_version"], "xparam_version")
    require(attr_text(f, "git_revision") == expected["git_revision"], "git_revision")
    require(attr_text(f, "options_json") == expected["options_json"], "options_json")
    et = expected["template"]
    require(attr_text(f["template"], "mesh_file") == et["mesh_file"], "template mesh_file")
    require(attr_text(f["template"], "mesh_sha256") == et["mesh_sha256"], "template mesh_sha256")
    require(close(f["template/vertices"][()], et["vertices"]), "template vertices")
    require(np.array_equal(f["template/faces"][()], np.array(et["faces"], dtype=np.int32)), "template faces")
    require(strings(f["template/anchor_names"]) == et["anchor_names"], "anchor names")
    require(list(f["template/anchor_vertices"][()]) == et["anchor_vertices"], "anchor vertices")
    offsets = f["template/curves/offsets"][()]
    for c, curve in enumerate(et["curves"]):
        require(strings(f["template/curves/names"])[c] == curve["name"], "curve name")
        rows = slice(offsets[c], offsets[c + 1])
        require(list(f["template/curves/face"][rows]) == curve["face"], "template curve faces " + curve["name"])
        require(close(f["template/curves/bary"][rows], curve["bary"]), "template curve bary " + curve["name"])
    require(strings(f["template/measurement_names"]) == et["measurement_names"], "measurement names")
    require(strings(f["template/measurement_units"]) == et["measurement_units"], "measurement units")
    require(close(f["template/measurement_values"][()], et["measurement_values"]), "template measurements")

    t = f["targets"]
    if et["measurement_names"]:
        names_attribute = [s.decode() if isinstance(s, bytes) else s for s in t["measurements"].attrs["names"]]
        require(names_attribute == et["measurement_names"], "/targets/measurements names attribute")
    require(strings(t["name"]) == [e["name"] for e in expected["targets"]], "target names and order")
    status = t["status"][()]
    metrics = t["metrics"][()]
    timings = t["timings"][()]
    curve_offsets = t["curves/offsets"][()]
    for i, e in enumerate(expected["targets"]):
        where = "target " + e["name"] + ": "
        require(bool(status[i]) == e["ok"], where + "status")
        if "status" in e:
            require(int(status[i]) == e["status"], where + "status value")
        for column in ("error", "diagnosis", "mesh_file", "anchors_file", "mesh_sha256", "anchors_sha256"):
            require(strings(t[column])[i] == e[column], where + column)
        for column in METRICS:
            require(close(metrics[column][i], nan_of(e["metrics"][column])), where + "metric " + column)
        require(close(timings[i], nan_of(e["seconds"])), where + "timings")
        if not e["ok"]:
            continue
        # Slicing one subject, as an h5py user would.
        require(close(t["remesh_vertices"][i], e["remesh_vertices"]), where + "remesh_vertices")
        require(list(t["corr_face"][i]) == e["corr_face"], where + "corr_face")
        require(close(t["corr_bary"][i], e["corr_bary"]), where + "corr_bary")
        require(close(t["distance_to_scan"][i], e["distance_to_scan"]), where + "distance_to_scan")
        require(list(t["face_patch"][i]) == e["face_patch"], where + "face_patch")
        require(close(t["face_l2_stretch"][i], e["face_l2_stretch"]), where + "face_l2_stretch")
        require(close(t["face_angle_distortion"][i], e["face_angle_distortion"]), where + "face_angle_distortion")
        require(close(t["anchor_miss"][i], nan_of(e["anchor_miss"])), where + "anchor_miss")
        if "measurements" in e and e["measurements"]:
            require(close(t["measurements"][i], nan_of(e["measurements"])), where + "measurements")
        for c, curve in enumerate(e["curves"]):
            rows = slice(curve_offsets[i, c], curve_offsets[i, c + 1])
            require(list(t["curves/face"][rows]) == curve["face"], where + f"curve {c} faces")
            require(close(t["curves/bary"][rows].reshape(-1, 3), np.reshape(curve["bary"], (-1, 3))),
                    where + f"curve {c} bary")
            require(close(t["curves/xyz"][rows].reshape(-1, 3), np.reshape(curve["xyz"], (-1, 3))),
                    where + f"curve {c} xyz")


def datasets_of(f):
    found = {}
    f.visititems(lambda name, obj: found.__setitem__("/" + name, obj) if isinstance(obj, h5py.Dataset) else None)
    return found


def compare(path_a, path_b):
    a = check_layout(path_a)
    b = check_layout(path_b)
    da, db = datasets_of(a), datasets_of(b)
    require(sorted(da) == sorted(db), f"dataset sets differ: {sorted(set(da) ^ set(db))}")
    for name in sorted(da):
        x, y = da[name], db[name]
        require(x.shape == y.shape and x.dtype == y.dtype, name + ": shape or type differs")
        require(x.chunks == y.chunks and x.compression == y.compression, name + ": storage differs")
        if name in NON_DETERMINISTIC:
            continue
        if h5py.check_string_dtype(x.dtype) is not None:
            require(strings(x) == strings(y), name + ": strings differ")
        else:
            require(x[()].tobytes() == y[()].tobytes(), name + ": values differ")
    for key in ("schema_version", "xparam_version", "git_revision", "options_json"):
        require(attr_text(a, key) == attr_text(b, key), "root attribute " + key + " differs")


def main(argv):
    try:
        if len(argv) == 3 and argv[1] == "--open":
            check_layout(argv[2])
        elif len(argv) == 4 and argv[1] == "--compare":
            compare(argv[2], argv[3])
        elif len(argv) == 3:
            with open(argv[2], encoding="utf-8") as expected_file:
                expected = json.load(expected_file)
            check_values(check_layout(argv[1]), expected)
        else:
            print(__doc__, file=sys.stderr)
            return 2
    except Mismatch as mismatch:
        print("archive_read_back: " + str(mismatch), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))

#!/usr/bin/env python3
"""Compare `xparam check --json` with the MESH STATS tables of ../shared/data/*/SOURCE.txt.

Every SOURCE.txt may hold a table introduced by a line starting with "MESH STATS", whose
header row starts with "file" and whose columns are
    file  V  F  boundary_loops  components  nonmanifold_edges  genus(if 1 comp; chi-based)  faces
(`faces` lists polygon sizes, e.g. "3-gon:13776" or "3-gon:10,4-gon:2"). Every row whose file
is present is checked (some listed meshes are kept aside and absent; they are counted, not
failed):
  V, F (triangles after fan triangulation), boundary loops, components, non-manifold edges,
  and polygons_triangulated: exactly.
  genus: the table's genus is (2 - chi - b) / 2 from the Euler characteristic, fractional on a
  pinched or non-orientable mesh; so our euler_characteristic must equal 2 - 2 g - b exactly.
  Where xparam reports an integer genus it must equal the table's -- after xparam's repair
  of pinched vertices, which adds one vertex per extra fan (`vertex_copies`), so the repaired
  genus is the table's minus vertex_copies / 2 (SCAPE: 0.5 - 1/2 = 0). xparam leaves genus null
  when it is not meaningful (non-manifold edge, non-orientable, several components, a pinch it
  did not split); those rows are listed as notes with the reason.
  "-" (several components): xparam's genus must be null.
Exit status 0 when every present mesh agrees, 2 when some disagree (as `xparam check` when some mesh
is unusable), 1 when the comparison cannot run. Usage:
    scripts/check_shared_data.py [--xparam BUILD/src/cli/xparam] [--data ../shared/data]
"""
import argparse
import json
import pathlib
import subprocess
import sys
from fractions import Fraction


def parse_tables(data_dir):
    """Yields (mesh path, row dict) for every row of every MESH STATS table."""
    for source in sorted(data_dir.glob("*/SOURCE.txt")):
        lines = source.read_text(errors="replace").splitlines()
        in_stats = False
        header = None
        for line in lines:
            if line.startswith("MESH STATS"):
                in_stats, header = True, None
                continue
            if not in_stats:
                continue
            fields = line.split()
            if header is None:
                if fields and fields[0] == "file":
                    header = fields
                continue
            if len(fields) != 8:  # the table ends at the first line that is not a row
                in_stats = False
                continue
            name, v, f, loops, components, nm_edges, genus, faces = fields
            yield source.parent / name, {
                "table": str(source.relative_to(data_dir)),
                "vertices": int(v),
                "faces_column": faces,
                "boundary_loops": int(loops),
                "components": int(components),
                "non_manifold_edges": int(nm_edges),
                "genus": None if genus == "-" else Fraction(genus),
            }


def expected_triangles(faces_column):
    """(triangles, polygons with more than 3 corners) from e.g. '3-gon:10,4-gon:2'."""
    triangles = polygons = 0
    for part in faces_column.split(","):
        size, count = part.split("-gon:")
        size, count = int(size), int(count)
        triangles += (size - 2) * count
        polygons += count if size > 3 else 0
    return triangles, polygons


def genus_text(genus):
    return str(genus.numerator) if genus.denominator == 1 else str(float(genus))


def why_no_genus(ours):
    reasons = []
    if ours["components"] != 1:
        reasons.append(f"{ours['components']} components")
    if ours["non_manifold_edges"]:
        reasons.append(f"{ours['non_manifold_edges']} non-manifold edges")
    if ours["non_manifold_vertices"] and not ours.get("split_vertices"):
        reasons.append(f"{ours['non_manifold_vertices']} non-manifold vertices")
    if not ours["orientable"]:
        reasons.append("not orientable")
    reasons += [p.split(": ", 1)[-1] for p in ours.get("problems", []) if ": after repair: " in p][:1]
    return ", ".join(reasons) or "chi + boundary loops is odd"


def compare(path, row, ours):
    """List of mismatch descriptions (empty when everything agrees) and a note or None."""
    mismatches = []
    if "error" in ours:
        return [f"xparam could not read it: {ours['error']}"], None
    triangles, polygons = expected_triangles(row["faces_column"])
    checks = [
        ("vertices", row["vertices"], ours["vertices"]),
        ("faces (triangles)", triangles, ours["faces"]),
        ("polygons_triangulated", polygons, ours["polygons_triangulated"]),
        ("boundary_loops", row["boundary_loops"], ours["boundary_loops"]),
        ("components", row["components"], ours["components"]),
        ("non_manifold_edges", row["non_manifold_edges"], ours["non_manifold_edges"]),
    ]
    for what, expected, got in checks:
        if expected != got:
            mismatches.append(f"{what}: table {expected}, xparam {got}")
    note = None
    genus = row["genus"]
    if genus is None:
        if ours["genus"] is not None:
            mismatches.append(f"genus: table '-' (several components), xparam {ours['genus']}")
    else:
        chi = 2 - 2 * genus - row["boundary_loops"]
        if chi != ours["euler_characteristic"]:
            mismatches.append(f"Euler characteristic: table {chi} (genus {genus_text(genus)}), "
                              f"xparam {ours['euler_characteristic']}")
        copies = ours.get("vertex_copies", 0)
        repaired = genus - Fraction(copies, 2)
        if ours["genus"] is not None and ours["genus"] != repaired:
            split = f" less {copies} split-vertex copies / 2 = {genus_text(repaired)}" if copies else ""
            mismatches.append(f"genus: table {genus_text(genus)}{split}, xparam {ours['genus']}")
        if ours["genus"] is not None and copies:
            note = (f"table genus {genus_text(genus)} (chi {chi} agrees); xparam splits "
                    f"{len(ours['split_vertices'])} pinched vertices into {copies} more: genus {ours['genus']}")
        if ours["genus"] is None:
            note = (f"table genus {genus_text(genus)} (chi {chi} agrees); xparam leaves genus undefined: "
                    f"{why_no_genus(ours)}")
    return mismatches, note


def main():
    root = pathlib.Path(__file__).resolve().parent.parent
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--xparam", default=str(root / "build" / "src" / "cli" / "xparam"))
    parser.add_argument("--data", default=str(root.parent / "shared" / "data"))
    args = parser.parse_args()
    data_dir = pathlib.Path(args.data)
    if not data_dir.is_dir():
        print(f"{data_dir}: no shared data folder; nothing to compare")
        return 0

    rows = list(parse_tables(data_dir))
    present = [(path, row) for path, row in rows if path.is_file()]
    absent = [path for path, _ in rows if not path.is_file()]
    if not present:
        print(f"no mesh listed in {data_dir}/*/SOURCE.txt is present")
        return 1
    # One process for all files; exit status 2 only means some mesh is unusable.
    run = subprocess.run([args.xparam, "check", "--json"] + [str(p) for p, _ in present],
                         capture_output=True, text=True)
    if run.returncode not in (0, 2):
        print(f"xparam check failed with status {run.returncode}:\n{run.stderr}")
        return 1
    results = {pathlib.Path(entry["file"]): entry for entry in json.loads(run.stdout)}

    failures = 0
    for path, row in present:
        mismatches, note = compare(path, row, results[path])
        name = path.relative_to(data_dir)
        for mismatch in mismatches:
            print(f"MISMATCH {name}: {mismatch}")
        failures += bool(mismatches)
        if note:
            print(f"note {name}: {note}")
    tables = len({row["table"] for _, row in rows})
    print(f"compared {len(present)} meshes from {tables} tables ({len(absent)} listed meshes absent): "
          + ("all agree" if failures == 0 else f"{failures} disagree"))
    return 0 if failures == 0 else 2


if __name__ == "__main__":
    sys.exit(main())

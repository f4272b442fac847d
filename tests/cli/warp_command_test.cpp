// `xparam warp` run as a user runs it, on an archive written from synthetic records: a sphere
// template, its identity image, a scaled and moved image and a failed target.
#include "io/archive_hdf5.h"
#include "io/archive_writer.h"
#include "io/garment_obj.h"
#include "io/sha256.h"

#include "support/test_data.h"
#include "support/warp_shapes.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>

namespace xparam {
namespace {

namespace fs = std::filesystem;

const Eigen::Vector3d kShift(0.5, -0.25, 2.0);
constexpr double kScale = 1.2;

// The template: a sphere of 66 vertices, anchors a, b, c at vertices 0, 2, 4.
TemplateRecord sphere_template() {
  const TriangleSoup sphere = test::sphere_soup(2);
  TemplateRecord t;
  t.mesh_file = "sphere.obj";
  t.anchors_file = "sphere.anchors.json";
  t.vertices.resize(static_cast<Eigen::Index>(sphere.vertices.size()), 3);
  for (std::size_t v = 0; v < sphere.vertices.size(); ++v) t.vertices.row(static_cast<Eigen::Index>(v)) = sphere.vertices[v];
  t.faces.resize(static_cast<Eigen::Index>(sphere.triangles.size()), 3);
  for (std::size_t f = 0; f < sphere.triangles.size(); ++f)
    t.faces.row(static_cast<Eigen::Index>(f)) << sphere.triangles[f][0], sphere.triangles[f][1], sphere.triangles[f][2];
  t.anchor_names = {"a", "b", "c"};
  t.anchor_vertices = {0, 2, 4};
  return t;
}

// A mapped target whose remesh is the template scaled and moved; its files NAME.obj, NAME.json
// (not written here).
TargetRecord sphere_target(const TemplateRecord& t, const std::string& name, double scale, const Eigen::Vector3d& shift) {
  TargetRecord r;
  r.name = name;
  r.ok = true;
  r.mesh_file = name + ".obj";
  r.anchors_file = name + ".json";
  r.remesh_vertices = (t.vertices * scale).rowwise() + shift.transpose();
  const auto n = t.vertices.rows();
  r.corr_face = Eigen::VectorXi::Zero(n);
  r.corr_bary = Eigen::MatrixX3d::Constant(n, 3, 1.0 / 3.0);
  r.distance_to_scan = Eigen::VectorXd::Zero(n);
  r.face_patch = Eigen::VectorXi::Zero(t.faces.rows());
  r.face_l2_stretch = Eigen::VectorXd::Ones(t.faces.rows());
  r.face_angle_distortion = Eigen::VectorXd::Zero(t.faces.rows());
  r.anchor_miss = Eigen::VectorXd::Constant(3, std::numeric_limits<double>::quiet_NaN());
  return r;
}

// The archive: template = a sphere; "same" maps it onto itself, "grown" onto 1.2x it moved by
// kShift, "lost" failed. No target file exists, so every body is the remesh.
fs::path write_sphere_archive(const fs::path& dir) {
  const TemplateRecord t = sphere_template();
  const auto target = [&](const std::string& name, double scale, const Eigen::Vector3d& shift) {
    return sphere_target(t, name, scale, shift);
  };
  TargetRecord lost;
  lost.name = "lost";
  lost.error = "lost.obj: genus 1, the template has genus 0";
  lost.mesh_file = "lost.obj";
  write_archive(dir / "run.h5", t, current_provenance("{}"), {target("same", 1.0, Eigen::Vector3d::Zero()),
                                                              target("grown", kScale, kShift), lost});
  return dir / "run.h5";
}

// A cap over the sphere at 1.05 (every fifth vertex at `sunk`: 0.95, inside), with UVs from x, y.
fs::path write_garment(const fs::path& dir, double sunk = 0.95) {
  const TriangleSoup fine = test::sphere_soup(3);
  std::ofstream out(dir / "cap.obj");
  std::vector<int> index(fine.vertices.size(), -1);
  int n = 0;
  for (std::size_t v = 0; v < fine.vertices.size(); ++v) {
    const Eigen::Vector3d& p = fine.vertices[v];
    if (p.z() < 0.2) continue;
    index[v] = n++;
    const Eigen::Vector3d q = (v % 5 == 0 ? sunk : 1.05) * p;
    out << "v " << q.x() << " " << q.y() << " " << q.z() << "\nvt " << 0.5 + p.x() / 2 << " " << 0.5 + p.y() / 2 << "\n";
  }
  for (const auto& [a, b, c] : fine.triangles) {
    if (index[a] >= 0 && index[b] >= 0 && index[c] >= 0)
      out << "f " << index[a] + 1 << "/" << index[a] + 1 << " " << index[b] + 1 << "/" << index[b] + 1 << " "
          << index[c] + 1 << "/" << index[c] + 1 << "\n";
  }
  return dir / "cap.obj";
}

std::string command(const fs::path& archive, const fs::path& garment, const std::string& rest) {
  return "warp --archive " + archive.string() + " --garment " + garment.string() + " " + rest;
}

TEST(WarpCommand, WarpsOntoEveryMappedTargetKeepingOrderAndUvs) {
  const fs::path dir = test::fresh_temp_dir("cli_warp_folder");
  const fs::path archive = write_sphere_archive(dir);
  const fs::path garment = write_garment(dir);
  const fs::path out = dir / "warped";
  std::string errors;
  // "lost" has no map: exit 2, the others are written.
  ASSERT_EQ(test::run_xparam(command(archive, garment, "--out " + out.string()), dir, errors), 2) << errors;
  EXPECT_NE(errors.find("lost"), std::string::npos) << errors;
  const GarmentObj rest = read_garment_obj(garment);
  const GarmentObj same = read_garment_obj(out / "same.obj");
  const GarmentObj grown = read_garment_obj(out / "grown.obj");
  EXPECT_EQ(same.mesh.triangles, rest.mesh.triangles);
  EXPECT_EQ(same.uvs, rest.uvs);
  EXPECT_EQ(grown.triangle_uvs, rest.triangle_uvs);
  for (std::size_t g = 0; g < rest.mesh.vertices.size(); ++g) {
    EXPECT_LT((same.mesh.vertices[g] - rest.mesh.vertices[g]).norm(), 1e-12) << g;
    EXPECT_LT((grown.mesh.vertices[g] - (kScale * rest.mesh.vertices[g] + kShift)).norm(), 1e-12) << g;
  }
  std::ifstream summary_file(out / "summary.json");
  const nlohmann::json summary = nlohmann::json::parse(summary_file);
  ASSERT_EQ(summary["targets"].size(), 3u);
  EXPECT_EQ(summary["targets"][0]["name"], "grown");  // the archive's (name) order
  EXPECT_EQ(summary["targets"][1]["status"], "failed");
  EXPECT_NEAR(summary["targets"][0]["figures"]["edge_ratio_mean"].get<double>(), kScale, 1e-12);
  EXPECT_GT(summary["targets"][2]["figures"]["placed_inside"].get<int>(), 0);  // the sunk vertices

  // Again without --force: refused, nothing changed; with --force and a clearance: nothing inside.
  EXPECT_EQ(test::run_xparam(command(archive, garment, "--out " + out.string()), dir, errors), 1);
  EXPECT_NE(errors.find("--force"), std::string::npos) << errors;
  ASSERT_EQ(test::run_xparam(command(archive, garment, "--target same --target grown --clearance 0.02 --force --out " +
                                                           out.string()),
                             dir, errors),
            0)
      << errors;
  std::ifstream cleared_file(out / "summary.json");
  const nlohmann::json cleared = nlohmann::json::parse(cleared_file);
  for (const auto& target : cleared["targets"]) {
    EXPECT_EQ(target["figures"]["inside"], 0) << target;
    EXPECT_GT(target["figures"]["pushed"].get<int>(), 0) << target;
  }
}

TEST(WarpCommand, WritesOneHdf5FileAndRefusesUnknownTargets) {
  const fs::path dir = test::fresh_temp_dir("cli_warp_h5");
  const fs::path archive = write_sphere_archive(dir);
  const fs::path garment = write_garment(dir);
  std::string errors;
  EXPECT_EQ(test::run_xparam(command(archive, garment, "--target nobody --out " + (dir / "w.h5").string()), dir, errors), 1);
  EXPECT_NE(errors.find("no target \"nobody\""), std::string::npos) << errors;
  EXPECT_FALSE(fs::exists(dir / "w.h5"));
  ASSERT_EQ(test::run_xparam(command(archive, garment, "--target grown --out " + (dir / "w.h5").string()), dir, errors), 0)
      << errors;
  const h5::Handle file = h5::open_file(dir / "w.h5");
  const h5::Handle vertices = h5::open_dataset(file.get(), "targets/vertices");
  const GarmentObj rest = read_garment_obj(garment);
  EXPECT_EQ(h5::shape(vertices.get()), (std::vector<hsize_t>{1, rest.mesh.vertices.size(), 3}));
  const std::vector<double> xyz = h5::read_all<double>(vertices.get());
  EXPECT_NEAR(xyz[0], kScale * rest.mesh.vertices[0].x() + kShift.x(), 1e-12);
  EXPECT_EQ(h5::read_strings(file.get(), "targets/name"), std::vector<std::string>{"grown"});
}

// `soup` as an OBJ file.
void write_obj(const fs::path& path, const TriangleSoup& soup) {
  std::ofstream out(path);
  out.precision(17);
  for (const Eigen::Vector3d& p : soup.vertices) out << "v " << p.x() << " " << p.y() << " " << p.z() << "\n";
  for (const auto& [a, b, c] : soup.triangles) out << "f " << a + 1 << " " << b + 1 << " " << c + 1 << "\n";
}

nlohmann::json read_json(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

TEST(WarpCommand, MeasuresPenetrationOnTheTargetsOwnSurfaceWhenItsFileIsUnchanged) {
  // Three targets whose remesh is the coarse template sphere itself and whose files are a fine
  // unit sphere (the true surface, its faces within 4e-4 of it): "kept" where the batch read it,
  // "moved" to another folder, "edited" changed since (scaled by 1.01).
  const fs::path dir = test::fresh_temp_dir("cli_warp_surface");
  const TriangleSoup fine = test::sphere_soup(5);
  const TemplateRecord t = sphere_template();
  std::vector<TargetRecord> targets;
  fs::create_directories(dir / "elsewhere");
  for (const std::string name : {"edited", "kept", "moved"}) {
    TargetRecord r = sphere_target(t, name, 1.0, Eigen::Vector3d::Zero());
    r.mesh_file = (dir / r.mesh_file).string();  // as the batch records a path given in full
    r.anchors_file = (dir / r.anchors_file).string();
    write_obj(r.mesh_file, fine);
    std::ofstream(r.anchors_file) << R"({"anchors": [{"name": "a", "vertex": 0}, {"name": "b", "vertex": 2},
                                                {"name": "c", "vertex": 4}, {"name": "d", "vertex": 5}]})";
    r.mesh_sha256 = sha256_file_hex(r.mesh_file);
    r.anchors_sha256 = sha256_file_hex(r.anchors_file);
    targets.push_back(r);
  }
  TriangleSoup larger = fine;
  for (Eigen::Vector3d& p : larger.vertices) p *= 1.01;
  write_obj(dir / "edited.obj", larger);
  for (const char* file : {"moved.obj", "moved.json"}) fs::rename(dir / file, dir / "elsewhere" / file);
  write_archive(dir / "run.h5", t, current_provenance("{}"), targets);
  // The cap's sunk vertices at 0.99: inside the unit sphere, outside the coarse chords over the
  // middle of a face (about 0.97 from the centre there).
  const fs::path garment = write_garment(dir, 0.99);
  const GarmentObj rest = read_garment_obj(garment);
  int sunk = 0, under_chords = 0;
  TriangleSoup remesh;
  remesh.vertices.resize(static_cast<std::size_t>(t.vertices.rows()));
  for (Eigen::Index v = 0; v < t.vertices.rows(); ++v) remesh.vertices[static_cast<std::size_t>(v)] = t.vertices.row(v);
  for (Eigen::Index f = 0; f < t.faces.rows(); ++f) remesh.triangles.push_back({t.faces(f, 0), t.faces(f, 1), t.faces(f, 2)});
  for (const Eigen::Vector3d& p : rest.mesh.vertices) {
    sunk += test::winding_number(fine, p) > 0.5 ? 1 : 0;
    under_chords += test::winding_number(remesh, p) > 0.5 ? 1 : 0;
  }
  ASSERT_GT(sunk, under_chords);

  std::string errors;
  const fs::path out = dir / "warped";
  ASSERT_EQ(test::run_xparam(command(dir / "run.h5", garment, "--out " + out.string()), dir, errors), 0) << errors;
  nlohmann::json summary = read_json(out / "summary.json");
  const auto target = [&](const std::string& name) {
    for (const auto& entry : summary["targets"])
      if (entry["name"] == name) return entry;
    ADD_FAILURE() << name << " not in the summary";
    return nlohmann::json();
  };
  EXPECT_EQ(target("kept")["body"], "surface");
  EXPECT_EQ(target("kept")["body_note"], (dir / "kept.obj").string());
  EXPECT_EQ(target("kept")["figures"]["placed_inside"], sunk);
  EXPECT_EQ(target("edited")["body"], "remesh");
  EXPECT_EQ(target("edited")["figures"]["placed_inside"], under_chords);
  EXPECT_NE(target("edited")["body_note"].get<std::string>().find("edited.obj changed since the batch mapped it"),
            std::string::npos);
  EXPECT_EQ(target("moved")["body"], "remesh");
  EXPECT_NE(target("moved")["body_note"].get<std::string>().find("moved.obj is missing"), std::string::npos);
  // One warning line per fallback, naming the target, the file and why.
  EXPECT_NE(errors.find("warning: edited: penetration and clearance measured against its remesh, not its own surface: "
                        "its mesh file " + (dir / "edited.obj").string() + " changed since the batch mapped it"),
            std::string::npos)
      << errors;
  EXPECT_NE(errors.find("warning: moved: penetration and clearance measured against its remesh, not its own surface: "
                        "its mesh file " + (dir / "moved.obj").string() + " is missing (give --targets DIR"),
            std::string::npos)
      << errors;
  EXPECT_EQ(errors.find("warning: kept"), std::string::npos) << errors;

  // --targets finds the moved files by name; the edited one is still refused; in the HDF5 file too.
  ASSERT_EQ(test::run_xparam(command(dir / "run.h5", garment,
                                     "--targets " + (dir / "elsewhere").string() + " --out " + (dir / "w.h5").string()),
                             dir, errors),
            0)
      << errors;
  const h5::Handle file = h5::open_file(dir / "w.h5");
  EXPECT_EQ(h5::read_strings(file.get(), "targets/name"), (std::vector<std::string>{"edited", "kept", "moved"}));
  EXPECT_EQ(h5::read_strings(file.get(), "targets/body"), (std::vector<std::string>{"remesh", "surface", "surface"}));
  EXPECT_EQ(h5::read_strings(file.get(), "targets/body_note")[2], (dir / "elsewhere" / "moved.obj").string());
  EXPECT_NE(errors.find("warning: edited: "), std::string::npos) << errors;
  EXPECT_EQ(errors.find("warning: moved"), std::string::npos) << errors;
}

}  // namespace
}  // namespace xparam

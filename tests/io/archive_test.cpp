// The HDF5 archive: write / read back exactly, the stored layout (chunks, filters, fills),
// determinism, the commit protocol under SIGKILL, resume, merge, XDMF, and an independent
// read-back with Debian's python3-h5py (tests/io/archive_read_back.py).
//
// The records are synthetic on purpose: the archive is the unit under test. Every target's
// arrays are a different function of its index, so a row mix-up changes what is read back.
#include "io/archive_commit.h"
#include "io/archive_hdf5.h"
#include "io/archive_merge.h"
#include "io/archive_reader.h"
#include "io/archive_writer.h"
#include "io/sha256.h"
#include "io/xdmf.h"

#include "core/errors.h"
#include "support/record_comparison.h"
#include "support/test_data.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <thread>

namespace xparam {
namespace {

namespace fs = std::filesystem;
using test::expect_same_results;
using test::same_bits;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

TemplateRecord make_template(int n_vertices) {
  TemplateRecord t;
  t.mesh_file = "template/head.obj";
  t.anchors_file = "template/head.anchors.json";
  t.curves_file = "template/head.curves.json";
  t.mesh_sha256 = sha256_hex("mesh bytes");
  t.anchors_sha256 = sha256_hex("anchor bytes");
  t.curves_sha256 = sha256_hex("curve bytes");
  const int n_faces = 2 * n_vertices - 4;
  t.vertices.resize(n_vertices, 3);
  for (int i = 0; i < n_vertices; ++i) t.vertices.row(i) << i, (i * i) % 7, std::sin(i);
  t.faces.resize(n_faces, 3);
  for (int f = 0; f < n_faces; ++f)
    t.faces.row(f) << f % n_vertices, (f + 1) % n_vertices, (f + 3) % n_vertices;
  t.anchor_names = {"nose", "chin", "ear_left"};
  t.anchor_vertices = {0, n_vertices / 2, n_vertices - 1};
  for (int c = 0; c < 2; ++c) {
    TemplateCurve curve;
    curve.name = c == 0 ? "lip" : "brow";
    curve.closed = c == 0;
    const int points = 3 + 2 * c;
    curve.bary.resize(points, 3);
    for (int p = 0; p < points; ++p) {
      curve.face.push_back((5 * p + c) % n_faces);
      curve.bary.row(p) << 0.25, 0.25 + 0.05 * p, 0.5 - 0.05 * p;
    }
    t.curves.push_back(curve);
  }
  t.measurements_file = "template/head.measurements.json";
  t.measurements_sha256 = sha256_hex("measurement bytes");
  t.measurement_names = {"head_girth", "face_height"};
  t.measurement_units = {"m", "m"};
  t.measurement_values = Eigen::Vector2d(0.56, 0.21);
  return t;
}

// Target number k: every array an affine function of k, curve lengths varying with k (some empty).
TargetRecord make_target(const TemplateRecord& t, const std::string& name, int k) {
  TargetRecord r;
  r.name = name;
  r.ok = true;
  r.mesh_file = "targets/" + name + ".ply";
  r.anchors_file = "targets/" + name + ".anchors.json";
  r.mesh_sha256 = sha256_hex(name + " mesh");
  r.anchors_sha256 = sha256_hex(name + " anchors");
  const Eigen::Index n_vertices = t.vertices.rows();
  const Eigen::Index n_faces = t.faces.rows();
  r.remesh_vertices = (t.vertices * (1.0 + 0.5 * k)).array() + k;
  r.corr_face.resize(n_vertices);
  r.corr_bary.resize(n_vertices, 3);
  for (Eigen::Index i = 0; i < n_vertices; ++i) {
    r.corr_face(i) = static_cast<int>((3 * i + k) % 1000);
    const double a = static_cast<double>((i + k) % 5) / 10.0;
    const double b = static_cast<double>((i * k) % 3) / 10.0;
    r.corr_bary.row(i) << a, b, 1.0 - a - b;
  }
  // corr_face at or above file_faces (1000 + k) is on a fill face: none here, so every distance is 0.
  r.distance_to_scan = Eigen::VectorXd::Zero(n_vertices);
  r.face_patch.resize(n_faces);
  r.face_l2_stretch.resize(n_faces);
  r.face_angle_distortion.resize(n_faces);
  for (Eigen::Index f = 0; f < n_faces; ++f) {
    r.face_patch(f) = static_cast<int>((f + k) % 6);
    r.face_l2_stretch(f) = 1.0 + 0.01 * static_cast<double>(f) + k;
    r.face_angle_distortion(f) = 0.5 * static_cast<double>(f) - k;
  }
  // Target k released anchor k % #A when k is odd.
  r.anchor_miss = Eigen::VectorXd::Constant(static_cast<Eigen::Index>(t.anchor_names.size()), kNaN);
  if (k % 2 == 1) r.anchor_miss[k % r.anchor_miss.size()] = 0.01 * k;
  for (std::size_t c = 0; c < t.curves.size(); ++c) {
    TransferredCurve curve;
    const int points = static_cast<int>((c + static_cast<std::size_t>(k)) % 4);
    curve.bary.resize(points, 3);
    curve.xyz.resize(points, 3);
    for (int p = 0; p < points; ++p) {
      curve.face.push_back(10 * k + p);
      curve.bary.row(p) << 0.2, 0.3 + 0.01 * k, 0.5 - 0.01 * k;
      curve.xyz.row(p) << k, p, static_cast<double>(c);
    }
    r.curves.push_back(curve);
  }
  // Target k: the first measurement grows with k, the second has no value on odd targets.
  r.measurements = Eigen::Vector2d(0.5 + 0.01 * k, k % 2 ? kNaN : 0.2);
  r.metrics.e_l2 = 1.0 + k / 10.0;
  r.metrics.e_ang = 2.0 + k;
  r.metrics.stretch_max_sv = 3.0 + k;
  r.metrics.flipped_faces = k;
  r.metrics.strictly_folded_faces = k / 2;
  r.metrics.area_ratio = 1.0 - 0.01 * k;
  r.metrics.gt_error = k % 2 ? kNaN : 0.1 * k;
  r.metrics.swaps = 2 * k;
  r.metrics.merges = k % 3;
  r.metrics.released_anchors = k % 2;
  r.metrics.dropped_faces = 4 * k;
  r.metrics.dropped_area = 0.01 * k;
  r.metrics.holes_filled = k % 3;
  r.metrics.filled_area = 0.02 * k;
  r.metrics.on_filled_vertices = 5 * k;
  r.metrics.max_distance_to_scan = 0.001 * k;
  r.metrics.file_faces = 1000 + k;
  for (std::size_t s = 0; s < r.seconds.size(); ++s) r.seconds[s] = 0.1 * static_cast<double>(s) + k;
  // Every other target is suspect, with a diagnosis in UTF-8 (a landmark name with an accent).
  r.suspect = k % 2 == 1;
  r.diagnosis = R"({"reasons":[)" + std::string(r.suspect ? R"j("E_L2 12 (limit 10)")j" : "") +
                R"(],"folds_by_anchor":[{"anchor":"Épaule","folded_faces":)" + std::to_string(k) + "}]}";
  return r;
}

TargetRecord make_failed(const std::string& name) {
  TargetRecord r;
  r.name = name;
  r.ok = false;
  r.error = "targets/" + name + ".ply: edge (12, 40) has 3 faces";
  r.mesh_file = "targets/" + name + ".ply";
  r.anchors_file = "targets/" + name + ".anchors.json";
  r.seconds[0] = 0.25;
  return r;
}

// Five targets, deliberately not in name order, one failed.
std::vector<TargetRecord> make_targets(const TemplateRecord& t) {
  return {make_target(t, "subject_07", 7), make_target(t, "subject_02", 2), make_failed("subject_05"),
          make_target(t, "Subject 10 (scan)", 10), make_target(t, "subject_03", 3)};
}

ArchiveProvenance test_provenance() { return current_provenance(R"({"metric":"SDL","merge":true})"); }

void expect_same_target(const TargetRecord& a, const TargetRecord& b) {
  expect_same_results(a, b);
  for (std::size_t s = 0; s < a.seconds.size(); ++s) EXPECT_TRUE(same_bits(a.seconds[s], b.seconds[s])) << s;
}

std::vector<TargetRecord> sorted_by_name(std::vector<TargetRecord> targets) {
  std::sort(targets.begin(), targets.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  return targets;
}

std::string file_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

// Debian's interpreter first: a user-installed python3 earlier in PATH may lack h5py.
std::string python_with_h5py() {
  for (const char* candidate : {"/usr/bin/python3", "python3"}) {
    const std::string command = std::string(candidate) + " -c 'import h5py' > /dev/null 2>&1";
    if (std::system(command.c_str()) == 0) return candidate;
  }
  return {};
}

fs::path read_back_script() { return fs::path(XPARAM_SOURCE_DIR) / "tests" / "io" / "archive_read_back.py"; }

int run_read_back(const std::string& python, const std::string& arguments) {
  const std::string command = python + " " + read_back_script().string() + " " + arguments;
  return std::system(command.c_str());
}

nlohmann::json matrix_json(const Eigen::MatrixXd& m) {
  nlohmann::json rows = nlohmann::json::array();
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    nlohmann::json row = nlohmann::json::array();
    for (Eigen::Index j = 0; j < m.cols(); ++j) row.push_back(m(i, j));
    rows.push_back(row);
  }
  return rows;
}

std::vector<int> vector_of(const Eigen::VectorXi& v) { return {v.data(), v.data() + v.size()}; }
std::vector<double> vector_of(const Eigen::VectorXd& v) { return {v.data(), v.data() + v.size()}; }

// What archive_read_back.py compares against: every value the test wrote (NaN as null).
nlohmann::json expectation(const TemplateRecord& t, const ArchiveProvenance& p,
                           std::vector<TargetRecord> targets) {
  nlohmann::json e;
  e["schema_version"] = kArchiveSchemaVersion;
  e["xparam_version"] = p.xparam_version;
  e["git_revision"] = p.git_revision;
  e["options_json"] = p.options_json;
  e["template"] = {{"mesh_file", t.mesh_file},
                   {"mesh_sha256", t.mesh_sha256},
                   {"vertices", matrix_json(t.vertices)},
                   {"faces", matrix_json(t.faces.cast<double>())},
                   {"anchor_names", t.anchor_names},
                   {"anchor_vertices", t.anchor_vertices}};
  for (const TemplateCurve& c : t.curves)
    e["template"]["curves"].push_back({{"name", c.name}, {"face", c.face}, {"bary", matrix_json(c.bary)}});
  e["template"]["measurement_names"] = t.measurement_names;
  e["template"]["measurement_units"] = t.measurement_units;
  e["template"]["measurement_values"] = vector_of(t.measurement_values);
  e["stages"] = std::vector<std::string>(kTimingStages.begin(), kTimingStages.end());
  for (const TargetRecord& r : sorted_by_name(std::move(targets))) {
    nlohmann::json j = {{"name", r.name},
                        {"ok", r.ok},
                        {"status", !r.ok ? 0 : r.suspect ? 2 : 1},
                        {"error", r.error},
                        {"diagnosis", r.diagnosis},
                        {"mesh_file", r.mesh_file},
                        {"anchors_file", r.anchors_file},
                        {"mesh_sha256", r.mesh_sha256},
                        {"anchors_sha256", r.anchors_sha256},
                        {"metrics",
                         {{"E_L2", r.metrics.e_l2},
                          {"E_ang", r.metrics.e_ang},
                          {"stretch_max_sv", r.metrics.stretch_max_sv},
                          {"flipped_faces", r.metrics.flipped_faces},
                          {"strictly_folded_faces", r.metrics.strictly_folded_faces},
                          {"area_ratio", r.metrics.area_ratio},
                          {"gt_error", r.metrics.gt_error},
                          {"swaps", r.metrics.swaps},
                          {"merges", r.metrics.merges},
                          {"released_anchors", r.metrics.released_anchors},
                          {"dropped_faces", r.metrics.dropped_faces},
                          {"dropped_area", r.metrics.dropped_area},
                          {"holes_filled", r.metrics.holes_filled},
                          {"filled_area", r.metrics.filled_area},
                          {"on_filled_vertices", r.metrics.on_filled_vertices},
                          {"max_distance_to_scan", r.metrics.max_distance_to_scan},
                          {"file_faces", r.metrics.file_faces}}},
                        {"seconds", std::vector<double>(r.seconds.begin(), r.seconds.end())}};
    if (r.ok) {
      j["remesh_vertices"] = matrix_json(r.remesh_vertices);
      j["corr_face"] = vector_of(r.corr_face);
      j["corr_bary"] = matrix_json(r.corr_bary);
      j["distance_to_scan"] = vector_of(r.distance_to_scan);
      j["face_patch"] = vector_of(r.face_patch);
      j["face_l2_stretch"] = vector_of(r.face_l2_stretch);
      j["face_angle_distortion"] = vector_of(r.face_angle_distortion);
      j["anchor_miss"] = vector_of(r.anchor_miss);
      j["measurements"] = vector_of(r.measurements);
      for (const TransferredCurve& c : r.curves)
        j["curves"].push_back({{"face", c.face}, {"bary", matrix_json(c.bary)}, {"xyz", matrix_json(c.xyz)}});
    }
    e["targets"].push_back(j);
  }
  return e;
}

TEST(Sha256, KnownDigestsAndFiles) {
  // FIPS 180-2 test vectors.
  EXPECT_EQ(sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  const fs::path dir = test::fresh_temp_dir("sha256");
  std::string big(200000, 'x');  // longer than one read block
  for (std::size_t i = 0; i < big.size(); ++i) big[i] = static_cast<char>('a' + i % 26);
  std::ofstream(dir / "big.bin", std::ios::binary) << big;
  EXPECT_EQ(sha256_file_hex(dir / "big.bin"), sha256_hex(big));
  EXPECT_THROW(sha256_file_hex(dir / "missing.bin"), InputError);
  fs::remove_all(dir);
}

TEST(Archive, RoundTripIsExactAndSortedByName) {
  const fs::path dir = test::fresh_temp_dir("archive_round_trip");
  const TemplateRecord t = make_template(12);
  const std::vector<TargetRecord> targets = make_targets(t);
  write_archive(dir / "run.h5", t, test_provenance(), targets);
  EXPECT_FALSE(fs::exists(dir / "run.h5.tmp"));

  const ArchiveContents read = read_archive(dir / "run.h5");
  EXPECT_EQ(read.provenance.xparam_version, kVersion);
  EXPECT_EQ(read.provenance.git_revision, kGitRevision);
  EXPECT_EQ(read.provenance.options_json, test_provenance().options_json);
  EXPECT_TRUE(same_template(read.template_record, t));
  const std::vector<TargetRecord> expected = sorted_by_name(targets);
  ASSERT_EQ(read.targets.size(), expected.size());
  EXPECT_EQ(read.targets.front().name, "Subject 10 (scan)");  // byte order: upper case first
  for (std::size_t i = 0; i < expected.size(); ++i) expect_same_target(read.targets[i], expected[i]);

  const ArchiveReader reader(dir / "run.h5");
  EXPECT_EQ(reader.find("subject_05"), std::optional<std::size_t>(3));
  EXPECT_FALSE(reader.find("subject_04").has_value());
  EXPECT_FALSE(reader.targets()[3].ok);
  EXPECT_TRUE(std::isnan(reader.targets()[3].metrics.e_l2));
  EXPECT_EQ(reader.targets()[3].metrics.flipped_faces, -1);
  EXPECT_THROW(reader.read_target(5), ArchiveError);
  fs::remove_all(dir);
}

TEST(Archive, StoredLayoutIsChunkedPerSubjectDeflatedAndFilled) {
  const fs::path dir = test::fresh_temp_dir("archive_layout");
  const TemplateRecord t = make_template(12);
  write_archive(dir / "run.h5", t, test_provenance(), make_targets(t));

  const h5::Handle file = h5::open_file(dir / "run.h5");
  EXPECT_EQ(h5::read_int_attribute(file.get(), "schema_version"), kArchiveSchemaVersion);
  const h5::Handle remesh = h5::open_dataset(file.get(), "targets/remesh_vertices");
  EXPECT_EQ(h5::shape(remesh.get()), (std::vector<hsize_t>{5, 12, 3}));
  const h5::Handle plist(H5Dget_create_plist(remesh.get()), H5Pclose, "plist");
  std::vector<hsize_t> chunk(3);
  ASSERT_EQ(H5Pget_chunk(plist.get(), 3, chunk.data()), 3);
  EXPECT_EQ(chunk, (std::vector<hsize_t>{1, 12, 3}));
  // Deflate, then the Fletcher-32 checksum of the stored (deflated) bytes.
  ASSERT_EQ(H5Pget_nfilters(plist.get()), 2);
  unsigned flags = 0;
  std::size_t n_values = 1;
  unsigned level = 0;
  EXPECT_EQ(H5Pget_filter2(plist.get(), 0, &flags, &n_values, &level, 0, nullptr, nullptr),
            H5Z_FILTER_DEFLATE);
  EXPECT_EQ(level, 4u);
  n_values = 0;
  EXPECT_EQ(H5Pget_filter2(plist.get(), 1, &flags, &n_values, nullptr, 0, nullptr, nullptr),
            H5Z_FILTER_FLETCHER32);
  // Every numeric dataset is checksummed, the small tables and the template's too.
  for (const char* name : {"targets/metrics", "targets/status", "targets/timings", "targets/anchor_miss",
                           "targets/curves/offsets", "template/vertices", "template/faces"}) {
    const h5::Handle dataset = h5::open_dataset(file.get(), name);
    const h5::Handle creation(H5Dget_create_plist(dataset.get()), H5Pclose, name);
    EXPECT_EQ(H5Pget_filter_by_id2(creation.get(), H5Z_FILTER_FLETCHER32, &flags, &n_values, nullptr, 0, nullptr,
                                   nullptr),
              0)
        << name;
  }

  // Row 3 is the failed subject_05: NaN positions, -1 faces and patches.
  const std::vector<double> failed = h5::read_rows<double>(remesh.get(), 3, 1);
  EXPECT_TRUE(std::all_of(failed.begin(), failed.end(), [](double x) { return std::isnan(x); }));
  const std::vector<std::int32_t> patches =
      h5::read_rows<std::int32_t>(h5::open_dataset(file.get(), "targets/face_patch").get(), 3, 1);
  EXPECT_EQ(patches, std::vector<std::int32_t>(20, -1));
  // Curve offsets are global rows into the flat point arrays; the failed row adds none.
  const std::vector<std::int64_t> offsets =
      h5::read_all<std::int64_t>(h5::open_dataset(file.get(), "targets/curves/offsets").get());
  ASSERT_EQ(offsets.size(), 5u * 3u);
  EXPECT_EQ(offsets[3 * 3 + 0], offsets[3 * 3 + 2]);
  EXPECT_EQ(offsets[2 * 3 + 2], offsets[3 * 3 + 0]);
  EXPECT_EQ(h5::shape(h5::open_dataset(file.get(), "targets/curves/face").get())[0],
            static_cast<hsize_t>(offsets.back()));
  fs::remove_all(dir);
}

TEST(Archive, BytesDoNotDependOnTheOrderTargetsArrive) {
  const fs::path dir = test::fresh_temp_dir("archive_order");
  const TemplateRecord t = make_template(30);
  std::vector<TargetRecord> targets = make_targets(t);
  write_archive(dir / "a.h5", t, test_provenance(), targets);
  std::reverse(targets.begin(), targets.end());
  write_archive(dir / "b.h5", t, test_provenance(), targets);
  EXPECT_EQ(file_bytes(dir / "a.h5"), file_bytes(dir / "b.h5"));
  fs::remove_all(dir);
}

TEST(Archive, RejectsRecordsThatDoNotFitAndKeepsThePreviousArchive) {
  const fs::path dir = test::fresh_temp_dir("archive_reject");
  const TemplateRecord t = make_template(12);
  write_archive(dir / "run.h5", t, test_provenance(), make_targets(t));
  const std::string before = file_bytes(dir / "run.h5");

  std::vector<TargetRecord> bad = make_targets(t);
  bad[1].remesh_vertices.conservativeResize(11, 3);
  try {
    write_archive(dir / "run.h5", t, test_provenance(), bad);
    ADD_FAILURE() << "a short remesh was accepted";
  } catch (const ArchiveError& e) {
    EXPECT_NE(std::string(e.what()).find("subject_02"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("remesh_vertices"), std::string::npos) << e.what();
  }
  bad = make_targets(t);
  bad[0].name = bad[1].name;
  EXPECT_THROW(write_archive(dir / "run.h5", t, test_provenance(), bad), ArchiveError);
  bad = make_targets(t);
  bad[2].error.clear();  // a failure must say why
  EXPECT_THROW(write_archive(dir / "run.h5", t, test_provenance(), bad), ArchiveError);
  bad = make_targets(t);
  bad[4].curves.pop_back();
  EXPECT_THROW(write_archive(dir / "run.h5", t, test_provenance(), bad), ArchiveError);
  TemplateRecord bad_template = t;
  bad_template.faces(3, 1) = 12;
  EXPECT_THROW(write_archive(dir / "run.h5", bad_template, test_provenance(), make_targets(t)), ArchiveError);
  // Unsorted input to the streaming writer.
  const std::vector<TargetRecord> targets = make_targets(t);
  EXPECT_THROW(
      write_archive(dir / "run.h5", t, test_provenance(), 2, [&](std::size_t i) { return targets[i]; }),
      ArchiveError);

  EXPECT_EQ(file_bytes(dir / "run.h5"), before);
  EXPECT_FALSE(fs::exists(dir / "run.h5.tmp"));
  fs::remove_all(dir);
}

TEST(Archive, ReaderNamesWhatIsWrongWithAFile) {
  const fs::path dir = test::fresh_temp_dir("archive_reader_errors");
  std::ofstream(dir / "text.h5") << "not hdf5";
  const auto message_of = [](const fs::path& path) {
    try {
      ArchiveReader reader(path);
    } catch (const ArchiveError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message_of(dir / "text.h5").find("text.h5: not an HDF5 file"), std::string::npos);
  EXPECT_NE(message_of(dir / "missing.h5").find("missing.h5: no such archive file"), std::string::npos);
  {
    const h5::Handle other = h5::create_file(dir / "other.h5");
    h5::create_group(other.get(), "template");
  }
  EXPECT_NE(message_of(dir / "other.h5").find("not an xparam archive"), std::string::npos);
  fs::remove_all(dir);
}

TEST(BatchArchive, CommitsFromThreadsAssembleLikeOneWrite) {
  const fs::path dir = test::fresh_temp_dir("batch_threads");
  const TemplateRecord t = make_template(40);
  const std::vector<TargetRecord> targets = make_targets(t);
  write_archive(dir / "reference.h5", t, test_provenance(), targets);

  BatchArchive batch = BatchArchive::create(dir / "run.h5", t, test_provenance());
  EXPECT_TRUE(ArchiveReader(dir / "run.h5").targets().empty());
  std::vector<std::thread> threads;
  for (int thread = 0; thread < 2; ++thread)
    threads.emplace_back([&, thread] {
      for (std::size_t i = static_cast<std::size_t>(thread); i < targets.size(); i += 2)
        batch.commit(targets[i]);
    });
  for (std::thread& thread : threads) thread.join();
  EXPECT_EQ(batch.committed().size(), targets.size());
  batch.finish();
  EXPECT_FALSE(fs::exists(parts_directory(dir / "run.h5")));
  EXPECT_EQ(file_bytes(dir / "run.h5"), file_bytes(dir / "reference.h5"));
  fs::remove_all(dir);
}

TEST(BatchArchive, ResumeKeepsCommittedTargetsAndRefusesAnotherRun) {
  const fs::path dir = test::fresh_temp_dir("batch_resume");
  const fs::path archive = dir / "run.h5";
  const TemplateRecord t = make_template(16);
  const std::vector<TargetRecord> targets = make_targets(t);
  write_archive(dir / "reference.h5", t, test_provenance(), targets);
  {
    BatchArchive batch = BatchArchive::create(archive, t, test_provenance());
    batch.commit(targets[0]);
    batch.commit(targets[2]);
  }  // "killed" before any assembly: the archive on disk still has no targets
  EXPECT_TRUE(ArchiveReader(archive).targets().empty());

  TemplateRecord other = t;
  other.vertices(0, 0) += 1e-9;
  EXPECT_THROW(BatchArchive::resume(archive, other, test_provenance()), ArchiveError);
  EXPECT_THROW(BatchArchive::resume(archive, t, current_provenance(R"({"metric":"DL2"})")), ArchiveError);

  {
    BatchArchive batch = BatchArchive::resume(archive, t, test_provenance());
    EXPECT_EQ(batch.committed(), (std::vector<std::string>{"subject_05", "subject_07"}));
    EXPECT_TRUE(batch.is_committed("subject_05"));
    EXPECT_FALSE(batch.is_committed("subject_02"));
    batch.commit(targets[1]);
    batch.finish();  // parts removed: the next resume reads the archive
  }
  {
    BatchArchive batch = BatchArchive::resume(archive, t, test_provenance());
    EXPECT_EQ(batch.committed(), (std::vector<std::string>{"subject_02", "subject_05", "subject_07"}));
    batch.commit(targets[3]);
    batch.commit(targets[4]);
    batch.finish();
  }
  EXPECT_EQ(file_bytes(archive), file_bytes(dir / "reference.h5"));
  fs::remove_all(dir);
}

TEST(BatchArchive, PartFileNamesSurviveAnyTargetName) {
  const fs::path archive = "/data/run.h5";
  EXPECT_EQ(target_part_path(archive, "subject_01-a").filename(), "subject_01-a.h5");
  EXPECT_EQ(target_part_path(archive, "../x y").filename(), "%2E%2E%2Fx%20y.h5");
  EXPECT_EQ(target_part_path(archive, "a").parent_path(), "/data/run.h5.parts/targets");
  const fs::path dir = test::fresh_temp_dir("batch_names");
  const TemplateRecord t = make_template(8);
  BatchArchive batch = BatchArchive::create(dir / "run.h5", t, test_provenance());
  batch.commit(make_target(t, "../x y", 1));
  batch.commit(make_target(t, "%2E", 2));
  EXPECT_EQ(BatchArchive::resume(dir / "run.h5", t, test_provenance()).committed(),
            (std::vector<std::string>{"%2E", "../x y"}));
  fs::remove_all(dir);
}

// A child process commits targets and re-assembles after each one, until the parent kills it
// with SIGKILL at some instant; whatever that instant, the archive opens, every row in it is
// a committed target with the right values, and resume recovers every committed part.
TEST(BatchArchive, SigkillAtAnyInstantLeavesAReadableArchive) {
  const TemplateRecord t = make_template(3000);
  const std::string python = python_with_h5py();
  const auto name_of = [](int k) {
    std::string name = "t" + std::to_string(1000 + k);
    return name;
  };
  // Kill after a growing number of milliseconds past the first assembly, to land in
  // different phases (part write, rename, assembly).
  for (const int delay_ms : {0, 11, 60}) {
    SCOPED_TRACE(delay_ms);
    const fs::path dir = test::fresh_temp_dir("batch_kill_" + std::to_string(delay_ms));
    const fs::path archive = dir / "run.h5";
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      try {
        BatchArchive batch = BatchArchive::create(archive, t, test_provenance());
        for (int k = 0; k < 1000; ++k) {
          batch.commit(k % 5 == 3 ? make_failed(name_of(k)) : make_target(t, name_of(k), k));
          batch.assemble();
        }
      } catch (...) {
        _exit(2);
      }
      _exit(0);
    }
    // Wait for the first target to be assembled, then let the child run a little longer.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (std::chrono::steady_clock::now() < deadline) {
      if (fs::exists(archive) && ArchiveReader(archive).targets().size() >= 1) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
    ASSERT_EQ(kill(child, SIGKILL), 0);
    int status = 0;
    ASSERT_EQ(waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFSIGNALED(status)) << "the child ended before it was killed";

    const ArchiveReader killed(archive);
    ASSERT_GE(killed.targets().size(), 1u);
    for (std::size_t row = 0; row < killed.targets().size(); ++row) {
      const int k = std::stoi(killed.targets()[row].name.substr(1)) - 1000;
      expect_same_target(killed.read_target(row),
                         k % 5 == 3 ? make_failed(name_of(k)) : make_target(t, name_of(k), k));
    }
    if (!python.empty()) {
      EXPECT_EQ(run_read_back(python, "--open " + archive.string()), 0);
    }

    // Resume: the parts are the committed truth; the archive lags them by at most one assembly.
    BatchArchive resumed = BatchArchive::resume(archive, t, test_provenance());
    const std::vector<std::string> committed = resumed.committed();
    ASSERT_GE(committed.size(), killed.targets().size());
    ASSERT_LE(committed.size(), killed.targets().size() + 1);
    for (std::size_t i = 0; i < committed.size(); ++i) EXPECT_EQ(committed[i], name_of(static_cast<int>(i)));
    resumed.finish();
    const ArchiveContents done = read_archive(archive);
    ASSERT_EQ(done.targets.size(), committed.size());
    for (std::size_t i = 0; i < committed.size(); ++i) {
      const int k = static_cast<int>(i);
      expect_same_target(done.targets[i],
                         k % 5 == 3 ? make_failed(name_of(k)) : make_target(t, name_of(k), k));
    }
    fs::remove_all(dir);
  }
}

TEST(Merge, TwoShardsGiveTheDatasetsOfOneRun) {
  const fs::path dir = test::fresh_temp_dir("merge");
  const TemplateRecord t = make_template(25);
  const std::vector<TargetRecord> targets = make_targets(t);
  write_archive(dir / "single.h5", t, test_provenance(), targets);
  // Interleaved names: shard 1 has rows 0, 2, 4 of the single run, shard 2 rows 1, 3.
  const std::vector<TargetRecord> sorted = sorted_by_name(targets);
  write_archive(dir / "shard1.h5", t, test_provenance(), {sorted[4], sorted[0], sorted[2]});
  write_archive(dir / "shard2.h5", t, test_provenance(), {sorted[3], sorted[1]});
  merge_archives({dir / "shard2.h5", dir / "shard1.h5"}, dir / "merged.h5");

  const ArchiveContents single = read_archive(dir / "single.h5");
  const ArchiveContents merged = read_archive(dir / "merged.h5");
  EXPECT_TRUE(same_template(single.template_record, merged.template_record));
  ASSERT_EQ(merged.targets.size(), single.targets.size());
  for (std::size_t i = 0; i < single.targets.size(); ++i)
    expect_same_target(merged.targets[i], single.targets[i]);
  EXPECT_EQ(file_bytes(dir / "merged.h5"), file_bytes(dir / "single.h5"));
  // Same rows, same grids; only the archive file named in the sidecar differs.
  std::string single_xdmf = file_bytes(xdmf_path(dir / "single.h5"));
  for (std::size_t at = single_xdmf.find("single.h5"); at != std::string::npos;
       at = single_xdmf.find("single.h5"))
    single_xdmf.replace(at, 6, "merged");
  EXPECT_EQ(file_bytes(xdmf_path(dir / "merged.h5")), single_xdmf);
  const std::string python = python_with_h5py();
  if (!python.empty()) {
    EXPECT_EQ(run_read_back(python,
                            "--compare " + (dir / "single.h5").string() + " " + (dir / "merged.h5").string()),
              0);
  }
  fs::remove_all(dir);
}

TEST(Merge, RefusesOverlappingOrForeignShards) {
  const fs::path dir = test::fresh_temp_dir("merge_refuse");
  const TemplateRecord t = make_template(10);
  const std::vector<TargetRecord> targets = make_targets(t);
  write_archive(dir / "a.h5", t, test_provenance(), {targets[0], targets[1]});
  write_archive(dir / "b.h5", t, test_provenance(), {targets[1], targets[2]});
  try {
    merge_archives({dir / "a.h5", dir / "b.h5"}, dir / "out.h5");
    ADD_FAILURE() << "overlapping shards were merged";
  } catch (const ArchiveError& e) {
    EXPECT_NE(std::string(e.what()).find("subject_02"), std::string::npos) << e.what();
  }
  TemplateRecord other = t;
  other.anchor_vertices[0] = 1;
  write_archive(dir / "c.h5", other, test_provenance(), {targets[2]});
  EXPECT_THROW(merge_archives({dir / "a.h5", dir / "c.h5"}, dir / "out.h5"), ArchiveError);
  write_archive(dir / "d.h5", t, current_provenance("{}"), {targets[2]});
  EXPECT_THROW(merge_archives({dir / "a.h5", dir / "d.h5"}, dir / "out.h5"), ArchiveError);
  EXPECT_THROW(merge_archives({}, dir / "out.h5"), ArchiveError);
  EXPECT_FALSE(fs::exists(dir / "out.h5"));
  fs::remove_all(dir);
}

TEST(Xdmf, OneTimeStepPerOkTargetReferencingItsRows) {
  const fs::path dir = test::fresh_temp_dir("xdmf");
  const TemplateRecord t = make_template(12);
  write_archive(dir / "run.h5", t, test_provenance(), make_targets(t));
  const std::string xml = file_bytes(dir / "run.xdmf");
  // Four ok targets (rows 0, 1, 2, 4), the failed row 3 left out.
  std::size_t grids = 0;
  for (std::size_t at = xml.find("GridType=\"Uniform\""); at != std::string::npos;
       at = xml.find("GridType=\"Uniform\"", at + 1))
    ++grids;
  EXPECT_EQ(grids, 4u);
  EXPECT_EQ(xml.find("subject_05"), std::string::npos);
  EXPECT_NE(xml.find("<Grid Name=\"Subject 10 (scan)\""), std::string::npos);
  EXPECT_NE(xml.find("<Time Value=\"4\"/>"), std::string::npos);
  EXPECT_EQ(xml.find("<Time Value=\"3\"/>"), std::string::npos);
  EXPECT_NE(xml.find(">4 0 0 1 1 1 1 12 3</DataItem>"), std::string::npos);  // row 4's hyperslab
  EXPECT_NE(xml.find("run.h5:/template/faces"), std::string::npos);
  EXPECT_NE(xdmf_text({"a&b<.h5", 1, 3, 1, {"x\"y"}, {0}}).find("<Grid Name=\"x&quot;y\""),
            std::string::npos);
  if (std::system("xmllint --version > /dev/null 2>&1") == 0) {
    EXPECT_EQ(std::system(("xmllint --noout " + (dir / "run.xdmf").string()).c_str()), 0);
  }
  fs::remove_all(dir);
}

TEST(ReadBack, H5pyReadsEveryValueWithoutXparam) {
  const std::string python = python_with_h5py();
  if (python.empty()) GTEST_SKIP() << "no python3 with h5py";
  const fs::path dir = test::fresh_temp_dir("read_back");
  const TemplateRecord t = make_template(12);
  const std::vector<TargetRecord> targets = make_targets(t);
  write_archive(dir / "run.h5", t, test_provenance(), targets);
  std::ofstream(dir / "expected.json") << expectation(t, test_provenance(), targets).dump();
  EXPECT_EQ(run_read_back(python, (dir / "run.h5").string() + " " + (dir / "expected.json").string()), 0);

  // The checker must notice a wrong value (here: one remesh coordinate of one subject).
  std::vector<TargetRecord> altered = targets;
  altered[4].remesh_vertices(5, 1) += 1e-12;
  std::ofstream(dir / "altered.json") << expectation(t, test_provenance(), altered).dump();
  EXPECT_NE(run_read_back(python,
                          (dir / "run.h5").string() + " " + (dir / "altered.json").string() + " 2>/dev/null"),
            0);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace xparam

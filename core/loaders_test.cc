// Every loader rejects each kind of bad input with a message that names the file and the key.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <bitset>
#include <filesystem>
#include <functional>

#include "core/camera_yaml.h"
#include "core/codes/artkplus_id_code.h"
#include "core/codes/runetag_cyclic_code.h"
#include "core/file_bytes.h"
#include "core/marker_yaml.h"
#include "core/test_files.h"
#include "core/yaml_reader.h"

namespace markerbench {
namespace {

using ::testing::HasSubstr;

const char kGoodCamera[] = R"(image_width: 640
image_height: 480
camera_name: test
camera_matrix: {rows: 3, cols: 3, data: [600, 0, 319.5, 0, 600, 239.5, 0, 0, 1]}
distortion_model: plumb_bob
distortion_coefficients: {rows: 1, cols: 5, data: [-0.1, 0.01, 0, 0, 0]}
rectification_matrix: {rows: 3, cols: 3, data: [1, 0, 0, 0, 1, 0, 0, 0, 1]}
projection_matrix: {rows: 3, cols: 4, data: [600, 0, 319.5, 0, 0, 600, 239.5, 0, 0, 0, 1, 0]}
)";

const char kGoodCirclesA[] = R"(kind: circles_a
disks:
  - {center: [0.0, 0.0], radius: 0.03, color: [1.0, 0.0, 0.0]}
  - {center: [0.08, 0.0], radius: 0.03, color: [0.0, 0.0, 1.0]}
background: [1.0, 1.0, 1.0]
)";

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

// Loads `text` with `load` and returns the ConfigError message ("" when it loaded).
template <typename Load>
std::string ErrorOf(const std::string& name, const std::string& text, Load load) {
  const std::string path = WriteTestFile(name, text);
  try {
    load(path);
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr(path)) << "the message must name the file";
    return e.what();
  }
  return "";
}

std::string CameraError(const std::string& text) {
  return ErrorOf("camera.yaml", text, LoadCameraYaml);
}
std::string MarkerError(const std::string& text) {
  return ErrorOf("marker.yaml", text, LoadMarkerYaml);
}

TEST(CameraYaml, LoadsRosCameraInfo) {
  const Camera camera = LoadCameraYaml(WriteTestFile("camera.yaml", kGoodCamera));
  EXPECT_EQ(camera.width, 640);
  EXPECT_EQ(camera.fx, 600.0);
  EXPECT_EQ(camera.cy, 239.5);
  EXPECT_EQ(camera.distortion[0], -0.1);
  EXPECT_EQ(camera.name, "test");
}

TEST(CameraYaml, UnknownKey) {
  EXPECT_THAT(CameraError(std::string(kGoodCamera) + "focal: 3\n"),
              HasSubstr("key 'focal': unknown key"));
}

TEST(CameraYaml, MissingKey) {
  EXPECT_THAT(CameraError(Replace(kGoodCamera, "image_height: 480\n", "")),
              HasSubstr("key 'image_height': missing"));
}

TEST(CameraYaml, WrongType) {
  const std::string message = CameraError(Replace(kGoodCamera, "640", "wide"));
  EXPECT_THAT(message, HasSubstr("key 'image_width': expected an integer"));
  EXPECT_THAT(message, HasSubstr(":1:")) << "the message must give the line";
}

TEST(CameraYaml, OutOfRange) {
  EXPECT_THAT(CameraError(Replace(kGoodCamera, "[600, 0, 319.5", "[-600, 0, 319.5")),
              HasSubstr("key 'camera_matrix'"));
  EXPECT_THAT(CameraError(Replace(kGoodCamera, "image_width: 640", "image_width: 0")),
              HasSubstr("key 'image_width': expected an integer in [1"));
}

// A camera that cannot be drawn is the camera file's error, named there, never blamed on the
// scenario's poses (fx = 1e300 once failed as "poses.distance_m: markers in view").
TEST(CameraYaml, ImpossibleCamerasNameTheirKey) {
  const std::string focal =
      "key 'camera_matrix': expected focal lengths data[0] (fx) and "
      "data[4] (fy) in [0.001, 1e7] px";
  EXPECT_THAT(CameraError(Replace(kGoodCamera, "[600, 0, 319.5", "[1e300, 0, 319.5")),
              HasSubstr(focal));
  EXPECT_THAT(CameraError(Replace(kGoodCamera,
                                  "[600, 0, 319.5, 0, 600",
                                  "[1e-300, 0, 319.5, 0, "
                                  "1e-300")),
              HasSubstr(focal));
  EXPECT_THAT(CameraError(Replace(kGoodCamera, "[600, 0, 319.5", "[600, 0, 1e300")),
              HasSubstr("key 'camera_matrix': expected a principal point data[2] (cx), data[5] "
                        "(cy) inside the image"));
  EXPECT_THAT(CameraError(Replace(kGoodCamera, "[-0.1, 0.01, 0, 0, 0]", "[1e6, 0, 0, 0, 0]")),
              HasSubstr("key 'distortion_coefficients': expected |k1|, |k2|, |k3| <= 100"));
  // k1 = -1 folds the image back on itself before its corners (r_d peaks at r = 1/√3).
  EXPECT_THAT(CameraError(Replace(Replace(kGoodCamera, "[-0.1, 0.01, 0, 0, 0]", "[-1, 0, 0, 0, 0]"),
                                  "[600, 0, 319.5, 0, 600",
                                  "[300, 0, 319.5, 0, 300")),
              HasSubstr("key 'distortion_coefficients': expected distortion that is one to one"));
  EXPECT_THAT(CameraError(Replace(Replace(kGoodCamera, "image_width: 640", "image_width: 100000"),
                                  "image_height: 480",
                                  "image_height: 100000")),
              HasSubstr("key 'image_height': expected an image of at most 67108864 pixels"));
}

TEST(CameraYaml, WrongMatrixShape) {
  EXPECT_THAT(CameraError(Replace(kGoodCamera, "data: [-0.1, 0.01, 0, 0, 0]", "data: [-0.1]")),
              HasSubstr("key 'distortion_coefficients.data'"));
}

TEST(CameraYaml, UnsupportedDistortionModel) {
  EXPECT_THAT(CameraError(Replace(kGoodCamera, "plumb_bob", "equidistant")),
              HasSubstr("key 'distortion_model': expected 'plumb_bob'"));
}

TEST(CameraYaml, MissingFileAndBadYaml) {
  try {
    LoadCameraYaml("/nonexistent/camera.yaml");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("/nonexistent/camera.yaml: cannot open"));
  }
  EXPECT_THAT(CameraError("image_width: [1, 2\n"), HasSubstr("not valid YAML"));
}

TEST(YamlFiles, DuplicateKeysNameBothLines) {
  // yaml-cpp would keep the first image_width silently.
  EXPECT_THAT(CameraError(std::string(kGoodCamera) + "image_width: 1280\n"),
              HasSubstr(":9: key 'image_width' is given twice, first on line 1"));
  EXPECT_THAT(MarkerError(Replace(kGoodCirclesA, "radius: 0.03,", "radius: 0.03, radius: 0.04,")),
              HasSubstr(":3: key 'radius' is given twice, first on line 3"));
}

TEST(YamlFiles, ComplexKeysAreRefused) {
  EXPECT_THAT(CameraError(std::string(kGoodCamera) + "? [a, b]\n: 1\n"),
              HasSubstr(":9: a key must be a plain name, got [a, b]"));
  EXPECT_THAT(MarkerError(std::string(kGoodCirclesA) + "? {a: 1}\n: 1\n"),
              HasSubstr("a key must be a plain name, got a mapping"));
}

// An integer may be written as any whole number within an int (1e+05: how NumberText writes
// 100000); a fraction, or a whole number beyond an int, is not one.
TEST(YamlFiles, IntegersAreWholeNumbersInAnyNotation) {
  const YamlMap map(YAML::Load("{plain: 42, exponent: 1e+05, short: 1e5, point: 7.0, hex: 0x10,"
                               " fraction: 2.5, huge: 1e10, word: ten}"),
                    "numbers.yaml",
                    "");
  EXPECT_EQ(map.Get<int>("plain"), 42);
  EXPECT_EQ(map.Get<int>("exponent"), 100000);
  EXPECT_EQ(map.Get<int>("short"), 100000);
  EXPECT_EQ(map.Get<int>("point"), 7);
  EXPECT_EQ(map.Get<int>("hex"), 16);
  for (const char* key : {"fraction", "huge", "word"}) {
    try {
      map.Get<int>(key);
      ADD_FAILURE() << key << " was read as an integer";
    } catch (const ConfigError& e) {
      EXPECT_THAT(e.what(), HasSubstr(std::string("key '") + key + "': expected an integer"));
    }
  }
}

TEST(YamlFiles, AliasesThatExpandTooFarAreRefused) {
  // Nine levels of ten aliases each: a billion values from ten lines.
  std::string text = "l0: &l0 [x, x, x, x, x, x, x, x, x, x]\n";
  for (int level = 1; level <= 9; ++level) {
    const std::string name = "l" + std::to_string(level);
    const std::string alias = "*l" + std::to_string(level - 1);
    text += name + ": &" + name + " [" + alias;
    for (int i = 1; i < 10; ++i) text += ", " + alias;
    text += "]\n";
  }
  EXPECT_THAT(CameraError(text), HasSubstr("more than 1000000 values"));
}

TEST(YamlFiles, OnlyRegularFilesAreRead) {
  const std::filesystem::path folder = WriteTestFile("folder.yaml", "") + ".d";
  std::filesystem::create_directories(folder);
  for (const auto& [path, kind] : std::vector<std::pair<std::string, std::string>>{
           {folder.string(), "a directory"}, {"/dev/null", "a character device"}}) {
    try {
      LoadCameraYaml(path);
      ADD_FAILURE() << path;
    } catch (const ConfigError& e) {
      EXPECT_THAT(e.what(), HasSubstr(path + ": expected a regular file, got " + kind));
    }
  }
  // A FIFO would block the reader until someone writes to it.
  const std::string fifo = WriteTestFile("fifo.yaml", "") + ".fifo";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  try {
    LoadMarkerYaml(fifo);
    ADD_FAILURE() << fifo;
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr(fifo + ": expected a regular file, got a FIFO"));
  }
}

// Overrides change values, nested maps and list items, create missing keys, and errors about
// an overridden value name the override instead of a line of the file.
TEST(YamlFiles, OverridesApplyBeforeReadingAndNameThemselvesInErrors) {
  const std::string path =
      WriteTestFile("overrides.yaml", "a: 1\nlist:\n  - {x: 1}\n  - {x: 2}\nnested: {b: text}\n");
  const YamlMap map = YamlMap::LoadFile(
      path, {"a=5", "list[1].x=7", "nested.c=[1, 2]", "fresh.deep=0.5", "nested.b={k: v}"});
  EXPECT_EQ(map.Get<int>("a"), 5);
  EXPECT_EQ(map.GetMapList("list")[0].Get<int>("x"), 1);
  EXPECT_EQ(map.GetMapList("list")[1].Get<int>("x"), 7);
  EXPECT_EQ(map.GetMap("nested").Get<std::vector<int>>("c"), (std::vector<int>{1, 2}));
  EXPECT_EQ(map.GetMap("nested").GetMap("b").Get<std::string>("k"), "v");
  EXPECT_DOUBLE_EQ(map.GetMap("fresh").Get<double>("deep"), 0.5);
  // The last override of a key wins.
  EXPECT_EQ(YamlMap::LoadFile(path, {"a=5", "a=6"}).Get<int>("a"), 6);

  const auto error_of = [&](const std::vector<std::string>& overrides,
                            const std::function<void(const YamlMap&)>& read) {
    try {
      read(YamlMap::LoadFile(path, overrides));
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const auto read_a = [](const YamlMap& m) { m.GetDouble("a", 2.0, 3.0); };
  EXPECT_EQ(error_of({"a=9"}, read_a),
            path + " (--set a=9): key 'a': expected a number in [2, 3], got '9'");
  EXPECT_EQ(error_of({}, read_a), path + ":1: key 'a': expected a number in [2, 3], got '1'");
  const auto read_list = [](const YamlMap& m) { m.GetMapList("list")[1].Get<int>("x"); };
  EXPECT_THAT(error_of({"list[1].x=seven"}, read_list),
              HasSubstr("(--set list[1].x=seven): key 'list[1].x': expected an integer"));
  const auto strict = [](const YamlMap& m) {
    m.Get<int>("a");
    m.GetMapList("list");
    const YamlMap nested = m.GetMap("nested");
    nested.Get<std::string>("b");
    nested.RejectUnknownKeys();
  };
  EXPECT_THAT(error_of({"nested.typo=1"}, strict),
              HasSubstr(path + " (--set nested.typo=1): key 'nested.typo': unknown key"));
  for (const auto& [bad, message] : std::vector<std::pair<std::string, std::string>>{
           {"a", "expected KEY=VALUE"},
           {"=1", "an empty key"},
           {"a..b=1", "an empty key"},
           {"a.=1", "an empty key"},
           {"list[x].x=1", "a list index [N]"},
           {"list[2].x=1", "'list' has no item 2"},
           {"a.b=1", "'a' is not a mapping"},
           {"nested[0]=1", "'nested' has no item 0"},
           {"a=", "expected a value after '='"},
           {"a=[1, 2", "the value is not valid YAML"}}) {
    EXPECT_THAT(error_of({bad}, read_a), HasSubstr("--set " + bad + ": " + message)) << bad;
  }
}

TEST(MarkerYaml, ScaleMultipliesEveryLength) {
  const MarkerSpec plain = LoadMarkerYaml(WriteTestFile("circles_a.yaml", kGoodCirclesA));
  const MarkerSpec scaled =
      LoadMarkerYaml(WriteTestFile("circles_a.yaml", std::string(kGoodCirclesA) + "scale: 2.5\n"));
  EXPECT_EQ(scaled.name, plain.name);
  ASSERT_EQ(scaled.keypoints.size(), plain.keypoints.size());
  EXPECT_EQ(scaled.keypoints[1], 2.5 * plain.keypoints[1]);
  EXPECT_DOUBLE_EQ(scaled.circles[1].radius_m, 2.5 * plain.circles[1].radius_m);
  EXPECT_THAT(MarkerError(std::string(kGoodCirclesA) + "scale: 0\n"), HasSubstr("key 'scale'"));
}

TEST(MarkerYaml, LoadsCirclesA) {
  const MarkerSpec spec = LoadMarkerYaml(WriteTestFile("circles_a.yaml", kGoodCirclesA));
  EXPECT_EQ(spec.kind, MarkerKind::kCirclesA);
  EXPECT_EQ(spec.name, "circles_a");
  ASSERT_EQ(spec.keypoints.size(), 2u);
  EXPECT_EQ(spec.keypoints[1], Eigen::Vector2d(0.08, 0.0));
  EXPECT_TRUE(spec.HasColor());
  const Eigen::AlignedBox2d ink = spec.InkBounds();
  EXPECT_NEAR(ink.min().x(), -0.03, 1e-12);
  EXPECT_NEAR(ink.max().x(), 0.11, 1e-12);
  EXPECT_NEAR(ink.max().y(), 0.03, 1e-12);
}

TEST(MarkerYaml, UnknownKey) {
  EXPECT_THAT(
      MarkerError(Replace(
          kGoodCirclesA, "radius: 0.03, color: [1.0", "radius: 0.03, label: m0, color: [1.0")),
      HasSubstr("key 'disks[0].label': unknown key"));
}

TEST(MarkerYaml, MissingKey) {
  EXPECT_THAT(MarkerError(Replace(kGoodCirclesA, "kind: circles_a\n", "")),
              HasSubstr("key 'kind': missing"));
}

TEST(MarkerYaml, WrongType) {
  EXPECT_THAT(
      MarkerError(Replace(kGoodCirclesA, "radius: 0.03, color: [1.0", "radius: big, color: [1.0")),
      HasSubstr("key 'disks[0].radius': expected a number"));
}

TEST(MarkerYaml, OutOfRange) {
  EXPECT_THAT(MarkerError(Replace(kGoodCirclesA, "[0.0, 0.0, 1.0]", "[0.0, 0.0, 2.0]")),
              HasSubstr("key 'disks[1].color': expected an RGB colour"));
  EXPECT_THAT(MarkerError(Replace(
                  kGoodCirclesA, "radius: 0.03, color: [1.0", "radius: -0.03, color: [1.0")),
              HasSubstr("key 'disks[0].radius': expected a number in [1e-06, 10000]"));
  // Sizes the renderer cannot draw in doubles are refused at load, never looped over.
  EXPECT_THAT(MarkerError(Replace(
                  kGoodCirclesA, "radius: 0.03, color: [1.0", "radius: 1e300, color: [1.0")),
              HasSubstr("key 'disks[0].radius': expected a number in [1e-06, 10000]"));
  EXPECT_THAT(MarkerError(Replace(kGoodCirclesA, "[0.08, 0.0]", "[1e300, 0.0]")),
              HasSubstr("key 'disks[1].center': expected [x, y] in metres, each in [-10000, "
                        "10000]"));
}

TEST(MarkerYaml, BrokenGeometry) {
  EXPECT_THAT(MarkerError(Replace(kGoodCirclesA, "[0.08, 0.0]", "[0.05, 0.0]")),
              HasSubstr("two separate disks"));
  const std::string circles_c = ReadFileBytes("scenarios/markers/circles_c.yaml");
  EXPECT_THAT(
      MarkerError(Replace(
          circles_c, "{center: [0.0, 0.0], radius: 0.03", "{center: [0.001, 0.0], radius: 0.03")),
      HasSubstr("key 'disks': expected an inner circle concentric"));
}

// Markers (a)-(d) may sit anywhere in their file's frame: m0 and m1 follow the disks.
TEST(MarkerYaml, CircleMarkersKeepTheFileFrame) {
  const MarkerSpec spec = LoadMarkerYaml(WriteTestFile(
      "moved.yaml",
      Replace(
          Replace(kGoodCirclesA, "[0.0, 0.0]", "[0.02, 0.01]"), "[0.08, 0.0]", "[0.02, 0.09]")));
  ASSERT_EQ(spec.keypoints.size(), 2u);
  EXPECT_EQ(spec.keypoints[0], Eigen::Vector2d(0.02, 0.01));
  EXPECT_EQ(spec.keypoints[1], Eigen::Vector2d(0.02, 0.09));
  EXPECT_EQ(spec.circles[1].center, Eigen::Vector2d(0.02, 0.09));
}

TEST(MarkerYaml, UnknownKindNamesTheKinds) {
  EXPECT_THAT(MarkerError("kind: hexagon\n"), HasSubstr("key 'kind': expected one of circles_a"));
}

TEST(MarkerYaml, AprilTagIdOutOfRange) {
  EXPECT_THAT(MarkerError("kind: apriltag\nfamily: tag36h11\nid: 587\nsize_m: 0.1\n"),
              HasSubstr("key 'id': expected an id in [0, 586]"));
  EXPECT_THAT(MarkerError("kind: apriltag\nfamily: tag99\nid: 0\nsize_m: 0.1\n"),
              HasSubstr("key 'family': expected one of the libapriltag families"));
}

TEST(MarkerYaml, ArucoDictionaryAndGrid) {
  const MarkerSpec spec = LoadMarkerYaml(
      WriteTestFile("aruco.yaml", "kind: aruco\ndictionary: DICT_6X6_250\nid: 3\nsize_m: 0.08\n"));
  ASSERT_EQ(spec.layers.size(), 1u);
  const auto& grid = std::get<GridShape>(spec.layers[0].shape);
  EXPECT_EQ(grid.rows, 8);
  EXPECT_NEAR(spec.InkBounds().sizes().x(), 0.08, 1e-12);
  ASSERT_EQ(spec.keypoints.size(), 4u);
  EXPECT_EQ(spec.keypoints[0], Eigen::Vector2d(-0.04, 0.04));  // top-left
  EXPECT_THAT(MarkerError("kind: aruco\ndictionary: DICT_6X6_250\nid: 250\nsize_m: 0.1\n"),
              HasSubstr("key 'id': expected an id in [0, 249]"));
}

TEST(MarkerYaml, AprilTagBlackSquareSpansSize) {
  const MarkerSpec spec = LoadMarkerYaml(
      WriteTestFile("tag.yaml", "kind: apriltag\nfamily: tag36h11\nid: 0\nsize_m: 0.1\n"));
  const auto& grid = std::get<GridShape>(spec.layers[0].shape);
  EXPECT_EQ(grid.rows, 10);
  EXPECT_NEAR(grid.cell_m, 0.0125, 1e-15);
  EXPECT_FALSE(grid.Ink(0, 0));  // white ring
  EXPECT_TRUE(grid.Ink(1, 1));   // black border
  EXPECT_NEAR(spec.InkBounds().sizes().x(), 0.1, 1e-12);
}

TEST(MarkerYaml, BitGridValidatesData) {
  const std::string good =
      "kind: bit_grid\nsize_m: 0.1\nborder_cells: 1\nquiet_zone_cells: 1\n"
      "data: ['#.', '.#']\n";
  const MarkerSpec spec = LoadMarkerYaml(WriteTestFile("grid.yaml", good));
  const auto& grid = std::get<GridShape>(spec.layers[0].shape);
  EXPECT_EQ(grid.rows, 6);
  EXPECT_TRUE(grid.Ink(2, 2));
  EXPECT_FALSE(grid.Ink(2, 3));
  EXPECT_NEAR(spec.InkBounds().sizes().x(), 0.1, 1e-12);
  EXPECT_THAT(MarkerError(Replace(good, "'.#'", "'.x'")), HasSubstr("key 'data'"));
}

TEST(MarkerYaml, ArtkPlusGridHoldsTheCodewordInsideItsBorder) {
  const std::string good =
      "kind: artkplus\nmode: bch\nid: 100\nborder_fraction: 0.25\nsize_m: 0.12\n";
  const MarkerSpec spec = LoadMarkerYaml(WriteTestFile("artk.yaml", good));
  EXPECT_EQ(spec.kind, MarkerKind::kArtkPlus);
  EXPECT_EQ(spec.family, "bch");
  EXPECT_EQ(spec.id, 100);
  EXPECT_EQ(spec.border_fraction, 0.25);
  const auto& grid = std::get<GridShape>(spec.layers[0].shape);
  ASSERT_EQ(grid.rows, 14);  // 1 quiet + 3 border + 6 data + 3 border + 1 quiet
  EXPECT_NEAR(grid.cell_m, 0.01, 1e-15);
  EXPECT_FALSE(grid.Ink(0, 5));  // quiet zone
  EXPECT_TRUE(grid.Ink(3, 5));   // border
  const uint64_t word = ArtkPlusEncode(ArtkPlusIdMode::kBch, 100);
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 6; ++c) {
      const bool white = (word >> (35 - (6 * r + c)) & 1) != 0;
      EXPECT_EQ(grid.Ink(4 + r, 4 + c), !white) << "cell " << r << ", " << c;
    }
  }
  EXPECT_NEAR(spec.InkBounds().sizes().x(), 0.12, 1e-12);
  const MarkerSpec thin = LoadMarkerYaml(
      WriteTestFile("thin.yaml", Replace(Replace(good, "0.25", "0.125"), "bch", "simple")));
  EXPECT_EQ(std::get<GridShape>(thin.layers[0].shape).rows, 10);
  EXPECT_NEAR(thin.InkBounds().sizes().x(), 0.12, 1e-12);
}

TEST(MarkerYaml, ArtkPlusErrorsNameTheKey) {
  const std::string good =
      "kind: artkplus\nmode: simple\nid: 511\nborder_fraction: 0.25\nsize_m: 0.1\n";
  EXPECT_THAT(MarkerError(Replace(good, "511", "512")),
              HasSubstr("key 'id': expected an id in [0, 511] for mode simple"));
  EXPECT_THAT(MarkerError(Replace(good, "simple", "bhc")),
              HasSubstr("key 'mode': expected an id mode: bch or simple"));
  EXPECT_THAT(MarkerError(Replace(good, "0.25", "0.2")),
              HasSubstr("key 'border_fraction': expected a border fraction of 0.25 or 0.125"));
  EXPECT_THAT(MarkerError(Replace(good, "mode: simple\n", "")), HasSubstr("key 'mode'"));
}

TEST(MarkerYaml, RuneTagDotsFollowTheCodeword) {
  const MarkerSpec spec =
      LoadMarkerYaml(WriteTestFile("rune.yaml", "kind: runetag\nid: 23\nradius_m: 0.05\n"));
  EXPECT_EQ(spec.kind, MarkerKind::kRuneTag);
  EXPECT_EQ(spec.size_m, 0.1);
  size_t dots = 0;
  for (uint8_t symbol : RuneCodeword(23)) dots += std::bitset<3>(symbol).count();
  ASSERT_EQ(spec.keypoints.size(), dots);
  ASSERT_EQ(spec.layers.size(), dots);
  // Sector 0 lies on +x; its first dot is on the innermost ring present.
  const uint8_t s0 = RuneCodeword(23)[0];
  const double first_ring = (s0 & 4) ? 4.0 / 6.0 : (s0 & 2) ? 5.0 / 6.0 : 1.0;
  EXPECT_NEAR(spec.keypoints[0].x(), first_ring * 0.05, 1e-12);
  EXPECT_NEAR(spec.keypoints[0].y(), 0.0, 1e-12);
  EXPECT_NEAR(std::get<DiskShape>(spec.layers[0].shape).radius, first_ring * 0.05 / 17.8, 1e-12);
  EXPECT_THAT(MarkerError("kind: runetag\nid: 9\nradius_m: 0.05\n"),
              HasSubstr("key 'id': expected an id of the original RUNETag code list"));
  EXPECT_THAT(MarkerError("kind: runetag\nid: 8\n"), HasSubstr("key 'radius_m'"));
}

TEST(MarkerYaml, DotRingsValidatesPattern) {
  const std::string good =
      "kind: dot_rings\nradius_m: 0.05\nring_radii: [0.5, 1.0]\nsectors: 4\n"
      "dot_radius_ratio: 10\npattern: ['1010', '0111']\n";
  const MarkerSpec spec = LoadMarkerYaml(WriteTestFile("rings.yaml", good));
  EXPECT_EQ(spec.keypoints.size(), 5u);
  EXPECT_THAT(MarkerError(Replace(good, "'0111'", "'011'")), HasSubstr("key 'pattern'"));
  EXPECT_THAT(MarkerError(Replace(good, "[0.5, 1.0]", "[0.5, 1.5]")),
              HasSubstr("key 'ring_radii'"));
}

}  // namespace
}  // namespace markerbench

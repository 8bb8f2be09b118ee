#include "core/option_fields.h"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/config_error.h"
#include "core/yaml_reader.h"

namespace markerbench {
namespace {

enum class Shape { kRound, kSquare, kStar };

// An options struct of every kind of field, with its list of keys.
struct ExampleOptions {
  double scale_px = 2.5;
  int passes = 3;
  bool refine = true;
  std::string family = "tag36h11";
  Shape shape = Shape::kRound;
};

template <typename Options, typename Fields>
void VisitExampleFields(Options& o, Fields&& fields) {
  fields("scale_px", o.scale_px);
  fields("passes", o.passes);
  fields("refine", o.refine);
  fields("family", o.family);
  fields.Choice("shape", o.shape, {{Shape::kRound, "round"}, {Shape::kSquare, "square"}});
}

ExampleOptions ReadExample(const std::string& yaml) {
  const YamlMap map(YAML::Load(yaml), "example.yaml", "");
  ExampleOptions o;
  VisitExampleFields(o, FieldReader(map));
  map.RejectUnknownKeys();
  return o;
}

std::vector<std::pair<std::string, std::string>> Written(const ExampleOptions& o) {
  FieldWriter fields;
  VisitExampleFields(o, fields);
  return fields.parameters;
}

std::string ReadError(const std::string& yaml) {
  try {
    ReadExample(yaml);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(OptionFields, WritesEveryKeyInTheListsOrder) {
  const std::vector<std::pair<std::string, std::string>> expected = {{"scale_px", "2.5"},
                                                                     {"passes", "3"},
                                                                     {"refine", "true"},
                                                                     {"family", "tag36h11"},
                                                                     {"shape", "round"}};
  EXPECT_EQ(Written(ExampleOptions()), expected);
}

TEST(OptionFields, ReadsEachKeyIntoItsField) {
  const ExampleOptions o =
      ReadExample("{scale_px: 0.1, passes: 7, refine: false, family: tag25h9, shape: square}");
  EXPECT_EQ(o.scale_px, 0.1);
  EXPECT_EQ(o.passes, 7);
  EXPECT_FALSE(o.refine);
  EXPECT_EQ(o.family, "tag25h9");
  EXPECT_EQ(o.shape, Shape::kSquare);
}

TEST(OptionFields, AbsentKeysKeepTheirValues) {
  const ExampleOptions o = ReadExample("{passes: 1}");
  EXPECT_EQ(o.passes, 1);
  EXPECT_EQ(Written(o)[0].second, "2.5");
  EXPECT_EQ(o.shape, Shape::kRound);
}

TEST(OptionFields, WrittenFieldsReadBackToTheSameOptions) {
  ExampleOptions changed;
  changed.scale_px = 1.0 / 3.0;  // no short decimal: NumberText must keep every bit
  changed.passes = 100000;
  changed.refine = false;
  changed.shape = Shape::kSquare;
  YAML::Node node(YAML::NodeType::Map);
  for (const auto& [key, text] : Written(changed)) node[key] = YAML::Load(text);
  const ExampleOptions read = ReadExample(YAML::Dump(node));
  EXPECT_EQ(read.scale_px, changed.scale_px);
  EXPECT_EQ(read.passes, changed.passes);
  EXPECT_EQ(Written(read), Written(changed));
}

TEST(OptionFields, BadValuesFailNamingTheKey) {
  EXPECT_NE(ReadError("{shape: star}").find("'shape': expected round or square"), std::string::npos)
      << ReadError("{shape: star}");
  EXPECT_NE(ReadError("{passes: many}").find("passes"), std::string::npos);
  EXPECT_NE(ReadError("{refine: 2}").find("refine"), std::string::npos);
  EXPECT_NE(ReadError("{shapes: round}").find("shapes"), std::string::npos);  // unknown key
}

TEST(OptionFields, AValueWithoutANameIsTheListsError) {
  ExampleOptions o;
  o.shape = Shape::kStar;
  EXPECT_THROW(Written(o), std::logic_error);
}

}  // namespace
}  // namespace markerbench

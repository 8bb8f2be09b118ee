// One list of an options struct's keys for both directions: reading the options from YAML and
// writing them out as a run's parameters (its manifest, `markerbench list trackers`). The list is
// a template over the visitor,
//   template <typename Options, typename Fields> void VisitFields(Options& o, Fields& fields);
// calling fields(key, o.member) for a plain value (double, int, bool, std::string) and
// fields.Choice(key, o.member, names) for a value written as one of a few names. A key is then
// written as the field it is read into, by construction.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/number_text.h"
#include "core/yaml_reader.h"

namespace markerbench {

// A value of a field that is written as a name ("auto", "rpp", "edges").
template <typename Value>
struct NamedValue {
  Value value;
  const char* name;
};

// Reads each key present in the map into its field; absent keys keep the field's value. A
// choice's other text fails naming the key and its names ("rpp or classic").
class FieldReader {
 public:
  explicit FieldReader(const YamlMap& map) : map_(map) {}

  template <typename T>
  void operator()(const char* key, T& field) const {
    field = map_.GetOr<T>(key, field);
  }

  template <typename Value, std::size_t N>
  void Choice(const char* key, Value& field, const NamedValue<Value> (&names)[N]) const {
    if (!map_.Has(key)) return;
    const std::string text = map_.Get<std::string>(key);
    std::string expected;
    for (std::size_t i = 0; i < N; ++i) {
      if (text == names[i].name) {
        field = names[i].value;
        return;
      }
      expected += std::string(i == 0 ? "" : i + 1 == N ? " or " : ", ") + names[i].name;
    }
    map_.Fail(key, expected);
  }

 private:
  const YamlMap& map_;
};

// Lists each key with its field's text, in the order visited: numbers as NumberText (the
// shortest text that reads back to the same value), booleans as true or false. A choice's value
// missing from its names is the list's error (std::logic_error).
class FieldWriter {
 public:
  void operator()(const char* key, double value) { Add(key, NumberText(value)); }
  void operator()(const char* key, int value) { Add(key, NumberText(value)); }
  void operator()(const char* key, bool value) { Add(key, BoolText(value)); }
  void operator()(const char* key, const std::string& value) { Add(key, value); }

  template <typename Value, std::size_t N>
  void Choice(const char* key, const Value& field, const NamedValue<Value> (&names)[N]) {
    for (const NamedValue<Value>& named : names) {
      if (named.value == field) {
        Add(key, named.name);
        return;
      }
    }
    throw std::logic_error(std::string(key) + ": a value without a name");
  }

  std::vector<std::pair<std::string, std::string>> parameters;

 private:
  void Add(const char* key, std::string text) { parameters.emplace_back(key, std::move(text)); }
};

}  // namespace markerbench

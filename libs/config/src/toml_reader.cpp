// TOML text → ConfigDraft. toml++ supplies the syntax and a source region for every key and value;
// this file walks the tables against the schema in keys.cpp, type-checks each value and reports
// every unknown key, wrong type and bad value it meets.
#include <algorithm>
#include <array>
#include <string>

#include <toml++/toml.h>

#include "draft.hpp"
#include "text_util.hpp"

namespace mocaplink::config::detail {
namespace {

constexpr std::array<std::string_view, 6> kTables = {"mocap",    "origin", "vehicle",
                                                     "tracking", "http",   "ros2"};

Where at(const std::string& file, const toml::source_region& region) {
  return Where{file, region.begin.line, region.begin.column};
}

const char* type_name(toml::node_type type) {
  switch (type) {
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a float";
    case toml::node_type::boolean:
      return "a boolean";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::table:
      return "a table";
    case toml::node_type::date:
      return "a date";
    case toml::node_type::time:
      return "a time";
    case toml::node_type::date_time:
      return "a date-time";
    case toml::node_type::none:
      break;
  }
  return "nothing";
}

std::optional<Value> to_value(const toml::node& node, ValueType type, Where where, std::string key,
                              Diagnostics& diagnostics) {
  Value value;
  value.where = where;
  value.key = std::move(key);
  bool ok = false;
  switch (type) {
    case ValueType::string:
      if (const auto* s = node.as_string()) {
        value.data = s->get();
        ok = true;
      }
      break;
    case ValueType::integer:
      if (const auto* i = node.as_integer()) {
        value.data = i->get();
        ok = true;
      }
      break;
    case ValueType::number:
      if (const auto* i = node.as_integer()) {
        value.data = static_cast<double>(i->get());
        ok = true;
      } else if (const auto* f = node.as_floating_point()) {
        value.data = f->get();
        ok = true;
      }
      break;
    case ValueType::boolean:
      if (const auto* b = node.as_boolean()) {
        value.data = b->get();
        ok = true;
      }
      break;
    case ValueType::string_list:
      if (const auto* array = node.as_array()) {
        std::vector<std::string> items;
        ok = true;
        for (std::size_t i = 0; i < array->size(); ++i) {
          const auto& element = *array->get(i);
          if (const auto* s = element.as_string()) {
            items.push_back(s->get());
          } else {
            diagnostics.error(at(where.file, element.source()),
                              value.key + "[" + std::to_string(i + 1) + "]",
                              std::string("expected a string, got ") + type_name(element.type()));
            ok = false;
          }
        }
        if (!ok) return std::nullopt;
        value.data = std::move(items);
      }
      break;
  }
  if (!ok) {
    diagnostics.error(
        where, value.key,
        std::string("expected ") + expected_name(type) + ", got " + type_name(node.type()));
    return std::nullopt;
  }
  return value;
}

template <typename Target>
void read_table(const toml::table& table, const std::string& file, const std::string& prefix,
                std::span<const KeySpec<Target>> specs, Target& target, Diagnostics& diagnostics) {
  std::vector<std::string_view> names;
  for (const auto& spec : specs) names.push_back(spec.name);
  for (auto&& [key, node] : table) {
    const std::string path = prefix + std::string(key.str());
    const KeySpec<Target>* spec = nullptr;
    for (const auto& s : specs) {
      if (s.name == key.str()) spec = &s;
    }
    if (spec == nullptr) {
      diagnostics.error(at(file, key.source()), path, unknown_key_message(key.str(), names));
      continue;
    }
    if (auto value = to_value(node, spec->type, at(file, node.source()), path, diagnostics)) {
      spec->apply(target, *value, diagnostics);
    } else {
      target.mistyped.emplace_back(spec->name);
    }
  }
}

const toml::table* expect_table(const toml::node& node, const Where& where, std::string_view name,
                                Diagnostics& diagnostics) {
  if (const auto* table = node.as_table()) return table;
  diagnostics.error(
      where, std::string(name),
      "expected a table ([" + std::string(name) + "]), got " + type_name(node.type()));
  return nullptr;
}

void read_vehicles(const toml::node& node, const Where& where, const std::string& file,
                   ConfigDraft& draft, Diagnostics& diagnostics) {
  const auto* array = node.as_array();
  if (array == nullptr) {
    diagnostics.error(
        where, "vehicle",
        std::string("expected an array of tables ([[vehicle]]), got ") + type_name(node.type()));
    return;
  }
  for (std::size_t i = 0; i < array->size(); ++i) {
    const auto& element = *array->get(i);
    VehicleDraft vehicle;
    vehicle.header = at(file, element.source());
    vehicle.prefix = "vehicle[" + std::to_string(i + 1) + "].";
    const auto* table = element.as_table();
    if (table == nullptr) {
      diagnostics.error(vehicle.header, "vehicle[" + std::to_string(i + 1) + "]",
                        std::string("expected a table, got ") + type_name(element.type()));
      continue;
    }
    read_table(*table, file, vehicle.prefix, vehicle_keys(), vehicle, diagnostics);
    draft.vehicles.push_back(std::move(vehicle));
  }
}

}  // namespace

bool read_toml(std::string_view text, std::string_view filename, ConfigDraft& draft,
               Diagnostics& diagnostics) {
  const std::string file(filename);
  draft.document = Where{file, 1, 1};
  toml::table root;
  try {
    root = toml::parse(text, std::string_view(filename));
  } catch (const toml::parse_error& e) {
    diagnostics.error(at(file, e.source()), "",
                      "TOML syntax error: " + std::string(e.description()));
    return false;
  }
  for (auto&& [key, node] : root) {
    const Where key_where = at(file, key.source());
    const std::string name(key.str());
    if (name == "vehicle") {
      read_vehicles(node, key_where, file, draft, diagnostics);
      continue;
    }
    const bool known = std::find(kTables.begin(), kTables.end(), name) != kTables.end();
    if (!known) {
      diagnostics.error(key_where, name, unknown_key_message(name, kTables));
      continue;
    }
    const auto* table = expect_table(node, key_where, name, diagnostics);
    if (table == nullptr) {
      // `mocap = "vicon://..."`: already reported; do not also call [mocap] source missing.
      if (name == "mocap") draft.mistyped.emplace_back("source");
      continue;
    }
    const Where header = at(file, node.source());
    const std::string prefix = name + ".";
    if (name == "mocap") {
      draft.mocap_header = header;
      read_table(*table, file, prefix, mocap_keys(), draft, diagnostics);
    } else if (name == "origin") {
      draft.origin_header = header;
      read_table(*table, file, prefix, origin_keys(), draft, diagnostics);
    } else if (name == "tracking") {
      read_table(*table, file, prefix, tracking_keys(), draft, diagnostics);
    } else if (name == "ros2") {
      draft.ros2_header = header;
      read_table(*table, file, prefix, ros2_keys(), draft, diagnostics);
    } else {
      read_table(*table, file, prefix, http_keys(), draft, diagnostics);
    }
  }
  return true;
}

}  // namespace mocaplink::config::detail

#include "core/fields/constraint_set.h"

#include <cmath>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>

#include "core/mesh/tet_topology.h"
#include "core/util/error.h"
#include "core/util/json_errors.h"
#include "core/util/text_file.h"

namespace facehex {
namespace {

using nlohmann::json;

Eigen::Vector3d vec3(const json& j, const std::string& what) {
  if (!j.is_array() || j.size() != 3) throw std::runtime_error(what + " must be an array of 3 numbers");
  return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
}

json to_array(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }

Selection parse_selection(const json& j) {
  Selection s;
  int kinds = 0;
  if (j.contains("ids")) {
    ++kinds;
    if (!j.at("ids").is_array()) throw std::runtime_error("\"ids\" must be an array of vertex ids");
    for (const auto& id : j.at("ids")) {
      if (!id.is_number_integer() || id.get<long long>() > std::numeric_limits<int>::max())
        throw std::runtime_error("vertex id " + id.dump() + " is not a whole number of range");
      const int v = id.get<int>();
      if (v < 0) throw std::runtime_error("negative vertex id " + std::to_string(v));
      s.ids.push_back(v);
    }
  }
  if (j.contains("side")) {
    ++kinds;
    const auto side = side_from_name(j.at("side").get<std::string>());
    if (!side) throw std::runtime_error("unknown side '" + j.at("side").get<std::string>() + "' (u0 u1 v0 v1 w0 w1)");
    s.side = side;
  }
  if (j.contains("plane")) {
    ++kinds;
    PlaneSelection p;
    p.point = vec3(j.at("plane").at("point"), "plane.point");
    p.normal = vec3(j.at("plane").at("normal"), "plane.normal");
    if (p.normal.norm() < 1e-12) throw std::runtime_error("plane.normal is zero");
    p.normal.normalize();
    p.band = j.value("band", 1.0);
    if (!(p.band > 0)) throw std::runtime_error("band must be positive");
    p.region = j.value("region", std::string("volume"));
    if (p.region != "volume" && p.region != "boundary" && !side_from_name(p.region))
      throw std::runtime_error("unknown region '" + p.region + "' (volume, boundary, or a side name)");
    if (j.contains("within")) {
      p.within_center = vec3(j.at("within").at("center"), "within.center");
      p.within_radius = j.at("within").at("radius").get<double>();
      if (!(p.within_radius > 0)) throw std::runtime_error("within.radius must be positive");
    }
    if (j.contains("exclude"))
      for (const auto& name : j.at("exclude")) {
        const auto side = side_from_name(name.get<std::string>());
        if (!side) throw std::runtime_error("unknown side '" + name.get<std::string>() + "' in exclude");
        p.exclude_sides |= side_bit(*side);
      }
    s.plane = p;
  }
  if (kinds != 1) throw std::runtime_error("select needs exactly one of \"ids\", \"side\", \"plane\"");
  return s;
}

json selection_json(const Selection& s) {
  json j;
  if (s.side) {
    j["side"] = kSideNames[*s.side];
  } else if (s.plane) {
    const PlaneSelection& p = *s.plane;
    j["plane"] = {{"point", to_array(p.point)}, {"normal", to_array(p.normal)}};
    j["band"] = p.band;
    j["region"] = p.region;
    if (p.within_center) j["within"] = {{"center", to_array(*p.within_center)}, {"radius", p.within_radius}};
    if (p.exclude_sides) {
      j["exclude"] = json::array();
      for (int side = 0; side < kNumSides; ++side)
        if (p.exclude_sides & side_bit(static_cast<Side>(side))) j["exclude"].push_back(kSideNames[side]);
    }
  } else {
    j["ids"] = s.ids;
  }
  return j;
}

// An exception's message for the user: a JSON library error ("[json.exception.type_error.302] type must be number,
// but is string") as "a value has the wrong type: type must be number, but is string".
std::string message_of(const std::exception& e) {
  if (dynamic_cast<const nlohmann::json::exception*>(&e) == nullptr) return e.what();
  return "a value has the wrong type or is missing: " + without_json_error_code(e.what());
}

}  // namespace

ConstraintSet parse_constraint_set(const std::string& json_text, const std::string& source) {
  json root;
  try {
    root = json::parse(json_text);
  } catch (const json::exception& e) {
    throw Error(source, "not valid JSON: " + without_json_error_code(e.what()));
  }
  ConstraintSet set;
  try {
    if (root.value("format", std::string()) != "facehex-constraints")
      throw std::runtime_error("\"format\" must be \"facehex-constraints\"");
    if (!root.contains("version") || !root.at("version").is_number_integer() || root.at("version").get<int>() != 1)
      throw std::runtime_error("unsupported \"version\" (expected 1)");
    for (const auto& c : root.at("constraints")) {
      Constraint k;
      k.name = c.value("name", std::string("constraint ") + std::to_string(set.constraints.size() + 1));
      try {
        const std::string field = c.at("field").get<std::string>();
        k.field = field == "u" ? 0 : field == "v" ? 1 : field == "w" ? 2 : -1;
        if (k.field < 0) throw std::runtime_error("field must be \"u\", \"v\" or \"w\"");
        k.value = c.at("value").get<double>();
        if (!(k.value >= 0 && k.value <= 1))
          throw std::runtime_error("value " + c.at("value").dump() +
                                   " is outside 0..1 (each field runs from 0 on one side to 1 on the other)");
        k.select = parse_selection(c.at("select"));
      } catch (const std::exception& e) {
        throw std::runtime_error("constraint '" + k.name + "': " + message_of(e));
      }
      set.constraints.push_back(std::move(k));
    }
  } catch (const std::exception& e) {
    throw Error(source, message_of(e));
  }
  return set;
}

ConstraintSet read_constraint_set(const std::string& path) { return parse_constraint_set(read_text_file(path), path); }

std::string to_json(const ConstraintSet& set) {
  json root = {{"format", "facehex-constraints"}, {"version", 1}, {"constraints", json::array()}};
  for (const auto& c : set.constraints)
    root["constraints"].push_back(
        {{"name", c.name}, {"field", kFieldNames[c.field]}, {"value", c.value}, {"select", selection_json(c.select)}});
  return root.dump(2) + "\n";
}

void write_constraint_set(const std::string& path, const ConstraintSet& set) { write_text_file(path, to_json(set)); }

ConstraintSet side_constraints() {
  ConstraintSet set;
  for (int s = 0; s < kNumSides; ++s) {
    Constraint c;
    c.name = kSideDescriptions[s];
    c.field = side_field(static_cast<Side>(s));
    c.value = side_value(static_cast<Side>(s));
    c.select.side = static_cast<Side>(s);
    set.constraints.push_back(c);
  }
  return set;
}

bool within_selection_limits(const PlaneSelection& p, const Eigen::Vector3d& x, bool on_boundary, int side_mask) {
  if (p.region == "boundary" && !on_boundary) return false;
  if (p.region != "volume" && p.region != "boundary" && !(side_mask & side_bit(*side_from_name(p.region))))
    return false;
  if (p.within_center && (x - *p.within_center).norm() > p.within_radius) return false;
  return (side_mask & p.exclude_sides) == 0;
}

std::vector<int> select_vertices(const Selection& selection, const Eigen::MatrixXd& V,
                                 const std::vector<char>& boundary_flags, const Eigen::VectorXi& side_mask) {
  std::vector<int> out;
  if (!selection.ids.empty()) {
    for (int v : selection.ids)
      if (v >= V.rows()) throw std::runtime_error("vertex id " + std::to_string(v) + " is out of range");
    out = selection.ids;
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }
  if (!selection.side && !selection.plane) return out;  // an empty id list selects nothing
  auto on_side = [&](int v, Side s) { return (side_mask(v) & side_bit(s)) != 0; };
  const bool needs_mask =
      selection.side ||
      (selection.plane && ((selection.plane->region != "volume" && selection.plane->region != "boundary") ||
                           selection.plane->exclude_sides != 0));
  if (needs_mask && side_mask.size() != V.rows())
    throw std::runtime_error("selects by side but the model has no \"side_mask\" array");
  for (int v = 0; v < V.rows(); ++v) {
    if (selection.side) {
      if (on_side(v, *selection.side)) out.push_back(v);
      continue;
    }
    const PlaneSelection& p = *selection.plane;
    const Eigen::Vector3d x = V.row(v).transpose();
    if (std::abs((x - p.point).dot(p.normal)) > p.band / 2) continue;
    if (within_selection_limits(p, x, boundary_flags[v] != 0, side_mask.size() > 0 ? side_mask(v) : 0))
      out.push_back(v);
  }
  return out;
}

ResolvedConstraints resolve_constraints(const ConstraintSet& set, const Eigen::MatrixXd& V, const Eigen::MatrixXi& T,
                                        const Eigen::VectorXi& side_mask, const std::string& source) {
  const std::vector<char> boundary = boundary_vertex_flags(static_cast<int>(V.rows()), boundary_faces(T).F);
  ResolvedConstraints out;
  // Per field, the value and constraint index already given to each vertex, to report conflicts by name.
  std::array<std::map<int, std::pair<double, size_t>>, 3> assigned;
  std::array<bool, 3> has_zero{}, has_one{};
  for (size_t i = 0; i < set.constraints.size(); ++i) {
    const Constraint& c = set.constraints[i];
    std::vector<int> sel;
    try {
      sel = select_vertices(c.select, V, boundary, side_mask);
    } catch (const std::exception& e) {
      throw Error(source, "constraint '" + c.name + "': " + e.what());
    }
    if (sel.empty())
      throw Error(source,
                  "constraint '" + c.name + "' selects no vertex" + (c.origin.empty() ? "" : " (" + c.origin + ")"));
    for (int v : sel) {
      auto [it, inserted] = assigned[c.field].emplace(v, std::make_pair(c.value, i));
      if (!inserted && it->second.first != c.value)
        throw Error(source, "vertex " + std::to_string(v) + " gets two values in field " + kFieldNames[c.field] + ": " +
                                std::to_string(it->second.first) + " from '" + set.constraints[it->second.second].name +
                                "' and " + std::to_string(c.value) + " from '" + c.name + "'");
    }
    has_zero[c.field] = has_zero[c.field] || c.value == 0.0;
    has_one[c.field] = has_one[c.field] || c.value == 1.0;
    out.selected.push_back(std::move(sel));
  }
  for (int f = 0; f < 3; ++f) {
    if (!has_zero[f] || !has_one[f])
      throw Error(source, std::string("field ") + kFieldNames[f] + " is missing its " + (has_zero[f] ? "1" : "0") +
                              " end (each direction needs a shape end at 0 and one at 1)");
    for (const auto& [v, value] : assigned[f]) {
      out.fields[f].vertices.push_back(v);
      out.fields[f].values.push_back(value.first);
    }
  }
  return out;
}

Eigen::VectorXi side_mask_of(const VolumeMesh& mesh) {
  const auto it = mesh.point_data.find(kSideMaskArray);
  if (it == mesh.point_data.end()) return {};
  return it->second.col(0).array().round().cast<int>();
}

}  // namespace facehex

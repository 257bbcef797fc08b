#include "core/face/landmark_file.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "core/mesh/ct_landmarks.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"
#include "core/util/json_errors.h"

namespace facehex {
namespace {

using json = nlohmann::json;

bool is_slicer(const std::string& path) {
  const std::string suffix = ".mrk.json";
  return path.size() >= suffix.size() && path.compare(path.size() - suffix.size(), suffix.size(), suffix) == 0;
}

Eigen::Vector3d position_of(const std::string& path, const json& p, const std::string& name) {
  if (!p.is_array() || p.size() != 3 || !std::all_of(p.begin(), p.end(), [](const json& v) { return v.is_number(); }))
    throw Error(path, "landmark '" + name + "': the position must be three numbers [x, y, z] (mm)");
  const Eigen::Vector3d v(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
  if (!v.allFinite()) throw Error(path, "landmark '" + name + "': the position is not finite");
  return v;
}

LandmarkStatus status_of(const std::string& path, const std::string& text, const std::string& name) {
  for (const LandmarkStatus s : {LandmarkStatus::found, LandmarkStatus::estimated, LandmarkStatus::given})
    if (text == status_name(s)) return s;
  throw Error(path, "landmark '" + name + "': unknown status '" + text + "' (found, estimated or given)");
}

void check_name(const std::string& path, const std::string& name, std::set<std::string>& seen) {
  if (!is_landmark_name(name))
    throw Error(path, "unknown landmark '" + name + "' (known: " + landmark_names_text() + ")");
  if (!seen.insert(name).second) throw Error(path, "landmark '" + name + "' is given twice");
}

std::vector<NamedLandmark> read_facehex(const std::string& path, const json& doc, const ScanFrame& frame) {
  if (doc.value("format", "") != "facehex-landmarks")
    throw Error(path,
                "not a FaceHex landmark file (\"format\": \"facehex-landmarks\" is missing); a 3D Slicer "
                "markups file must be named *.mrk.json");
  if (doc.value("units", "mm") != "mm") throw Error(path, "units must be \"mm\"");
  if (!doc.contains("landmarks") || !doc["landmarks"].is_array())
    throw Error(path, "\"landmarks\" must be a list of {\"name\", \"position\"}");
  std::vector<NamedLandmark> out;
  std::set<std::string> seen;
  for (const json& l : doc["landmarks"]) {
    if (!l.is_object() || !l.contains("name") || !l["name"].is_string())
      throw Error(path, "every landmark needs a \"name\"");
    NamedLandmark n;
    const std::string name = l["name"].get<std::string>();
    check_name(path, name, seen);
    if (!l.contains("position")) throw Error(path, "landmark '" + name + "' has no \"position\"");
    n.position = position_of(path, l["position"], name);
    n.name = patient_side_name(name, frame);
    if (l.contains("status")) {
      if (!l["status"].is_string()) throw Error(path, "landmark '" + n.name + "': \"status\" must be a word");
      n.status = status_of(path, l["status"].get<std::string>(), name);
    }
    out.push_back(n);
  }
  return out;
}

std::vector<NamedLandmark> read_slicer(const std::string& path, const json& doc, const ScanFrame& frame) {
  if (!doc.contains("markups") || !doc["markups"].is_array() || doc["markups"].empty())
    throw Error(path, "not a 3D Slicer markups file (no \"markups\" list)");
  std::vector<NamedLandmark> out;
  std::set<std::string> seen;
  for (const json& m : doc["markups"]) {
    if (m.value("type", "") != "Fiducial")
      throw Error(path, "markup of type '" + m.value("type", std::string("?")) +
                            "': only Fiducial (point list) markups hold landmarks");
    const std::string system = m.value("coordinateSystem", "LPS");
    if (system != "LPS" && system != "RAS") throw Error(path, "coordinateSystem '" + system + "': expected LPS or RAS");
    if (m.value("coordinateUnits", "mm") != "mm") throw Error(path, "coordinateUnits must be mm");
    if (!m.contains("controlPoints") || !m["controlPoints"].is_array())
      throw Error(path, "a Fiducial markup has no \"controlPoints\" list");
    for (const json& c : m["controlPoints"]) {
      if (!c.is_object() || !c.contains("label") || !c["label"].is_string())
        throw Error(path, "every control point needs a \"label\" naming the landmark");
      NamedLandmark n;
      const std::string name = c["label"].get<std::string>();
      check_name(path, name, seen);
      if (!c.contains("position")) throw Error(path, "landmark '" + name + "' has no \"position\"");
      Eigen::Vector3d scan = position_of(path, c["position"], name);
      if (system == "RAS") scan.head<2>() *= -1;
      n.name = patient_side_name(name, frame);
      n.position = frame.from_scan(scan);
      if (c.contains("description") && c["description"].is_string() && !c["description"].get<std::string>().empty())
        n.status = status_of(path, c["description"].get<std::string>(), name);
      out.push_back(n);
    }
  }
  return out;
}

}  // namespace

const std::vector<std::string>& landmark_names() {
  static const std::vector<std::string> names = {"glabella",          "nasion",           "pronasale",
                                                 "subnasale",         "labrale superius", "stomion",
                                                 "labrale inferius",  "pogonion",         "menton",
                                                 "endocanthion left", "exocanthion left", "endocanthion right",
                                                 "exocanthion right", "cheilion left",    "cheilion right",
                                                 "tragus left",       "tragus right"};
  return names;
}

bool is_landmark_name(const std::string& name) {
  const std::vector<std::string>& names = landmark_names();
  return std::find(names.begin(), names.end(), name) != names.end();
}

std::string landmark_names_text() {
  std::string text;
  for (const std::string& name : landmark_names()) text += (text.empty() ? "" : ", ") + name;
  return text;
}

bool lies_on_model_skin(const std::string& name) { return name != kTragusNames[0] && name != kTragusNames[1]; }

const char* status_name(LandmarkStatus status) {
  switch (status) {
    case LandmarkStatus::found:
      return "found";
    case LandmarkStatus::estimated:
      return "estimated";
    case LandmarkStatus::given:
      return "given";
  }
  return "given";
}

std::vector<NamedLandmark> read_landmark_file(const std::string& path, const ScanFrame& frame) {
  std::ifstream in(path);
  if (!in) throw Error(path, "cannot open the landmark file");
  json doc;
  try {
    in >> doc;
  } catch (const json::exception& e) {
    throw Error(path, std::string("not valid JSON (") + e.what() + ")");
  }
  if (!doc.is_object()) throw Error(path, "a landmark file holds one JSON object");
  std::vector<NamedLandmark> out;
  try {
    out = is_slicer(path) ? read_slicer(path, doc, frame) : read_facehex(path, doc, frame);
  } catch (const json::exception& e) {  // a value of another type than the format's, e.g. a number for a markup
    throw Error(path, "a value has the wrong type: " + without_json_error_code(e.what()));
  }
  if (out.empty()) throw Error(path, "holds no landmark");
  return out;
}

void write_landmark_file(const std::string& path, const std::vector<NamedLandmark>& landmarks, const ScanFrame& frame) {
  json doc;
  if (is_slicer(path)) {
    json points = json::array();
    int id = 1;
    for (const NamedLandmark& l : landmarks) {
      const Eigen::Vector3d scan = frame.to_scan(l.position);
      points.push_back({{"id", std::to_string(id++)},
                        {"label", patient_side_name(l.name, frame)},
                        {"description", status_name(l.status)},
                        {"position", {scan.x(), scan.y(), scan.z()}},
                        {"positionStatus", "defined"}});
    }
    doc = {
        {"@schema",
         "https://raw.githubusercontent.com/slicer/slicer/master/Modules/Loadable/Markups/Resources/Schema/"
         "markups-schema-v1.0.3.json#"},
        {"markups",
         {{{"type", "Fiducial"}, {"coordinateSystem", "LPS"}, {"coordinateUnits", "mm"}, {"controlPoints", points}}}}};
  } else {
    json list = json::array();
    for (const NamedLandmark& l : landmarks)
      list.push_back({{"name", patient_side_name(l.name, frame)},
                      {"position", {l.position.x(), l.position.y(), l.position.z()}},
                      {"status", status_name(l.status)}});
    doc = {{"format", "facehex-landmarks"}, {"version", 1}, {"units", "mm"}, {"landmarks", list}};
  }
  write_atomically(path, [&](const std::string& tmp) {
    std::ofstream out(tmp);
    out << doc.dump(1) << "\n";
    if (!out) throw Error(path, "cannot write the landmark file");
  });
}

}  // namespace facehex

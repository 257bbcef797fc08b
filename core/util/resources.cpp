#include "core/util/resources.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "core/util/error.h"

namespace facehex {
namespace fs = std::filesystem;

namespace {

std::vector<BundledModel> list_models(const std::string& kind, const std::string& mesh_name) {
  std::vector<BundledModel> out;
  const fs::path dir = fs::path(resource_dir()) / kind;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const fs::path mesh = entry.path() / mesh_name;
    if (!fs::exists(mesh)) continue;
    BundledModel m{entry.path().filename().string(), mesh.string(), (entry.path() / "constraints.json").string(), ""};
    std::ifstream readme(entry.path() / "README.md");
    if (readme) {
      std::getline(readme, m.description);
      m.description.erase(0, m.description.find_first_not_of("# "));
    }
    out.push_back(m);
  }
  std::sort(out.begin(), out.end(), [](const BundledModel& a, const BundledModel& b) { return a.name < b.name; });
  return out;
}

}  // namespace

std::string resource_dir() {
  if (const char* env = std::getenv("FACEHEX_RESOURCES"); env && *env) return env;
  return FACEHEX_RESOURCE_DIR;
}

std::vector<BundledModel> bundled_standards() { return list_models("standards", "standard.vtu"); }
std::vector<BundledModel> bundled_patients() { return list_models("patients", "patient.vtu"); }

BundledModel find_standard(const std::string& name_or_path) {
  for (const auto& s : bundled_standards())
    if (s.name == name_or_path) return s;
  const fs::path p(name_or_path);
  if (!fs::exists(p))
    throw Error(name_or_path, "no bundled standard of that name and no such file (see 'facehex standards')");
  std::string constraints = constraints_beside(name_or_path);
  if (constraints.empty()) constraints = fs::path(p).replace_extension(".json").string();  // named in the read error
  return {p.stem().string(), p.string(), constraints, ""};
}

std::string constraints_beside(const std::string& model_path) {
  const fs::path p(model_path);
  for (const fs::path& candidate : {fs::path(p).replace_extension(".json"), p.parent_path() / "constraints.json"})
    if (fs::is_regular_file(candidate)) return candidate.string();
  return "";
}

BundledModel default_standard() {
  const auto all = bundled_standards();
  const auto it =
      std::find_if(all.begin(), all.end(), [](const BundledModel& m) { return m.name == "artisynth-refface"; });
  if (it != all.end()) return *it;
  if (all.empty()) throw Error(resource_dir(), "no bundled standard found (resources/standards/*/standard.vtu)");
  return all.front();
}

BundledModel default_patient() {
  const auto all = bundled_patients();
  if (all.empty()) throw Error(resource_dir(), "no bundled sample patient found (resources/patients/*/patient.vtu)");
  return all.front();
}

std::string default_ct() {
  const fs::path ct = fs::path(resource_dir()) / "ct" / "headsq" / "headsq.mhd";
  if (!fs::exists(ct)) throw Error(ct.string(), "the bundled sample CT is missing");
  return ct.string();
}

}  // namespace facehex

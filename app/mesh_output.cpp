#include "app/mesh_output.h"

#include <algorithm>

#include "core/util/error.h"
#include "core/util/text_file.h"

namespace facehex::cli {

MeshWriteOptions write_options(const Args& args) {
  MeshWriteOptions o;
  o.allow_inverted = args.has("force-export");
  return o;
}

std::vector<std::string> export_formats(const std::string& list) {
  std::vector<std::string> formats;
  const std::vector<std::string> writable = writable_volume_extensions();
  for (const std::string& f : split_commas(list)) {
    if (std::find(writable.begin(), writable.end(), "." + f) == writable.end())
      throw UsageError("--export", "cannot write '" + f + "' (use feb, inp, msh, vtk or vtu)");
    formats.push_back(f);
  }
  return formats;
}

void write_json(const std::string& path, const nlohmann::json& j) { write_text_file(path, j.dump(2) + "\n"); }

}  // namespace facehex::cli

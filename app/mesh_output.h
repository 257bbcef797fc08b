#pragma once
// Options and helpers of the commands that write meshes: --force-export, --export lists, JSON files.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/cli_args.h"
#include "core/io/mesh_io.h"

namespace facehex::cli {

constexpr const char* kForceExportHelp = "write .inp / .feb even if the mesh has inverted elements";

// The writing options of --force-export.
MeshWriteOptions write_options(const Args& args);

// "feb,inp,msh" -> {"feb", "inp", "msh"}, checked up front so that a typo does not cost a whole run.
std::vector<std::string> export_formats(const std::string& list);

void write_json(const std::string& path, const nlohmann::json& j);

}  // namespace facehex::cli

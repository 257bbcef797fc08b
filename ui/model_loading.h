#pragma once
// Models from files, with the core calls the CLI makes (read, check and orient, parameterization domain, constraint
// set). Run on the controller's worker thread; every failure is a facehex::Error naming the file.
#include "core/io/mesh_io.h"
#include "ui/session_model.h"

#include <string>

namespace facehex::gui {

// A patient tet model or closed surface. Its constraints: NAME.json beside it, else constraints.json in its folder
// (the bundled patients' layout), else the six sides when it has "side_mask", else none.
LoadedModel load_patient(const std::string& path, const MeshReadOptions& options = {});

// A bundled standard by name, or a hex-dominant mesh file (constraints found as in core/resources.h), on the CLI's
// default parameterization domain (closed_domain: its openings filled).
LoadedModel load_standard(const std::string& name_or_path);

// The bundled sample patient; while none is bundled, the synthetic face-like shell of core/synthetic_shell.h
// (tetrahedralized, sides labelled, constrained by its six sides).
LoadedModel demo_patient();

}  // namespace facehex::gui
